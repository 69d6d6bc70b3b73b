//! Stage kinds: where the orchestrator (parameters, tables) meets the physics.
//! Each kind binds one physics function to typed, validated parameters and a table.

pub mod bem;
pub mod figure;
pub mod fit;
pub mod pb;
pub mod pulloff;
pub mod theory;
pub mod util;

use crate::pipeline::kind::Registry;

/// Every stage kind a pipeline may use.
pub fn registry() -> Registry {
    let mut r = Registry::new();
    theory::register(&mut r);
    bem::register(&mut r);
    pulloff::register(&mut r);
    figure::register(&mut r);
    fit::register(&mut r);
    pb::register(&mut r);
    util::register(&mut r);
    r
}

/// Shared parameter checks, returning the errors for one field.
pub(crate) mod check {
    use crate::pipeline::kind::FieldError;

    pub fn positive(errs: &mut Vec<FieldError>, name: &str, x: f64) {
        if !(x > 0.0) {
            errs.push(FieldError::new(name, format!("must be positive, got {x}")));
        }
    }

    pub fn in_open(errs: &mut Vec<FieldError>, name: &str, x: f64, lo: f64, hi: f64, what: &str) {
        if !(x > lo && x < hi) {
            errs.push(FieldError::new(name, format!("{what} must lie in ({lo}, {hi}), got {x}")));
        }
    }

    pub fn at_least(errs: &mut Vec<FieldError>, name: &str, x: usize, lo: usize) {
        if x < lo {
            errs.push(FieldError::new(name, format!("must be at least {lo}, got {x}")));
        }
    }
}
