//! Limits on what one client may send: message size and message rate. Violations get an
//! error reply; the connection and the server carry on.

use std::time::{Duration, Instant};

/// Largest text message a client may send [bytes]; larger ones get `message_too_large`.
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024;
/// Hard cap on a WebSocket message: above this the connection is closed (protects memory).
pub const HARD_MAX_MESSAGE_BYTES: usize = 1024 * 1024;
/// Largest `load_scene` message (a scene file's text) [bytes].
pub const MAX_SCENE_MESSAGE_BYTES: usize = HARD_MAX_MESSAGE_BYTES;
/// Messages per second a client may send on average.
pub const MAX_MESSAGES_PER_SECOND: f64 = 200.0;
/// Burst a client may send at once.
pub const MAX_BURST: f64 = 200.0;
/// At most one `rate_limited` error per this interval.
pub const RATE_ERROR_INTERVAL: Duration = Duration::from_millis(500);
/// Largest `step{n}`.
pub const MAX_STEPS_PER_REQUEST: u32 = 100_000;

/// A token bucket: `rate` tokens per second, at most `burst` stored.
#[derive(Debug)]
pub struct RateLimiter {
    rate: f64,
    burst: f64,
    tokens: f64,
    last: Instant,
    dropped: u64,
    last_error: Option<Instant>,
}

/// What to do with one incoming message.
#[derive(Debug, PartialEq, Eq)]
pub enum Admit {
    /// Handle it.
    Yes,
    /// Drop it silently (an error was sent recently).
    Drop,
    /// Drop it and tell the client how many were dropped since the last error.
    DropAndReport(u64),
}

impl RateLimiter {
    pub fn new(rate: f64, burst: f64) -> Self {
        RateLimiter {
            rate,
            burst,
            tokens: burst,
            last: Instant::now(),
            dropped: 0,
            last_error: None,
        }
    }

    /// Whether a message arriving at `now` is admitted.
    pub fn admit(&mut self, now: Instant) -> Admit {
        let dt = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now;
        self.tokens = (self.tokens + dt * self.rate).min(self.burst);
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            return Admit::Yes;
        }
        self.dropped += 1;
        if self
            .last_error
            .is_none_or(|t| now.saturating_duration_since(t) >= RATE_ERROR_INTERVAL)
        {
            self.last_error = Some(now);
            let n = self.dropped;
            self.dropped = 0;
            Admit::DropAndReport(n)
        } else {
            Admit::Drop
        }
    }
}

impl Default for RateLimiter {
    fn default() -> Self {
        RateLimiter::new(MAX_MESSAGES_PER_SECOND, MAX_BURST)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn burst_then_drops_with_one_report_per_interval() {
        let mut r = RateLimiter::new(10.0, 5.0);
        let t = Instant::now();
        for _ in 0..5 {
            assert_eq!(r.admit(t), Admit::Yes);
        }
        assert_eq!(r.admit(t), Admit::DropAndReport(1));
        assert_eq!(r.admit(t), Admit::Drop);
        assert_eq!(r.admit(t), Admit::Drop);
        let later = t + Duration::from_secs(1);
        assert_eq!(r.admit(later), Admit::Yes);
    }
}
