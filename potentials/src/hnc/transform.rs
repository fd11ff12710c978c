//! Uniform radial grid and the three-dimensional Fourier transform of radial functions,
//!
//! F(k) = (4 pi/k) int_0^inf r f(r) sin(kr) dr,  f(r) = 1/(2 pi^2 r) int_0^inf k F(k) sin(kr) dk,
//!
//! discretised on r_i = i dr, k_j = j dk with dk = pi/(n dr), i, j = 0..n-1, as a discrete
//! sine transform (DST-I): sin(k_j r_i) = sin(pi i j / n). The pair is exactly inverse for
//! i, j >= 1; the points r = 0 and k = 0 take the limits sin(kr)/k -> r, sin(kr)/r -> k. A
//! plain O(n^2) sum over a table of sin(pi m / n), m = 0..2n-1, indexed by i j mod 2n.

use std::f64::consts::PI;

/// Radial grid r_i = i dr, i = 0..n-1, with its sine-transform pair.
#[derive(Clone, Debug)]
pub struct RadialGrid {
    n: usize,
    dr: f64,
    dk: f64,
    /// sin(pi m / n) for m = 0..2n-1.
    sin: Vec<f64>,
}

impl RadialGrid {
    /// `n` points spaced `dr` (range n dr); n >= 2.
    pub fn new(n: usize, dr: f64) -> Self {
        assert!(n >= 2 && dr > 0.0, "a radial grid needs n >= 2 points and dr > 0");
        let sin = (0..2 * n).map(|m| (PI * m as f64 / n as f64).sin()).collect();
        Self { n, dr, dk: PI / (n as f64 * dr), sin }
    }

    /// Number of points n.
    pub fn points(&self) -> usize {
        self.n
    }

    pub fn dr(&self) -> f64 {
        self.dr
    }

    /// r_i = i dr.
    pub fn r(&self, i: usize) -> f64 {
        i as f64 * self.dr
    }

    /// k_j = j pi / (n dr).
    pub fn k(&self, j: usize) -> f64 {
        j as f64 * self.dk
    }

    /// sum_i a_i sin(pi i j / n) for every j, and sum_i a_i x_i at j = 0 (the limit).
    fn sine_sums(&self, a: &[f64], x: &[f64], out: &mut [f64]) {
        let two_n = 2 * self.n;
        out[0] = a.iter().zip(x).map(|(a, x)| a * x).sum();
        for (j, o) in out.iter_mut().enumerate().skip(1) {
            let (mut m, mut s) = (j, 0.0);
            for &ai in &a[1..] {
                s += ai * self.sin[m];
                m += j;
                if m >= two_n {
                    m -= two_n;
                }
            }
            *o = s;
        }
    }

    /// F(k_j) of f(r_i).
    pub fn forward(&self, f: &[f64], out: &mut [f64]) {
        assert!(f.len() == self.n && out.len() == self.n);
        let a: Vec<f64> = (0..self.n).map(|i| self.r(i) * f[i]).collect();
        let r: Vec<f64> = (0..self.n).map(|i| self.r(i)).collect();
        self.sine_sums(&a, &r, out);
        out[0] *= 4.0 * PI * self.dr;
        for (j, o) in out.iter_mut().enumerate().skip(1) {
            *o *= 4.0 * PI * self.dr / self.k(j);
        }
    }

    /// f(r_i) of F(k_j).
    pub fn inverse(&self, fk: &[f64], out: &mut [f64]) {
        assert!(fk.len() == self.n && out.len() == self.n);
        let a: Vec<f64> = (0..self.n).map(|j| self.k(j) * fk[j]).collect();
        let k: Vec<f64> = (0..self.n).map(|j| self.k(j)).collect();
        self.sine_sums(&a, &k, out);
        let c = self.dk / (2.0 * PI * PI);
        out[0] *= c;
        for (i, o) in out.iter_mut().enumerate().skip(1) {
            *o *= c / self.r(i);
        }
    }

    /// int d^3r f = 4 pi int r^2 f dr by the trapezoid rule (f -> 0 at the end of the grid).
    pub fn integrate(&self, f: &[f64]) -> f64 {
        assert_eq!(f.len(), self.n);
        let s: f64 = (1..self.n).map(|i| self.r(i).powi(2) * f[i]).sum();
        4.0 * PI * self.dr * (s - 0.5 * self.r(self.n - 1).powi(2) * f[self.n - 1])
    }

    /// A table g(r) (r increasing) on this grid by linear interpolation: the first value
    /// below the table, 1 above it (a pair distribution function).
    pub fn sample(&self, r: &[f64], g: &[f64]) -> Vec<f64> {
        assert!(r.len() == g.len() && !r.is_empty(), "one g per r");
        (0..self.n)
            .map(|i| {
                let x = self.r(i);
                let p = r.partition_point(|&ri| ri <= x);
                if p == 0 {
                    g[0]
                } else if p == r.len() {
                    if x == r[p - 1] {
                        g[p - 1]
                    } else {
                        1.0
                    }
                } else {
                    let t = (x - r[p - 1]) / (r[p] - r[p - 1]);
                    g[p - 1] + t * (g[p] - g[p - 1])
                }
            })
            .collect()
    }
}
