//! The critical adhesion gamma_c above which the shell no longer snaps through on loading
//! (thesis Section 3.4, Fig. 3.9), and the thickness above which it never does.
//!
//! A probe is one loading leg (`cycle::load_unload` with `stop_at_buckling`) at a given work
//! of adhesion: it answers "unstable before delta_max?", and if so gives F_buckling, delta
//! and the contact radius r there. gamma_c is bracketed: from a first guess, multiply or
//! divide by `growth` until the answer changes, then bisect geometrically until
//! hi / lo - 1 < rel_tol. Every probe is kept (a repeated gamma is not recomputed) and
//! reported. The analytic estimate of Eq. 3.7, gamma_c = E h (r/R)^4, uses the r of the
//! last probe that buckled (the instability closest to gamma_c).
//!
//! A probe whose loading fails to converge before either answer is counted as buckling if
//! it got past a quarter of delta_max (the snap is where Newton on the flattened branch
//! fails), else as not buckling; either way it is reported. A loading that fails within
//! the last percent of delta_max (`END_FRACTION`), stable up to there, has not snapped
//! before delta_max to that tolerance: not buckling, and decided.

use super::contact::Plate;
use super::cycle::{load_unload, CycleOptions, Jump};
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
}

/// The fraction of delta_max past which a loading that fails to converge, every state
/// before stable, counts as not snapping before delta_max. Measured (h/R = 0.02, mu = 0.5,
/// gamma/(E h) = 0.04, default mesh 230 x 2): the loading to delta_max = 0.35 R failed at
/// delta/R = 0.3497 (residual 1e-4), and so did gamma (1 + 1e-3) at 0.3496 and gamma 0.08 at
/// 0.3497, while the same loading to 0.34 R or to 0.36 R runs through stable without a snap:
/// the failure is the last step's, not a fold. Counted as buckling by the quarter rule,
/// such probes had put gamma_c at 0.082 instead of between 0.02 and 0.04.
pub const END_FRACTION: f64 = 0.99;

impl Probe {
    /// A snap, or a loading that failed after a quarter of delta_max (where Newton on the
    /// flattened branch fails, the snap is near) but before `END_FRACTION` of it. A loading
    /// that failed earlier (strong adhesion at first contact) is no evidence of buckling:
    /// counted as not buckling.
    pub fn buckles(&self) -> bool {
        self.buckling.is_some() || (!self.decided() && self.reached > 0.25)
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

/// Brackets the threshold of a parameter x >= 0 below which the shell buckles and above
/// which it does not: starts at `guess`, steps by the factor `growth` up to `x_max`, and
/// bisects (geometrically) to `rel_tol`. If x = 0 does not buckle, the bracket is [0, 0].
pub fn bracket(mut probe: impl FnMut(f64) -> Probe, guess: f64, growth: f64, x_max: f64, rel_tol: f64) -> Bracket {
    assert!(guess > 0.0 && growth > 1.0 && rel_tol > 0.0);
    let mut m = Memo { probe: &mut probe, done: Vec::new() };
    if !m.at(0.0).buckles() {
        return Bracket { lo: 0.0, hi: 0.0, found: true, probes: m.done };
    }
    let (mut lo, mut hi) = (0.0, f64::INFINITY);
    let mut x = guess.min(x_max);
    loop {
        if m.at(x).buckles() {
            lo = x;
            if x >= x_max {
                return Bracket { lo, hi: x_max, found: false, probes: m.done };
            }
            if hi.is_finite() {
                break;
            }
            x = (x * growth).min(x_max);
        } else {
            hi = x;
            if lo > 0.0 || x < guess / growth.powi(12) {
                break;
            }
            x /= growth;
        }
    }
    while hi / lo.max(f64::MIN_POSITIVE) - 1.0 > rel_tol {
        let mid = if lo > 0.0 { (lo * hi).sqrt() } else { 0.5 * hi };
        if m.at(mid).buckles() {
            lo = mid;
        } else {
            hi = mid;
        }
        if lo == 0.0 && hi < guess * 1e-6 {
            break;
        }
    }
    Bracket { lo, hi, found: true, probes: m.done }
}

/// Relative change of the probed parameter with which a probe that did not converge is
/// run once more (`retrying`).
pub const RETRY_SHIFT: f64 = 1e-3;

/// `probe`, run once more at x (1 + RETRY_SHIFT) when it does not decide (`Probe::decided`);
/// the answer found there stands for x (its `x` stays x). Measured: with friction the
/// loading's Newton can stall on a node at the stick/slip kink for one value and not for
/// its neighbour (h/R = 0.02, mu = 0.5, gamma/(E h) = 0.04: the stage's gamma failed at
/// delta/R = 0.3497 with residual 6e-5, the same gamma 2e-16 lower ran through, stable, to
/// delta_max), and a failed probe only answers by `Probe::buckles`' rule of thumb. The
/// shift is far inside any bracketing tolerance (rel_tol 0.1).
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
        c.points.iter().filter(|p| p.step.converged).map(|p| p.step.delta).fold(0.0, f64::max) / opt.delta_max;
    Probe { x, buckling: c.buckling.filter(|j| opt.snap.counts(j)), complete: c.complete, reached }
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
            }
        };
        let b = bracket(f, 1e-3, 3.0, 1.0, 0.02);
        assert!(b.found && b.lo < 0.0123 && b.hi >= 0.0123 && b.hi / b.lo - 1.0 <= 0.02, "{b:?}");
        assert_eq!(b.probes.len(), calls);
        // Nothing above x_max: not found; nothing at 0: [0, 0].
        let b = bracket(|x| Probe { x, buckling: None, complete: false, reached: 0.5 }, 1e-3, 3.0, 1.0, 0.02);
        assert!(!b.found && b.lo == 1.0);
        let b = bracket(|x| Probe { x, buckling: None, complete: true, reached: 1.0 }, 1e-3, 3.0, 1.0, 0.02);
        assert!(b.found && b.hi == 0.0 && b.probes.len() == 1);
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
        let failed = |reached: f64| Probe { x: 1.0, buckling: None, complete: false, reached };
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
        // Measured: gamma_c/(E h) in [0.0095, 0.0104] (bracketed to 10%).
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
