//! A hand move given by its speed: the duration over which the move's smooth start and
//! stop travel the path at that mean speed — the path's length over the speed. The
//! timeline's `move_hand` with `speed_m_s` and Python's `Simulation.move_hand(speed=…)`
//! both time their moves with it.

use glam::DVec3;

/// The shortest duration a move given by its speed takes \[s\]: a path of (nearly) zero
/// length still gets a move the smooth step can run.
pub const SHORTEST_MOVE: f64 = 1e-3;

/// The duration \[s\] of a move from `start` through `waypoints` (a polyline) at the mean
/// speed `speed` \[m/s\]: the polyline's length over the speed, at least
/// [`SHORTEST_MOVE`]. The smooth step's mean speed is then the given one.
pub fn duration_at_speed(start: DVec3, waypoints: &[DVec3], speed: f64) -> f64 {
    let mut length = 0.0;
    let mut at = start;
    for p in waypoints {
        length += (*p - at).length();
        at = *p;
    }
    (length / speed).max(SHORTEST_MOVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_duration_is_the_polyline_length_over_the_speed() {
        // 3-4-5 leg then a 1 m leg: 6 m at 2 m/s
        let start = DVec3::ZERO;
        let path = [DVec3::new(3.0, 4.0, 0.0), DVec3::new(3.0, 4.0, 1.0)];
        assert_eq!(duration_at_speed(start, &path, 2.0), 3.0);
    }

    #[test]
    fn a_path_of_no_length_takes_the_shortest_move() {
        let start = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(duration_at_speed(start, &[start], 0.5), SHORTEST_MOVE);
        assert_eq!(duration_at_speed(start, &[], 0.5), SHORTEST_MOVE);
    }
}
