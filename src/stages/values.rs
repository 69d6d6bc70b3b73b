//! The value policies every stage kind follows: no NaN or infinity in a table (`finite`,
//! `bound`), and the parameter checks and size bounds they share (`check`).

/// The one policy for non-finite numbers (tables never hold NaN or infinity): a value
/// becomes 0, and the row's `converged` column says whether to trust it.
pub fn finite(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

/// The same policy for an error bound or a residual: one that is infinite or NaN says
/// "unbounded" and is published as f64::MAX, never as 0 (which would read as exact).
pub fn bound(e: f64) -> f64 {
    if e.is_finite() {
        e
    } else {
        f64::MAX
    }
}

/// Shared parameter checks and bounds. Numeric bounds are declared on the parameter types
/// (`#[schemars(range(..))]`, `#[schemars(extend("exclusiveMinimum" = ..))]`): the schema,
/// `repro kinds KIND` and the check of every point (`pipeline::kind::bound_errors`) read
/// them there. The upper bounds of sizes keep a task's memory and time to what a laptop
/// has (a size that passes is never an allocation that aborts).
pub mod check {
    use pipeline::kind::FieldError;

    pub fn non_negative(errs: &mut Vec<FieldError>, name: &str, x: f64) {
        if !(x >= 0.0 && x.is_finite()) {
            errs.push(FieldError::new(name, format!("must be zero or positive, got {x}")));
        }
    }

    /// Rows of a tabulated curve.
    pub const MAX_POINTS: usize = 1_000_000;
    /// Elements along the shell's meridian, and load steps.
    pub const MAX_SHELL_ELEMENTS: usize = 20_000;
    pub const MAX_STEPS: usize = 100_000;
}
