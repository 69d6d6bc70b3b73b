use repro::bem::solver::*;
fn main() {
    let a: Vec<f64> = std::env::args().skip(1).map(|s| s.parse().unwrap()).collect();
    let params = Params { lambda: a[0], w: a[1], k: a[2], v0: a[3] };
    let mesh = if a.len() > 5 { Mesh { n: a[4] as usize, half_length: a[5] } } else { default_mesh(&params) };
    let t = std::time::Instant::now();
    let s = solve(&params, mesh);
    let f = s.friction();
    println!(
        "{:?} n={} L={:.2} conv {} res {:.1e} it {} load {:.6} mu* {:.5} adh {:.5} comp {:.5} persson {:.5} t {:.2}s",
        params,
        mesh.n,
        mesh.half_length,
        s.converged,
        s.residual,
        s.iterations,
        s.load(),
        f.mu_star,
        f.mu_adh,
        f.mu_comp,
        repro::theory::persson::mu_star(params.k, params.v0, 1e-8).mu_star,
        t.elapsed().as_secs_f64()
    );
}
