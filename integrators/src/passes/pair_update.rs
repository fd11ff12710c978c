//! One irreversible pair update of the eSSA (2019 eq 87; 2021 appendix B with its u_j
//! sign erratum corrected): friction and noise on the momenta by a velocity-Verlet
//! half step and an exact implicit half step, then the pair's kinetic-energy change
//! split equally into u_i and u_j, plus the pair heat flow and its noise.
//! Conserves total momentum and K + u exactly up to round-off.

use crate::passes::heat::{HeatFlow, Temps};
use crate::passes::noise::Noise;
use gendpde_engine::{dot, Vec3};

/// The pair's mechanical state, updated in place.
pub struct PairState<'a> {
    pub p_i: &'a mut Vec3,
    pub p_j: &'a mut Vec3,
    pub u_i: &'a mut f64,
    pub u_j: &'a mut f64,
    pub inv_m_i: f64,
    pub inv_m_j: f64,
}

/// Kernel values, temperatures and noises of one pair in one step.
#[derive(Clone, Copy, Debug)]
pub struct PairDrive {
    /// Unit vector e_ij = (r_i - r_j)/|r_i - r_j|.
    pub e: Vec3,
    /// Friction kernel gamma omega(r)^2 (eq 66), times T0 for the harmonic noise
    /// ([`Noise::coefficients`]).
    pub gamma: f64,
    /// kappa omegabar(r)^2 (eq 71).
    pub kappa: f64,
    pub ti: Temps,
    pub tj: Temps,
    /// Symmetric momentum noise xi_ij and antisymmetric heat noise xibar_ij.
    pub xi: f64,
    pub xibar: f64,
}

/// Energy moved by one pair update: `heat` into i (out of j), and half the pair's
/// kinetic-energy change, taken from each of u_i and u_j.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairDeltas {
    pub heat: f64,
    pub half_dk: f64,
}

/// Applies Phi^irr_ij over `dt` (eq 87); returns the energy it moved.
#[inline(always)]
pub fn pair_update<H: HeatFlow, N: Noise>(s: PairState<'_>, d: &PairDrive, kb: f64, dt: f64, sqrt_dt: f64) -> PairDeltas {
    let e = d.e;
    let (pi, pj) = (*s.p_i, *s.p_j);
    let mut qi = pi;
    let mut qj = pj;
    let mut half_dk = 0.0;
    if d.gamma > 0.0 {
        // the explicit half kick a = -h (v.e) + noise and the implicit one
        // b = -h/(1 + mu h) (v.e + mu a + mu noise) + noise (h = gamma dt / 2) folded into
        // one kick A = a + b = 2 (noise - h v.e)/(1 + mu h): no intermediate kick (which can
        // overshoot by orders of magnitude when gamma dt mu >> 1) is rounded into p, no a
        // and b of opposite signs cancel, and theta reaches A through few operations
        let mu = s.inv_m_i + s.inv_m_j;
        let (gamma, sigma) = N::coefficients(kb, d.gamma, d.ti, d.tj);
        let h = 0.5 * dt * gamma;
        let noise = (0.5 * sqrt_dt * d.xi) * sigma;
        let v = [pi[0] * s.inv_m_i - pj[0] * s.inv_m_j, pi[1] * s.inv_m_i - pj[1] * s.inv_m_j, pi[2] * s.inv_m_i - pj[2] * s.inv_m_j];
        let ve = dot(v, e);
        let big_a = (noise - h * ve) * (2.0 / (1.0 + mu * h));
        kick(&mut qi, &mut qj, e, big_a);
        // K' - K of p_i + A e, p_j - A e: A (v.e) + A^2 mu / 2, without the cancellation
        // of two kinetic energies
        half_dk = 0.5 * big_a * (ve + 0.5 * mu * big_a);
    }
    let heat = if H::ACTIVE && d.kappa > 0.0 {
        let (q, alpha) = H::pair(kb, d.kappa, d.ti, d.tj);
        dt * q + sqrt_dt * alpha * d.xibar
    } else {
        0.0
    };
    *s.p_i = qi;
    *s.p_j = qj;
    *s.u_i += heat - half_dk;
    *s.u_j += -heat - half_dk;
    PairDeltas { heat, half_dk }
}

#[inline(always)]
fn kick(qi: &mut Vec3, qj: &mut Vec3, e: Vec3, a: f64) {
    for k in 0..3 {
        qi[k] += a * e[k];
        qj[k] -= a * e[k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::passes::heat::{Fourier, Original};
    use crate::passes::noise::{Arithmetic, Harmonic};

    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    fn check_conservation<H: HeatFlow, N: Noise>() -> (f64, f64) {
        let mut g = Lcg(7);
        let (mut worst_p, mut worst_e): (f64, f64) = (0.0, 0.0);
        for _ in 0..20_000 {
            let scale = 10f64.powf(g.range(-2.0, 2.0));
            let mut p_i = [g.range(-1.0, 1.0) * scale, g.range(-1.0, 1.0) * scale, g.range(-1.0, 1.0) * scale];
            let mut p_j = [g.range(-1.0, 1.0) * scale, g.range(-1.0, 1.0) * scale, g.range(-1.0, 1.0) * scale];
            let (mut u_i, mut u_j) = (g.range(1.0, 500.0), g.range(1.0, 500.0));
            let (m_i, m_j) = (g.range(0.1, 10.0), g.range(0.1, 10.0));
            let e = {
                let v = [g.range(-1.0, 1.0), g.range(-1.0, 1.0), g.range(-1.0, 1.0) + 1e-3];
                let n = dot(v, v).sqrt();
                [v[0] / n, v[1] / n, v[2] / n]
            };
            let temps = |g: &mut Lcg| {
                let theta = g.range(0.05, 20.0);
                Temps { theta, inv_tau: (1.0 - 1.0 / g.range(1.5, 100.0)) / theta }
            };
            let d = PairDrive {
                e,
                gamma: g.range(0.0, 50.0),
                kappa: g.range(0.0, 20.0),
                ti: temps(&mut g),
                tj: temps(&mut g),
                xi: g.range(-4.0, 4.0),
                xibar: g.range(-4.0, 4.0),
            };
            let dt = g.range(0.001, 0.1);
            let before_p = [p_i[0] + p_j[0], p_i[1] + p_j[1], p_i[2] + p_j[2]];
            let energy = |p_i: Vec3, p_j: Vec3, u_i: f64, u_j: f64| {
                0.5 * dot(p_i, p_i) / m_i + 0.5 * dot(p_j, p_j) / m_j + u_i + u_j
            };
            let before_e = energy(p_i, p_j, u_i, u_j);
            let s = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: 1.0 / m_i, inv_m_j: 1.0 / m_j };
            pair_update::<H, N>(s, &d, 1.0, dt, dt.sqrt());
            let after_p = [p_i[0] + p_j[0], p_i[1] + p_j[1], p_i[2] + p_j[2]];
            let pscale = dot(p_i, p_i).sqrt() + dot(p_j, p_j).sqrt();
            for k in 0..3 {
                worst_p = worst_p.max((after_p[k] - before_p[k]).abs() / pscale);
            }
            worst_e = worst_e.max((energy(p_i, p_j, u_i, u_j) - before_e).abs() / before_e.abs());
        }
        (worst_p, worst_e)
    }

    #[test]
    fn pair_update_conserves_momentum_and_energy_original() {
        let (p, e) = check_conservation::<Original, Arithmetic>();
        eprintln!("original: worst relative momentum error {p:.2e}, energy error {e:.2e}");
        assert!(p < 1e-15 && e < 1e-13, "momentum {p:e}, energy {e:e}");
    }

    #[test]
    fn pair_update_conserves_momentum_and_energy_fourier() {
        let (p, e) = check_conservation::<Fourier, Arithmetic>();
        eprintln!("fourier: worst relative momentum error {p:.2e}, energy error {e:.2e}");
        assert!(p < 1e-15 && e < 1e-13, "momentum {p:e}, energy {e:e}");
    }

    #[test]
    fn pair_update_conserves_momentum_and_energy_harmonic_noise() {
        let (p, e) = check_conservation::<Original, Harmonic>();
        eprintln!("harmonic noise: worst relative momentum error {p:.2e}, energy error {e:.2e}");
        assert!(p < 1e-15 && e < 1e-13, "momentum {p:e}, energy {e:e}");
    }

    /// Without noise, the implicit half step drives the normal relative velocity towards 0
    /// and the deterministic heat flows from hot to cold.
    #[test]
    fn friction_damps_and_heat_flows_downhill() {
        let (mut p_i, mut p_j, mut u_i, mut u_j) = ([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 10.0, 10.0);
        let hot = Temps { theta: 2.0, inv_tau: 0.4 };
        let cold = Temps { theta: 1.0, inv_tau: 0.8 };
        let d = PairDrive { e: [1.0, 0.0, 0.0], gamma: 5.0, kappa: 1.0, ti: hot, tj: cold, xi: 0.0, xibar: 0.0 };
        let s = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: 1.0, inv_m_j: 1.0 };
        pair_update::<Fourier, Arithmetic>(s, &d, 1.0, 0.01, 0.1);
        assert!(p_i[0] < 1.0 && p_i[0] > 0.0);
        // friction heats both equally; conduction moves heat from i (hot) to j
        assert!(u_j - u_i > 0.0);
    }
}
