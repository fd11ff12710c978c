//! `region ID block|sphere|cylinder ... [side in|out]`: geometric regions in box units,
//! with LAMMPS's inclusive boundaries.

use gendpde_engine::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// Axis-aligned; infinite bounds leave a side open (INF, EDGE).
    Block { lo: Vec3, hi: Vec3 },
    Sphere { centre: Vec3, radius: f64 },
    /// Along `axis` from `lo` to `hi`, through (c1, c2) in the other two axes in order.
    Cylinder { axis: usize, c: [f64; 2], radius: f64, lo: f64, hi: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub shape: Shape,
    /// `side out`: the region is everything outside the shape.
    pub outside: bool,
}

impl Region {
    /// Whether `x` lies in the region (the shape's boundary belongs to the shape, as in
    /// LAMMPS's match).
    pub fn contains(&self, x: Vec3) -> bool {
        let inside = match &self.shape {
            Shape::Block { lo, hi } => (0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]),
            Shape::Sphere { centre, radius } => (0..3).map(|d| (x[d] - centre[d]).powi(2)).sum::<f64>().sqrt() <= *radius,
            Shape::Cylinder { axis, c, radius, lo, hi } => {
                let (a, b) = Self::others(*axis);
                let dist = ((x[a] - c[0]).powi(2) + (x[b] - c[1]).powi(2)).sqrt();
                dist <= *radius && x[*axis] >= *lo && x[*axis] <= *hi
            }
        };
        inside != self.outside
    }

    /// The bounding box of the region, None when it is unbounded (`side out`).
    pub fn extent(&self) -> Option<(Vec3, Vec3)> {
        if self.outside {
            return None;
        }
        Some(match &self.shape {
            Shape::Block { lo, hi } => (*lo, *hi),
            Shape::Sphere { centre, radius } => (centre.map(|c| c - radius), centre.map(|c| c + radius)),
            Shape::Cylinder { axis, c, radius, lo, hi } => {
                let (a, b) = Self::others(*axis);
                let (mut l, mut h) = ([0.0; 3], [0.0; 3]);
                (l[*axis], h[*axis]) = (*lo, *hi);
                (l[a], h[a], l[b], h[b]) = (c[0] - radius, c[0] + radius, c[1] - radius, c[1] + radius);
                (l, h)
            }
        })
    }

    /// The two axes across a cylinder along `axis`, in LAMMPS's order of c1, c2.
    pub fn others(axis: usize) -> (usize, usize) {
        match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundaries_belong_to_the_shape_and_side_out_inverts() {
        let sphere = Region { shape: Shape::Sphere { centre: [1.0, 2.0, 3.0], radius: 2.0 }, outside: false };
        assert!(sphere.contains([3.0, 2.0, 3.0]) && !sphere.contains([3.0 + 1e-12, 2.0, 3.0]));
        let out = Region { outside: true, ..sphere.clone() };
        assert!(!out.contains([3.0, 2.0, 3.0]) && out.contains([3.1, 2.0, 3.0]));
        assert_eq!(sphere.extent(), Some(([-1.0, 0.0, 1.0], [3.0, 4.0, 5.0])));
        assert_eq!(out.extent(), None);
        // along y through x = 1, z = 2
        let cyl = Region { shape: Shape::Cylinder { axis: 1, c: [1.0, 2.0], radius: 1.0, lo: 0.0, hi: 5.0 }, outside: false };
        assert!(cyl.contains([2.0, 5.0, 2.0]) && !cyl.contains([2.0, 5.1, 2.0]) && !cyl.contains([1.0, 1.0, 3.1]));
        assert_eq!(cyl.extent(), Some(([0.0, 0.0, 1.0], [2.0, 5.0, 3.0])));
        let block = Region { shape: Shape::Block { lo: [0.0; 3], hi: [1.0; 3] }, outside: false };
        assert!(block.contains([1.0, 0.0, 0.5]) && !block.contains([1.0, -1e-15, 0.5]));
    }
}
