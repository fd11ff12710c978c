//! Counter-based random numbers: Philox4x32-10 (Salmon et al., SC'11).
//!
//! Every random number of a step is a pure function of (seed, step, min tag, max tag,
//! stream), so no rank count or sweep order can change it.

const M0: u32 = 0xD251_1F53;
const M1: u32 = 0xCD9E_8D57;
const W0: u32 = 0x9E37_79B9;
const W1: u32 = 0xBB67_AE85;

/// Streams that keep the uses of one key independent.
pub mod stream {
    /// Pair friction noise xi and heat noise xibar.
    pub const PAIR: u32 = 0;
    /// Heat-reservoir noise of one particle.
    pub const RESERVOIR: u32 = 1;
    /// `velocity create`.
    pub const VELOCITY: u32 = 2;
    /// Random pair forces of `pair dpd` and `pair mdpd`.
    pub const FORCE: u32 = 3;
}

/// Philox4x32 with 10 rounds.
#[inline(always)]
pub fn philox4x32(ctr: [u32; 4], key: [u32; 2]) -> [u32; 4] {
    let (mut c, mut k) = (ctr, key);
    for _ in 0..10 {
        let p0 = (M0 as u64) * (c[0] as u64);
        let p1 = (M1 as u64) * (c[2] as u64);
        c = [((p1 >> 32) as u32) ^ c[1] ^ k[0], p1 as u32, ((p0 >> 32) as u32) ^ c[3] ^ k[1], p0 as u32];
        k = [k[0].wrapping_add(W0), k[1].wrapping_add(W1)];
    }
    c
}

/// Uniform in the open interval (0, 1) from 64 random bits (53 used).
#[inline(always)]
fn open_unit(hi: u32, lo: u32) -> f64 {
    let x = (((hi as u64) << 32) | lo as u64) >> 11;
    (x as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// Two independent standard normal numbers for the key, by Box-Muller.
#[inline(always)]
pub fn normal_pair(seed: u64, step: u64, a: u64, b: u64, stream: u32) -> (f64, f64) {
    let x = uniform4(seed, step, a, b, stream);
    let r = (-2.0 * x[0].ln()).sqrt();
    let (s, c) = (std::f64::consts::TAU * x[1]).sin_cos();
    (r * c, r * s)
}

/// Two uniforms in (0, 1) for the key (the other two outputs of the block are unused).
#[inline(always)]
pub fn uniform4(seed: u64, step: u64, a: u64, b: u64, stream: u32) -> [f64; 2] {
    let ctr = [step as u32, a as u32, b as u32, stream ^ ((step >> 32) as u32).rotate_left(16)];
    let o = philox4x32(ctr, [seed as u32, (seed >> 32) as u32]);
    [open_unit(o[0], o[1]), open_unit(o[2], o[3])]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Known-answer vectors of the Random123 distribution (kat_vectors, philox4x32_10).
    #[test]
    fn philox_matches_random123_known_answers() {
        assert_eq!(philox4x32([0; 4], [0; 2]), [0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8]);
        assert_eq!(philox4x32([u32::MAX; 4], [u32::MAX; 2]), [0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd]);
        assert_eq!(
            philox4x32([0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344], [0xa4093822, 0x299f31d0]),
            [0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1]
        );
    }

    #[test]
    fn normals_have_unit_moments_and_are_uncorrelated() {
        let n = 200_000;
        let (mut s1, mut s2, mut q1, mut q2, mut c, mut k4) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let (a, b) = normal_pair(42, 7, i, i + 1, stream::PAIR);
            s1 += a;
            s2 += b;
            q1 += a * a;
            q2 += b * b;
            c += a * b;
            k4 += a * a * a * a;
        }
        let n = n as f64;
        // 5 standard errors of each estimator
        assert!((s1 / n).abs() < 5.0 / n.sqrt() && (s2 / n).abs() < 5.0 / n.sqrt());
        assert!((q1 / n - 1.0).abs() < 5.0 * (2.0 / n).sqrt() && (q2 / n - 1.0).abs() < 5.0 * (2.0 / n).sqrt());
        assert!((c / n).abs() < 5.0 / n.sqrt());
        assert!((k4 / n - 3.0).abs() < 5.0 * (96.0 / n).sqrt());
    }

    #[test]
    fn keys_differ_in_every_component() {
        let base = normal_pair(1, 2, 3, 4, 0);
        for other in [normal_pair(9, 2, 3, 4, 0), normal_pair(1, 9, 3, 4, 0), normal_pair(1, 2, 9, 4, 0),
                      normal_pair(1, 2, 3, 9, 0), normal_pair(1, 2, 3, 4, 1), normal_pair(1, 2 + (1 << 32), 3, 4, 0)] {
            assert_ne!(base, other);
        }
    }
}
