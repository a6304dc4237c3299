//! Deterministic randomness: every random number is a pure function of
//! `(seed, pixel, sample index, dimension)`.
//!
//! Nothing here keeps state between calls, so a sample can be replayed on its own, and an
//! image does not depend on the number of threads, the order of tiles, or how the work is split.

pub mod distribution;
pub mod mis;
mod rng;
pub mod sobol;
pub mod stratified;
pub mod warp;

pub use rng::Rng;
pub use stratified::pixel_offset;

/// A 64-bit finaliser with full avalanche (the splitmix64 output function).
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A hash of the key `(seed, pixel, sample, dim)`.
#[inline]
pub fn hash(seed: u64, pixel: u64, sample: u32, dim: u32) -> u64 {
    let h = mix64(seed ^ 0x9e37_79b9_7f4a_7c15);
    let h = mix64(h ^ pixel);
    mix64(h ^ ((u64::from(sample) << 32) | u64::from(dim)))
}

/// A uniform number in `[0, 1)` for the key `(seed, pixel, sample, dim)`.
#[inline]
pub fn uniform(seed: u64, pixel: u64, sample: u32, dim: u32) -> f32 {
    to_unit_float(hash(seed, pixel, sample, dim))
}

/// The top 24 bits of `bits` as a float in `[0, 1)`: every value exactly representable.
#[inline]
pub fn to_unit_float(bits: u64) -> f32 {
    (bits >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// A bijection of `[0, n)` chosen by `key`: `i` goes to a pseudo-random position.
///
/// An invertible mix on the smallest power-of-two range holding `n` (xor-shifts, odd
/// multiplications and additions, each masked, are bijections on it), applied repeatedly
/// until the value falls inside `[0, n)` ("cycle walking"); the result is a bijection of `[0, n)`.
pub fn permute(i: u32, n: u32, key: u64) -> u32 {
    debug_assert!(i < n);
    if n <= 1 {
        return 0;
    }
    let bits = 32 - (n - 1).leading_zeros();
    let mask = if bits == 32 {
        u32::MAX
    } else {
        (1u32 << bits) - 1
    };
    let (k0, k1) = (key as u32, (key >> 32) as u32);
    let half = (bits / 2).max(1);
    let mut x = i;
    loop {
        x ^= k0 & mask;
        x = x.wrapping_mul(0x9e37_79b1 | 1) & mask;
        x ^= x >> half;
        x = x.wrapping_add(k1) & mask;
        x = x.wrapping_mul(0x85eb_ca6b | 1) & mask;
        x ^= x >> half;
        if x < n {
            return x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_bijection() {
        for n in [1, 2, 3, 7, 16, 17, 100, 1000] {
            for key in [0, 1, 0xdead_beef_1234_5678] {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let p = permute(i, n, key);
                    assert!(!seen[p as usize], "n = {n}, key = {key}: {p} twice");
                    seen[p as usize] = true;
                }
            }
        }
    }

    #[test]
    fn uniform_is_in_range_and_roughly_uniform() {
        let n = 100_000;
        let mut bins = [0u32; 10];
        for i in 0..n {
            let u = uniform(7, i, 3, 1);
            assert!((0.0..1.0).contains(&u));
            bins[(u * 10.0) as usize] += 1;
        }
        // Each bin expects 10,000 ± 95 (one standard deviation); allow five.
        for b in bins {
            assert!((b as i32 - 10_000).abs() < 475, "{bins:?}");
        }
    }

    #[test]
    fn every_key_component_changes_the_value() {
        let base = uniform(1, 2, 3, 4);
        assert_ne!(base, uniform(9, 2, 3, 4));
        assert_ne!(base, uniform(1, 9, 3, 4));
        assert_ne!(base, uniform(1, 2, 9, 4));
        assert_ne!(base, uniform(1, 2, 3, 9));
        assert_eq!(base, uniform(1, 2, 3, 4));
    }
}
