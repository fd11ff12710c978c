//! Tait's equation of state for water in isothermal form, as LAMMPS's SPH and DPD-SMOOTH
//! packages use it: P(rho) = B [(rho/rho0)^7 - 1], B = c0^2 rho0 / 7 (so that
//! dP/drho = c0^2 at rho0).
//!
//! It does not go through [`super::Eos`]: that trait maps a particle's internal energy
//! and number density to its temperature and pi/n^2, while isothermal Tait water has no
//! energy variable, only the mass density that the SPH continuity equation carries.

/// One particle type's Tait water.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tait {
    /// The reference density rho0.
    pub rho0: f64,
    /// B = c0^2 rho0 / 7.
    pub b: f64,
}

impl Tait {
    /// Tait water of reference density `rho0` and sound speed `c0`.
    pub fn new(rho0: f64, c0: f64) -> Self {
        Self { rho0, b: c0 * c0 * rho0 / 7.0 }
    }

    /// P(rho) / rho^2, the factor the SPH pressure force takes from each particle (with
    /// LAMMPS's operation order).
    #[inline(always)]
    pub fn p_over_rho2(&self, rho: f64) -> f64 {
        let x = rho / self.rho0;
        let x3 = x * x * x;
        self.b * (x3 * x3 * x - 1.0) / (rho * rho)
    }
}

#[cfg(test)]
mod tests {
    use super::Tait;

    #[test]
    fn pressure_vanishes_at_rho0_and_its_slope_is_c0_squared() {
        let t = Tait::new(2.0, 3.0);
        assert_eq!(t.p_over_rho2(2.0), 0.0);
        let p = |rho: f64| t.p_over_rho2(rho) * rho * rho;
        let h = 1e-6;
        let slope = (p(2.0 + h) - p(2.0 - h)) / (2.0 * h);
        assert!((slope - 9.0).abs() < 1e-6, "dP/drho = {slope}");
    }
}
