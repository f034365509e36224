//! Fuzz targets of the file readers besides scenes and meshes: session
//! logs, calibration specs and curves, KBL harness files. Each never panics and checks
//! what its reader promises.

use crate::seeds;
use pliant_assembly::workcell::log::InputLog;
use pliant_assembly::workcell::log_reading::tick_limit;

/// The session log reader: never panics; what it reads has ticks that never go back and
/// stay within the limit, an end tick at or after the last input, and damage is named
/// by a line after the header, with the tick the log is trusted to.
pub fn session_log(input: &[u8]) -> Result<(), String> {
    let Ok(reading) = InputLog::read_bytes(input, "fuzz.jsonl") else {
        return Ok(());
    };
    let log = &reading.log;
    let limit = tick_limit(log.header.time_step);
    let mut last = 0;
    for i in &log.inputs {
        if i.tick < last || i.tick > limit {
            return Err(format!(
                "input tick {} after {last} (limit {limit})",
                i.tick
            ));
        }
        last = i.tick;
    }
    if log.end_tick < last || log.end_tick > limit {
        return Err(format!("end tick {} (last input {last})", log.end_tick));
    }
    if let Some(d) = &reading.damage {
        if d.line < 2 || d.readable_to != log.end_tick || d.reason.trim().is_empty() {
            return Err(format!("damage {d:?} with end tick {}", log.end_tick));
        }
    }
    if reading.damage.is_some() && reading.torn_tail.is_some() {
        return Err("both damage and a torn tail".into());
    }
    Ok(())
}

/// The calibration: a material it writes has only finite values.
fn calibration(spec: &str, curves: &[(String, String)]) -> Result<(), String> {
    let Ok(spec) = pliant_calibrate::Spec::parse(spec, "fuzz.toml") else {
        return Ok(());
    };
    match pliant_calibrate::calibrate_texts(spec, curves, "fuzz.toml") {
        Ok(c) => match c.material.first_non_finite() {
            Some((key, v)) => Err(format!("the material has {key} = {v}")),
            None => {
                let toml = c.material_toml();
                if toml.contains("nan") || toml.contains("inf") {
                    return Err(format!("material.toml holds a non-finite number:\n{toml}"));
                }
                Ok(())
            }
        },
        Err(e) if e.to_string().trim().is_empty() => Err("an error without a message".into()),
        Err(_) => Ok(()),
    }
}

fn example_curves() -> Vec<(String, String)> {
    seeds::CALIBRATION_CURVES
        .iter()
        .map(|(n, c)| (n.to_string(), c.to_string()))
        .collect()
}

/// A fuzzed calibration spec with the example curves.
pub fn calibration_spec(input: &[u8]) -> Result<(), String> {
    calibration(&String::from_utf8_lossy(input), &example_curves())
}

/// The example spec with one of its curves (chosen by the input's length) fuzzed.
pub fn calibration_csv(input: &[u8]) -> Result<(), String> {
    let mut curves = example_curves();
    let k = input.len() % curves.len();
    curves[k].1 = String::from_utf8_lossy(input).into_owned();
    calibration(seeds::CALIBRATION_SPEC, &curves)
}

/// The KBL and VEC readers: never panic; a harness they read has finite node positions
/// and control points and segments between existing nodes.
pub fn kbl(input: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let read = [
        pliant_harness::kbl::parse_kbl("fuzz.kbl", &text).ok(),
        pliant_harness::vec::parse_vec("fuzz.vec", &text).ok(),
    ];
    for h in read.into_iter().flatten() {
        if let Some(n) = h.nodes.iter().find(|n| !n.position.is_finite()) {
            return Err(format!("node {} at {}", n.kbl_id, n.position));
        }
        for s in &h.segments {
            if s.start_node >= h.nodes.len() || s.end_node >= h.nodes.len() {
                return Err(format!("segment {} between missing nodes", s.kbl_id));
            }
            let points = s.curves.iter().flat_map(|c| &c.control_points);
            if let Some(p) = points.into_iter().find(|p| !p.is_finite()) {
                return Err(format!("segment {} has a control point at {p}", s.kbl_id));
            }
        }
    }
    Ok(())
}
