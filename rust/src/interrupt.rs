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
        last: Instant::now(),
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
        let now = Instant::now();
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

    #[test]
    fn a_hook_is_polled_within_the_interval_and_stops_the_loop() {
        let polls = Rc::new(Cell::new(0));
        let seen = polls.clone();
        let start = Instant::now();
        let r = with_hook(
            move || {
                seen.set(seen.get() + 1);
                start.elapsed() > Duration::from_millis(50)
            },
            || -> BeltResult<()> {
                loop {
                    check(1)?;
                }
            },
        );
        assert_eq!(r, Err(BeltError::Interrupted));
        let late = start.elapsed();
        assert!(late < Duration::from_millis(200), "stopped after {late:?}");
        assert!(polls.get() >= 2);
        // The hook is gone afterwards.
        check(1 << 40).unwrap();
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
