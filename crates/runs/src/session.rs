//! Session folders (SPEC W2): a copy of the scene beside the input log of a study, so
//! that `pliant replay` can rebuild the workcell and reproduce the study bit for bit.

use crate::cad_converter::load_options;
use pliant_assembly::workcell::log::log_path;
use pliant_assembly::workcell::log::{
    header_line, line_text, InputLog, LogHeader, LogLine, LOG_FILE,
};
use pliant_assembly::workcell::log_reading::{LogDamage, TornTail};
use pliant_assembly::workcell::replay::replay;
use pliant_assembly::{NoObserver, Workcell, WorkcellError, WorkcellOptions};
use pliant_scene::load::MAX_SCENE_FILE_BYTES;
use pliant_scene::timeline::MAX_HANDS;
use pliant_scene::{load_scene_json_str_with, load_scene_str_with, LoadedScene};
use std::fs::File;
use std::io::Write;
use std::path::Path;

/// Creates the session folder `dir`: the scene's copy (`scene.toml` or `scene.json`) and
/// the input log's header. Returns the log file for [`Workcell::log_to`].
pub fn start_session_folder(
    dir: &Path,
    scene: &LoadedScene,
    cell: &Workcell,
) -> std::io::Result<File> {
    start_folder(dir, scene, *cell.options(), cell.time_step())
}

/// Writes a whole session folder at once: the scene's copy and the log `log` (its header
/// options and time step, its inputs, a mark at its last tick) — a live session's report
/// keeps its log beside it this way.
pub fn write_session_folder(
    dir: &Path,
    scene: &LoadedScene,
    log: &InputLog,
) -> std::io::Result<()> {
    let mut file = start_folder(dir, scene, log.header.options, log.header.time_step)?;
    let mut text = String::new();
    for s in &log.inputs {
        text.push_str(&line_text(&LogLine::Input(s.clone())));
    }
    text.push_str(&line_text(&LogLine::Mark { tick: log.end_tick }));
    file.write_all(text.as_bytes())?;
    file.flush()
}

fn start_folder(
    dir: &Path,
    scene: &LoadedScene,
    options: WorkcellOptions,
    time_step: f64,
) -> std::io::Result<File> {
    std::fs::create_dir_all(dir)?;
    let scene_file = if scene.is_json() {
        "scene.json"
    } else {
        "scene.toml"
    };
    std::fs::write(dir.join(scene_file), &scene.text)?;
    let header = LogHeader::new(
        &scene.name,
        &scene.source,
        scene_file,
        &scene.base_dir.display().to_string(),
        options,
        time_step,
    );
    let mut log = File::create(dir.join(LOG_FILE))?;
    log.write_all(header_line(&header).as_bytes())?;
    log.flush()?;
    Ok(log)
}

/// A session folder read back: its scene, its log, and a fresh workcell to replay it in.
pub struct Session {
    pub scene: LoadedScene,
    /// The log up to its damage, if any (see [`Session::damage`]).
    pub log: InputLog,
    /// Whether the log's lines carry checksums (a version 1 log does not).
    pub sealed: bool,
    /// The log's last line, torn by a writer killed mid-line (the log is read up to it).
    pub torn_tail: Option<TornTail>,
    /// The log's first damaged line: `log` stops before it. Only
    /// [`Session::open_up_to_damage`] opens such a session.
    pub damage: Option<LogDamage>,
}

impl Session {
    /// Reads the session folder `dir` (or its `inputs.jsonl`); a damaged log is an
    /// error naming the line and what would be lost.
    pub fn open(path: &Path) -> Result<Session, String> {
        let s = Self::open_up_to_damage(path)?;
        match &s.damage {
            Some(d) => Err(format!("{}: {d}", log_path(path).display())),
            None => Ok(s),
        }
    }

    /// Reads the session folder `dir` (or its `inputs.jsonl`), a damaged log up to its
    /// first damaged line (said in [`Session::damage`]).
    pub fn open_up_to_damage(path: &Path) -> Result<Session, String> {
        let reading = InputLog::read(path).map_err(|e| e.to_string())?;
        let log = reading.log;
        let dir = if path.is_dir() {
            path.to_path_buf()
        } else {
            path.parent().map(Path::to_path_buf).unwrap_or_default()
        };
        let file = dir.join(&log.header.scene_file);
        let text = pliant_files::read_regular_text(&file, MAX_SCENE_FILE_BYTES).map_err(|e| {
            format!(
                "{}: cannot read the session's scene copy: {}",
                e.path, e.kind
            )
        })?;
        let origin = file.display().to_string();
        let base = Path::new(&log.header.scene_base_dir);
        let scene = if log.header.scene_file.ends_with(".json") {
            load_scene_json_str_with(&text, &origin, base, &load_options())
        } else {
            load_scene_str_with(&text, &origin, base, &load_options())
        }
        .map_err(|e| e.to_string())?;
        Ok(Session {
            scene,
            log,
            sealed: reading.sealed,
            torn_tail: reading.torn_tail,
            damage: reading.damage,
        })
    }

    /// A fresh workcell with the log's options; its step must be the log's.
    pub fn workcell(&self) -> Result<Workcell, WorkcellError> {
        let options: WorkcellOptions = self.log.header.options;
        let cell = self.scene.workcell(options)?;
        if cell.time_step() != self.log.header.time_step {
            return Err(WorkcellError::TimeStep {
                scene: cell.time_step(),
                log: self.log.header.time_step,
            });
        }
        Ok(cell)
    }

    /// A fresh workcell ([`Session::workcell`]) with the whole log replayed into it
    /// (SPEC W2): the session as it ended.
    pub fn replayed(&self) -> Result<Workcell, String> {
        let mut cell = self.workcell().map_err(|e| e.to_string())?;
        replay(
            &mut cell,
            &self.log.inputs,
            self.log.end_tick,
            &mut NoObserver,
        )
        .map_err(|e| e.to_string())?;
        Ok(cell)
    }
}

/// The session as an ordinary scene file (TOML): the scene with its timeline replaced
/// by the log's inputs as actions, in the scene's length unit, with `run` actions for
/// the steps between them. Moves do not wait (the runs carry the time). Inputs a
/// timeline cannot say (ergonomic profile changes, removing one load case, arresting,
/// static solves) are listed in comments at the top, and a reset starts the timeline
/// over. Hands are numbered 0 … 7 in the order they first grab.
pub fn log_to_scene(scene: &LoadedScene, log: &InputLog, time_step: f64) -> Result<String, String> {
    use pliant_assembly::Input;
    use toml::value::{Array, Table};
    use toml::Value;
    let mut doc: Table = if scene.is_json() {
        let json: serde_json::Value =
            serde_json::from_str(&scene.text).map_err(|e| e.to_string())?;
        Value::try_from(json)
            .map_err(|e| e.to_string())?
            .as_table()
            .cloned()
            .unwrap_or_default()
    } else {
        toml::from_str(&scene.text).map_err(|e| e.to_string())?
    };
    let original = doc.remove("timeline");
    // the initial load cases the session started from: the scene's leading fixes and loads
    let initial: Array = match (&original, log.header.options.initial_loads) {
        (Some(Value::Array(a)), true) => a
            .iter()
            .take_while(|e| {
                matches!(
                    e.get("action").and_then(Value::as_str),
                    Some("fix" | "load")
                )
            })
            .cloned()
            .collect(),
        _ => Array::new(),
    };
    let per_m = 1.0 / scene.length_unit.to_metres();
    let point = |p: glam::DVec3| Value::Array((p * per_m).to_array().map(Value::Float).to_vec());
    let points = |ps: &[glam::DVec3]| Value::Array(ps.iter().map(|p| point(*p)).collect());
    let vector = |v: glam::DVec3| Value::Array(v.to_array().map(Value::Float).to_vec());
    let rotate = |r: glam::DVec3| {
        let mut t = Table::new();
        t.insert("axis".into(), vector(r.normalize_or_zero()));
        t.insert("angle_deg".into(), Value::Float(r.length().to_degrees()));
        Value::Table(t)
    };
    // a move's path, turn and duration; it does not wait (the runs carry the time)
    let motion =
        |t: &mut Table, waypoints: &[glam::DVec3], rotation: glam::DVec3, duration: f64| {
            if !waypoints.is_empty() {
                t.insert("to".into(), points(waypoints));
            }
            if rotation != glam::DVec3::ZERO {
                t.insert("rotate".into(), rotate(rotation));
            }
            t.insert("duration_s".into(), Value::Float(duration));
            t.insert("wait".into(), Value::Boolean(false));
        };
    let node = |t: &mut Table, n: &pliant_assembly::NodeRef| {
        t.insert(
            "hose".into(),
            Value::String(scene.hose_names[n.hose].clone()),
        );
        t.insert("node".into(), Value::Integer(n.node as i64));
    };
    let mut hand_numbers: Vec<u32> = Vec::new();
    let mut hand = |h: u32| -> Result<Value, String> {
        let k = match hand_numbers.iter().position(|x| *x == h) {
            Some(k) => k,
            None => {
                hand_numbers.push(h);
                hand_numbers.len() - 1
            }
        };
        if k >= MAX_HANDS {
            return Err(format!(
                "the session used more than {} hands; a timeline has hands 0 … {}",
                MAX_HANDS,
                MAX_HANDS - 1
            ));
        }
        Ok(Value::Integer(k as i64))
    };
    let mut actions = initial.clone();
    let mut notes = Vec::new();
    let mut tick = 0u64;
    let run = |actions: &mut Array, steps: u64| {
        if steps > 0 {
            let mut t = Table::new();
            t.insert("action".into(), Value::String("run".into()));
            t.insert("duration_s".into(), Value::Float(steps as f64 * time_step));
            actions.push(Value::Table(t));
        }
    };
    for s in &log.inputs {
        run(&mut actions, s.tick - tick);
        tick = s.tick;
        let time = s.tick as f64 * time_step;
        let mut t = Table::new();
        let action = match &s.input {
            Input::Fix { node: n } => {
                node(&mut t, n);
                "fix"
            }
            Input::Mount { node: n, part } => {
                node(&mut t, n);
                t.insert("part".into(), Value::String(part.clone()));
                "mount"
            }
            Input::Unload { node: n, name } => {
                node(&mut t, n);
                if let Some(name) = name {
                    t.insert("name".into(), Value::String(name.clone()));
                }
                "unload"
            }
            Input::Release { node: n } => {
                node(&mut t, n);
                "release"
            }
            Input::Tie { node: n, to } => {
                node(&mut t, n);
                let mut other = Table::new();
                node(&mut other, to);
                t.insert("to".into(), Value::Table(other));
                "tie"
            }
            Input::Load {
                node: n,
                force,
                moment,
                ramp,
                name,
            } => {
                node(&mut t, n);
                t.insert("force_n".into(), vector(*force));
                t.insert("moment_nm".into(), vector(*moment));
                if *ramp > 0.0 {
                    t.insert("ramp_s".into(), Value::Float(*ramp));
                }
                if let Some(name) = name {
                    t.insert("name".into(), Value::String(name.clone()));
                }
                "load"
            }
            Input::Drive {
                node: n,
                waypoints,
                rotation,
                duration,
            } => {
                node(&mut t, n);
                motion(&mut t, waypoints, *rotation, *duration);
                "move"
            }
            Input::Grab { hand: h, at, grip } => {
                t.insert("hand".into(), hand(*h)?);
                t.insert("at".into(), point(*at));
                if *grip != pliant_assembly::Grip::Firm {
                    t.insert("grip".into(), grip.name().into());
                }
                "grab"
            }
            Input::MoveHand {
                hand: h,
                waypoints,
                rotation,
                duration,
            } => {
                t.insert("hand".into(), hand(*h)?);
                motion(&mut t, waypoints, *rotation, *duration);
                "move_hand"
            }
            Input::AimHand {
                hand: h,
                position,
                orientation,
            } => {
                t.insert("hand".into(), hand(*h)?);
                t.insert("position".into(), point(*position));
                if let Some(q) = orientation {
                    let wxyz = [q.w, q.x, q.y, q.z].map(Value::Float).to_vec();
                    t.insert("orientation_wxyz".into(), Value::Array(wxyz));
                }
                "aim_hand"
            }
            Input::ReleaseHand { hand: h } => {
                t.insert("hand".into(), hand(*h)?);
                "release_hand"
            }
            Input::MovePart {
                part,
                by,
                to,
                duration,
            } => {
                t.insert("part".into(), Value::String(part.clone()));
                if let Some(by) = by {
                    t.insert("by".into(), point(*by));
                }
                if let Some(to) = to {
                    t.insert("to".into(), point(*to));
                }
                t.insert("duration_s".into(), Value::Float(*duration));
                t.insert("wait".into(), Value::Boolean(false));
                "move_part"
            }
            Input::RotatePart {
                part,
                axis,
                point: pivot,
                by,
                to,
                duration,
            } => {
                t.insert("part".into(), Value::String(part.clone()));
                t.insert("axis".into(), vector(*axis));
                if let Some(p) = pivot {
                    t.insert("point".into(), point(*p));
                }
                if let Some(by) = by {
                    t.insert("by_deg".into(), Value::Float(by.to_degrees()));
                }
                if let Some(to) = to {
                    t.insert("to_deg".into(), Value::Float(to.to_degrees()));
                }
                t.insert("duration_s".into(), Value::Float(*duration));
                t.insert("wait".into(), Value::Boolean(false));
                "rotate_part"
            }
            Input::Reset => {
                notes.push(format!(
                    "t = {time:.3} s (tick {}): reset — the timeline starts over here",
                    s.tick
                ));
                actions = initial.clone();
                continue;
            }
            other => {
                notes.push(format!(
                    "t = {time:.3} s (tick {}): `{}` has no timeline action and is left out: {}",
                    s.tick,
                    other.name(),
                    serde_json::to_string(other).unwrap_or_default()
                ));
                continue;
            }
        };
        t.insert("action".into(), Value::String(action.into()));
        actions.push(Value::Table(t));
    }
    run(&mut actions, log.end_tick.saturating_sub(tick));
    doc.insert("timeline".into(), Value::Array(actions));
    let mut text = format!(
        "# Scene '{}' with the timeline of a recorded session (pliant replay --timeline).\n",
        scene.name
    );
    for n in &notes {
        text.push_str(&format!("# note: {n}\n"));
    }
    text.push_str(&toml::to_string(&doc).map_err(|e| e.to_string())?);
    Ok(text)
}
