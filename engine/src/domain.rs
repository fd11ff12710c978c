//! The orthogonal periodic simulation box.

use crate::Vec3;

/// An orthogonal box [lo, hi) periodic in the dimensions flagged `periodic`.
#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    pub lo: Vec3,
    pub hi: Vec3,
    pub periodic: [bool; 3],
}

impl Domain {
    pub fn new(lo: Vec3, hi: Vec3) -> Self {
        Self { lo, hi, periodic: [true; 3] }
    }

    pub fn len(&self) -> Vec3 {
        [self.hi[0] - self.lo[0], self.hi[1] - self.lo[1], self.hi[2] - self.lo[2]]
    }

    pub fn volume(&self) -> f64 {
        let l = self.len();
        l[0] * l[1] * l[2]
    }

    /// Maps `r` into [lo, hi) and counts the box crossings in `image`. Non-finite
    /// coordinates are left as they are (the integrator reports them).
    pub fn wrap(&self, r: &mut Vec3, image: &mut [i32; 3]) {
        let l = self.len();
        for d in 0..3 {
            if !self.periodic[d] || !r[d].is_finite() {
                continue;
            }
            if r[d] >= self.hi[d] || r[d] < self.lo[d] {
                let k = ((r[d] - self.lo[d]) / l[d]).floor();
                r[d] -= k * l[d];
                image[d] = image[d].saturating_add(k.clamp(i32::MIN as f64, i32::MAX as f64) as i32);
            }
            // rounding can leave r at hi itself or just below lo
            if r[d] >= self.hi[d] {
                r[d] -= l[d];
                image[d] = image[d].saturating_add(1);
            }
            if r[d] < self.lo[d] {
                r[d] = self.lo[d];
            }
        }
    }

    /// Position with the periodic images undone.
    pub fn unwrap(&self, r: Vec3, image: [i32; 3]) -> Vec3 {
        let l = self.len();
        [r[0] + image[0] as f64 * l[0], r[1] + image[1] as f64 * l[1], r[2] + image[2] as f64 * l[2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_counts_images_and_stays_inside() {
        let d = Domain::new([0.0; 3], [2.0, 3.0, 4.0]);
        let mut r = [4.5, -0.5, 3.999];
        let mut im = [0; 3];
        d.wrap(&mut r, &mut im);
        assert_eq!(im, [2, -1, 0]);
        assert!((r[0] - 0.5).abs() < 1e-15 && (r[1] - 2.5).abs() < 1e-15);
        assert_eq!(d.unwrap(r, im), [4.5, -0.5, 3.999]);
        let mut tiny = [-1e-300, 0.0, 0.0];
        d.wrap(&mut tiny, &mut im);
        assert!(tiny[0] >= 0.0 && tiny[0] < 2.0);
        // far away and non-finite coordinates neither loop nor panic
        let (mut far, mut im) = ([1e300, f64::INFINITY, f64::NAN], [0; 3]);
        d.wrap(&mut far, &mut im);
        assert!(far[0] >= 0.0 && far[0] < 2.0 && far[1].is_infinite() && far[2].is_nan());
    }
}
