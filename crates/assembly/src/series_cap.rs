//! A time series kept within a fixed size however long a session runs. A live session
//! has no planned end, so a series recorded at a fixed interval would grow without bound
//! (a range-of-motion row per checked instant, a worker sample per posed instant). When
//! the series reaches its cap, every other row is dropped — except the rows the caller
//! keeps (the worst instants a verdict names, and the last) — and from then on only every
//! second instant offered is recorded: the series' resolution halves each time it fills,
//! its memory stays below the cap, and what it found at its worst instants stays exact.

/// Largest size of one capped series \[bytes\] (a sweep's rows, a worker's samples).
pub const MAX_SERIES_BYTES: usize = 32 * 1024 * 1024;

/// The cap of one series and how thinned it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SeriesCap {
    max_rows: usize,
    /// Every `stride`-th instant offered is recorded (a power of two).
    stride: u64,
    offered: u64,
}

impl SeriesCap {
    /// A cap of [`MAX_SERIES_BYTES`] for rows of `row_bytes` bytes (at least 16 rows).
    pub fn of_rows(row_bytes: usize) -> SeriesCap {
        SeriesCap::with_max_rows(MAX_SERIES_BYTES / row_bytes.max(1))
    }

    /// A cap of `max_rows` rows (at least 16).
    pub fn with_max_rows(max_rows: usize) -> SeriesCap {
        SeriesCap {
            max_rows: max_rows.max(16),
            stride: 1,
            offered: 0,
        }
    }

    /// The most rows the series holds.
    pub fn max_rows(&self) -> usize {
        self.max_rows
    }

    /// How many instants offered make one recorded (1 until the series first fills).
    pub fn stride(&self) -> u64 {
        self.stride
    }

    /// Whether the instant offered now is recorded.
    pub fn take(&mut self) -> bool {
        let take = self.offered % self.stride == 0;
        self.offered += 1;
        take
    }

    /// After a row was added to a series of `rows` rows: `Some(keep)` when it is full, the
    /// rows to keep — every even one, the last, and those `worst` marks — after which
    /// every second instant is recorded; `None` while it has room.
    pub fn thin(&mut self, rows: usize, worst: impl Fn(usize) -> bool) -> Option<Vec<bool>> {
        if rows < self.max_rows {
            return None;
        }
        self.stride = self.stride.saturating_mul(2);
        Some(
            (0..rows)
                .map(|i| i % 2 == 0 || i + 1 == rows || worst(i))
                .collect(),
        )
    }

    /// Back to an empty series, recording every instant.
    pub fn reset(&mut self) {
        self.stride = 1;
        self.offered = 0;
    }
}

/// Keeps the rows of `rows` (flat, `width` values each) that `keep` marks.
pub fn retain_flat(rows: &mut Vec<f64>, width: usize, keep: &[bool]) {
    let width = width.max(1);
    let mut to = 0;
    for (i, &k) in keep.iter().enumerate() {
        if k {
            rows.copy_within(i * width..(i + 1) * width, to * width);
            to += 1;
        }
    }
    rows.truncate(to * width);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A series offered 10 000 instants with a cap of 100 rows: it never holds more than
    /// the cap, keeps the worst instant and the last, and its rows stay in time order.
    #[test]
    fn a_long_series_stays_within_its_cap_and_keeps_its_worst_and_last_rows() {
        let mut cap = SeriesCap::with_max_rows(100);
        let mut rows: Vec<f64> = Vec::new(); // (time, value) rows
                                             // a spike at an instant recorded at every stride up to 1024
        let value = |t: f64| if t == 4096.0 { 1e3 } else { (t * 0.01).sin() };
        let mut recorded_max = (f64::NAN, f64::NEG_INFINITY);
        for k in 0..10_000 {
            let t = k as f64;
            if !cap.take() {
                continue;
            }
            if value(t) > recorded_max.1 {
                recorded_max = (t, value(t));
            }
            rows.extend([t, value(t)]);
            let n = rows.len() / 2;
            let worst = rows
                .chunks_exact(2)
                .enumerate()
                .max_by(|a, b| a.1[1].total_cmp(&b.1[1]))
                .map(|(i, _)| i);
            if let Some(keep) = cap.thin(n, |i| Some(i) == worst) {
                retain_flat(&mut rows, 2, &keep);
            }
            assert!(rows.len() / 2 < 100, "{} rows at t = {t}", rows.len() / 2);
        }
        let times: Vec<f64> = rows.chunks_exact(2).map(|r| r[0]).collect();
        assert!(times.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(recorded_max.0, 4096.0, "the spike was recorded");
        assert!(times.contains(&4096.0), "the worst instant is kept");
        assert!(cap.stride() >= 128, "stride {}", cap.stride());
        assert!(times.len() > 30, "{} rows left", times.len());
    }

    #[test]
    fn retain_flat_keeps_marked_rows_in_order() {
        let mut rows = vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5];
        retain_flat(&mut rows, 2, &[true, false, true]);
        assert_eq!(rows, vec![0.0, 0.5, 2.0, 2.5]);
    }
}
