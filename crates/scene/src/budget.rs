//! What a scene will cost before it is built: the memory its hoses and parts need, from
//! their element and triangle counts, checked against a limit while the scene loads —
//! each hose and each part is counted before the next is built, so a scene too big for
//! the machine is refused with the field and the estimate instead of aborting on a
//! failed allocation.
//!
//! The per-item sizes are measured (peak resident memory of `pliant run`, release build,
//! slope over 10 000 → 50 000 elements and 0.33 → 1.3 million sphere triangles):
//! explicit ≈ 1.4 kB per element, implicit and static ≈ 3.7 kB (Newton's banded
//! matrices); ≈ 380 B per triangle (the mesh, its contact copy and bounding-volume
//! tree), plus the 128 B of its bounding planes for contact (`contact/planes.rs`, made
//! once per triangle since 2026-11-27; added by size, not re-measured). The estimate takes the larger element size, as the solver may be changed
//! after loading (`--solver`, the viewer).
//!
//! Hose–hose contact pairs are counted too: the pair list holds every pair of
//! beams whose boxes overlap, a few per beam for hoses laid apart (inside the per-element
//! size) but every pair for hoses laid on top of each other (5 000 hoses of 4 elements
//! along one line: 2·10⁸ pairs). They are counted on the rest geometry once all hoses
//! are built (`pliant_core::contact::rest_pair_count`), at
//! [`pliant_core::contact::BYTES_PER_CONTACT_PAIR`] (16 B) each. What the report writer holds
//! grows with the elements (one profile per hose, the scene copied for at most
//! `MAX_SCENE_PICTURES` hoses) and is inside the per-element size. While a run goes,
//! the pairs listed at once are capped at what the memory limit leaves beside the rest
//! ([`Budget::contact_pair_room`], `SimSettings::max_contact_pairs`): hoses piling up
//! beyond it stop the run as diverged. What grows with the run's length — the samples
//! kept for the report per recorded time ([`Recorded`]) — is checked when the run is
//! planned (`LoadedScene::check_planned_steps`); the range-of-motion rows and the
//! worker's samples are capped however long a run goes
//! ([`pliant_assembly::series_cap`]), and a live session, which has no planned end, is
//! checked against those caps when it starts (`LoadedScene::check_live_session`). The
//! estimate is tested against the measured peak in `crates/cli/tests/budget.rs`.

use crate::error::FieldError;
use pliant_assembly::fasteners::FastenerSample;
use pliant_assembly::report::HandSample;
use pliant_core::contact::{rest_pair_count, BYTES_PER_CONTACT_PAIR};
use pliant_core::HoseSpec;

/// Memory a run needs per beam element \[bytes\] (measured, see the module doc; rounded up).
pub const BYTES_PER_ELEMENT: u64 = 4096;
/// Memory a run needs per rigid-part triangle \[bytes\] (measured, rounded up).
pub const BYTES_PER_TRIANGLE: u64 = 512;
/// Memory of a run with an empty scene \[bytes\] (program, library, buffers).
pub const BASE_BYTES: u64 = 16 * 1024 * 1024;
/// Default memory limit of a scene \[bytes\]: 4 GiB.
pub const DEFAULT_MAX_MEMORY_BYTES: u64 = 4 * 1024 * 1024 * 1024;

/// Default most steps of a planned run (`pliant run`; `--max-steps` raises it): 10⁹ —
/// hours of wall time for a single short hose, far more for a large model.
pub const DEFAULT_MAX_STEPS: u64 = 1_000_000_000;

/// Limits a scene is checked against while it loads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Largest estimated memory of a run \[bytes\].
    pub max_memory_bytes: u64,
    /// Most beam elements (bounds the cost of one step; `pliant serve` limits the
    /// scenes its clients send so that no scene stalls the session).
    pub max_elements: u64,
    /// Most rigid-part triangles (bounds what a live session sends every client).
    pub max_triangles: u64,
    /// Most steps of a planned run: its timeline's duration over the time step
    /// ([`check_steps`], before the run starts).
    pub max_steps: u64,
    /// Where the limits are raised, for messages (e.g. "--max-memory").
    pub raise_with: &'static str,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_memory_bytes: DEFAULT_MAX_MEMORY_BYTES,
            max_elements: u64::MAX,
            max_triangles: u64::MAX,
            max_steps: DEFAULT_MAX_STEPS,
            raise_with: "--max-memory",
        }
    }
}

impl Limits {
    /// The default limits with another memory limit.
    pub fn with_memory(max_memory_bytes: u64) -> Limits {
        Limits {
            max_memory_bytes,
            ..Limits::default()
        }
    }
}

/// The running estimate of a scene's size.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    /// Beam elements of every hose.
    pub elements: u64,
    /// Triangles of every rigid part.
    pub triangles: u64,
    /// Hose–hose contact pairs listed at rest (counted up to what the limit allows).
    pub contact_pairs: u64,
}

impl Estimate {
    /// Estimated peak memory of a run \[bytes\].
    pub fn memory_bytes(&self) -> u64 {
        BASE_BYTES
            .saturating_add(self.elements.saturating_mul(BYTES_PER_ELEMENT))
            .saturating_add(self.triangles.saturating_mul(BYTES_PER_TRIANGLE))
            .saturating_add(self.contact_pairs.saturating_mul(BYTES_PER_CONTACT_PAIR))
    }
}

/// An estimate growing as a scene loads, and the limits it must stay within.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    pub estimate: Estimate,
    pub limits: Limits,
    /// The contact pairs were counted only up to what the limit allows (there are more).
    pairs_capped: bool,
}

impl Budget {
    pub fn new(limits: Limits) -> Budget {
        Budget {
            estimate: Estimate::default(),
            limits,
            pairs_capped: false,
        }
    }

    /// Adds `elements` from the hose at `field`; fails if the scene no longer fits.
    pub fn add_elements(&mut self, field: &str, elements: u64) -> Result<(), FieldError> {
        self.estimate.elements = self.estimate.elements.saturating_add(elements);
        self.check(field)
    }

    /// Adds `triangles` from the part at `field` (counted before they are made, where
    /// possible); fails if the scene no longer fits.
    pub fn add_triangles(&mut self, field: &str, triangles: u64) -> Result<(), FieldError> {
        self.estimate.triangles = self.estimate.triangles.saturating_add(triangles);
        self.check(field)
    }

    /// Adds the hose–hose contact pairs of `hoses` at rest (all hoses built; `field`
    /// names them in errors); fails if the scene no longer fits. Counting stops once the
    /// limit is passed.
    pub fn add_contact_pairs(&mut self, field: &str, hoses: &[HoseSpec]) -> Result<(), FieldError> {
        let room = self
            .limits
            .max_memory_bytes
            .saturating_sub(self.estimate.memory_bytes());
        let most = room / BYTES_PER_CONTACT_PAIR + 1;
        let pairs = rest_pair_count(hoses, most);
        self.pairs_capped = pairs >= most;
        self.estimate.contact_pairs = self.estimate.contact_pairs.saturating_add(pairs);
        self.check(field)
    }

    /// The most hose–hose contact pairs a run may list at once: what the memory limit
    /// leaves beside everything else the estimate counts (at least the pairs at rest),
    /// for [`pliant_core::SimSettings::max_contact_pairs`].
    pub fn contact_pair_room(&self) -> usize {
        let others = Estimate {
            contact_pairs: 0,
            ..self.estimate
        }
        .memory_bytes();
        let room = self.limits.max_memory_bytes.saturating_sub(others) / BYTES_PER_CONTACT_PAIR;
        usize::try_from(room.max(self.estimate.contact_pairs)).unwrap_or(usize::MAX)
    }

    fn check(&self, field: &str) -> Result<(), FieldError> {
        let (e, l) = (&self.estimate, &self.limits);
        for (count, max, what) in [
            (e.elements, l.max_elements, "elements"),
            (e.triangles, l.max_triangles, "part triangles"),
        ] {
            if count > max {
                return Err(FieldError::about(
                    field,
                    format!(
                        "the scene up to here has {count} {what}; at most {max} are allowed here (raise with {})",
                        l.raise_with
                    ),
                ));
            }
        }
        let need = self.estimate.memory_bytes();
        if need <= self.limits.max_memory_bytes {
            return Ok(());
        }
        Err(FieldError::about(
            field,
            format!(
                "the scene up to here ({} elements, {} triangles, {}{} hose–hose contact pairs at rest) needs {} {}; the limit is {} (raise it with {})",
                self.estimate.elements,
                self.estimate.triangles,
                if self.pairs_capped { "more than " } else { "" },
                self.estimate.contact_pairs,
                if self.pairs_capped { "more than" } else { "≈" },
                human_bytes(need),
                human_bytes(self.limits.max_memory_bytes),
                self.limits.raise_with
            ),
        ))
    }
}

/// Refuses a run of `planned` seconds at `time_step` \[s\] beyond `max_steps` steps,
/// with its estimate. Returns the planned steps.
pub fn check_steps(planned: f64, time_step: f64, max_steps: u64) -> Result<u64, String> {
    refuse_beyond((planned / time_step).ceil(), planned, time_step, max_steps)
}

/// Refuses a run of `steps` steps of `time_step` \[s\] (a replayed log's end tick) beyond
/// `max_steps`, with the same estimate as [`check_steps`]. Returns `steps`.
pub fn check_step_count(steps: u64, time_step: f64, max_steps: u64) -> Result<u64, String> {
    refuse_beyond(steps as f64, steps as f64 * time_step, time_step, max_steps)
}

fn refuse_beyond(steps: f64, planned: f64, time_step: f64, max_steps: u64) -> Result<u64, String> {
    if steps.is_finite() && steps >= 0.0 && steps <= max_steps as f64 {
        return Ok(steps as u64);
    }
    let hours = if steps.is_finite() && time_step > 0.0 {
        // at a guess of 1 µs per step, the least a step of one short hose costs here
        format!(
            " (at least {:.1e} hours of wall time)",
            steps * 1e-6 / 3600.0
        )
    } else {
        String::new()
    };
    Err(format!(
        "the run is planned at {planned:.3e} s with a time step of {time_step:.3e} s: \
         {steps:.3e} steps{hours}; at most {max_steps} are allowed (raise with --max-steps)"
    ))
}

/// Memory each recorded time holds until the report is written, per hand \[bytes\]: its
/// sample for the report's plots, in a growing `Vec` (up to twice its length).
pub const RECORD_BYTES_PER_HAND: u64 = 2 * std::mem::size_of::<HandSample>() as u64;
/// The same per stub or clip (its force sample).
pub const RECORD_BYTES_PER_FASTENER: u64 = 2 * std::mem::size_of::<FastenerSample>() as u64;

/// The times a run of `planned` seconds records at `interval` \[s\] (0: every one of its
/// `steps` steps), with the first and the last.
pub fn planned_records(planned: f64, interval: f64, steps: u64) -> u64 {
    let by_interval = if interval > 0.0 {
        (planned / interval).ceil()
    } else {
        f64::INFINITY
    };
    let records = if by_interval.is_finite() && by_interval >= 0.0 {
        (by_interval as u64).min(steps)
    } else {
        steps
    };
    records.saturating_add(2)
}

/// The same per node, for a caller that keeps every node's position at each recorded
/// time (the Python `RunResult`).
pub const RECORD_BYTES_PER_NODE: u64 = 2 * std::mem::size_of::<glam::DVec3>() as u64;

/// What a run keeps in memory at each recorded time until its report is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recorded {
    /// Recorded times ([`planned_records`]).
    pub records: u64,
    /// A sample per hand, per stub or clip, and (when kept) a position per node.
    pub hands: u64,
    pub fasteners: u64,
    pub nodes: u64,
    /// Values of a range-of-motion row (`[sweep]`), 8 bytes each; 0 without a sweep.
    pub sweep_values: u64,
    /// Whether a worker is posed (a sample per posed instant).
    pub worker: bool,
}

/// Most memory one capped series holds \[bytes\]: its cap
/// ([`pliant_assembly::series_cap::MAX_SERIES_BYTES`]), twice over as its `Vec` may have
/// grown to twice its length before it was thinned.
pub const MAX_CAPPED_SERIES_BYTES: u64 = 2 * pliant_assembly::series_cap::MAX_SERIES_BYTES as u64;

impl Recorded {
    /// Memory the recorded series take \[bytes\].
    pub fn bytes(&self) -> u64 {
        let per_record = self
            .hands
            .saturating_mul(RECORD_BYTES_PER_HAND)
            .saturating_add(self.fasteners.saturating_mul(RECORD_BYTES_PER_FASTENER))
            .saturating_add(self.nodes.saturating_mul(RECORD_BYTES_PER_NODE));
        // the range-of-motion rows and the worker's samples are capped however long the
        // run (pliant_assembly::series_cap)
        let capped = |bytes_per_record: u64| {
            self.records
                .saturating_mul(2 * bytes_per_record)
                .min(MAX_CAPPED_SERIES_BYTES)
        };
        let worker = if self.worker {
            capped(std::mem::size_of::<pliant_assembly::worker::WorkerSample>() as u64)
        } else {
            0
        };
        self.records
            .saturating_mul(per_record)
            .saturating_add(capped(self.sweep_values.saturating_mul(8)))
            .saturating_add(worker)
    }
}

/// Refuses a run whose recorded series ([`Recorded::bytes`]) on top of the scene's
/// estimate exceed the memory limit, with the numbers.
pub fn check_recorded(estimate: &Estimate, limits: &Limits, kept: &Recorded) -> Result<(), String> {
    let Recorded {
        records,
        hands,
        fasteners,
        nodes,
        sweep_values,
        worker: _,
    } = *kept;
    let series = kept.bytes();
    let need = estimate.memory_bytes().saturating_add(series);
    if need <= limits.max_memory_bytes {
        return Ok(());
    }
    Err(format!(
        "the run records {records} times ({hands} hand(s), {fasteners} stub(s) and clip(s), {nodes} node position(s) kept, {sweep_values} range-of-motion value(s)): \
         {} of series for the report on top of the scene's {}; {} in all, the limit is {} \
         (raise it with {}, or record less often: [output] record_interval_s)",
        human_bytes(series),
        human_bytes(estimate.memory_bytes()),
        human_bytes(need),
        human_bytes(limits.max_memory_bytes),
        limits.raise_with
    ))
}

/// `bytes` as "3.2 GB" / "640 MB" / "12 kB" (decimal units).
pub fn human_bytes(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else if b >= 1e6 {
        format!("{:.0} MB", b / 1e6)
    } else {
        format!("{:.0} kB", b / 1e3)
    }
}

/// Parses a size such as "2G", "512M", "2GB", "1.5 GiB" or a byte count.
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let value: f64 = number
        .parse()
        .map_err(|_| format!("\"{text}\" is not a size (e.g. 2G, 512M, 1000000)"))?;
    let scale = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "kib" => 1024.0,
        "m" | "mb" => 1e6,
        "mib" => 1024.0 * 1024.0,
        "g" | "gb" => 1e9,
        "gib" => 1024.0 * 1024.0 * 1024.0,
        "t" | "tb" => 1e12,
        other => {
            return Err(format!(
                "unknown size unit \"{other}\" in \"{text}\"; use k, M, G or T"
            ))
        }
    };
    let bytes = value * scale;
    if !bytes.is_finite() || bytes < 1.0 || bytes > u64::MAX as f64 {
        return Err(format!("\"{text}\" is not a usable size"));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hose_that_breaks_the_limit_is_named_with_the_estimate() {
        let limits = Limits::with_memory(2_000_000_000);
        let mut e = Budget::new(limits);
        e.add_elements("hoses[0]", 100_000).unwrap();
        let err = e.add_elements("hoses[1]", 400_000).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("hoses[1]") && text.contains("500000 elements"),
            "{text}"
        );
        assert!(
            text.contains("≈ 2.1 GB") && text.contains("2.0 GB") && text.contains("--max-memory"),
            "{text}"
        );
        let mut t = Budget::new(limits);
        assert!(t
            .add_triangles("parts[0].sphere.subdivisions", 20 * 4u64.pow(12))
            .is_err());
    }

    #[test]
    fn a_run_beyond_the_step_limit_is_refused_with_its_estimate() {
        assert_eq!(check_steps(1.0, 1e-3, 1000), Ok(1000));
        let err = check_steps(60.0, 3.7e-11, DEFAULT_MAX_STEPS).unwrap_err();
        assert!(
            err.contains("1.622e12 steps") && err.contains("--max-steps"),
            "{err}"
        );
        assert!(check_steps(1.0, 0.0, u64::MAX).is_err());
        assert!(check_steps(f64::INFINITY, 1e-3, u64::MAX).is_err());
    }

    #[test]
    fn sizes_parse_with_units() {
        assert_eq!(parse_bytes("2G").unwrap(), 2_000_000_000);
        assert_eq!(parse_bytes("512MiB").unwrap(), 512 * 1024 * 1024);
        assert_eq!(parse_bytes("1.5 GB").unwrap(), 1_500_000_000);
        assert_eq!(parse_bytes("1000").unwrap(), 1000);
        assert!(parse_bytes("-1G").is_err());
        assert!(parse_bytes("2 parsecs").is_err());
        assert!(parse_bytes("0").is_err());
    }
}
