//! The session thread gives way to the haptic stream. A haptic loop must answer every
//! period (1 ms) while the session's solver may run flat out (a whole harness under the
//! static solver takes tens of milliseconds a step); on a machine with few cores the
//! two compete with the device's own client. As in haptic rendering's usual split — a
//! fast haptic loop beside a slower simulation loop at lower priority (Salisbury,
//! Conti and Barbagli 2004, "Haptic rendering: introductory concepts", IEEE CG&A
//! 24(2)) — the session thread lowers its own scheduling priority once a stream asks
//! for its state. Lowering needs no privileges; raising the stream's would.

/// How much the session thread raises its nice value once a haptic stream has asked for
/// its state (for the rest of the session: a stream that stops does not restore it).
pub const SESSION_NICE_INCREMENT: i32 = 10;
/// The largest nice value (lowest priority) on Linux.
pub const NICE_MAX: i32 = 19;

/// Raises the calling thread's nice value by [`SESSION_NICE_INCREMENT`] (at most to
/// [`NICE_MAX`]); on Linux the nice value belongs to the thread (setpriority(2),
/// "Bugs"), so the process's other threads keep theirs. Returns the new nice value, or
/// `None` where it did not take effect (not Linux, or refused).
pub fn lower_this_thread() -> Option<i32> {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: gettid, getpriority and setpriority take plain integers and touch no
        // memory of ours; errno is cleared first because -1 is also a valid nice value.
        unsafe {
            let tid = libc::gettid() as libc::id_t;
            *libc::__errno_location() = 0;
            let now = libc::getpriority(libc::PRIO_PROCESS, tid);
            if *libc::__errno_location() != 0 {
                return None;
            }
            let lower = (now + SESSION_NICE_INCREMENT).min(NICE_MAX);
            (libc::setpriority(libc::PRIO_PROCESS, tid, lower) == 0).then_some(lower)
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}
