//! A padded, Owen-scrambled Sobol sampler (Burley 2020, "Practical Hash-based Owen Scrambling").
//!
//! Every value is a pure function of `(seed, pixel, sample index, dimension)`: a [`Sampler`]
//! holds those four numbers and nothing else, so any sample can be replayed on its own and an
//! image does not depend on how its samples are spread over threads.
//!
//! # How a value is made
//! Each draw (one value for [`Sampler::next_1d`], a pair for [`Sampler::next_2d`]) is taken from
//! the first one or two dimensions of the Sobol sequence, which together form a
//! (0,2)-sequence in base 2: for `N = 2^k`, any aligned block of `N` consecutive points puts
//! exactly one point in every elementary interval of area `1/N` (every `2^a × 2^(k−a)` grid).
//! To use that pair again and again without the draws being correlated with one another
//! ("padding"), each draw
//! 1. shuffles the sample index: Owen-scrambles its bits with a key hashed from
//!    `(seed, pixel, dimension)`. Each bit is flipped by a function of the bits above it, so
//!    the indices `[0, 2^k)` go to one aligned block of `2^k` indices, permuted: the first
//!    `2^k` samples of a pixel are one aligned block of the sequence and stay a net;
//! 2. takes the Sobol point of the shuffled index;
//! 3. Owen-scrambles each coordinate with a key of its own, which keeps the net property and
//!    decorrelates pixels and draws.
//!
//! The Owen scrambles use a Laine–Karras style hash: a bijection of 32-bit words in which bit
//! `b` of the output is bit `b` of the input flipped by a function of the bits below it (what
//! additions and multiplications do), applied to the bit-reversed value so that the most
//! significant bits of the fraction decide the flips of the less significant ones.

use arrayvec::ArrayVec;
use glam::Vec2;

use crate::lanes::LANES;

use super::{Rng, hash, mix64, to_unit_float};

/// Distinguishes the sampler's scrambling keys from other uses of [`hash`] with the same
/// arguments (the digits of π).
const KEY_SALT: u64 = 0x3243_f6a8_885a_308d;

/// The columns of the generator matrix of Sobol's second dimension, most significant bit
/// first: the direction numbers of the primitive polynomial `x + 1`, `v₀ = 1/2`,
/// `vⱼ₊₁ = vⱼ ⊕ (vⱼ >> 1)` (Pascal's triangle mod 2: `m = 1, 3, 5, 15, 17, 51, …`).
const SOBOL_1_MATRIX: [u32; 32] = sobol_1_matrix();

const fn sobol_1_matrix() -> [u32; 32] {
    let mut columns = [0u32; 32];
    let mut v = 1u32 << 31;
    let mut j = 0;
    while j < 32 {
        columns[j] = v;
        v ^= v >> 1;
        j += 1;
    }
    columns
}

/// Sobol's second dimension as a 32-bit fraction: the xor of the matrix columns of the set
/// bits of `index` (the definition, bit by bit; the sampler uses [`sobol_1_reversed`]).
#[cfg(test)]
fn sobol_1(index: u32) -> u32 {
    (0..32)
        .filter(|j| index & (1 << j) != 0)
        .fold(0, |x, j| x ^ SOBOL_1_MATRIX[j])
}

/// Sobol's second dimension bit-reversed, `sobol_1(index).reverse_bits()`: what an Owen
/// scramble starts from.
#[inline]
fn sobol_1_reversed(index: u32) -> u32 {
    // The matrix is linear over GF(2), and so is reversal: the xor of one table entry per byte
    // of the index, branch-free (a scrambled index has all 32 bits in play).
    let t = &SOBOL_1_BYTES_REVERSED;
    t[0][(index & 0xff) as usize]
        ^ t[1][((index >> 8) & 0xff) as usize]
        ^ t[2][((index >> 16) & 0xff) as usize]
        ^ t[3][(index >> 24) as usize]
}

/// [`sobol_1_reversed`] of every byte value in each of the four byte positions.
static SOBOL_1_BYTES_REVERSED: [[u32; 256]; 4] = sobol_1_bytes_reversed();

const fn sobol_1_bytes_reversed() -> [[u32; 256]; 4] {
    let mut t = [[0u32; 256]; 4];
    let mut byte = 0;
    while byte < 4 {
        let mut v = 0;
        while v < 256 {
            let mut x = 0u32;
            let mut bit = 0;
            while bit < 8 {
                if v & (1 << bit) != 0 {
                    x ^= SOBOL_1_MATRIX[byte * 8 + bit];
                }
                bit += 1;
            }
            t[byte][v] = x.reverse_bits();
            v += 1;
        }
        byte += 1;
    }
    t
}

/// A key-dependent bijection of 32-bit words in which bit `b` of the output is bit `b` of the
/// input flipped by a function of the input bits below `b` (and the key).
///
/// Every step keeps that shape: adding a key (the carry into bit `b` comes from lower bits),
/// multiplying by an odd number (`x·(2m + 1) = x + 2m·x`), and xoring in `x` times an even
/// number (whose bit `b` depends on the bits of `x` below `b`). The key enters three times,
/// through an addition and an odd multiplier, so that the flip of each bit depends on the key
/// as well as on the lower bits; the fixed even multipliers spread the lower bits upward.
#[inline]
fn laine_karras_permute(mut x: u32, key: u64) -> u32 {
    let (k0, k1) = (key as u32, (key >> 32) as u32);
    x = x.wrapping_add(k0);
    x ^= x.wrapping_mul(0x2f4a_7c16);
    x = x.wrapping_mul(k1 | 1);
    x ^= x.wrapping_mul(0xd1b5_4a32);
    x = x.wrapping_add(k1.rotate_left(13));
    x ^= x.wrapping_mul(0x6a09_e668);
    x ^= x.wrapping_mul(0x9b05_688c);
    x
}

/// Owen's nested uniform scramble of a 32-bit fraction `x` with `key`: each bit is flipped by
/// a random function of the bits above it (the more significant digits), so the scrambled
/// points of any elementary interval stay in one elementary interval of the same shape.
#[cfg(test)]
fn owen_scramble(x: u32, key: u64) -> u32 {
    laine_karras_permute(x.reverse_bits(), key).reverse_bits()
}

/// The sample index whose bits, most significant first, are `index_reversed`, shuffled with
/// `key`: each bit is flipped by a function of the bits above it, so each aligned block of 2^k
/// indices goes to an aligned block, permuted.
#[inline(always)]
fn shuffled(index_reversed: u32, key: u64) -> u32 {
    laine_karras_permute(index_reversed, key).reverse_bits()
}

/// Sobol's first dimension at shuffled index `i`, Owen-scrambled with `key`, as a 32-bit
/// fraction. The first dimension is the bit-reversed index (van der Corput); Owen-scrambling
/// reverses it again, so the two reversals cancel: `i` itself is scrambled.
#[inline(always)]
fn first_dimension(i: u32, key: u64) -> u32 {
    laine_karras_permute(i, key).reverse_bits()
}

/// Sobol's second dimension at shuffled index `i`, Owen-scrambled with `key`. Owen-scrambling
/// reverses, permutes and reverses back; the first reversal is in the table (reversal
/// distributes over xor).
#[inline(always)]
fn second_dimension(i: u32, key: u64) -> u32 {
    laine_karras_permute(sobol_1_reversed(i), key).reverse_bits()
}

/// The 32-bit fraction `x` as a float in `[0, 1)`: its top 24 bits, never rounded up to 1.
#[inline]
fn fraction_to_float(x: u32) -> f32 {
    to_unit_float(u64::from(x) << 32)
}

/// The sampler of one (pixel, sample): padded, Owen-scrambled Sobol (Burley 2020).
///
/// Draws are taken dimension by dimension: a [`next_1d`](Self::next_1d) uses one dimension, a
/// [`next_2d`](Self::next_2d) two. The value of a draw depends only on the seed, the pixel, the
/// sample index and how many dimensions were drawn before it, so the `n`-th draw of a sample is
/// the same whichever thread computes it and whatever other samples were taken. A copy of a
/// sampler continues identically to the original.
///
/// Samples `0..2^k` of one pixel are stratified in each draw: the values of a `next_1d` take one
/// of each `2^k` equal intervals of `[0, 1)`, and the pairs of a `next_2d` form a (0,k,2)-net
/// (one point in every `2^a × 2^(k−a)` elementary interval). Different draws, pixels and seeds
/// are decorrelated. Any sample count may be used; powers of two are stratified best.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampler {
    /// A hash of `(seed, pixel)`, computed once: each draw's keys then cost one mix.
    pixel_key: u64,
    index: u32,
    /// `index` bit-reversed, the start of every draw's index shuffle, computed once.
    index_reversed: u32,
    dimension: u32,
}

impl Sampler {
    /// The sampler of sample `index` of pixel `pixel` (a number unique to the pixel within the
    /// image, e.g. `y · width + x`) in a render with random seed `seed`, at its first dimension.
    pub fn new(seed: u64, pixel: u64, index: u32) -> Self {
        Self {
            pixel_key: hash(seed, pixel, u32::MAX, u32::MAX) ^ KEY_SALT,
            index,
            index_reversed: index.reverse_bits(),
            dimension: 0,
        }
    }

    /// The sample's index within its pixel.
    pub fn index(&self) -> u32 {
        self.index
    }

    /// A sequential generator of this sample's own, for draws whose number is not known in
    /// advance; its stream depends on the pixel, the sample and the dimension reached.
    pub fn stream(&self) -> Rng {
        Rng::new(mix64(
            self.pixel_key ^ (u64::from(self.index) << 32 | u64::from(self.dimension)),
        ))
    }

    /// How many dimensions have been drawn so far (one per value).
    pub fn dimension(&self) -> u32 {
        self.dimension
    }

    /// The scrambling key number `role` of the current draw: the same for every sample of the
    /// pixel, so that the samples are scrambled together and stay a net.
    #[inline]
    fn key(&self, role: u32) -> u64 {
        let draw = (u64::from(self.dimension) << 2) | u64::from(role);
        mix64(self.pixel_key ^ draw.wrapping_mul(0x9e37_79b9_7f4a_7c15))
    }

    /// The current draw's shuffled sample index.
    #[inline]
    fn shuffled_index(&self) -> u32 {
        shuffled(self.index_reversed, self.key(0))
    }

    /// This sampler as it stands, for the next `dimensions` draws to be taken from later (or
    /// never); `self` moves past them. The copy's draws are those `self` would have made, so
    /// a decision that needs its numbers only some of the time pays for them only then, and
    /// every sample still spends the same dimensions on the same decisions.
    #[inline]
    pub fn defer(&mut self, dimensions: u32) -> Sampler {
        let at = *self;
        self.dimension = self.dimension.wrapping_add(dimensions);
        at
    }

    /// The next value in [0,1), dimension by dimension.
    pub fn next_1d(&mut self) -> f32 {
        let x = first_dimension(self.shuffled_index(), self.key(1));
        self.dimension = self.dimension.wrapping_add(1);
        fraction_to_float(x)
    }

    /// The next pair in [0,1)², stratified with the other samples of the pixel (a
    /// (0,2)-sequence in its two dimensions).
    pub fn next_2d(&mut self) -> Vec2 {
        let i = self.shuffled_index();
        let (x, y) = (
            first_dimension(i, self.key(1)),
            second_dimension(i, self.key(2)),
        );
        self.dimension = self.dimension.wrapping_add(2);
        Vec2::new(fraction_to_float(x), fraction_to_float(y))
    }
}

/// Draws of many samplers at once: the lanes of one bounce, which stand at the same dimension.
/// Each value is the one the sampler's own [`Sampler::next_1d`] or [`Sampler::next_2d`] gives;
/// samplers of one pixel share their scrambling keys, which are then made once, and their
/// indices are scrambled together (in a loop the compiler vectorises).
impl Sampler {
    /// [`Sampler::next_1d`] of each sampler.
    #[inline(always)]
    pub fn next_1d_lanes(samplers: &mut [Sampler]) -> ArrayVec<f32, LANES> {
        let Some(keys) = shared_keys(samplers) else {
            return samplers.iter_mut().map(Sampler::next_1d).collect();
        };
        let (k0, k1) = (keys.key(0), keys.key(1));
        let i = shuffled_lanes(samplers, k0);
        let x: [u32; LANES] = std::array::from_fn(|l| first_dimension(i[l], k1));
        for s in samplers.iter_mut() {
            s.dimension = s.dimension.wrapping_add(1);
        }
        x[..samplers.len()]
            .iter()
            .map(|&x| fraction_to_float(x))
            .collect()
    }

    /// [`Sampler::next_2d`] of each sampler.
    #[inline(always)]
    pub fn next_2d_lanes(samplers: &mut [Sampler]) -> ArrayVec<Vec2, LANES> {
        let Some(keys) = shared_keys(samplers) else {
            return samplers.iter_mut().map(Sampler::next_2d).collect();
        };
        let (k0, k1, k2) = (keys.key(0), keys.key(1), keys.key(2));
        let i = shuffled_lanes(samplers, k0);
        let x: [u32; LANES] = std::array::from_fn(|l| first_dimension(i[l], k1));
        let y: [u32; LANES] = std::array::from_fn(|l| second_dimension(i[l], k2));
        for s in samplers.iter_mut() {
            s.dimension = s.dimension.wrapping_add(2);
        }
        (0..samplers.len())
            .map(|l| Vec2::new(fraction_to_float(x[l]), fraction_to_float(y[l])))
            .collect()
    }
}

/// The first of `samplers` when all of them draw with the same keys (one pixel and seed, one
/// dimension) and there are at most [`LANES`] of them.
fn shared_keys(samplers: &[Sampler]) -> Option<Sampler> {
    let first = *samplers.first()?;
    let shared = samplers
        .iter()
        .all(|s| s.pixel_key == first.pixel_key && s.dimension == first.dimension);
    (shared && samplers.len() <= LANES).then_some(first)
}

/// The shuffled indices of `samplers` (their draw's key `k0`), lanes past them 0.
#[inline(always)]
fn shuffled_lanes(samplers: &[Sampler], k0: u64) -> [u32; LANES] {
    let reversed: [u32; LANES] =
        std::array::from_fn(|l| samplers.get(l).map_or(0, |s| s.index_reversed));
    std::array::from_fn(|l| shuffled(reversed[l], k0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::uniform;
    use crate::sampling::warp::chi2;

    /// The draws each sample makes in the tests: a mix of 1D and 2D, so the 2D draws start at
    /// both even and odd dimensions.
    #[derive(Clone, Copy)]
    enum Draw {
        One,
        Two,
    }
    const PATTERN: [Draw; 6] = [
        Draw::Two,
        Draw::One,
        Draw::Two,
        Draw::Two,
        Draw::One,
        Draw::Two,
    ];

    /// The 2D points of draw `d` (an index into [`PATTERN`], which must be a 2D draw) for
    /// samples `0..n` of a pixel.
    fn points_2d(seed: u64, pixel: u64, n: u32, d: usize) -> Vec<Vec2> {
        (0..n)
            .map(|i| {
                let mut s = Sampler::new(seed, pixel, i);
                let mut out = Vec2::ZERO;
                for (j, draw) in PATTERN.iter().enumerate().take(d + 1) {
                    match draw {
                        Draw::One => {
                            s.next_1d();
                        }
                        Draw::Two => {
                            let p = s.next_2d();
                            if j == d {
                                out = p;
                            }
                        }
                    }
                }
                out
            })
            .collect()
    }

    #[test]
    fn deferred_draws_are_the_draws_skipped() {
        for index in [0, 1, 7, 1000] {
            let mut direct = Sampler::new(3, 41, index);
            let expected = (direct.next_1d(), direct.next_2d(), direct.next_1d());
            let mut s = Sampler::new(3, 41, index);
            let mut first = s.defer(3);
            let after = s.next_1d();
            assert_eq!(after, expected.2);
            assert_eq!((first.next_1d(), first.next_2d()), (expected.0, expected.1));
        }
    }

    #[test]
    fn draws_in_lanes_are_each_samplers_own() {
        // Eight samples of one pixel (shared keys), and samples of several pixels (not).
        let groups: [Vec<Sampler>; 3] = [
            (0..8).map(|i| Sampler::new(9, 17, i)).collect(),
            (0..5).map(|i| Sampler::new(9, 17, 40 + i)).collect(),
            (0..8)
                .map(|i| Sampler::new(9, 17 + u64::from(i % 3), i))
                .collect(),
        ];
        for group in groups {
            let mut lanes = group.clone();
            let mut alone = group;
            for _ in 0..4 {
                let got = Sampler::next_1d_lanes(&mut lanes);
                let want: Vec<f32> = alone.iter_mut().map(Sampler::next_1d).collect();
                assert_eq!(got.as_slice(), want.as_slice());
                let got = Sampler::next_2d_lanes(&mut lanes);
                let want: Vec<Vec2> = alone.iter_mut().map(Sampler::next_2d).collect();
                assert_eq!(got.as_slice(), want.as_slice());
            }
            assert_eq!(lanes, alone);
        }
    }

    #[test]
    fn the_second_generator_matrix_is_sobols() {
        // The first direction numbers of dimension 2 in Joe & Kuo's tables: m = 1, 3, 5, 15, 17.
        let m = [1u32, 3, 5, 15, 17, 51, 85, 255];
        for (j, &mj) in m.iter().enumerate() {
            assert_eq!(SOBOL_1_MATRIX[j], mj << (31 - j as u32), "column {j}");
        }
        // Its first points: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
        let first: Vec<u32> = (0..8).map(|i| sobol_1(i) >> 29).collect();
        assert_eq!(first, [0, 4, 6, 2, 5, 1, 3, 7]);
        for i in [0, 1, 5, 0x8000_0001, 0xdead_beef, u32::MAX] {
            assert_eq!(sobol_1_reversed(i), sobol_1(i).reverse_bits());
        }
    }

    #[test]
    fn the_scramble_flips_each_bit_by_the_bits_above_it() {
        // Changing bit b of the fraction leaves every more significant bit alone.
        for t in 0..2000u64 {
            let x = hash(1, t, 0, 0) as u32;
            let key = hash(2, t, 0, 0);
            for b in 0..32 {
                let y = x ^ (1 << b);
                let diff = owen_scramble(x, key) ^ owen_scramble(y, key);
                assert_eq!(diff >> b, 1, "x = {x:#x}, bit {b}: {diff:#x}");
            }
        }
        // Restricted to the top 12 bits it is a bijection.
        let key = hash(3, 4, 5, 6);
        let mut seen = vec![false; 1 << 12];
        for top in 0..1u32 << 12 {
            let s = (owen_scramble(top << 20, key) >> 20) as usize;
            assert!(!seen[s]);
            seen[s] = true;
        }
    }

    #[test]
    fn the_scramble_decisions_are_unbiased_and_independent() {
        // For each bit b, over many keys: the bit is flipped half the time, and the flips for
        // two different sets of higher bits agree half the time (an Owen scramble draws them
        // independently). 20,000 keys: σ = 0.0035; allow 5σ.
        let keys = 20_000u64;
        for b in 1..24u32 {
            // The higher bits of the two fractions differ in the most significant bit, or in
            // the one just above bit b.
            for differ in [31, 32 - b] {
                let (mut flips, mut agree) = (0u32, 0u32);
                for k in 0..keys {
                    let key = hash(11, k, b, differ);
                    let h = hash(12, k, b, differ);
                    // Bit b (from the top) clear, the bits above random, the bits below too.
                    let x = (h as u32) & !(1 << (31 - b));
                    let (xa, xb) = (x, x ^ (1 << differ));
                    let bit = |v: u32| (v >> (31 - b)) & 1;
                    let fa = bit(owen_scramble(xa, key));
                    let fb = bit(owen_scramble(xb, key));
                    flips += fa;
                    agree += u32::from(fa == fb);
                }
                let (pf, pa) = (flips as f64 / keys as f64, agree as f64 / keys as f64);
                assert!((pf - 0.5).abs() < 0.0177, "bit {b}: flipped {pf}");
                assert!((pa - 0.5).abs() < 0.0177, "bit {b}, {differ}: agree {pa}");
            }
        }
    }

    #[test]
    fn power_of_two_sample_counts_form_nets() {
        for k in 0..=8u32 {
            let n = 1u32 << k;
            for (seed, pixel) in [(0u64, 0u64), (7, 12_345), (0xdead_beef, 3)] {
                for (d, draw) in PATTERN.iter().enumerate() {
                    if let Draw::One = draw {
                        continue;
                    }
                    let points = points_2d(seed, pixel, n, d);
                    for a in 0..=k {
                        let (cols, rows) = (1u32 << a, 1u32 << (k - a));
                        let mut seen = vec![false; n as usize];
                        for p in &points {
                            assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
                            let cell =
                                (p.y * rows as f32) as u32 * cols + (p.x * cols as f32) as u32;
                            assert!(
                                !seen[cell as usize],
                                "N = {n}, draw {d}, {cols} × {rows}: two points in cell {cell}"
                            );
                            seen[cell as usize] = true;
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn one_dimensional_draws_are_stratified() {
        for k in 0..=10u32 {
            let n = 1u32 << k;
            let mut seen = vec![false; n as usize];
            for i in 0..n {
                let mut s = Sampler::new(5, 77, i);
                s.next_2d();
                let u = s.next_1d();
                let cell = (u * n as f32) as usize;
                assert!(!seen[cell], "N = {n}: two values in stratum {cell}");
                seen[cell] = true;
            }
        }
    }

    #[test]
    fn values_are_a_pure_function_of_the_key() {
        let run = |seed, pixel, index| {
            let mut s = Sampler::new(seed, pixel, index);
            let a = s.next_1d();
            let b = s.next_2d();
            let c = s.next_1d();
            (a, b, c)
        };
        // Forward, backward and interleaved orders agree, and so does a copy made mid-way.
        let forward: Vec<_> = (0..64).map(|i| run(3, 99, i)).collect();
        let backward: Vec<_> = (0..64).rev().map(|i| run(3, 99, i)).collect();
        assert!(forward.iter().eq(backward.iter().rev()));
        let mut samplers: Vec<_> = (0..64).map(|i| Sampler::new(3, 99, i)).collect();
        let firsts: Vec<_> = samplers.iter_mut().map(|s| s.next_1d()).collect();
        let mut copies = samplers.clone();
        for (i, s) in samplers.iter_mut().enumerate().rev() {
            assert_eq!((firsts[i], s.next_2d(), s.next_1d()), forward[i]);
        }
        for (c, s) in copies.iter_mut().zip(&samplers) {
            c.next_2d();
            c.next_1d();
            assert_eq!(c, s);
            assert_eq!(c.dimension(), 4);
        }
        // Every part of the key matters.
        let base = run(3, 99, 5);
        assert_ne!(base, run(4, 99, 5));
        assert_ne!(base, run(3, 100, 5));
        assert_ne!(base, run(3, 99, 6));
    }

    /// The mean of `f` over pixels `0..n`, and its standard error.
    fn mean_and_error(n: u64, f: impl Fn(u64) -> f64) -> (f64, f64) {
        let (mut sum, mut sq) = (0.0, 0.0);
        for p in 0..n {
            let v = f(p);
            sum += v;
            sq += v * v;
        }
        let mean = sum / n as f64;
        let var = (sq / n as f64 - mean * mean).max(0.0);
        (mean, (var / n as f64).sqrt())
    }

    #[test]
    fn pixels_and_dimensions_are_decorrelated() {
        let n = 100_000;
        // Products of two values that would be 1/4 if they were independent and uniform.
        type Pair = fn(u64) -> f64;
        let pairs: [(&str, Pair); 6] = [
            ("x and y of one draw", |p| {
                let v = Sampler::new(1, p, 0).next_2d();
                f64::from(v.x * v.y)
            }),
            ("x of draws 1 and 2", |p| {
                let mut s = Sampler::new(1, p, 3);
                f64::from(s.next_2d().x * s.next_2d().x)
            }),
            ("y of draw 1, x of draw 2", |p| {
                let mut s = Sampler::new(1, p, 3);
                f64::from(s.next_2d().y * s.next_2d().x)
            }),
            ("1D dimensions 0 and 1", |p| {
                let mut s = Sampler::new(1, p, 17);
                f64::from(s.next_1d() * s.next_1d())
            }),
            ("neighbouring pixels", |p| {
                let a = Sampler::new(1, 2 * p, 9).next_1d();
                f64::from(a * Sampler::new(1, 2 * p + 1, 9).next_1d())
            }),
            ("neighbouring seeds", |p| {
                let a = Sampler::new(1, p, 9).next_2d().x;
                f64::from(a * Sampler::new(2, p, 9).next_2d().x)
            }),
        ];
        for (name, f) in pairs {
            let (mean, se) = mean_and_error(n, f);
            assert!((mean - 0.25).abs() < 5.0 * se, "{name}: {mean} ± {se}");
        }
        // Within one pixel, values of different draws paired up by sample fill the square
        // evenly: 4,096 samples in an 8 × 8 histogram.
        let n = 4096;
        let mut counts = vec![0.0; 64];
        for i in 0..n {
            let mut s = Sampler::new(8, 8, i);
            let (a, b) = (s.next_2d().x, s.next_2d().y);
            counts[(a * 8.0) as usize * 8 + (b * 8.0) as usize] += 1.0;
        }
        chi2::assert_fits("padded draws", &counts, &[n as f64 / 64.0; 64]);
    }

    #[test]
    fn smooth_integrands_converge_much_faster_than_random_sampling() {
        // f(x, y) = exp(x·y); ∫∫ f = Σₙ 1 / (n!·(n + 1)²).
        let f = |x: f32, y: f32| (f64::from(x) * f64::from(y)).exp();
        let mut exact = 0.0;
        let mut fact = 1.0;
        for n in 0..20 {
            if n > 0 {
                fact *= n as f64;
            }
            exact += 1.0 / (fact * ((n + 1) * (n + 1)) as f64);
        }
        let (pixels, spp) = (400u64, 256u32);
        let (mut sobol_sq, mut random_sq) = (0.0, 0.0);
        for p in 0..pixels {
            let (mut a, mut b) = (0.0, 0.0);
            for i in 0..spp {
                let mut s = Sampler::new(21, p, i);
                s.next_1d();
                let v = s.next_2d();
                a += f(v.x, v.y);
                b += f(uniform(21, p, i, 0), uniform(21, p, i, 1));
            }
            sobol_sq += (a / spp as f64 - exact).powi(2);
            random_sq += (b / spp as f64 - exact).powi(2);
        }
        let (sobol, random) = (
            (sobol_sq / pixels as f64).sqrt(),
            (random_sq / pixels as f64).sqrt(),
        );
        // Owen-scrambled Sobol converges as N^-1.5 on smooth integrands, random sampling as
        // N^-0.5: at 256 samples the error is about 1/75 of random's; require 1/16.
        assert!(
            sobol < random / 16.0,
            "RMS error {sobol} vs random {random}"
        );
    }

    #[test]
    fn one_dimensional_values_are_uniform() {
        // Over many pixels (one sample each, so no stratification helps) and within pixels.
        let mut across = vec![0.0; 100];
        let mut within = vec![0.0; 100];
        for p in 0..50_000u64 {
            let mut s = Sampler::new(4, p, 0);
            s.next_2d();
            across[(s.next_1d() * 100.0) as usize] += 1.0;
        }
        for p in 0..50u64 {
            for i in 0..1000 {
                let mut s = Sampler::new(4, p, i);
                within[(s.next_1d() * 100.0) as usize] += 1.0;
            }
        }
        chi2::assert_fits("1D across pixels", &across, &[500.0; 100]);
        chi2::assert_fits("1D within pixels", &within, &[500.0; 100]);
    }

    #[test]
    fn values_stay_below_one() {
        assert!(fraction_to_float(u32::MAX) < 1.0);
        assert_eq!(fraction_to_float(0), 0.0);
    }
}
