//! The haptic stream's test client and benchmark (SPEC H1): grabs a hose
//! through the haptic stream, then sends poses along a path at a fixed rate (1 kHz by
//! default) for a while, one request in flight at a time, and measures the rate held
//! (answers per second, and the share of periods answered within the period) and the
//! round-trip latency (send → reply with the same sequence number: p50, p90, p99, p99.9,
//! max),
//! with the server's own solve time and Newton iterations from the replies.
//!
//! ```text
//! cargo run --release -p pliant-server --example haptic_client -- [--seconds 5]
//!     [--rate 1000] [--radius 0.02] [--solver explicit|implicit|static] [--scene FILE]
//!     [--timeline] [--whole-scene] [--grab X,Y,Z] [--addr 127.0.0.1:PORT --grab X,Y,Z [--token T]] [--json]
//! ```
//!
//! Without `--addr` it serves the scene (the demo engine bay by default) in this process,
//! the haptic stream on a free loopback port, and grabs the free end of the demo's lower
//! hose (the middle node of the scene's hose of most nodes otherwise; `--grab` takes it there
//! instead); `--timeline` runs the scene's timeline before serving (an imported harness:
//! its fixings pressed in; the engine bay: its clips seated); `--whole-scene` has the
//! stream solve each pose on the whole scene instead of the part the hand can move (the
//! same answers; for comparing costs). With `--addr` it talks to a
//! running `pliant serve --haptic-port PORT` and grabs at `--grab`. The path is a
//! horizontal circle of `--radius` through the grab point, once every 4 s. A benchmark,
//! not a test: it asserts nothing; every loop is bounded by `--seconds`.

use glam::DVec3;
use pliant_assembly::Grip;
use pliant_core::SolverKind;
use pliant_server::haptic::datagram::{Kind, Reply, Request, Status, KEY_BYTES};
use pliant_server::session::SessionOptions;
use pliant_server::{start, RunningServer, ServerConfig, Session};
use serde_json::json;
use std::collections::BTreeMap;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

/// A request not answered within this is counted lost.
const REPLY_TIMEOUT: Duration = Duration::from_millis(100);
/// The path's period \[s\].
const PATH_PERIOD: f64 = 4.0;

struct Args {
    seconds: f64,
    rate: f64,
    radius: f64,
    solver: Option<SolverKind>,
    scene: Option<String>,
    timeline: bool,
    whole_scene: bool,
    addr: Option<SocketAddr>,
    grab: Option<DVec3>,
    token: Option<String>,
    json: bool,
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        seconds: 5.0,
        rate: 1000.0,
        radius: 0.02,
        solver: None,
        scene: None,
        timeline: false,
        whole_scene: false,
        addr: None,
        grab: None,
        token: None,
        json: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        let number = |v: String, name: &str| -> Result<f64, String> {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x > 0.0)
                .ok_or_else(|| format!("{name} must be a positive number, not {v:?}"))
        };
        match flag.as_str() {
            "--seconds" => a.seconds = number(value()?, "--seconds")?.min(86_400.0),
            "--rate" => a.rate = number(value()?, "--rate")?.min(100_000.0),
            "--radius" => a.radius = number(value()?, "--radius")?.min(1.0),
            "--solver" => a.solver = Some(value()?.parse()?),
            "--scene" => a.scene = Some(value()?),
            "--timeline" => a.timeline = true,
            "--whole-scene" => a.whole_scene = true,
            "--addr" => {
                let v = value()?;
                a.addr = Some(v.parse().map_err(|e| format!("--addr {v}: {e}"))?)
            }
            "--grab" => {
                let v = value()?;
                let p: Vec<f64> = v
                    .split(',')
                    .map(|x| x.trim().parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|e| format!("--grab {v}: {e}"))?;
                match p[..] {
                    [x, y, z] if p.iter().all(|c| c.is_finite()) => {
                        a.grab = Some(DVec3::new(x, y, z))
                    }
                    _ => return Err(format!("--grab takes X,Y,Z in metres, not {v:?}")),
                }
            }
            "--token" => a.token = Some(value()?),
            "--json" => a.json = true,
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if a.addr.is_some() && a.grab.is_none() {
        return Err("--addr needs --grab X,Y,Z (where to take the hose)".into());
    }
    Ok(a)
}

/// The demo's lower hose's free end; in another scene the middle node of its hose of
/// most nodes.
fn default_grab(s: &RunningServer) -> DVec3 {
    let session = s.session();
    let snap = session.latest();
    if let Some(k) = session.scene().hoses.iter().position(|h| h.name == "lower") {
        return DVec3::from_array(*snap.hoses[k].positions.last().expect("a hose has nodes"));
    }
    let longest = snap
        .hoses
        .iter()
        .max_by_key(|h| h.positions.len())
        .expect("a scene has hoses");
    DVec3::from_array(longest.positions[longest.positions.len() / 2])
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
    sorted[k.min(sorted.len() - 1)]
}

struct Link {
    socket: UdpSocket,
    sequence: u64,
    key: [u8; KEY_BYTES],
}

impl Link {
    /// Sends one request; the reply with its sequence number, or `None` after
    /// [`REPLY_TIMEOUT`] (stale replies of earlier requests are skipped).
    fn ask(&mut self, kind: Kind, hand: u32, position: DVec3) -> Option<Reply> {
        self.sequence += 1;
        let request = Request::new(kind, hand, self.sequence, position, self.key);
        self.socket.send(&request.encode()).ok()?;
        let deadline = Instant::now() + REPLY_TIMEOUT;
        let mut buf = [0u8; 256];
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return None;
            }
            self.socket.set_read_timeout(Some(left)).ok()?;
            let n = self.socket.recv(&mut buf).ok()?;
            match Reply::decode(&buf[..n]) {
                Some(r) if r.sequence == self.sequence => return Some(r),
                _ => continue,
            }
        }
    }
}

fn run(a: Args, addr: SocketAddr, grab: DVec3) -> Result<serde_json::Value, String> {
    let socket = UdpSocket::bind("127.0.0.1:0").map_err(|e| e.to_string())?;
    socket.connect(addr).map_err(|e| e.to_string())?;
    let key = Request::key_for(a.token.as_deref()).ok_or("--token: at most 32 characters")?;
    let mut link = Link {
        socket,
        sequence: 0,
        key,
    };
    let hand = 900;
    match link.ask(Kind::Grab(Grip::Firm), hand, grab) {
        Some(r) if r.status == Status::Pending || r.status == Status::Ok => {}
        Some(r) => return Err(format!("the grab was refused: {}", r.status.name())),
        None => return Err(format!("no answer from {addr}: is the haptic stream on?")),
    }
    let until = Instant::now() + Duration::from_secs(30);
    loop {
        match link.ask(Kind::Pose, hand, grab) {
            Some(r) if r.status.has_load() => break,
            Some(r) if r.status == Status::Pending => {}
            Some(r) => return Err(format!("the grab did not take: {}", r.status.name())),
            None => {}
        }
        if Instant::now() > until {
            return Err("the session did not take the grab within 30 s".into());
        }
    }
    let period = Duration::from_secs_f64(1.0 / a.rate);
    let omega = std::f64::consts::TAU / PATH_PERIOD;
    let total = (a.seconds * a.rate).round() as u64;
    let mut latencies = Vec::with_capacity(total as usize);
    let mut solves = Vec::with_capacity(total as usize);
    let (mut iterations, mut lost, mut in_period, mut late_sends) = (0u64, 0u64, 0u64, 0u64);
    let mut statuses: BTreeMap<&'static str, u64> = BTreeMap::new();
    let (mut peak_force, mut last_force) = (0.0_f64, DVec3::ZERO);
    let start = Instant::now();
    let mut next = start;
    for k in 0..total {
        // pacing: sleep to just before the slot, then spin (thread::sleep alone is coarse)
        let now = Instant::now();
        if next > now {
            let ahead = next - now;
            if ahead > Duration::from_micros(200) {
                std::thread::sleep(ahead - Duration::from_micros(150));
            }
            while Instant::now() < next {
                std::hint::spin_loop();
            }
        } else if now - next > period {
            late_sends += 1;
            next = now; // behind by more than a period: no catching up in a burst
        }
        let t = k as f64 / a.rate;
        let p = grab + a.radius * DVec3::new(1.0 - (omega * t).cos(), (omega * t).sin(), 0.0);
        let sent = Instant::now();
        let reply = link.ask(Kind::Pose, hand, p);
        let took = sent.elapsed();
        match reply {
            Some(r) => {
                *statuses.entry(r.status.name()).or_default() += 1;
                latencies.push(took.as_secs_f64() * 1e6);
                if took <= period {
                    in_period += 1;
                }
                if r.status.has_load() {
                    solves.push(r.solve_seconds * 1e6);
                    iterations += u64::from(r.iterations);
                    peak_force = peak_force.max(r.force.length());
                    last_force = r.force;
                }
            }
            None => lost += 1,
        }
        next += period;
    }
    let elapsed = start.elapsed().as_secs_f64();
    let _ = link.ask(Kind::Release, hand, grab);
    latencies.sort_by(f64::total_cmp);
    solves.sort_by(f64::total_cmp);
    let answered = latencies.len() as u64;
    Ok(json!({
        "target_rate_hz": a.rate,
        "seconds": elapsed,
        "sent": total,
        "answered": answered,
        "lost": lost,
        "late_sends": late_sends,
        "rate_held_hz": answered as f64 / elapsed,
        "answered_within_period": in_period as f64 / total.max(1) as f64,
        "latency_us": {
            "p50": percentile(&latencies, 50.0),
            "p90": percentile(&latencies, 90.0),
            "p99": percentile(&latencies, 99.0),
            "p99_9": percentile(&latencies, 99.9),
            "max": latencies.last().copied().unwrap_or(f64::NAN),
        },
        "server_solve_us": {
            "p50": percentile(&solves, 50.0),
            "p99": percentile(&solves, 99.0),
            "p99_9": percentile(&solves, 99.9),
        },
        "newton_iterations_mean": iterations as f64 / solves.len().max(1) as f64,
        "statuses": statuses,
        "peak_force_n": peak_force,
        "last_force_n": last_force.to_array(),
        "path": { "radius_m": a.radius, "period_s": PATH_PERIOD, "grab": grab.to_array() },
        "machine": {
            "logical_cores": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
            "os": std::env::consts::OS,
            "arch": std::env::consts::ARCH,
        },
    }))
}

fn print_text(v: &serde_json::Value) {
    let l = &v["latency_us"];
    let s = &v["server_solve_us"];
    println!(
        "haptic stream: {:.0} of {:.0} Hz held over {:.1} s ({:.1} % answered within the period; {} lost, {} late sends)",
        v["rate_held_hz"].as_f64().unwrap_or(0.0),
        v["target_rate_hz"].as_f64().unwrap_or(0.0),
        v["seconds"].as_f64().unwrap_or(0.0),
        100.0 * v["answered_within_period"].as_f64().unwrap_or(0.0),
        v["lost"],
        v["late_sends"],
    );
    println!(
        "latency (send → reply): p50 {:.0} µs, p90 {:.0} µs, p99 {:.0} µs, p99.9 {:.0} µs, max {:.0} µs",
        l["p50"].as_f64().unwrap_or(f64::NAN),
        l["p90"].as_f64().unwrap_or(f64::NAN),
        l["p99"].as_f64().unwrap_or(f64::NAN),
        l["p99_9"].as_f64().unwrap_or(f64::NAN),
        l["max"].as_f64().unwrap_or(f64::NAN),
    );
    println!(
        "server solve: p50 {:.0} µs, p99 {:.0} µs, p99.9 {:.0} µs, {:.2} Newton iterations per pose; statuses {}",
        s["p50"].as_f64().unwrap_or(f64::NAN),
        s["p99"].as_f64().unwrap_or(f64::NAN),
        s["p99_9"].as_f64().unwrap_or(f64::NAN),
        v["newton_iterations_mean"].as_f64().unwrap_or(f64::NAN),
        v["statuses"],
    );
}

fn main() {
    let a = match args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("haptic_client: {e}");
            std::process::exit(2);
        }
    };
    let json_out = a.json;
    let result = match a.addr {
        Some(addr) => {
            let grab = a.grab.expect("checked in args");
            run(a, addr, grab)
        }
        None => serve_and_run(a),
    };
    match result {
        Ok(v) if json_out => println!("{v}"),
        Ok(v) => print_text(&v),
        Err(e) => {
            eprintln!("haptic_client: {e}");
            std::process::exit(1);
        }
    }
}

/// Serves the scene in this process (haptic stream on a free loopback port) and runs
/// the client against it.
fn serve_and_run(a: Args) -> Result<serde_json::Value, String> {
    let scene = match &a.scene {
        Some(p) => pliant_scene::load_scene_file(std::path::Path::new(p))
            .map_err(|e| format!("{p}: {e}"))?,
        None => pliant_scene::demo_scene().map_err(|e| e.to_string())?,
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()
        .map_err(|e| e.to_string())?;
    let options = SessionOptions {
        solver: a.solver,
        ..SessionOptions::default()
    };
    let session = if a.timeline {
        Session::start_settled(&scene, options)
    } else {
        Session::start(&scene, options)
    }
    .map_err(|e| e.to_string())?;
    let config = ServerConfig {
        port: 0,
        haptic_port: Some(0),
        haptic_whole_scene: a.whole_scene,
        ..ServerConfig::default()
    };
    let server = runtime
        .block_on(start(session, &config))
        .map_err(|e| e.to_string())?;
    let addr = server
        .haptic_addr()
        .ok_or("the haptic stream did not start")?;
    let grab = a.grab.unwrap_or_else(|| default_grab(&server));
    eprintln!(
        "haptic_client: serving '{}' in-process, haptic stream on {addr}, grabbing at {grab}",
        scene.name
    );
    let result = run(a, addr, grab);
    server.stop();
    result
}
