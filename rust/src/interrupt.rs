//! Cooperative interruption of long calls (Ctrl-C in Python, a GUI's stop button, ...).
//!
//! A caller installs a hook for the current thread with [`with_hook`] around a long call;
//! the core's long loops (compiling, stepping, relaxing, reading a checkpoint) report the
//! work they did to [`check`], which polls the hook about every [`POLL_INTERVAL`] of wall
//! time and turns a `true` from it into [`BeltError::Interrupted`]. Loops call `check` only
//! between whole steps or elements, so an interrupted step or relaxation leaves a
//! consistent state. Without a hook `check` costs one thread-local read and an addition.
//!
//! The core stays free of Python: the bindings install a hook that takes the GIL for an
//! instant and runs Python's signal handlers (`PyErr_CheckSignals`).

use crate::error::{BeltError, BeltResult};
use std::cell::RefCell;
use std::time::{Duration, Instant};

/// Wall time between two polls of the hook (at most; loops report work in small units).
pub const POLL_INTERVAL: Duration = Duration::from_millis(20);

/// Work units (about one node update each, a few ns) between two readings of the clock.
const WORK_PER_CLOCK_READ: u64 = 1 << 14;

type Poll = Box<dyn FnMut() -> bool>;

struct Hook {
    poll: Option<Poll>,
    work: u64,
    last: Instant,
    /// The wall clock (`Instant::now`; the tests give a clock they step themselves).
    clock: fn() -> Instant,
}

thread_local! {
    static HOOK: RefCell<Option<Hook>> = const { RefCell::new(None) };
    static DONE: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Report how far a long loop got (e.g. relaxation steps), for the hook to show progress
/// ([`reported`]).
#[inline]
pub fn report(done: u64) {
    DONE.with(|d| d.set(done));
}

/// What the current long loop last [`report`]ed on this thread.
pub fn reported() -> u64 {
    DONE.with(|d| d.get())
}

/// Run `f` with `poll` as this thread's interrupt hook (restoring the previous hook after,
/// also on a panic). `poll` returns true to interrupt.
pub fn with_hook<T>(poll: impl FnMut() -> bool + 'static, f: impl FnOnce() -> T) -> T {
    with_hook_on_clock(poll, Instant::now, f)
}

/// [`with_hook`] with `clock` as the wall clock.
fn with_hook_on_clock<T>(
    poll: impl FnMut() -> bool + 'static,
    clock: fn() -> Instant,
    f: impl FnOnce() -> T,
) -> T {
    struct Restore(Option<Hook>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            HOOK.with(|h| *h.borrow_mut() = previous);
        }
    }
    let hook = Hook {
        poll: Some(Box::new(poll)),
        work: 0,
        last: clock(),
        clock,
    };
    let _restore = Restore(HOOK.with(|h| h.borrow_mut().replace(hook)));
    f()
}

/// Report `work` units done (about one node update each); polls the hook when it is due.
/// Returns [`BeltError::Interrupted`] if the hook asks to stop.
#[inline]
pub fn check(work: u64) -> BeltResult<()> {
    let due = HOOK.with(|h| {
        let mut h = h.borrow_mut();
        let hook = h.as_mut()?;
        hook.work += work;
        if hook.work < WORK_PER_CLOCK_READ {
            return None;
        }
        hook.work = 0;
        let now = (hook.clock)();
        if now.duration_since(hook.last) < POLL_INTERVAL {
            return None;
        }
        hook.last = now;
        // Taken out while it runs: the hook may call back into the core (a Python signal
        // handler that saves a checkpoint), which must not find the cell borrowed.
        hook.poll.take()
    });
    let Some(mut poll) = due else {
        return Ok(());
    };
    let stop = poll();
    HOOK.with(|h| {
        if let Some(hook) = h.borrow_mut().as_mut() {
            hook.poll = Some(poll);
        }
    });
    if stop {
        Err(BeltError::Interrupted)
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;
    use std::rc::Rc;

    #[test]
    fn without_a_hook_check_never_interrupts() {
        for _ in 0..100_000 {
            check(1 << 20).unwrap();
        }
    }

    thread_local! {
        /// The test clock: its start and the clock reads so far.
        static TICKS: Cell<(Option<Instant>, u32)> = const { Cell::new((None, 0)) };
    }

    /// Each reading of this clock is 1 ms after the one before: the loop below reads it
    /// once per [`WORK_PER_CLOCK_READ`] units of work, so "wall time" is counted in work
    /// and the test does not depend on how fast (or how loaded) the machine is.
    fn ticking_clock() -> Instant {
        TICKS.with(|t| {
            let (start, reads) = t.get();
            let start = start.unwrap_or_else(Instant::now);
            t.set((Some(start), reads + 1));
            start + Duration::from_millis(reads.into())
        })
    }

    fn ticked() -> Duration {
        Duration::from_millis(TICKS.with(|t| t.get().1).saturating_sub(1).into())
    }

    /// The hook is polled once per [`POLL_INTERVAL`] of (clock) time, not more often and
    /// not less, and its `true` stops the loop at once with [`BeltError::Interrupted`].
    #[test]
    fn a_hook_is_polled_within_the_interval_and_stops_the_loop() {
        let polls = Rc::new(RefCell::new(Vec::new()));
        let seen = polls.clone();
        let r = with_hook_on_clock(
            move || {
                // Asks to stop once more than 50 ms have passed.
                seen.borrow_mut().push(ticked());
                ticked() > Duration::from_millis(50)
            },
            ticking_clock,
            || -> BeltResult<()> {
                loop {
                    check(1)?;
                }
            },
        );
        assert_eq!(r, Err(BeltError::Interrupted));
        // Polled at 20, 40 and 60 ms (every POLL_INTERVAL), stopped by the third poll:
        // within one interval of the hook's 50 ms.
        let interval = POLL_INTERVAL.as_millis() as u64;
        let expected: Vec<Duration> = (1..=3)
            .map(|k| Duration::from_millis(k * interval))
            .collect();
        assert_eq!(*polls.borrow(), expected);
        assert_eq!(ticked(), Duration::from_millis(3 * interval));
        // The hook is gone afterwards.
        check(1 << 40).unwrap();
    }

    /// The same on the real clock: the loop stops within a wide bound of the hook's time
    /// (a smoke test; the exact polling is checked on the test clock above).
    #[test]
    fn a_hook_on_the_wall_clock_stops_the_loop() {
        let start = Instant::now();
        let r = with_hook(
            move || start.elapsed() > Duration::from_millis(50),
            || -> BeltResult<()> {
                loop {
                    check(1)?;
                }
            },
        );
        assert_eq!(r, Err(BeltError::Interrupted));
        assert!(start.elapsed() >= Duration::from_millis(50));
    }

    #[test]
    fn hooks_nest_and_restore() {
        let r = with_hook(
            || true,
            || {
                with_hook(
                    || false,
                    || {
                        std::thread::sleep(POLL_INTERVAL);
                        check(WORK_PER_CLOCK_READ)
                    },
                )
                .unwrap();
                std::thread::sleep(POLL_INTERVAL);
                check(WORK_PER_CLOCK_READ)
            },
        );
        assert_eq!(r, Err(BeltError::Interrupted));
    }
}
