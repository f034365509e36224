//! `pliant serve`: the interactive server (SPEC I6; protocol in docs/protocol.md).

use anyhow::Context;
use pliant_scene::LoadOptions;
use pliant_server::access::{is_loopback, Access};
use pliant_server::limits::ClientScenes;
use pliant_server::session::SessionOptions;
use pliant_server::{ServerConfig, Session};
use std::path::Path;
use std::process::ExitCode;

/// What `pliant serve` was asked for.
pub struct ServeArgs<'a> {
    pub scene: Option<&'a Path>,
    pub host: &'a str,
    pub port: u16,
    pub solver: Option<pliant_core::SolverKind>,
    pub access: Access,
    pub max_clients: usize,
    /// The folder client scenes may read meshes from (`--assets`).
    pub assets: Option<&'a Path>,
    /// The haptic stream's UDP port on 127.0.0.1 (`--haptic-port`).
    pub haptic_port: Option<u16>,
    /// Limits of the served scene; client scenes get [`ClientScenes::within`] these.
    pub limits: LoadOptions,
}

pub fn run(args: &ServeArgs) -> anyhow::Result<ExitCode> {
    let &ServeArgs {
        scene: scene_path,
        host,
        port,
        solver,
        max_clients,
        ..
    } = args;
    let access = args.access.clone();
    if max_clients == 0 {
        anyhow::bail!("--max-clients must be at least 1");
    }
    let scene = match scene_path {
        Some(p) => pliant_scene::load_scene_file_with(p, &args.limits)
            .with_context(|| format!("cannot load {}", p.display()))?,
        None => pliant_scene::demo_scene().context("cannot load the demo scene")?,
    };
    // Scenes opened in the browser arrive as text: their relative mesh paths are resolved
    // against the served scene's folder (the examples folder for the built-in demo).
    let scene_dir = match (args.assets, scene_path) {
        (Some(dir), _) => {
            if !dir.is_dir() {
                anyhow::bail!("--assets {}: not a folder", dir.display());
            }
            dir.to_path_buf()
        }
        (None, Some(p)) => p.parent().map(Path::to_path_buf).unwrap_or_default(),
        (None, None) if Path::new("examples").is_dir() => "examples".into(),
        (None, None) => Default::default(),
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
            client_scenes: ClientScenes::within(&args.limits),
            haptic_port: args.haptic_port,
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
        if let Some(addr) = server.haptic_addr() {
            println!(
                "Haptic force stream (UDP, loopback only, docs/protocol.md): {addr}{}",
                if access.token().is_some() { " — datagrams carry the token" } else { "" }
            );
        }
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
            session.report(&out).map(|(verdict, _, _)| (out, verdict))
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
