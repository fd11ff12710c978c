//! Particle equations of state: from the internal energy u and the local density n
//! give the particle temperature theta (eq 6), the particle pressure pi (eq 7), the heat
//! capacity C_V (eq 22) and the dressed temperature tau (eqs 19, 23).
//!
//! A new EOS is one file in this folder implementing [`Eos`], plus one registration in
//! the app's style table (see docs/ARCHITECTURE.md, "What a new X touches").

mod linear;
mod lj;
mod lth;
mod table;
mod tait;

pub use linear::{LinearTheta, DEFAULT_CAP};
pub use lj::LennardJones;
pub use lth::Lth;
pub use lj::LjAt;
pub use tait::Tait;
pub use table::{ErrorAt, TableAt, TableError, TableErrors, TableGrid, Tabulated};

use std::fmt;

/// Local density below which a particle counts as isolated (2019 paper, secs 4.3, 5.3.2):
/// its density is raised to this value and its particle pressure set to zero, so its
/// forces vanish but stay finite.
pub const ISOLATED_DENSITY: f64 = 1e-6;

/// Thermodynamic state of one particle, as the dynamics needs it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EosState {
    /// Particle temperature theta = du/ds|_n (eq 6).
    pub theta: f64,
    /// pi/n^2 = du/dn|_s, the factor of the many-body force (eq 51).
    pub pn2: f64,
    /// Heat capacity C_V = du/dtheta|_n (eq 22).
    pub cv: f64,
}

/// Why a state cannot be evaluated.
#[derive(Clone, Debug, PartialEq)]
pub enum EosError {
    /// theta(u, n) <= 0 or not finite: u lies below the ground state at this density.
    NonPositiveTheta { u: f64, n: f64, theta: f64 },
    /// (u, n) lies outside the model's domain (a table's range): `why` says how.
    Outside { u: f64, n: f64, why: String },
}

impl EosError {
    /// The error of a state whose theta(u, n) came out non-positive or not finite: the
    /// model's reason when (u, n) lies outside its domain, else the bare values.
    pub fn at<E: Eos + ?Sized>(eos: &E, u: f64, n: f64, theta: f64) -> Self {
        match eos.outside(u, n) {
            Some(why) => Self::Outside { u, n, why },
            None => Self::NonPositiveTheta { u, n, theta },
        }
    }
}

impl fmt::Display for EosError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonPositiveTheta { u, n, theta } => write!(
                f,
                "particle temperature theta = {theta:e} is not positive (u = {u:e}, n = {n:e})"
            ),
            Self::Outside { why, .. } => write!(f, "{why}"),
        }
    }
}

impl std::error::Error for EosError {}

/// A particle equation of state u(s, n) with k_B = `kb()`.
pub trait Eos: Send + Sync {
    /// Boltzmann's constant in the units of the script.
    fn kb(&self) -> f64;
    /// Whether pi depends on n; a pairwise scene skips the density pass when false.
    fn density_dependent(&self) -> bool;
    /// theta(u, n); `guess` seeds iterative models (the last theta of the particle).
    fn theta(&self, u: f64, n: f64, guess: f64) -> f64;
    /// u(theta, n).
    fn u(&self, theta: f64, n: f64) -> f64;
    /// pi(theta, n) / n^2.
    fn pn2(&self, theta: f64, n: f64) -> f64;
    /// C_V(theta, n).
    fn cv(&self, theta: f64, n: f64) -> f64;
    /// Bare particle entropy s(u, n) (eq 45), where the model has a closed form.
    fn entropy(&self, u: f64, n: f64) -> Option<f64>;
    /// Largest local density the model accepts for an initial state (None: unbounded).
    fn max_density(&self) -> Option<f64>;

    /// theta(u, n) and C_V there, for callers that need both (the sweep's refresh of
    /// 1/tau after each pair update); models that get C_V from the same evaluation as
    /// theta override it (equal to `cv(theta(u, n), n)` up to round-off).
    #[inline]
    fn theta_cv(&self, u: f64, n: f64, guess: f64) -> (f64, f64) {
        let theta = self.theta(u, n, guess);
        (theta, self.cv(theta, n))
    }

    /// theta, pi/n^2 and C_V at (u, n), with the isolated-particle rule applied.
    /// A non-finite result (an absurd density or energy) is an error, never a value.
    #[inline]
    fn state(&self, u: f64, n: f64, guess: f64) -> Result<EosState, EosError> {
        let isolated = n < ISOLATED_DENSITY;
        let n = if isolated { ISOLATED_DENSITY } else { n };
        let theta = self.theta(u, n, guess);
        if !(theta > 0.0 && theta.is_finite()) || n.is_nan() {
            return Err(EosError::at(self, u, n, theta));
        }
        let pn2 = if isolated { 0.0 } else { self.pn2(theta, n) };
        let cv = self.cv(theta, n);
        if !(pn2.is_finite() && cv.is_finite()) {
            return Err(EosError::NonPositiveTheta { u, n, theta: f64::NAN });
        }
        Ok(EosState { theta, pn2, cv })
    }

    /// Why (u, n) lies outside the model's domain, if it does (a table's range); None for
    /// analytic models, which are defined wherever theta(u, n) is.
    fn outside(&self, _u: f64, _n: f64) -> Option<String> {
        None
    }

    /// 1/tau = (1 - k_B/C_V)/theta, the inverse dressed temperature (eqs 19, 23), as
    /// (C_V - k_B)/(C_V theta): one division (the sweep refreshes it after every pair).
    #[inline]
    fn inv_tau(&self, theta: f64, cv: f64) -> f64 {
        (cv - self.kb()) / (cv * theta)
    }
}

/// A model at one fixed density: theta(u) and 1/tau(u) as the Shardlow sweep refreshes
/// them after each pair update (the sweep does not move particles, so n stays fixed; eqs
/// 82, 87). What depends on n only (V(n), n-polynomials) is evaluated once per particle
/// and sweep in [`FixedDensity::at_density`], not in every refresh.
pub trait AtDensity: Copy {
    /// theta(u) at this density; `guess` seeds iterative models.
    fn theta(&self, u: f64, guess: f64) -> f64;
    /// theta(u) and 1/tau = (1 - k_B/C_V)/theta there (eqs 19, 23).
    fn theta_inv_tau(&self, u: f64, guess: f64) -> (f64, f64);
    /// [`AtDensity::theta`] of two particles, `self` at `u[0]` and `b` at `u[1]`: the same
    /// bits as two calls (iterative models interleave the two solves).
    #[inline(always)]
    fn theta_pair(&self, b: &Self, u: [f64; 2], guess: [f64; 2]) -> [f64; 2] {
        [self.theta(u[0], guess[0]), b.theta(u[1], guess[1])]
    }
    /// [`AtDensity::theta_inv_tau`] of two particles, as [`AtDensity::theta_pair`].
    #[inline(always)]
    fn theta_inv_tau_pair(&self, b: &Self, u: [f64; 2], guess: [f64; 2]) -> [(f64, f64); 2] {
        [self.theta_inv_tau(u[0], guess[0]), b.theta_inv_tau(u[1], guess[1])]
    }
    /// The guess for the solve after the energy moved by `du` from a state at `theta` with
    /// 1/tau = `inv_tau` (at this density): the model's own `theta` (the default, for models
    /// that ignore guesses), or the first-order step theta + du/C_V, 1/C_V = (1 - theta/tau)
    /// / k_B (eqs 19, 23), for iterative ones (then one Newton step usually converges; a
    /// guess that is no positive number makes them start from their own estimate).
    #[inline(always)]
    fn guess_after(&self, theta: f64, _inv_tau: f64, _du: f64) -> f64 {
        theta
    }
    /// The sweep's refresh of a pair, `self` and `b`, after a pair update moved their
    /// energies from `before[k].u` to `u[k]`: theta, and 1/tau where `inv_tau` (else 0).
    /// The default solves from the first-order guess ([`AtDensity::guess_after`]) where
    /// 1/tau is kept, else from the theta before.
    #[inline(always)]
    fn after_pair(&self, b: &Self, before: [Before; 2], u: [f64; 2], inv_tau: bool) -> [(f64, f64); 2] {
        if inv_tau {
            let guess = [
                self.guess_after(before[0].theta, before[0].inv_tau, u[0] - before[0].u),
                b.guess_after(before[1].theta, before[1].inv_tau, u[1] - before[1].u),
            ];
            self.theta_inv_tau_pair(b, u, guess)
        } else {
            self.theta_pair(b, u, [before[0].theta, before[1].theta]).map(|theta| (theta, 0.0))
        }
    }
}

/// A particle's state before a pair update moved its energy, where the sweep's refresh
/// ([`AtDensity::after_pair`]) starts.
#[derive(Clone, Copy, Debug)]
pub struct Before {
    pub theta: f64,
    /// 1/tau, read only where the sweep keeps it.
    pub inv_tau: f64,
    pub u: f64,
}

/// Models that can precompute their density-only parts ([`AtDensity`]).
pub trait FixedDensity: Eos {
    type At<'a>: AtDensity
    where
        Self: 'a;
    /// The model at density `n` (already raised to [`ISOLATED_DENSITY`] by the caller);
    /// its theta and 1/tau equal [`Eos::theta`] and [`Eos::theta_cv`] with
    /// [`Eos::inv_tau`] at `n`, bit for bit.
    fn at_density(&self, n: f64) -> Self::At<'_>;
    /// [`FixedDensity::at_density`] for a particle now at `theta`, whose refreshes will
    /// stay near it (the sweep's): models may keep data for such states (a table the cubic
    /// of theta's cell); the same results, bit for bit.
    #[inline(always)]
    fn at_state(&self, n: f64, _theta: f64) -> Self::At<'_> {
        self.at_density(n)
    }
}

/// The generic [`AtDensity`]: the model and n, through [`Eos::theta`] and [`Eos::theta_cv`].
#[derive(Debug)]
pub struct AtN<'a, E> {
    pub eos: &'a E,
    pub n: f64,
}

impl<E> Clone for AtN<'_, E> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<E> Copy for AtN<'_, E> {}

impl<E: Eos> AtDensity for AtN<'_, E> {
    #[inline(always)]
    fn theta(&self, u: f64, guess: f64) -> f64 {
        self.eos.theta(u, self.n, guess)
    }
    #[inline(always)]
    fn theta_inv_tau(&self, u: f64, guess: f64) -> (f64, f64) {
        let (theta, cv) = self.eos.theta_cv(u, self.n, guess);
        (theta, self.eos.inv_tau(theta, cv))
    }
    #[inline(always)]
    fn guess_after(&self, theta: f64, inv_tau: f64, du: f64) -> f64 {
        // times 1/k_B: a division the refresh need not wait for (exact for k_B = 1)
        theta + du * (1.0 - theta * inv_tau) * (1.0 / self.eos.kb())
    }
}

/// theta = (u - V(n))/C_V with constant C_V, the form of the linear family (eq 44) and of
/// the argon LTH model (eq 53): V(n) and 1 - k_B/C_V taken once.
#[derive(Clone, Copy, Debug)]
pub struct AffineAt {
    /// V(n).
    pub v: f64,
    pub inv_cv: f64,
    /// C_V - k_B, so that 1/tau = (1 - k_B/C_V)/theta = (C_V - k_B)/(u - V).
    pub excess: f64,
}

impl AffineAt {
    pub fn new(v: f64, cv: f64, kb: f64) -> Self {
        Self { v, inv_cv: 1.0 / cv, excess: cv - kb }
    }
}

impl AtDensity for AffineAt {
    #[inline(always)]
    fn theta(&self, u: f64, _guess: f64) -> f64 {
        (u - self.v) * self.inv_cv
    }
    /// theta and 1/tau from u - V side by side (one division, not two in a chain).
    #[inline(always)]
    fn theta_inv_tau(&self, u: f64, _guess: f64) -> (f64, f64) {
        let thermal = u - self.v;
        (thermal * self.inv_cv, self.excess / thermal)
    }
}
