//! `lattice` and the points of `create_atoms` (lattice or random).

use gendpde_engine::Vec3;
use rand_pcg::rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A cubic lattice: `lattice sc|bcc|fcc RHO` (lj units: RHO is the reduced number
/// density, so the lattice constant is (basis count / RHO)^(1/3), as in LAMMPS).
#[derive(Clone, Debug, PartialEq)]
pub struct Lattice {
    pub constant: f64,
    pub basis: Vec<Vec3>,
}

impl Lattice {
    pub fn new(style: &str, density: f64) -> Option<Self> {
        let basis: Vec<Vec3> = match style {
            "sc" => vec![[0.0; 3]],
            "bcc" => vec![[0.0; 3], [0.5; 3]],
            "fcc" => vec![[0.0; 3], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]],
            _ => return None,
        };
        let constant = (basis.len() as f64 / density).cbrt();
        Some(Self { constant, basis })
    }

    /// An upper bound of the number of points in the block [lo, hi) (no allocation).
    pub fn count_bound(&self, lo: Vec3, hi: Vec3) -> f64 {
        let cells: f64 = (0..3).map(|d| ((hi[d] - lo[d]) / self.constant).ceil() + 1.0).product();
        cells * self.basis.len() as f64
    }

    /// Lattice points inside the block [lo, hi), in LAMMPS's order (z, y, x, basis).
    pub fn points(&self, lo: Vec3, hi: Vec3) -> Vec<Vec3> {
        let a = self.constant;
        let eps = 1e-10 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(hi[2] - lo[2]);
        let range = |d: usize| ((lo[d] / a).floor() as i64 - 1)..=((hi[d] / a).ceil() as i64 + 1);
        let mut out = Vec::new();
        for k in range(2) {
            for j in range(1) {
                for i in range(0) {
                    for b in &self.basis {
                        let r = [(i as f64 + b[0]) * a, (j as f64 + b[1]) * a, (k as f64 + b[2]) * a];
                        if (0..3).all(|d| r[d] >= lo[d] - eps && r[d] < hi[d] - eps) {
                            out.push(r);
                        }
                    }
                }
            }
        }
        out
    }
}

/// `n` points uniform in the block [lo, hi) that `accept` takes (the others are drawn
/// again), from the sequential stream of `seed` (rand_pcg's Pcg64Mcg, x then y then z of
/// each point: the same points on every rank). Err when a million draws in a row fail.
pub fn random_points(n: u64, seed: u64, lo: Vec3, hi: Vec3, accept: impl Fn(Vec3) -> bool) -> Result<Vec<Vec3>, String> {
    const MAX_TRIES: u32 = 1_000_000;
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut uniform = || (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    let mut out = Vec::with_capacity(n as usize);
    let mut failed = 0;
    while out.len() < n as usize {
        let r: Vec3 = std::array::from_fn(|d| lo[d] + uniform() * (hi[d] - lo[d]));
        // rounding can land on hi, which belongs to the next image
        if (0..3).all(|d| r[d] < hi[d]) && accept(r) {
            out.push(r);
            failed = 0;
        } else {
            failed += 1;
            if failed == MAX_TRIES {
                return Err(format!("{MAX_TRIES} random points in a row missed the region: it has (almost) no volume in the box"));
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattices_hold_the_requested_density() {
        for (style, per_cell) in [("sc", 1), ("bcc", 2), ("fcc", 4)] {
            let l = Lattice::new(style, 0.5).unwrap();
            let side = 5.0 * l.constant;
            let pts = l.points([0.0; 3], [side; 3]);
            assert_eq!(pts.len(), 125 * per_cell, "{style}");
            let rho = pts.len() as f64 / side.powi(3);
            assert!((rho - 0.5).abs() < 1e-12);
        }
    }

    /// Chi-square of the counts in 4x4x4 bins against uniform (63 degrees of freedom:
    /// mean 63, sd 11.2), for several seeds; every point lies in the block.
    #[test]
    fn random_points_are_uniform_in_the_block() {
        let (lo, hi) = ([-1.0, 2.0, 0.5], [3.0, 2.5, 7.0]);
        let mut chi2s = Vec::new();
        for seed in 1..=20 {
            let pts = random_points(6400, seed, lo, hi, |_| true).unwrap();
            assert_eq!(pts.len(), 6400);
            let mut bins = [0.0; 64];
            for r in &pts {
                assert!((0..3).all(|d| r[d] >= lo[d] && r[d] < hi[d]), "{r:?}");
                let b: Vec<usize> = (0..3).map(|d| ((r[d] - lo[d]) / (hi[d] - lo[d]) * 4.0) as usize).collect();
                bins[b[0] + 4 * b[1] + 16 * b[2]] += 1.0;
            }
            chi2s.push(bins.iter().map(|c| (c - 100.0) * (c - 100.0) / 100.0).sum::<f64>());
        }
        let mean = chi2s.iter().sum::<f64>() / 20.0;
        // the mean of 20 chi-square(63) values: 63 +- 11.2 / sqrt(20) = 2.5; 4 sigma
        assert!((mean - 63.0).abs() < 10.0, "mean chi-square {mean} over 20 seeds: {chi2s:?}");
        assert!(chi2s.iter().all(|&c| c < 120.0), "a seed fails at p < 1e-5: {chi2s:?}");
        let some = |seed| random_points(4, seed, lo, hi, |_| true).unwrap();
        assert_ne!(some(1), some(2));
        assert_eq!(some(7), some(7));
        assert!(random_points(1, 1, lo, hi, |_| false).is_err());
    }

    #[test]
    fn points_follow_lammps_order() {
        let l = Lattice::new("sc", 1.0).unwrap();
        let pts = l.points([0.0; 3], [2.0; 3]);
        assert_eq!(pts[0], [0.0, 0.0, 0.0]);
        assert_eq!(pts[1], [1.0, 0.0, 0.0]);
        assert_eq!(pts[2], [0.0, 1.0, 0.0]);
        assert_eq!(pts.len(), 8);
    }
}
