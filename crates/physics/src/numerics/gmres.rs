//! GMRES (without restarts) with right preconditioning (Saad, Iterative Methods, Alg. 9.5):
//! solves A x = b for an operator given as a closure, with a preconditioner M^-1.

/// The result of a GMRES solve.
pub struct Gmres {
    pub x: Vec<f64>,
    /// The final residual norm |b - A x| (as tracked by the Givens rotations).
    pub residual: f64,
    pub iterations: usize,
    pub converged: bool,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Solves A x = b from x = 0, stopping when |b - A x| <= tol or after `max_iter` steps.
pub fn gmres(
    apply: impl Fn(&[f64]) -> Vec<f64>,
    precondition: impl Fn(&[f64]) -> Vec<f64>,
    b: &[f64],
    tol: f64,
    max_iter: usize,
) -> Gmres {
    let n = b.len();
    let beta = norm(b);
    if beta <= tol {
        return Gmres { x: vec![0.0; n], residual: beta, iterations: 0, converged: true };
    }
    let mut basis: Vec<Vec<f64>> = vec![b.iter().map(|v| v / beta).collect()];
    let mut h: Vec<Vec<f64>> = Vec::new(); // columns of the Hessenberg matrix
    let (mut cs, mut sn): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let mut g = vec![beta];
    let mut residual = beta;
    let mut k = 0;
    while k < max_iter && residual > tol {
        let z = precondition(&basis[k]);
        let mut w = apply(&z);
        let mut col = vec![0.0; k + 2];
        for (i, v) in basis.iter().enumerate() {
            col[i] = dot(&w, v);
            for (wj, vj) in w.iter_mut().zip(v) {
                *wj -= col[i] * vj;
            }
        }
        col[k + 1] = norm(&w);
        // Apply the previous rotations, then a new one to zero col[k + 1].
        for i in 0..k {
            let t = cs[i] * col[i] + sn[i] * col[i + 1];
            col[i + 1] = -sn[i] * col[i] + cs[i] * col[i + 1];
            col[i] = t;
        }
        let r = col[k].hypot(col[k + 1]);
        let (c, s) = if r == 0.0 { (1.0, 0.0) } else { (col[k] / r, col[k + 1] / r) };
        col[k] = r;
        col[k + 1] = 0.0;
        cs.push(c);
        sn.push(s);
        g.push(-s * g[k]);
        g[k] *= c;
        residual = g[k + 1].abs();
        let next_norm = norm(&w);
        h.push(col);
        k += 1;
        if next_norm == 0.0 {
            break;
        }
        basis.push(w.iter().map(|v| v / next_norm).collect());
    }
    // Back substitution for y, then x = M^-1 V y.
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let mut s = g[i];
        for j in i + 1..k {
            s -= h[j][i] * y[j];
        }
        y[i] = s / h[i][i];
    }
    let mut vy = vec![0.0; n];
    for (j, yj) in y.iter().enumerate() {
        for (a, v) in vy.iter_mut().zip(&basis[j]) {
            *a += yj * v;
        }
    }
    let x = precondition(&vy);
    Gmres { x, residual, iterations: k, converged: residual <= tol }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nonsymmetric_system_with_and_without_preconditioning() {
        let n = 50;
        let a = |i: usize, j: usize| {
            if i == j {
                4.0 + i as f64 * 0.1
            } else {
                1.0 / (1.0 + (i as f64 - 2.0 * j as f64).abs())
            }
        };
        let apply = |x: &[f64]| (0..n).map(|i| (0..n).map(|j| a(i, j) * x[j]).sum()).collect::<Vec<f64>>();
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let plain = gmres(apply, |v: &[f64]| v.to_vec(), &b, 1e-12, 200);
        assert!(plain.converged);
        let r: Vec<f64> = apply(&plain.x).iter().zip(&b).map(|(ax, bi)| ax - bi).collect();
        assert!(norm(&r) < 1e-11, "{}", norm(&r));
        // Jacobi preconditioning: same answer in fewer iterations.
        let jacobi = gmres(apply, |v: &[f64]| (0..n).map(|i| v[i] / a(i, i)).collect(), &b, 1e-12, 200);
        assert!(jacobi.converged && jacobi.iterations <= plain.iterations);
        let diff: f64 = jacobi.x.iter().zip(&plain.x).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        assert!(diff < 1e-10, "{diff}");
    }
}
