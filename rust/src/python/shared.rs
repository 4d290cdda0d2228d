//! A value shared by the Python threads that call one `Simulation`: a first-come,
//! first-served lock that is waited for without the GIL.
//!
//! PyO3's own borrow checking makes a second thread's call fail with a bare `RuntimeError:
//! Already borrowed`. Here the second call waits its turn instead; it waits with the GIL
//! released (the holder may need the GIL to poll Ctrl-C), and turns are served in order, so
//! a thread saving checkpoints during a long `run` (which calls the engine in short
//! chunks) gets in between two chunks instead of starving.

use pyo3::Python;
use std::cell::UnsafeCell;
use std::ops::{Deref, DerefMut};
use std::sync::{Condvar, Mutex, PoisonError};

/// Tickets: the next to hand out and the one being served.
#[derive(Default)]
struct Turns {
    next: u64,
    serving: u64,
}

/// `T` behind a fair lock (see the module documentation).
pub struct Shared<T> {
    value: UnsafeCell<T>,
    turns: Mutex<Turns>,
    turn_changed: Condvar,
}

// SAFETY: the value is only reached through a `Guard`, and at most one guard exists at a
// time (the ticket being served); `T: Send` lets it move between threads.
unsafe impl<T: Send> Sync for Shared<T> {}

impl<T: Send> Shared<T> {
    /// Wrap `value`.
    pub fn new(value: T) -> Self {
        Shared {
            value: UnsafeCell::new(value),
            turns: Mutex::new(Turns::default()),
            turn_changed: Condvar::new(),
        }
    }

    /// Wait for this caller's turn (without the GIL if it has to wait) and hold it until
    /// the guard is dropped.
    pub fn lock(&self, py: Python<'_>) -> Guard<'_, T> {
        let ticket = {
            let mut t = self.turns.lock().unwrap_or_else(PoisonError::into_inner);
            let ticket = t.next;
            t.next += 1;
            if t.serving == ticket {
                return Guard { shared: self };
            }
            ticket
        };
        let (turns, turn_changed) = (&self.turns, &self.turn_changed);
        py.detach(|| {
            let mut t = turns.lock().unwrap_or_else(PoisonError::into_inner);
            while t.serving != ticket {
                t = turn_changed.wait(t).unwrap_or_else(PoisonError::into_inner);
            }
        });
        Guard { shared: self }
    }
}

/// The caller's turn on a [`Shared`] value; the next caller's turn starts when it drops.
pub struct Guard<'a, T> {
    shared: &'a Shared<T>,
}

impl<T> Deref for Guard<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        // SAFETY: this guard holds the only turn.
        unsafe { &*self.shared.value.get() }
    }
}

impl<T> DerefMut for Guard<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        // SAFETY: this guard holds the only turn.
        unsafe { &mut *self.shared.value.get() }
    }
}

impl<T> Drop for Guard<'_, T> {
    fn drop(&mut self) {
        let mut t = self
            .shared
            .turns
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        t.serving += 1;
        drop(t);
        self.shared.turn_changed.notify_all();
    }
}
