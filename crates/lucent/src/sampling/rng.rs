//! A small sequential generator, for the draws whose number is not known in advance (the
//! collisions of delta and ratio tracking through a heterogeneous medium) and for tests.

use super::mix64;

/// splitmix64 (Steele, Lea & Flood 2014): its stream is a pure function of its seed.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator whose stream is a pure function of `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed ^ 0x5851_f42d_4c95_7f2d)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        mix64(self.0)
    }

    /// A uniform float in `[0, 1)`, 24 random bits.
    pub fn f32(&mut self) -> f32 {
        super::to_unit_float(self.next_u64())
    }
}
