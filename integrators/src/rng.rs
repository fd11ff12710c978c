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
    /// Random pair forces of `pair dpd` and `pair mdpd`.
    pub const FORCE: u32 = 3;
    /// The second pair of random pair forces of `pair dpd/ext` (across the pair axis).
    pub const FORCE_PERP: u32 = 4;
    /// Random stress and heat flux of one Voronoi cell (voronoi/finite_volume.rs).
    pub const VORONOI: u32 = 5;
    /// Pair noises dW, dV of one Voronoi DPD face (voronoi/dpd.rs): VORONOI_PAIR + the
    /// code (0..27) of the face's periodic image.
    pub const VORONOI_PAIR: u32 = 1 << 24;
    /// Brownian-bridge noises of split pair updates: SUBSTEP + node of the split tree.
    pub const SUBSTEP: u32 = 16;
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

/// [`philox4x32`] of `L` counters under one key: the same bits as `L` calls. On x86_64
/// the lanes run side by side in SSE2 registers (part of the x86_64 baseline), two per
/// register with each 32-bit word in a 64-bit slot: a round is two packed 32x32 -> 64-bit
/// multiplies, two shifts and four xors per two lanes, ~5 instructions per lane against
/// ~12 scalar.
#[inline(always)]
fn philox4x32_lanes<const L: usize>(ctr: [[u32; 4]; L], key: [u32; 2]) -> [[u32; 4]; L] {
    #[cfg(target_arch = "x86_64")]
    if L % 4 == 0 {
        return sse2::philox4x32_lanes(ctr, key);
    }
    ctr.map(|c| philox4x32(c, key))
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    use super::{M0, M1, W0, W1};
    use std::arch::x86_64::{__m128i, _mm_loadu_si128, _mm_mul_epu32, _mm_set1_epi64x, _mm_srli_epi64, _mm_storeu_si128, _mm_xor_si128};

    /// [`super::philox4x32_lanes`] for `L` a multiple of 4: four lanes per round body in
    /// two registers a word, the ten rounds unrolled. The upper halves of the 64-bit slots
    /// carry garbage between rounds (the multiplies read only the lower halves, and a
    /// word's garbage reaches only words that are next multiplied or finally truncated).
    #[inline(always)]
    pub(super) fn philox4x32_lanes<const L: usize>(ctr: [[u32; 4]; L], key: [u32; 2]) -> [[u32; 4]; L] {
        let mut out = [[0u32; 4]; L];
        for (lanes, into) in ctr.chunks_exact(4).zip(out.chunks_exact_mut(4)) {
            // SAFETY: SSE2 is part of the x86_64 baseline; loads and stores go through
            // arrays of two u64 (16 bytes, unaligned access).
            unsafe {
                let load = |w: usize, h: usize| {
                    let slots = [lanes[2 * h][w] as u64, lanes[2 * h + 1][w] as u64];
                    _mm_loadu_si128(slots.as_ptr().cast::<__m128i>())
                };
                let (m0, m1) = (_mm_set1_epi64x(M0 as i64), _mm_set1_epi64x(M1 as i64));
                // word w of lanes 0, 1 in c[w][0], of lanes 2, 3 in c[w][1]
                let mut c: [[__m128i; 2]; 4] = std::array::from_fn(|w| [load(w, 0), load(w, 1)]);
                macro_rules! round {
                    ($r:expr) => {{
                        let k0 = _mm_set1_epi64x(key[0].wrapping_add(W0.wrapping_mul($r)) as i64);
                        let k1 = _mm_set1_epi64x(key[1].wrapping_add(W1.wrapping_mul($r)) as i64);
                        for h in 0..2 {
                            let p0 = _mm_mul_epu32(c[0][h], m0);
                            let p1 = _mm_mul_epu32(c[2][h], m1);
                            c[0][h] = _mm_xor_si128(_mm_xor_si128(_mm_srli_epi64::<32>(p1), c[1][h]), k0);
                            c[1][h] = p1;
                            c[2][h] = _mm_xor_si128(_mm_xor_si128(_mm_srli_epi64::<32>(p0), c[3][h]), k1);
                            c[3][h] = p0;
                        }
                    }};
                }
                round!(0);
                round!(1);
                round!(2);
                round!(3);
                round!(4);
                round!(5);
                round!(6);
                round!(7);
                round!(8);
                round!(9);
                let mut words = [[[0u64; 2]; 2]; 4];
                for (w, halves) in c.iter().enumerate() {
                    for (h, &v) in halves.iter().enumerate() {
                        _mm_storeu_si128(words[w][h].as_mut_ptr().cast::<__m128i>(), v);
                    }
                }
                for (l, o) in into.iter_mut().enumerate() {
                    let (h, s) = (l / 2, l % 2);
                    *o = [words[0][h][s] as u32, words[1][h][s] as u32, words[2][h][s] as u32, words[3][h][s] as u32];
                }
            }
        }
        out
    }
}

/// Two independent standard normal numbers for the key, by the ziggurat method
/// (Marsaglia and Tsang 2000, Doornik's 128-layer variant): one Philox block feeds both
/// draws; the rare draws that fall outside the rectangles take further blocks of the
/// same key with a counter of their own.
#[inline(always)]
pub fn normal_pair(seed: u64, step: u64, a: u64, b: u64, stream: u32) -> (f64, f64) {
    Normals::get().pair(seed, step, a, b, stream)
}

/// [`normal_pair`] with the ziggurat table fetched once, for loops over many pairs.
#[derive(Clone, Copy)]
pub struct Normals(&'static Ziggurat);

/// Pairs whose noises a Shardlow sweep draws together ([`Normals::pairs`]).
pub const LANES: usize = 4;

impl Normals {
    pub fn get() -> Self {
        Self(ziggurat())
    }

    /// As [`normal_pair`].
    #[inline(always)]
    pub fn pair(self, seed: u64, step: u64, a: u64, b: u64, stream: u32) -> (f64, f64) {
        let ctr = counter(step, a, b, stream);
        let key = key_of(seed);
        self.draws(philox4x32(ctr, key), ctr, key)
    }

    /// [`Normals::pair`] of `L` keys `(a, b)` at once, their Philox blocks side by side
    /// ([`philox4x32_lanes`]): the same numbers as `L` calls. For loops whose keys are
    /// known ahead (the Shardlow sweep's pairs: tags and step do not change in a sweep).
    #[inline(always)]
    pub fn pairs<const L: usize>(self, seed: u64, step: u64, ab: [(u64, u64); L], stream: u32) -> [(f64, f64); L] {
        let ctr = ab.map(|(a, b)| counter(step, a, b, stream));
        let key = key_of(seed);
        let o = philox4x32_lanes(ctr, key);
        let mut draws = [(0.0, 0.0); L];
        for (l, d) in draws.iter_mut().enumerate() {
            *d = self.draws(o[l], ctr[l], key);
        }
        draws
    }

    /// The two ziggurat draws of block `o` of counter `ctr`.
    #[inline(always)]
    fn draws(self, o: [u32; 4], ctr: [u32; 4], key: [u32; 2]) -> (f64, f64) {
        let z = self.0;
        let (b0, b1) = (((o[0] as u64) << 32) | o[1] as u64, ((o[2] as u64) << 32) | o[3] as u64);
        let first = z.fast(b0).unwrap_or_else(|| z.slow(b0, ctr, key, 0));
        let second = z.fast(b1).unwrap_or_else(|| z.slow(b1, ctr, key, 1));
        (first, second)
    }
}

/// The Philox counter of key (step, a, b, stream).
#[inline(always)]
fn counter(step: u64, a: u64, b: u64, stream: u32) -> [u32; 4] {
    [step as u32, a as u32, b as u32, stream ^ ((step >> 32) as u32).rotate_left(16)]
}

#[inline(always)]
fn key_of(seed: u64) -> [u32; 2] {
    [seed as u32, (seed >> 32) as u32]
}

const LAYERS: usize = 128;
const ZIG_R: f64 = 3.442619855899;
const ZIG_V: f64 = 9.91256303526217e-3;

/// Layer edges x[i], densities f(x[i]) = exp(-x^2/2) and edge ratios x[i+1]/x[i] of
/// the ziggurat.
struct Ziggurat {
    x: [f64; LAYERS + 1],
    f: [f64; LAYERS + 1],
    ratio: [f64; LAYERS],
}

fn ziggurat() -> &'static Ziggurat {
    static TABLE: std::sync::OnceLock<Ziggurat> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let pdf = |x: f64| (-0.5 * x * x).exp();
        let mut x = [0.0; LAYERS + 1];
        x[0] = ZIG_V / pdf(ZIG_R);
        x[1] = ZIG_R;
        for i in 2..LAYERS {
            x[i] = (-2.0 * (ZIG_V / x[i - 1] + pdf(x[i - 1])).ln()).sqrt();
        }
        x[LAYERS] = 0.0;
        Ziggurat { x, f: x.map(pdf), ratio: std::array::from_fn(|i| x[i + 1] / x[i]) }
    })
}

impl Ziggurat {
    /// The draw from 64 random bits when it lands inside a rectangle (~99 %).
    #[inline(always)]
    fn fast(&self, bits: u64) -> Option<f64> {
        let i = (bits & 0x7f) as usize;
        let u = 2.0 * (((bits >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)) - 1.0;
        (u.abs() < self.ratio[i]).then(|| u * self.x[i])
    }

    /// Completes draw `which` whose first 64 bits `first` missed the rectangles: the
    /// wedge or tail test of that same (layer, u), then fresh attempts, with uniforms from
    /// further blocks of the key (counters marked in the top bit of the stream word).
    #[cold]
    fn slow(&self, first: u64, ctr: [u32; 4], key: [u32; 2], which: u32) -> f64 {
        let mut attempt = 0u32;
        let block = |attempt: u32| {
            let c = [ctr[0], ctr[1], ctr[2], ctr[3] ^ 0x8000_0000 ^ (which << 30) ^ attempt];
            let o = philox4x32(c, key);
            [((o[0] as u64) << 32) | o[1] as u64, ((o[2] as u64) << 32) | o[3] as u64]
        };
        let unit = |bits: u64| ((bits >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
        let mut bits = first;
        loop {
            let [extra, next] = block(attempt);
            attempt += 1;
            let i = (bits & 0x7f) as usize;
            let u = 2.0 * unit(bits) - 1.0;
            bits = next;
            if u.abs() < self.ratio[i] {
                return u * self.x[i];
            }
            if i == 0 {
                // the tail beyond R (Marsaglia 1964)
                loop {
                    let [t0, t1] = block(attempt);
                    attempt += 1;
                    let xt = -unit(t0).ln() / ZIG_R;
                    let yt = -unit(t1).ln();
                    if 2.0 * yt > xt * xt {
                        return if u < 0.0 { -(ZIG_R + xt) } else { ZIG_R + xt };
                    }
                }
            }
            let xx = u * self.x[i];
            if self.f[i + 1] + unit(extra) * (self.f[i] - self.f[i + 1]) < (-0.5 * xx * xx).exp() {
                return xx;
            }
        }
    }
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

    /// The lanes of [`Normals::pairs`] are the single draws bit for bit, over keys that
    /// reach the ziggurat's slow path and the tail (~1 % and ~0.03 % of draws).
    #[test]
    fn lanes_are_the_single_draws() {
        let z = Normals::get();
        let seeds = [0, 4928459, u64::MAX, 0x1234_5678_9abc_def0];
        let steps = [0, 1, 77, (1 << 32) + 5, u64::MAX];
        for (s, &seed) in seeds.iter().enumerate() {
            for &step in &steps {
                for n in 0..2_000u64 {
                    let ab: [(u64, u64); 4] = std::array::from_fn(|l| (n * 4 + l as u64, (n * 4 + l as u64) * 7919 + s as u64));
                    let lanes = z.pairs(seed, step, ab, stream::PAIR);
                    for (l, &(a, b)) in ab.iter().enumerate() {
                        let one = z.pair(seed, step, a, b, stream::PAIR);
                        assert_eq!((lanes[l].0.to_bits(), lanes[l].1.to_bits()), (one.0.to_bits(), one.1.to_bits()));
                    }
                }
            }
        }
    }

    /// The SSE2 lanes give the scalar blocks.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn sse2_lanes_are_the_scalar_philox() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 32) as u32
        };
        for _ in 0..5_000 {
            let ctr: [[u32; 4]; 8] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
            let key = [next(), next()];
            assert_eq!(sse2::philox4x32_lanes(ctr, key), ctr.map(|c| philox4x32(c, key)));
        }
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

    /// The distribution, not just its moments: Kolmogorov-Smirnov against the normal CDF
    /// over 400 000 draws, with the tails (|x| > 3) counted against their exact weight.
    #[test]
    fn normals_follow_the_normal_distribution() {
        let n = 200_000u64;
        let mut xs: Vec<f64> = (0..n).flat_map(|i| {
            let (a, b) = normal_pair(7, i, 3, 5, stream::PAIR);
            [a, b]
        }).collect();
        xs.sort_by(f64::total_cmp);
        let cdf = |x: f64| 0.5 * (1.0 + erf(x / std::f64::consts::SQRT_2));
        let m = xs.len() as f64;
        let d = xs.iter().enumerate().map(|(k, &x)| (cdf(x) - k as f64 / m).abs().max((cdf(x) - (k + 1) as f64 / m).abs())).fold(0.0, f64::max);
        // KS critical value at p = 0.001: 1.95 / sqrt(m)
        assert!(d < 1.95 / m.sqrt(), "KS distance {d}");
        let tail = xs.iter().filter(|x| x.abs() > 3.0).count() as f64 / m;
        let exact = 2.0 * (1.0 - cdf(3.0));
        assert!((tail - exact).abs() < 5.0 * (exact / m).sqrt(), "tail {tail} vs {exact}");
    }

    /// erf: Taylor series for |x| <= 3 (cancellation stays below 1e-12 there), the
    /// asymptotic series of erfc beyond (error below 1e-7 for |x| > 3).
    fn erf(x: f64) -> f64 {
        if x.abs() > 3.0 {
            let y = x.abs();
            let erfc = (-y * y).exp() / (y * std::f64::consts::PI.sqrt())
                * (1.0 - 1.0 / (2.0 * y * y) + 3.0 / (4.0 * y.powi(4)) - 15.0 / (8.0 * y.powi(6)));
            return x.signum() * (1.0 - erfc);
        }
        let (mut term, mut sum, mut n) = (x, x, 0.0);
        while term.abs() > 1e-17 * sum.abs().max(1e-300) && n < 200.0 {
            n += 1.0;
            term *= -x * x / n;
            sum += term / (2.0 * n + 1.0);
        }
        2.0 / std::f64::consts::PI.sqrt() * sum
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
