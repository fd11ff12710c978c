//! A step that cannot continue, naming the particle and the state that failed. `step`
//! is the last completed step: the failure happened while advancing from it.

use gendpde_engine::Particles;
use gendpde_potentials::EosError;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub struct StepError {
    pub tag: u64,
    pub step: u64,
    pub u: f64,
    pub n: f64,
    pub theta: f64,
    pub what: String,
    /// The failure happened on another rank (which reports it).
    pub elsewhere: bool,
}

impl StepError {
    /// An EOS failure of particle `i`.
    pub fn eos(s: &Particles, i: usize, step: u64, e: EosError) -> Self {
        let (u, n, theta, what) = match e {
            EosError::NonPositiveTheta { u, n, theta } => {
                let what = if theta.is_finite() && u.is_finite() { "particle temperature is not positive" } else { "particle state is not finite" };
                (u, n, theta, what.to_string())
            }
            EosError::Outside { u, n, why } => (u, n, f64::NAN, why),
        };
        Self { tag: s.tag[i], step, u, n, theta, what, elsewhere: false }
    }

    /// Particle `i` reached a state the dynamics cannot continue from.
    pub fn state(s: &Particles, i: usize, step: u64, what: &str) -> Self {
        let n = s.n.get(i).copied().unwrap_or(f64::NAN);
        Self { tag: s.tag[i], step, u: s.u[i], n, theta: s.theta[i], what: what.into(), elsewhere: false }
    }

    /// This rank stops because another one failed.
    pub fn elsewhere(step: u64) -> Self {
        Self { tag: 0, step, u: f64::NAN, n: f64::NAN, theta: f64::NAN, what: "another rank failed".into(), elsewhere: true }
    }
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.elsewhere {
            return write!(f, "stopped after step {}: another rank failed (its message names the particle)", self.step);
        }
        write!(
            f,
            "particle {} after step {}: {} (u = {:.9e}, n = {:.9e}, theta = {:.9e}); \
             a smaller timestep, a larger C_V or weaker noise may help",
            self.tag, self.step, self.what, self.u, self.n, self.theta
        )
    }
}

impl std::error::Error for StepError {}
