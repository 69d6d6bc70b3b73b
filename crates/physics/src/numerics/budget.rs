//! A time budget for the computation running on this thread. The long loops of the solvers
//! (Newton iterations, path following, adaptive quadrature) call [`checkpoint`], which
//! unwinds with [`Exhausted`] once the deadline set by [`within`] has passed; outside
//! `within` it costs one thread-local read. Unwinding leaves no shared state behind: a
//! solver's state is its own, and dropped.

use std::cell::Cell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

thread_local! {
    static DEADLINE: Cell<Option<Instant>> = const { Cell::new(None) };
}

/// The budget ran out before the computation ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Exhausted;

/// Runs `f` with `limit` of wall time; `Err(Exhausted)` if it reached a checkpoint after
/// the limit. A panic of `f` passes through. Budgets nest: the inner one ends no later
/// than the outer.
pub fn within<T>(limit: Duration, f: impl FnOnce() -> T) -> Result<T, Exhausted> {
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
        Err(payload) if payload.is::<Exhausted>() => Err(Exhausted),
        Err(payload) => resume_unwind(payload),
    }
}

/// Unwinds to the enclosing [`within`] if its deadline has passed (without the panic hook:
/// nothing is printed).
#[inline]
pub fn checkpoint() {
    if let Some(deadline) = DEADLINE.get() {
        if Instant::now() >= deadline {
            resume_unwind(Box::new(Exhausted));
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
        assert_eq!(r, Err::<(), _>(Exhausted));
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
        assert_eq!(r, Ok(Err::<(), _>(Exhausted)));
        // Another panic passes through.
        let p = std::panic::catch_unwind(|| within(Duration::from_secs(1), || panic!("boom")));
        assert!(p.is_err());
        checkpoint();
    }
}
