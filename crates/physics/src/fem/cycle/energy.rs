//! The energy criterion of the snap (the balance that thesis Eq. 3.7 estimates): the shell
//! snaps where the inverted state stores less total potential energy than the adhered
//! flattened state at the same plate displacement, or where the flattened branch ends.
//!
//! Model: Pi(state) = strain energy (with the imperfection's dead load) + penalty energy of
//! the contact + adhesive energy of the Lennard-Jones law (`Plate::energy`; friction is
//! not a potential and stores nothing). The flattened branch is loaded monolithically as
//! under `Snap::Instability`; if it loses stability before delta_max, that is the snap.
//! Otherwise the inverted state at delta_max is found where a damped jump from the
//! flattened one comes to rest (`ShellProblem::jump_to_inverted`), and the balance there is
//! recorded (`Balance`: the bracket of gamma_c places its probes by it,
//! `critical::Margin`); if the inverted Pi is lower, the
//! shell snaps, at the first loading state whose inverted neighbour is lower (found by
//! bisection over the loading states: Pi_flat - Pi_inv rises with delta, measured in
//! docs/shell.md, "The snap criteria").
//!
//! Why: as g0 -> 0 the adhesive energy tends to -dgamma times the area in contact, whatever
//! the law's range, so that the balance -dgamma A_flat + U_flat = -dgamma A_inv + U_inv
//! has a limit; to first order in dgamma, gamma_c = (U_flat - U_inv) / (A_flat - A_inv)
//! at delta_max. The barrier against lifting a touching interior off the plate (the local
//! criterion) is a strength of order dgamma / g0 instead, and moves with g0.

use super::loading::Loading;
use super::{Balance, Cycle, CycleOptions, CyclePoint, Jump, Leg, Snap};
use crate::fem::indent::{apex_z, Options, Step};
use crate::fem::problem::ShellProblem;

/// The snap at the flattened state `at`, the first whose inverted neighbour `inv` is lower,
/// the last state before it at `delta_stable`: the jump lands at once, at the same delta.
fn crossing(delta_stable: f64, at: &Step, inv: &Step) -> Jump {
    Jump {
        delta: at.delta,
        force_before: at.contact.force,
        delta_stable,
        force_unstable: at.contact.force,
        force_after: inv.contact.force,
        radius_before: at.contact.radius,
        pull_before: at.contact.adhesive,
        delta_after: at.delta,
    }
}

/// Whether the criterion `snap` weighs the friction work of the jump (`Snap::Energy`).
fn friction(snap: Snap) -> bool {
    matches!(snap, Snap::Energy { friction: true })
}

impl ShellProblem<'_> {
    /// The total potential energy Pi of the state `s` (module doc); None if an element is
    /// inverted.
    pub fn total_energy(&self, s: &Step) -> Option<f64> {
        let z_plate = apex_z(self.model) - s.delta;
        Some(self.model.strain_energy(&s.u)? + self.plate.energy(&self.model.mesh, &s.u, z_plate))
    }

    /// The adhesive energy of the state `s` (<= 0).
    fn adhesive_energy(&self, s: &Step) -> f64 {
        self.plate.adhesive_energy(&self.model.mesh, &s.u, apex_z(self.model) - s.delta)
    }

    /// The work Coulomb friction does as the contact slides from the flattened state `flat`
    /// to the inverted state `inv` at the same delta: per outer node, mu times its mean
    /// contact pressure over the two states, its tributary area and its radial slip
    /// |r_inv - r_flat| (the plate is flat: the slip is radial). The path between the two
    /// is not traced; the mean pressure takes it straight. Zero without friction.
    pub fn friction_work(&self, flat: &Step, inv: &Step) -> f64 {
        let Some(friction) = self.plate.friction else { return 0.0 };
        let mesh = &self.model.mesh;
        let pressure = |s: &Step, k: usize| s.contact.pressure.get(k).copied().unwrap_or(0.0);
        mesh.outer
            .iter()
            .enumerate()
            .map(|(k, &a)| {
                let slip = (inv.u[2 * a] - flat.u[2 * a]).abs();
                friction.mu * 0.5 * (pressure(flat, k) + pressure(inv, k)) * self.plate.weights[k] * slip
            })
            .sum()
    }

    /// The inverted state at the delta of the flattened state `flat`, and the balance of
    /// the two (with the friction work of the way if `friction`); none if no inverted state
    /// is found there.
    pub(super) fn balance(&self, flat: &Step, friction: bool) -> Option<(Step, Balance)> {
        let inv = self.jump_to_inverted(flat)?;
        let friction_work = if friction { self.friction_work(flat, &inv) } else { 0.0 };
        let balance = Balance {
            delta: flat.delta,
            inverted_less_flat: self.total_energy(&inv)? - self.total_energy(flat)? + friction_work,
            friction_work,
            adhesive_flat: self.adhesive_energy(flat),
            adhesive_inverted: self.adhesive_energy(&inv),
        };
        Some((inv, balance))
    }

    /// The inverted state at the delta of the flattened state `flat`, if it lies lower in
    /// Pi (by the friction work too if `friction`) than `flat`.
    fn lower_inverted(&self, flat: &Step, friction: bool) -> Option<Step> {
        self.balance(flat, friction).and_then(|(inv, b)| (b.inverted_less_flat < 0.0).then_some(inv))
    }

    /// The first of the flattened states `flat` (indices into `points`, in order) whose
    /// inverted neighbour lies lower, given that the last one's, `inv`, does: bisection over
    /// the states (Pi_flat - Pi_inv rises with delta). That state's index, its inverted
    /// state, and the jump there; the state before the first of `flat` is the adhering
    /// start.
    fn first_lower(&self, points: &[CyclePoint], flat: &[usize], mut inv: Step, friction: bool) -> (usize, Step, Jump) {
        // `hi` is such a state, every state before `lo` (an index one past the last known
        // not to be) is not.
        let (mut lo, mut hi) = (0usize, flat.len() - 1);
        while lo < hi {
            let mid = (lo + hi) / 2;
            match self.lower_inverted(&points[flat[mid]].step, friction) {
                Some(i) => {
                    hi = mid;
                    inv = i;
                }
                None => lo = mid + 1,
            }
        }
        let at = &points[flat[hi]].step;
        let before = &points[if hi > 0 { flat[hi - 1] } else { flat[0].saturating_sub(1) }].step;
        let jump = crossing(before.delta, at, &inv);
        (flat[hi], inv, jump)
    }

    /// Bisects in delta between the flattened state `lo`, whose inverted neighbour is not
    /// lower, and `hi`, whose inverted neighbour `inv` is, `opt.bisections` times (fewer if a
    /// solve fails or leaves the branch): the crossing located to the bracket / 2^bisections.
    /// The bracket's ends and the inverted state at its upper end.
    fn refine_crossing(
        &self,
        mut lo: Step,
        mut hi: Step,
        mut inv: Step,
        opt: CycleOptions,
        friction: bool,
    ) -> (Step, Step, Step) {
        for _ in 0..opt.bisections {
            let mut mid = self.solve_from(0.5 * (lo.delta + hi.delta), &lo, Options::default());
            mid.stable = mid.converged() && self.is_stable(&mid, opt.criterion, opt.hold);
            if !mid.stable {
                break;
            }
            match self.balance(&mid, friction) {
                Some((i, b)) if b.inverted_less_flat < 0.0 => {
                    hi = mid;
                    inv = i;
                }
                // No inverted state at mid (the inverted branch begins past it): no snap
                // there either.
                Some(_) | None => lo = mid,
            }
        }
        (lo, hi, inv)
    }

    /// The loading leg under the energy criterion (module doc), stopped at the snap.
    pub(super) fn energy_loading(&self, opt: CycleOptions) -> Cycle {
        let local = CycleOptions { snap: Snap::Instability, stop_at_buckling: true, unload: false, ..opt };
        let mut cycle = self.load_unload(local);
        if let Some(b) = cycle.buckling.as_mut() {
            // The flattened branch ends: a snap under this criterion too, wherever it lands.
            b.delta_after = b.delta;
            return cycle;
        }
        if !cycle.complete {
            return cycle;
        }
        let flat: Vec<usize> = (0..cycle.points.len())
            .filter(|&i| cycle.points[i].step.converged() && cycle.points[i].step.delta > 0.0)
            .collect();
        let Some(&last) = flat.last() else { return cycle };
        let Some((inv, balance)) = self.balance(&cycle.points[last].step, friction(opt.snap)) else { return cycle };
        cycle.balance = Some(balance);
        if balance.inverted_less_flat >= 0.0 {
            return cycle;
        }
        let (at, _, jump) = self.first_lower(&cycle.points, &flat, inv, friction(opt.snap));
        cycle.buckling = Some(jump);
        cycle.points.truncate(at + 1);
        cycle.work_loading = super::work(&cycle.points);
        cycle
    }

    /// The whole cycle under the energy criterion. The loading leg is traced as under the
    /// local criterion (the flattened branch, and past its end the jump and the inverted
    /// branch to delta_max); then the balance is taken at the last flattened state (before
    /// the branch ends, or at delta_max). Where the inverted state lies lower there, the
    /// snap is at the first flattened state where it does (`first_lower`): the leg is cut
    /// there, jumps to that inverted state and follows the inverted branch to delta_max
    /// (`Loading::resumed`). The unloading leg follows as under the local criterion.
    pub(super) fn energy_cycle(&self, opt: CycleOptions) -> Cycle {
        let local = CycleOptions { snap: Snap::Instability, ..opt };
        let mut loading = self.local_loading(local);
        if loading.complete {
            let end = loading.buckling.map_or(f64::INFINITY, |b| b.delta_stable);
            let flat: Vec<usize> = (0..loading.points.len())
                .filter(|&i| {
                    let p = &loading.points[i];
                    p.step.converged() && !p.inverted && p.step.delta > 0.0 && p.step.delta <= end
                })
                .collect();
            let lower = flat.last().and_then(|&last| self.balance(&loading.points[last].step, friction(opt.snap)));
            if let Some((inv, _)) = lower.filter(|(_, b)| b.inverted_less_flat < 0.0) {
                let (at, inv, _) = self.first_lower(&loading.points, &flat, inv, friction(opt.snap));
                let mut points = loading.points;
                let at = points[at].step.clone();
                points.truncate(points.iter().position(|p| p.step.delta >= at.delta).unwrap_or(points.len()));
                let before = points.last().expect("the start precedes every loaded state").step.clone();
                let (lo, hi, mut inv) = self.refine_crossing(before.clone(), at, inv, local, friction(opt.snap));
                let flat = |step: Step| CyclePoint { step, leg: Leg::Loading, inverted: false };
                if lo.delta > before.delta {
                    points.push(flat(lo.clone()));
                }
                points.push(flat(hi.clone()));
                inv.stable = self.is_stable(&inv, local.criterion, local.hold);
                let jump = crossing(lo.delta, &hi, &inv);
                loading = Loading::resumed(self, local, points, inv, jump);
                loading.run();
            }
        }
        self.with_unloading(local, loading)
    }
}
