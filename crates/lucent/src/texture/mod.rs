//! Textures: a colour that varies over a surface.
//!
//! A texture is evaluated at a hit's `texture_coords` (see [`crate::shape::SurfaceHit`]).
//! To add a kind: a file with its struct and `eval`, a variant here, and its scene-file key.

pub mod checker;

pub use checker::Checker;

use crate::Rgb;
use glam::Vec3;

/// A colour over a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Texture {
    /// The same colour everywhere.
    Solid(Rgb),
    /// A 3D checkerboard of two colours.
    Checker(Checker),
}

impl Texture {
    /// The colour at surface coordinates `p`.
    #[inline]
    pub fn eval(&self, p: Vec3) -> Rgb {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker(c) => c.eval(p),
        }
    }
}

impl From<Rgb> for Texture {
    fn from(c: Rgb) -> Self {
        Texture::Solid(c)
    }
}
