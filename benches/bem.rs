//! Time per converged point of the Chapter 4 BEM at the thesis' resolutions (N = 401 and
//! 1201) and with the default resolution (rel_tol 1e-3: starting mesh, then doubling until
//! the Richardson estimate meets it), each with the error of mu* against a reference (the
//! Richardson extrapolation of N = 4801 and 9601 on the same domain), so that speed is
//! always quoted with accuracy. Run: `cargo bench --bench bem`.

use repro::bem::solver::{domain_half_length, solve, solve_to_tolerance, starting_mesh, Mesh, Params};
use std::time::Instant;

fn main() {
    println!(
        "{:>6} {:>5} {:>8} {:>6} {:>9} {:>12} {:>10} {:>10} {:>6} {:>4}",
        "lambda", "W", "mesh", "N", "time_s", "mu_star", "rel_error", "estimate", "newton", "lu"
    );
    for (lambda, w) in [(1.0, 1.0), (3.0, 1.0), (1.0, 0.1), (3.0, 0.1), (6.0, 0.1)] {
        let params = Params::sls(lambda, w, 0.1, 1.0);
        let half_length = domain_half_length(&params, 1e-3);
        let fine = solve(&params, Mesh { n: 9601, half_length });
        let coarse = solve(&params, Mesh { n: 4801, half_length });
        assert!(fine.converged() && coarse.converged(), "reference did not converge");
        let (mf, mc) = (fine.friction().mu_star, coarse.friction().mu_star);
        let mu_ref = mf + (mf - mc) / 3.0;
        let report = |label: &str, n: usize, dt: f64, mu: f64, est: f64, it: usize, lu: usize, ok: bool| {
            println!(
                "{lambda:>6} {w:>5} {label:>8} {n:>6} {dt:>9.3} {mu:>12.6} {:>10.2e} {:>10.2e} {it:>6} {lu:>4}{}",
                ((mu - mu_ref) / mu_ref).abs(),
                est / mu.abs(),
                if ok { "" } else { "  (not converged)" }
            )
        };
        for n in [401, 1201] {
            let t0 = Instant::now();
            let s = solve(&params, Mesh { n, half_length });
            let dt = t0.elapsed().as_secs_f64();
            report(
                "fixed",
                n,
                dt,
                s.friction().mu_star,
                f64::NAN,
                s.cost.iterations,
                s.cost.factorizations,
                s.converged(),
            );
        }
        let t0 = Instant::now();
        let (s, est) = solve_to_tolerance(&params, starting_mesh(&params, 1e-3), 1e-3, 16_000);
        let dt = t0.elapsed().as_secs_f64();
        report(
            "rel 1e-3",
            s.mesh.n,
            dt,
            s.friction().mu_star,
            est,
            s.cost.iterations,
            s.cost.factorizations,
            s.converged(),
        );
        println!(
            "{lambda:>6} {w:>5} {:>8} {:>6} {:>9} {mu_ref:>12.6}   (reference, L = {half_length:.2})",
            "richard", "", ""
        );
    }
}
