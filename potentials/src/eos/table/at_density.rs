//! The table at one density for the Shardlow sweep's refreshes: [`TableAt`] keeps the
//! cubics u(t) of the cells around a particle's theta (n is fixed during a sweep).

use super::{cubic, newton, slope, unit, value, within, Tabulated};
use crate::eos::{AtDensity, AtN, Before, Eos, FixedDensity};

impl<E: Eos> FixedDensity for Tabulated<E> {
    type At<'a> = TableAt<'a, E> where E: 'a;
    #[inline]
    fn at_density(&self, n: f64) -> TableAt<'_, E> {
        self.at_state(n, f64::NAN)
    }
    /// With the cubics u(t) of theta's cell and its two neighbours at this density.
    #[inline]
    fn at_state(&self, n: f64, theta: f64) -> TableAt<'_, E> {
        let mut at = TableAt {
            full: AtN { eos: self, n },
            nodes: [f64::NAN; 4],
            c: [[f64::NAN; 4]; 3],
            p1: [f64::NAN; 3],
            inv_h: [f64::NAN; 3],
            tol: [f64::NAN; 3],
        };
        if let Some(l) = self.locate(theta, n) {
            let m = self.nt - 1;
            let first = l.i.saturating_sub(1).min(m.saturating_sub(3));
            for k in 0..3.min(m) {
                let i = first + k;
                let c = cubic(&self.pu[self.cell(i, l.j)], l.s);
                (at.c[k], at.p1[k], at.inv_h[k], at.tol[k]) = (c, value(&c, 1.0), self.inv_h[i], self.newton_tol(i));
                (at.nodes[k], at.nodes[k + 1]) = (self.thetas[i], self.thetas[i + 1]);
            }
        }
        at
    }
}

/// A table at one density with the cubics u(t) of three adjacent cells (nodes[k] <= theta
/// <= nodes[k + 1]) at hand: a solve whose guess lies inside one of them (between its
/// nodes) and whose u lies between that cell's end values (most of the sweep's refreshes)
/// skips the cell lookup and the cubic's assembly, and does the rest of
/// [`Tabulated::solve`]'s operations (the same bits); others go through [`Eos::theta_cv`].
#[derive(Debug)]
pub struct TableAt<'a, E: Eos> {
    full: AtN<'a, Tabulated<E>>,
    nodes: [f64; 4],
    c: [[f64; 4]; 3],
    /// u at each cell's upper end, value(c, 1).
    p1: [f64; 3],
    inv_h: [f64; 3],
    /// [`Tabulated::newton_tol`] of each cell.
    tol: [f64; 3],
}

impl<E: Eos> Clone for TableAt<'_, E> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<E: Eos> Copy for TableAt<'_, E> {}

impl<E: Eos> TableAt<'_, E> {
    /// The cell k at hand whose nodes bracket theta (a < theta < b), its nodes a, b and
    /// cubic, when u lies between the cell's end values; else None (the full lookup).
    #[inline(always)]
    fn cell_of(&self, theta: f64, u: f64) -> Option<(usize, f64, f64, &[f64; 4])> {
        let x = &self.nodes;
        let k = if theta < x[1] { 0 } else if theta < x[2] { 1 } else { 2 };
        let (a, b, c) = (x[k], x[k + 1], &self.c[k]);
        (a < theta && theta < b && c[0] < u && u < self.p1[k]).then_some((k, a, b, c))
    }

    /// theta and C_V of cell k at the root t.
    #[inline(always)]
    fn at_root(&self, k: usize, (a, b, c): (f64, f64, &[f64; 4]), t: f64) -> (f64, f64) {
        (within(a + t * (b - a), a, b), slope(c, t) * self.inv_h[k])
    }

    /// theta and C_V from the cells at hand, None when the solve needs the full lookup.
    #[inline(always)]
    pub(super) fn in_cell(&self, u: f64, guess: f64) -> Option<(f64, f64)> {
        let (k, a, b, c) = self.cell_of(guess, u)?;
        let t0 = unit((guess - a) * self.inv_h[k]);
        let (r, d1, d2) = (value(c, t0) - u, slope(c, t0), 6.0 * c[3] * t0 + 2.0 * c[2]);
        Some(self.at_root(k, (a, b, c), first_newton(c, u, t0, (r, d1, d2), self.tol[k])))
    }

    /// theta and C_V after the energy moved from `before.u` (at `before.theta`) to `u`,
    /// from the cells at hand, None when the solve needs the full lookup. The Newton step
    /// starts from t0 = t_b + s du (t_b the local coordinate of theta before, s = 1/c'(t_b),
    /// taken from 1/tau before where `inv_tau`, without a division) with the residual
    /// c(t0) - u and the slope c'(t0) written as polynomials in du = u - u_b whose
    /// coefficients (the cubic's Taylor coefficients at t_b) do not depend on u: they are
    /// ready before the pair update ends, and a refresh waits for du through three
    /// multiply-adds instead of the guess, t0 and the cubic's value (the sweep's updates
    /// of one particle form a chain). The root of [`TableAt::in_cell`] up to round-off.
    #[inline(always)]
    pub(super) fn in_cell_after(&self, before: Before, u: f64, inv_tau: bool) -> Option<(f64, f64)> {
        let (k, a, b, c) = self.cell_of(before.theta, u)?;
        let tb = (before.theta - a) * self.inv_h[k];
        // c(tb + x) = c(tb) + e1 x + e2 x^2 + c3 x^3, x = s du
        let (e1, e2) = (slope(c, tb), 3.0 * c[3] * tb + c[2]);
        // 1/c'(tb) = h/C_V, 1/C_V = (1 - theta/tau)/k_B (eqs 19, 23)
        let s = if inv_tau { (1.0 - before.theta * before.inv_tau) * self.full.eos.inv_kb * self.inv_h[k] } else { 1.0 / e1 };
        let p0 = value(c, tb) - before.u;
        let (p1, p2, p3) = (e1 * s - 1.0, e2 * s * s, c[3] * s * s * s);
        let du = u - before.u;
        let x = s * du;
        let r = ((p3 * du + p2) * du + p1) * du + p0;
        let (d1, d2) = ((3.0 * c[3] * x + 2.0 * e2) * x + e1, 6.0 * c[3] * x + 2.0 * e2);
        Some(self.at_root(k, (a, b, c), first_newton(c, u, tb + x, (r, d1, d2), self.tol[k])))
    }

    /// [`AtDensity::after_pair`] of one particle: from the state before in its cell, else
    /// (u beyond that cell: in a neighbouring cell at hand, or the full lookup) from the
    /// first-order guess where 1/tau is kept, else from theta before.
    #[inline(always)]
    fn after(&self, before: Before, u: f64, inv_tau: bool) -> (f64, f64) {
        match (self.in_cell_after(before, u, inv_tau), inv_tau) {
            (Some((theta, cv)), true) => (theta, self.full.eos.inv_tau(theta, cv)),
            (Some((theta, _)), false) => (theta, 0.0),
            (None, true) => self.theta_inv_tau(u, self.guess_after(before.theta, before.inv_tau, u - before.u)),
            (None, false) => (self.theta(u, before.theta), 0.0),
        }
    }
}

/// The root of the cubic c(t) = u from t0 with c(t0) - u = r, c'(t0) = d1, c''(t0) = d2:
/// the first Newton step inline, which usually ends the solve (the start is close), else
/// [`newton`]'s iteration from t0 (limited to [0, 1]).
#[inline(always)]
fn first_newton(c: &[f64; 4], u: f64, t0: f64, (r, d1, d2): (f64, f64, f64), tol: f64) -> f64 {
    let dt = r / d1;
    let next = t0 - dt;
    // (r = 0 gives next = t0 and passes, as in `newton`)
    if (0.0..=1.0).contains(&next) && (d2 * dt * dt).abs() <= 2.0 * tol * d1 {
        next
    } else {
        newton(c, u, unit(t0), tol)
    }
}

impl<E: Eos> AtDensity for TableAt<'_, E> {
    #[inline(always)]
    fn theta(&self, u: f64, guess: f64) -> f64 {
        match self.in_cell(u, guess) {
            Some((theta, _)) => theta,
            None => self.full.theta(u, guess),
        }
    }
    #[inline(always)]
    fn theta_inv_tau(&self, u: f64, guess: f64) -> (f64, f64) {
        match self.in_cell(u, guess) {
            Some((theta, cv)) => (theta, self.full.eos.inv_tau(theta, cv)),
            None => self.full.theta_inv_tau(u, guess),
        }
    }
    #[inline(always)]
    fn guess_after(&self, theta: f64, inv_tau: f64, du: f64) -> f64 {
        self.full.guess_after(theta, inv_tau, du)
    }
    /// Each particle from its state before ([`TableAt::in_cell_after`]).
    #[inline(always)]
    fn after_pair(&self, b: &Self, before: [Before; 2], u: [f64; 2], inv_tau: bool) -> [(f64, f64); 2] {
        [self.after(before[0], u[0], inv_tau), b.after(before[1], u[1], inv_tau)]
    }
}
