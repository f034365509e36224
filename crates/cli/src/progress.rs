//! A progress bar over simulated time for long runs (`--quiet` hides it).

use indicatif::{ProgressBar, ProgressStyle};
use pliant_assembly::{Action, Observer};
use pliant_core::State;

pub struct Progress {
    bar: ProgressBar,
    steps_seen: u64,
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
                "{spinner} [{bar:40}] {pos}/{len} ms simulated ({elapsed}) {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        Progress { bar, steps_seen: 0 }
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
        self.steps_seen += 1;
        if self.steps_seen % 512 == 0 {
            self.bar.set_position((time * 1000.0) as u64);
        }
    }
}
