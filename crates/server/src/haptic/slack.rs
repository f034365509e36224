//! When the haptic stream re-synchronises its mirror: in the slack between an answer and
//! the next pose, not in front of a pose. A device asks at a steady rate (1 kHz), so the
//! next pose is due one period after this one arrived; a re-synchronisation (the state
//! copied, the hand's component searched again — on a harness several times a pose's
//! solve) that would still run then delays that pose's answer past its period. As in
//! slack stealing for aperiodic work beside periodic tasks (Lehoczky and
//! Ramos-Thuel 1992, "An optimal algorithm for scheduling soft-aperiodic tasks in
//! fixed-priority preemptive systems", RTSS), the optional work runs only where it fits
//! before the next periodic deadline; it is deferred at most [`MAX_DEFER`], after which
//! it is done in any case, so the mirror never lags the session by more than one
//! snapshot interval and [`MAX_DEFER`].

use std::time::{Duration, Instant};

/// Longest a due re-synchronisation waits for slack; then it is done before the next
/// answer whatever it costs.
pub const MAX_DEFER: Duration = Duration::from_millis(16);
/// Kept free before the next pose is due, for the estimates' error and the wake-up.
pub const MARGIN: Duration = Duration::from_micros(100);
/// Weight of a new inter-arrival time in the period's running mean.
const PERIOD_WEIGHT: f64 = 1.0 / 16.0;
/// Factor by which the cost estimate decays towards a cheaper measured one.
const COST_DECAY: f64 = 0.9;
/// Inter-arrival times above this are pauses of the device, not its period.
const LONGEST_PERIOD: Duration = Duration::from_millis(100);

/// The stream's estimates of the device's period and of a re-synchronisation's cost, and
/// how long a due one has waited.
#[derive(Clone, Debug, Default)]
pub struct SyncSlack {
    /// When the last pose arrived.
    last_pose: Option<Instant>,
    /// Running mean of the time between poses \[s\]; `None` before the second pose.
    period: Option<f64>,
    /// A re-synchronisation's cost \[s\]: the newest measurement when it is dearer than
    /// the estimate, else the estimate decayed towards it (quick to rise, slow to fall).
    cost: f64,
    /// Since when a re-synchronisation has been due and deferred.
    due_since: Option<Instant>,
}

impl SyncSlack {
    /// A pose arrived at `at`.
    pub fn pose_arrived(&mut self, at: Instant) {
        if let Some(last) = self.last_pose {
            let gap = at.saturating_duration_since(last);
            if gap <= LONGEST_PERIOD {
                let gap = gap.as_secs_f64();
                self.period = Some(match self.period {
                    Some(p) => p + PERIOD_WEIGHT * (gap - p),
                    None => gap,
                });
            }
        }
        self.last_pose = Some(at);
    }

    /// A re-synchronisation took `took`.
    pub fn synced(&mut self, took: Duration) {
        let took = took.as_secs_f64();
        self.cost = took.max(self.cost * COST_DECAY + (1.0 - COST_DECAY) * took);
        self.due_since = None;
    }

    /// Whether a re-synchronisation that is due fits now, before the next pose: it
    /// does when no steady stream of poses is known, when it has waited [`MAX_DEFER`],
    /// or when its estimated cost and [`MARGIN`] end before the next pose is due. A
    /// deferred one is remembered as due from `now`.
    pub fn fits(&mut self, now: Instant) -> bool {
        let (Some(last), Some(period)) = (self.last_pose, self.period) else {
            return true;
        };
        let due_since = *self.due_since.get_or_insert(now);
        if now.saturating_duration_since(due_since) >= MAX_DEFER {
            return true;
        }
        let next_pose = last + Duration::from_secs_f64(period);
        let done = now + Duration::from_secs_f64(self.cost) + MARGIN;
        done <= next_pose
    }

    /// Whether a due re-synchronisation has waited its longest and must be done before
    /// the next answer.
    pub fn overdue(&self, now: Instant) -> bool {
        self.due_since
            .is_some_and(|since| now.saturating_duration_since(since) >= MAX_DEFER)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);
    const US: Duration = Duration::from_micros(1);

    /// A stream of poses 1 ms apart from `t0`, `count` of them, and a sync cost.
    fn steady(t0: Instant, count: u32, cost: Duration) -> SyncSlack {
        let mut s = SyncSlack::default();
        for k in 0..count {
            s.pose_arrived(t0 + k * MS);
        }
        s.synced(cost);
        s
    }

    #[test]
    fn without_a_steady_stream_a_sync_always_fits() {
        let t0 = Instant::now();
        let mut s = SyncSlack::default();
        assert!(s.fits(t0));
        s.pose_arrived(t0);
        assert!(s.fits(t0 + 10 * US), "one pose gives no period");
    }

    #[test]
    fn a_sync_fits_only_when_it_ends_before_the_next_pose() {
        let t0 = Instant::now();
        let mut s = steady(t0, 10, 600 * US);
        let last = t0 + 9 * MS;
        // answered at 0.1 ms: 0.6 ms of sync and 0.1 ms of margin end at 0.8 ms
        assert!(s.fits(last + 100 * US));
        s.synced(600 * US);
        // answered at 0.35 ms: they would end at 1.05 ms, after the next pose
        assert!(!s.fits(last + 350 * US));
        assert!(!s.overdue(last + 350 * US));
    }

    #[test]
    fn a_deferred_sync_is_done_after_its_longest_wait() {
        let t0 = Instant::now();
        let mut s = steady(t0, 10, 2 * MS); // a sync longer than the period never fits
        let mut now = t0 + 9 * MS + 10 * US;
        assert!(!s.fits(now));
        let due = now;
        while now < due + MAX_DEFER {
            assert!(!s.overdue(now));
            s.pose_arrived(now);
            now += MS;
            assert_eq!(s.fits(now), now >= due + MAX_DEFER);
        }
        assert!(s.overdue(now));
        s.synced(2 * MS);
        assert!(!s.overdue(now), "done: no longer due");
    }

    #[test]
    fn the_cost_estimate_rises_at_once_and_falls_slowly() {
        let mut s = SyncSlack::default();
        s.synced(500 * US);
        assert_eq!(s.cost, 500e-6);
        s.synced(100 * US);
        assert!((s.cost - (0.9 * 500e-6 + 0.1 * 100e-6)).abs() < 1e-15);
        s.synced(900 * US);
        assert_eq!(s.cost, 900e-6);
    }

    #[test]
    fn pauses_of_the_device_are_not_its_period() {
        let t0 = Instant::now();
        let mut s = steady(t0, 3, 100 * US);
        s.pose_arrived(t0 + 2 * MS + 5 * LONGEST_PERIOD);
        assert!((s.period.unwrap() - 1e-3).abs() < 1e-12);
    }
}
