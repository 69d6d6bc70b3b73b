//! Products with a (rectangular) Toeplitz matrix in O(N log N) by circulant embedding
//! and the FFT: y_i = sum_j c[i - j + n_in - 1] x_j, i < n_out, j < n_in, where c holds
//! the n_out + n_in - 1 diagonals. The circulant of size M >= n_out + n_in - 1 reproduces
//! the linear convolution on the rows that are needed.
//!
//! The data are real: real-to-complex transforms (`realfft`, a complex FFT of half the
//! length), and M the smallest even 2^a 3^b, not the next power of two (n = 2810 elements:
//! 5832 instead of 8192): about a third fewer instructions than the complex transform of
//! the next power of two where the products dominate (docs/tuning.md).

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::sync::Arc;

#[derive(Clone)]
pub struct Toeplitz {
    n_in: usize,
    n_out: usize,
    /// The real FFT of the diagonals (M/2 + 1 values), divided by M (the unnormalised
    /// inverse transform's factor).
    spectrum: Vec<Complex<f64>>,
    forward: Arc<dyn RealToComplex<f64>>,
    inverse: Arc<dyn ComplexToReal<f64>>,
}

/// The smallest even 2^a 3^b (a >= 1) at least `min`: a length rustfft transforms fast.
pub fn fft_len(min: usize) -> usize {
    let mut best = min.max(2).next_power_of_two();
    let mut three = 1;
    while three < best {
        // The smallest 2^a >= min / three (a >= 1) times three.
        let two = min.div_ceil(three).max(2).next_power_of_two();
        best = best.min(two * three);
        three *= 3;
    }
    best
}

impl Toeplitz {
    /// From the diagonals c (length n_out + n_in - 1), c[n_in - 1] being the main one.
    pub fn new(c: &[f64], n_in: usize, n_out: usize) -> Toeplitz {
        assert_eq!(c.len(), n_out + n_in - 1, "a Toeplitz matrix needs n_out + n_in - 1 diagonals");
        let m = fft_len(c.len());
        let mut planner = RealFftPlanner::<f64>::new();
        let forward = planner.plan_fft_forward(m);
        let inverse = planner.plan_fft_inverse(m);
        let mut padded: Vec<f64> = c.iter().map(|&v| v / m as f64).collect();
        padded.resize(m, 0.0);
        let mut spectrum = forward.make_output_vec();
        forward.process(&mut padded, &mut spectrum).expect("lengths from the plan");
        Toeplitz { n_in, n_out, spectrum, forward, inverse }
    }

    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.n_in);
        let m = self.forward.len();
        let mut signal = Vec::with_capacity(m);
        signal.extend_from_slice(x);
        signal.resize(m, 0.0);
        let mut buf = self.forward.make_output_vec();
        self.forward.process(&mut signal, &mut buf).expect("lengths from the plan");
        for (b, s) in buf.iter_mut().zip(&self.spectrum) {
            *b *= s;
        }
        // The zero and Nyquist frequencies of a real signal's spectrum are real.
        let last = buf.len() - 1;
        buf[0].im = 0.0;
        buf[last].im = 0.0;
        self.inverse.process(&mut buf, &mut signal).expect("lengths from the plan, real end values");
        signal.truncate(self.n_in - 1 + self.n_out);
        signal.drain(..self.n_in - 1);
        signal
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
        for (n_in, n_out) in [(1, 1), (7, 7), (100, 101), (64, 30), (257, 257), (2810, 2810), (1000, 1001)] {
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

    /// Even and of the form 2^a 3^b.
    fn even_smooth(k: usize) -> bool {
        let mut r = k;
        while r > 0 && r.is_multiple_of(2) {
            r /= 2;
        }
        while r > 0 && r.is_multiple_of(3) {
            r /= 3;
        }
        k.is_multiple_of(2) && r == 1
    }

    #[test]
    fn the_transform_lengths_are_the_smallest_even_smooth_numbers() {
        assert_eq!(fft_len(1), 2);
        assert_eq!(fft_len(5619), 5832); // 2^3 3^6
        assert_eq!(fft_len(15999), 16384);
        assert_eq!(fft_len(97), 108); // 2^2 3^3
        for min in 1..3000 {
            let m = fft_len(min);
            assert!(m >= min && even_smooth(m), "{min} -> {m}");
            assert!(!(min.max(2)..m).any(even_smooth), "{min} -> {m}: a smaller one fits");
        }
    }
}
