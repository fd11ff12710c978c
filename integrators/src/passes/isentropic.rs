//! The isentropic alternative of the reversible step (SPEC section 6): each particle keeps
//! the entropy s_i = s(u_i, n_i) it has at the start of the step, and after the density
//! pass u_i = u(s_i, n_i(t + dt)). Then sum_i u(s_i, n_i(r)) is a potential energy of the
//! positions alone, the conservative force is minus its gradient (eqs 50-51 with
//! pi/n^2 = du/dn at fixed s), and the velocity-Verlet step is symplectic: its energy
//! error stays O(dt^2) and bounded, with no work term to split.
//!
//! s_i has to travel with a particle that changes rank in the list rebuild between the
//! drift and the density pass. The theta field carries it there ([`hold`]): theta is a
//! function of (u, n) that [`release`] sets again, before anything reads it.
#![allow(clippy::approx_constant)] // 1.4142 is the vdW b of the 2019 paper, not sqrt 2

use crate::error::{lowest, StepError};
use crate::passes::many_body::density_of;
use crate::passes::species::Species;
use crate::system::System;
use gendpde_potentials::eos::Lth;
use gendpde_potentials::{Eos, EosError, LennardJones, LinearTheta, Tabulated, ISOLATED_DENSITY};

/// An EOS whose energy can be evaluated at a given entropy.
pub trait FixedEntropy: Eos {
    /// (u, theta) with s(u, n) = s; `u0` is the particle's energy before the move (a
    /// starting point). None where the EOS has no entropy.
    fn at_entropy(&self, s: f64, n: f64, u0: f64) -> Option<(f64, f64)>;
}

/// u = C_V theta + V(n) and s = C_V ln theta + h(n) with constant C_V (2019 paper eqs
/// 43-46; argon paper eqs 52-56): theta = exp((s - h(n))/C_V) with h(n) the entropy at
/// theta = 1, which is the first step of [`newton`] from theta = 1, exact here.
fn linear_in_theta<E: Eos>(eos: &E, s: f64, n: f64) -> Option<(f64, f64)> {
    let h = eos.entropy(eos.u(1.0, n), n)?;
    let theta = ((s - h) / eos.cv(1.0, n)).exp();
    (theta > 0.0 && theta.is_finite()).then(|| (eos.u(theta, n), theta))
}

/// Newton's method on g(x) = s(u(e^x, n), n) - s in x = ln theta, with dg/dx = C_V
/// (ds/du = 1/theta), from theta(u0, n) (or theta = 1 when u0 lies below the ground
/// state at n). g increases with x; a step that leaves the bracket of the iterates so far
/// is replaced by bisection.
fn newton<E: Eos>(eos: &E, s: f64, n: f64, u0: f64) -> Option<(f64, f64)> {
    let start = eos.theta(u0, n, f64::NAN);
    let mut x = if start > 0.0 && start.is_finite() { start.ln() } else { 0.0 };
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for _ in 0..100 {
        let theta = x.exp();
        let u = eos.u(theta, n);
        let g = eos.entropy(u, n)? - s;
        if g < 0.0 { lo = x } else { hi = x }
        let step = -g / eos.cv(theta, n);
        if !step.is_finite() {
            return None;
        }
        if step.abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0) {
            return Some((u, theta));
        }
        let next = x + step;
        x = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
    }
    None
}

impl FixedEntropy for LinearTheta {
    fn at_entropy(&self, s: f64, n: f64, _: f64) -> Option<(f64, f64)> {
        linear_in_theta(self, s, n)
    }
}

impl FixedEntropy for Lth {
    fn at_entropy(&self, s: f64, n: f64, _: f64) -> Option<(f64, f64)> {
        linear_in_theta(self, s, n)
    }
}

impl FixedEntropy for LennardJones {
    fn at_entropy(&self, s: f64, n: f64, u0: f64) -> Option<(f64, f64)> {
        newton(self, s, n, u0)
    }
}

/// A table's entropy is its inner model's (potentials/src/eos/table.rs), so u(s, n) is
/// solved for, whatever the inner model.
impl<E: Eos> FixedEntropy for Tabulated<E> {
    fn at_entropy(&self, s: f64, n: f64, u0: f64) -> Option<(f64, f64)> {
        newton(self, s, n, u0)
    }
}

/// theta_i := s(u_i, n_i) for owned particles, at the densities of the start of the step.
pub fn hold<E: Eos>(eos: &Species<E>, sys: &mut System) -> Result<(), StepError> {
    let step = sys.clock.step;
    let s = &mut sys.store;
    let mut first = Ok(());
    for i in 0..s.nlocal {
        let n = density_of(s, i).max(ISOLATED_DENSITY);
        match eos.of(s.kind[i]).entropy(s.u[i], n) {
            Some(entropy) => s.theta[i] = entropy,
            None => {
                let e = EosError::NonPositiveTheta { u: s.u[i], n, theta: s.theta[i] };
                first = lowest(first, Err(StepError::eos(s, i, step, e)));
            }
        }
    }
    first
}

/// u_i := u(s_i, n_i) and theta_i at the new densities, with s_i from [`hold`].
pub fn release<E: FixedEntropy>(eos: &Species<E>, sys: &mut System) -> Result<(), StepError> {
    let step = sys.clock.step;
    let s = &mut sys.store;
    let mut first = Ok(());
    for i in 0..s.nlocal {
        let n = density_of(s, i).max(ISOLATED_DENSITY);
        match eos.of(s.kind[i]).at_entropy(s.theta[i], n, s.u[i]) {
            Some((u, theta)) => (s.u[i], s.theta[i]) = (u, theta),
            None => {
                let e = StepError::state(s, i, step, "no internal energy has the particle's entropy at its new density");
                first = lowest(first, Err(e));
            }
        }
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;
    use gendpde_potentials::TableGrid;

    /// u(s, n') at the entropy of (theta, n): s is recovered, and the closed form of the
    /// linear family agrees with the Newton solve.
    #[test]
    fn energy_at_entropy_inverts_the_entropy() {
        let lj = LennardJones::new(60.0);
        let vdw = LinearTheta::vdw_excess(60.0, 2.4682, 1.4142);
        let lth = Lth::new(11.008, 29.345, 1.0112, 0.11606, 0.011054, 1.0);
        let table = Tabulated::new(LennardJones::new(60.0), TableGrid { theta: (0.5, 5.0, 61), n: (0.05, 0.85, 65) }).unwrap();
        for &(theta, n, n2) in &[(1.3, 0.2, 0.23), (2.0, 0.6, 0.55), (0.9, 0.4, 0.41)] {
            for (name, eos, u0) in [("lj", &lj as &dyn Check, lj.u(theta, n)), ("table", &table, table.u(theta, n))] {
                let s = eos.s(u0, n);
                let (u, t) = eos.solve(s, n2, u0);
                assert!((eos.s(u, n2) - s).abs() < 1e-12 * s.abs().max(1.0), "{name}: s {} vs {s}", eos.s(u, n2));
                assert!((eos.t(u, n2) - t).abs() < 1e-12 * t, "{name}: theta");
            }
            let s = vdw.entropy(vdw.u(theta, n), n).unwrap();
            let closed = vdw.at_entropy(s, n2, 0.0).unwrap();
            let solved = newton(&vdw, s, n2, vdw.u(theta, n)).unwrap();
            assert!((closed.0 - solved.0).abs() < 1e-13 * closed.0.abs() && (closed.1 - solved.1).abs() < 1e-13 * closed.1);
            assert!((vdw.entropy(closed.0, n2).unwrap() - s).abs() < 1e-13 * s.abs());
        }
        for &(theta, n, n2) in &[(0.011, 1.0, 1.01), (0.012, 0.95, 0.9)] {
            let s = lth.entropy(lth.u(theta, n), n).unwrap();
            let (u, t) = lth.at_entropy(s, n2, 0.0).unwrap();
            assert!((lth.entropy(u, n2).unwrap() - s).abs() < 1e-13 * s.abs());
            assert!((lth.theta(u, n2, t) - t).abs() < 1e-12 * t);
        }
    }

    /// Object-safe view of the EOS under test.
    trait Check {
        fn s(&self, u: f64, n: f64) -> f64;
        fn t(&self, u: f64, n: f64) -> f64;
        fn solve(&self, s: f64, n: f64, u0: f64) -> (f64, f64);
    }

    impl<E: FixedEntropy> Check for E {
        fn s(&self, u: f64, n: f64) -> f64 {
            self.entropy(u, n).unwrap()
        }
        fn t(&self, u: f64, n: f64) -> f64 {
            self.theta(u, n, f64::NAN)
        }
        fn solve(&self, s: f64, n: f64, u0: f64) -> (f64, f64) {
            self.at_entropy(s, n, u0).unwrap()
        }
    }
}
