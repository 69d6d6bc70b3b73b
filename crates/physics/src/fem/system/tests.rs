use super::*;

/// Linear response (one Newton step from the reference state) to a downward load on the
/// outer surface within r <= c ~ h, much less than the bending length sqrt(R h): the
/// apex stiffness F / delta (delta of the mid-surface) over Reissner's shallow-shell
/// point-load value 4 E h^2 / (R sqrt(3 (1 - nu^2))), R the mid-surface radius.
fn reissner_ratio(h: f64, n_meridian: usize, grading: f64) -> f64 {
    let (e, nu, r) = (1.3, 0.45, 1.0);
    let mesh = ShellMesh::hemisphere(r, h, n_meridian, 4, grading);
    let idx = mesh.outer.iter().position(|&a| mesh.nodes[a][0] >= h).unwrap();
    let c = mesh.nodes[mesh.outer[idx + idx % 2]][0]; // an element corner
    let model = Model::new(mesh, e, nu, Base::Clamped);
    let f_ext = outer_pressure_forces(&model.mesh, |rr| if rr <= c { 1.0 } else { 0.0 });
    let total: f64 = -f_ext.iter().skip(1).step_by(2).sum::<f64>();
    assert!((total / (std::f64::consts::PI * c * c) - 1.0).abs() < 1e-3, "{total}");
    let (_, k) = model.assemble(&vec![0.0; model.n_dofs()]).unwrap();
    let du = model.solve(&k, &f_ext).unwrap();
    let mid = model.mesh.axis[model.mesh.axis.len() / 2];
    let delta = -du[2 * mid + 1];
    total / delta / (4.0 * e * h * h / ((r + 0.5 * h) * (3.0 * (1.0 - nu * nu)).sqrt()))
}

#[test]
fn thin_shell_apex_stiffness_tends_to_reissners() {
    // Measured (c ~ h): 0.964, 0.980, 0.987 at h/R = 0.02, 0.01, 0.005, the same to 3
    // digits with twice the elements along the meridian or through the thickness; the
    // ratio grows with c/h (1.02 at c = 2h, 1.13 at 4h for h/R = 0.01): a load spread
    // over a cap is no longer a point load.
    let (r1, r2) = (reissner_ratio(0.01, 120, 40.0), reissner_ratio(0.005, 200, 60.0));
    assert!((r1 - 1.0).abs() < 0.025 && (r2 - 1.0).abs() < 0.015, "{r1} {r2}");
    assert!((r2 - 1.0).abs() < 0.75 * (r1 - 1.0).abs(), "not converging to the thin limit: {r1} {r2}");
}

#[test]
fn cholesky_and_lu_solve_the_same_system_and_slip_takes_lu() {
    // A pressed state with friction: the tangent is symmetric while every node sticks, so
    // `solve` takes Cholesky, and LU on the same system agrees to rounding; a slipping
    // node's entry breaks the symmetry (and `solve` then takes LU).
    let (e, r) = (1.3, 15.0);
    let model = Model::new(ShellMesh::hemisphere(r, 1.0, 40, 2, 3.0), e, 0.45, Base::Clamped);
    let plate = crate::fem::contact::Plate::new(&model.mesh, e, 1000.0).with_friction(0.5);
    let path = crate::fem::indent::load_path(&model, &plate, e, 0.05 * r, 5, 4);
    let s = path.last().unwrap();
    let (_, mut k) = model.assemble(&s.u).unwrap();
    let rhs: Vec<f64> = (0..model.n_dofs()).map(|i| (i as f64 * 0.37).sin()).collect();
    assert!(k.is_symmetric() && model.cholesky(&k).is_some());
    let x = model.solve(&k, &rhs).unwrap();
    let mut y = model.to_free(&[&rhs]).remove(0);
    model.factorize(&k).unwrap().solve_in_place(&mut y);
    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, &j) in model.pattern.index.iter().enumerate() {
        if j != usize::MAX {
            assert!((x[i] - y[j]).abs() < 1e-9 * scale, "{i}: {} vs {}", x[i], y[j]);
        } else {
            assert_eq!(x[i], 0.0);
        }
    }
    // A slip entry (u_r row, u_z column of one node) breaks the symmetry.
    let a = model.mesh.outer[3];
    k.push((2 * a, 2 * a + 1, 1e-3));
    assert!(!k.is_symmetric());
}

#[test]
#[should_panic(expected = "outside the model's pattern")]
fn an_entry_coupling_two_elements_apart_is_refused() {
    let model = Model::new(ShellMesh::hemisphere(15.0, 1.0, 40, 2, 3.0), 1.3, 0.45, Base::Clamped);
    let mut k = model.zero_stiffness();
    let (a, b) = (model.mesh.outer[0], model.mesh.outer[20]);
    k.push((2 * a + 1, 2 * b + 1, 1.0));
}

#[test]
fn the_tangent_is_a_band_of_one_elements_width() {
    // Numbered along the meridian, an element of a 2-layer mesh spans 11 nodes (a corner
    // row of 5, a mid-side row of 3, and 3 of the next corner row): |i - j| <= 21 on the
    // full numbering; the fixed dofs removed, no more. The pattern is that of every
    // tangent along a path (friction and contact changing): the load path keeps working
    // on it, with LU factorisations made where friction slips.
    let (e, r) = (1.3, 15.0);
    let model = Model::new(ShellMesh::hemisphere(r, 1.0, 40, 2, 3.0), e, 0.45, Base::Clamped);
    assert!(model.pattern.half_band <= 21 && model.pattern.half_band >= 19, "{}", model.pattern.half_band);
    // The memory bound's node count and half-band (`mesh::node_count`, `mesh::half_band`)
    // hold for any layering: the count exactly, the band from above by at most the fixed
    // dofs' two.
    for layers in [1, 2, 4, 8] {
        let mesh = ShellMesh::hemisphere(r, 1.0, 12, layers, 3.0);
        assert_eq!(crate::fem::mesh::node_count(12, layers), mesh.nodes.len() as u64);
        let band = Model::new(mesh, e, 0.45, Base::Clamped).pattern.half_band;
        let bound = crate::fem::mesh::half_band(layers);
        assert!(band <= bound && band + 2 >= bound, "{layers} layers: {band} against {bound}");
    }
    let plate = crate::fem::contact::Plate::new(&model.mesh, e, 1000.0).with_friction(0.5);
    let path = crate::fem::indent::load_path(&model, &plate, e, 0.12 * r, 12, 4);
    assert!(path.iter().all(|s| s.converged()) && path.last().unwrap().contact.force > 0.0);
    assert!(model.factorizations() > 0);
}

#[test]
fn the_forces_alone_are_the_assemblys_bitwise_and_none_when_inverted() {
    // A line search compares the residual norms of trial points built from
    // `internal_forces` with those of `assemble`: they must be the same numbers, or the
    // accepted point's norm would differ from the one that was accepted.
    let model = Model::new(ShellMesh::hemisphere(15.0, 1.0, 30, 2, 3.0), 1.3, 0.45, Base::Clamped);
    let mut u: Vec<f64> = (0..model.n_dofs()).map(|i| 0.01 * ((i as f64) * 0.37).sin()).collect();
    model.fixed.iter().zip(u.iter_mut()).for_each(|(&f, v)| *v = if f { 0.0 } else { *v });
    let (f, _) = model.assemble(&u).unwrap();
    let alone = model.internal_forces(&u).unwrap();
    assert!(f.iter().any(|v| v.abs() > 1e-6));
    assert!(f.iter().zip(&alone).all(|(a, b)| a.to_bits() == b.to_bits()));
    // Crush the apex row through the thickness: inverted elements, no forces.
    let apex: Vec<usize> = model.mesh.outer.iter().take(3).copied().collect();
    for &a in &apex {
        u[2 * a + 1] -= 5.0;
    }
    assert!(model.assemble(&u).is_none() && model.internal_forces(&u).is_none());
}

#[test]
fn the_smallest_eigenvalue_is_where_a_shift_loses_definiteness() {
    // Sylvester: K - s I is positive definite for every s below the smallest eigenvalue
    // of K and for none above, so the inverse iteration's value must sit between two
    // shifts 0.1 % apart (the tangent of the unloaded shell and of a pressed state).
    let (e, r) = (1.3, 15.0);
    let model = Model::new(ShellMesh::hemisphere(r, 1.0, 40, 2, 3.0), e, 0.45, Base::Clamped);
    let shifted = |k: &Stiffness, s: f64| {
        let mut k = k.clone();
        for i in (0..model.n_dofs()).filter(|&i| !model.fixed[i]) {
            k.push((i, i, -s));
        }
        k
    };
    let mut u = vec![0.0; model.n_dofs()];
    for (i, v) in u.iter_mut().enumerate() {
        *v = if model.fixed[i] { 0.0 } else { 1e-3 * ((i as f64) * 0.37).sin() };
    }
    for state in [vec![0.0; model.n_dofs()], u] {
        let (_, k) = model.assemble(&state).unwrap();
        let lambda = model.smallest_eigenvalue(&k, 300).unwrap();
        assert!(lambda > 0.0);
        assert!(model.is_stable(&shifted(&k, 0.999 * lambda)), "{lambda}");
        assert!(!model.is_stable(&shifted(&k, 1.001 * lambda)), "{lambda}");
    }
    // Not positive definite: no margin.
    let (_, k) = model.assemble(&vec![0.0; model.n_dofs()]).unwrap();
    let lambda = model.smallest_eigenvalue(&k, 300).unwrap();
    assert!(model.smallest_eigenvalue(&shifted(&k, 1.01 * lambda), 15).is_none());
}

#[test]
fn the_reduced_rules_spurious_modes_do_not_propagate_through_a_shell() {
    // Each 2 x 2 element has one zero-energy mode (`element::tests`), which neighbours do
    // not share: the clamped shell's tangent at rest stays positive definite, with the
    // smallest eigenvalue of the 3 x 3 rule's within 0.1 % (measured on the default mesh of
    // h/R = 0.06, 239 x 2 elements: 5.0978e-4 and 5.0990e-4).
    use crate::fem::element::Integration;
    let (r, h) = (15.0, 0.9);
    let smallest = |rule| {
        let model =
            Model::new(ShellMesh::hemisphere(r, h, 60, 2, 3.0), 1.3, 0.45, Base::Clamped).with_integration(rule);
        let (_, k) = model.assemble(&vec![0.0; model.n_dofs()]).unwrap();
        assert!(model.is_stable(&k), "{rule:?}");
        model.smallest_eigenvalue(&k, 60).unwrap()
    };
    let (full, reduced) = (smallest(Integration::Full), smallest(Integration::Reduced));
    assert!(reduced < full && (reduced / full - 1.0).abs() < 1e-3, "{reduced} {full}");
}
