//! Textures: a colour that varies over a surface.
//!
//! A texture is evaluated at a hit's `texture_coords` (see [`crate::shape::SurfaceHit`]).
//! To add a kind: a file with its struct and `eval`, a variant here, and its scene-file key.

pub mod checker;
pub mod image;

pub use checker::Checker;
pub use image::ImageTexture;

use crate::Rgb;
use glam::{Vec2, Vec3};

/// A colour over a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Texture {
    /// The same colour everywhere.
    Solid(Rgb),
    /// A 3D checkerboard of two colours.
    Checker(Checker),
    /// An image of the scene's (`Scene::images`, by index), looked up by texture coordinates.
    Image(u32),
}

impl Texture {
    /// The colour at a surface point with solid coordinates `p` and texture coordinates
    /// `uv()` (asked for only by image textures); `images` are the scene's.
    #[inline]
    pub fn eval(&self, p: Vec3, uv: impl FnOnce() -> Vec2, images: &[ImageTexture]) -> Rgb {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker(c) => c.eval(p),
            Texture::Image(i) => images
                .get(*i as usize)
                .map_or(Rgb::BLACK, |img| img.lookup(uv())),
        }
    }
}

impl From<Rgb> for Texture {
    fn from(c: Rgb) -> Self {
        Texture::Solid(c)
    }
}
