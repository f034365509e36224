//! A progress bar over simulated time for long runs (`--quiet` hides it).

use indicatif::{ProgressBar, ProgressStyle};
use pliant_assembly::{Action, Observer};
use pliant_core::State;
use std::time::{Duration, Instant};

/// How often the bar moves at most (a check of the clock per step is far cheaper than a
/// step; drawing is not).
const REDRAW: Duration = Duration::from_millis(100);

pub struct Progress {
    bar: ProgressBar,
    last_draw: Instant,
}

impl Progress {
    /// A bar up to `planned` seconds of simulated time.
    pub fn new(planned: f64, quiet: bool) -> Self {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new((planned * 1000.0).ceil() as u64)
        };
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} [{bar:40}] {pos}/{len} ms simulated ({elapsed}, ETA {eta}) {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        Progress {
            bar,
            last_draw: Instant::now(),
        }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Observer for Progress {
    fn on_action(&mut self, index: usize, action: &Action, _state: &State) {
        let name = format!("{action:?}");
        let short = name.split([' ', '{', '(']).next().unwrap_or("").to_string();
        self.bar
            .set_message(format!("action {}: {short}", index + 1));
    }

    fn on_step(&mut self, time: f64) {
        // by the clock, not by step count: runs whose steps take seconds move the bar too
        let now = Instant::now();
        if now.duration_since(self.last_draw) >= REDRAW {
            self.last_draw = now;
            self.bar.set_position((time * 1000.0) as u64);
        }
    }
}
