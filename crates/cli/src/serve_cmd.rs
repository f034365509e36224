//! `pliant serve`: the interactive server (SPEC I6; protocol in docs/protocol.md).

use anyhow::Context;
use pliant_server::session::SessionOptions;
use pliant_server::{ServerConfig, Session};
use std::path::Path;
use std::process::ExitCode;

pub fn run(
    scene_path: Option<&Path>,
    host: &str,
    port: u16,
    solver: Option<pliant_core::SolverKind>,
) -> anyhow::Result<ExitCode> {
    let scene = match scene_path {
        Some(p) => pliant_scene::load_scene_file(p)
            .with_context(|| format!("cannot load {}", p.display()))?,
        None => pliant_scene::demo_scene().context("cannot load the demo scene")?,
    };
    // Scenes opened in the browser arrive as text: their relative mesh paths are resolved
    // against the served scene's folder (the examples folder for the built-in demo).
    let scene_dir = match scene_path {
        Some(p) => p.parent().map(Path::to_path_buf).unwrap_or_default(),
        None if Path::new("examples").is_dir() => "examples".into(),
        None => Default::default(),
    };
    // every session is a recording (SPEC W2): the scene's copy and the input log go into
    // a fresh folder under out/sessions as the session runs
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let folder = Path::new("out")
        .join("sessions")
        .join(format!("session-{stamp}"));
    let session = Session::start(
        &scene,
        SessionOptions {
            solver,
            folder: Some(folder.clone()),
            ..SessionOptions::default()
        },
    )?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let config = ServerConfig {
            host: host.to_string(),
            port,
            scene_dir,
        };
        let server = pliant_server::start(session, &config)
            .await
            .with_context(|| format!("cannot listen on {host}:{port}"))?;
        println!("Pliant serving '{}' at {}", scene.name, server.url());
        if !pliant_server::assets::viewer_embedded() {
            println!("(this binary has no browser viewer: run scripts/build-web.sh, then rebuild)");
        }
        println!(
            "WebSocket (protocol v1): {}  — Ctrl-C stops",
            server.ws_url()
        );
        // Scripts and tests read the URL from stdout: make sure it is not left buffered.
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
        println!(
            "Recording the session in {d} — `pliant replay {d}` replays it and writes its report",
            d = folder.display()
        );
        tokio::select! {
            r = server.wait() => r.context("server failed")?,
            _ = tokio::signal::ctrl_c() => println!("stopped; the session is in {}", folder.display()),
        }
        Ok(ExitCode::SUCCESS)
    })
}
