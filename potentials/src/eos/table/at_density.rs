//! The table at one density for the Shardlow sweep's refreshes: [`TableAt`] keeps the
//! cubics u(t) of the cells around a particle's theta (n is fixed during a sweep).

use super::{cubic, newton, slope, unit, value, within, Tabulated};
use crate::eos::{AtDensity, AtN, Eos, FixedDensity};

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
    /// theta and C_V from the cells at hand, None when the solve needs the full lookup.
    #[inline(always)]
    pub(super) fn in_cell(&self, u: f64, guess: f64) -> Option<(f64, f64)> {
        let x = &self.nodes;
        let k = if guess < x[1] { 0 } else if guess < x[2] { 1 } else { 2 };
        let (a, b, c) = (x[k], x[k + 1], &self.c[k]);
        if !(a < guess && guess < b && c[0] < u && u < self.p1[k]) {
            return None;
        }
        let t0 = unit((guess - a) * self.inv_h[k]);
        // newton's first iteration, which usually ends it (the guess is close), inline
        let (r, d1) = (value(c, t0) - u, slope(c, t0));
        let dt = r / d1;
        let next = t0 - dt;
        let d2 = 6.0 * c[3] * t0 + 2.0 * c[2];
        let t = if r != 0.0 && (0.0..=1.0).contains(&next) && (d2 * dt * dt).abs() <= 2.0 * self.tol[k] * d1 {
            next
        } else {
            newton(c, u, t0, self.tol[k])
        };
        Some((within(a + t * (b - a), a, b), slope(c, t) * self.inv_h[k]))
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
}
