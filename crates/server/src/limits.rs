//! Limits on what one client may send: message size and message rate. Violations get an
//! error reply; the connection and the server carry on.

use pliant_scene::{Limits, LoadOptions};
use std::time::{Duration, Instant};

/// Largest text message a client may send \[bytes\]; larger ones get `message_too_large`.
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024;
/// Hard cap on a WebSocket message: above this the connection is closed (protects memory).
pub const HARD_MAX_MESSAGE_BYTES: usize = 1024 * 1024;
/// Largest `load_scene` message (a scene file's text) \[bytes\].
pub const MAX_SCENE_MESSAGE_BYTES: usize = HARD_MAX_MESSAGE_BYTES;
/// Messages per second a client may send on average.
pub const MAX_MESSAGES_PER_SECOND: f64 = 200.0;
/// Burst a client may send at once.
pub const MAX_BURST: f64 = 200.0;
/// At most one `rate_limited` error per this interval.
pub const RATE_ERROR_INTERVAL: Duration = Duration::from_millis(500);
/// Largest `step{n}`.
pub const MAX_STEPS_PER_REQUEST: u32 = 100_000;

/// Most beam elements of a scene a client sends: one explicit step of 20 000 elements
/// takes ≈ 10 ms here, so the session stays responsive for everyone.
pub const MAX_CLIENT_ELEMENTS: u64 = 20_000;
/// Most part triangles of a scene a client sends: every client receives them in the
/// `welcome` (≈ 40 bytes of JSON each, ≈ 40 MB at the limit).
pub const MAX_CLIENT_TRIANGLES: u64 = 1_000_000;
/// Memory limit of a scene a client sends \[bytes\] (at most the server's own).
pub const MAX_CLIENT_MEMORY_BYTES: u64 = 1_000_000_000;
/// Largest mesh file a client's scene may name \[bytes\].
pub const MAX_CLIENT_MESH_BYTES: u64 = 64 * 1024 * 1024;

/// How scenes sent with `load_scene` are loaded: confined to the served folder
/// (`FileAccess::sandbox`), and checked against limits before anyone receives them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClientScenes {
    pub options: LoadOptions,
}

impl ClientScenes {
    /// The client limits, none above the served scene's own `limits`.
    pub fn within(server: &LoadOptions) -> ClientScenes {
        ClientScenes {
            options: LoadOptions {
                limits: Limits {
                    max_memory_bytes: MAX_CLIENT_MEMORY_BYTES.min(server.limits.max_memory_bytes),
                    max_elements: MAX_CLIENT_ELEMENTS.min(server.limits.max_elements),
                    max_triangles: MAX_CLIENT_TRIANGLES.min(server.limits.max_triangles),
                    max_steps: server.limits.max_steps,
                    raise_with: "options of `pliant serve`; or load it there as the served scene",
                },
                max_file_bytes: MAX_CLIENT_MESH_BYTES.min(server.max_file_bytes),
                sandboxed: true,
                converter: server.converter,
            },
        }
    }
}

impl Default for ClientScenes {
    fn default() -> Self {
        ClientScenes::within(&pliant_runs::load_options())
    }
}

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
