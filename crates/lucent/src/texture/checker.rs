//! The checkerboard of Whitted's 1980 picture, as a solid texture.

use crate::Rgb;
use glam::Vec3;

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
}

impl Checker {
    /// The colour at `p`.
    pub fn eval(&self, p: Vec3) -> Rgb {
        let cell = (p / self.size).floor();
        let parity = (cell.x + cell.y + cell.z).rem_euclid(2.0);
        if parity < 0.5 { self.even } else { self.odd }
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
        };
        assert_eq!(c.eval(Vec3::new(0.5, 0.5, 0.0)), Rgb::WHITE);
        assert_eq!(c.eval(Vec3::new(2.5, 0.5, 0.0)), Rgb::BLACK);
        assert_eq!(c.eval(Vec3::new(-0.5, 0.5, 0.0)), Rgb::BLACK);
        assert_eq!(c.eval(Vec3::new(-0.5, -0.5, 0.0)), Rgb::WHITE);
    }
}
