//! The state of a `fix nph` barostat (what LAMMPS's FixNH keeps between steps and
//! writes to restart files) and its restart record; the dynamics is [`crate::passes::barostat`].

/// The state of a barostat: what LAMMPS writes to its restart files (omega, omega_dot, the
/// chain, V0, T0, h0^-1), the fixed point, and what the step derives from them.
#[derive(Clone, Debug, PartialEq)]
pub struct NphState {
    pub id: String,
    pub omega: [f64; 3],
    pub omega_dot: [f64; 3],
    pub etap: Vec<f64>,
    /// The chain velocities and one dummy 0 past the end (as LAMMPS).
    pub etap_dot: Vec<f64>,
    /// Reference volume and inverse cell lengths (0: not yet set).
    pub vol0: f64,
    pub h0_inv: [f64; 3],
    /// Reference temperature of the masses (0: not yet set).
    pub t0: f64,
    pub fixedpoint: [f64; 3],
    // derived at each set-up and step
    pub(crate) omega_mass: [f64; 3],
    pub(crate) etap_mass: Vec<f64>,
    pub(crate) etap_dotdot: Vec<f64>,
    pub(crate) t_current: f64,
    pub(crate) tdof: f64,
    /// sum m v_d^2 over the barostatted dimensions, fresh at every pressure (aniso MTK).
    pub(crate) mvv: f64,
    pub(crate) natoms: f64,
    pub(crate) p_current: [f64; 3],
    pub(crate) p_target: [f64; 3],
    pub(crate) p_hydro: f64,
    pub(crate) sigma: [f64; 3],
    pub(crate) mtk_term2: f64,
    /// First and last step of the run (the ramp from Pstart to Pstop).
    pub(crate) span: (u64, u64),
}

/// Words of the restart record before the chain: pchain, omega, omega_dot, vol0, t0,
/// h0_inv, fixedpoint.
const HEAD: usize = 1 + 3 + 3 + 1 + 1 + 3 + 3;

impl NphState {
    /// A barostat at rest with a chain of `pchain` links, dilating about `fixedpoint`.
    pub fn new(id: &str, pchain: usize, fixedpoint: [f64; 3]) -> Self {
        Self {
            id: id.to_string(),
            omega: [0.0; 3],
            omega_dot: [0.0; 3],
            etap: vec![0.0; pchain],
            etap_dot: vec![0.0; pchain + 1],
            vol0: 0.0,
            h0_inv: [0.0; 3],
            t0: 0.0,
            fixedpoint,
            omega_mass: [0.0; 3],
            etap_mass: vec![0.0; pchain],
            etap_dotdot: vec![0.0; pchain],
            t_current: 0.0,
            tdof: 0.0,
            mvv: 0.0,
            natoms: 0.0,
            p_current: [0.0; 3],
            p_target: [0.0; 3],
            p_hydro: 0.0,
            sigma: [0.0; 3],
            mtk_term2: 0.0,
            span: (0, 0),
        }
    }

    /// The restart record (see [`Self::from_record`]).
    pub fn record(&self) -> Vec<f64> {
        let mut v = vec![self.etap.len() as f64];
        v.extend(self.omega);
        v.extend(self.omega_dot);
        v.extend([self.vol0, self.t0]);
        v.extend(self.h0_inv);
        v.extend(self.fixedpoint);
        v.extend(&self.etap);
        v.extend(&self.etap_dot[..self.etap.len()]);
        v
    }

    /// The state of a restart record; None if it is not one.
    pub fn from_record(id: &str, v: &[f64]) -> Option<Self> {
        let m = *v.first()?;
        if !(m >= 0.0 && m.fract() == 0.0 && v.len() == HEAD + 2 * m as usize) {
            return None;
        }
        let m = m as usize;
        let three = |k: usize| [v[k], v[k + 1], v[k + 2]];
        let mut s = Self::new(id, m, three(12));
        (s.omega, s.omega_dot, s.vol0, s.t0, s.h0_inv) = (three(1), three(4), v[7], v[8], three(9));
        s.etap.copy_from_slice(&v[HEAD..HEAD + m]);
        s.etap_dot[..m].copy_from_slice(&v[HEAD + m..]);
        Some(s)
    }
}


#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_reads_back_and_a_damaged_one_is_refused() {
        let mut s = NphState::new("0", 3, [1.0, 2.0, 3.0]);
        (s.omega, s.omega_dot, s.vol0, s.t0, s.h0_inv) = ([0.1, 0.2, 0.3], [-1e-3, 2e-3, 3e-3], 732.5, 1.25, [0.11, 0.12, 0.13]);
        s.etap.copy_from_slice(&[0.5, 0.6, 0.7]);
        s.etap_dot[..3].copy_from_slice(&[-0.5, -0.6, -0.7]);
        let back = NphState::from_record("0", &s.record()).unwrap();
        assert_eq!(back, NphState { etap_mass: back.etap_mass.clone(), ..s.clone() });
        let r = s.record();
        assert!(NphState::from_record("0", &r[..r.len() - 1]).is_none());
        assert!(NphState::from_record("0", &[]).is_none());
        assert!(NphState::from_record("0", &[f64::NAN]).is_none());
        assert!(NphState::from_record("0", &[-1.0]).is_none());
    }
}
