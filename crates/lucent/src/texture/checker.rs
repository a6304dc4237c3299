//! Checkerboards: the one of Whitted's 1980 picture as a solid texture, and Mitsuba's over
//! texture coordinates.

use super::UvTransform;
use crate::Rgb;
use glam::{Vec2, Vec3};

/// Cubes of side `size` alternating between `even` and `odd`.
///
/// The cube holding `p` is `⌊p / size⌋`; its colour is `even` when the sum of its three
/// integer coordinates is even. On a plane, `p` is in the plane's own frame (its third
/// coordinate exactly zero), so the pattern is a flat checkerboard with no rounding flicker.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
    /// Colour of the cubes whose coordinates sum to an even number (the one at the origin).
    pub even: Rgb,
    /// Colour of the others.
    pub odd: Rgb,
    /// Side length of a cube, positive.
    pub size: f32,
    /// With a transform, the cubes lie in the space it takes world positions to, on every
    /// shape (planes too: POV-Ray's `checker`), and a point within [`ON_THE_EDGE`] of a cube's
    /// lower face counts as inside it, so a plane on a grid line shows one cell, not rounding
    /// noise. Without one, in solid coordinates (a plane's own frame on planes).
    pub world: Option<glam::Affine3A>,
}

/// How close (in cells) under a cell's lower face a point may be and count as inside it.
pub const ON_THE_EDGE: f32 = 1e-5;

impl Checker {
    /// The colour at world position `world`, solid coordinates `p`.
    pub fn eval_at(&self, p: Vec3, world: Vec3) -> Rgb {
        match self.world {
            Some(m) => {
                let cell = (m.transform_point3(world) / self.size + ON_THE_EDGE).floor();
                let parity = (cell.x + cell.y + cell.z).rem_euclid(2.0);
                if parity < 0.5 { self.even } else { self.odd }
            }
            None => self.eval(p),
        }
    }

    /// The colour at solid coordinates `p`.
    pub fn eval(&self, p: Vec3) -> Rgb {
        let cell = (p / self.size).floor();
        let parity = (cell.x + cell.y + cell.z).rem_euclid(2.0);
        if parity < 0.5 { self.even } else { self.odd }
    }
}

/// Mitsuba's `checkerboard`: the unit square of texture coordinates (after `transform`) split
/// into 2 × 2 cells, `even` where `u` and `v` fall in the same half, `odd` elsewhere; it
/// repeats with period 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvChecker {
    /// Colour of the cells where `frac(u) < ½` and `frac(v) < ½`, or both are not.
    pub even: Rgb,
    /// Colour of the other cells.
    pub odd: Rgb,
    /// Applied to the surface's texture coordinates first.
    pub transform: UvTransform,
}

impl UvChecker {
    /// The colour at texture coordinates `uv`.
    pub fn eval(&self, uv: Vec2) -> Rgb {
        let uv = self.transform.apply(uv);
        let u = uv.x - uv.x.floor() > 0.5;
        let v = uv.y - uv.y.floor() > 0.5;
        if u == v { self.even } else { self.odd }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbouring_cells_alternate() {
        let c = Checker {
            even: Rgb::WHITE,
            odd: Rgb::BLACK,
            size: 2.0,
            world: None,
        };
        assert_eq!(c.eval(Vec3::new(0.5, 0.5, 0.0)), Rgb::WHITE);
        assert_eq!(c.eval(Vec3::new(2.5, 0.5, 0.0)), Rgb::BLACK);
        assert_eq!(c.eval(Vec3::new(-0.5, 0.5, 0.0)), Rgb::BLACK);
        assert_eq!(c.eval(Vec3::new(-0.5, -0.5, 0.0)), Rgb::WHITE);
    }

    #[test]
    fn the_uv_checkerboard_has_four_cells_per_unit() {
        let c = UvChecker {
            even: Rgb::WHITE,
            odd: Rgb::BLACK,
            transform: UvTransform::IDENTITY,
        };
        assert_eq!(c.eval(Vec2::new(0.25, 0.25)), Rgb::WHITE);
        assert_eq!(c.eval(Vec2::new(0.75, 0.25)), Rgb::BLACK);
        assert_eq!(c.eval(Vec2::new(0.75, 0.75)), Rgb::WHITE);
        assert_eq!(c.eval(Vec2::new(-0.25, 0.25)), Rgb::BLACK);
        assert_eq!(c.eval(Vec2::new(1.25, 1.25)), Rgb::WHITE);
    }
}
