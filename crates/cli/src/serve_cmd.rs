//! `pliant serve`: the interactive server (SPEC I6; protocol in docs/protocol.md).

use anyhow::Context;
use pliant_server::access::{is_loopback, Access};
use pliant_server::session::SessionOptions;
use pliant_server::{ServerConfig, Session};
use std::path::Path;
use std::process::ExitCode;

pub fn run(
    scene_path: Option<&Path>,
    host: &str,
    port: u16,
    solver: Option<pliant_core::SolverKind>,
    access: Access,
    max_clients: usize,
) -> anyhow::Result<ExitCode> {
    if max_clients == 0 {
        anyhow::bail!("--max-clients must be at least 1");
    }
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
    let sessions_dir = Path::new("out").join("sessions");
    let folder = pliant_server::server::new_session_folder(&sessions_dir);
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
            sessions_dir: Some(sessions_dir.clone()),
            access: access.clone(),
            max_clients,
            ..ServerConfig::default()
        };
        let mut server = pliant_server::start(session, &config)
            .await
            .with_context(|| format!("cannot listen on {host}:{port}"))?;
        let url = match access.token() {
            Some(t) => format!("{}?token={t}", server.url()),
            None => server.url(),
        };
        // before the URL line: scripts that read the URL may stop the server right after
        if !is_loopback(host) {
            eprintln!(
                "WARNING: listening on {host}, reachable from the network: whoever has the URL \
                 below (with its token) can drive this session and load scenes. Only the \
                 server's own pages{} may connect.",
                if access.token().is_some() { " presenting the token" } else { "" }
            );
        }
        println!("Pliant serving '{}' at {url}", scene.name);
        if !pliant_server::assets::viewer_embedded() {
            println!("(this binary has no browser viewer: run scripts/build-web.sh, then rebuild)");
        }
        println!(
            "WebSocket (protocol v1): {}{}  — Ctrl-C stops",
            server.ws_url(),
            access.token().map(|t| format!("?token={t}")).unwrap_or_default()
        );
        // Scripts and tests read the URL from stdout: make sure it is not left buffered.
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
        println!(
            "Recording the session in {} (the viewer's Report button, or Ctrl-C, writes its report)",
            folder.display()
        );
        let _ = std::io::stdout().flush();
        tokio::select! {
            r = server.wait() => return r.context("server failed").map(|_| ExitCode::SUCCESS),
            _ = tokio::signal::ctrl_c() => {}
        }
        // Stopping the server reports the session as it stands (SPEC W2).
        let session = server.session();
        server.stop();
        println!("stopped; writing the session's report …");
        let written = tokio::task::spawn_blocking(move || {
            let out = session
                .next_report_folder()
                .ok_or_else(|| "the session records into no folder".to_string())?;
            session.report(&out).map(|(verdict, _)| (out, verdict))
        })
        .await
        .map_err(|e| anyhow::anyhow!("writing the report failed: {e}"))?;
        match written {
            Ok((out, verdict)) => {
                println!("verdict so far: {}", verdict.word());
                for r in &verdict.reasons {
                    println!("  - {r}");
                }
                println!("report: {}", out.join("report.html").display());
            }
            Err(e) => eprintln!("error: the session's report could not be written: {e}"),
        }
        Ok(ExitCode::SUCCESS)
    })
}
