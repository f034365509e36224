//! A small persistent pool of helper threads for the explicit step: the step
//! hands it a job of independent chunks (groups of whole hoses), and the calling thread
//! and the helpers claim chunks until none is left.
//!
//! **Determinism.** A chunk writes only its own hoses' nodes and computes them exactly as
//! the serial step does; which thread runs which chunk, and how many threads there are,
//! changes nothing but the wall time. So a step gives the same bits with 1, 2 or any
//! number of threads, and the pool may run a job on fewer threads than asked (a helper
//! that is busy, descheduled or asleep simply finds no chunk left; the caller does them).
//!
//! **Cost.** The helpers are started once per process (no thread is spawned per step,
//! nothing is allocated per job). After a job they spin for a short while ([`SPIN`])
//! waiting for the next one — the next phase or step of a running simulation — and then
//! sleep until woken. One job runs at a time: a caller that finds the pool busy (another
//! simulation in the same process stepping) runs its job alone.

use std::cell::UnsafeCell;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering::SeqCst};
use std::sync::{Mutex, OnceLock};
use std::thread::Thread;
use std::time::{Duration, Instant};

/// How long an idle helper spins for the next job before it sleeps.
pub const SPIN: Duration = Duration::from_micros(300);

/// The number of logical cores (at least 1).
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

type Job = *const (dyn Fn(usize) + Sync);

/// What the caller publishes for one job.
struct Slot {
    job: Option<Job>,
    chunks: usize,
    /// Helpers allowed to take part (threads − 1).
    helpers: usize,
}

struct Shared {
    /// Odd while a job is open; each open and close increments it.
    seq: AtomicU64,
    /// Next chunk to claim, and chunks finished.
    next: AtomicUsize,
    done: AtomicUsize,
    /// Helpers inside the current job (the slot must outlive them).
    inside: AtomicUsize,
    /// A chunk panicked on a helper.
    panicked: AtomicBool,
    slot: UnsafeCell<Slot>,
}

// SAFETY: `slot` is written only by the thread holding `Pool::lock` while no helper is
// inside a job (seq even and `inside` zero), and read by helpers only while they are
// counted in `inside` for an open job.
unsafe impl Sync for Shared {}

struct Helper {
    thread: Thread,
    sleeping: AtomicBool,
}

/// The process's helper threads.
pub struct Pool {
    shared: &'static Shared,
    helpers: Vec<&'static Helper>,
    lock: Mutex<()>,
}

static POOL: OnceLock<Pool> = OnceLock::new();

impl Pool {
    /// The pool, with one helper per logical core beyond the first (started on first use).
    pub fn global() -> &'static Pool {
        POOL.get_or_init(|| Pool::start(available_cores().saturating_sub(1)))
    }

    fn start(helpers: usize) -> Pool {
        let shared: &'static Shared = Box::leak(Box::new(Shared {
            seq: AtomicU64::new(0),
            next: AtomicUsize::new(0),
            done: AtomicUsize::new(0),
            inside: AtomicUsize::new(0),
            panicked: AtomicBool::new(false),
            slot: UnsafeCell::new(Slot {
                job: None,
                chunks: 0,
                helpers: 0,
            }),
        }));
        let mut list = Vec::with_capacity(helpers);
        for index in 0..helpers {
            let (tx, rx) = std::sync::mpsc::channel::<&'static Helper>();
            let spawned = std::thread::Builder::new()
                .name(format!("pliant-helper-{}", index + 1))
                .spawn(move || {
                    let me: &'static Helper = Box::leak(Box::new(Helper {
                        thread: std::thread::current(),
                        sleeping: AtomicBool::new(false),
                    }));
                    let _ = tx.send(me);
                    helper_loop(shared, me, index);
                });
            match spawned.ok().and_then(|_| rx.recv().ok()) {
                Some(h) => list.push(h),
                None => break, // could not start a thread: run with fewer
            }
        }
        Pool {
            shared,
            helpers: list,
            lock: Mutex::new(()),
        }
    }

    /// Helper threads running.
    pub fn helpers(&self) -> usize {
        self.helpers.len()
    }

    /// Runs `f(0) … f(chunks − 1)` on the calling thread and up to `threads − 1` helpers;
    /// returns when all have finished. With `threads` ≤ 1, one chunk, or the pool busy,
    /// the calling thread runs them all, in order.
    pub fn run(&self, threads: usize, chunks: usize, f: &(dyn Fn(usize) + Sync)) {
        let helpers = threads.saturating_sub(1).min(self.helpers.len());
        if helpers == 0 || chunks <= 1 {
            return (0..chunks).for_each(f);
        }
        let Ok(_guard) = self.lock.try_lock() else {
            return (0..chunks).for_each(f);
        };
        let s = self.shared;
        // SAFETY: we hold the lock and the previous job is closed with no helper inside.
        // The job's lifetime is erased; it is only called until this function returns,
        // which waits for every helper to leave the job.
        unsafe {
            let job: &'static (dyn Fn(usize) + Sync) = std::mem::transmute(f);
            *s.slot.get() = Slot {
                job: Some(job as Job),
                chunks,
                helpers,
            };
        }
        s.next.store(0, SeqCst);
        s.done.store(0, SeqCst);
        s.seq.fetch_add(1, SeqCst); // open
        for h in &self.helpers[..helpers] {
            if h.sleeping.load(SeqCst) {
                h.thread.unpark();
            }
        }
        let mut own_panic = None;
        loop {
            let i = s.next.fetch_add(1, SeqCst);
            if i >= chunks {
                break;
            }
            if let Err(p) = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(i))) {
                own_panic.get_or_insert(p);
            }
            s.done.fetch_add(1, SeqCst);
        }
        wait_until(|| s.done.load(SeqCst) >= chunks);
        s.seq.fetch_add(1, SeqCst); // close
        wait_until(|| s.inside.load(SeqCst) == 0);
        // SAFETY: closed, no helper inside.
        unsafe { (*s.slot.get()).job = None };
        if let Some(p) = own_panic {
            std::panic::resume_unwind(p);
        }
        if s.panicked.swap(false, SeqCst) {
            panic!("a chunk of a parallel job panicked on a helper thread");
        }
    }
}

/// Spins, then yields, until `ready`.
fn wait_until(ready: impl Fn() -> bool) {
    let mut spins = 0u32;
    while !ready() {
        if spins < 1 << 14 {
            std::hint::spin_loop();
            spins += 1;
        } else {
            std::thread::yield_now();
        }
    }
}

fn helper_loop(s: &'static Shared, me: &'static Helper, index: usize) {
    let mut seen = 0u64;
    loop {
        // wait for a new open job: spin a while, then sleep
        let since = Instant::now();
        let seq = loop {
            let seq = s.seq.load(SeqCst);
            if seq != seen && seq % 2 == 1 {
                break seq;
            }
            if since.elapsed() < SPIN {
                std::hint::spin_loop();
                continue;
            }
            me.sleeping.store(true, SeqCst);
            let seq = s.seq.load(SeqCst);
            if seq != seen && seq % 2 == 1 {
                me.sleeping.store(false, SeqCst);
                break seq;
            }
            std::thread::park_timeout(Duration::from_millis(50));
            me.sleeping.store(false, SeqCst);
        };
        seen = seq;
        s.inside.fetch_add(1, SeqCst);
        if s.seq.load(SeqCst) != seq {
            s.inside.fetch_sub(1, SeqCst); // closed meanwhile
            continue;
        }
        // SAFETY: the job is open and we are counted inside it (see `Shared`).
        let (job, chunks, helpers) = unsafe {
            let slot = &*s.slot.get();
            (slot.job, slot.chunks, slot.helpers)
        };
        if let (Some(job), true) = (job, index < helpers) {
            // SAFETY: the caller waits for `inside` to drop to zero before returning.
            let f = unsafe { &*job };
            loop {
                let i = s.next.fetch_add(1, SeqCst);
                if i >= chunks {
                    break;
                }
                if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(i))).is_err() {
                    s.panicked.store(true, SeqCst);
                }
                s.done.fetch_add(1, SeqCst);
            }
        }
        s.inside.fetch_sub(1, SeqCst);
    }
}

/// A raw pointer that may be shared between the threads of one job, each chunk using a
/// disjoint part of what it points to.
#[derive(Clone, Copy)]
pub struct SharedMut<T>(pub *mut T);

// SAFETY: used only to hand disjoint sub-slices to the chunks of one job.
unsafe impl<T: Send> Sync for SharedMut<T> {}
unsafe impl<T: Send> Send for SharedMut<T> {}

impl<T> SharedMut<T> {
    pub fn new(s: &mut [T]) -> Self {
        SharedMut(s.as_mut_ptr())
    }

    /// Elements `range` of the slice this was made from.
    ///
    /// # Safety
    /// `range` must lie within that slice, the slice must outlive the use, and no two
    /// users may hold overlapping ranges at the same time.
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn slice(&self, range: std::ops::Range<usize>) -> &mut [T] {
        std::slice::from_raw_parts_mut(self.0.add(range.start), range.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_chunk_runs_once_on_any_number_of_threads() {
        for threads in [1, 2, 4] {
            for chunks in [0, 1, 2, 7, 100] {
                let hits: Vec<AtomicUsize> = (0..chunks).map(|_| AtomicUsize::new(0)).collect();
                for _ in 0..50 {
                    Pool::global().run(threads, chunks, &|i| {
                        hits[i].fetch_add(1, SeqCst);
                    });
                }
                assert!(
                    hits.iter().all(|h| h.load(SeqCst) == 50),
                    "{threads} {chunks}"
                );
            }
        }
    }

    #[test]
    fn a_panicking_chunk_panics_the_caller_and_the_pool_goes_on() {
        let r = std::panic::catch_unwind(|| {
            Pool::global().run(2, 8, &|i| {
                if i == 5 {
                    panic!("chunk 5");
                }
            })
        });
        assert!(r.is_err());
        let n = AtomicUsize::new(0);
        Pool::global().run(2, 8, &|_| {
            n.fetch_add(1, SeqCst);
        });
        assert_eq!(n.load(SeqCst), 8);
    }

    /// With a helper, two chunks really run at the same time: each chunk waits until
    /// both have started, which only a second thread can bring about (the caller, stuck
    /// in its chunk, cannot claim the other). A pool of its own, so that no other test's
    /// job keeps the lock or the helper busy (the pool would then rightly run the job
    /// alone). Were the chunks run one after the other, the first would wait for ever;
    /// the bound on the wait only turns that hang into a failure.
    #[test]
    fn two_chunks_run_at_the_same_time_on_a_helper() {
        use std::sync::{Condvar, Mutex};
        let pool = Pool::start(1);
        assert_eq!(pool.helpers(), 1);
        let started = Mutex::new(0usize);
        let both = Condvar::new();
        let met = AtomicUsize::new(0);
        for _ in 0..3 {
            *started.lock().unwrap() = 0;
            pool.run(2, 2, &|_| {
                let mut n = started.lock().unwrap();
                *n += 1;
                both.notify_all();
                let (n, wait) = both
                    .wait_timeout_while(n, Duration::from_secs(120), |n| *n < 2)
                    .unwrap();
                if !wait.timed_out() && *n == 2 {
                    met.fetch_add(1, SeqCst);
                }
            });
        }
        assert_eq!(
            met.load(SeqCst),
            6,
            "the two chunks did not run at the same time"
        );
    }
}
