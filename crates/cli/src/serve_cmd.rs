//! `pliant serve`: the interactive server (SPEC I6; protocol in docs/protocol.md).

use anyhow::Context;
use pliant_server::session::SessionOptions;
use pliant_server::{ServerConfig, Session};
use std::path::Path;
use std::process::ExitCode;

pub fn run(scene: Option<&Path>, host: &str, port: u16) -> anyhow::Result<ExitCode> {
    let scene = match scene {
        Some(p) => pliant_scene::load_scene_file(p)
            .with_context(|| format!("cannot load {}", p.display()))?,
        None => pliant_scene::demo_scene().context("cannot load the demo scene")?,
    };
    let session = Session::start(&scene, SessionOptions::default())?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let config = ServerConfig {
            host: host.to_string(),
            port,
        };
        let server = pliant_server::start(session, &config)
            .await
            .with_context(|| format!("cannot listen on {host}:{port}"))?;
        println!("Pliant serving '{}' at {}", scene.name, server.url());
        println!(
            "WebSocket (protocol v1): {}  — Ctrl-C stops",
            server.ws_url()
        );
        tokio::select! {
            r = server.wait() => r.context("server failed")?,
            _ = tokio::signal::ctrl_c() => println!("stopped"),
        }
        Ok(ExitCode::SUCCESS)
    })
}
