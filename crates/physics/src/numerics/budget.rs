//! A time budget for the computation running on this thread. The long loops of the solvers
//! (Newton iterations, path following, adaptive quadrature) call [`checkpoint`], which
//! unwinds with [`Exhausted`] once the deadline set by [`within`] has passed, or once the
//! process asked every budgeted computation to stop ([`cancel`]: an interrupt, Ctrl-C in
//! the Python package); outside `within` it costs one thread-local read. Unwinding leaves
//! no shared state behind: a solver's state is its own, and dropped.

use std::cell::Cell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

thread_local! {
    static DEADLINE: Cell<Option<Instant>> = const { Cell::new(None) };
}

/// Set by [`cancel`]: every budgeted computation stops at its next checkpoint, and none
/// starts, until [`resume`].
static CANCELLED: AtomicBool = AtomicBool::new(false);

/// Why a budgeted computation stopped before it ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exhausted {
    /// Its time limit passed.
    Deadline,
    /// The process cancelled it ([`cancel`]).
    Cancelled,
}

/// Stops every computation running within a budget, on any thread, at its next
/// checkpoint, and every one that starts, until [`resume`].
pub fn cancel() {
    CANCELLED.store(true, Ordering::SeqCst);
}

/// Lets budgeted computations run again after [`cancel`].
pub fn resume() {
    CANCELLED.store(false, Ordering::SeqCst);
}

/// Whether [`cancel`] holds.
pub fn cancelled() -> bool {
    CANCELLED.load(Ordering::Relaxed)
}

/// Runs `f` with `limit` of wall time; `Err(Exhausted::Deadline)` if it reached a
/// checkpoint after the limit, `Err(Exhausted::Cancelled)` if it was cancelled (then `f`
/// may not have started). A panic of `f` passes through. Budgets nest: the inner one ends
/// no later than the outer.
pub fn within<T>(limit: Duration, f: impl FnOnce() -> T) -> Result<T, Exhausted> {
    if cancelled() {
        return Err(Exhausted::Cancelled);
    }
    let deadline = Instant::now().checked_add(limit);
    let outer = DEADLINE.get();
    let inner = match (outer, deadline) {
        (Some(o), Some(d)) => Some(o.min(d)),
        (o, d) => d.or(o),
    };
    DEADLINE.set(inner);
    let result = catch_unwind(AssertUnwindSafe(f));
    DEADLINE.set(outer);
    match result {
        Ok(v) => Ok(v),
        Err(payload) => match payload.downcast::<Exhausted>() {
            Ok(why) => Err(*why),
            Err(payload) => resume_unwind(payload),
        },
    }
}

/// Unwinds to the enclosing [`within`] if its deadline has passed or the process cancelled
/// budgeted computations (without the panic hook: nothing is printed).
#[inline]
pub fn checkpoint() {
    if let Some(deadline) = DEADLINE.get() {
        if cancelled() {
            resume_unwind(Box::new(Exhausted::Cancelled));
        }
        if Instant::now() >= deadline {
            resume_unwind(Box::new(Exhausted::Deadline));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_with_checkpoints_stops_at_its_deadline_and_the_budget_is_restored() {
        let t0 = Instant::now();
        let r = within(Duration::from_millis(50), || loop {
            checkpoint();
            std::thread::sleep(Duration::from_millis(1));
        });
        assert_eq!(r, Err::<(), _>(Exhausted::Deadline));
        let dt = t0.elapsed();
        assert!(dt >= Duration::from_millis(50) && dt < Duration::from_secs(5), "{dt:?}");
        // Outside a budget a checkpoint never unwinds; a computation within its budget
        // returns its value.
        checkpoint();
        assert_eq!(within(Duration::from_secs(60), || 7), Ok(7));
        // The inner of two budgets cannot outlast the outer.
        let r = within(Duration::from_millis(20), || {
            within(Duration::from_secs(60), || loop {
                checkpoint();
                std::thread::sleep(Duration::from_millis(1));
            })
        });
        assert_eq!(r, Ok(Err::<(), _>(Exhausted::Deadline)));
        // Another panic passes through.
        let p = std::panic::catch_unwind(|| within(Duration::from_secs(1), || panic!("boom")));
        assert!(p.is_err());
        checkpoint();
        // A cancel stops a running computation at its next checkpoint, on another thread
        // too, and refuses to start one, until resume. (In this test alone: the flag is the
        // process's.)
        let worker = std::thread::spawn(|| {
            within(Duration::from_secs(60), || loop {
                checkpoint();
                std::thread::sleep(Duration::from_millis(1));
            })
        });
        std::thread::sleep(Duration::from_millis(20));
        cancel();
        assert_eq!(worker.join().unwrap(), Err::<(), _>(Exhausted::Cancelled));
        let mut started = false;
        assert_eq!(within(Duration::from_secs(60), || started = true), Err(Exhausted::Cancelled));
        assert!(!started);
        resume();
        assert_eq!(within(Duration::from_secs(60), || 7), Ok(7));
    }
}
