//! `fix vv/euler`: the integrator of the argon paper (sec 4.1): velocity Verlet for r and
//! p under all pair forces (eqs 19-20: conservative eq 27, friction eq 28, random eq 29),
//! and a forward Euler step for u (eq 21) with the pair heat flow of the chosen model.
//!
//! One step from t, with F^C(t) and F_ij of the last force pass:
//!
//! 1. per pair, at the state of t: f^D_ij = -gamma_ij (v_ij . e) e, the random impulse
//!    dp^R_ij = sigma_ij xi_ij sqrt(dt) e (sigma^2 = k_B (theta_i + theta_j) gamma_ij), and
//!    the heat dt q_ij + sqrt(dt) alpha_ij xibar_ij (`HeatFlow`);
//! 2. eq 21: u_i += -1/2 sum_j v_ij . (f^C_ij dt + f^D_ij dt + dp^R_ij)
//!    - |sum_j dp^R_ij|^2 / (2 m_i) + sum_j (dt q_ij + sqrt(dt) alpha_ij xibar_ij);
//! 3. p_i += dt/2 (F^C_i + F^D_i) + dP^R_i/2;  r_i += dt p_i/m_i;  p_i += dP^R_i/2
//!    (the random force sigma xi/sqrt(dt) acts over the whole step, like the others, so
//!    each half kick carries half its impulse; the drift sees half of it);
//! 4. lists, n(t+dt), theta(u(t+dt), n(t+dt)), F^C(t+dt); F^D at r(t+dt) and the
//!    prediction p_i + dt/2 (F^C_i(t+dt) + F^D_i(t)) of p_i(t+dt);
//! 5. p_i += dt/2 (F^C_i + F^D_i), with F^D from step 4.
//!
//! The double sum of eq 21 (the Ito term) removes the kinetic energy the noise adds at
//! O(dt) per step. Measured (tests/it/styles/integrators_alt.rs): without friction and noise the
//! error of K + sum u is bounded and O(dt) (the work is taken at the velocities of t);
//! with them the mean drift per time unit is O(dt^2). The prediction of v(t+dt) matters:
//! with the momenta after step 3 alone (all the noise, half the deterministic kick) the
//! friction of step 5 lags, and the vdW scene of examples/vdw-equilibrium lost 1 % of
//! its energy per time unit at dt = 0.01, first order in dt; with it, 0.11 %. Momentum
//! is conserved pair by pair.
//!
//! Every pair term is evaluated in the orientation of increasing tag and added to the
//! owned particle(s) of the half list, so the sums do not depend on the decomposition
//! (see [`gendpde_engine::NeighborList`]); ghosts hold forwarded momenta, theta and 1/tau.

use crate::error::StepError;
use crate::passes::heat::HeatFlow;
use crate::passes::many_body::{kick, velocity};
use crate::passes::noise::Arithmetic;
use crate::rng::{stream, Normals};
use crate::passes::dissipation::Dissipation;
use crate::passes::sweep::temps;
use crate::system::System;
use crate::passes::verlet;
use gendpde_engine::{dot, sub, Particles, Vec3};

/// Pair (i, j) of the list in the orientation of increasing tag, with r_ij and v_ij.
#[inline(always)]
fn oriented(s: &Particles, i: u32, j: u32) -> (usize, usize, Vec3, Vec3) {
    let (i, j) = (i as usize, j as usize);
    let (i, j) = if s.tag[i] < s.tag[j] { (i, j) } else { (j, i) };
    (i, j, sub(s.r[i], s.r[j]), sub(velocity(s, i), velocity(s, j)))
}

/// gamma (1 - r/rc_D)^2 (eq 66), 0 beyond rc_D.
#[inline(always)]
fn friction_kernel(d: &Dissipation, r: f64) -> f64 {
    let w = (1.0 - r / d.rc_friction).max(0.0);
    d.gamma * w * w
}

/// Steps 1 and 2: the friction and random impulses of the step (kept in `sys.scratch.friction`
/// and `sys.scratch.noise` for the kicks) and the Euler update of u.
pub fn start<H: HeatFlow>(d: Option<&Dissipation>, kb: f64, sys: &mut System, dt: f64) {
    let sqrt_dt = dt.sqrt();
    let (step, normals) = (sys.noise_step(sys.clock.step), Normals::get());
    let rc = d.map_or(0.0, Dissipation::cutoff);
    let s = &mut sys.store;
    let n = s.nlocal;
    let (friction, noise, sums) = (&mut sys.scratch.friction, &mut sys.scratch.noise, &mut sys.scratch.pair_sums);
    for v in [&mut *friction, &mut *noise] {
        v.clear();
        v.resize(n, [0.0; 3]);
    }
    sums.clear();
    sums.resize(n, 0.0);
    // F_ij of the pairs the force pass visited (a subsequence of the list, in order)
    let mut forced = sys.scratch.active.iter().zip(&sys.scratch.pair_force).peekable();
    for &pair in &sys.nlist.pairs {
        let big_f = forced.next_if(|&(&p, _)| p == pair).map_or(0.0, |(_, &f)| f);
        let (i, j, dr, v) = oriented(s, pair[0], pair[1]);
        let r2 = dot(dr, dr);
        let near = r2 < rc * rc && r2 > 0.0;
        if big_f == 0.0 && !near {
            continue;
        }
        let mut work = dt * big_f * dot(v, dr);
        let mut heat = 0.0;
        if let Some(d) = d.filter(|_| near) {
            let r = r2.sqrt();
            let inv_r = 1.0 / r;
            let e = dr.map(|x| x * inv_r);
            let ve = dot(v, e);
            let gamma = friction_kernel(d, r);
            let (xi, xibar) = normals.pair(d.seed, step, s.tag[i], s.tag[j], stream::PAIR);
            let f_d = -gamma * ve;
            let dp = (kb * (s.theta[i] + s.theta[j]) * gamma).sqrt() * xi * sqrt_dt;
            work += ve * (f_d * dt + dp);
            kick(&mut friction[..n], i, j, f_d, e);
            kick(&mut noise[..n], i, j, dp, e);
            let wh = (1.0 - r / d.rc_heat).max(0.0);
            let kappa = d.kappa * wh * wh;
            if H::ACTIVE && kappa > 0.0 {
                let (q, alpha) = H::pair(kb, kappa, temps::<H, Arithmetic>(s, i), temps::<H, Arithmetic>(s, j));
                heat = dt * q + sqrt_dt * alpha * xibar;
            }
        }
        if i < n {
            sums[i] += heat - 0.5 * work;
        }
        if j < n {
            sums[j] += -heat - 0.5 * work;
        }
    }
    for i in 0..n {
        s.u[i] += sums[i] - 0.5 * dot(noise[i], noise[i]) / s.mass[i];
    }
}

/// Step 3: the first half kick with the whole random impulse around the drift. The
/// momenta after it are kept in `vest` (which travels with a particle that changes rank
/// at the list rebuild), and p becomes vest + dt/2 F^D(t), the part of the prediction of
/// step 4 that is known before the particles move.
pub fn first_half(sys: &mut System, dt: f64) -> Result<(), StepError> {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.p[i][c] += 0.5 * dt * (s.f[i][c] + sys.scratch.friction[i][c]) + 0.5 * sys.scratch.noise[i][c];
        }
    }
    let drifted = verlet::drift(sys, dt);
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.vest[i][c] = s.p[i][c] + 0.5 * sys.scratch.noise[i][c];
            s.p[i][c] = s.vest[i][c] + 0.5 * dt * sys.scratch.friction[i][c];
        }
    }
    drifted
}

/// F^D_i at the current positions and momenta (ghosts forwarded) into `sys.scratch.friction`.
pub fn friction(d: Option<&Dissipation>, sys: &mut System) {
    let s = &sys.store;
    let n = s.nlocal;
    let friction = &mut sys.scratch.friction;
    friction.clear();
    friction.resize(n, [0.0; 3]);
    let Some(d) = d.filter(|d| d.gamma > 0.0) else { return };
    let rc2 = d.rc_friction * d.rc_friction;
    for &[i, j] in &sys.nlist.pairs {
        let (i, j, dr, v) = oriented(s, i, j);
        let r2 = dot(dr, dr);
        if r2 < rc2 && r2 > 0.0 {
            let r = r2.sqrt();
            let inv_r = 1.0 / r;
            let e = dr.map(|x| x * inv_r);
            kick(&mut friction[..n], i, j, -friction_kernel(d, r) * dot(v, e), e);
        }
    }
}

/// Step 5: p_i = vest_i + dt/2 (F^C_i + F^D_i) with the friction at the prediction.
pub fn second_half(sys: &mut System, dt: f64) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.p[i][c] = s.vest[i][c] + 0.5 * dt * (s.f[i][c] + sys.scratch.friction[i][c]);
        }
    }
}
