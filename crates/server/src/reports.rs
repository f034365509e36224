//! Disk and CPU of a live session's reports, bounded (200 `report` messages
//! wrote 2.6 GB in 90 s, each costing more the longer the session ran). A report replays
//! the session's whole log and writes its CSVs, so per session:
//!
//! - **one at a time, at most one per [`ReportLimits::min_interval`]**: a `report` while
//!   one is written, or sooner after the last one began, is refused with `rate_limited`
//!   and the seconds to wait;
//! - **each report's time series within half of [`ReportLimits::max_report_bytes`]**:
//!   their record interval is raised so that their estimated size fits (the reply says
//!   so; the VTK frames, at most ≈ 200, add ≈ 16 kB per node);
//! - **all reports within [`ReportLimits::max_session_bytes`]**: before a report is
//!   written, the oldest reports of the session are removed until it fits, and the
//!   reply lists them.
//!
//! The replay runs on a blocking worker, never on the simulation thread; the simulation
//! thread only copies the input log (a memory copy, at most once per interval).

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

/// Bounds on one session's reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReportLimits {
    /// Shortest time between the starts of two reports of a session.
    pub min_interval: Duration,
    /// Largest estimated size of one report \[bytes\].
    pub max_report_bytes: u64,
    /// Largest total size of a session's reports \[bytes\].
    pub max_session_bytes: u64,
}

/// Default [`ReportLimits::min_interval`].
pub const REPORT_INTERVAL: Duration = Duration::from_secs(10);
/// Default [`ReportLimits::max_report_bytes`]: 256 MB.
pub const MAX_REPORT_BYTES: u64 = 256_000_000;
/// Default [`ReportLimits::max_session_bytes`]: 1 GB.
pub const MAX_SESSION_REPORT_BYTES: u64 = 1_000_000_000;

impl Default for ReportLimits {
    fn default() -> Self {
        ReportLimits {
            min_interval: REPORT_INTERVAL,
            max_report_bytes: MAX_REPORT_BYTES,
            max_session_bytes: MAX_SESSION_REPORT_BYTES,
        }
    }
}

/// Estimated bytes of a report's time series per recorded instant and node (a
/// `nodes.csv` row is ≈ 110 characters; contacts, colours and energy add less).
const BYTES_PER_NODE_RECORD: f64 = 128.0;
/// The record interval \[s\] that keeps the time series of a report of `simulated`
/// seconds of `nodes` nodes within half of `max_bytes`: the scene's `interval` if they
/// fit, else the smallest that does.
pub fn record_interval_within(interval: f64, simulated: f64, nodes: usize, max_bytes: u64) -> f64 {
    let nodes = nodes.max(1) as f64;
    let room = 0.5 * max_bytes as f64;
    let records = room / (BYTES_PER_NODE_RECORD * nodes);
    let needed = simulated / records.max(1.0);
    if needed > interval {
        needed
    } else {
        interval
    }
}

/// The reports of one session so far and whether one is being written.
#[derive(Debug, Default)]
pub struct ReportLedger {
    state: Mutex<LedgerState>,
}

#[derive(Debug, Default)]
struct LedgerState {
    busy: bool,
    last_start: Option<Instant>,
    /// Reports written, oldest first, with their size \[bytes\].
    kept: VecDeque<(PathBuf, u64)>,
    /// Number of the next report folder (`report-N`).
    next: u64,
}

/// The right to write one report; dropping it lets the next one start.
#[derive(Debug)]
pub struct ReportTicket<'a> {
    ledger: &'a ReportLedger,
}

impl Drop for ReportTicket<'_> {
    fn drop(&mut self) {
        self.ledger.lock().busy = false;
    }
}

impl ReportLedger {
    fn lock(&self) -> std::sync::MutexGuard<'_, LedgerState> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The right to write a report now, or why not (one is being written; the last one
    /// began less than `limits.min_interval` ago).
    pub fn begin(&self, limits: &ReportLimits, now: Instant) -> Result<ReportTicket<'_>, String> {
        let mut s = self.lock();
        if s.busy {
            return Err(
                "a report of this session is being written; ask again when its reply has come"
                    .into(),
            );
        }
        if let Some(last) = s.last_start {
            let since = now.saturating_duration_since(last);
            if since < limits.min_interval {
                return Err(format!(
                    "at most one report per {} s per session: ask again in {:.1} s",
                    limits.min_interval.as_secs_f64(),
                    (limits.min_interval - since).as_secs_f64()
                ));
            }
        }
        s.busy = true;
        s.last_start = Some(now);
        Ok(ReportTicket { ledger: self })
    }

    /// A new folder `report-N` in `dir`, N counting up (never reusing a removed one's).
    pub fn next_folder(&self, dir: &Path) -> PathBuf {
        let mut s = self.lock();
        loop {
            s.next += 1;
            let p = dir.join(format!("report-{}", s.next));
            if !p.exists() {
                return p;
            }
        }
    }

    /// Removes the oldest reports until `need` more bytes fit within
    /// `limits.max_session_bytes`; the folders removed.
    pub fn make_room(&self, limits: &ReportLimits, need: u64) -> Vec<PathBuf> {
        let mut s = self.lock();
        let mut removed = Vec::new();
        let mut total: u64 = s.kept.iter().map(|k| k.1).sum();
        while total.saturating_add(need) > limits.max_session_bytes {
            let Some((folder, bytes)) = s.kept.pop_front() else {
                break;
            };
            let _ = std::fs::remove_dir_all(&folder);
            total -= bytes;
            removed.push(folder);
        }
        removed
    }

    /// Notes a report written into `folder`; its size \[bytes\].
    pub fn written(&self, folder: &Path) -> u64 {
        let bytes = folder_bytes(folder);
        self.lock().kept.push_back((folder.to_path_buf(), bytes));
        bytes
    }
}

/// Bytes of the regular files in `dir` and its subfolders (links not followed).
pub fn folder_bytes(dir: &Path) -> u64 {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .map(|e| match e.file_type() {
            Ok(t) if t.is_dir() => folder_bytes(&e.path()),
            Ok(t) if t.is_file() => e.metadata().map_or(0, |m| m.len()),
            _ => 0,
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_report_at_a_time_and_one_per_interval() {
        let limits = ReportLimits::default();
        let ledger = ReportLedger::default();
        let t = Instant::now();
        let ticket = ledger.begin(&limits, t).unwrap();
        assert!(ledger
            .begin(&limits, t)
            .unwrap_err()
            .contains("being written"));
        drop(ticket);
        let err = ledger
            .begin(&limits, t + Duration::from_secs(1))
            .err()
            .unwrap();
        assert!(err.contains("ask again in 9.0 s"), "{err}");
        assert!(ledger.begin(&limits, t + REPORT_INTERVAL).is_ok());
    }

    #[test]
    fn a_long_session_is_recorded_coarser_to_fit_its_report() {
        // 1 h of 21 000 nodes at 10 ms would be 9.7 TB of nodes.csv
        let interval = record_interval_within(0.01, 3600.0, 21_000, MAX_REPORT_BYTES);
        let records = 3600.0 / interval;
        let bytes = records * 21_000.0 * BYTES_PER_NODE_RECORD;
        assert!(bytes <= 0.5 * MAX_REPORT_BYTES as f64, "{bytes}");
        assert_eq!(
            record_interval_within(0.01, 10.0, 100, MAX_REPORT_BYTES),
            0.01
        );
    }
}
