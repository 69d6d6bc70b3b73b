//! Micro-benchmarks (divan): BEM kernel assembly (the Toeplitz influence coefficients of an
//! SLS, Eq. 4.12), one BEM solve at a fixed mesh, one FEM Newton step (tangent and residual
//! assembly with contact, then the band solve), the band factorisations of a shell-sized
//! tangent and the cache's hashing (task key, entry verification). Run: `cargo bench --bench micro` (`make bench` runs it).

use repro::bem::solver::{solve, Mesh, Params};
use repro::fem::contact::Plate;
use repro::fem::indent::{apex_z, solve_at, Options};
use repro::fem::mesh::ShellMesh;
use repro::fem::system::{Base, Model};
use repro::pipeline::cache::{decode_entry, Entry};
use repro::pipeline::key::{content_hash, task_key};
use repro::pipeline::kind::Output;
use repro::pipeline::table::Table;
use repro::rheology::Spectrum;
use std::collections::BTreeMap;

fn main() {
    divan::main();
}

#[divan::bench(args = [400, 1600, 6400])]
fn bem_kernel_assembly(bencher: divan::Bencher, n: usize) {
    let spectrum = Spectrum::sls();
    bencher.bench(|| repro::bem::kernel::toeplitz_coefficients(divan::black_box(n), 0.01, 1.0, 0.1, &spectrum));
}

#[divan::bench(args = [401, 1201])]
fn bem_solve(bencher: divan::Bencher, n: usize) {
    let params = Params::sls(1.0, 1.0, 0.1, 1.0);
    bencher.bench(|| {
        let s = solve(&params, Mesh { n, half_length: 4.0 });
        assert!(s.converged());
        s.friction().mu_star
    });
}

/// One Newton iteration of the shell pressed to delta/R = 0.1 (100 x 4 mesh: a fixed size
/// for comparisons over time).
#[divan::bench(sample_count = 20)]
fn fem_newton_step(bencher: divan::Bencher) {
    let (e, r, h) = (1.3, 15.0, 1.0);
    let model = Model::new(ShellMesh::hemisphere(r, h, 100, 4, 3.0), e, 0.45, Base::Clamped);
    let plate = Plate::new(&model.mesh, e, 1000.0);
    let delta = 0.1 * r;
    let step = solve_at(&model, &plate, e, delta, &vec![0.0; model.n_dofs()], &[], Options::default());
    assert!(step.converged());
    bencher.bench(|| {
        let (fint, mut trip) = model.assemble(&step.u).unwrap();
        let mut fext = vec![0.0; model.n_dofs()];
        let mut q = vec![0.0; model.n_dofs()];
        plate.apply(
            &model.mesh,
            &step.u,
            apex_z(&model) - delta,
            &step.contact.stick,
            &mut fext,
            &mut trip,
            &mut q,
            repro::fem::adhesion::Tangent::Exact,
        );
        let rhs: Vec<f64> = fint.iter().zip(&fext).map(|(a, b)| b - a).collect();
        model.solve(&trip, &rhs).unwrap()
    });
}

/// LU (partial pivoting) and Cholesky of a band of the shell tangent's shape: 3690 dofs,
/// half-width 21 (the 230 x 2 default mesh numbered along the meridian).
#[divan::bench(args = ["lu", "cholesky"])]
fn fem_band_factorisation(bencher: divan::Bencher, which: &str) {
    let (n, half) = (3690, 21);
    let mut band = repro::numerics::banded::Band::zeros(n, half, half);
    for i in 0..n {
        for j in i.saturating_sub(half)..=(i + half).min(n - 1) {
            let v = if i == j { 4.0 * half as f64 } else { -1.0 / (1.0 + i.abs_diff(j) as f64) };
            band.set(i, j, v);
        }
    }
    bencher.bench(|| match which {
        "lu" => band.clone().lu().is_some(),
        _ => band.cholesky().is_some(),
    });
}

#[divan::bench]
fn cache_task_key(bencher: divan::Bencher) {
    let params = serde_json::json!({"lambda": 1.0, "W": 1.0, "k": 0.1, "V0": 0.3, "rel_tol": 1e-3, "model": {"R": 15.0, "E": 1.3}});
    let inputs: BTreeMap<String, String> = BTreeMap::from([("sweep".to_string(), content_hash(b"upstream"))]);
    bencher.bench(|| task_key("bem.sweep", 4, divan::black_box(&params), &inputs));
}

/// Reading back a typical entry: header, blake3 of the body, JSON, output hash.
#[divan::bench]
fn cache_entry_verify(bencher: divan::Bencher) {
    let table = Table::new().with_f64("mu_star", vec![1.5; 20]).with_f64("V0", (0..20).map(f64::from).collect());
    let key = content_hash(b"task");
    let entry = Entry::new(key.clone(), "bem.sweep", 4, serde_json::json!({"lambda": 1.0}), Output::from(table), 0.1);
    let body = serde_json::to_vec(&entry).unwrap();
    let mut bytes = format!("repro-entry-1 {}\n", content_hash(&body)).into_bytes();
    bytes.extend_from_slice(&body);
    bencher.bench(|| decode_entry(&key, divan::black_box(&bytes)).unwrap());
}
