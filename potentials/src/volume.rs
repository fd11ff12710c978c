//! Corrected particle volume of the argon paper (Colella et al., eqs 2-3 and 23-26): an
//! approximate partition of unity. With the quadratic kernel of radius R~ = R_cut/f_cut
//! (f_cut > 1), w~(r) = 15/(2 pi R~^3) (1 - r/R~)^2, the volume of particle i is
//!
//! Vol_i = int d^3r w~(r) / (w~(r) + n^b_i) = 4 pi R~^3 I(k_i),  k_i = (2 pi/15) R~^3 n^b_i,
//! I(k) = int_0^1 (1 - x)^2 x^2 / (x^2 + k) dx
//!      = 1/3 - sqrt(k) {(1 - k) atan(1/sqrt(k)) + sqrt(k) [1 - ln((k + 1)/k)]}   (eq 2),
//!
//! and n_i = 1/Vol_i (eq 3), where n^b_i = sum_j w(r_ij) is the primitive density of eq 1
//! (normalised weight of radius R_cut; the paper's choice is the quadratic one, see the
//! reading notes). Positions enter only through n^b, so dn_i/dr_ij = zeta_i w'(r_ij) with
//! zeta = dn/dn^b (eqs 23-26): the forces stay pairwise and central (eq 27).
//!
//! For k > 4 the closed form loses digits to cancellation (1/3 minus nearly 1/3); there I
//! and its derivatives are summed from the convergent series
//! I(k) = sum_m (-1)^m c_m k^-(m+1), c_m = int_0^1 (1 - x)^2 x^(2m+2) dx = 2/((2m+3)(2m+4)(2m+5)).
//! A particle without neighbours has n^b = 0 and the finite volume 4 pi R~^3/3.

use crate::weight::Weight;
use std::f64::consts::PI;

/// Above this k the series replaces the closed form (both agree to ~1e-13 there).
const K_SERIES: f64 = 4.0;

/// The corrected volume function of eq 2 for one R~ = R_cut / f_cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionVolume {
    /// R~^3.
    r3: f64,
}

/// Corrected density of one particle and its derivatives with respect to n^b.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorrectedDensity {
    /// Primitive density n^b (eq 1).
    pub nb: f64,
    /// Particle volume Vol (eq 2).
    pub volume: f64,
    /// n = 1/Vol (eq 3).
    pub n: f64,
    /// zeta = dn/dn^b (eq 24); 0 without neighbours, where no w' multiplies it.
    pub zeta: f64,
    /// dzeta/dn^b (enters \[W_nn\], eq 88); 0 without neighbours.
    pub zeta_n: f64,
}

impl PartitionVolume {
    /// R~ = rcut / fcut (eq 2); f_cut > 1 in the paper (Table 4).
    pub fn new(rcut: f64, fcut: f64) -> Self {
        let r = rcut / fcut;
        Self { r3: r * r * r }
    }

    /// k = (2 pi/15) R~^3 n^b (eq 2); dk/dn^b = (2 pi/15) R~^3 (eq 26).
    #[inline]
    pub fn k(&self, nb: f64) -> f64 {
        2.0 * PI / 15.0 * self.r3 * nb
    }

    /// Vol(n^b), eq 2.
    #[inline]
    pub fn volume(&self, nb: f64) -> f64 {
        4.0 * PI * self.r3 * integral(self.k(nb)).0
    }

    /// Vol, n = 1/Vol, zeta = dn/dn^b (eqs 24-26) and dzeta/dn^b at n^b.
    pub fn density(&self, nb: f64) -> CorrectedDensity {
        let k = self.k(nb);
        let (i, i1, i2) = integral(k);
        let c = 4.0 * PI * self.r3; // Vol = c I(k)
        let kn = 2.0 * PI / 15.0 * self.r3; // dk/dn^b
        let volume = c * i;
        let n = 1.0 / volume;
        let (zeta, zeta_n) = if k > 0.0 {
            // n = 1/(c I): dn/dk = -I'/(c I^2), d2n/dk2 = (2 I'^2/I - I'')/(c I^2)
            let d1 = -i1 / (c * i * i);
            let d2 = (2.0 * i1 * i1 / i - i2) / (c * i * i);
            (d1 * kn, d2 * kn * kn)
        } else {
            (0.0, 0.0)
        };
        CorrectedDensity { nb, volume, n, zeta, zeta_n }
    }

    /// The corrected density of one particle from its neighbours' distances `r` (all
    /// below the weight's cutoff or contributing zero), with dVol/dr_ij for every
    /// neighbour written to `dvol_dr` (same length as `r`): dVol/dr_ij = -zeta w'(r_ij)/n^2.
    /// The force of eq 27 needs dn_i/dr_ij = zeta w'(r_ij) = -n^2 dVol/dr_ij.
    pub fn particle<W: Weight>(&self, w: &W, r: &[f64], dvol_dr: &mut [f64]) -> CorrectedDensity {
        assert_eq!(r.len(), dvol_dr.len(), "one derivative slot per neighbour");
        let rc = w.cutoff();
        let eval = |x: f64| if x < rc { w.eval(x) } else { (0.0, 0.0) };
        let nb = r.iter().map(|&x| eval(x).0).sum();
        let d = self.density(nb);
        let f = -d.zeta / (d.n * d.n);
        for (out, &x) in dvol_dr.iter_mut().zip(r) {
            *out = f * eval(x).1;
        }
        d
    }
}

/// I(k), I'(k), I''(k) of eq 2 (I' is eq 25 over -4 pi R~^3).
#[inline]
fn integral(k: f64) -> (f64, f64, f64) {
    if k > K_SERIES {
        return series(k);
    }
    if k <= 0.0 {
        return (1.0 / 3.0, f64::NEG_INFINITY, f64::INFINITY);
    }
    let s = k.sqrt();
    let at = (1.0 / s).atan();
    let ln = (1.0 / k).ln_1p(); // ln((k + 1)/k)
    let i = 1.0 / 3.0 - s * ((1.0 - k) * at + s * (1.0 - ln));
    let i1 = -(1.5 + (1.0 - 3.0 * k) / (2.0 * s) * at - ln);
    let i2 = (1.0 + 3.0 * k) / (4.0 * k * s) * at - 0.75 / k;
    (i, i1, i2)
}

/// I, I', I'' from the series in 1/k (k > 4: terms fall at least by 4 per order).
fn series(k: f64) -> (f64, f64, f64) {
    let (mut i, mut i1, mut i2) = (0.0, 0.0, 0.0);
    let mut t = 1.0 / k; // (-1)^m k^-(m+1)
    for m in 0..200 {
        let mf = m as f64;
        let tc = t * 2.0 / ((2.0 * mf + 3.0) * (2.0 * mf + 4.0) * (2.0 * mf + 5.0));
        i += tc;
        i1 -= (mf + 1.0) * tc / k;
        i2 += (mf + 1.0) * (mf + 2.0) * tc / (k * k);
        if ((mf + 1.0) * (mf + 2.0) * tc).abs() < 1e-18 * i.abs() {
            break;
        }
        t = -t / k;
    }
    (i, i1, i2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::weight::Quadratic;

    /// Composite Gauss-Legendre (5 points) of f on [a, b] with `panels` panels.
    fn gauss(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
        const X: [f64; 5] = [
            0.0,
            0.538_469_310_105_683_1,
            -0.538_469_310_105_683_1,
            0.906_179_845_938_664,
            -0.906_179_845_938_664,
        ];
        const W: [f64; 5] = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        let h = (b - a) / panels as f64;
        (0..panels)
            .map(|p| {
                let mid = a + (p as f64 + 0.5) * h;
                X.iter().zip(W).map(|(x, w)| w * f(mid + 0.5 * h * x)).sum::<f64>() * 0.5 * h
            })
            .sum()
    }

    /// The definition: Vol = int d^3r w~/(w~ + n^b), w~ the quadratic kernel of radius R~.
    fn volume_by_quadrature(rcut: f64, fcut: f64, nb: f64) -> f64 {
        let rt = rcut / fcut;
        let wt = |r: f64| 15.0 / (2.0 * PI * rt.powi(3)) * (1.0 - r / rt).powi(2);
        gauss(|r| 4.0 * PI * r * r * wt(r) / (wt(r) + nb), 0.0, rt, 400)
    }

    const CASES: [(f64, f64); 4] = [(1.3365, 1.41), (1.6839, 1.35), (2.1564, 1.33), (6.0, 1.1)];
    const DENSITIES: [f64; 8] = [1e-4, 0.05, 0.42, 0.85, 1.0, 1.7, 4.0, 30.0];

    #[test]
    fn eq_2_matches_quadrature_of_the_partition_of_unity() {
        for (rc, fc) in CASES {
            let v = PartitionVolume::new(rc, fc);
            for nb in DENSITIES {
                let q = volume_by_quadrature(rc, fc, nb);
                let e = v.volume(nb);
                assert!((e - q).abs() < 1e-12 * q, "R {rc}, n^b {nb}: {e} vs {q}, k {}", v.k(nb));
            }
        }
    }

    /// Closed form and series agree where they meet, and the volume is smooth across.
    #[test]
    fn series_continues_the_closed_form() {
        let s = series(K_SERIES);
        let c = integral(K_SERIES * (1.0 - 1e-15));
        assert!((s.0 - c.0).abs() < 1e-12 * s.0);
        assert!((s.1 - c.1).abs() < 1e-12 * s.1.abs());
        assert!((s.2 - c.2).abs() < 1e-10 * s.2.abs());
    }

    /// Eq 25 (dVol/dk), zeta (eq 24) and dzeta/dn^b against finite differences of eq 2.
    #[test]
    fn derivatives_match_finite_differences() {
        let d1 = |f: &dyn Fn(f64) -> f64, x: f64, h: f64| {
            (8.0 * (f(x + h) - f(x - h)) - (f(x + 2.0 * h) - f(x - 2.0 * h))) / (12.0 * h)
        };
        for (rc, fc) in CASES {
            let v = PartitionVolume::new(rc, fc);
            for nb in DENSITIES.into_iter().skip(1) {
                let h = 1e-3 * nb;
                let d = v.density(nb);
                let n = |x: f64| 1.0 / v.volume(x);
                let zeta = d1(&n, nb, h);
                assert!((zeta - d.zeta).abs() < 1e-8 * d.zeta, "zeta {nb}: {zeta} vs {}", d.zeta);
                let zeta_n = d1(&|x| v.density(x).zeta, nb, h);
                // round-off of the difference quotient: ~1e-15 zeta / h
                let tol = 1e-7 * d.zeta_n.abs() + 1e-12 * d.zeta / nb;
                assert!((zeta_n - d.zeta_n).abs() < tol, "{zeta_n} vs {}", d.zeta_n);
                // eq 25 as printed, against d/dk of eq 2
                let k = v.k(nb);
                let c = 4.0 * PI * v.r3;
                let eq25 = -c
                    * (1.5 + (1.0 - 3.0 * k) / (2.0 * k.sqrt()) * (1.0 / k.sqrt()).atan()
                        - ((k + 1.0) / k).ln());
                let fd = d1(&|x| c * integral(x).0, k, 1e-3 * k);
                assert!((eq25 - fd).abs() < 1e-7 * fd.abs(), "eq 25 at k {k}: {eq25} vs {fd}");
            }
        }
    }

    /// dVol/dr_ij of a particle against moving one neighbour, and n = 1/Vol.
    #[test]
    fn per_neighbour_derivative_matches_finite_differences() {
        let (rc, fc) = (2.1564, 1.33);
        let (v, w) = (PartitionVolume::new(rc, fc), Quadratic::new(rc));
        let r = [0.6, 0.95, 1.1, 1.3, 1.62, 1.9, 2.1, 2.3];
        let mut dv = [0.0; 8];
        let d = v.particle(&w, &r, &mut dv);
        let nb: f64 = r.iter().filter(|&&x| x < rc).map(|&x| w.eval(x).0).sum();
        assert!((d.nb - nb).abs() < 1e-15);
        assert_eq!(d.n, 1.0 / d.volume);
        assert_eq!(dv[7], 0.0);
        for j in 0..7 {
            let vol_at = |x: f64| {
                let mut rr = r;
                rr[j] = x;
                v.particle(&w, &rr, &mut [0.0; 8]).volume
            };
            let h = 1e-5;
            let fd = (vol_at(r[j] + h) - vol_at(r[j] - h)) / (2.0 * h);
            assert!((fd - dv[j]).abs() < 1e-8 * dv[j].abs(), "neighbour {j}: {fd} vs {}", dv[j]);
            assert!(dv[j] > 0.0, "moving a neighbour away grows the volume");
        }
    }

    /// Vol -> 1/n^b when R~ grows (the kernel becomes flat over the neighbours), with the
    /// leading correction Vol n^b - 1 = -(c_1/c_0)/k = -(2/7)/k; Vol < 1/n^b always; an
    /// isolated particle keeps the finite volume 4 pi R~^3/3.
    #[test]
    fn limits() {
        for nb in [0.3, 1.0, 2.0] {
            let big = PartitionVolume::new(400.0, 1.0001);
            let k = big.k(nb);
            let x = (big.volume(nb) * nb - 1.0) * k;
            assert!((x + 2.0 / 7.0).abs() < 1e-5, "{x}");
            for (rc, fc) in CASES {
                assert!(PartitionVolume::new(rc, fc).volume(nb) * nb < 1.0);
            }
        }
        let v = PartitionVolume::new(2.0, 1.25);
        let d = v.density(0.0);
        assert!((d.volume - 4.0 * PI / 3.0 * 1.6f64.powi(3)).abs() < 1e-14);
        assert_eq!((d.zeta, d.zeta_n), (0.0, 0.0));
        let lone = v.particle(&Quadratic::new(2.0), &[], &mut []);
        assert_eq!(lone, d);
    }

    /// Reading notes (argon paper, Table 4): at n^b = 1 the three (R*, f_cut) pairs give
    /// n = 1.654, 1.313, 1.150, and n = 1 needs n^b = 0.420, 0.697, 0.851.
    #[test]
    fn table_4_cutoffs_at_unit_primitive_density() {
        let expect = [(1.654, 0.420), (1.313, 0.697), (1.150, 0.851)];
        for ((rc, fc), (n1, nb1)) in CASES.into_iter().zip(expect) {
            let v = PartitionVolume::new(rc, fc);
            assert!((v.density(1.0).n - n1).abs() < 5e-4, "R {rc}: n {}", v.density(1.0).n);
            assert!((v.density(nb1).n - 1.0).abs() < 2e-3, "R {rc}: n {}", v.density(nb1).n);
        }
    }
}
