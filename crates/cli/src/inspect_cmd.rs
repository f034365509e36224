//! `pliant inspect SCENE [--json]`: what a scene builds — its hoses (length, elements,
//! node positions), junctions (degree, position; a junction body's own mass, centre of
//! mass and inertia tensor about it, and its shape: the part, its kind and box),
//! fixings (stubs and clips) and parts —
//! in metres, for people (a summary) and scripts (JSON).

use anyhow::{anyhow, Result};
use pliant_core::Model;
use pliant_scene::{load_scene_file_with, LoadedScene, PartInfo};
use serde_json::{json, Value};
use std::path::Path;
use std::process::ExitCode;

/// The scene's contents as JSON (see the module doc).
pub fn describe(scene: &LoadedScene, model: &Model) -> Value {
    let hoses: Vec<Value> = model
        .hoses
        .iter()
        .enumerate()
        .map(|(h, info)| {
            let nodes: Vec<[f64; 3]> = info.nodes().map(|i| model.rest_x[i].to_array()).collect();
            json!({
                "name": info.name,
                "length_m": scene.hoses[h].length,
                "elements": info.element_count,
                "d_outer_m": scene.hoses[h].d_outer,
                "min_bend_radius_m": scene.hoses[h].min_bend_radius,
                "nodes": nodes,
            })
        })
        .collect();
    let junctions: Vec<Value> = model
        .junctions
        .iter()
        .map(|j| {
            let body = &model.bodies[j.body];
            let ends: Vec<Value> = j
                .nodes
                .iter()
                .map(|&i| {
                    let h = model
                        .hoses
                        .iter()
                        .position(|info| info.nodes().contains(&i))
                        .unwrap_or(0);
                    let info = &model.hoses[h];
                    let end = if i == info.first_node { "start" } else { "end" };
                    json!({ "hose": info.name, "end": end })
                })
                .collect();
            // a welded branch point has no body of its own
            let own = (j.own.mass > 0.0 || !j.own.lumped).then(|| {
                json!({
                    "mass_kg": j.own.mass,
                    "centre_of_mass_m": j.own.centre.to_array(),
                    "inertia_kg_m2": j.own.inertia.transpose().to_cols_array_2d(),
                    "lumped_on_outlets": j.own.lumped,
                })
            });
            json!({
                "name": j.name,
                "degree": j.degree(),
                "position": body.rest_centre.to_array(),
                "mass_kg": body.mass,
                "body": own,
                "shape": junction_shape(scene, model, j),
                "ends": ends,
            })
        })
        .collect();
    let mut fixings: Vec<Value> = scene
        .stubs
        .iter()
        .map(|s| {
            json!({
                "name": s.name,
                "kind": "stub",
                "hose": scene.hose_names[s.hose_end.hose],
                "spec": s.spec,
            })
        })
        .collect();
    fixings.extend(scene.connectors.iter().map(|c| {
        let m = &c.mating;
        let counterpart = m.counterpart();
        json!({
            "name": c.name,
            "kind": "connector",
            "hose": scene.hose_names[c.hose_end.hose],
            "spec": {
                "origin": counterpart.origin().to_array(),
                "axis": counterpart.axis().to_array(),
                "travel": counterpart.length(),
                "size": counterpart.diameter(),
                "mating_force": m.curve(),
                "latch_at": m.latch_at(),
                "retention_force": m.retention(),
            },
        })
    }));
    fixings.extend(scene.clips.iter().map(|c| {
        json!({
            "name": c.name,
            "kind": "clip",
            "hose": scene.hose_names[c.hose],
            "spec": c.spec,
        })
    }));
    let parts: Vec<Value> = scene
        .parts
        .iter()
        .map(|p| {
            json!({
                "name": p.name,
                "source": p.source,
                "triangles": p.triangles,
                "bounds_m": [p.bounds.0.to_array(), p.bounds.1.to_array()],
            })
        })
        .collect();
    json!({
        "scene": scene.name,
        "source": scene.source,
        "hoses": hoses,
        "junctions": junctions,
        "fixings": fixings,
        "parts": parts,
        "elements": model.elements.len(),
        "nodes": model.node_count(),
        "time_step_s": model.time_step,
    })
}

/// The part a junction body carries as its shape (`body.part`), in the scene's parts.
fn shape_part<'a>(
    scene: &'a LoadedScene,
    model: &Model,
    j: &pliant_core::Junction,
) -> Option<&'a PartInfo> {
    let name = &model.environment.parts.get(j.shape?)?.name;
    scene.parts.iter().find(|p| &p.name == name)
}

/// A junction body's shape as JSON: the part's name, its kind (`box`, `cylinder`,
/// `sphere` or the mesh file), its triangles and its bounding box at rest; `null`
/// without a shape.
fn junction_shape(scene: &LoadedScene, model: &Model, j: &pliant_core::Junction) -> Value {
    match shape_part(scene, model, j) {
        Some(p) => json!({
            "part": p.name,
            "kind": p.source,
            "triangles": p.triangles,
            "bounds_m": [p.bounds.0.to_array(), p.bounds.1.to_array()],
            "size_m": (p.bounds.1 - p.bounds.0).to_array(),
        }),
        None => Value::Null,
    }
}

/// Loads and builds the scene and prints what it holds.
pub fn run(scene_path: &Path, as_json: bool) -> Result<ExitCode> {
    let scene = load_scene_file_with(scene_path, &pliant_runs::load_options())
        .map_err(|e| anyhow!("{e}"))?;
    let model = scene.build_model().map_err(|e| anyhow!(e))?;
    let d = describe(&scene, &model);
    if as_json {
        println!("{}", serde_json::to_string_pretty(&d)?);
        return Ok(ExitCode::SUCCESS);
    }
    let total: f64 = scene.hoses.iter().map(|h| h.length).sum();
    println!(
        "{}: {} hose(s), {:.3} m in all, {} elements, {} junction(s), {} stub(s), {} connector(s), {} clip(s), {} part(s); explicit time step {:.3e} s",
        scene.source,
        model.hoses.len(),
        total,
        model.elements.len(),
        model.junctions.len(),
        scene.stubs.len(),
        scene.connectors.len(),
        scene.clips.len(),
        scene.parts.len(),
        model.time_step
    );
    for (h, info) in model.hoses.iter().enumerate() {
        let x = |i: usize| model.rest_x[i] * 1e3;
        let (a, b) = (x(info.first_node), x(info.first_node + info.node_count - 1));
        println!(
            "  hose {:<24} {:>9.1} mm  {:>4} elements  d {:>5.1} mm  from ({:.1}, {:.1}, {:.1}) to ({:.1}, {:.1}, {:.1}) mm",
            info.name,
            scene.hoses[h].length * 1e3,
            info.element_count,
            scene.hoses[h].d_outer * 1e3,
            a.x,
            a.y,
            a.z,
            b.x,
            b.y,
            b.z
        );
    }
    for j in &model.junctions {
        let p = model.bodies[j.body].rest_centre * 1e3;
        let shape = match shape_part(&scene, &model, j) {
            Some(part) => {
                let size = (part.bounds.1 - part.bounds.0) * 1e3;
                format!(
                    "  shape: part {} ({}, {:.1} × {:.1} × {:.1} mm)",
                    part.name, part.source, size.x, size.y, size.z
                )
            }
            None => String::new(),
        };
        println!(
            "  junction {:<20} degree {:>2}  at ({:.1}, {:.1}, {:.1}) mm{shape}",
            j.name,
            j.nodes.len(),
            p.x,
            p.y,
            p.z
        );
    }
    for f in d["fixings"].as_array().into_iter().flatten() {
        println!(
            "  {} {} on hose {}",
            f["kind"].as_str().unwrap_or(""),
            f["name"].as_str().unwrap_or(""),
            f["hose"].as_str().unwrap_or("")
        );
    }
    for p in &scene.parts {
        println!(
            "  part {} ({} triangles, {})",
            p.name, p.triangles, p.source
        );
    }
    Ok(ExitCode::SUCCESS)
}
