//! Kick and drift of the reversible velocity-Verlet step (eq 84).

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

/// r_i += h p_i/m_i for owned particles; a non-finite position is reported (the rank
/// carries on so that the others do not wait).
pub fn drift(sys: &mut System, h: f64) -> Result<(), StepError> {
    let s = &mut sys.store;
    let mut bad = None;
    for i in 0..s.nlocal {
        let k = h / s.mass[i];
        for c in 0..3 {
            s.r[i][c] += k * s.p[i][c];
        }
        if bad.is_none() && !s.r[i].iter().all(|x| x.is_finite()) {
            bad = Some(i);
        }
    }
    match bad {
        None => Ok(()),
        Some(i) => Err(StepError::state(s, i, sys.step, "position or momentum is not finite")),
    }
}
