//! Kick and drift of velocity Verlet, shared by every dynamics (eq 84; `fix nve`), and
//! the two halves of the modified velocity Verlet of the many-body, eDPD and SPH styles.

use crate::error::StepError;
use crate::system::System;
use gendpde_engine::Particles;

/// p_i += h f_i for owned particles.
pub fn kick(sys: &mut System, h: f64) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.p[i][c] += h * s.f[i][c];
        }
    }
}

/// r_i += h p_i/m_i for owned particles; see [`finite_positions`].
pub fn drift(sys: &mut System, h: f64) -> Result<(), StepError> {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let k = h / s.mass[i];
        for c in 0..3 {
            s.r[i][c] += k * s.p[i][c];
        }
    }
    finite_positions(sys)
}

/// The owned particle of lowest tag whose position is not finite, if any (the rank
/// carries on so that the others do not wait).
pub fn finite_positions(sys: &System) -> Result<(), StepError> {
    let s = &sys.store;
    let bad = (0..s.nlocal).filter(|&i| !s.r[i].iter().all(|x| x.is_finite())).min_by_key(|&i| s.tag[i]);
    bad.map_or(Ok(()), |i| Err(StepError::state(s, i, sys.clock.step, "position or momentum is not finite")))
}

/// The first half of the modified velocity Verlet of Groot and Warren (J. Chem. Phys.
/// 107, 4423 (1997); LAMMPS's fix mvv/dpd, mvv/edpd, and fix sph with lambda = 1)
/// for owned particles: vest = p + dt/2 f; r += dt vest/m; p += lambda dt f, the estimate
/// the forces then read (vest travels with a particle that changes rank). `carried(s, i)`
/// advances, for each particle, what the model integrates besides (eDPD's T, fix sph's
/// rho); see [`finite_positions`].
#[inline(always)]
pub fn mvv_first_half(sys: &mut System, dt: f64, lambda: f64, mut carried: impl FnMut(&mut Particles, usize)) -> Result<(), StepError> {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.vest[i][c] = s.p[i][c] + 0.5 * dt * s.f[i][c];
            s.r[i][c] += dt * s.vest[i][c] / s.mass[i];
            s.p[i][c] += lambda * dt * s.f[i][c];
        }
        carried(s, i);
    }
    finite_positions(sys)
}

/// The second half of [`mvv_first_half`], after the forces: p = vest + dt/2 f, then
/// `carried(s, i)` for each owned particle.
#[inline(always)]
pub fn mvv_second_half(sys: &mut System, dt: f64, mut carried: impl FnMut(&mut Particles, usize)) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        for c in 0..3 {
            s.p[i][c] = s.vest[i][c] + 0.5 * dt * s.f[i][c];
        }
        carried(s, i);
    }
}
