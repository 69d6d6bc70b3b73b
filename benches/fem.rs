//! Time of one full load-unload cycle of the Chapter 3 shell (R = 15, h = 1, E = 1.3,
//! nu = 0.45, clamped; to delta/R = 0.3 and back in 30 steps, unstable branch traced) on
//! meshes along the meridian and through the thickness, with F_buckling, the snap-through
//! and snap-back displacements and the loop area W, and the error of F_buckling against
//! the finest mesh. The default mesh of `fem.indent` is 100 x 4, grading 3.
//! Run: `cargo bench --bench fem`.

use repro::fem::contact::Plate;
use repro::fem::cycle::{load_unload, CycleOptions};
use repro::fem::mesh::ShellMesh;
use repro::fem::stability::{Criterion, LIFT_THRESHOLD};
use repro::fem::system::{Base, Model};
use std::time::Instant;

fn main() {
    let (e, nu, r, h): (f64, f64, f64, f64) = (1.3, 0.45, 15.0, 1.0);
    let fbar = |f: f64| f * r / (e * h.powi(3));
    let meshes =
        [(240, 6, 3.0), (60, 3, 8.0), (80, 4, 3.0), (100, 4, 3.0), (150, 4, 3.0), (100, 2, 3.0), (100, 6, 3.0)];
    println!(
        "{:>5} {:>3} {:>5} {:>6} {:>8} {:>10} {:>9} {:>9} {:>8} {:>10}",
        "n_mer", "n_t", "grad", "dofs", "time_s", "F_buckl", "d_b/R", "d_snap/R", "W_bar", "F_b error"
    );
    let mut reference = None;
    for (nm, nt, g) in meshes {
        let model = Model::new(ShellMesh::hemisphere(r, h, nm, nt, g), e, nu, Base::Clamped);
        let plate = Plate::new(&model.mesh, e, 1000.0);
        let opt = CycleOptions {
            delta_max: 0.3 * r,
            steps: 30,
            max_cuts: 8,
            bisections: 6,
            criterion: Criterion::LiftThreshold(LIFT_THRESHOLD),
            hold: Default::default(),
            trace_unstable: true,
            unload: true,
            stop_at_buckling: false,
            snap: Default::default(),
        };
        let t0 = Instant::now();
        let c = load_unload(&model, &plate, e, opt);
        let dt = t0.elapsed().as_secs_f64();
        let fb = c.buckling.map_or(f64::NAN, |b| fbar(b.force_before));
        let reference = *reference.get_or_insert(fb);
        println!(
            "{nm:>5} {nt:>3} {g:>5} {:>6} {dt:>8.2} {fb:>10.4} {:>9.5} {:>9.5} {:>8.5} {:>10.2e}{}",
            model.n_dofs(),
            c.buckling.map_or(f64::NAN, |b| b.delta / r),
            c.snap_back.map_or(f64::NAN, |b| b.delta / r),
            c.dissipated() / (e * h.powi(3)),
            (fb - reference).abs() / reference,
            if c.complete { "" } else { "  (incomplete)" }
        );
    }
}
