//! LAMMPS's Park–Miller generator (RanPark: minimal standard, multiplier 16807 modulo
//! 2^31 - 1, Schrage's method), with its position-keyed reseeding. The script commands
//! that LAMMPS randomises with it (`velocity create`, `set type/fraction`, `create_atoms
//! random`) draw the same numbers here, so they give LAMMPS's values for the same seed
//! and coordinates.

const IA: i32 = 16807;
const IM: i32 = 2_147_483_647;
const IQ: i32 = 127_773;
const IR: i32 = 2836;

/// Largest seed (LAMMPS reads seeds as C ints).
pub const MAX_SEED: u64 = IM as u64;

pub struct Park {
    seed: i32,
    /// The second normal of the last Marsaglia pair, not yet returned.
    saved: Option<f64>,
}

impl Park {
    /// A stream from `seed` in 1..=[`MAX_SEED`].
    pub fn new(seed: u64) -> Self {
        debug_assert!((1..=MAX_SEED).contains(&seed));
        Self { seed: seed as i32, saved: None }
    }

    /// LAMMPS's `RanPark::reset(seed, coord)`: the state becomes Jenkins's one-at-a-time
    /// hash of the bytes of the seed (a C int) and of the three coordinates (doubles),
    /// each byte read as a signed char; 27 bits are kept (LAMMPS masks with 0x7ffffff),
    /// then 5 numbers are discarded.
    pub fn at(seed: u64, x: [f64; 3]) -> Self {
        let mut hash: u32 = 0;
        let mut mix = |b: u8| {
            hash = hash.wrapping_add(b as i8 as i32 as u32);
            hash = hash.wrapping_add(hash << 10);
            hash ^= hash >> 6;
        };
        (seed as i32).to_le_bytes().into_iter().for_each(&mut mix);
        x.iter().flat_map(|c| c.to_le_bytes()).for_each(&mut mix);
        hash = hash.wrapping_add(hash << 3);
        hash ^= hash >> 11;
        hash = hash.wrapping_add(hash << 15);
        let mut p = Self { seed: ((hash & 0x7ff_ffff) as i32).max(1), saved: None };
        for _ in 0..5 {
            p.uniform();
        }
        p
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        let k = self.seed / IQ;
        self.seed = IA * (self.seed - k * IQ) - IR * k;
        if self.seed < 0 {
            self.seed += IM;
        }
        self.seed as f64 * (1.0 / IM as f64)
    }

    /// Standard normal (Marsaglia's polar method; the pair's second value is returned
    /// by the next call, as in LAMMPS).
    pub fn gaussian(&mut self) -> f64 {
        if let Some(x) = self.saved.take() {
            return x;
        }
        loop {
            let v1 = 2.0 * self.uniform() - 1.0;
            let v2 = 2.0 * self.uniform() - 1.0;
            let rsq = v1 * v1 + v2 * v2;
            if rsq < 1.0 && rsq != 0.0 {
                let fac = (-2.0 * rsq.ln() / rsq).sqrt();
                self.saved = Some(v1 * fac);
                return v2 * fac;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The minimal standard's check value (Park & Miller 1988): from seed 1 the
    /// 10000th state is 1043618065.
    #[test]
    fn minimal_standard_check_value() {
        let mut p = Park::new(1);
        for _ in 0..9999 {
            p.uniform();
        }
        assert_eq!((p.uniform() * IM as f64).round() as i64, 1_043_618_065);
    }

    #[test]
    fn gaussian_pairs_have_unit_variance() {
        let mut p = Park::new(12345);
        let n = 200_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let x = p.gaussian();
            s += x;
            s2 += x * x;
        }
        let mean = s / n as f64;
        // standard errors 1/sqrt(n) = 0.0022 and sqrt(2/n) = 0.0032; 5 sigma
        assert!(mean.abs() < 0.011, "{mean}");
        assert!((s2 / n as f64 - 1.0).abs() < 0.016, "{}", s2 / n as f64);
    }

    #[test]
    fn position_keyed_streams_differ_by_position_and_seed() {
        let a = Park::at(7, [1.0, 2.0, 3.0]).uniform();
        assert_eq!(a, Park::at(7, [1.0, 2.0, 3.0]).uniform());
        assert_ne!(a, Park::at(8, [1.0, 2.0, 3.0]).uniform());
        assert_ne!(a, Park::at(7, [1.0, 2.0, 3.0 + 1e-15]).uniform());
    }
}
