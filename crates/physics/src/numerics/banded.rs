//! Direct solvers for band matrices: LU with partial pivoting (as LAPACK's dgbtrf) and
//! Cholesky, on a dense band stored row by row.
//!
//! Why not a sparse solver: the shell's tangent (`fem::system`) is a band of half-width 21
//! on ~3700 dofs (a meridian strip of quadratic elements, numbered along the meridian). A
//! band factorisation costs n kl (kl + ku) multiply-adds in contiguous loops, without the
//! graph searches of a general sparse LU (`benches/micro.rs`, `fem_band_factorisation`;
//! the comparison with faer's simplicial sparse LU in docs/tuning.md).
//!
//! Both factorisations skip the exact zeros past each row's last nonzero (a profile, or
//! skyline, within the band: `Band::lu`), and the LU keeps its multipliers column by column
//! for the forward substitution; the results are the whole-window algorithm's bit for bit
//! (tested), with fewer instructions (docs/tuning.md).
//!
//! One file: both factorisations share the band storage and its profile; two fifths of it
//! are their tests.

// Index loops over rows and columns read like the factorisations they implement.
#![allow(clippy::needless_range_loop)]

use super::vectorized_fn;

/// A band matrix: row i holds columns i - kl ..= i + kl + ku (the extra kl columns on the
/// right take the fill of the row interchanges of the LU).
#[derive(Clone, Debug)]
pub struct Band {
    n: usize,
    kl: usize,
    ku: usize,
    width: usize,
    values: Vec<f64>,
    /// Per row, a column past which the row is zero (at least its last nonzero; at least
    /// the diagonal), kept by `set`.
    end: Vec<usize>,
}

impl Band {
    /// A zero n x n matrix with `kl` sub- and `ku` super-diagonals.
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Band {
        let width = 2 * kl + ku + 1;
        Band { n, kl, ku, width, values: vec![0.0; n * width], end: (0..n).collect() }
    }

    /// A band matrix written row by row: `row(i, w)` sets row i's entries of columns
    /// i - kl ..= i + ku as w[j + kl - i] (w zeroed; columns outside 0..n must stay zero).
    /// Each row is written once, in order: filling a zeroed band column by column instead
    /// touched a cache line per entry (9 % of a frictional shell point, perf).
    pub fn from_rows(n: usize, kl: usize, ku: usize, mut row: impl FnMut(usize, &mut [f64])) -> Band {
        let width = 2 * kl + ku + 1;
        // Each row cleared just before it is written (one pass over the band, not a clear of
        // the whole band and then a second pass).
        let mut values = Vec::with_capacity(n * width);
        let mut end = Vec::with_capacity(n);
        for i in 0..n {
            values.resize((i + 1) * width, 0.0);
            let w = &mut values[i * width..i * width + kl + ku + 1];
            row(i, w);
            end.push((kl..w.len()).rev().find(|&c| w[c] != 0.0).map_or(i, |c| i + c - kl));
        }
        Band { n, kl, ku, width, values, end }
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// The storage index of entry (i, j), which must lie in row i's window (the callers
    /// keep to it; always inlined: in the dev profile `make figures` runs, a call per entry
    /// was 10 % of a shell loading).
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.width + j + self.kl - i
    }

    /// Sets entry (i, j), which must lie in the band (|i - j| within kl below, ku above).
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, v: f64) {
        assert!(i < self.n && j < self.n && j + self.kl >= i && j <= i + self.ku, "({i}, {j}) outside the band");
        let k = self.at(i, j);
        self.values[k] = v;
        if v != 0.0 && j > self.end[i] {
            self.end[i] = j;
        }
    }

    pub fn get(&self, i: usize, j: usize) -> f64 {
        if j + self.kl < i || j > i + self.ku {
            0.0
        } else {
            self.values[self.at(i, j)]
        }
    }

    /// Row i's window from column `from` to `to` (inclusive).
    #[inline]
    fn row(&self, i: usize, from: usize, to: usize) -> &[f64] {
        &self.values[self.at(i, from)..=self.at(i, to)]
    }

    /// LU factorisation with partial pivoting, or None if a pivot column is zero (the
    /// matrix is singular) or not finite.
    ///
    /// Each row's updates stop at its last entry that can be nonzero (`end`): past it
    /// the pivot row holds exact zeros, whose updates a -= l 0 change nothing. A shell
    /// tangent rarely needs an interchange, so most rows end near column i + ku, and half
    /// of the window (the kl columns of fill room) is never touched. The result is the
    /// full-window factorisation's, bitwise (up to the sign of zeros).
    pub fn lu(self) -> Option<BandLu> {
        lu_of(self)
    }

    #[inline(always)]
    fn lu_kernel(mut self) -> Option<BandLu> {
        let (n, kl) = (self.n, self.kl);
        let mut pivots = vec![0; n];
        // Written in order, column by column (each column's kl entries, zeros past the last
        // row): filled by pushes, not cleared first.
        let mut lower = Vec::with_capacity(n * kl);
        let mut end = std::mem::take(&mut self.end);
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            // The first row of largest magnitude, the running maximum kept in a register
            // (not read back from the band at every comparison).
            let (mut p, mut largest) = (k, self.values[self.at(k, k)].abs());
            for i in k + 1..=last_row {
                let v = self.values[self.at(i, k)].abs();
                if v > largest {
                    (p, largest) = (i, v);
                }
            }
            let pivot = self.values[self.at(p, k)];
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            pivots[k] = p;
            if p != k {
                // Both rows are zero left of column k.
                for j in k..=end[k].max(end[p]) {
                    let (a, b) = (self.at(k, j), self.at(p, j));
                    self.values.swap(a, b);
                }
                end.swap(k, p);
            }
            let last_col = end[k];
            let (start, stop) = (self.at(k, k) + 1, self.at(k, last_col) + 1);
            // Multipliers by the pivot's reciprocal, as LAPACK's dgbtf2 scales its column: a
            // division per row had been a fifth of the factorisation's time (perf).
            let reciprocal = 1.0 / pivot;
            for i in k + 1..=last_row {
                // The multiplier goes to `lower` only: the band's entry (i, k) is not read
                // again.
                let l = self.values[self.at(i, k)] * reciprocal;
                lower.push(l);
                if l != 0.0 && stop > start {
                    let from = self.at(i, k + 1);
                    let (head, tail) = self.values.split_at_mut(from);
                    let pivot_row = &head[start..stop];
                    for (a, b) in tail[..stop - start].iter_mut().zip(pivot_row) {
                        *a -= l * b;
                    }
                    end[i] = end[i].max(last_col);
                }
            }
            lower.resize((k + 1) * kl, 0.0);
        }
        Some(BandLu { band: self, pivots, lower, end })
    }

    /// Cholesky factorisation U^T U from the lower band (the upper one is not read), or
    /// None if the matrix is not positive definite. Right-looking, on the rows of U, so
    /// that every update is a contiguous row operation, as in `lu`.
    pub fn cholesky(&self) -> Option<BandCholesky> {
        let (n, kl) = (self.n, self.kl);
        // Row i of U = L^T holds columns i ..= i + kl; u_ij starts as a_ji.
        let w = kl + 1;
        let mut u = vec![0.0; n * w];
        for i in 0..n {
            for j in i..=(i + kl).min(n - 1) {
                u[i * w + j - i] = self.values[self.at(j, i)];
            }
        }
        // Row i of U ends where column i of the lower band does (the upper band is not read).
        let mut end: Vec<usize> = (0..n).collect();
        for i in 0..n {
            for j in i.saturating_sub(kl)..i {
                if self.values[self.at(i, j)] != 0.0 {
                    end[j] = end[j].max(i);
                }
            }
        }
        BandCholesky::factor(n, kl, u, end)
    }
}

vectorized_fn! {
    fn lu_of(band: Band) -> Option<BandLu> = Band::lu_kernel;
}

vectorized_fn! {
    fn cholesky_of(n: usize, kl: usize, u: Vec<f64>, end: Vec<usize>) -> Option<BandCholesky> = BandCholesky::factor_kernel;
}

/// A band LU factorisation: the multipliers of column k below the diagonal (not permuted
/// by later interchanges, as in LAPACK), U on and above it, and row k swapped with
/// `pivots[k]` at step k. The multipliers are kept a second time, column by column in
/// `lower` (column k at k kl ..), so that the forward substitution reads them contiguously:
/// in the band's rows a column is strided by the row width, a cache line per entry, and
/// the substitution had cost 40 % of a factorisation (perf, a frictional shell point).
#[derive(Clone, Debug)]
pub struct BandLu {
    band: Band,
    pivots: Vec<usize>,
    lower: Vec<f64>,
    /// Per row of U, its last column that can be nonzero.
    end: Vec<usize>,
}

impl BandLu {
    /// Solves A x = b in place.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let a = &self.band;
        let (n, kl) = (a.n, a.kl);
        assert_eq!(b.len(), n);
        for k in 0..n {
            b.swap(k, self.pivots[k]);
            let bk = b[k];
            if bk != 0.0 {
                let last = (k + kl).min(n - 1);
                let column = &self.lower[k * kl..k * kl + last - k];
                for (x, l) in b[k + 1..=last].iter_mut().zip(column) {
                    *x -= l * bk;
                }
            }
        }
        for k in (0..n).rev() {
            let last = self.end[k];
            let dot: f64 = a.row(k, k, last)[1..].iter().zip(&b[k + 1..=last]).map(|(u, x)| u * x).sum();
            b[k] = (b[k] - dot) / a.values[a.at(k, k)];
        }
    }
}

/// A band Cholesky factorisation A = U^T U: row i of U holds columns i ..= i + kl.
#[derive(Clone, Debug)]
pub struct BandCholesky {
    n: usize,
    kl: usize,
    u: Vec<f64>,
    /// Per row of U, its last column that can be nonzero.
    end: Vec<usize>,
}

impl BandCholesky {
    /// Factorises A = U^T U in place, A's lower band given as the rows of U (row i holds
    /// a_ji for j = i ..= i + kl, zero past n, and past `end[i]`), or None if A is not
    /// positive definite.
    /// Right-looking, on the rows of U, so that every update is a contiguous row operation,
    /// as in `Band::lu`, and, as there, stops at the row's last entry that can be nonzero.
    pub fn factor(n: usize, kl: usize, u: Vec<f64>, end: Vec<usize>) -> Option<BandCholesky> {
        cholesky_of(n, kl, u, end)
    }

    #[inline(always)]
    fn factor_kernel(n: usize, kl: usize, mut u: Vec<f64>, mut end: Vec<usize>) -> Option<BandCholesky> {
        let w = kl + 1;
        assert_eq!(u.len(), n * w);
        assert!(end.len() == n && end.iter().enumerate().all(|(i, &e)| e >= i && e < n && e <= i + kl));
        for k in 0..n {
            let d = u[k * w];
            if !(d > 0.0) || !d.is_finite() {
                return None;
            }
            let d = d.sqrt();
            let last = end[k];
            let (head, tail) = u.split_at_mut((k + 1) * w);
            let row = &mut head[k * w..=k * w + last - k];
            row[0] = d;
            // By the reciprocal, as in the LU.
            let reciprocal = 1.0 / d;
            row[1..].iter_mut().for_each(|v| *v *= reciprocal);
            for i in k + 1..=last {
                let uki = row[i - k];
                if uki != 0.0 {
                    let target = &mut tail[(i - k - 1) * w..=(i - k - 1) * w + last - i];
                    for (a, b) in target.iter_mut().zip(&row[i - k..]) {
                        *a -= uki * b;
                    }
                    end[i] = end[i].max(last);
                }
            }
        }
        Some(BandCholesky { n, kl, u, end })
    }

    /// Solves A x = b in place.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, w) = (self.n, self.kl + 1);
        assert_eq!(b.len(), n);
        for k in 0..n {
            let last = self.end[k];
            let row = &self.u[k * w..=k * w + last - k];
            b[k] /= row[0];
            let bk = b[k];
            for (x, u) in b[k + 1..=last].iter_mut().zip(&row[1..]) {
                *x -= u * bk;
            }
        }
        for k in (0..n).rev() {
            let last = self.end[k];
            let row = &self.u[k * w..=k * w + last - k];
            let dot: f64 = row[1..].iter().zip(&b[k + 1..=last]).map(|(u, x)| u * x).sum();
            b[k] = (b[k] - dot) / row[0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic pseudo-random band matrix (LCG), and the same as a dense one.
    fn random_band(n: usize, kl: usize, ku: usize, seed: u64, diagonal: f64) -> (Band, Vec<Vec<f64>>) {
        let mut s = seed;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut band = Band::zeros(n, kl, ku);
        let mut dense = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = next() + if i == j { diagonal } else { 0.0 };
                band.set(i, j, v);
                dense[i][j] = v;
            }
        }
        (band, dense)
    }

    /// The backward error max |A x - b| / (|A| |x| + |b|) (max norms): rounding-sized for
    /// a stable solver however ill-conditioned A is (a random triangular band is very).
    fn residual(dense: &[Vec<f64>], x: &[f64], b: &[f64]) -> f64 {
        let max = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0, f64::max);
        let r = max(&mut dense
            .iter()
            .zip(b)
            .map(|(row, bi)| (row.iter().zip(x).map(|(a, x)| a * x).sum::<f64>() - bi).abs()));
        let a = max(&mut dense.iter().map(|row| row.iter().map(|v| v.abs()).sum::<f64>()));
        r / (a * max(&mut x.iter().map(|v| v.abs())) + max(&mut b.iter().map(|v| v.abs())))
    }

    #[test]
    fn the_band_lu_solves_unsymmetric_systems_that_need_pivoting() {
        // No diagonal dominance (diagonal ~ U(-0.5, 0.5)): row interchanges happen.
        for (n, kl, ku, seed) in
            [(1, 0, 0, 1), (7, 2, 1, 2), (60, 5, 3, 3), (200, 13, 13, 4), (50, 0, 4, 5), (50, 4, 0, 6)]
        {
            let (band, dense) = random_band(n, kl, ku, seed, 0.0);
            let b: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.37).sin()).collect();
            let mut x = b.clone();
            band.lu().expect("nonsingular").solve_in_place(&mut x);
            let r = residual(&dense, &x, &b);
            assert!(r < 1e-13, "n {n} kl {kl} ku {ku}: backward error {r}");
        }
        // Interchanges did happen: the first column's largest entry is below the diagonal.
        let (band, _) = random_band(60, 5, 3, 3, 0.0);
        assert!(band.lu().unwrap().pivots.iter().enumerate().any(|(k, &p)| p != k));
    }

    /// A band whose rows end at random columns short of the band (a profile), with zeros
    /// inside the band on the left too, and no diagonal dominance (interchanges happen).
    fn random_profile(n: usize, kl: usize, ku: usize, seed: u64) -> (Band, Vec<Vec<f64>>) {
        let (full, _) = random_band(n, kl, ku, seed, 0.0);
        let mut band = Band::zeros(n, kl, ku);
        let mut dense = vec![vec![0.0; n]; n];
        for i in 0..n {
            let reach = (i * 7 + seed as usize) % (ku + 1);
            for j in i.saturating_sub(kl)..=(i + reach).min(n - 1) {
                let v = full.get(i, j);
                if (i + 3 * j) % 5 != 0 || i == j {
                    band.set(i, j, v);
                    dense[i][j] = v;
                }
            }
        }
        (band, dense)
    }

    /// The textbook band LU with partial pivoting (LAPACK's dgbtf2) over the whole window,
    /// multipliers stored in the band, and its solve: the reference of
    /// `skipping_the_zeros_past_each_rows_end_changes_no_bit`.
    fn whole_window_lu_solve(mut a: Band, b: &[f64]) -> Vec<f64> {
        let (n, kl, ku) = (a.n, a.kl, a.ku);
        let mut pivots = vec![0; n];
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + kl + ku).min(n - 1);
            let p = (k..=last_row).fold(k, |p, i| if a.get(i, k).abs() > a.get(p, k).abs() { i } else { p });
            pivots[k] = p;
            for j in k..=last_col {
                let (x, y) = (a.at(k, j), a.at(p, j));
                a.values.swap(x, y);
            }
            let reciprocal = 1.0 / a.get(k, k);
            for i in k + 1..=last_row {
                let l = a.get(i, k) * reciprocal;
                let ik = a.at(i, k);
                a.values[ik] = l;
                for j in k + 1..=last_col {
                    let (ij, kj) = (a.at(i, j), a.at(k, j));
                    a.values[ij] -= l * a.values[kj];
                }
            }
        }
        let mut x = b.to_vec();
        for k in 0..n {
            x.swap(k, pivots[k]);
            for i in k + 1..=(k + kl).min(n - 1) {
                x[i] -= a.get(i, k) * x[k];
            }
        }
        for k in (0..n).rev() {
            // U's row reaches into the fill room, past `get`'s band.
            let dot: f64 = (k + 1..=(k + kl + ku).min(n - 1)).map(|j| a.values[a.at(k, j)] * x[j]).sum();
            x[k] = (x[k] - dot) / a.get(k, k);
        }
        x
    }

    #[test]
    fn skipping_the_zeros_past_each_rows_end_changes_no_bit() {
        // The factorisations that stop at each row's end against the same ones over the whole
        // window (the textbook LU; the Cholesky with every row's end at the window's last
        // column): the same solutions, bit for bit, and a rounding-sized backward error.
        for (n, kl, ku, seed) in [(60, 5, 3, 11), (200, 13, 13, 12), (300, 21, 21, 13), (40, 4, 2, 14)] {
            let (band, dense) = random_profile(n, kl, ku, seed);
            assert!(band.end.iter().enumerate().any(|(i, &e)| e < (i + ku).min(n - 1)));
            let b: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.37).sin()).collect();
            let mut x = b.clone();
            let lu = band.clone().lu().expect("nonsingular");
            assert!(lu.pivots.iter().enumerate().any(|(k, &p)| p != k));
            lu.solve_in_place(&mut x);
            let y = whole_window_lu_solve(band.clone(), &b);
            assert!(x.iter().zip(&y).all(|(a, b)| a.to_bits() == b.to_bits()), "n {n}: LU differs");
            let r = residual(&dense, &x, &b);
            assert!(r < 1e-13, "n {n} kl {kl} ku {ku}: backward error {r}");
            // Cholesky of a symmetric definite matrix with the same profile (its lower band).
            let mut sym = Band::zeros(n, kl, kl);
            for i in 0..n {
                for j in i.saturating_sub(kl)..i {
                    let v = dense[i][j].abs().max(dense.get(j).map_or(0.0, |r| r[i].abs()));
                    if v != 0.0 {
                        sym.set(i, j, v);
                        sym.set(j, i, v);
                    }
                }
                sym.set(i, i, 2.0 * kl as f64 + 1.0);
            }
            let (mut x, mut y) = (b.clone(), b.clone());
            sym.cholesky().unwrap().solve_in_place(&mut x);
            let mut window = sym.cholesky().unwrap();
            window.end = (0..n).map(|i| (i + kl).min(n - 1)).collect();
            // Refactor over the whole window from the same lower band.
            let w = kl + 1;
            let mut u = vec![0.0; n * w];
            for i in 0..n {
                for j in i..=(i + kl).min(n - 1) {
                    u[i * w + j - i] = sym.get(j, i);
                }
            }
            BandCholesky::factor(n, kl, u, window.end.clone()).unwrap().solve_in_place(&mut y);
            assert!(x.iter().zip(&y).all(|(a, b)| a.to_bits() == b.to_bits()), "n {n}: Cholesky differs");
        }
    }

    #[test]
    fn a_band_written_row_by_row_is_the_band_set_entry_by_entry() {
        let (n, kl, ku) = (50, 6, 4);
        let (band, _) = random_profile(n, kl, ku, 21);
        let rows = Band::from_rows(n, kl, ku, |i, w| {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                w[j + kl - i] = band.get(i, j);
            }
        });
        assert_eq!(rows.values.len(), band.values.len());
        assert!(rows.values.iter().zip(&band.values).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert_eq!(rows.end, band.end);
    }

    #[test]
    fn a_singular_band_has_no_lu() {
        let mut band = Band::zeros(3, 1, 1);
        band.set(0, 0, 1.0);
        band.set(1, 0, 2.0);
        band.set(2, 2, 1.0);
        // Column 1 is zero.
        assert!(band.lu().is_none());
    }

    #[test]
    fn the_band_cholesky_solves_definite_systems_and_refuses_indefinite_ones() {
        for (n, kl, seed) in [(1, 0, 7), (40, 3, 8), (300, 26, 9)] {
            // A^T A-like: symmetric with a dominant diagonal.
            let (mut band, _) = random_band(n, kl, kl, seed, 0.0);
            for i in 0..n {
                for j in i.saturating_sub(kl)..i {
                    let v = band.get(i, j);
                    band.set(j, i, v);
                }
                band.set(i, i, 2.0 * kl as f64 + 1.0);
            }
            let dense: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| band.get(i, j)).collect()).collect();
            let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
            let mut x = b.clone();
            band.cholesky().expect("definite").solve_in_place(&mut x);
            let r = residual(&dense, &x, &b);
            assert!(r < 1e-14, "n {n} kl {kl}: backward error {r}");
            // The LU of the same matrix agrees.
            let mut y = b.clone();
            band.clone().lu().unwrap().solve_in_place(&mut y);
            assert!(x.iter().zip(&y).all(|(a, b)| (a - b).abs() < 1e-10 * (1.0 + a.abs())));
        }
        // [[1, 2], [2, 1]] has eigenvalues 3 and -1.
        let mut band = Band::zeros(2, 1, 1);
        for (i, j, v) in [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)] {
            band.set(i, j, v);
        }
        assert!(band.cholesky().is_none());
        assert!(band.lu().is_some());
    }
}
