//! Lennard-Jones fluid EOS of Kolafa and Nezbeda, Fluid Phase Equilib. 100, 1 (1994)
//! (2019 paper, appendix A.3, eqs 104-108; eq 107 is misprinted there, the form used here
//! is the one of the project's physics spec, SPEC.md sec 3). Reduced LJ units, k_B = 1.
//!
//! Residual Helmholtz energy per particle, with eta = (pi/6) n d(theta)^3 (eq 104):
//!
//! f_res = theta [A_HS(eta) + n dB2(theta) e^{-gamma_BH n^2}] + sum_ij C_ij theta^{i/2} n^j,
//! A_HS(eta) = (5/3) ln(1 - eta) + eta (34 - 33 eta + 4 eta^2) / (6 (1 - eta)^2)   (eq 106),
//!
//! with the hybrid Barker-Henderson diameter d(theta) (fit of eq 105) and the residual
//! second virial coefficient dB2(theta) (fit of eq 108). As a particle EOS (constant ideal
//! heat capacity C_V, theta0 = 1):
//!
//! f = f_res - C_V theta (ln theta - 1),  u = C_V theta + u_res,  u_res = f_res - theta f_res,t,
//! pi/n^2 = f_res,n (an excess pressure, text after eq 53),  s = C_V ln theta - f_res,t,
//! C_V(theta, n) = C_V - theta f_res,tt  (eq 22),
//!
//! where ,t and ,n denote d/dtheta and d/dn. All derivatives are exact: f_res is evaluated
//! once over a four-component forward-mode jet (value, d/dtheta, d^2/dtheta^2, d/dn); u,
//! C_V and the theta(u, n) solve use the closed form at a fixed density of [`LjAt`] (the
//! same values to round-off).
//!
//! Domain. d(theta) and dB2(theta) diverge as theta -> 0 (like 1/theta and theta^-3.5), so
//! eta reaches the pole of A_HS at 1 at any density once theta is small enough, and the fit
//! is meaningless long before. States are accepted for [`LennardJones::THETA_MIN`] <= theta
//! <= [`LennardJones::THETA_MAX`] and eta(theta, n) <= [`LennardJones::ETA_MAX`] = 0.9: the
//! lowest admissible theta at density n is where eta = 0.9 (about 0.014 at n = 0.5, 0.036
//! at n = 1, 0.40 at n = 1.5), and no theta is admissible above n ~ 6.0. [`Eos::theta`]
//! returns 0 when u lies below u at that floor (the model's ground state at this density
//! within the domain), +inf when u lies above u(THETA_MAX, n), NaN for non-finite input or
//! n ~> 6, so that [`Eos::state`] reports an error. On this domain the residual heat
//! capacity -theta f_res,tt is positive for n <= 1.5 (checked on a fine grid), so u is
//! monotonic in theta and the root is unique; above n ~ 1.55 the fitted C_ij polynomial
//! gives negative residual heat capacities at moderate theta (far outside the fitted fluid
//! range), hence [`Eos::max_density`] = 1.5. There u(theta) is no longer monotonic: the
//! solve never diverges or panics, but it may return one of several roots or an error
//! value although a root exists (a randomized check over n <= 1.5, theta in the domain and
//! C_V from 0.01 to 1e4 recovered theta to 3e-14 relative). The public formulas
//! ([`LennardJones::f_res`] etc.) are evaluated without domain checks (NaN once eta >= 1).

use super::{AtDensity, Eos, FixedDensity};
use std::f64::consts::PI;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Coefficients of d(theta) = D_LN ln T + D_M1 / T + D_MH / sqrt T + D_0 + D_H sqrt T.
const D_LN: f64 = -0.063920968;
const D_M1: f64 = 0.011117524;
const D_MH: f64 = -0.076383859;
const D_0: f64 = 1.080142248;
const D_H: f64 = 0.000693129;

/// dB2(theta) = DB2_0 + sum_k DB2[k] T^-(k+2)/2, k = 0..5 (powers -1, -1.5, ..., -3.5).
const DB2_0: f64 = 0.02459877;
const DB2: [f64; 6] = [-7.02181962, 2.90616279, -4.13749995, 0.87361369, 0.43102052, -0.58544978];

/// gamma_BH of the exp(-gamma n^2) damping of the virial term.
const GAMMA_BH: f64 = 1.92907278;

/// C_ij for i = 0, -1, -2, -4 (rows; theta^{i/2}) and j = 2..6 (columns; n^j).
const C: [[f64; 5]; 4] = [
    [2.01546797, -28.17881636, 28.28313847, -10.42402873, 0.0],
    [-19.58371655, 75.62340289, -120.70586598, 93.92740328, -27.37737354],
    [29.34470520, -112.35356937, 170.64908980, -123.06669187, 34.42288969],
    [-13.37031968, 65.38059570, -115.09233113, 88.91973082, -25.62099890],
];

/// Kolafa-Nezbeda Lennard-Jones EOS with constant ideal heat capacity `cv` (k_B = 1).
#[derive(Clone, Debug, PartialEq)]
pub struct LennardJones {
    /// Ideal (constant) part of the particle heat capacity C_V.
    pub cv: f64,
}

/// f_res and the derivatives the particle EOS needs, at one (theta, n).
#[derive(Clone, Copy, Debug)]
struct Fres {
    f: f64,
    ft: f64,
    fn_: f64,
}

impl LennardJones {
    /// Lowest particle temperature accepted by [`Eos::theta`].
    pub const THETA_MIN: f64 = 1e-3;
    /// Highest particle temperature accepted by [`Eos::theta`].
    pub const THETA_MAX: f64 = 1e3;
    /// Largest packing fraction eta accepted by [`Eos::theta`] (A_HS has its pole at 1).
    pub const ETA_MAX: f64 = 0.9;
    /// Iteration cap of the theta(u, n) solve (pure bisection needs about 50).
    const MAX_ITER: usize = 200;
    /// Relative tolerance of the theta(u, n) solve on the last Newton step.
    const TOL: f64 = 1e-14;
    /// Relative tolerance of the theta(u, n) solve on the error predicted to remain after
    /// the last Newton step (quadratic convergence): usually met after two evaluations.
    const PREDICTED_TOL: f64 = 1e-15;

    pub fn new(cv: f64) -> Self {
        Self { cv }
    }

    /// Hybrid Barker-Henderson diameter d(theta) (fit of eq 105).
    pub fn diameter(theta: f64) -> f64 {
        let sq = theta.sqrt();
        D_LN * theta.ln() + D_M1 / theta + D_MH / sq + D_0 + D_H * sq
    }

    /// Packing fraction eta = (pi/6) n d(theta)^3 (eq 104).
    pub fn packing_fraction(theta: f64, n: f64) -> f64 {
        PI / 6.0 * n * Self::diameter(theta).powi(3)
    }

    /// Whether (theta, n) lies in the domain where [`Eos::theta`] accepts states.
    pub fn in_domain(theta: f64, n: f64) -> bool {
        (Self::THETA_MIN..=Self::THETA_MAX).contains(&theta)
            && n >= 0.0
            && Self::packing_fraction(theta, n) <= Self::ETA_MAX
    }

    /// Residual Helmholtz energy per particle f_res(theta, n).
    pub fn f_res(&self, theta: f64, n: f64) -> f64 {
        Self::eval(theta, n).f
    }

    /// Residual internal energy per particle u_res = f_res - theta df_res/dtheta.
    pub fn u_res(&self, theta: f64, n: f64) -> f64 {
        let r = Self::eval(theta, n);
        r.f - theta * r.ft
    }

    /// Total macroscopic pressure P = n theta + n^2 df_res/dn (the KN pressure).
    pub fn pressure(&self, theta: f64, n: f64) -> f64 {
        n * theta + n * n * Self::eval(theta, n).fn_
    }

    /// f_res over a jet seeded with d/dtheta and d/dn.
    #[inline]
    fn eval(theta: f64, n: f64) -> Fres {
        let j = Self::f_res_jet(Jet::var_t(theta), Jet::var_n(n));
        Fres { f: j.v, ft: j.t, fn_: j.n }
    }

    /// f_res(theta, n) evaluated over jets (eqs 104-107 in the form of SPEC.md sec 3).
    #[inline]
    fn f_res_jet(t: Jet, n: Jet) -> Jet {
        let Theta { s, s2, d, db2 } = Theta::of(t);
        let a_hs = a_hs((PI / 6.0) * n * d * d * d);
        let n2 = n * n;
        let virial = n * db2 * (-GAMMA_BH * n2).exp();
        // sum_ij C_ij theta^{i/2} n^j = n^2 [P_0(n) + s P_-1(n) + s^2 P_-2(n) + s^4 P_-4(n)]
        let poly = |row: &[f64; 5]| {
            let mut q = Jet::cst(row[4]);
            for &c in row[..4].iter().rev() {
                q = q * n + c;
            }
            q
        };
        let sum = n2 * (poly(&C[0]) + s * poly(&C[1]) + s2 * (poly(&C[2]) + s2 * poly(&C[3])));
        t * (a_hs + virial) + sum
    }
}

/// The theta-only factors of f_res: s = theta^-1/2, s^2, the diameter d(theta) (eq 105)
/// and dB2(theta) (eq 108).
struct Theta {
    s: Jet,
    s2: Jet,
    d: Jet,
    db2: Jet,
}

impl Theta {
    #[inline(always)]
    fn of(t: Jet) -> Self {
        let sq = t.sqrt();
        let s = sq.recip();
        let s2 = s * s;
        let d = D_LN * t.ln() + D_M1 * s2 + D_MH * s + D_0 + D_H * sq;
        // dB2 in powers of s, Horner
        let mut p = Jet::cst(DB2[5]);
        for &c in DB2[..5].iter().rev() {
            p = p * s + c;
        }
        Self { s, s2, d, db2: p * s2 + DB2_0 }
    }
}

/// A_HS(eta), eq 106.
#[inline(always)]
fn a_hs(eta: Jet) -> Jet {
    let om = 1.0 - eta;
    (5.0 / 3.0) * om.ln() + eta * (34.0 + eta * (-33.0 + 4.0 * eta)) / (6.0 * om * om)
}

/// The Kolafa-Nezbeda model at one density, collapsed once per density to what a theta(u)
/// solve needs: u(theta), C_V(theta) and dC_V/dtheta in closed form, at the cost of one
/// division, one square root and one logarithm per evaluation.
///
/// At fixed n, f_res = theta A_HS(eta(theta)) + B(theta), where B = n e^{-gamma n^2} theta
/// dB2(theta) + n^2 sum_i C_i(n) theta^{i/2} is a polynomial in s = theta^{-1/2} (plus a
/// term linear in theta, which drops out of u and its derivatives): B = sum_m b_m s^m,
/// m = 0..5 (eqs 107-108). With theta^a -> d^k/dtheta^k = a (a-1) .. (a-k+1) theta^a /
/// theta^k, u_res = f_res - theta f_res,t = sum_m (1 + m/2) b_m s^m - theta^2 dA/dtheta
/// (A_HS itself cancels, so no ln(1 - eta) is needed), and the derivatives of A_HS(eta)
/// (eq 106) in eta are polynomials in q = 1/(1 - eta):
/// A_HS = (5/3) ln(1 - eta) + (5/6) q^2 + (10/3) q - 7/2 - (2/3)(1 - eta).
#[derive(Clone, Copy, Debug)]
pub struct LjAt {
    cv: f64,
    n: f64,
    /// (pi/6) n.
    eta_n: f64,
    /// (1 + m/2) b_m, m = 0..5: u_res's polynomial in s.
    bu: [f64; 6],
    /// a (a - 1) b_m and a (a - 1) (a - 2) b_m with a = -m/2, m = 1..5: theta^2 B,tt and
    /// theta^3 B,ttt as polynomials in s (divided by s).
    b2: [f64; 5],
    b3: [f64; 5],
}

/// u, C_V = du/dtheta, dC_V/dtheta and the packing fraction eta at one theta.
#[derive(Clone, Copy, Debug)]
struct Eval {
    u: f64,
    cv: f64,
    dcv: f64,
    eta: f64,
}

/// p_0 + s p_1 + s^2 p_2 + ... (Horner).
#[inline(always)]
fn horner<const K: usize>(p: &[f64; K], s: f64) -> f64 {
    p[..K - 1].iter().rev().fold(p[K - 1], |q, &c| q * s + c)
}

impl LjAt {
    fn new(cv: f64, n: f64) -> Self {
        let row = |r: &[f64; 5]| r[..4].iter().rev().fold(r[4], |q, &c| q * n + c);
        let (n2, nd) = (n * n, n * (-GAMMA_BH * n * n).exp());
        let c = [row(&C[0]), row(&C[1]), row(&C[2]), row(&C[3])];
        // b_m: coefficient of s^m in B(theta) (without B's term linear in theta)
        let b = [
            nd * DB2[0] + n2 * c[0],
            nd * DB2[1] + n2 * c[1],
            nd * DB2[2] + n2 * c[2],
            nd * DB2[3],
            nd * DB2[4] + n2 * c[3],
            nd * DB2[5],
        ];
        let a = |m: usize| -0.5 * m as f64;
        Self {
            cv,
            n,
            eta_n: n * (PI / 6.0),
            bu: std::array::from_fn(|m| (1.0 - a(m)) * b[m]),
            b2: std::array::from_fn(|k| a(k + 1) * (a(k + 1) - 1.0) * b[k + 1]),
            b3: std::array::from_fn(|k| a(k + 1) * (a(k + 1) - 1.0) * (a(k + 1) - 2.0) * b[k + 1]),
        }
    }

    /// u, C_V, dC_V/dtheta and eta at theta (see the type's doc).
    #[inline(always)]
    fn eval(&self, x: f64) -> Eval {
        let r = 1.0 / x;
        let sq = x.sqrt();
        let s = sq * r;
        // d(theta) (eq 105) and its three derivatives: theta^a terms as above, ln theta's
        // derivatives r, -r^2, 2 r^3
        let d = D_LN * x.ln() + D_M1 * r + D_MH * s + D_0 + D_H * sq;
        let d1 = r * (D_LN - D_M1 * r - 0.5 * D_MH * s + 0.5 * D_H * sq);
        let d2 = r * r * (-D_LN + 2.0 * D_M1 * r + 0.75 * D_MH * s - 0.25 * D_H * sq);
        let d3 = r * r * r * (2.0 * D_LN - 6.0 * D_M1 * r - 1.875 * D_MH * s + 0.375 * D_H * sq);
        // eta = (pi/6) n d^3 (eq 104) and its derivatives
        let dd = d * d;
        let eta = self.eta_n * dd * d;
        let e1 = self.eta_n * 3.0 * dd * d1;
        let e2 = self.eta_n * (3.0 * dd * d2 + 6.0 * d * d1 * d1);
        let e3 = self.eta_n * (3.0 * dd * d3 + 18.0 * d * d1 * d2 + 6.0 * d1 * d1 * d1);
        // dA_HS/deta, d^2/deta^2, d^3/deta^3 (eq 106) in q = 1/(1 - eta)
        let q = 1.0 / (1.0 - eta);
        let q2 = q * q;
        let g1 = 2.0 / 3.0 + q * (-5.0 / 3.0 + q * (10.0 / 3.0 + q * (5.0 / 3.0)));
        let g2 = q2 * (-5.0 / 3.0 + q * (20.0 / 3.0 + q * 5.0));
        let g3 = q2 * q * (-10.0 / 3.0 + q * (20.0 + q * 20.0));
        // derivatives of A_HS(eta(theta)) in theta
        let a1 = g1 * e1;
        let a2 = g1 * e2 + g2 * e1 * e1;
        let a3 = g1 * e3 + 3.0 * g2 * e1 * e2 + g3 * e1 * e1 * e1;
        // f_res,tt and f_res,ttt of theta A_HS + B
        let ftt = 2.0 * a1 + x * a2 + r * r * s * horner(&self.b2, s);
        let fttt = 3.0 * a2 + x * a3 + r * r * r * s * horner(&self.b3, s);
        Eval {
            u: self.cv * x + horner(&self.bu, s) - x * x * a1,
            cv: self.cv - x * ftt,
            dcv: -ftt - x * fttt,
            eta,
        }
    }

    /// Bracketed Newton solve of u(theta, n) = u on [THETA_MIN, THETA_MAX] (see module doc);
    /// with theta and C_V there (theta within TOL of the last Newton iterate, or within
    /// PREDICTED_TOL of the root by the predicted error; C_V NaN when the solve ended
    /// otherwise).
    fn solve(&self, u: f64, guess: f64) -> (f64, f64) {
        let mut s = match Newton::new(self, u, guess) {
            Ok(s) => s,
            Err(done) => return done,
        };
        loop {
            if let Some(done) = s.take(self.eval(s.x)) {
                return done;
            }
        }
    }

    /// The solves of two particles (`ats[k]` at `u[k]` from `guess[k]`) in lockstep, each
    /// step's two evaluations side by side: two independent chains the processor overlaps.
    /// The same bits as two [`LjAt::solve`]s.
    fn solve_pair(ats: [&Self; 2], u: [f64; 2], guess: [f64; 2]) -> [(f64, f64); 2] {
        let (a, b) = (Newton::new(ats[0], u[0], guess[0]), Newton::new(ats[1], u[1], guess[1]));
        let (mut sa, mut sb) = match (a, b) {
            (Ok(sa), Ok(sb)) => (sa, sb),
            (Err(x), Err(y)) => return [x, y],
            (Err(x), Ok(_)) => return [x, ats[1].solve(u[1], guess[1])],
            (Ok(_), Err(y)) => return [ats[0].solve(u[0], guess[0]), y],
        };
        loop {
            let (ea, eb) = (ats[0].eval(sa.x), ats[1].eval(sb.x));
            match (sa.take(ea), sb.take(eb)) {
                (None, None) => {}
                (Some(x), Some(y)) => return [x, y],
                (Some(x), None) => return [x, sb.finish(ats[1])],
                (None, Some(y)) => return [sa.finish(ats[0]), y],
            }
        }
    }

    /// theta and 1/tau = (1 - 1/C_V)/theta from a solve's (theta, C_V), C_V evaluated anew
    /// when the solve did not end on a Newton step.
    #[inline]
    fn with_inv_tau(&self, (theta, cv): (f64, f64)) -> (f64, f64) {
        let cv = if cv.is_finite() { cv } else { self.eval(theta).cv };
        (theta, (1.0 - 1.0 / cv) / theta)
    }
}

/// One bracketed Newton solve of u(theta) = u at a fixed density, as a state machine:
/// `x` is the next point to evaluate, [`Newton::take`] consumes its evaluation and gives
/// the result when the solve ended.
struct Newton {
    u: f64,
    lo: f64,
    hi: f64,
    /// Whether an in-domain point with u(x) < u (resp. > u) has been seen.
    lo_hit: bool,
    hi_hit: bool,
    x: f64,
    iter: usize,
}

impl Newton {
    /// The solve from `guess` (or from a first estimate at theta = 1), or its result for
    /// invalid input.
    #[inline(always)]
    fn new(at: &LjAt, u: f64, guess: f64) -> Result<Self, (f64, f64)> {
        let n = at.n;
        if !(u.is_finite() && n.is_finite() && n >= 0.0) {
            return Err((f64::NAN, f64::NAN));
        }
        let (lo, hi) = (LennardJones::THETA_MIN, LennardJones::THETA_MAX);
        let x = if guess > 0.0 && guess.is_finite() {
            guess
        } else {
            let e = at.eval(1.0);
            let x0 = if e.eta <= LennardJones::ETA_MAX { 1.0 + (u - e.u) / at.cv } else { f64::NAN };
            if x0.is_finite() {
                x0.max(lo)
            } else {
                (lo * hi).sqrt()
            }
        };
        Ok(Self { u, lo, hi, lo_hit: false, hi_hit: false, x: x.clamp(lo, hi), iter: 0 })
    }

    /// Takes the evaluation at `x`: the result when the solve ended (converged, or ran out
    /// of steps), else moves `x` to the next point.
    #[inline(always)]
    fn take(&mut self, e: Eval) -> Option<(f64, f64)> {
        let x = self.x;
        if !(e.eta <= LennardJones::ETA_MAX) {
            // x in [THETA_MIN, THETA_MAX] is out of the domain only by eta > ETA_MAX:
            // below the floor at this density, so the root lies above
            self.lo = x;
            return self.advance(f64::NAN);
        }
        let r = e.u - self.u;
        if r == 0.0 {
            return Some((x, e.cv));
        }
        if r < 0.0 {
            self.lo = x;
            self.lo_hit = true;
        } else {
            self.hi = x;
            self.hi_hit = true;
        }
        let step = r / e.cv;
        let next = x - step;
        // Newton converges quadratically: the error left after this step is
        // |u''/(2 u')| step^2 (u'' = dC_V/dtheta), with a step short enough that its own
        // round-off stays below PREDICTED_TOL; C_V carried to `next` along dC_V/dtheta
        let left = (e.dcv / (2.0 * e.cv)).abs() * step * step;
        let converged = step.abs() <= LennardJones::TOL * x && next > 0.0;
        let predicted = left <= LennardJones::PREDICTED_TOL * x && step.abs() <= 0.01 * x;
        if converged || (predicted && next > self.lo && next < self.hi) {
            return Some((next, e.cv - e.dcv * step));
        }
        self.advance(next)
    }

    /// Ends an iteration: the result once the bracket is within TOL or the iterations are
    /// spent, else moves to `next` (bisection in ln theta when it leaves the bracket: the
    /// bracket spans decades).
    #[inline(always)]
    fn advance(&mut self, next: f64) -> Option<(f64, f64)> {
        self.iter += 1;
        if self.hi - self.lo <= LennardJones::TOL * self.lo || self.iter >= LennardJones::MAX_ITER {
            return Some(self.ended());
        }
        self.x = if next > self.lo && next < self.hi { next } else { (self.lo * self.hi).sqrt() };
        None
    }

    /// The rest of the solve alone.
    fn finish(&mut self, at: &LjAt) -> (f64, f64) {
        loop {
            if let Some(done) = self.take(at.eval(self.x)) {
                return done;
            }
        }
    }

    /// The result of a solve that ran out of Newton steps: the bracket's middle, or the
    /// bound the root lies beyond (C_V NaN).
    fn ended(&self) -> (f64, f64) {
        let theta = match (self.lo_hit, self.hi_hit) {
            (true, true) => 0.5 * (self.lo + self.hi),
            (false, true) => 0.0, // u below the ground state at this density
            (true, false) => f64::INFINITY, // u above u(THETA_MAX, n)
            (false, false) => f64::NAN, // eta > ETA_MAX at every theta: n too high
        };
        (theta, f64::NAN)
    }
}

impl AtDensity for LjAt {
    #[inline]
    fn theta(&self, u: f64, guess: f64) -> f64 {
        self.solve(u, guess).0
    }
    /// C_V from the solve's last Newton evaluation: one evaluation of f_res saved.
    #[inline]
    fn theta_inv_tau(&self, u: f64, guess: f64) -> (f64, f64) {
        self.with_inv_tau(self.solve(u, guess))
    }
    #[inline]
    fn theta_pair(&self, b: &Self, u: [f64; 2], guess: [f64; 2]) -> [f64; 2] {
        LjAt::solve_pair([self, b], u, guess).map(|(theta, _)| theta)
    }
    #[inline]
    fn theta_inv_tau_pair(&self, b: &Self, u: [f64; 2], guess: [f64; 2]) -> [(f64, f64); 2] {
        let [x, y] = LjAt::solve_pair([self, b], u, guess);
        [self.with_inv_tau(x), b.with_inv_tau(y)]
    }
    /// theta + du/C_V with 1/C_V = 1 - theta/tau (k_B = 1).
    #[inline(always)]
    fn guess_after(&self, theta: f64, inv_tau: f64, du: f64) -> f64 {
        theta + du * (1.0 - theta * inv_tau)
    }
}

impl FixedDensity for LennardJones {
    type At<'a> = LjAt;
    #[inline]
    fn at_density(&self, n: f64) -> LjAt {
        LjAt::new(self.cv, n)
    }
}

impl Eos for LennardJones {
    fn kb(&self) -> f64 {
        1.0
    }
    fn density_dependent(&self) -> bool {
        true
    }
    #[inline]
    fn theta(&self, u: f64, n: f64, guess: f64) -> f64 {
        self.at_density(n).solve(u, guess).0
    }
    /// C_V from the solve's last Newton evaluation: one evaluation of f_res saved.
    #[inline]
    fn theta_cv(&self, u: f64, n: f64, guess: f64) -> (f64, f64) {
        let at = self.at_density(n);
        match at.solve(u, guess) {
            (theta, cv) if cv.is_finite() => (theta, cv),
            (theta, _) => (theta, at.eval(theta).cv),
        }
    }
    #[inline]
    fn u(&self, theta: f64, n: f64) -> f64 {
        self.at_density(n).eval(theta).u
    }
    #[inline]
    fn pn2(&self, theta: f64, n: f64) -> f64 {
        Self::eval(theta, n).fn_
    }
    #[inline]
    fn cv(&self, theta: f64, n: f64) -> f64 {
        self.at_density(n).eval(theta).cv
    }
    fn entropy(&self, u: f64, n: f64) -> Option<f64> {
        let theta = self.at_density(n).solve(u, f64::NAN).0;
        (theta > 0.0 && theta.is_finite()).then(|| self.cv * theta.ln() - Self::eval(theta, n).ft)
    }
    /// 1.5: above it the fit loses thermodynamic stability (see the module doc).
    fn max_density(&self) -> Option<f64> {
        Some(1.5)
    }
}

/// Truncated two-variable Taylor jet a(theta0 + dt, n0 + dn) modulo (dt^3, dt dn, dn^2):
/// value, d/dtheta, d^2/dtheta^2 and d/dn, exact under +, -, *, / and the elementary
/// functions below. Copy, four f64, no allocation.
#[derive(Clone, Copy, Debug)]
struct Jet {
    v: f64,
    t: f64,
    tt: f64,
    n: f64,
}

impl Jet {
    #[inline]
    fn cst(v: f64) -> Self {
        Self { v, t: 0.0, tt: 0.0, n: 0.0 }
    }
    #[inline]
    fn var_t(v: f64) -> Self {
        Self { v, t: 1.0, tt: 0.0, n: 0.0 }
    }
    #[inline]
    fn var_n(v: f64) -> Self {
        Self { v, t: 0.0, tt: 0.0, n: 1.0 }
    }
    /// g(self) from g, g', g'' at self.v (chain rule to second order in theta).
    #[inline]
    fn chain(self, g: f64, g1: f64, g2: f64) -> Self {
        Self { v: g, t: g1 * self.t, tt: g1 * self.tt + g2 * self.t * self.t, n: g1 * self.n }
    }
    #[inline]
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }
    #[inline]
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s, -0.25 / (s * self.v))
    }
    #[inline]
    fn ln(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(self.v.ln(), r, -r * r)
    }
    #[inline]
    fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e, e)
    }
}

impl Add for Jet {
    type Output = Jet;
    #[inline]
    fn add(self, b: Jet) -> Jet {
        Jet { v: self.v + b.v, t: self.t + b.t, tt: self.tt + b.tt, n: self.n + b.n }
    }
}
impl Sub for Jet {
    type Output = Jet;
    #[inline]
    fn sub(self, b: Jet) -> Jet {
        Jet { v: self.v - b.v, t: self.t - b.t, tt: self.tt - b.tt, n: self.n - b.n }
    }
}
impl Mul for Jet {
    type Output = Jet;
    #[inline]
    fn mul(self, b: Jet) -> Jet {
        Jet {
            v: self.v * b.v,
            t: self.v * b.t + self.t * b.v,
            tt: self.v * b.tt + 2.0 * self.t * b.t + self.tt * b.v,
            n: self.v * b.n + self.n * b.v,
        }
    }
}
impl Div for Jet {
    type Output = Jet;
    #[inline]
    fn div(self, b: Jet) -> Jet {
        // q = a/b: q' = (a' - q b')/b, q'' = (a'' - 2 q' b' - q b'')/b
        let r = 1.0 / b.v;
        let v = self.v * r;
        let t = (self.t - v * b.t) * r;
        Jet { v, t, tt: (self.tt - 2.0 * t * b.t - v * b.tt) * r, n: (self.n - v * b.n) * r }
    }
}
impl Neg for Jet {
    type Output = Jet;
    #[inline]
    fn neg(self) -> Jet {
        Jet { v: -self.v, t: -self.t, tt: -self.tt, n: -self.n }
    }
}
impl Add<f64> for Jet {
    type Output = Jet;
    #[inline]
    fn add(self, c: f64) -> Jet {
        Jet { v: self.v + c, ..self }
    }
}
impl Add<Jet> for f64 {
    type Output = Jet;
    #[inline]
    fn add(self, a: Jet) -> Jet {
        a + self
    }
}
impl Sub<Jet> for f64 {
    type Output = Jet;
    #[inline]
    fn sub(self, a: Jet) -> Jet {
        -a + self
    }
}
impl Mul<f64> for Jet {
    type Output = Jet;
    #[inline]
    fn mul(self, c: f64) -> Jet {
        Jet { v: self.v * c, t: self.t * c, tt: self.tt * c, n: self.n * c }
    }
}
impl Mul<Jet> for f64 {
    type Output = Jet;
    #[inline]
    fn mul(self, a: Jet) -> Jet {
        a * self
    }
}

#[cfg(test)]
mod tests;
