//! `lattice` and the points of `create_atoms` (lattice or random).

use gendpde_engine::Vec3;
use crate::base::park::Park;
use std::collections::HashMap;
use nalgebra::{Matrix3, Vector3};

/// A lattice as LAMMPS's `lattice STYLE SCALE [origin x y z] [orient dim i j k]...
/// [spacing x y z]`: basis points in the unit cell of primitive vectors a1 a2 a3, scaled,
/// rotated so that the orient directions lie along x, y, z, shifted by the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct Lattice {
    /// Primitive vectors as columns (cubic; a2 = sqrt 3, a3 = sqrt(8/3) for hcp).
    primitive: Matrix3<f64>,
    /// Rows: the normalised orient vectors.
    rotate: Matrix3<f64>,
    scale: f64,
    /// Basis points in lattice coordinates (none for `lattice none`).
    pub basis: Vec<Vec3>,
    /// LAMMPS's xlattice, ylattice, zlattice: the lengths of `units lattice`.
    pub spacing: Vec3,
    /// The origin shift in box units (spacing times the origin fractions).
    shift: Vector3<f64>,
}

/// The settings of a `lattice` command besides its style and scale.
#[derive(Clone, Debug, PartialEq)]
pub struct LatticeOptions {
    /// Fractions of the spacings, each in [0, 1).
    pub origin: Vec3,
    /// The lattice directions along x, y and z (rows).
    pub orient: [[i64; 3]; 3],
    /// Spacings in units of the scale (default: the extent of the rotated unit cell).
    pub spacing: Option<Vec3>,
}

impl Default for LatticeOptions {
    fn default() -> Self {
        Self { origin: [0.0; 3], orient: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], spacing: None }
    }
}

impl Lattice {
    /// `lattice none S`: no points, spacing S.
    pub fn none(spacing: f64) -> Self {
        let identity = Matrix3::identity();
        Self { primitive: identity, rotate: identity, scale: spacing, basis: Vec::new(), spacing: [spacing; 3], shift: Vector3::zeros() }
    }

    /// Lattice `style` (sc, bcc, fcc, hcp, diamond) of `scale`: the reduced density of
    /// points in lj units (`reduced`), else the lattice constant. Err names the problem.
    pub fn new(style: &str, scale: f64, reduced: bool, o: &LatticeOptions) -> Result<Self, String> {
        let basis: Vec<Vec3> = match style {
            "sc" => vec![[0.0; 3]],
            "bcc" => vec![[0.0; 3], [0.5; 3]],
            "fcc" => vec![[0.0; 3], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]],
            "hcp" => vec![[0.0; 3], [0.5, 0.5, 0.0], [0.5, 5.0 / 6.0, 0.5], [0.0, 1.0 / 3.0, 0.5]],
            "diamond" => vec![
                [0.0; 3],
                [0.0, 0.5, 0.5],
                [0.5, 0.0, 0.5],
                [0.5, 0.5, 0.0],
                [0.25; 3],
                [0.25, 0.75, 0.75],
                [0.75, 0.25, 0.75],
                [0.75, 0.75, 0.25],
            ],
            _ => return Err(format!("unknown lattice style '{style}'; known: none, sc, bcc, fcc, hcp, diamond")),
        };
        let primitive = if style == "hcp" { Matrix3::from_diagonal(&Vector3::new(1.0, 3f64.sqrt(), (8.0f64 / 3.0).sqrt())) } else { Matrix3::identity() };
        let [x, y, z] = o.orient.map(|v| Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64));
        if [x, y, z].iter().any(|v| v.norm() == 0.0) {
            return Err("an orient vector has zero length".into());
        }
        if x.dot(&y) != 0.0 || y.dot(&z) != 0.0 || x.dot(&z) != 0.0 {
            return Err("the orient vectors are not orthogonal".into());
        }
        if x.cross(&y).dot(&z) <= 0.0 {
            return Err("the orient vectors are not right-handed".into());
        }
        if o.origin.iter().any(|f| !(0.0..1.0).contains(f)) {
            return Err("each origin fraction must lie in [0, 1)".into());
        }
        let rotate = Matrix3::from_rows(&[x.normalize().transpose(), y.normalize().transpose(), z.normalize().transpose()]);
        // lj units: SCALE is the number density of points (as LAMMPS)
        let scale = if reduced { (basis.len() as f64 / primitive.determinant() / scale).cbrt() } else { scale };
        let mut lattice = Self { primitive, rotate, scale, basis, spacing: [0.0; 3], shift: Vector3::zeros() };
        lattice.spacing = match o.spacing {
            Some(s) => s.map(|x| x * scale),
            // the extent of the rotated unit cell
            None => {
                let corners: Vec<Vec3> = (0..8).map(|c| lattice.to_box([(c & 1) as f64, (c >> 1 & 1) as f64, (c >> 2 & 1) as f64])).collect();
                std::array::from_fn(|d| {
                    let v = corners.iter().map(|r| r[d]);
                    v.clone().fold(f64::NEG_INFINITY, f64::max) - v.fold(f64::INFINITY, f64::min)
                })
            }
        };
        lattice.shift = Vector3::from(std::array::from_fn(|d| lattice.spacing[d] * o.origin[d]));
        Ok(lattice)
    }

    /// Box coordinates of lattice coordinates `x` (LAMMPS's lattice2box).
    pub fn to_box(&self, x: Vec3) -> Vec3 {
        let r = self.rotate * (self.primitive * Vector3::from(x) * self.scale) + self.shift;
        [r.x, r.y, r.z]
    }

    /// Lattice coordinates of box coordinates `r`.
    fn to_lattice(&self, r: Vec3) -> Option<Vec3> {
        let inverse = self.primitive.try_inverse()?;
        let x = inverse * (self.rotate.transpose() * (Vector3::from(r) - self.shift) / self.scale);
        Some([x.x, x.y, x.z])
    }

    /// The unit cells whose points can fall in the block [lo, hi], per lattice axis.
    fn cells(&self, lo: Vec3, hi: Vec3) -> [std::ops::RangeInclusive<i64>; 3] {
        let corners: Vec<Vec3> = (0..8)
            .map(|c| [if c & 1 == 0 { lo[0] } else { hi[0] }, if c & 2 == 0 { lo[1] } else { hi[1] }, if c & 4 == 0 { lo[2] } else { hi[2] }])
            .filter_map(|r| self.to_lattice(r))
            .collect();
        std::array::from_fn(|d| {
            let v = corners.iter().map(|x| x[d]);
            let (min, max) = (v.clone().fold(f64::INFINITY, f64::min), v.fold(f64::NEG_INFINITY, f64::max));
            (min.floor() as i64 - 1)..=(max.ceil() as i64 + 1)
        })
    }

    /// An upper bound of the number of points in the block [lo, hi] (no allocation).
    pub fn count_bound(&self, lo: Vec3, hi: Vec3) -> f64 {
        self.cells(lo, hi).iter().map(|r| (r.end() - r.start() + 1) as f64).product::<f64>() * self.basis.len() as f64
    }

    /// The lattice points near the block [lo, hi] that `keep` takes, each with its basis
    /// index, in LAMMPS's order (z, y, x, basis).
    pub fn points(&self, lo: Vec3, hi: Vec3, keep: impl Fn(Vec3) -> bool) -> Vec<(Vec3, usize)> {
        let [ri, rj, rk] = self.cells(lo, hi);
        let mut out = Vec::new();
        for k in rk {
            for j in rj.clone() {
                for i in ri.clone() {
                    for (m, b) in self.basis.iter().enumerate() {
                        let r = self.to_box([i as f64 + b[0], j as f64 + b[1], k as f64 + b[2]]);
                        if keep(r) {
                            out.push((r, m));
                        }
                    }
                }
            }
        }
        out
    }
}

/// LAMMPS's `create_atoms random` (create_atoms.cpp `add_random`): RanPark seeded with
/// `seed`, warmed up by 30 draws, then for each of `n` particles up to `maxtry` candidates
/// `lo + u (hi - lo)` (x, y, z in turn) until `accept` takes one; a particle whose tries
/// all fail is skipped. The same points on every rank. Returns the accepted points in
/// draw order.
pub fn random_points(n: u64, seed: u64, lo: Vec3, hi: Vec3, maxtry: u64, mut accept: impl FnMut(Vec3) -> bool) -> Vec<Vec3> {
    let mut rng = Park::new(seed);
    for _ in 0..30 {
        rng.uniform();
    }
    let mut out = Vec::with_capacity(n.min(1 << 24) as usize);
    for _ in 0..n {
        for _ in 0..maxtry {
            let r: Vec3 = std::array::from_fn(|d| lo[d] + rng.uniform() * (hi[d] - lo[d]));
            if accept(r) {
                out.push(r);
                break;
            }
        }
    }
    out
}

/// The points placed so far, binned in cells at least `distance` wide, answering whether
/// a point lies closer than `distance` to any of them under LAMMPS's minimum image
/// (create_atoms `overlap`; the cells only narrow the search, the test is LAMMPS's).
pub struct Overlap {
    lo: Vec3,
    len: Vec3,
    count: [usize; 3],
    distsq: f64,
    cells: HashMap<[usize; 3], Vec<Vec3>>,
}

impl Overlap {
    /// No points yet, in the periodic box [lo, lo + len).
    pub fn new(lo: Vec3, len: Vec3, distance: f64) -> Self {
        // a margin over `distance` so that rounding never splits a close pair by two cells
        let count = std::array::from_fn(|d| ((len[d] / (distance * (1.0 + 1e-9))).floor() as usize).max(1));
        Self { lo, len, count, distsq: distance * distance, cells: HashMap::new() }
    }

    fn cell(&self, r: Vec3) -> [usize; 3] {
        std::array::from_fn(|d| {
            let f = ((r[d] - self.lo[d]) / self.len[d]).rem_euclid(1.0);
            ((f * self.count[d] as f64) as usize).min(self.count[d] - 1)
        })
    }

    pub fn add(&mut self, r: Vec3) {
        self.cells.entry(self.cell(r)).or_default().push(r);
    }

    /// Whether `r` lies closer than the distance to a point added (LAMMPS: the squared
    /// minimum-image distance below the squared overlap).
    pub fn hits(&self, r: Vec3) -> bool {
        let c = self.cell(r);
        // the cells within one of c along each axis (all of them when there are fewer than 3)
        let near = |d: usize| -> Vec<usize> {
            let n = self.count[d];
            if n < 3 { (0..n).collect() } else { vec![(c[d] + n - 1) % n, c[d], (c[d] + 1) % n] }
        };
        let (nx, ny, nz) = (near(0), near(1), near(2));
        for &i in &nx {
            for &j in &ny {
                for &k in &nz {
                    let Some(points) = self.cells.get(&[i, j, k]) else { continue };
                    for p in points {
                        let dist: Vec3 = std::array::from_fn(|d| {
                            let x = r[d] - p[d];
                            if x.abs() > 0.5 * self.len[d] { if x < 0.0 { x + self.len[d] } else { x - self.len[d] } } else { x }
                        });
                        if dist[0] * dist[0] + dist[1] * dist[1] + dist[2] * dist[2] < self.distsq {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points of the half-open block [lo, hi), with a tolerance.
    fn inside(lo: Vec3, hi: Vec3) -> impl Fn(Vec3) -> bool {
        move |r| (0..3).all(|d| r[d] >= lo[d] - 1e-9 && r[d] < hi[d] - 1e-9)
    }

    #[test]
    fn lattices_hold_the_requested_density() {
        for (style, per_cell) in [("sc", 1), ("bcc", 2), ("fcc", 4), ("hcp", 4), ("diamond", 8)] {
            let l = Lattice::new(style, 0.5, true, &LatticeOptions::default()).unwrap();
            let side = l.spacing.map(|s| 5.0 * s);
            let pts = l.points([0.0; 3], side, inside([0.0; 3], side));
            assert_eq!(pts.len(), 125 * per_cell, "{style}");
            let rho = pts.len() as f64 / side.iter().product::<f64>();
            assert!((rho - 0.5).abs() < 1e-12, "{style}: {rho}");
        }
    }

    /// A rotated lattice keeps its density; the orient vectors are checked.
    #[test]
    fn orient_rotates_and_is_checked() {
        let o = LatticeOptions { orient: [[1, 1, 0], [-1, 1, 0], [0, 0, 1]], ..Default::default() };
        let l = Lattice::new("fcc", 3.0, false, &o).unwrap();
        let s = 3.0 * 2f64.sqrt();
        assert!((l.spacing[0] - s).abs() < 1e-12 && (l.spacing[2] - 3.0).abs() < 1e-12, "{:?}", l.spacing);
        let side = [4.0 * s, 4.0 * s, 12.0];
        assert_eq!(l.points([0.0; 3], side, inside([0.0; 3], side)).len(), 4 * 4 * 4 * 8);
        let bad = |orient| Lattice::new("sc", 1.0, false, &LatticeOptions { orient, ..Default::default() }).unwrap_err();
        assert_eq!(bad([[1, 1, 0], [1, 0, 0], [0, 0, 1]]), "the orient vectors are not orthogonal");
        assert_eq!(bad([[1, 0, 0], [0, 1, 0], [0, 0, -1]]), "the orient vectors are not right-handed");
    }

    /// Chi-square of the counts in 4x4x4 bins against uniform (63 degrees of freedom:
    /// mean 63, sd 11.2), for several seeds; every point lies in the block.
    #[test]
    fn random_points_are_uniform_in_the_block() {
        let (lo, hi) = ([-1.0, 2.0, 0.5], [3.0, 2.5, 7.0]);
        let mut chi2s = Vec::new();
        for seed in 1..=20 {
            let pts = random_points(6400, seed, lo, hi, 1000, |_| true);
            assert_eq!(pts.len(), 6400);
            let mut bins = [0.0; 64];
            for r in &pts {
                assert!((0..3).all(|d| r[d] >= lo[d] && r[d] <= hi[d]), "{r:?}");
                let b: Vec<usize> = (0..3).map(|d| ((r[d] - lo[d]) / (hi[d] - lo[d]) * 4.0) as usize).collect();
                bins[b[0] + 4 * b[1] + 16 * b[2]] += 1.0;
            }
            chi2s.push(bins.iter().map(|c| (c - 100.0) * (c - 100.0) / 100.0).sum::<f64>());
        }
        let mean = chi2s.iter().sum::<f64>() / 20.0;
        // the mean of 20 chi-square(63) values: 63 +- 11.2 / sqrt(20) = 2.5; 4 sigma
        assert!((mean - 63.0).abs() < 10.0, "mean chi-square {mean} over 20 seeds: {chi2s:?}");
        assert!(chi2s.iter().all(|&c| c < 120.0), "a seed fails at p < 1e-5: {chi2s:?}");
        let some = |seed| random_points(4, seed, lo, hi, 1000, |_| true);
        assert_ne!(some(1), some(2));
        assert_eq!(some(7), some(7));
        assert!(random_points(3, 1, lo, hi, 5, |_| false).is_empty());
    }

    /// The cells find every pair closer than the distance across the periodic faces, as
    /// the all-pairs minimum-image test does.
    #[test]
    fn overlap_agrees_with_all_pairs() {
        let (lo, len, dist) = ([0.0, -1.0, 2.0], [5.0, 3.0, 1.1], 0.7);
        let placed = random_points(300, 3, lo, [5.0, 2.0, 3.1], 1, |_| true);
        let mut o = Overlap::new(lo, len, dist);
        placed.iter().for_each(|&p| o.add(p));
        let image = |x: f64, l: f64| if x.abs() > 0.5 * l { if x < 0.0 { x + l } else { x - l } } else { x };
        for r in random_points(2000, 4, lo, [5.0, 2.0, 3.1], 1, |_| true) {
            let brute = placed.iter().any(|p| (0..3).map(|d| image(r[d] - p[d], len[d]).powi(2)).sum::<f64>() < dist * dist);
            assert_eq!(o.hits(r), brute, "{r:?}");
        }
    }

    #[test]
    fn points_follow_lammps_order() {
        let l = Lattice::new("sc", 1.0, true, &LatticeOptions::default()).unwrap();
        let pts = l.points([0.0; 3], [2.0; 3], inside([0.0; 3], [2.0; 3]));
        assert_eq!(pts[0], ([0.0, 0.0, 0.0], 0));
        assert_eq!(pts[1], ([1.0, 0.0, 0.0], 0));
        assert_eq!(pts[2], ([0.0, 1.0, 0.0], 0));
        assert_eq!(pts.len(), 8);
    }
}
