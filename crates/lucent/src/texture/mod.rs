//! Textures: a value that varies over a surface — a colour, or a single number (roughness,
//! metalness, opacity, a height) read from one.
//!
//! A texture is evaluated at a hit's [`TexCoords`]: its solid coordinates (for the 3D
//! checkerboard), its texture coordinates `uv`, their footprint (how far `uv` moves from one
//! pixel to the next, for MIP-mapped lookups) and the mesh's vertex colour. Number-valued
//! parameters read a texture through [`Texture::eval_float`]: the channel an image lookup
//! picks, or the luminance of a colour (as Mitsuba does).
//!
//! To add a kind: a file with its struct and `eval`, a variant here and its arms in
//! [`Texture::eval`], [`Texture::mean`] and [`Texture::uses_uv`], and its scene-file key in
//! `lucent-scene` (`desc/texture.rs`).

pub mod bump;
pub mod checker;
pub mod image;
pub mod pattern;
pub mod transform;

pub use checker::{Checker, UvChecker};
pub use image::{Filter, ImageTexture, Texel, Wrap};
pub use pattern::{Pattern, PatternKind, Turbulence, Wave};
pub use transform::UvTransform;

use crate::Rgb;
use glam::{Vec2, Vec3};

/// Where on a surface a texture is looked up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexCoords {
    /// Solid-texture coordinates: the world position, or a plane's own 2D frame.
    pub p: Vec3,
    /// The world position (a plane's too): where textures placed in the world look.
    pub world: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// How `uv` changes from one pixel to the next across the image, along x and y; zero for
    /// a point lookup.
    pub duv: [Vec2; 2],
    /// The mesh's interpolated vertex colour, white elsewhere.
    pub color: Rgb,
}

impl TexCoords {
    /// A point lookup at `uv` (and solid coordinates `p`), without footprint or vertex colour.
    pub fn at(p: Vec3, uv: Vec2) -> Self {
        Self {
            p,
            world: p,
            uv,
            duv: [Vec2::ZERO; 2],
            color: Rgb::WHITE,
        }
    }
}

/// Which channels of an image a lookup reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Channel {
    /// The colour.
    #[default]
    Rgb,
    /// One channel, as grey: red, green, blue or alpha (glTF packs roughness in green,
    /// metalness in blue, coverage in the base colour's alpha).
    R,
    /// See [`Channel::R`].
    G,
    /// See [`Channel::R`].
    B,
    /// See [`Channel::R`].
    A,
}

/// An image looked up through texture coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageMap {
    /// The scene's image (`Scene::images`, by index).
    pub image: u32,
    /// Applied to the surface's `uv` before the lookup.
    pub transform: UvTransform,
    /// Outside `[0, 1]`, along u and along v.
    pub wrap: [Wrap; 2],
    /// Texel interpolation.
    pub filter: Filter,
    /// The channels read.
    pub channel: Channel,
}

impl ImageMap {
    /// The colour of image `image` with the defaults: repeat, anisotropic, untransformed.
    pub fn new(image: u32) -> Self {
        Self {
            image,
            transform: UvTransform::IDENTITY,
            wrap: [Wrap::Repeat; 2],
            filter: Filter::Anisotropic,
            channel: Channel::Rgb,
        }
    }

    fn eval(&self, at: &TexCoords, images: &[ImageTexture]) -> Rgb {
        let Some(img) = images.get(self.image as usize) else {
            return Rgb::BLACK;
        };
        let uv = self.transform.apply(at.uv);
        let duv = at.duv.map(|d| self.transform.apply_vector(d));
        let t = img.sample(uv, duv, self.wrap, self.filter);
        match self.channel {
            Channel::Rgb => t.rgb,
            Channel::R => Rgb::gray(t.rgb.r),
            Channel::G => Rgb::gray(t.rgb.g),
            Channel::B => Rgb::gray(t.rgb.b),
            Channel::A => Rgb::gray(t.alpha),
        }
    }

    fn mean(&self, images: &[ImageTexture]) -> Rgb {
        let Some(img) = images.get(self.image as usize) else {
            return Rgb::BLACK;
        };
        let m = img.mean();
        match self.channel {
            Channel::Rgb => m,
            Channel::R => Rgb::gray(m.r),
            Channel::G => Rgb::gray(m.g),
            Channel::B => Rgb::gray(m.b),
            Channel::A => Rgb::gray(img.mean_alpha()),
        }
    }
}

/// A value over a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same value everywhere.
    Solid(Rgb),
    /// A 3D checkerboard of two colours in solid coordinates (Whitted's floor).
    Checker(Checker),
    /// A checkerboard over texture coordinates (Mitsuba's `checkerboard`).
    UvChecker(UvChecker),
    /// A solid pattern placed in the world (POV-Ray's pigments).
    Pattern(Box<Pattern>),
    /// An image.
    Image(ImageMap),
    /// The mesh's vertex colour (Mitsuba's `mesh_attribute` of `vertex_color`); white on
    /// shapes without one.
    VertexColor,
    /// The product of two textures.
    Product(Box<Texture>, Box<Texture>),
    /// `a·(1 − t) + b·t`, `t` a number-valued texture clamped to [0, 1] (beyond it the blend
    /// would extrapolate, to negative values of the parameters it feeds).
    Mix {
        /// Where `t` is 0.
        a: Box<Texture>,
        /// Where `t` is 1.
        b: Box<Texture>,
        /// The blend.
        t: Box<Texture>,
    },
    /// 1 where `value` (each channel) reaches `cutoff`, 0 below: glTF's alpha `MASK`.
    Step {
        /// The texture thresholded.
        value: Box<Texture>,
        /// The threshold.
        cutoff: f32,
    },
}

/// The largest magnitude of a texture's value: the largest colour component a scene file
/// takes and an image may hold. It leaves the BSDFs' arithmetic room (a microfacet
/// distribution's peak, a coat's `1/η²`) below `f32::MAX`.
pub const MAX_VALUE: f32 = 1e30;

/// `c` with each channel held within ±[`MAX_VALUE`]: the product of two values within it (or a
/// blend of them) can leave it.
fn bounded(c: Rgb) -> Rgb {
    c.clamp(-MAX_VALUE, MAX_VALUE)
}

impl Texture {
    /// The value at `at`; `images` are the scene's.
    #[inline]
    pub fn eval(&self, at: &TexCoords, images: &[ImageTexture]) -> Rgb {
        match self {
            Texture::Solid(c) => *c,
            _ => self.eval_varying(at, images),
        }
    }

    /// [`Texture::eval`] of a texture that is not [`Texture::Solid`] (kept out of line, so that
    /// the common constant stays a load).
    fn eval_varying(&self, at: &TexCoords, images: &[ImageTexture]) -> Rgb {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker(c) => c.eval_at(at.p, at.world),
            Texture::UvChecker(c) => c.eval(at.uv),
            Texture::Pattern(p) => p.eval(at.world),
            Texture::Image(m) => m.eval(at, images),
            Texture::VertexColor => at.color,
            Texture::Product(a, b) => bounded(a.eval(at, images) * b.eval(at, images)),
            Texture::Mix { a, b, t } => {
                let t = t.eval_float(at, images).clamp(0.0, 1.0);
                bounded(a.eval(at, images).lerp(b.eval(at, images), t))
            }
            Texture::Step { value, cutoff } => step(value.eval(at, images), *cutoff),
        }
    }

    /// The value at `at` as one number: a grey texture's value, else the luminance.
    #[inline]
    pub fn eval_float(&self, at: &TexCoords, images: &[ImageTexture]) -> f32 {
        let c = self.eval(at, images);
        if c.r == c.g && c.g == c.b {
            c.r
        } else {
            c.luminance()
        }
    }

    /// The average over the texture (vertex colours count as white): what a model that needs
    /// one value, like the Whitted integrator's ambient term, uses.
    pub fn mean(&self, images: &[ImageTexture]) -> Rgb {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker(c) => (c.even + c.odd) * 0.5,
            Texture::UvChecker(c) => (c.even + c.odd) * 0.5,
            Texture::Pattern(p) => {
                let n = p.map.len().max(1) as f32;
                p.map.iter().fold(Rgb::BLACK, |s, e| s + e.1) * (1.0 / n)
            }
            Texture::Image(m) => m.mean(images),
            Texture::VertexColor => Rgb::WHITE,
            Texture::Product(a, b) => bounded(a.mean(images) * b.mean(images)),
            Texture::Mix { a, b, t } => {
                let t = t.mean(images);
                let t = if t.r == t.g && t.g == t.b {
                    t.r
                } else {
                    t.luminance()
                };
                bounded(a.mean(images).lerp(b.mean(images), t.clamp(0.0, 1.0)))
            }
            // The share of texels above the cutoff is not kept; the mean's step stands in.
            Texture::Step { value, cutoff } => step(value.mean(images), *cutoff),
        }
    }

    /// The constant value, if the texture is one.
    pub fn constant(&self) -> Option<Rgb> {
        match self {
            Texture::Solid(c) => Some(*c),
            _ => None,
        }
    }

    /// Whether evaluating needs the hit's texture coordinates (spheres work theirs out only
    /// then).
    #[inline(always)]
    pub fn uses_uv(&self) -> bool {
        match self {
            Texture::Solid(_)
            | Texture::Checker(_)
            | Texture::Pattern(_)
            | Texture::VertexColor => false,
            Texture::UvChecker(_) | Texture::Image(_) => true,
            _ => self.any_child_uses_uv(),
        }
    }

    /// [`Texture::uses_uv`] of a composite texture (kept out of line: the leaves are asked at
    /// every hit).
    fn any_child_uses_uv(&self) -> bool {
        match self {
            Texture::Product(a, b) => a.uses_uv() || b.uses_uv(),
            Texture::Mix { a, b, t } => a.uses_uv() || b.uses_uv() || t.uses_uv(),
            Texture::Step { value, .. } => value.uses_uv(),
            leaf => leaf.uses_uv(),
        }
    }

    /// The images this texture reads.
    pub fn images(&self, out: &mut Vec<u32>) {
        match self {
            Texture::Image(m) => out.push(m.image),
            Texture::Product(a, b) => {
                a.images(out);
                b.images(out);
            }
            Texture::Mix { a, b, t } => {
                a.images(out);
                b.images(out);
                t.images(out);
            }
            Texture::Step { value, .. } => value.images(out),
            _ => {}
        }
    }
}

/// Each channel of `c` as 1 where it reaches `cutoff`, else 0.
fn step(c: Rgb, cutoff: f32) -> Rgb {
    let s = |v: f32| if v >= cutoff { 1.0 } else { 0.0 };
    Rgb::new(s(c.r), s(c.g), s(c.b))
}

impl From<Rgb> for Texture {
    fn from(c: Rgb) -> Self {
        Texture::Solid(c)
    }
}

impl From<f32> for Texture {
    fn from(v: f32) -> Self {
        Texture::Solid(Rgb::gray(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composite_textures_combine_their_parts() {
        let at = TexCoords {
            color: Rgb::new(1.0, 0.5, 0.25),
            ..TexCoords::at(Vec3::ZERO, Vec2::ZERO)
        };
        let tinted = Texture::Product(Box::new(Texture::VertexColor), Box::new(Texture::from(0.5)));
        assert_eq!(tinted.eval(&at, &[]), Rgb::new(0.5, 0.25, 0.125));
        let mix = Texture::Mix {
            a: Box::new(Texture::from(0.0)),
            b: Box::new(Texture::from(1.0)),
            t: Box::new(Texture::from(0.25)),
        };
        assert_eq!(mix.eval_float(&at, &[]), 0.25);
        assert_eq!(mix.mean(&[]), Rgb::gray(0.25));
        // A colour read as a number is its luminance.
        let green = Texture::Solid(Rgb::new(0.0, 1.0, 0.0));
        assert!((green.eval_float(&at, &[]) - 0.715_16).abs() < 1e-6);
        assert!(!tinted.uses_uv() && Texture::Image(ImageMap::new(0)).uses_uv());
        // A step is 1 from its cutoff on (the cutoff itself included), per channel.
        let mask = |v: Rgb| Texture::Step {
            value: Box::new(Texture::Solid(v)),
            cutoff: 0.5,
        };
        assert_eq!(
            mask(Rgb::new(0.5, 0.49, 0.9)).eval(&at, &[]),
            Rgb::new(1.0, 0.0, 1.0)
        );
        assert_eq!(mask(Rgb::gray(0.2)).mean(&[]), Rgb::BLACK);
    }

    #[test]
    fn an_image_map_picks_its_channel_and_transforms_uv() {
        let img = ImageTexture::new(2, 1, vec![Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.4, 0.5, 0.6)])
            .unwrap()
            .with_alpha(vec![0.25, 0.75])
            .unwrap();
        let images = [img];
        let at = TexCoords::at(Vec3::ZERO, Vec2::new(0.25, 0.5));
        let mut map = ImageMap {
            filter: Filter::Nearest,
            ..ImageMap::new(0)
        };
        assert_eq!(
            Texture::Image(map).eval(&at, &images),
            Rgb::new(0.1, 0.2, 0.3)
        );
        map.channel = Channel::G;
        assert_eq!(Texture::Image(map).eval(&at, &images), Rgb::gray(0.2));
        map.channel = Channel::A;
        assert_eq!(Texture::Image(map).eval_float(&at, &images), 0.25);
        // Shifted by half the image: the other texel.
        map.transform = UvTransform::new(Vec2::ONE, 0.0, Vec2::new(0.5, 0.0));
        assert_eq!(Texture::Image(map).eval_float(&at, &images), 0.75);
        assert_eq!(Texture::Image(map).mean(&images), Rgb::gray(0.5));
    }
}
