//! The momentum friction and noise of a sweep pair: the fluctuation-dissipation pair
//! (gamma_ij, sigma_ij) of `fix shardlow ... noise arithmetic|harmonic`.
//!
//! Arithmetic (the papers' eq 76): gamma_ij = gamma omega^2 constant,
//! sigma_ij^2 = k_B (theta_i + theta_j) gamma_ij. Harmonic (the classic DPDE form):
//! sigma_ij^2 = 2 k_B gamma T0 omega^2 constant, gamma_ij = sigma_ij^2 / (2 k_B Theta_ij),
//! 1/Theta_ij = (1/tau_i + 1/tau_j)/2. Only the harmonic form has eq 88 as the stationary
//! law of the pair update for any EOS (docs/models/gendpde.md, "Choices where the papers are
//! silent or wrong").

use crate::passes::heat::Temps;

/// The noise amplitude of friction `gamma` at temperature `temperature` by the
/// fluctuation-dissipation relation of Espanol and Warren (Europhys. Lett. 30, 191
/// (1995)), sigma^2 = 2 gamma k_B T: sigma = sqrt(2 k_B T gamma).
#[inline(always)]
pub fn isothermal_sigma(kb: f64, temperature: f64, gamma: f64) -> f64 {
    (2.0 * kb * temperature * gamma).sqrt()
}

/// The friction of noise amplitude `sigma` at temperature `temperature` by the same
/// relation (Espanol and Warren 1995, sigma^2 = 2 gamma k_B T): gamma = sigma^2 / (2 k_B T).
#[inline(always)]
pub fn isothermal_gamma(kb: f64, temperature: f64, sigma: f64) -> f64 {
    sigma * sigma / (2.0 * kb * temperature)
}

/// A friction/noise law of one pair.
pub trait Noise: Copy + Send + Sync {
    /// Whether the law reads 1/tau (the store then keeps it up to date).
    const NEEDS_INV_TAU: bool;
    /// (gamma_ij, sigma_ij) from the kernel value `g` the sweep passes: gamma omega^2 for
    /// the arithmetic form, sigma_ij^2/(2 k_B) = gamma T0 omega^2 for the harmonic one.
    fn coefficients(kb: f64, g: f64, i: Temps, j: Temps) -> (f64, f64);
}

/// Eq 76: constant friction, noise on the arithmetic mean of theta.
#[derive(Clone, Copy, Debug)]
pub struct Arithmetic;

/// Constant noise, friction on the harmonic mean of the dressed temperatures tau.
#[derive(Clone, Copy, Debug)]
pub struct Harmonic;

impl Noise for Arithmetic {
    const NEEDS_INV_TAU: bool = false;
    #[inline(always)]
    fn coefficients(kb: f64, g: f64, i: Temps, j: Temps) -> (f64, f64) {
        (g, ((i.theta + j.theta) * (kb * g)).sqrt())
    }
}

impl Noise for Harmonic {
    const NEEDS_INV_TAU: bool = true;
    #[inline(always)]
    fn coefficients(kb: f64, g: f64, i: Temps, j: Temps) -> (f64, f64) {
        (0.5 * g * (i.inv_tau + j.inv_tau), (2.0 * kb * g).sqrt())
    }
}

/// The noise laws a script can choose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoiseForm {
    Arithmetic,
    /// gamma_ij = gamma omega^2 where Theta_ij = `temperature` (T0).
    Harmonic {
        temperature: f64,
    },
}

impl NoiseForm {
    /// The factor of gamma omega^2 that gives the kernel value `g` of [`Noise::coefficients`].
    pub fn scale(&self) -> f64 {
        match self {
            Self::Arithmetic => 1.0,
            Self::Harmonic { temperature } => *temperature,
        }
    }
}
