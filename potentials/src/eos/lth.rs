//! Local thermodynamic (LTh) model of a condensed phase, Colella et al., "Statistical
//! Mechanics of Density- and Temperature-Dependent Potentials" (argon paper; equation
//! numbers are that paper's). The particle pressure is linear in theta and logarithmic in n
//! around a reference state (pi00, theta0, n00) with constant particle compressibility
//! kappa_T, expansion coefficient alpha and heat capacity C_V:
//!
//! pi(theta, n) = pi00 + (alpha/kappa_T)(theta - theta0) + ln(n/n00)/kappa_T      (eq 41)
//! V(n) = -pi00/n + alpha theta0/(n kappa_T) - (ln(n/n00) + 1)/(n kappa_T)          (eq 54)
//!
//! in its high-temperature form theta >> Theta (eqs 52-53, 55-58), the form the paper
//! simulates:
//!
//! u = C_V theta + V(n),  theta = (u - V(n))/C_V,  pi/n^2 = alpha theta/(kappa_T n^2) + V'(n),
//! s = alpha/(n kappa_T) + C_V ln[(u - V)/(C_V Theta)] + C_V.
//!
//! The Debye-like scale Theta of eqs 45-50 is never given; like [`super::LinearTheta`], s
//! is reported with Theta = 1 (it only shifts s by a constant). The paper's reduced units
//! (eqs 114-117) have k_B = 1; any consistent units work, theta being k_B times a
//! temperature.

use super::{AffineAt, Eos, FixedDensity};

/// The LTh particle EOS, high-temperature form (eqs 41, 52-58).
#[derive(Clone, Debug, PartialEq)]
pub struct Lth {
    /// Particle heat capacity C_V (energy per temperature).
    pub cv: f64,
    /// Boltzmann's constant (1 in reduced units).
    pub kb: f64,
    /// Particle thermal expansion coefficient alpha (1/temperature), eq 38.
    pub alpha: f64,
    /// Particle isothermal compressibility kappa_T (1/pressure), eq 36.
    pub kappa_t: f64,
    /// Reference particle pressure pi00 = pi(n00, theta0).
    pub pi00: f64,
    /// Reference particle temperature theta0.
    pub theta0: f64,
    /// Reference density n00.
    pub n00: f64,
}

impl Lth {
    /// LTh model with k_B = 1.
    pub fn new(cv: f64, alpha: f64, kappa_t: f64, pi00: f64, theta0: f64, n00: f64) -> Self {
        Self { cv, kb: 1.0, alpha, kappa_t, pi00, theta0, n00 }
    }

    /// Particle pressure pi(theta, n), eq 41.
    #[inline]
    pub fn pressure(&self, theta: f64, n: f64) -> f64 {
        self.pi00 + (self.alpha * (theta - self.theta0) + (n / self.n00).ln()) / self.kappa_t
    }

    /// Density potential V(n), eq 54.
    #[inline]
    pub fn potential(&self, n: f64) -> f64 {
        (-self.pi00 + (self.alpha * self.theta0 - (n / self.n00).ln() - 1.0) / self.kappa_t) / n
    }
}

impl Eos for Lth {
    fn kb(&self) -> f64 {
        self.kb
    }
    fn density_dependent(&self) -> bool {
        true
    }
    /// Eq 53.
    #[inline]
    fn theta(&self, u: f64, n: f64, _guess: f64) -> f64 {
        (u - self.potential(n)) / self.cv
    }
    /// Eq 52.
    #[inline]
    fn u(&self, theta: f64, n: f64) -> f64 {
        self.cv * theta + self.potential(n)
    }
    /// Eqs 41 = 58 over n^2.
    #[inline]
    fn pn2(&self, theta: f64, n: f64) -> f64 {
        self.pressure(theta, n) / (n * n)
    }
    #[inline]
    fn cv(&self, _theta: f64, _n: f64) -> f64 {
        self.cv
    }
    /// Eq 55 with Theta = 1.
    fn entropy(&self, u: f64, n: f64) -> Option<f64> {
        let x = (u - self.potential(n)) / self.cv;
        (x > 0.0).then(|| self.alpha / (n * self.kappa_t) + self.cv * (x.ln() + 1.0))
    }
    fn max_density(&self) -> Option<f64> {
        None
    }
}

impl FixedDensity for Lth {
    type At<'a> = AffineAt;
    #[inline]
    fn at_density(&self, n: f64) -> AffineAt {
        AffineAt::new(self.potential(n), self.cv, self.kb)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Table 1 of the argon paper (liquid argon, reduced units), C_V of eq 108.
    fn liquid() -> Lth {
        Lth::new(11.008, 29.345, 1.0112, 0.11606, 0.011054, 1.0)
    }

    fn models() -> Vec<Lth> {
        let mut hot = Lth::new(7.06, 9.778, 1.0902, 0.4999, 0.08276, 1.0);
        hot.kb = 1.3;
        vec![liquid(), hot]
    }

    fn states() -> Vec<(f64, f64)> {
        vec![(0.011, 1.0), (0.0121, 0.9), (0.0095, 1.12), (0.08, 1.05), (0.02, 0.5)]
    }

    /// Central five-point first derivative, error O(h^4).
    fn d1(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
        (8.0 * (f(x + h) - f(x - h)) - (f(x + 2.0 * h) - f(x - 2.0 * h))) / (12.0 * h)
    }

    /// u(s, n) of eq 56, from the entropy of eq 55 (Theta = 1).
    fn u_at(m: &Lth, s: f64, n: f64) -> f64 {
        m.potential(n) + m.cv * ((s - m.cv - m.alpha / (n * m.kappa_t)) / m.cv).exp()
    }

    #[test]
    fn pressure_and_temperature_are_derivatives_of_u_at_fixed_entropy() {
        for m in models() {
            for (theta, n) in states() {
                let u = m.u(theta, n);
                let s = m.entropy(u, n).unwrap();
                assert!((u_at(&m, s, n) - u).abs() < 1e-13 * u.abs().max(1.0));
                let pn2 = d1(|x| u_at(&m, s, x), n, 1e-4);
                assert!((pn2 - m.pn2(theta, n)).abs() < 1e-9 * pn2.abs().max(1.0), "{pn2}");
                let ts = d1(|x| u_at(&m, x, n), s, 1e-3);
                assert!((ts - theta).abs() < 1e-9 * theta, "du/ds {ts} vs {theta}");
                let cv = d1(|t| m.u(t, n), theta, 1e-4 * theta);
                assert!((cv - m.cv(theta, n)).abs() < 1e-9 * m.cv);
            }
        }
    }

    #[test]
    fn pi_is_n2_dv_dn_plus_alpha_theta_over_kappa() {
        // eq 58 from V(n) of eq 54, independently of eq 41
        for m in models() {
            for (theta, n) in states() {
                let dv = d1(|x| m.potential(x), n, 1e-4);
                let pi = m.alpha * theta / m.kappa_t + n * n * dv;
                assert!((pi - m.pressure(theta, n)).abs() < 1e-9, "{pi}");
            }
        }
    }

    #[test]
    fn reference_state_compressibility_and_expansion() {
        let m = liquid();
        assert!((m.pressure(m.theta0, m.n00) - m.pi00).abs() < 1e-15);
        for (theta, n) in states() {
            // eq 36: kappa_T = (1/n) dn/dpi at fixed theta
            let dpi_dn = d1(|x| m.pressure(theta, x), n, 1e-4);
            assert!((1.0 / (n * dpi_dn) - m.kappa_t).abs() < 1e-9);
            // eq 38: alpha = -(1/n) dn/dtheta at fixed pi
            let dpi_dt = d1(|t| m.pressure(t, n), theta, 1e-5);
            assert!((dpi_dt / (n * dpi_dn) - m.alpha).abs() < 1e-8);
        }
    }

    #[test]
    fn theta_inverts_u() {
        for m in models() {
            for (theta, n) in states() {
                let u = m.u(theta, n);
                let tol = 4.0 * f64::EPSILON * m.potential(n).abs().max(1.0) / m.cv;
                assert!((m.theta(u, n, f64::NAN) - theta).abs() < tol);
                let st = m.state(u, n, 0.0).unwrap();
                assert_eq!(st.pn2, m.pn2(st.theta, n));
                assert_eq!(st.cv, m.cv);
            }
            assert!(m.state(m.potential(1.0) - 1e-3, 1.0, 0.0).is_err());
            assert!(m.entropy(m.potential(1.0), 1.0).is_none());
        }
    }

    /// Table 5 of the paper: U/N = 3/2 T + V(n) + C_V T (eq 99) at n = 1 with the Table 1
    /// parameters and the printed C_V0* = 12.51 gives -0.629, within the simulated
    /// -0.62 .. -0.63 (+- 0.01).
    #[test]
    fn energy_per_particle_at_the_reference_state() {
        let m = Lth { cv: 12.508, ..liquid() };
        let t = m.theta0;
        let u = 1.5 * t + m.u(t, 1.0);
        assert!((u + 0.629).abs() < 5e-4, "{u}");
    }
}
