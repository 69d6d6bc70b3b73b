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

use super::{Balance, Cycle, CycleOptions, Jump, Snap};
use crate::fem::indent::{apex_z, Step};
use crate::fem::problem::ShellProblem;

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

    /// The inverted state at the delta of the flattened state `flat`, and the balance of
    /// the two; none if no inverted state is found there.
    fn balance(&self, flat: &Step) -> Option<(Step, Balance)> {
        let inv = self.jump_to_inverted(flat)?;
        let balance = Balance {
            delta: flat.delta,
            inverted_less_flat: self.total_energy(&inv)? - self.total_energy(flat)?,
            adhesive_flat: self.adhesive_energy(flat),
            adhesive_inverted: self.adhesive_energy(&inv),
        };
        Some((inv, balance))
    }

    /// The inverted state at the delta of the flattened state `flat`, if it lies lower in
    /// Pi than `flat`.
    fn lower_inverted(&self, flat: &Step) -> Option<Step> {
        self.balance(flat).and_then(|(inv, b)| (b.inverted_less_flat < 0.0).then_some(inv))
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
            .filter(|&i| cycle.points[i].step.converged && cycle.points[i].step.delta > 0.0)
            .collect();
        let Some(&last) = flat.last() else { return cycle };
        let Some((mut inv, balance)) = self.balance(&cycle.points[last].step) else { return cycle };
        cycle.balance = Some(balance);
        if balance.inverted_less_flat >= 0.0 {
            return cycle;
        }
        // Bisection over the loading states for the first whose inverted state is lower:
        // `hi` is such a state, every state before `lo` (an index one past the last known not
        // to be) is not; the state before the first loaded one is the adhering start.
        let (mut lo, mut hi) = (0usize, flat.len() - 1);
        while lo < hi {
            let mid = (lo + hi) / 2;
            match self.lower_inverted(&cycle.points[flat[mid]].step) {
                Some(i) => {
                    hi = mid;
                    inv = i;
                }
                None => lo = mid + 1,
            }
        }
        let at = &cycle.points[flat[hi]].step;
        let before = &cycle.points[if hi > 0 { flat[hi - 1] } else { flat[0] - 1 }].step;
        cycle.buckling = Some(Jump {
            delta: at.delta,
            force_before: at.contact.force,
            delta_stable: before.delta,
            force_unstable: at.contact.force,
            force_after: inv.contact.force,
            radius_before: at.contact.radius,
            pull_before: at.contact.adhesive,
            delta_after: at.delta,
        });
        cycle.points.truncate(flat[hi] + 1);
        cycle.work_loading = super::work(&cycle.points);
        cycle
    }
}
