//! `lattice`, `region block` and the lattice points of `create_atoms`.

use gendpde_engine::Vec3;

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

/// `region ID block xlo xhi ylo yhi zlo zhi`, in box units.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub lo: Vec3,
    pub hi: Vec3,
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
