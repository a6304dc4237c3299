//! `Lanes`: eight `f32` lanes in memory, 32-byte aligned: the storage of node planes and
//! triangle packs, loaded into registers by [`super::simd`].

/// Lanes per node and per triangle pack.
pub const LANES: usize = 8;

/// Eight `f32` lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct Lanes(pub [f32; LANES]);

impl Lanes {
    /// All lanes `v`.
    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        Self([v; LANES])
    }
}
