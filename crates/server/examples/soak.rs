//! The soak benchmark: N clients on one live session, each holding
//! its own grip on the demo's hoses and moving it in slow circles (3 cm radius, ≈ 6 cm/s)
//! at 30 Hz, taking hold again at its grab point every 10 s (a `grab` while holding,
//! which moves the grip) — the load under which live sessions used to diverge. It
//! reports per client the snapshot rate, the inputs refused (by error code), the
//! divergences (rolled back and reset) and the process's memory over time.
//!
//! ```text
//! cargo run --release -p pliant-server --example soak -- [--clients 10] [--seconds 600]
//!     [--solver explicit|implicit|static] [--regrab 10] [--json FILE] [--folder DIR]
//! ```
//!
//! A benchmark, not a test: it measures, it asserts nothing. Traffic goes to a server on
//! the loopback interface only, started in this process; every loop is bounded by
//! `--seconds`.

use futures_util::{SinkExt, StreamExt};
use pliant_core::SolverKind;
use pliant_server::session::SessionOptions;
use pliant_server::{start, ServerConfig, Session};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::time::{Duration, Instant};
use tokio_tungstenite::tungstenite::Message;

/// Circle radius \[m\] and angular speed \[rad/s\] (0.03 m × 2 rad/s = 6 cm/s).
const RADIUS: f64 = 0.03;
const OMEGA: f64 = 2.0;
/// Input rate \[Hz\].
const RATE_HZ: f64 = 30.0;

struct Args {
    clients: usize,
    seconds: f64,
    solver: SolverKind,
    /// Re-grab period \[s\].
    regrab: f64,
    json: Option<String>,
    /// Session folder: the input log is written there (replayable with `pliant replay`).
    folder: Option<std::path::PathBuf>,
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        clients: 10,
        seconds: 600.0,
        solver: SolverKind::Explicit,
        regrab: 10.0,
        json: None,
        folder: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--clients" => a.clients = value()?.parse().map_err(|e| format!("--clients: {e}"))?,
            "--seconds" => a.seconds = value()?.parse().map_err(|e| format!("--seconds: {e}"))?,
            "--solver" => a.solver = value()?.parse().map_err(|e| format!("--solver: {e}"))?,
            "--regrab" => a.regrab = value()?.parse().map_err(|e| format!("--regrab: {e}"))?,
            "--json" => a.json = Some(value()?),
            "--folder" => a.folder = Some(value()?.into()),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if !(1..=16).contains(&a.clients) {
        return Err("--clients must be 1 to 16 (the session's hand limit)".into());
    }
    if !(a.regrab > 0.0 && a.regrab.is_finite()) {
        return Err("--regrab must be a positive number of seconds".into());
    }
    if !(a.seconds > 0.0 && a.seconds <= 86_400.0) {
        return Err("--seconds must be in (0, 86400]".into());
    }
    Ok(a)
}

/// What one client saw.
#[derive(Default, Debug)]
struct ClientReport {
    snapshots: u64,
    inputs: u64,
    errors: BTreeMap<String, u64>,
    /// Largest `rollbacks` and `epoch` seen in a snapshot.
    rollbacks: u64,
    resets: u64,
    last_notice: Option<String>,
    first_time: f64,
    last_time: f64,
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse().ok())
        })
        .unwrap_or(0)
}

fn position(snap: &Value, hose: usize, node: usize) -> Option<[f64; 3]> {
    let p = snap["hoses"][hose]["positions"][node].as_array()?;
    Some([p[0].as_f64()?, p[1].as_f64()?, p[2].as_f64()?])
}

async fn client(url: String, id: usize, clients: usize, seconds: f64, regrab: f64) -> ClientReport {
    let mut report = ClientReport::default();
    let Ok((ws, _)) = tokio_tungstenite::connect_async(url).await else {
        report.errors.insert("connect".into(), 1);
        return report;
    };
    let (mut tx, mut rx) = ws.split();
    let send = |v: Value| Message::text(v.to_string());
    let _ = tx.send(send(json!({"type": "hello", "version": 1}))).await;
    // the first snapshot gives the hoses: clients spread over both hoses, evenly along each
    let first = loop {
        match rx.next().await {
            Some(Ok(Message::Text(t))) => {
                let v: Value = serde_json::from_str(t.as_str()).unwrap_or(Value::Null);
                if v["type"] == "snapshot" {
                    break v;
                }
            }
            Some(Ok(_)) => {}
            _ => return report,
        }
    };
    let hoses = first["hoses"].as_array().map_or(1, |h| h.len().max(1));
    let hose = id % hoses;
    let per_hose = clients.div_ceil(hoses);
    let nodes = first["hoses"][hose]["positions"]
        .as_array()
        .map_or(2, |p| p.len());
    let node = (nodes - 1) * (id / hoses + 1) / (per_hose + 1);
    let Some(p0) = position(&first, hose, node) else {
        return report;
    };
    report.first_time = first["time"].as_f64().unwrap_or(0.0);
    let grab = json!({"type": "grab", "hand_id": id, "position": p0});
    let _ = tx.send(send(grab.clone())).await;
    let start = Instant::now();
    let end = start + Duration::from_secs_f64(seconds);
    let mut tick = tokio::time::interval(Duration::from_secs_f64(1.0 / RATE_HZ));
    let mut next_grab = regrab;
    let phase = id as f64; // the clients' circles are out of step
    loop {
        tokio::select! {
            _ = tick.tick() => {
                let now = Instant::now();
                if now >= end { break; }
                let t = (now - start).as_secs_f64();
                let message = if t >= next_grab {
                    next_grab += regrab;
                    grab.clone()
                } else {
                    let a = OMEGA * t + phase;
                    let target = [
                        p0[0] + RADIUS * (a.cos() - phase.cos()),
                        p0[1] + RADIUS * (a.sin() - phase.sin()),
                        p0[2],
                    ];
                    json!({"type": "move", "hand_id": id, "position": target})
                };
                report.inputs += 1;
                if tx.send(send(message)).await.is_err() { break; }
            }
            msg = rx.next() => {
                let Some(Ok(msg)) = msg else { break };
                let Message::Text(t) = msg else { continue };
                let Ok(v) = serde_json::from_str::<Value>(t.as_str()) else { continue };
                match v["type"].as_str() {
                    Some("snapshot") => {
                        report.snapshots += 1;
                        report.last_time = v["time"].as_f64().unwrap_or(report.last_time);
                        report.rollbacks = report.rollbacks.max(v["rollbacks"].as_u64().unwrap_or(0));
                        report.resets = report.resets.max(v["epoch"].as_u64().unwrap_or(0));
                        if let Some(n) = v["notice"].as_str() {
                            if n.contains("diverged") {
                                report.last_notice = Some(n.to_owned());
                            }
                        }
                    }
                    Some("error") => {
                        let code = v["code"].as_str().unwrap_or("?").to_owned();
                        *report.errors.entry(code).or_default() += 1;
                    }
                    _ => {}
                }
            }
        }
    }
    let _ = tx
        .send(send(json!({"type": "release", "hand_id": id})))
        .await;
    report
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

#[tokio::main(flavor = "multi_thread", worker_threads = 2)]
async fn main() {
    let a = match args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("soak: {e}");
            std::process::exit(2);
        }
    };
    let scene = pliant_scene::demo_scene().expect("the built-in demo loads");
    let options = SessionOptions {
        solver: Some(a.solver),
        folder: a.folder.clone(),
        ..SessionOptions::default()
    };
    let session = Session::start(&scene, options).expect("the demo session starts");
    let config = ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        ..ServerConfig::default()
    };
    let server = start(session, &config).await.expect("the server starts");
    let url = server.ws_url();
    eprintln!(
        "soak: {} clients × {RATE_HZ} Hz for {} s on {} ({} solver)",
        a.clients, a.seconds, url, a.solver
    );
    let started = Instant::now();
    let tasks: Vec<_> = (0..a.clients)
        .map(|id| tokio::spawn(client(url.clone(), id, a.clients, a.seconds, a.regrab)))
        .collect();
    // memory every 10 s (the whole process: server, simulation and clients)
    let mut memory = vec![(0.0, rss_kib())];
    while tasks.iter().any(|t| !t.is_finished()) {
        tokio::time::sleep(Duration::from_secs(1)).await;
        let t = started.elapsed().as_secs_f64();
        if t - memory.last().map_or(0.0, |m| m.0) >= 10.0 {
            memory.push((t, rss_kib()));
            eprintln!(
                "soak: {t:5.0} s  RSS {} MiB",
                memory.last().unwrap().1 / 1024
            );
        }
    }
    let wall = started.elapsed().as_secs_f64();
    let mut reports = Vec::new();
    for t in tasks {
        reports.push(t.await.unwrap_or_default());
    }
    server.stop();
    let rates: Vec<f64> = reports.iter().map(|r| r.snapshots as f64 / wall).collect();
    let simulated = reports
        .iter()
        .map(|r| r.last_time - r.first_time)
        .fold(0.0, f64::max);
    let mut errors = BTreeMap::new();
    for r in &reports {
        for (k, n) in &r.errors {
            *errors.entry(k.clone()).or_insert(0u64) += n;
        }
    }
    let inputs: u64 = reports.iter().map(|r| r.inputs).sum();
    let rollbacks = reports.iter().map(|r| r.rollbacks).max().unwrap_or(0);
    let resets = reports.iter().map(|r| r.resets).max().unwrap_or(0);
    let rss: Vec<u64> = memory.iter().map(|m| m.1).collect();
    let summary = json!({
        "solver": a.solver.to_string(),
        "clients": a.clients,
        "regrab_s": a.regrab,
        "wall_s": wall,
        "simulated_s_last_epoch": simulated,
        "snapshot_hz_per_client": {"min": rates.iter().cloned().fold(f64::INFINITY, f64::min), "median": median(rates.clone())},
        "inputs_sent": inputs,
        "inputs_refused": errors,
        "rollbacks": rollbacks,
        "resets": resets,
        "rss_mib": {"start": rss[0] as f64 / 1024.0, "max": rss.iter().max().copied().unwrap_or(0) as f64 / 1024.0, "end": rss.last().copied().unwrap_or(0) as f64 / 1024.0},
        "memory_kib_over_time": memory,
        "last_divergence": reports.iter().filter_map(|r| r.last_notice.clone()).next(),
    });
    println!("{}", serde_json::to_string_pretty(&summary).unwrap());
    if let Some(path) = a.json {
        if let Err(e) = std::fs::write(&path, summary.to_string()) {
            eprintln!("soak: cannot write {path}: {e}");
            std::process::exit(1);
        }
    }
}
