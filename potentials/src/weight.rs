//! Weight functions w(r) for the local density, eqs 2-3: n_i = sum_j w(r_ij) / [w].
//!
//! Every weight is zero for r >= rc and is evaluated already divided by its exact
//! normalisation [w] = 4 pi int_0^rc w(r) r^2 dr, so `eval` returns w/[w] and w'/[w].

use std::f64::consts::PI;

/// A normalised, compactly supported weight function.
pub trait Weight: Copy + Send + Sync + 'static {
    /// Support radius rc.
    fn cutoff(&self) -> f64;
    /// (w(r)/[w], w'(r)/[w]) for 0 <= r < rc.
    fn eval(&self, r: f64) -> (f64, f64);
}

/// The weight functions a script can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WeightKind {
    Quadratic,
    Linear,
    Lucy,
    CubicSpline,
}

impl WeightKind {
    /// Parses a script keyword (`quadratic`, `linear`, `lucy`, `spline`).
    pub fn parse(word: &str) -> Option<Self> {
        match word {
            "quadratic" => Some(Self::Quadratic),
            "linear" => Some(Self::Linear),
            "lucy" => Some(Self::Lucy),
            "spline" | "cubic" => Some(Self::CubicSpline),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Quadratic => "quadratic",
            Self::Linear => "linear",
            Self::Lucy => "lucy",
            Self::CubicSpline => "spline",
        }
    }
}

/// Stores rc, 1/rc and 1/[w]; shared by all kernels.
#[derive(Clone, Copy, Debug)]
struct Scale {
    rc: f64,
    inv_rc: f64,
    inv_norm: f64,
}

impl Scale {
    fn new(rc: f64, norm_over_rc3: f64) -> Self {
        Self { rc, inv_rc: 1.0 / rc, inv_norm: 1.0 / (norm_over_rc3 * rc * rc * rc) }
    }
}

macro_rules! weight_type {
    ($(#[$doc:meta])* $name:ident, $norm:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug)]
        pub struct $name(Scale);

        impl $name {
            pub fn new(rc: f64) -> Self {
                Self(Scale::new(rc, $norm))
            }
        }
    };
}

weight_type!(
    /// w = (1 - r/rc)^2, [w] = 2 pi rc^3 / 15 (the 2019 paper's density weight).
    Quadratic,
    2.0 * PI / 15.0
);
weight_type!(
    /// w = 1 - r/rc, [w] = pi rc^3 / 3.
    Linear,
    PI / 3.0
);
weight_type!(
    /// Lucy: w = (1 + 3r/rc)(1 - r/rc)^3, [w] = 16 pi rc^3 / 105.
    Lucy,
    16.0 * PI / 105.0
);
weight_type!(
    /// Cubic M4 spline with h = rc/2: 1 - 3q^2/2 + 3q^3/4 (q < 1), (2 - q)^3/4 (q < 2),
    /// q = r/h; [w] = pi h^3 = pi rc^3 / 8.
    CubicSpline,
    PI / 8.0
);

impl Weight for Quadratic {
    fn cutoff(&self) -> f64 {
        self.0.rc
    }
    #[inline(always)]
    fn eval(&self, r: f64) -> (f64, f64) {
        let s = &self.0;
        let a = 1.0 - r * s.inv_rc;
        (a * a * s.inv_norm, -2.0 * a * s.inv_rc * s.inv_norm)
    }
}

impl Weight for Linear {
    fn cutoff(&self) -> f64 {
        self.0.rc
    }
    #[inline(always)]
    fn eval(&self, r: f64) -> (f64, f64) {
        let s = &self.0;
        ((1.0 - r * s.inv_rc) * s.inv_norm, -s.inv_rc * s.inv_norm)
    }
}

impl Weight for Lucy {
    fn cutoff(&self) -> f64 {
        self.0.rc
    }
    #[inline(always)]
    fn eval(&self, r: f64) -> (f64, f64) {
        let s = &self.0;
        let x = r * s.inv_rc;
        let a = 1.0 - x;
        let a2 = a * a;
        ((1.0 + 3.0 * x) * a2 * a * s.inv_norm, -12.0 * x * a2 * s.inv_rc * s.inv_norm)
    }
}

impl Weight for CubicSpline {
    fn cutoff(&self) -> f64 {
        self.0.rc
    }
    #[inline(always)]
    fn eval(&self, r: f64) -> (f64, f64) {
        let s = &self.0;
        let inv_h = 2.0 * s.inv_rc;
        let q = r * inv_h;
        if q < 1.0 {
            let w = 1.0 - 1.5 * q * q + 0.75 * q * q * q;
            (w * s.inv_norm, (-3.0 * q + 2.25 * q * q) * inv_h * s.inv_norm)
        } else {
            let a = 2.0 - q;
            (0.25 * a * a * a * s.inv_norm, -0.75 * a * a * inv_h * s.inv_norm)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 4 pi int_0^rc w r^2 dr by composite Simpson, for the normalised weight.
    fn integral<W: Weight>(w: W) -> f64 {
        let m = 20_000;
        let h = w.cutoff() / m as f64;
        let f = |k: usize| {
            let r = k as f64 * h;
            if k == m { 0.0 } else { w.eval(r).0 * r * r }
        };
        let mut s = f(0) + f(m);
        for k in 1..m {
            s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k);
        }
        4.0 * PI * s * h / 3.0
    }

    fn check_derivative<W: Weight>(w: W) {
        let rc = w.cutoff();
        for k in 1..40 {
            let r = rc * k as f64 / 40.5;
            let h = 1e-6 * rc;
            let fd = (w.eval(r + h).0 - w.eval(r - h).0) / (2.0 * h);
            let an = w.eval(r).1;
            assert!((fd - an).abs() <= 1e-7 * an.abs().max(1e-3), "r={r} fd={fd} an={an}");
        }
    }

    #[test]
    fn weights_are_normalised_and_vanish_at_the_cutoff() {
        for rc in [1.0, 2.5, 4.0] {
            for (name, norm, at_rc) in [
                ("quadratic", integral(Quadratic::new(rc)), Quadratic::new(rc).eval(rc).0),
                ("linear", integral(Linear::new(rc)), Linear::new(rc).eval(rc).0),
                ("lucy", integral(Lucy::new(rc)), Lucy::new(rc).eval(rc).0),
                ("spline", integral(CubicSpline::new(rc)), CubicSpline::new(rc).eval(rc).0),
            ] {
                assert!((norm - 1.0).abs() < 1e-10, "{name} rc={rc}: integral {norm}");
                assert!(at_rc.abs() < 1e-15, "{name} w(rc) = {at_rc}");
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        check_derivative(Quadratic::new(3.0));
        check_derivative(Linear::new(3.0));
        check_derivative(Lucy::new(3.0));
        check_derivative(CubicSpline::new(3.0));
    }

    #[test]
    fn spline_is_continuous_at_q_equal_one() {
        let w = CubicSpline::new(2.0);
        let (a, da) = w.eval(1.0 - 1e-12);
        let (b, db) = w.eval(1.0 + 1e-12);
        assert!((a - b).abs() < 1e-10 && (da - db).abs() < 1e-10);
    }
}
