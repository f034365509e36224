//! The cost of hoses asleep on a moving part (`pliant_core::sleep::carried`) against the
//! same hoses asleep on the part at rest: 5 hoses × 30 elements lying straight and free on
//! a flat floor of 2·224² = 100 352 triangles (the contact benchmark's size), sleeping on;
//! the floor stands still, or glides along x at 0.05 m/s. Steps until every hose sleeps
//! (or `max warm-up` steps), then times `steps` steps (CPU time):
//!
//! ```sh
//! cargo run --release -p pliant --example carried_sleep_steps -- [steps] [glide: 0 | 1] [sleeping: 1 | 0] [max warm-up]
//! ```

use glam::DVec3;
use pliant_core::integrators::explicit;
use pliant_core::kinematics::{PartMotion, Profile, Slide};
use pliant_core::{
    HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings, State, WorldSpec,
};

const QUADS: usize = 224;
const ELEMENT_LENGTH: f64 = 0.02;
const RADIUS: f64 = 0.008;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let steps: u64 = args.get(1).map_or(Ok(20_000), |s| s.parse())?;
    let glide = args.get(2).map(String::as_str) == Some("1");
    let sleeping = args.get(3).map(String::as_str) != Some("0");
    let max_warm: u64 = args.get(4).map_or(Ok(60_000), |s| s.parse())?;
    let (mut model, mut state) = world(glide)?;
    model.threads = 1;
    state.sleep.enabled = sleeping;
    let mut warm = 0;
    while warm < max_warm && !(sleeping && state.sleep.sleeping() == model.hoses.len()) {
        explicit::step(&model, &mut state);
        warm += 1;
    }
    let t0 = cpu_seconds();
    let mut points = 0;
    for _ in 0..steps {
        explicit::step(&model, &mut state);
        points += state.contact.points.len();
    }
    let cpu = cpu_seconds() - t0;
    let carried = (0..model.hoses.len())
        .filter(|&h| state.sleep.carried.part_of_hose(h).is_some())
        .count();
    println!(
        "floor {}, sleeping {}: after {warm} steps, {steps} steps at {:.2} µs CPU per step, \
         {:.2} contact points per step, {} of {} hoses asleep ({carried} carried)",
        if glide { "gliding" } else { "still" },
        if sleeping { "on" } else { "off" },
        cpu * 1e6 / steps as f64,
        points as f64 / steps as f64,
        state.sleep.sleeping(),
        model.hoses.len(),
    );
    Ok(())
}

/// The flat floor (1.3 m × 2 m at z = 0) and five hoses lying on it along x, 0.1 m apart.
fn world(glide: bool) -> anyhow::Result<(Model, State)> {
    let (x0, x1, y0, y1) = (-0.3, 1.0, -0.8, 1.2);
    let mut vertices = Vec::with_capacity((QUADS + 1) * (QUADS + 1));
    for j in 0..=QUADS {
        for i in 0..=QUADS {
            let x = x0 + (x1 - x0) * i as f64 / QUADS as f64;
            let y = y0 + (y1 - y0) * j as f64 / QUADS as f64;
            vertices.push(DVec3::new(x, y, 0.0));
        }
    }
    let idx = |i: usize, j: usize| (j * (QUADS + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * QUADS * QUADS);
    for j in 0..QUADS {
        for i in 0..QUADS {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    let motion = glide.then_some({
        PartMotion::Slide(Slide {
            direction: DVec3::X,
            distance: Profile::UniformAcceleration {
                start_time: 0.0,
                initial_rate: 0.05,
                acceleration: 0.0,
            },
        })
    });
    let floor = RigidPartSpec {
        name: "floor".into(),
        vertices,
        triangles,
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion,
        parent: None,
        movable: false,
    };
    let hoses = (0..5)
        .map(|h| HoseSpec {
            name: format!("hose{h}"),
            material: Material::isotropic(12e6, 0.49, 940.0),
            nodes: (0..=30)
                .map(|i| DVec3::new(i as f64 * ELEMENT_LENGTH, 0.1 * h as f64, RADIUS))
                .collect(),
            sections: vec![Section::new(0.010, 2.0 * RADIUS)],
            normal_hint: Some(DVec3::Z),
        })
        .collect();
    let model = Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![floor],
        settings: SimSettings::default(),
    })?;
    let state = State::at_rest(&model);
    Ok((model, state))
}

/// User + system CPU time of this process \[s\].
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|s| s.parse::<f64>().ok()).unwrap_or(0.0);
    // fields 14 and 15 of /proc/pid/stat (utime, stime), counted after the ')' from 3
    (ticks(11) + ticks(12)) / 100.0
}
