//! The input log of a study (SPEC W2): one JSON object per line — a header naming the
//! scene and the workcell options, then every input with the tick before which it took
//! effect, and now and then a mark saying how far the study has got. Append-only and
//! flushed line by line, so a crash or a killed server loses at most the time since the
//! last mark. A session folder holds the log (`inputs.jsonl`) beside a copy of the scene.
//!
//! Version 2 (evidence is never silently lost) seals every line with
//! its CRC-32: the line's JSON object gets a last member `"crc32":"xxxxxxxx"`, the
//! CRC-32 (IEEE) in hex of the line as it would read without that member, so each line
//! stays JSON and a changed byte anywhere in it is found ([`seal`], [`unseal`]).
//! Version 1 logs (no checksums) are still read, with what can be checked without them.
//! How a log is read back — damage, torn last lines and absurd ticks included — is
//! [`super::log_reading`].

use super::input::StampedInput;
use super::WorkcellOptions;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// The log file's name in a session folder.
pub const LOG_FILE: &str = "inputs.jsonl";
/// What the header's `format` says.
pub const LOG_FORMAT: &str = "pliant-input-log";
/// The log format's version this Pliant writes: 2, every line sealed with its CRC-32.
pub const LOG_VERSION: u32 = 2;
/// The oldest version still read: 1, the same lines without checksums.
pub const LOG_VERSION_UNSEALED: u32 = 1;

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

/// The log file of a session folder, or `path` itself when it is a file.
pub fn log_path(path: &Path) -> PathBuf {
    if path.is_dir() {
        path.join(LOG_FILE)
    } else {
        path.to_path_buf()
    }
}

/// The header's line (what a shell writes first), sealed, with its newline.
pub fn header_line(header: &LogHeader) -> String {
    line_text(&LogLine::Header {
        header: header.clone(),
    })
}

/// One line of the log as written: the entry's JSON sealed with its checksum, and a
/// newline — written in one piece, so a killed writer can only tear the last line.
pub fn line_text(line: &LogLine) -> String {
    let json = serde_json::to_string(line).expect("a log line serialises");
    let mut s = seal(&json);
    s.push('\n');
    s
}

/// The member a sealed line ends with, up to the checksum's hex digits.
const SEAL_KEY: &str = ",\"crc32\":\"";
/// Length of the seal: the key, eight hex digits, the closing `"}`.
const SEAL_LEN: usize = SEAL_KEY.len() + 8 + 2;

/// `json` (one JSON object, not empty) with the member `"crc32":"xxxxxxxx"` added last:
/// the CRC-32 of `json` itself.
pub fn seal(json: &str) -> String {
    debug_assert!(json.ends_with('}') && json.len() > 2);
    let crc = crc32fast::hash(json.as_bytes());
    format!("{}{SEAL_KEY}{crc:08x}\"}}", &json[..json.len() - 1])
}

/// A line read back: the JSON its checksum was taken of and whether the line was
/// sealed at all — or why its seal does not hold.
pub fn unseal(line: &str) -> Result<(Cow<'_, str>, bool), String> {
    let n = line.len();
    let sealed = n > SEAL_LEN
        && line.ends_with("\"}")
        && line.is_char_boundary(n - SEAL_LEN)
        && line[n - SEAL_LEN..].starts_with(SEAL_KEY);
    if !sealed {
        return Ok((line.into(), false));
    }
    let hex = &line[n - 10..n - 2];
    let stated = Some(hex)
        .filter(|h| h.bytes().all(|b| b.is_ascii_hexdigit()))
        .and_then(|h| u32::from_str_radix(h, 16).ok())
        .ok_or_else(|| format!("its checksum '{hex}' is not eight hex digits"))?;
    let body = format!("{}}}", &line[..n - SEAL_LEN]);
    let actual = crc32fast::hash(body.as_bytes());
    if actual != stated {
        return Err(format!(
            "its checksum does not match (the line says {stated:08x}, its content gives {actual:08x}): the line was changed after it was written"
        ));
    }
    Ok((body.into(), true))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sealed_line_is_json_and_any_changed_byte_is_found() {
        let line = line_text(&LogLine::Mark { tick: 1234 });
        assert_eq!(line.matches('\n').count(), 1);
        let line = line.trim_end();
        let value: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(value["tick"], 1234);
        let (body, sealed) = unseal(line).unwrap();
        assert!(sealed);
        assert_eq!(body, "{\"tick\":1234}");
        let changed = line.replace("1234", "1235");
        let e = unseal(&changed).unwrap_err();
        assert!(e.contains("checksum does not match"), "{e}");
        // an old line without a seal reads as it is
        let (old, sealed) = unseal("{\"tick\":5}").unwrap();
        assert_eq!((old.as_ref(), sealed), ("{\"tick\":5}", false));
    }
}
