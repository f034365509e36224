//! The input log of a study (SPEC W2): one JSON object per line — a header naming the
//! scene and the workcell options, then every input with the tick before which it took
//! effect, and now and then a mark saying how far the study has got. Append-only and
//! flushed line by line, so a crash or a killed server loses at most the time since the
//! last mark. A session folder holds the log (`inputs.jsonl`) beside a copy of the scene.

use super::input::StampedInput;
use super::WorkcellOptions;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The log file's name in a session folder.
pub const LOG_FILE: &str = "inputs.jsonl";
/// What the header's `format` says.
pub const LOG_FORMAT: &str = "pliant-input-log";
/// The log format's version.
pub const LOG_VERSION: u32 = 1;

/// The first line: what the inputs were given to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LogHeader {
    pub format: String,
    pub version: u32,
    pub pliant_version: String,
    /// The scene's name and where it came from.
    pub scene_name: String,
    pub scene_source: String,
    /// The copy of the scene file in the session folder (`scene.toml` or `scene.json`).
    pub scene_file: String,
    /// The folder relative mesh paths of the scene are read from.
    pub scene_base_dir: String,
    /// The workcell's options (solver, sleeping, initial loads, hand limits).
    pub options: WorkcellOptions,
    /// The step the study advanced by \[s\] (a replay checks it has the same).
    pub time_step: f64,
}

impl LogHeader {
    /// A header of this Pliant version.
    pub fn new(
        scene_name: &str,
        scene_source: &str,
        scene_file: &str,
        scene_base_dir: &str,
        options: WorkcellOptions,
        time_step: f64,
    ) -> Self {
        LogHeader {
            format: LOG_FORMAT.into(),
            version: LOG_VERSION,
            pliant_version: env!("CARGO_PKG_VERSION").into(),
            scene_name: scene_name.into(),
            scene_source: scene_source.into(),
            scene_file: scene_file.into(),
            scene_base_dir: scene_base_dir.into(),
            options,
            time_step,
        }
    }
}

/// One line of the log.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum LogLine {
    Header { header: LogHeader },
    Input(StampedInput),
    Mark { tick: u64 },
}

/// A log as read back.
#[derive(Clone, Debug, PartialEq)]
pub struct InputLog {
    pub header: LogHeader,
    pub inputs: Vec<StampedInput>,
    /// The last tick the log vouches for (its last mark or input).
    pub end_tick: u64,
}

/// Why a log could not be read.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {reason}")]
pub struct LogError {
    pub path: String,
    pub reason: String,
}

impl InputLog {
    /// Reads a log from its text; `origin` names it in errors.
    pub fn parse(text: &str, origin: &str) -> Result<InputLog, LogError> {
        let fail = |reason: String| LogError {
            path: origin.into(),
            reason,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, first) = lines
            .next()
            .ok_or_else(|| fail("the log is empty (no header line)".into()))?;
        let header = match serde_json::from_str::<LogLine>(first) {
            Ok(LogLine::Header { header }) => header,
            _ => return Err(fail(
                "line 1: expected the header ({\"header\": {...}}) — is this a Pliant input log?"
                    .into(),
            )),
        };
        if header.format != LOG_FORMAT || header.version != LOG_VERSION {
            return Err(fail(format!(
                "line 1: format '{}' version {} — this Pliant reads '{LOG_FORMAT}' version {LOG_VERSION}",
                header.format, header.version
            )));
        }
        let mut inputs = Vec::new();
        let mut end_tick = 0;
        for (k, line) in lines {
            let n = k + 1;
            let value: serde_json::Value = match serde_json::from_str(line) {
                Ok(v) => v,
                // a line cut short by a crash can only be the last one
                Err(e) if e.is_eof() => break,
                Err(e) => return Err(fail(format!("line {n}: {e}"))),
            };
            let entry = if value.get("input").is_some() {
                serde_json::from_value::<StampedInput>(value).map(LogLine::Input)
            } else {
                serde_json::from_value::<LogLine>(value)
            }
            .map_err(|e| fail(format!("line {n}: {e}")))?;
            match entry {
                LogLine::Input(i) => {
                    if i.tick < end_tick {
                        return Err(fail(format!(
                            "line {n}: tick {} comes after tick {end_tick}: ticks never go back",
                            i.tick
                        )));
                    }
                    end_tick = i.tick;
                    inputs.push(i);
                }
                LogLine::Mark { tick } => end_tick = end_tick.max(tick),
                LogLine::Header { .. } => return Err(fail(format!("line {n}: a second header"))),
            }
        }
        Ok(InputLog {
            header,
            inputs,
            end_tick,
        })
    }

    /// Reads `inputs.jsonl` of a session folder (or the log file itself).
    pub fn read(path: &Path) -> Result<InputLog, LogError> {
        let file = log_path(path);
        let text = std::fs::read_to_string(&file).map_err(|e| LogError {
            path: file.display().to_string(),
            reason: format!("cannot read the input log: {e}"),
        })?;
        Self::parse(&text, &file.display().to_string())
    }
}

/// The log file of a session folder, or `path` itself when it is a file.
pub fn log_path(path: &Path) -> PathBuf {
    if path.is_dir() {
        path.join(LOG_FILE)
    } else {
        path.to_path_buf()
    }
}

/// The header's line (what a shell writes first).
pub fn header_line(header: &LogHeader) -> String {
    let mut s = serde_json::to_string(&LogLine::Header {
        header: header.clone(),
    })
    .expect("a header serialises");
    s.push('\n');
    s
}
