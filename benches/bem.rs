//! Time per converged point of the Chapter 4 BEM at the thesis' resolutions (N = 401 and
//! 1201), with the error of mu* against a reference at N = 2401 on the same domain, so
//! that speed is always quoted with accuracy. Run: `cargo bench --bench bem`.

use repro::bem::solver::{domain_half_length, solve, Mesh, Params};
use std::time::Instant;

fn main() {
    println!(
        "{:>6} {:>5} {:>6} {:>10} {:>12} {:>10} {:>6} {:>4}",
        "lambda", "W", "N", "time_s", "mu_star", "rel_error", "newton", "lu"
    );
    for (lambda, w) in [(1.0, 1.0), (3.0, 1.0), (1.0, 0.1)] {
        let params = Params { lambda, w, k: 0.1, v0: 1.0 };
        let half_length = domain_half_length(&params, 1e-3);
        let reference = solve(&params, Mesh { n: 2401, half_length });
        assert!(reference.converged, "reference did not converge");
        let mu_ref = reference.friction().mu_star;
        for n in [401, 1201] {
            let t0 = Instant::now();
            let s = solve(&params, Mesh { n, half_length });
            let dt = t0.elapsed().as_secs_f64();
            let mu = s.friction().mu_star;
            println!(
                "{lambda:>6} {w:>5} {n:>6} {dt:>10.3} {mu:>12.6} {:>10.2e} {:>6} {:>4}{}",
                ((mu - mu_ref) / mu_ref).abs(),
                s.iterations,
                s.factorizations,
                if s.converged { "" } else { "  (not converged)" }
            );
        }
        println!("{lambda:>6} {w:>5} {:>6} {:>10} {mu_ref:>12.6}   (reference)", 2401, "");
    }
}
