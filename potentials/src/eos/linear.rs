//! EOS linear in the particle temperature (eqs 43-46, 93-96):
//!
//! u(s, n) = C_V theta0 e^{s/C_V} psi(n)^{k_B/C_V} + V(n),  theta = (u - V(n)) / C_V,
//! pi/n^2 = k_B theta (ln psi)'(n) + V'(n),  s = C_V ln[(u - V)/(C_V theta0)] - k_B ln psi.
//!
//! Here ln psi(n) = q ln n - r ln(1 - b n) and V(n) = sum_k c_k n^k, which covers
//! van der Waals full (q = r = 1, V = -a n, eq 38) and excess (q = 0, r = 1, eq 41),
//! the ideal gas (q = 1, eq 101) and the density-only model (q = r = 0, eq 98).
//!
//! Density cap: 1 - b n must stay positive. Above n_s = cap/b (cap < 1) ln psi is
//! continued by its second-order Taylor polynomial at n_s, so the model stays smooth
//! (C^2), finite and strongly repulsive at any density; below n_s it is exact.
#![allow(clippy::approx_constant)] // 1.4142 is the vdW b of the 2019 paper, not sqrt 2

use super::{AffineAt, Eos, FixedDensity};

/// The linear-in-theta family with constant C_V (theta0 = 1).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearTheta {
    pub cv: f64,
    pub kb: f64,
    /// Exponent of n in psi.
    pub q: f64,
    /// Exponent of 1/(1 - b n) in psi.
    pub r: f64,
    /// Excluded volume b.
    pub b: f64,
    /// V(n) = sum_k coeffs[k-1] n^k.
    pub v_coeffs: Vec<f64>,
    /// n_s = cap / b, where the Taylor continuation of ln psi starts.
    pub cap: f64,
}

/// Default fraction of 1/b where the density cap starts.
pub const DEFAULT_CAP: f64 = 0.95;

impl LinearTheta {
    /// `fix eos/cv`: u = C_V theta (psi = 1, V = 0).
    pub fn cv_only(cv: f64) -> Self {
        Self::density_only(cv, vec![])
    }
    /// Ideal gas, pi = k_B theta n (eq 100).
    pub fn ideal(cv: f64) -> Self {
        Self { q: 1.0, ..Self::cv_only(cv) }
    }
    /// van der Waals, pi = n k_B theta/(1 - b n) - a n^2 (eq 29).
    pub fn vdw_full(cv: f64, a: f64, b: f64) -> Self {
        Self { q: 1.0, r: 1.0, b, v_coeffs: vec![-a], ..Self::cv_only(cv) }
    }
    /// van der Waals excess, pi/n^2 = b k_B theta/(1 - b n) - a (eq 40).
    pub fn vdw_excess(cv: f64, a: f64, b: f64) -> Self {
        Self { r: 1.0, b, v_coeffs: vec![-a], ..Self::cv_only(cv) }
    }
    /// Temperature-independent many-body EOS, pi/n^2 = V'(n) (eq 97).
    pub fn density_only(cv: f64, v_coeffs: Vec<f64>) -> Self {
        Self { cv, kb: 1.0, q: 0.0, r: 0.0, b: 0.0, v_coeffs, cap: DEFAULT_CAP }
    }

    /// n_s, start of the density cap (infinite without excluded volume).
    pub fn cap_density(&self) -> f64 {
        if self.r != 0.0 && self.b > 0.0 { self.cap / self.b } else { f64::INFINITY }
    }

    /// V(n) and V'(n).
    #[inline]
    fn v(&self, n: f64) -> (f64, f64) {
        let (mut v, mut dv, mut pow) = (0.0, 0.0, 1.0);
        for (k, c) in self.v_coeffs.iter().enumerate() {
            dv += (k + 1) as f64 * c * pow;
            pow *= n;
            v += c * pow;
        }
        (v, dv)
    }

    /// ln psi(n) and (ln psi)'(n), with the Taylor continuation above n_s.
    #[inline]
    fn ln_psi(&self, n: f64) -> (f64, f64) {
        let (mut l, mut dl) = (0.0, 0.0);
        if self.q != 0.0 {
            l += self.q * n.ln();
            dl += self.q / n;
        }
        if self.r != 0.0 {
            let ns = self.cap_density();
            if n <= ns {
                let g = 1.0 - self.b * n;
                l -= self.r * g.ln();
                dl += self.r * self.b / g;
            } else {
                let g = 1.0 - self.b * ns;
                let (d1, d2) = (self.r * self.b / g, self.r * self.b * self.b / (g * g));
                let x = n - ns;
                l += -self.r * g.ln() + x * (d1 + 0.5 * d2 * x);
                dl += d1 + d2 * x;
            }
        }
        (l, dl)
    }
}

impl Eos for LinearTheta {
    fn kb(&self) -> f64 {
        self.kb
    }
    fn density_dependent(&self) -> bool {
        self.q != 0.0 || self.r != 0.0 || !self.v_coeffs.is_empty()
    }
    #[inline]
    fn theta(&self, u: f64, n: f64, _guess: f64) -> f64 {
        (u - self.v(n).0) / self.cv
    }
    #[inline]
    fn u(&self, theta: f64, n: f64) -> f64 {
        self.cv * theta + self.v(n).0
    }
    #[inline]
    fn pn2(&self, theta: f64, n: f64) -> f64 {
        self.kb * theta * self.ln_psi(n).1 + self.v(n).1
    }
    #[inline]
    fn cv(&self, _theta: f64, _n: f64) -> f64 {
        self.cv
    }
    fn entropy(&self, u: f64, n: f64) -> Option<f64> {
        let x = (u - self.v(n).0) / self.cv;
        (x > 0.0).then(|| self.cv * x.ln() - self.kb * self.ln_psi(n).0)
    }
    fn max_density(&self) -> Option<f64> {
        (self.r != 0.0 && self.b > 0.0).then(|| 1.0 / self.b)
    }
}

impl FixedDensity for LinearTheta {
    type At<'a> = AffineAt;
    #[inline]
    fn at_density(&self, n: f64) -> AffineAt {
        AffineAt::new(self.v(n).0, self.cv, self.kb)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn models() -> Vec<LinearTheta> {
        vec![
            LinearTheta::vdw_full(60.0, 2.4682, 1.4142),
            LinearTheta::vdw_excess(60.0, 2.4682, 1.4142),
            LinearTheta::ideal(5.0),
            LinearTheta::density_only(10.0, vec![-1.0, 0.5, 0.25]),
        ]
    }

    /// u(s, n) of eq 43 reconstructed from s(u, n): pi/n^2 must equal du/dn at fixed s.
    #[test]
    fn particle_pressure_is_du_dn_at_fixed_entropy() {
        for m in models() {
            for &(theta, n) in &[(1.5, 0.5), (0.7, 0.3), (3.0, 0.65), (2.0, 0.69)] {
                let u = m.u(theta, n);
                let s = m.entropy(u, n).unwrap();
                // u(s, n) = C_V exp(s/C_V) psi^{kB/C_V} + V(n)
                let u_at = |n: f64| m.cv * ((s + m.kb * m.ln_psi(n).0) / m.cv).exp() + m.v(n).0;
                assert!((u_at(n) - u).abs() < 1e-10 * u.abs().max(1.0));
                let h = 1e-6;
                let fd = (u_at(n + h) - u_at(n - h)) / (2.0 * h);
                let pn2 = m.pn2(theta, n);
                assert!((fd - pn2).abs() < 1e-6 * pn2.abs().max(1.0), "{m:?}: fd {fd} vs {pn2}");
                // theta = du/ds at fixed n (eq 6)
                let ts = (u_at_s(&m, s + h, n) - u_at_s(&m, s - h, n)) / (2.0 * h);
                assert!((ts - theta).abs() < 1e-6 * theta);
            }
        }
    }

    fn u_at_s(m: &LinearTheta, s: f64, n: f64) -> f64 {
        m.cv * ((s + m.kb * m.ln_psi(n).0) / m.cv).exp() + m.v(n).0
    }

    #[test]
    fn vdw_pressures_match_eqs_29_and_40() {
        let (a, b, theta, n) = (2.4682, 1.4142, 1.5, 0.5);
        let full = LinearTheta::vdw_full(60.0, a, b);
        let pi = full.pn2(theta, n) * n * n;
        assert!((pi - (n * theta / (1.0 - b * n) - a * n * n)).abs() < 1e-12);
        let ex = LinearTheta::vdw_excess(60.0, a, b);
        assert!((ex.pn2(theta, n) - (b * theta / (1.0 - b * n) - a)).abs() < 1e-12);
        assert_eq!(ex.theta(ex.u(theta, n), n, 0.0), theta);
    }

    #[test]
    fn density_cap_is_smooth_finite_and_repulsive() {
        let m = LinearTheta::vdw_excess(60.0, 2.4682, 1.4142);
        let ns = m.cap_density();
        let below = m.ln_psi(ns - 1e-12);
        let above = m.ln_psi(ns + 1e-12);
        assert!((below.0 - above.0).abs() < 1e-9 && (below.1 - above.1).abs() < 1e-8);
        let mut last = m.pn2(1.0, ns);
        for k in 1..50 {
            let p = m.pn2(1.0, ns + 0.05 * k as f64);
            assert!(p.is_finite() && p > last, "pi/n^2 must keep growing past the cap");
            last = p;
        }
        assert_eq!(m.max_density(), Some(1.0 / 1.4142));
    }

    #[test]
    fn isolated_particles_feel_no_pressure() {
        let m = LinearTheta::vdw_excess(60.0, 2.4682, 1.4142);
        let st = m.state(90.0, 0.0, 1.5).unwrap();
        assert_eq!(st.pn2, 0.0);
        assert!((st.theta - (90.0 + 2.4682e-6) / 60.0).abs() < 1e-14);
    }

    #[test]
    fn negative_temperature_is_an_error() {
        let m = LinearTheta::vdw_excess(60.0, 2.4682, 1.4142);
        assert!(matches!(m.state(-5.0, 0.5, 1.0), Err(EosError::NonPositiveTheta { .. })));
        assert!(m.state(f64::NAN, 0.5, 1.0).is_err());
    }

    #[test]
    fn dressed_temperature_follows_eq_23() {
        let m = LinearTheta::cv_only(5.0);
        assert!((1.0 / m.inv_tau(1.5, 5.0) - 1.5 / (1.0 - 0.2)).abs() < 1e-14);
    }

    use super::super::EosError;
}
