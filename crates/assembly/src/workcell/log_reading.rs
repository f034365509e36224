//! Reading an input log back (SPEC W2; evidence is never silently
//! lost). A log is read line by line and every line is checked — its checksum (version
//! 2), its JSON, its entry, its tick — and reading stops at the first line that fails.
//! Where that line is decides what it means:
//!
//! - the **last** line, not ended by a newline: a *torn tail*, what a writer killed in
//!   the middle of a line (`kill -9`, a crash, a full disk) leaves. The log is read up
//!   to it and the tear is reported ([`TornTail`]); nothing logged before the kill is
//!   lost.
//! - any other line: *damage* ([`LogDamage`]): the log was changed after it was
//!   written. The reading says which line, why, and what is lost after it (how many
//!   inputs, up to which tick); a replay refuses such a log unless told to replay up to
//!   the damage.
//!
//! A tick beyond [`tick_limit`] (more than [`MAX_LOG_TICKS`] steps, or more than
//! [`MAX_LOG_SECONDS`] of simulated time at the log's time step) is damage too: no
//! session runs that long, and replaying it would never end.

use super::input::StampedInput;
use super::log::{
    unseal, InputLog, LogError, LogHeader, LogLine, LOG_FORMAT, LOG_VERSION, LOG_VERSION_UNSEALED,
};

/// Most steps a log may span.
pub const MAX_LOG_TICKS: u64 = 10_000_000_000;

/// Most simulated time a log may span \[s\]: a week (a live session runs no faster than
/// real time).
pub const MAX_LOG_SECONDS: f64 = 7.0 * 24.0 * 3600.0;

/// The largest tick a log of time step `time_step` \[s\] may hold: [`MAX_LOG_TICKS`] or
/// [`MAX_LOG_SECONDS`] of simulated time, whichever is fewer steps.
pub fn tick_limit(time_step: f64) -> u64 {
    let by_time = MAX_LOG_SECONDS / time_step;
    if by_time.is_finite() && by_time > 0.0 {
        (by_time as u64).min(MAX_LOG_TICKS)
    } else {
        MAX_LOG_TICKS
    }
}

/// A last line cut short by a writer that was killed mid-line.
#[derive(Clone, Debug, PartialEq)]
pub struct TornTail {
    /// The line's number (1 = the header).
    pub line: usize,
    /// The bytes of it that were written.
    pub bytes: usize,
}

/// A damaged line in a log, and what reading stops short of because of it.
#[derive(Clone, Debug, PartialEq)]
pub struct LogDamage {
    /// The damaged line's number (1 = the header).
    pub line: usize,
    /// What is wrong with it.
    pub reason: String,
    /// Inputs that can still be told on the lines after it (not replayed).
    pub inputs_after: usize,
    /// The last tick named on the lines after it, if any.
    pub last_tick_after: Option<u64>,
    /// The last tick the log vouches for before the damage.
    pub readable_to: u64,
}

impl std::fmt::Display for LogDamage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "line {} is damaged: {}; the log can be trusted up to tick {}, and the damaged line and {} input(s) after it",
            self.line, self.reason, self.readable_to, self.inputs_after
        )?;
        if let Some(t) = self.last_tick_after {
            write!(f, " (up to tick {t})")?;
        }
        write!(f, " would be lost")
    }
}

/// A log as read: everything up to the first damaged line (or all of it), and what
/// reading found.
#[derive(Clone, Debug, PartialEq)]
pub struct LogReading {
    /// The inputs and end tick up to the damage or tear, if any.
    pub log: InputLog,
    /// Whether the lines carry checksums (version 2) — a version 1 log is checked only
    /// for its JSON, entries and ticks.
    pub sealed: bool,
    /// The last line, torn by a writer killed mid-line.
    pub torn_tail: Option<TornTail>,
    /// The first damaged line, if any.
    pub damage: Option<LogDamage>,
}

impl LogReading {
    /// The whole log, or an error naming the damage (a torn tail is no error).
    pub fn complete(self, origin: &str) -> Result<InputLog, LogError> {
        match self.damage {
            None => Ok(self.log),
            Some(d) => Err(LogError {
                path: origin.into(),
                reason: d.to_string(),
            }),
        }
    }
}

/// One line of the file: its number, its bytes, whether a newline ended it.
struct RawLine<'a> {
    number: usize,
    bytes: &'a [u8],
    ended: bool,
}

fn raw_lines(bytes: &[u8]) -> Vec<RawLine<'_>> {
    let pieces: Vec<&[u8]> = bytes.split(|b| *b == b'\n').collect();
    let count = pieces.len();
    pieces
        .into_iter()
        .enumerate()
        .map(|(k, piece)| RawLine {
            number: k + 1,
            bytes: piece,
            ended: k + 1 < count,
        })
        .filter(|l| !l.bytes.iter().all(u8::is_ascii_whitespace))
        .collect()
}

/// The entry of one line: checked seal (required when `sealed`), JSON, entry shape.
fn entry(line: &[u8], sealed: bool) -> Result<LogLine, String> {
    let text = std::str::from_utf8(line)
        .map_err(|e| format!("it is not UTF-8 text (byte {} is not)", e.valid_up_to() + 1))?;
    let text = text.trim_end_matches('\r');
    let (body, had_seal) = unseal(text)?;
    if sealed && !had_seal {
        return Err("it carries no checksum (every line of a version 2 log does)".into());
    }
    let value: serde_json::Value =
        serde_json::from_str(&body).map_err(|e| format!("it is not JSON: {e}"))?;
    if value.get("input").is_some() {
        serde_json::from_value::<StampedInput>(value).map(LogLine::Input)
    } else {
        serde_json::from_value::<LogLine>(value)
    }
    .map_err(|e| format!("it is not a log entry: {e}"))
}

/// What can still be told of the lines after a damaged one: their inputs and last tick
/// (their checksums are not trusted, their ticks only counted).
fn what_follows(lines: &[RawLine<'_>]) -> (usize, Option<u64>) {
    let mut inputs = 0;
    let mut last = None;
    for l in lines {
        let Ok(text) = std::str::from_utf8(l.bytes) else {
            continue;
        };
        let body = unseal(text)
            .map(|(b, _)| b.into_owned())
            .unwrap_or_else(|_| text.into());
        let Ok(value) = serde_json::from_str::<serde_json::Value>(&body) else {
            continue;
        };
        if value.get("input").is_some() {
            inputs += 1;
        }
        if let Some(t) = value.get("tick").and_then(|t| t.as_u64()) {
            last = Some(last.map_or(t, |l: u64| l.max(t)));
        }
    }
    (inputs, last)
}

impl InputLog {
    /// Reads a log from its bytes; `origin` names it in errors. Fails only when the
    /// header cannot be read (nothing of the log can be trusted then); damage further on
    /// is in the reading's [`LogReading::damage`].
    pub fn read_bytes(bytes: &[u8], origin: &str) -> Result<LogReading, LogError> {
        let fail = |reason: String| LogError {
            path: origin.into(),
            reason,
        };
        let lines = raw_lines(bytes);
        let first = lines
            .first()
            .ok_or_else(|| fail("the log is empty (no header line)".into()))?;
        let not_a_log = |why: String| {
            fail(format!(
                "line {}: expected the header ({{\"header\": {{...}}}}) — is this a Pliant input log? ({why})",
                first.number
            ))
        };
        let header: LogHeader = match entry(first.bytes, false) {
            Ok(LogLine::Header { header }) => header,
            Ok(_) => return Err(not_a_log("the first line is an input or a mark".into())),
            Err(why) => return Err(not_a_log(why)),
        };
        if header.format != LOG_FORMAT
            || !(LOG_VERSION_UNSEALED..=LOG_VERSION).contains(&header.version)
        {
            return Err(fail(format!(
                "line {}: format '{}' version {} — this Pliant reads '{LOG_FORMAT}' versions {LOG_VERSION_UNSEALED} to {LOG_VERSION}",
                first.number, header.format, header.version
            )));
        }
        let sealed = header.version >= 2;
        if sealed {
            entry(first.bytes, true)
                .map_err(|why| fail(format!("line {}: {why}", first.number)))?;
        }
        let limit = tick_limit(header.time_step);
        let mut inputs = Vec::new();
        let mut end_tick = 0;
        let mut torn_tail = None;
        let mut damage = None;
        for (k, line) in lines.iter().enumerate().skip(1) {
            let checked = entry(line.bytes, sealed).and_then(|e| {
                let tick = match &e {
                    LogLine::Input(i) => i.tick,
                    LogLine::Mark { tick } => *tick,
                    LogLine::Header { .. } => return Err("a second header".into()),
                };
                if tick > limit {
                    return Err(format!(
                        "tick {tick} is beyond the {limit} steps a log may span ({MAX_LOG_TICKS} steps or {MAX_LOG_SECONDS} s of simulated time at the log's time step of {:e} s)",
                        header.time_step
                    ));
                }
                if matches!(e, LogLine::Input(_)) && tick < end_tick {
                    return Err(format!(
                        "tick {tick} comes after tick {end_tick}: ticks never go back"
                    ));
                }
                Ok(e)
            });
            match checked {
                Ok(LogLine::Input(i)) => {
                    end_tick = i.tick;
                    inputs.push(i);
                }
                Ok(LogLine::Mark { tick }) => end_tick = end_tick.max(tick),
                Ok(LogLine::Header { .. }) => unreachable!("refused above"),
                Err(reason) => {
                    if k + 1 == lines.len() && !line.ended {
                        torn_tail = Some(TornTail {
                            line: line.number,
                            bytes: line.bytes.len(),
                        });
                    } else {
                        let (inputs_after, last_tick_after) = what_follows(&lines[k + 1..]);
                        damage = Some(LogDamage {
                            line: line.number,
                            reason,
                            inputs_after,
                            last_tick_after,
                            readable_to: end_tick,
                        });
                    }
                    break;
                }
            }
        }
        Ok(LogReading {
            log: InputLog {
                header,
                inputs,
                end_tick,
            },
            sealed,
            torn_tail,
            damage,
        })
    }

    /// Reads a whole log from its text; a damaged line is an error naming it (a torn
    /// last line is not: the log is read up to it).
    pub fn parse(text: &str, origin: &str) -> Result<InputLog, LogError> {
        Self::read_bytes(text.as_bytes(), origin)?.complete(origin)
    }

    /// Reads `inputs.jsonl` of a session folder (or the log file itself): a regular file
    /// of at most [`pliant_files::MAX_LOG_BYTES`].
    pub fn read(path: &std::path::Path) -> Result<LogReading, LogError> {
        let file = super::log::log_path(path);
        let shown = file.display().to_string();
        let bytes =
            pliant_files::read_regular_file(&file, pliant_files::MAX_LOG_BYTES).map_err(|e| {
                LogError {
                    path: shown.clone(),
                    reason: format!("cannot read the input log: {}", e.kind),
                }
            })?;
        Self::read_bytes(&bytes, &shown)
    }
}

#[cfg(test)]
mod tests {
    use super::super::log::{header_line, line_text};
    use super::*;
    use crate::workcell::{Input, WorkcellOptions};

    fn header() -> LogHeader {
        LogHeader::new(
            "s",
            "s.toml",
            "scene.toml",
            ".",
            WorkcellOptions::default(),
            1e-3,
        )
    }

    /// A log of `n` inputs (a release of hand 1 every 10 ticks) and a final mark.
    fn log_text(n: u64) -> String {
        let mut s = header_line(&header());
        for k in 0..n {
            s.push_str(&line_text(&LogLine::Input(StampedInput {
                tick: 10 * k,
                input: Input::Reset,
            })));
        }
        s.push_str(&line_text(&LogLine::Mark { tick: 10 * n }));
        s
    }

    #[test]
    fn a_whole_log_reads_back_sealed() {
        let r = InputLog::read_bytes(log_text(5).as_bytes(), "t").unwrap();
        assert!(r.sealed && r.damage.is_none() && r.torn_tail.is_none());
        assert_eq!(r.log.inputs.len(), 5);
        assert_eq!(r.log.end_tick, 50);
    }

    #[test]
    fn a_changed_line_in_the_middle_is_damage_naming_what_is_lost() {
        let text = log_text(194);
        // line 98 (the 97th input, tick 960): one digit changed, still valid JSON
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        lines[97] = lines[97].replacen("960", "961", 1);
        let damaged = lines.join("\n") + "\n";
        let r = InputLog::read_bytes(damaged.as_bytes(), "t").unwrap();
        let d = r.damage.clone().unwrap();
        assert_eq!(d.line, 98);
        assert!(d.reason.contains("checksum"), "{}", d.reason);
        assert_eq!(r.log.inputs.len(), 96);
        assert_eq!(d.readable_to, 950);
        assert_eq!(d.inputs_after, 97);
        assert_eq!(d.last_tick_after, Some(1940));
        let e = r.complete("t").unwrap_err().to_string();
        assert!(e.contains("line 98") && e.contains("97 input(s)"), "{e}");
    }

    #[test]
    fn a_line_cut_in_the_middle_is_damage_not_a_torn_tail() {
        let text = log_text(10);
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        lines[4].truncate(20); // a JSON "end of input" error, but not the last line
        let damaged = lines.join("\n") + "\n";
        let r = InputLog::read_bytes(damaged.as_bytes(), "t").unwrap();
        assert_eq!(r.damage.unwrap().line, 5);
        assert!(r.torn_tail.is_none());
    }

    #[test]
    fn a_torn_last_line_reads_up_to_it() {
        let mut text = log_text(3);
        text.push_str("{\"tick\":30,\"input\":{\"aim_ha");
        let r = InputLog::read_bytes(text.as_bytes(), "t").unwrap();
        assert!(r.damage.is_none());
        assert_eq!(r.torn_tail, Some(TornTail { line: 6, bytes: 27 }));
        assert_eq!(r.log.inputs.len(), 3);
        assert_eq!(r.log.end_tick, 30);
        // a complete last line that fails its checksum was not torn: damage
        let mut lines: Vec<String> = log_text(3).lines().map(String::from).collect();
        let last = lines.len() - 1;
        lines[last] = lines[last].replacen("30", "31", 1);
        let r = InputLog::read_bytes((lines.join("\n") + "\n").as_bytes(), "t").unwrap();
        assert_eq!(r.damage.unwrap().line, 5);
    }

    #[test]
    fn absurd_ticks_are_damage() {
        for tick in [1_000_000_000_000u64, 1 << 63, u64::MAX] {
            let mut text = log_text(2);
            text.push_str(&line_text(&LogLine::Mark { tick }));
            text.push_str(&line_text(&LogLine::Mark { tick: 30 }));
            let r = InputLog::read_bytes(text.as_bytes(), "t").unwrap();
            let d = r.damage.unwrap();
            assert_eq!(d.line, 5);
            assert!(d.reason.contains("beyond"), "{}", d.reason);
            assert_eq!(r.log.end_tick, 20);
        }
        assert_eq!(tick_limit(1e-3), 604_800_000);
        assert_eq!(tick_limit(1e-9), MAX_LOG_TICKS);
        assert_eq!(tick_limit(0.0), MAX_LOG_TICKS);
    }

    #[test]
    fn version_1_logs_without_checksums_still_read() {
        let mut h = header();
        h.version = 1;
        let mut text = serde_json::to_string(&LogLine::Header { header: h }).unwrap() + "\n";
        text.push_str("{\"tick\":0,\"input\":\"reset\"}\n{\"tick\":7}\n");
        let r = InputLog::read_bytes(text.as_bytes(), "old").unwrap();
        assert!(!r.sealed && r.damage.is_none());
        assert_eq!((r.log.inputs.len(), r.log.end_tick), (1, 7));
        // but a version 2 line without its checksum is damage
        let text = log_text(1).replace(&line_text(&LogLine::Mark { tick: 10 }), "{\"tick\":10}\n");
        let r = InputLog::read_bytes(text.as_bytes(), "t").unwrap();
        assert!(r.damage.unwrap().reason.contains("no checksum"));
    }

    #[test]
    fn an_unreadable_header_is_an_error() {
        let e = InputLog::read_bytes(b"{\"tick\": 1}\n", "bad").unwrap_err();
        assert!(e.to_string().contains("header"), "{e}");
        let e = InputLog::read_bytes(b"", "empty").unwrap_err();
        assert!(e.to_string().contains("empty"), "{e}");
        let mut text = log_text(1);
        text.replace_range(20..21, "X");
        assert!(InputLog::read_bytes(text.as_bytes(), "t").is_err());
    }
}
