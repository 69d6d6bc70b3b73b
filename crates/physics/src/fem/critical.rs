//! The critical adhesion gamma_c above which the shell no longer snaps through on loading
//! (thesis Section 3.4, Fig. 3.9), and the thickness above which it never does.
//!
//! A probe is one loading leg (`cycle::load_unload` with `stop_at_buckling`) at a given work
//! of adhesion: it answers "unstable before delta_max?", and if so gives F_buckling, delta
//! and the contact radius r there. gamma_c is bracketed until hi / lo - 1 <= rel_tol, and
//! every probe is kept (a repeated gamma is not recomputed) and reported. The analytic
//! estimate of Eq. 3.7, gamma_c = E h (r/R)^4, uses the r of the last probe that buckled
//! (the instability closest to gamma_c).
//!
//! Where the next probe goes (`bracket`): adhesion delays the snap, and the snap's delta
//! rises smoothly with gamma until it reaches delta_max, which is where the snap leaves the
//! loading: the threshold is the root of the signal s = delta_snap / delta_max - 1 of the
//! probes that snap (`Probe::signal`). Its estimate is the secant through the two snapping
//! probes nearest the threshold, interpolated in x^1.5 (s is convex in x on the map's points:
//! the linear secant overshoots the root, the quadratic one undershoots). A probe that snaps
//! by the stability test was the dearer (`ABOVE`), so the search stays above the estimate: the
//! first trial is `guess` times -s(0), divided by `DESCENT` (then by `growth`) until one
//! snaps; then each probe goes a little above the estimate, or, where the estimate lies
//! within (1 + rel_tol) of the lowest probe that did not snap, just inside that probe's
//! reach, so that the one probe that must snap near the threshold usually closes the
//! bracket. A bracket narrower than (1 + rel_tol)^1.96 is closed by one probe, at the
//! estimate if it lies within both ends' reach. Without an estimate, or after three probes in a row
//! that did not snap, it bisects geometrically. The verdicts alone decide the bracket: the
//! signal makes the search cheaper, never its answer wrong.
//!
//! Under the energy criterion a probe that reaches delta_max also carries a margin: the
//! balance Pi_inverted - Pi_flat there, continuous across the threshold and nearly linear in
//! the work of adhesion (`Margin`). Its root (a secant through probes on both sides, else a
//! Newton step) is then the estimate, and the search probes just above it and just below
//! it, closing the bracket in two probes when it is right (at most `GUIDED` in a row). The
//! snap's delta under that criterion moves in the steps of the loading, too coarse for the
//! secant of the signal (probe counts: docs/tuning.md, "Shell snap search").
//!
//! A probe whose loading fails to converge before either answer is counted as buckling if
//! it got past a quarter of delta_max (the snap is where Newton on the flattened branch
//! fails), else as not buckling; either way it is reported. A loading that fails within
//! the last percent of delta_max (`END_FRACTION`), stable up to there, has not snapped
//! before delta_max to that tolerance: not buckling, and decided.

use super::contact::Plate;
use super::cycle::{load_unload, Balance, CycleOptions, Jump};
use super::system::Model;

/// One loading run at a given adhesion (or thickness).
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    /// The varied parameter (work of adhesion, or h/R).
    pub x: f64,
    pub buckling: Option<Jump>,
    /// The loading leg converged to its answer.
    pub complete: bool,
    /// The largest delta reached, over delta_max.
    pub reached: f64,
    /// A measure of the distance to the threshold that is continuous across it, where the
    /// criterion has one (`Margin`).
    pub margin: Option<Margin>,
}

/// The energy criterion's balance at delta_max as a function of the probed work of
/// adhesion x: `value` = Pi_inverted - Pi_flat (< 0 on the buckling side, > 0 on the
/// other) and `slope` = d value / dx = (E_adh,inverted - E_adh,flat) / x (each state an
/// equilibrium at fixed delta, so that only the adhesive energy's explicit dependence on x,
/// which is linear, enters to first order). The balance is nearly linear in x (docs/shell.md,
/// "The snap criteria": to first order (U_flat - U_inv) - x (A_flat - A_inv)), so that one
/// probe's Newton step, or two probes' secant, places the threshold far inside a bracket's
/// tolerance.
#[derive(Clone, Copy, Debug)]
pub struct Margin {
    pub value: f64,
    pub slope: f64,
}

impl Margin {
    /// The balance of a cycle at work of adhesion x > 0; none at x = 0, where the slope is
    /// 0/0, or where it is not positive and finite.
    pub fn of(balance: &Balance, x: f64) -> Option<Margin> {
        let slope = (balance.adhesive_inverted - balance.adhesive_flat) / x;
        (x > 0.0 && slope > 0.0 && slope.is_finite() && balance.inverted_less_flat.is_finite())
            .then_some(Margin { value: balance.inverted_less_flat, slope })
    }
}

/// The fraction of delta_max past which a loading that fails to converge, every state
/// before stable, counts as not snapping before delta_max: a failure of the last step is not
/// a fold, and counted as buckling by the quarter rule it would move gamma_c far above the
/// probes that ran through (docs/tuning.md, "Shell snap search").
pub const END_FRACTION: f64 = 0.99;

impl Probe {
    /// A snap, or a loading that failed after a quarter of delta_max (where Newton on the
    /// flattened branch fails, the snap is near) but before `END_FRACTION` of it. A loading
    /// that failed earlier (strong adhesion at first contact) is no evidence of buckling:
    /// counted as not buckling.
    pub fn buckles(&self) -> bool {
        self.buckling.is_some() || (!self.decided() && self.reached > 0.25)
    }

    /// How far the snap lies from delta_max: delta_snap / delta_max - 1 (< 0), for a probe
    /// that snapped; none for one that did not or that failed without a snap.
    pub fn signal(&self) -> Option<f64> {
        self.buckling.map(|_| self.reached - 1.0)
    }

    /// The probe answers its question: it converged to its answer, or it failed past
    /// `END_FRACTION` of delta_max with every state before stable (no snap before
    /// delta_max, to that tolerance).
    pub fn decided(&self) -> bool {
        self.complete || (self.buckling.is_none() && self.reached >= END_FRACTION)
    }
}

/// A bracket [lo, hi] of a threshold: `lo` on the buckling side, `hi` on the other.
#[derive(Clone, Debug)]
pub struct Bracket {
    pub lo: f64,
    pub hi: f64,
    /// The bracket was closed (false: the threshold lies beyond the searched range).
    pub found: bool,
    pub probes: Vec<Probe>,
}

impl Bracket {
    /// Geometric (lo > 0) or arithmetic midpoint.
    pub fn mid(&self) -> f64 {
        if self.lo > 0.0 {
            (self.lo * self.hi).sqrt()
        } else {
            0.5 * (self.lo + self.hi)
        }
    }

    /// Both ends of the bracket rest on decided probes (`Probe::decided`; a failed probe
    /// otherwise decides a side by the rule of `Probe::buckles` only).
    pub fn reliable(&self) -> bool {
        let ok = |x: f64| self.probes.iter().find(|p| p.x == x).is_none_or(|p| p.decided());
        self.found && ok(self.lo) && ok(self.hi)
    }

    /// The last probe on the buckling side with a buckling event (the closest to the
    /// threshold).
    pub fn last_buckled(&self) -> Option<&Probe> {
        self.probes.iter().filter(|p| p.buckling.is_some() && p.x <= self.lo).max_by(|a, b| a.x.total_cmp(&b.x))
    }
}

/// Runs `probe(x)` at most once per x.
struct Memo<F: FnMut(f64) -> Probe> {
    probe: F,
    done: Vec<Probe>,
}

impl<F: FnMut(f64) -> Probe> Memo<F> {
    fn at(&mut self, x: f64) -> Probe {
        if let Some(p) = self.done.iter().find(|p| p.x == x) {
            return *p;
        }
        let p = (self.probe)(x);
        self.done.push(p);
        p
    }
}

/// The search places its probes a factor (1 + rel_tol)^ABOVE above the secant's estimate,
/// where they most likely do not snap, and keeps the probes that must snap, near the
/// threshold, to about one: for snaps located by halving failed steps, which cost several
/// times a probe that runs through; the published criteria's probes cost about the same
/// either side (docs/tuning.md, "Shell snap search", has the costs).
const ABOVE: f64 = 0.3;

/// The exponent of the secant's interpolation variable x^SECANT_POWER (see the module).
const SECANT_POWER: f64 = 1.5;

/// While no probe but the one at 0 has snapped, the first trials are divided by this
/// factor (then by `growth`): the first trial is usually within a few tens of percent of
/// the threshold.
const DESCENT: f64 = 1.2;

/// The secant's root of the signal through the two probes with a signal and the largest x
/// (both on the buckling side), interpolated in x^SECANT_POWER; none without two such
/// probes or with a signal that does not rise between them.
fn secant_estimate(probes: &[Probe]) -> Option<f64> {
    let mut with: Vec<(f64, f64)> = probes.iter().filter_map(|p| p.signal().map(|s| (p.x, s))).collect();
    with.sort_by(|a, b| a.0.total_cmp(&b.0));
    let [.., (x0, s0), (x1, s1)] = with[..] else { return None };
    if s1 <= s0 || s1 >= 0.0 {
        return None;
    }
    let (t0, t1) = (x0.powf(SECANT_POWER), x1.powf(SECANT_POWER));
    let root = (t1 - s1 * (t1 - t0) / (s1 - s0)).powf(1.0 / SECANT_POWER);
    root.is_finite().then_some(root)
}

/// The probes a margin may place in a row (`bracket`) before the search falls back to its
/// verdicts alone: a margin that misleads costs at most these.
const GUIDED: usize = 4;

/// Where the probes' margins (`Margin`) place the threshold: on the secant through the
/// nearest probes on either side of it, else by the Newton step of the probe nearest it;
/// none without a margin.
fn margin_estimate(probes: &[Probe]) -> Option<f64> {
    let with: Vec<(f64, Margin)> = probes.iter().filter_map(|p| p.margin.map(|m| (p.x, m))).collect();
    let below = with.iter().filter(|(_, m)| m.value < 0.0).max_by(|a, b| a.0.total_cmp(&b.0));
    let above = with.iter().filter(|(_, m)| m.value >= 0.0).min_by(|a, b| a.0.total_cmp(&b.0));
    let root = match (below, above) {
        (Some(&(x0, m0)), Some(&(x1, m1))) if x0 < x1 => x0 - m0.value * (x1 - x0) / (m1.value - m0.value),
        _ => {
            let step = |&(x, m): &(f64, Margin)| (x - m.value / m.slope, (m.value / m.slope).abs());
            with.iter().map(step).min_by(|a, b| a.1.total_cmp(&b.1))?.0
        }
    };
    (root.is_finite() && root > 0.0).then_some(root)
}

/// Brackets the threshold of a parameter x >= 0 below which the shell buckles and above
/// which it does not, to hi / lo - 1 <= `rel_tol`, searching up to `x_max` as the module's
/// doc says, with `guess` the first trial per unit of -s(0) and `growth` the factor of the
/// steps taken without a secant. If x = 0 does not buckle, the bracket is [0, 0].
pub fn bracket(mut probe: impl FnMut(f64) -> Probe, guess: f64, growth: f64, x_max: f64, rel_tol: f64) -> Bracket {
    assert!(guess > 0.0 && growth > 1.0 && rel_tol > 0.0);
    let mut m = Memo { probe: &mut probe, done: Vec::new() };
    let zero = m.at(0.0);
    if !zero.buckles() {
        return Bracket { lo: 0.0, hi: 0.0, found: true, probes: m.done };
    }
    let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
    let q = 1.0 + rel_tol;
    let first = (guess * zero.signal().map_or(1.0, |s| (-s).clamp(1e-3, 1.0))).min(x_max);
    let mut x = first;
    // Trials divided while only x = 0 has snapped, probes in a row that did not snap, and
    // probes placed by margins.
    let (mut descents, mut misses, mut guided) = (0, 0, 0);
    loop {
        if m.at(x).buckles() {
            lo = lo.max(x);
            misses = 0;
            if x >= x_max {
                return Bracket { lo, hi: x_max, found: false, probes: m.done };
            }
        } else {
            hi = hi.min(x);
            misses += 1;
        }
        if lo > 0.0 && hi / lo <= q {
            break;
        }
        // Nothing snaps six decades below the first trial: the threshold is 0 to that.
        if lo == 0.0 && hi < 1e-6 * first {
            break;
        }
        let estimate = if lo > 0.0 { secant_estimate(&m.done) } else { None };
        let bisection = (lo * hi).sqrt();
        let margin = margin_estimate(&m.done).filter(|&e| e > lo && e <= hi && guided < GUIDED);
        x = if let Some(e) = margin {
            guided += 1;
            // An estimate far from every probe with a margin extrapolates the balance's
            // linearisation: probed itself, it gives a margin near the threshold.
            let near = m.done.iter().filter(|p| p.margin.is_some()).any(|p| (p.x / e - 1.0).abs() < rel_tol);
            // Near one, just above the estimate, then just below it: two probes that close
            // the bracket (q^0.9 wide) when the estimate is right.
            if !near {
                e
            } else if hi > e * q.powf(0.5) {
                (e * q.powf(0.45)).min(x_max)
            } else {
                e / q.powf(0.45)
            }
        } else if lo == 0.0 {
            descents += 1;
            hi / if descents <= 2 { DESCENT } else { growth }
        } else if hi.is_infinite() {
            // No further than `growth` beyond the last snap: an estimate extrapolated from
            // two probes far below the threshold is a poor one.
            let top = lo * growth.max(q);
            estimate.map_or(lo * growth, |e| (e * q.powf(ABOVE)).clamp(lo * q.powf(0.98), top)).min(x_max)
        } else if hi / lo <= q.powf(1.96) {
            // One probe closes the bracket whichever way it answers.
            estimate.unwrap_or(bisection).clamp(hi / q.powf(0.98), lo * q.powf(0.98))
        } else {
            match estimate {
                // Three probes in a row that did not snap: the secant overshoots here.
                _ if misses > 2 => bisection,
                // The threshold just below hi: a probe that closes the bracket if it snaps.
                Some(e) if e >= hi / q => hi / q.powf(0.98),
                Some(e) => (e * q.powf(ABOVE)).clamp(lo * (hi / lo).powf(0.1), lo * (hi / lo).powf(0.9)),
                None => bisection,
            }
        };
        // Strictly inside the bracket (a secant through probes below a failed one taken for
        // a snap, which has no signal, may point below lo).
        if x <= lo || x >= hi {
            x = if hi.is_finite() { bisection } else { (lo * growth).min(x_max) };
        }
    }
    Bracket { lo, hi, found: true, probes: m.done }
}

/// Relative change of the probed parameter with which a probe that did not converge is
/// run once more (`retrying`).
pub const RETRY_SHIFT: f64 = 1e-3;

/// `probe`, run once more at x (1 + RETRY_SHIFT) when it does not decide (`Probe::decided`);
/// the answer found there stands for x (its `x` stays x): with friction the loading's
/// Newton can stall on a node at the stick/slip kink for one value and not for a
/// neighbour a rounding away, and a failed probe only answers by `Probe::buckles`' rule of
/// thumb. The shift is far inside any bracketing tolerance (rel_tol 0.1).
pub fn retrying(mut probe: impl FnMut(f64) -> Probe) -> impl FnMut(f64) -> Probe {
    move |x| {
        let p = probe(x);
        if p.decided() {
            return p;
        }
        let q = probe(x * (1.0 + RETRY_SHIFT));
        if q.decided() {
            Probe { x, ..q }
        } else {
            p
        }
    }
}

/// One loading probe of `model` against `plate`, stopping at the snap-through as
/// `opt.snap` defines it. With `Snap::Landing` a loss of stability that never lands (held
/// by the energy up to delta_max) is not a snap: no `buckling`.
pub fn probe(model: &Model, plate: &Plate, e: f64, x: f64, opt: CycleOptions) -> Probe {
    let c = load_unload(model, plate, e, CycleOptions { stop_at_buckling: true, unload: false, ..opt });
    let reached =
        c.points.iter().filter(|p| p.step.converged()).map(|p| p.step.delta).fold(0.0, f64::max) / opt.delta_max;
    let margin = c.balance.filter(|b| b.delta == opt.delta_max).and_then(|b| Margin::of(&b, x));
    Probe { x, buckling: c.buckling.filter(|j| opt.snap.counts(j)), complete: c.complete, reached, margin }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::mesh::ShellMesh;
    use crate::fem::stability::{AdhesiveHold, Criterion, LIFT_THRESHOLD};
    use crate::fem::system::Base;

    #[test]
    fn the_bracket_closes_on_a_known_threshold() {
        let mut calls = 0;
        let f = |x: f64| {
            calls += 1;
            Probe {
                x,
                reached: 1.0,
                buckling: (x < 0.0123).then_some(Jump {
                    delta: 0.0,
                    force_before: 1.0,
                    delta_stable: 0.0,
                    force_unstable: 1.0,
                    force_after: 0.5,
                    radius_before: 0.4,
                    pull_before: 0.0,
                    delta_after: 0.0,
                }),
                complete: true,
                margin: None,
            }
        };
        let b = bracket(f, 1e-3, 3.0, 1.0, 0.02);
        assert!(b.found && b.lo < 0.0123 && b.hi >= 0.0123 && b.hi / b.lo - 1.0 <= 0.02, "{b:?}");
        assert_eq!(b.probes.len(), calls);
        // Nothing above x_max: not found; nothing at 0: [0, 0].
        let b =
            bracket(|x| Probe { x, buckling: None, complete: false, reached: 0.5, margin: None }, 1e-3, 3.0, 1.0, 0.02);
        assert!(!b.found && b.lo == 1.0);
        let b =
            bracket(|x| Probe { x, buckling: None, complete: true, reached: 1.0, margin: None }, 1e-3, 3.0, 1.0, 0.02);
        assert!(b.found && b.hi == 0.0 && b.probes.len() == 1);
    }

    /// A probe of a synthetic shell whose snap lies at delta_snap / delta_max = 1 + s(x),
    /// s rising from s0 at x = 0 to 0 at the threshold `xc` with the convexity of the map's
    /// measured signals (s = s0 (1 - (x / xc)^p)); none above xc.
    fn synthetic(xc: f64, s0: f64, p: f64) -> impl FnMut(f64) -> Probe {
        move |x: f64| {
            let snaps = x < xc;
            let reached = if snaps { 1.0 + s0 * (1.0 - (x / xc).powf(p)) } else { 1.0 };
            let jump = Jump {
                delta: reached,
                force_before: 1.0,
                delta_stable: reached,
                force_unstable: 1.0,
                force_after: f64::NAN,
                radius_before: 0.5,
                pull_before: 0.0,
                delta_after: f64::NAN,
            };
            Probe { x, buckling: snaps.then_some(jump), complete: true, reached, margin: None }
        }
    }

    #[test]
    fn the_secant_search_closes_on_smooth_signals_with_few_snapping_probes() {
        // Thresholds and signals like the map's (gamma_c/(E h) 2e-6 to 7e-5, s(0) -0.03 to
        // -0.86, p 1.2 to 2.5), the pipeline's guess 4e-5 and guesses 10 times off: the
        // bracket always holds the threshold to rel_tol. The geometric bisection took 6-10
        // probes on the map's points with the pipeline's guess, 4-6 of them snapping
        // (counting the probe at 0); here at most 7 and 4, and, with the guess 10 times too
        // large, at most 4 snapping among at most 12 (the others cheap).
        for (xc, s0) in [(2.5e-5, -0.56), (4.5e-5, -0.85), (2e-6, -0.03), (6.6e-5, -0.86), (1.4e-5, -0.41)] {
            for p in [1.2, 1.5, 2.0, 2.5] {
                for (guess, most, snapping_most) in [(4e-5, 7, 4), (4e-4, 12, 4), (4e-6, 10, 7)] {
                    let b = bracket(synthetic(xc, s0, p), guess, 2.0, 0.1, 0.1);
                    assert!(
                        b.found && b.lo < xc && b.hi >= xc && b.hi / b.lo <= 1.1 + 1e-12,
                        "{xc} {p} {guess}: {b:?}"
                    );
                    let snapping = b.probes.iter().filter(|q| q.buckles()).count();
                    assert!(
                        b.probes.len() <= most && snapping <= snapping_most,
                        "{xc} {s0} {p} {guess}: {} probes, {snapping} snapping",
                        b.probes.len()
                    );
                }
            }
        }
    }

    /// A probe of a synthetic shell under the energy criterion: at x = 0 it snaps at the
    /// flattened branch's end (delta_snap = 0.44 delta_max, no margin); above `x_local` the
    /// branch reaches delta_max and the balance is value(x) = (x - xc) (1 + c (x - xc) / xc),
    /// slope its derivative (c = 0: linear, as to first order; c != 0: curved).
    fn balanced(xc: f64, x_local: f64, c: f64) -> impl FnMut(f64) -> Probe {
        move |x: f64| {
            let mut p = synthetic(x_local, -0.56, 1.5)(x);
            if x >= x_local {
                let value = (x - xc) * (1.0 + c * (x - xc) / xc);
                let slope = 1.0 + 2.0 * c * (x - xc) / xc;
                p.margin = Some(Margin { value, slope });
                p.buckling =
                    (value < 0.0).then_some(Jump { delta: 0.9, ..synthetic(1.0, -0.1, 1.0)(0.0).buckling.unwrap() });
                p.reached = if value < 0.0 { 0.9 } else { 1.0 };
            }
            p
        }
    }

    #[test]
    fn a_margin_closes_the_bracket_in_two_probes_after_the_first_that_has_one() {
        // The map's energy thresholds (3e-3 E h) from guesses a decade off either way for a
        // linear balance, a factor 3 for a curved one (the curvature 0.3: a 60 % change of
        // slope over the distance xc; -0.1, whose balance turns back only past 11 xc): the bracket holds xc to rel_tol, with two probes after the first
        // that carries a margin if the balance is linear, at most four if curved (without margins
        // the search took 14 probes on the map's point at h/R = 0.06, mu = 0).
        for (c, guesses) in [(0.0, [3e-3, 3e-4, 3e-2]), (0.3, [3e-3, 1e-3, 1e-2]), (-0.1, [3e-3, 1e-3, 1e-2])] {
            for guess in guesses {
                let b = bracket(balanced(3e-3, 2.5e-5, c), guess, 2.0, 1.0, 0.1);
                assert!(b.found && b.lo < 3e-3 && b.hi >= 3e-3 && b.hi / b.lo <= 1.1 + 1e-12, "{c} {guess}: {b:?}");
                let first = b.probes.iter().position(|p| p.margin.is_some()).unwrap();
                let after = b.probes.len() - first - 1;
                assert!(after <= if c == 0.0 { 2 } else { 4 }, "{c} {guess}: {after} probes after the first margin");
            }
        }
        // A margin that misleads (its zero a factor 3 off the verdicts' threshold) still
        // brackets the verdicts' threshold: the verdicts decide, the margin only places.
        let mut lying = balanced(3e-3, 2.5e-5, 0.0);
        let liar = move |x: f64| {
            let mut p = lying(x);
            if let Some(m) = p.margin.as_mut() {
                m.value = x - 1e-3;
            }
            p
        };
        let b = bracket(liar, 3e-3, 2.0, 1.0, 0.1);
        assert!(b.found && b.lo < 3e-3 && b.hi >= 3e-3 && b.hi / b.lo <= 1.1 + 1e-12, "{b:?}");
    }

    #[test]
    fn any_growth_and_tolerance_bracket_without_panicking() {
        // Every clamp of the search has its bounds in order: growth below and above
        // 1 + rel_tol, tolerances from 1e-3 to 3, thresholds and guesses over decades.
        for growth in [1.01, 1.05, 1.5, 2.0, 10.0] {
            for rel_tol in [1e-3, 0.05, 0.1, 0.5, 3.0] {
                for (xc, guess) in [(2.5e-5, 4e-5), (2.5e-5, 4e-7), (2e-6, 4e-3), (1e-3, 4e-5)] {
                    let b = bracket(synthetic(xc, -0.5, 1.7), guess, growth, 0.1, rel_tol);
                    assert!(b.found && b.lo < xc && b.hi >= xc, "{growth} {rel_tol} {xc} {guess}: {b:?}");
                    assert!(b.hi / b.lo <= 1.0 + rel_tol + 1e-12, "{growth} {rel_tol} {xc} {guess}: {b:?}");
                }
            }
        }
    }

    #[test]
    fn a_signal_that_misleads_the_secant_still_brackets() {
        // The snap leaving the loading at once (a cusp: s jumps from -0.5 to nothing at
        // xc) and a signal with a wiggle: the secant's estimates are wrong, the bracket is
        // not, and the bisection that takes over bounds the probes.
        let cusp = |x: f64| {
            let mut p = synthetic(3e-5, -0.9, 1.0)(x);
            p.reached = if p.buckling.is_some() { 0.1 + 0.4 * x / 3e-5 } else { 1.0 };
            p
        };
        let wiggle = |x: f64| {
            let mut p = synthetic(2.5e-5, -0.7, 1.5)(x);
            if p.buckling.is_some() {
                p.reached += 0.05 * (1e6 * x).sin();
            }
            p
        };
        for guess in [4e-6, 4e-5, 4e-4] {
            for (xc, b) in
                [(3e-5, bracket(cusp, guess, 2.0, 0.1, 0.1)), (2.5e-5, bracket(wiggle, guess, 2.0, 0.1, 0.1))]
            {
                assert!(b.found && b.lo < xc && b.hi >= xc && b.hi / b.lo <= 1.1 + 1e-12, "{b:?}");
                assert!(b.probes.len() <= 12, "{guess}: {} probes", b.probes.len());
            }
        }
    }

    #[test]
    fn a_probe_that_fails_is_answered_by_its_neighbour() {
        // Fails exactly at x = 0.5 (and at 0.7 and its neighbour): the retry answers 0.5
        // from 0.5005, keeps x = 0.5; 0.7 stays failed; a converged probe runs once.
        // A failure in the last percent of delta_max (x = 0.9) is decided: no rerun.
        let mut runs = Vec::new();
        let mut f = retrying(|x: f64| {
            runs.push(x);
            let complete = x != 0.5 && (x - 0.7).abs() > 0.01 && x != 0.9;
            Probe {
                x,
                buckling: None,
                complete,
                reached: if x == 0.9 {
                    0.995
                } else if complete {
                    1.0
                } else {
                    0.6
                },
                margin: None,
            }
        });
        let p = f(0.5);
        assert!(p.complete && p.x == 0.5);
        assert!(!f(0.7).complete);
        assert!(f(0.2).complete);
        let end = f(0.9);
        assert!(!end.complete && end.decided() && !end.buckles());
        drop(f);
        assert_eq!(runs, vec![0.5, 0.5 * (1.0 + RETRY_SHIFT), 0.7, 0.7 * (1.0 + RETRY_SHIFT), 0.2, 0.9]);
    }

    #[test]
    fn a_failed_loading_answers_by_where_it_failed() {
        // Past a quarter of delta_max: taken for the fold of a snap; before: no evidence; in
        // the last percent, every state before stable: no snap before delta_max.
        let failed = |reached: f64| Probe { x: 1.0, buckling: None, complete: false, reached, margin: None };
        assert!(!failed(0.1).buckles() && !failed(0.1).decided());
        assert!(failed(0.5).buckles() && !failed(0.5).decided());
        assert!(failed(0.98).buckles());
        assert!(!failed(0.995).buckles() && failed(0.995).decided());
        // A bracket end on such a probe is reliable; on a mid-way failure it is not.
        let bracket_on = |reached: f64| Bracket { lo: 0.5, hi: 1.0, found: true, probes: vec![failed(reached)] };
        assert!(bracket_on(0.995).reliable() && !bracket_on(0.5).reliable());
    }

    #[test]
    fn adhesion_suppresses_the_snap_above_gamma_c_and_not_below() {
        // R = 15, h = 0.9 (h/R = 0.06, the thesis' Fig. 3.4), mu = 0, coarse mesh, delta/R up
        // to 0.3: bracket gamma_c to 20%, then check a cycle on each side of the bracket.
        // The code brackets gamma_c/(E h) in [0.0095, 0.0104] at 10%.
        let (e, r, h) = (1.3, 15.0, 0.9);
        let model = Model::new(ShellMesh::hemisphere(r, h, 60, 3, 8.0), e, 0.45, Base::Clamped);
        let opt = CycleOptions {
            delta_max: 0.3 * r,
            steps: 30,
            max_cuts: 6,
            bisections: 4,
            criterion: Criterion::LiftThreshold(LIFT_THRESHOLD),
            hold: AdhesiveHold::Free,
            trace_unstable: false,
            unload: false,
            stop_at_buckling: true,
            snap: Default::default(),
        };
        let plate = |g: f64| Plate::new(&model.mesh, e, 1000.0).with_adhesion(g, 0.1);
        let b = bracket(|g| probe(&model, &plate(g), e, g, opt), 3e-3 * e * h, 2.0, 0.1 * e * h, 0.2);
        assert!(b.found && b.lo > 0.0, "{b:?}");
        let (lo, hi) = (b.lo / (e * h), b.hi / (e * h));
        // A factor-2 error in gamma (or in the law's work of separation) would fall outside.
        assert!(lo > 8e-3 && hi < 1.25e-2, "{lo} {hi}");
        // Both sides again, independently of the bracket's own probes: below, a snap; above,
        // none up to delta_max.
        let below = probe(&model, &plate(0.9 * b.lo), e, 0.9 * b.lo, opt);
        let above = probe(&model, &plate(1.1 * b.hi), e, 1.1 * b.hi, opt);
        assert!(below.buckling.is_some() && below.complete, "{below:?}");
        assert!(above.buckling.is_none() && above.complete, "{above:?}");
        // Adhesion delays the snap monotonically (probes on the buckling side): the delta of
        // the snap and the contact (compressive) force there rise with gamma. The net plate
        // force, contact minus adhesive pull, does not: measured on this mesh F R/(E h^3) =
        // 9.3, 11.3, 11.1, 10.0 at gamma/(E h) = 0, 5e-4, 1e-3, 2e-3 (the pull grows with the
        // contact's perimeter).
        // Only the snap-throughs count here, those past delta/R 0.05: with the former
        // jump-in (Newton, before `cycle::jump_in` became an energy descent) the adhering
        // start at gamma/(E h) = 6e-3 was itself unstable on this coarse mesh (delta/R <
        // 1e-3), which the cycle records as its instability.
        let mut side: Vec<_> = b
            .probes
            .iter()
            .filter_map(|p| p.buckling.map(|j| (p.x, j.delta, j.force_before - j.pull_before)))
            .filter(|&(_, d, _)| d > 0.05 * r)
            .collect();
        side.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(side.len() >= 3, "{side:?}");
        assert!(side.windows(2).all(|w| w[1].1 >= w[0].1 && w[1].2 > w[0].2), "{side:?}");
    }
}
