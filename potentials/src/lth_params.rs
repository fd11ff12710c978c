//! Reduced LTh model parameters from macroscopic data (argon paper, Colella et al., sec
//! 3.3.3 and 4.1, eqs 101-117).
//!
//! Units (eqs 114-117): L_ref = c0^(-1/3) with c0 = rho N_A/(phi M_w) the mesoparticle
//! density (eqs 109-110), u_ref = L_ref^3 / kappa_T0 (macroscopic compressibility),
//! m_ref = phi M_w / N_A, t_ref = sqrt(m_ref L_ref^2 / u_ref); k_B = 1. So c0* = 1 and the
//! macroscopic kappa_T0* = 1. With g = 1 and R_cut -> infinity (eq 100) the particle
//! parameters follow from the macroscopic ones:
//!
//! pi00 = P - c k_B T (101), kappa_T = kbar_T/(1 - kbar_T c k_B T) (103),
//! alpha = abar (1 + kappa_T c k_B T) - kappa_T c k_B (106), C_V = Cbar_V/N - 3/2 k_B (108),
//! with theta0 = T, n00 = c. The dissipation follows from the ideal-system estimates
//! nu = 45 m k_B T/(4 pi gamma R^3) + 2 pi gamma R^5 c^2/1575 (112), solved for gamma (the
//! larger root, the one of Table 2), and lambda = 45 C_V k_B T/(2 pi gamma R^3)
//! + 2 pi kappa R^5 c^2/(315 T^2) (113), solved for kappa with C_V of eq 108.
//!
//! Where the printed tables differ from these equations (tests/it/styles/lth.rs checks every entry):
//! - C_V0*: Tables 1 and 9 print Cbar_V/(N k_B) = C~_V0 m/k_B (eq 111, 12.51 and 8.56,
//!   [`LthParams::cv_macro`]), not C_V of eq 108 (11.008 and 7.063). Their kappa* values
//!   also follow from eq 113 with that C_V ([`LthDissipation::kappa_macro`]): with eq 108,
//!   kappa* = 0.0079638, 0.0025042, 0.00072502 (liquid) and 0.034838 (supercritical), printed
//!   0.0079, 0.0025, 0.00072, 0.034; with Cbar_V/N, 0.0079608 (printed 0.0079, which
//!   rounding would make 0.0080), 0.0025026, 0.00072429, 0.034213.
//! - pi00* of Table 9: 0.5211; eq 101 gives 0.49990 (+0.0212 unexplained, perhaps tuning).
//! - alpha* of Table 1: 29.35; eq 106 gives 29.3448.
//! - gamma* of Tables 2 and 9: 23.42, 7.37, 2.14, 1.05; eq 112 gives 23.408, 7.3651, 2.1346,
//!   1.0449. The printed set is consistent with a nu* about 0.05 % higher (for instance
//!   M_w = 39.948 g/mol in t_ref and L_ref), which no other printed value supports.

use crate::eos::Lth;
use std::f64::consts::PI;

/// Avogadro's number (1/mol), CODATA 2018 exact.
const N_A: f64 = 6.022_140_76e23;
/// Boltzmann's constant (J/K), CODATA 2018 exact.
const K_B: f64 = 1.380_649e-23;

/// A macroscopic reference state in SI units, with the degree of coarse graining and the
/// density cutoffs R_cut* (reduced) to derive the dissipation for.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// T0 (K).
    pub temperature: f64,
    /// Mass density rho~0 (kg/m^3).
    pub mass_density: f64,
    /// P0 (Pa).
    pub pressure: f64,
    /// Specific isochoric heat capacity C~_V0 (J/(kg K)).
    pub cv_specific: f64,
    /// Isothermal compressibility kbar_T0 (1/Pa).
    pub kappa_t: f64,
    /// Thermal expansion coefficient abar_0 (1/K).
    pub alpha: f64,
    /// Kinematic viscosity nu (m^2/s).
    pub viscosity: f64,
    /// Thermal conductivity lambda (W/(m K)).
    pub conductivity: f64,
    /// Molar mass M_w (kg/mol).
    pub molar_mass: f64,
    /// Molecules per mesoparticle phi.
    pub phi: f64,
    /// Reduced cutoffs R_cut* for gamma* and kappa*.
    pub cutoffs: Vec<f64>,
}

impl Reference {
    /// Liquid argon of sec 4.1 (NIST data as printed), cutoffs of Table 2.
    pub fn liquid_argon() -> Self {
        Self {
            temperature: 125.7,
            mass_density: 1419.7,
            pressure: 85.31e6,
            cv_specific: 5.20e2,
            kappa_t: 1.49e-9,
            alpha: 2.64e-3,
            viscosity: 1.69e-7,
            conductivity: 0.139,
            molar_mass: 4e-2,
            phi: 5.0,
            cutoffs: vec![1.3365, 1.6839, 2.1564],
        }
    }

    /// Supercritical argon of sec 4.2.4, R_cut* of Table 9.
    pub fn supercritical_argon() -> Self {
        Self {
            temperature: 418.8,
            mass_density: 695.99,
            pressure: 85.31e6,
            cv_specific: 3.56e2,
            kappa_t: 6.83e-9,
            alpha: 1.97e-3,
            viscosity: 7.98e-8,
            conductivity: 0.0532,
            cutoffs: vec![2.1564],
            ..Self::liquid_argon()
        }
    }
}

/// Reference scales of eqs 114-117 (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// L_ref (m).
    pub length: f64,
    /// u_ref (J).
    pub energy: f64,
    /// m_ref (kg).
    pub mass: f64,
    /// t_ref (s).
    pub time: f64,
}

/// Friction and heat conductivity for one cutoff (eqs 112-113, reduced).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LthDissipation {
    pub rcut: f64,
    /// gamma*, the larger root of eq 112 (NaN if eq 112 has no real root).
    pub gamma: f64,
    /// kappa* = kappa k_B t_ref / u_ref^2 from eq 113 with C_V of eq 108.
    pub kappa: f64,
    /// kappa* from eq 113 with C_V = Cbar_V/N, as in Tables 2 and 9.
    pub kappa_macro: f64,
}

/// Reduced state-point values and LTh parameters (Tables 1, 2, 9), k_B = 1.
#[derive(Clone, Debug, PartialEq)]
pub struct LthParams {
    pub scales: Scales,
    /// T0*.
    pub t0: f64,
    /// P0*.
    pub p0: f64,
    /// Mesoparticle density c0* (1 by construction).
    pub c0: f64,
    /// Cbar_V/(N k_B) = C~_V0 m / k_B (eq 111), the C_V0* printed in Tables 1 and 9.
    pub cv_macro: f64,
    /// Particle heat capacity C_V* of eq 108.
    pub cv: f64,
    /// Particle compressibility kappa_T* (eq 103).
    pub kappa_t: f64,
    /// Macroscopic expansion coefficient abar* = abar u_ref / k_B.
    pub alpha_macro: f64,
    /// Particle expansion coefficient alpha* (eq 106).
    pub alpha: f64,
    /// theta0* = T0*.
    pub theta0: f64,
    /// pi00* (eq 101).
    pub pi00: f64,
    /// n00* = c0*.
    pub n00: f64,
    /// Kinematic viscosity nu*.
    pub nu: f64,
    /// Thermal conductivity lambda*.
    pub lambda: f64,
    /// gamma*, kappa* for each cutoff of the reference.
    pub dissipation: Vec<LthDissipation>,
}

impl LthParams {
    /// Eqs 101-117 applied to a reference state.
    pub fn derive(r: &Reference) -> Self {
        let mass = r.phi * r.molar_mass / N_A; // eq 116
        let c_si = r.mass_density * N_A / r.molar_mass / r.phi; // eqs 109-110
        let length = c_si.powf(-1.0 / 3.0); // eq 114
        let energy = length.powi(3) / r.kappa_t; // eq 115
        let time = (mass * length * length / energy).sqrt(); // eq 117
        let scales = Scales { length, energy, mass, time };

        let t = K_B * r.temperature / energy;
        let c = c_si * length.powi(3);
        let kbar = r.kappa_t * energy / length.powi(3);
        let abar = r.alpha * energy / K_B;
        let cv_macro = r.cv_specific * mass / K_B;
        let kappa_t = kbar / (1.0 - kbar * c * t); // eq 103
        let alpha = abar * (1.0 + kappa_t * c * t) - kappa_t * c; // eq 106
        let cv = cv_macro - 1.5; // eq 108
        let p0 = r.pressure * length.powi(3) / energy;
        let nu = r.viscosity * time / (length * length);
        let lambda = r.conductivity * time * length / K_B;
        let dissipation = r
            .cutoffs
            .iter()
            .map(|&rc| {
                // eq 112: B gamma^2 - nu gamma + A = 0
                let a = 45.0 * t / (4.0 * PI * rc.powi(3));
                let b = 2.0 * PI * rc.powi(5) * c * c / 1575.0;
                let gamma = (nu + (nu * nu - 4.0 * a * b).sqrt()) / (2.0 * b);
                // eq 113
                let kappa = |cv: f64| {
                    let heat = 45.0 * cv * t / (2.0 * PI * gamma * rc.powi(3));
                    (lambda - heat) * 315.0 * t * t / (2.0 * PI * rc.powi(5) * c * c)
                };
                LthDissipation { rcut: rc, gamma, kappa: kappa(cv), kappa_macro: kappa(cv_macro) }
            })
            .collect();
        Self {
            scales,
            t0: t,
            p0,
            c0: c,
            cv_macro,
            cv,
            kappa_t,
            alpha_macro: abar,
            alpha,
            theta0: t,
            pi00: p0 - c * t, // eq 101
            n00: c,
            nu,
            lambda,
            dissipation,
        }
    }

    /// The particle EOS with these parameters (C_V of eq 108).
    pub fn eos(&self) -> Lth {
        Lth::new(self.cv, self.alpha, self.kappa_t, self.pi00, self.theta0, self.n00)
    }

    /// `name value` pairs, in the order of Tables 1, 2 and 9, then the scales.
    pub fn lines(&self) -> Vec<(String, f64)> {
        let mut out: Vec<(String, f64)> = [
            ("T0", self.t0),
            ("P0", self.p0),
            ("c0", self.c0),
            ("cv", self.cv),
            ("cv_macro", self.cv_macro),
            ("kappa_t", self.kappa_t),
            ("alpha", self.alpha),
            ("theta0", self.theta0),
            ("pi00", self.pi00),
            ("n00", self.n00),
            ("alpha_macro", self.alpha_macro),
            ("nu", self.nu),
            ("lambda", self.lambda),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        for d in &self.dissipation {
            out.push((format!("gamma@{}", d.rcut), d.gamma));
            out.push((format!("kappa@{}", d.rcut), d.kappa));
            out.push((format!("kappa_macro@{}", d.rcut), d.kappa_macro));
        }
        let s = &self.scales;
        out.extend([
            ("L_ref_m".to_string(), s.length),
            ("u_ref_J".to_string(), s.energy),
            ("m_ref_kg".to_string(), s.mass),
            ("t_ref_s".to_string(), s.time),
        ]);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inverse relations of the paper hold: eq 102 gives back kbar_T* = 1 and eq 105
    /// the macroscopic abar*; and the reduced scales of the reading notes.
    #[test]
    fn inverse_relations_and_scales() {
        for r in [Reference::liquid_argon(), Reference::supercritical_argon()] {
            let p = LthParams::derive(&r);
            let (c, t) = (p.c0, p.t0);
            assert!((p.c0 - 1.0).abs() < 1e-12);
            let kbar = 1.0 / (c * t + 1.0 / p.kappa_t); // eq 102
            assert!((kbar - 1.0).abs() < 1e-12);
            let abar = (c + p.alpha / p.kappa_t) / (c * t + 1.0 / p.kappa_t); // eq 105
            assert!((abar - p.alpha_macro).abs() < 1e-10 * abar);
            // eq 100 at the reference state: P = c T + pi(T, c)
            let pi = p.eos().pressure(t, c);
            assert!((c * t + pi - p.p0).abs() < 1e-14);
            for d in &p.dissipation {
                let rc = d.rcut;
                let nu = 45.0 * t / (4.0 * PI * d.gamma * rc.powi(3))
                    + 2.0 * PI * d.gamma * rc.powi(5) / 1575.0;
                assert!((nu - p.nu).abs() < 1e-12 * p.nu);
                for (cv, kappa) in [(p.cv, d.kappa), (p.cv_macro, d.kappa_macro)] {
                    let lambda = 45.0 * cv * t / (2.0 * PI * d.gamma * rc.powi(3))
                        + 2.0 * PI * kappa * rc.powi(5) / (315.0 * t * t);
                    assert!((lambda - p.lambda).abs() < 1e-12 * p.lambda);
                }
            }
        }
        let s = LthParams::derive(&Reference::liquid_argon()).scales;
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-4;
        assert!(close(s.length, 6.1616e-10) && close(s.energy, 1.5700e-19));
        assert!(close(s.mass, 3.3211e-25) && close(s.time, 8.9616e-13));
        let s = LthParams::derive(&Reference::supercritical_argon()).scales;
        assert!(close(s.length, 7.8143e-10) && close(s.energy, 6.9864e-20));
        assert!(close(s.time, 1.7037e-12));
    }
}
