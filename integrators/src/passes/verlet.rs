//! Kick and drift of velocity Verlet, shared by every dynamics (eq 84; `fix nve`).

use crate::error::StepError;
use crate::system::System;

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
