//! Products with a (rectangular) Toeplitz matrix in O(N log N) by circulant embedding
//! and the FFT: y_i = sum_j c[i - j + n_in - 1] x_j, i < n_out, j < n_in, where c holds
//! the n_out + n_in - 1 diagonals. The circulant of size M >= n_out + n_in - 1 (a power
//! of two) reproduces the linear convolution on the rows that are needed.

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

#[derive(Clone)]
pub struct Toeplitz {
    n_in: usize,
    n_out: usize,
    /// FFT of the diagonals, divided by M (the unnormalised inverse transform's factor).
    spectrum: Vec<Complex<f64>>,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
}

impl Toeplitz {
    /// From the diagonals c (length n_out + n_in - 1), c[n_in - 1] being the main one.
    pub fn new(c: &[f64], n_in: usize, n_out: usize) -> Toeplitz {
        assert_eq!(c.len(), n_out + n_in - 1, "a Toeplitz matrix needs n_out + n_in - 1 diagonals");
        let m = c.len().next_power_of_two();
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(m);
        let inverse = planner.plan_fft_inverse(m);
        let mut spectrum: Vec<Complex<f64>> = c.iter().map(|&v| Complex::new(v / m as f64, 0.0)).collect();
        spectrum.resize(m, Complex::new(0.0, 0.0));
        forward.process(&mut spectrum);
        Toeplitz { n_in, n_out, spectrum, forward, inverse }
    }

    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.n_in);
        let m = self.spectrum.len();
        let mut buf: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
        buf.resize(m, Complex::new(0.0, 0.0));
        self.forward.process(&mut buf);
        for (b, s) in buf.iter_mut().zip(&self.spectrum) {
            *b *= s;
        }
        self.inverse.process(&mut buf);
        buf[self.n_in - 1..self.n_in - 1 + self.n_out].iter().map(|c| c.re).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direct(c: &[f64], x: &[f64], n_out: usize) -> Vec<f64> {
        let n_in = x.len();
        (0..n_out).map(|i| (0..n_in).map(|j| c[i + n_in - 1 - j] * x[j]).sum()).collect()
    }

    #[test]
    fn matches_the_direct_product_for_square_and_rectangular_matrices() {
        for (n_in, n_out) in [(1, 1), (7, 7), (100, 101), (64, 30), (257, 257)] {
            let c: Vec<f64> = (0..n_in + n_out - 1).map(|i| ((i * 37 % 11) as f64 - 5.0) / (1.0 + i as f64)).collect();
            let x: Vec<f64> = (0..n_in).map(|j| (j as f64 * 0.3).cos()).collect();
            let fast = Toeplitz::new(&c, n_in, n_out).apply(&x);
            let slow = direct(&c, &x, n_out);
            let scale = slow.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            for (a, b) in fast.iter().zip(&slow) {
                assert!((a - b).abs() < 1e-12 * scale, "{n_in}x{n_out}: {a} vs {b}");
            }
        }
    }
}
