//! Mesh of a hemispherical shell's meridian section for the axisymmetric model of thesis
//! Chapter 3 (Section 3.2, Fig. 3.1b): 8-node serendipity quadrilaterals (as ANSYS PLANE183)
//! in the (r, z) half-plane, `n_thickness` elements through the thickness and `n_meridian`
//! along the meridian, graded towards the apex, where the plate touches first.
//!
//! Geometry: inner radius R, thickness h; the material occupies R <= rho <= R + h,
//! 0 <= phi <= pi/2 (phi from the axis), r = rho sin(phi), z = rho cos(phi). The apex of the
//! outer surface is at (0, R + h); the equator (phi = pi/2) is the base z = 0.
//! Nodes lie on the exact circles (isoparametric elements then represent the arcs to third
//! order in the element size).

use super::element::Integration;

/// One quadratic element: corner nodes counter-clockwise in (xi, eta), then mid-side nodes
/// (xi, eta) = (0,-1), (1,0), (0,1), (-1,0). xi runs along the meridian (apex to equator),
/// eta through the thickness (inner to outer).
pub type Element = [usize; 8];

#[derive(Clone, Debug)]
pub struct ShellMesh {
    /// Inner radius R and thickness h.
    pub radius: f64,
    pub thickness: f64,
    /// Node coordinates (r, z) in the reference configuration.
    pub nodes: Vec<[f64; 2]>,
    pub elements: Vec<Element>,
    /// Nodes on the axis r = 0 (u_r = 0 there).
    pub axis: Vec<usize>,
    /// Nodes on the base z = 0 (the equator section).
    pub base: Vec<usize>,
    /// Nodes of the outer surface, from the apex towards the equator (contact candidates).
    pub outer: Vec<usize>,
}

/// Elements along the meridian per (R + h) / g0 in the default mesh (grading 3): the
/// element at the contact rim of the snap (r ~ 0.5-0.6 R) is then about g0 long, which the
/// Lennard-Jones law of Eq. 3.3 needs (it varies over g0 in the gap). F_buckling and W on
/// it against 480 elements: docs/tuning.md, "Shell mesh".
pub const MERIDIAN_ELEMENTS_PER_G0: f64 = 1.5;

/// Relative error of F_buckling on the default mesh (`meridian_elements`, 2 elements
/// through the thickness) up to mu = 0.5, declared above the departures measured against
/// finer meshes (docs/tuning.md, "Shell mesh"); with friction: `default_mesh_rel_error`.
pub const DEFAULT_MESH_REL_ERROR: f64 = 0.005;

/// Relative error of a cycle's dissipated energy W on the default mesh (2 elements through
/// the thickness) under each Gauss rule. With 3 x 3 points the elements are too stiff where
/// adhesion and friction load the surface, and W comes out high; refining along the
/// meridian alone (the mesh study) does not show it. The largest departures over eight
/// cycles against four elements of the 2 x 2 rule, declared here as 5 % (3 x 3) and 1 %
/// (2 x 2), are in docs/shell.md, "The element's Gauss rule".
pub fn default_mesh_w_rel_error(integration: Integration) -> f64 {
    match integration {
        Integration::Full => 0.05,
        Integration::Reduced => 0.01,
    }
}

/// Relative error of F_buckling on the default mesh with friction `mu`, where the mesh
/// converges more slowly: `DEFAULT_MESH_REL_ERROR` up to mu = 0.5, rising linearly to 1.3 %
/// at mu = 1 and 1.3 % beyond (docs/tuning.md, "Shell mesh", has the departures measured).
pub fn default_mesh_rel_error(mu: f64) -> f64 {
    const AT_MU_1: f64 = 0.013;
    let t = ((mu - 0.5) / 0.5).clamp(0.0, 1.0);
    DEFAULT_MESH_REL_ERROR + t * (AT_MU_1 - DEFAULT_MESH_REL_ERROR)
}

/// The default number of meridian elements for a shell of inner radius `radius` and
/// `thickness` with the Lennard-Jones range `g0` (`MERIDIAN_ELEMENTS_PER_G0`).
pub fn meridian_elements(radius: f64, thickness: f64, g0: f64) -> usize {
    (MERIDIAN_ELEMENTS_PER_G0 * (radius + thickness) / g0).ceil().max(4.0) as usize
}

/// Nodes of the mesh: (n_meridian + 1) columns of 2 n_thickness + 1 corner and mid-side
/// nodes, and n_meridian columns of n_thickness + 1 mid-side ones (no element centres).
pub fn node_count(n_meridian: usize, n_thickness: usize) -> u64 {
    let (m, t) = (n_meridian as u64, n_thickness as u64);
    (m + 1) * (2 * t + 1) + m * (t + 1)
}

/// The half-width, in degrees of freedom, of the tangent's band on this numbering (nodes
/// along the meridian, through the thickness within a column): an element spans a corner
/// column of 2 n_thickness + 1 nodes, a mid-side column of n_thickness + 1 and 3 of the
/// next corner column, 3 n_thickness + 5 nodes, so |i - j| <= 6 n_thickness + 9.
pub fn half_band(n_thickness: usize) -> usize {
    6 * n_thickness + 9
}

/// An upper bound on the bytes a load-unload cycle of the shell allocates on this mesh,
/// keeping `states` states of its path, estimated before anything is allocated. Per
/// degree of freedom: the band LU with room for its fill (3 half-bands), the Cholesky band
/// (1), the sparse tangent's values and indices (4 x 2) and 76 work vectors; per kept
/// state its displacements and its contact nodes' state; 64 MiB for the process. Against
/// peak resident sets, 1.8-2.4 times the measured (docs/reliability.md, "Resources").
pub fn cycle_memory_bound(n_meridian: usize, n_thickness: usize, states: usize) -> u64 {
    let dofs = 2 * node_count(n_meridian, n_thickness);
    let per_dof = 8 * (12 * half_band(n_thickness) as u64 + 76);
    let per_state = 8 * dofs + 64 * (2 * n_meridian as u64 + 1);
    (64u64 << 20).saturating_add(dofs.saturating_mul(per_dof)).saturating_add((states as u64).saturating_mul(per_state))
}

/// Meridian angles of the element boundaries: `n` elements on [0, pi/2] whose sizes grow
/// geometrically from the apex so that the last is `grading` times the first.
pub fn graded_angles(n: usize, grading: f64) -> Vec<f64> {
    let q = if n > 1 { grading.powf(1.0 / (n - 1) as f64) } else { 1.0 };
    let sizes: Vec<f64> = (0..n).map(|i| q.powi(i as i32)).collect();
    let total: f64 = sizes.iter().sum();
    let mut out = vec![0.0];
    let mut acc = 0.0;
    for s in sizes {
        acc += s;
        out.push(std::f64::consts::FRAC_PI_2 * acc / total);
    }
    *out.last_mut().unwrap() = std::f64::consts::FRAC_PI_2;
    out
}

/// A Gauss point of a quadratic edge of the outer surface (reference configuration).
pub struct EdgePoint {
    /// Positions of the edge's three nodes in `outer` (corner, mid-side, corner).
    pub outer: [usize; 3],
    /// Their quadratic shape functions at the point.
    pub shape: [f64; 3],
    /// r at the point, dr/dxi, ds/dxi (meridian arc length) and the Gauss weight.
    pub r: f64,
    pub dr: f64,
    pub ds: f64,
    pub weight: f64,
}

impl ShellMesh {
    /// The 3-point Gauss rule along every outer edge (for surface loads and contact areas).
    pub fn outer_edge_points(&self) -> Vec<EdgePoint> {
        let mut out = Vec::new();
        for e in 0..(self.outer.len() - 1) / 2 {
            let ids = [2 * e, 2 * e + 1, 2 * e + 2];
            let x: [[f64; 2]; 3] = std::array::from_fn(|k| self.nodes[self.outer[ids[k]]]);
            for &(xi, weight) in &super::element::GAUSS {
                let shape = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
                let dn = [xi - 0.5, -2.0 * xi, xi + 0.5];
                let along = |c: usize, f: &[f64; 3]| (0..3).map(|k| f[k] * x[k][c]).sum::<f64>();
                let (dr, dz) = (along(0, &dn), along(1, &dn));
                out.push(EdgePoint {
                    outer: ids,
                    shape,
                    r: along(0, &shape),
                    dr,
                    ds: (dr * dr + dz * dz).sqrt(),
                    weight,
                });
            }
        }
        out
    }

    /// A hemispherical shell of inner radius `radius` and thickness `thickness`, with
    /// `n_meridian` x `n_thickness` elements, sizes along the meridian growing by `grading`
    /// from apex to equator.
    pub fn hemisphere(radius: f64, thickness: f64, n_meridian: usize, n_thickness: usize, grading: f64) -> ShellMesh {
        assert!(radius > 0.0 && thickness > 0.0 && n_meridian >= 1 && n_thickness >= 1 && grading > 0.0);
        let phi_el = graded_angles(n_meridian, grading);
        // Grid of (2 n_meridian + 1) x (2 n_thickness + 1) positions; serendipity elements
        // skip the positions with both indices odd (element centres).
        let (ni, nj) = (2 * n_meridian + 1, 2 * n_thickness + 1);
        let mut id = vec![usize::MAX; ni * nj];
        let mut nodes = Vec::new();
        for i in 0..ni {
            let phi = if i % 2 == 0 { phi_el[i / 2] } else { 0.5 * (phi_el[i / 2] + phi_el[i / 2 + 1]) };
            for j in 0..nj {
                if i % 2 == 1 && j % 2 == 1 {
                    continue;
                }
                let rho = radius + thickness * j as f64 / (nj - 1) as f64;
                let (s, c) = phi.sin_cos();
                // Exact zeros on the axis and the base.
                let r = if i == 0 { 0.0 } else { rho * s };
                let z = if i == ni - 1 { 0.0 } else { rho * c };
                id[i * nj + j] = nodes.len();
                nodes.push([r, z]);
            }
        }
        let at = |i: usize, j: usize| id[i * nj + j];
        let mut elements = Vec::with_capacity(n_meridian * n_thickness);
        for e in 0..n_meridian {
            for t in 0..n_thickness {
                let (i0, j0) = (2 * e, 2 * t);
                // (xi, eta) = (-1,-1), (1,-1), (1,1), (-1,1), then mid-sides.
                elements.push([
                    at(i0, j0),
                    at(i0 + 2, j0),
                    at(i0 + 2, j0 + 2),
                    at(i0, j0 + 2),
                    at(i0 + 1, j0),
                    at(i0 + 2, j0 + 1),
                    at(i0 + 1, j0 + 2),
                    at(i0, j0 + 1),
                ]);
            }
        }
        let axis = (0..nj).map(|j| at(0, j)).collect();
        let base = (0..nj).map(|j| at(ni - 1, j)).collect();
        let outer = (0..ni).map(|i| at(i, nj - 1)).collect();
        ShellMesh { radius, thickness, nodes, elements, axis, base, outer }
    }

    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// The apex of the inner surface (on the axis, where an apex force acts).
    pub fn inner_apex(&self) -> usize {
        self.axis[0]
    }

    /// The mesh with an axisymmetric dimple at the apex: every node moved towards the
    /// sphere's centre by w(s) = `depth` exp(-(s / `width`)^2), s = R phi the arc length from
    /// the apex along the inner surface (the Gaussian dimple of imperfection-sensitivity
    /// studies of spherical shells). Nodes stay on the axis and on the base; a zero depth
    /// leaves the mesh as it is, bit for bit.
    pub fn with_dimple(mut self, depth: f64, width: f64) -> ShellMesh {
        if depth == 0.0 {
            return self;
        }
        assert!(width > 0.0, "dimple width must be positive");
        for x in &mut self.nodes {
            let [r, z] = *x;
            let (rho, phi) = (r.hypot(z), r.atan2(z));
            let s = self.radius * phi / width;
            let scale = (rho - depth * (-s * s).exp()) / rho;
            *x = [r * scale, z * scale];
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn the_declared_mesh_error_grows_with_friction_as_measured() {
        // 0.5 % up to mu = 0.5 (the bench), 1.3 % from mu = 1 (240 against 480 elements).
        let e = default_mesh_rel_error;
        assert_eq!((e(0.0), e(0.5)), (0.005, 0.005));
        for (mu, want) in [(0.75, 0.009), (1.0, 0.013), (1.5, 0.013)] {
            assert!((e(mu) - want).abs() < 1e-12, "mu {mu}: {}", e(mu));
        }
    }

    #[test]
    fn the_default_meridian_resolves_g0_up_to_the_snap_rim() {
        // The outer elements up to phi = 33 deg (r ~ 0.55 R, where the contact rim is at the
        // snap) are at most g0 long, for any R, h and g0 (the rule scales with (R + h) / g0),
        // and a fifth fewer elements would not resolve it.
        let longest = |radius: f64, h: f64, n: usize| {
            let a = graded_angles(n, 3.0);
            a.windows(2).filter(|w| w[0] < 33f64.to_radians()).map(|w| (radius + h) * (w[1] - w[0])).fold(0.0, f64::max)
        };
        for radius in [10.0, 15.0, 25.0, 40.0] {
            for h_over_r in [0.02, 0.06, 0.2] {
                for g0 in [0.05, 0.1, 0.2] {
                    let h = h_over_r * radius;
                    let n = meridian_elements(radius, h, g0);
                    assert!(longest(radius, h, n) <= 1.005 * g0, "{radius} {h} {g0}: {n}");
                    assert!(longest(radius, h, n * 4 / 5) > g0, "{radius} {h} {g0}: {n}");
                }
            }
        }
        assert_eq!(meridian_elements(15.0, 1.0, 0.1), 240);
    }

    #[test]
    fn a_dimple_moves_the_apex_inwards_by_its_depth_and_keeps_the_supports() {
        let m = ShellMesh::hemisphere(15.0, 1.0, 40, 2, 3.0);
        assert_eq!(m.clone().with_dimple(0.0, 2.0).nodes, m.nodes);
        let d = m.clone().with_dimple(0.01, 2.0);
        assert!((d.nodes[d.outer[0]][1] - (16.0 - 0.01)).abs() < 1e-13);
        assert!((d.nodes[d.inner_apex()][1] - (15.0 - 0.01)).abs() < 1e-13);
        assert!(d.axis.iter().all(|&a| d.nodes[a][0] == 0.0) && d.base.iter().all(|&a| d.nodes[a][1] == 0.0));
        // One width along the meridian the depth has fallen by 1/e (arc length R phi).
        let (i, phi) = m
            .outer
            .iter()
            .map(|&a| (a, m.nodes[a][0].atan2(m.nodes[a][1])))
            .min_by(|x, y| (15.0 * x.1 - 2.0).abs().total_cmp(&(15.0 * y.1 - 2.0).abs()))
            .unwrap();
        let moved = m.nodes[i][0].hypot(m.nodes[i][1]) - d.nodes[i][0].hypot(d.nodes[i][1]);
        let want = 0.01 * (-(15.0 * phi / 2.0f64).powi(2)).exp();
        assert!((moved - want).abs() < 1e-12 * 0.01, "{moved} vs {want} at {phi}");
    }

    #[test]
    fn grading_and_counts() {
        let a = graded_angles(10, 4.0);
        assert_eq!(a.len(), 11);
        let first = a[1] - a[0];
        let last = a[10] - a[9];
        assert!((last / first - 4.0).abs() < 1e-12 && (a[10] - PI / 2.0).abs() < 1e-15);
        let m = ShellMesh::hemisphere(15.0, 1.0, 10, 4, 4.0);
        // Serendipity: (2m+1)(2t+1) - m t nodes.
        assert_eq!(m.n_nodes(), 21 * 9 - 40);
        assert_eq!(m.elements.len(), 40);
        assert_eq!(m.axis.len(), 9);
        assert_eq!(m.outer.len(), 21);
        // Every node is used by an element.
        let mut used = vec![false; m.n_nodes()];
        m.elements.iter().flatten().for_each(|&n| used[n] = true);
        assert!(used.iter().all(|&u| u));
        // Apex of the outer surface and the base.
        assert_eq!(m.nodes[m.outer[0]], [0.0, 16.0]);
        assert!(m.base.iter().all(|&n| m.nodes[n][1] == 0.0));
    }
}
