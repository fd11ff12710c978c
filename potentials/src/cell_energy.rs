//! Fundamental relations E(M, S, V) of a fluid cell whose mass, entropy and volume all
//! change (Serrano & Español, eqs 64, 66, 157-165), for the Voronoi fluid particles.
//!
//! Units are the paper's reduced van der Waals units (eq 160) in D = 3: volumes in 3b,
//! masses in molecules (m_0), energies in 8a/(27b), entropies in k_B, so k_B = 1, the
//! reduced density is n~ = M/V, s~ = S/V, the energy density eps~ = E/V, the temperature
//! T~ and the chemical potential mu~ (per molecule) are the paper's, and the pressure
//! p = -dE/dV is (3/8) P~ of eq 162.

use std::fmt;

/// Everything the equations of motion read from one cell's fundamental relation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CellState {
    /// E(M, S, V).
    pub energy: f64,
    /// T = dE/dS (eq 66).
    pub temperature: f64,
    /// p = -dE/dV (eq 66).
    pub pressure: f64,
    /// mu = dE/dM (eq 66).
    pub chemical: f64,
    /// C = T (dT/dS)^-1 at fixed M and V (eq 84), in units of k_B.
    pub heat_capacity: f64,
}

/// A cell state outside the relation's domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellStateError {
    pub m: f64,
    pub s: f64,
    pub v: f64,
    pub what: &'static str,
}

impl fmt::Display for CellStateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (M = {}, S = {}, V = {})", self.what, self.m, self.s, self.v)
    }
}

impl std::error::Error for CellStateError {}

/// A fundamental relation E(M, S, V), homogeneous of degree one: E = V eps(M/V, S/V).
pub trait CellEnergy: Send + Sync {
    /// E, T, p, mu and C of a cell of mass `m`, entropy `s` and volume `v`.
    fn state(&self, m: f64, s: f64, v: f64) -> Result<CellState, CellStateError>;
    /// The entropy at temperature `t` (the inverse of T(M, S, V) in S).
    fn entropy(&self, m: f64, v: f64, t: f64) -> f64;
}

/// Eq 162's constant c (water, D = 3, with the printed h, which is h-bar; see docs/models/voronoi.md).
pub const WATER_C: f64 = 4.836e-5;

fn domain(m: f64, s: f64, v: f64, n_max: f64) -> Result<(f64, f64), CellStateError> {
    let err = |what| Err(CellStateError { m, s, v, what });
    if !(m.is_finite() && s.is_finite() && v.is_finite()) {
        return err("cell state is not finite");
    }
    if !(m > 0.0 && v > 0.0) {
        return err("cell mass and volume must be positive");
    }
    let n = m / v;
    if n >= n_max {
        return err("cell density at or above the close packing 3 (1/b)");
    }
    Ok((n, s / v))
}

/// Van der Waals fluid, eqs 157-162 in reduced units (D = 3):
/// T~ = c exp{(2/3)[s~/n~ - 5/2 + ln(n~/(3 - n~))]}, eps~ = (3/2) T~ n~ - (9/8) n~^2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VdwCell {
    pub c: f64,
}

impl CellEnergy for VdwCell {
    fn state(&self, m: f64, s: f64, v: f64) -> Result<CellState, CellStateError> {
        let (n, sd) = domain(m, s, v, 3.0)?;
        let x = (n / (3.0 - n)).ln();
        let t = self.c * ((2.0 / 3.0) * (sd / n - 2.5 + x)).exp();
        let eps = 1.5 * t * n - 1.125 * n * n;
        Ok(CellState {
            energy: v * eps,
            temperature: t,
            pressure: 3.0 * t * n / (3.0 - n) - 1.125 * n * n,
            chemical: t * (x + n / (3.0 - n)) - 2.25 * n - 1.5 * t * (t / self.c).ln(),
            heat_capacity: 1.5 * m,
        })
    }

    fn entropy(&self, m: f64, v: f64, t: f64) -> f64 {
        vdw_entropy(self.c, m, v, t)
    }
}

/// Ideal gas in the same units (the a, b -> 0 limit of eq 159 at fixed c):
/// T = c n^(2/3) exp{(2/3)(s/n - 5/2)}, eps = (3/2) n T, p = n T, mu = (5/2) T - T s/n.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IdealCell {
    pub c: f64,
}

impl CellEnergy for IdealCell {
    fn state(&self, m: f64, s: f64, v: f64) -> Result<CellState, CellStateError> {
        let (n, sd) = domain(m, s, v, f64::INFINITY)?;
        let t = self.c * ((2.0 / 3.0) * (sd / n - 2.5 + n.ln())).exp();
        Ok(CellState {
            energy: v * 1.5 * n * t,
            temperature: t,
            pressure: n * t,
            chemical: 2.5 * t - t * sd / n,
            heat_capacity: 1.5 * m,
        })
    }

    fn entropy(&self, m: f64, v: f64, t: f64) -> f64 {
        m * (1.5 * (t / self.c).ln() - (m / v).ln() + 2.5)
    }
}

impl<E: CellEnergy + ?Sized> CellEnergy for &E {
    fn state(&self, m: f64, s: f64, v: f64) -> Result<CellState, CellStateError> {
        (**self).state(m, s, v)
    }

    fn entropy(&self, m: f64, v: f64, t: f64) -> f64 {
        (**self).entropy(m, v, t)
    }
}

/// Entropy of a vdW cell at reduced density n~ and temperature T~ (eq 162 inverted):
/// S = V n~ [(3/2) ln(T~/c) + 5/2 - ln(n~/(3 - n~))].
pub fn vdw_entropy(c: f64, m: f64, v: f64, t: f64) -> f64 {
    let n = m / v;
    m * (1.5 * (t / c).ln() + 2.5 - (n / (3.0 - n)).ln())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T, p, mu and C against central differences of E(M, S, V).
    fn check_derivatives<E: CellEnergy>(e: &E, m: f64, s: f64, v: f64) {
        let st = e.state(m, s, v).unwrap();
        let en = |m, s, v| e.state(m, s, v).unwrap().energy;
        let h = 1e-5;
        let d = |f: &dyn Fn(f64) -> f64, x: f64| (f(x * (1.0 + h)) - f(x * (1.0 - h))) / (2.0 * h * x);
        let t = d(&|s| en(m, s, v), s);
        let p = -d(&|v| en(m, s, v), v);
        let mu = d(&|m| en(m, s, v), m);
        let dt = d(&|s| e.state(m, s, v).unwrap().temperature, s);
        for (name, a, b) in [("T", st.temperature, t), ("p", st.pressure, p), ("mu", st.chemical, mu), ("C", st.heat_capacity, st.temperature / dt)] {
            assert!((a - b).abs() < 1e-7 * (1.0 + a.abs()), "{name}: {a} vs finite difference {b}");
        }
        // Euler relation of a homogeneous E: E = T S - p V + mu M.
        let euler = st.temperature * s - st.pressure * v + st.chemical * m;
        assert!((euler - st.energy).abs() < 1e-10 * (1.0 + st.energy.abs()));
    }

    #[test]
    fn vdw_and_ideal_cells_derive_t_p_mu_c_from_e() {
        let vdw = VdwCell { c: WATER_C };
        for (n, t) in [(0.3197, 0.85), (1.8071, 0.85), (1.0, 1.0), (2.5, 2.0)] {
            let v = 20.0;
            let m = n * v;
            let s = vdw_entropy(WATER_C, m, v, t);
            let st = vdw.state(m, s, v).unwrap();
            assert!((st.temperature - t).abs() < 1e-12 * t);
            check_derivatives(&vdw, m, s, v);
        }
        let ideal = IdealCell { c: 1.0 };
        check_derivatives(&ideal, 3.0, 7.0, 2.0);
        let s = ideal.entropy(3.0, 2.0, 1.7);
        assert!((ideal.state(3.0, s, 2.0).unwrap().temperature - 1.7).abs() < 1e-12);
    }

    /// The paper's reduced equations of state at the critical point and on the
    /// coexistence line of T~ = 0.85 (reading notes, targets a and b).
    #[test]
    fn vdw_cell_has_the_critical_point_and_maxwell_pressures() {
        let vdw = VdwCell { c: WATER_C };
        let at = |n: f64, t: f64| vdw.state(n * 30.0, vdw_entropy(WATER_C, n * 30.0, 30.0, t), 30.0).unwrap();
        // P~ = (8/3) p: the critical point n~ = T~ = P~ = 1.
        assert!(((8.0 / 3.0) * at(1.0, 1.0).pressure - 1.0).abs() < 1e-12);
        let (g, l) = (at(0.3197, 0.85), at(1.8071, 0.85));
        assert!(((8.0 / 3.0) * g.pressure - 0.5045).abs() < 2e-4 && ((8.0 / 3.0) * l.pressure - 0.5045).abs() < 2e-4);
        assert!((g.chemical - l.chemical).abs() < 2e-3, "mu~ gas {} liquid {}", g.chemical, l.chemical);
    }

    #[test]
    fn states_outside_the_domain_are_errors() {
        let vdw = VdwCell { c: WATER_C };
        assert!(vdw.state(3.0, 1.0, 1.0).is_err());
        assert!(vdw.state(-1.0, 1.0, 1.0).is_err());
        assert!(vdw.state(1.0, f64::NAN, 1.0).is_err());
        assert!(IdealCell { c: 1.0 }.state(1.0, 1.0, 0.0).is_err());
    }
}
