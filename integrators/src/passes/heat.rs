//! Heat-flow models between particle pairs and with a reservoir.
//!
//! Original (2019, eqs 70, 72, 80): q_ij = kappa_ij (1/tau_i - 1/tau_j) into i, noise
//! amplitude alpha = sqrt(2 k_B kappa_ij). Fourier-like (2021 PRE, eqs 47, 61):
//! q_ij = -kappa_ij (theta_i - theta_j), alpha = sqrt(2 k_B kappa_ij theta_i theta_j).

/// Temperatures of one particle as the heat laws read them.
#[derive(Clone, Copy, Debug)]
pub struct Temps {
    pub theta: f64,
    /// 1/tau; only the original model reads it.
    pub inv_tau: f64,
}

/// A pairwise heat-conduction law with its fluctuation-dissipation partner.
pub trait HeatFlow: Copy + Send + Sync {
    /// Whether the law reads 1/tau (the store then keeps it up to date).
    const NEEDS_INV_TAU: bool;
    /// Whether heat flows at all (kappa > 0); without it no heat noise is drawn.
    const ACTIVE: bool = true;
    /// (q, alpha): deterministic heat into i per unit time and unit kernel, and the noise
    /// amplitude, for kernel value `kappa` between `i` and `j`.
    fn pair(kb: f64, kappa: f64, i: Temps, j: Temps) -> (f64, f64);
    /// Same, for a particle and a reservoir at temperature `t`.
    fn reservoir(kb: f64, kappa: f64, i: Temps, t: f64) -> (f64, f64);
}

/// The 2019 law on inverse dressed temperatures.
#[derive(Clone, Copy, Debug)]
pub struct Original;

/// The 2021 Fourier-like law on particle temperatures.
#[derive(Clone, Copy, Debug)]
pub struct Fourier;

/// No heat conduction (kappa = 0).
#[derive(Clone, Copy, Debug)]
pub struct NoHeat;

impl HeatFlow for Original {
    const NEEDS_INV_TAU: bool = true;
    #[inline(always)]
    fn pair(kb: f64, kappa: f64, i: Temps, j: Temps) -> (f64, f64) {
        (kappa * (i.inv_tau - j.inv_tau), (2.0 * kb * kappa).sqrt())
    }
    #[inline(always)]
    fn reservoir(kb: f64, kappa: f64, i: Temps, t: f64) -> (f64, f64) {
        (kappa * (i.inv_tau - 1.0 / t), (2.0 * kb * kappa).sqrt())
    }
}

impl HeatFlow for Fourier {
    const NEEDS_INV_TAU: bool = false;
    #[inline(always)]
    fn pair(kb: f64, kappa: f64, i: Temps, j: Temps) -> (f64, f64) {
        (-kappa * (i.theta - j.theta), (2.0 * kb * kappa * i.theta * j.theta).sqrt())
    }
    /// By analogy with eq 61 (the 2021 paper prints no amplitude): detailed balance of
    /// P(u) ~ exp(-u/k_B T + z(u)/k_B) with Ito noise gives alpha^2 = 2 k_B kappa theta T.
    #[inline(always)]
    fn reservoir(kb: f64, kappa: f64, i: Temps, t: f64) -> (f64, f64) {
        (-kappa * (i.theta - t), (2.0 * kb * kappa * i.theta * t).sqrt())
    }
}

impl HeatFlow for NoHeat {
    const NEEDS_INV_TAU: bool = false;
    const ACTIVE: bool = false;
    #[inline(always)]
    fn pair(_: f64, _: f64, _: Temps, _: Temps) -> (f64, f64) {
        (0.0, 0.0)
    }
    #[inline(always)]
    fn reservoir(_: f64, _: f64, _: Temps, _: f64) -> (f64, f64) {
        (0.0, 0.0)
    }
}

/// The heat models a script can choose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeatModel {
    Original,
    Fourier,
}

impl HeatModel {
    pub fn parse(word: &str) -> Option<Self> {
        match word {
            "original" | "2019" => Some(Self::Original),
            "fourier" | "2021" => Some(Self::Fourier),
            _ => None,
        }
    }
}
