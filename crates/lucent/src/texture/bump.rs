//! A solid pattern that bends a surface's shading normal, as POV-Ray's `normal { … }` does:
//! the pattern is a height over space, and the normal leans away from where it rises,
//! `N' = normalize(N − amount·∇ₜh)` with `∇ₜh` the height's gradient along the surface.

use super::pattern::Pattern;
use glam::Vec3;

/// POV-Ray's default `accuracy`: how far apart the pattern is sampled for its slope.
pub const ACCURACY: f32 = 0.02;

/// A bump pattern and its depth.
#[derive(Clone, Debug, PartialEq)]
pub struct Bump {
    /// The height, from the pattern's shaped value (its colour map is not used).
    pub pattern: Pattern,
    /// How strongly the slope bends the normal: POV-Ray's `bump_size` (the number after the
    /// pattern's name), times the step its slope is measured over for the patterns whose
    /// slope POV-Ray estimates from neighbouring values (see `docs/povray.md`).
    pub amount: f32,
}

impl Bump {
    /// The unit normal `n` at `point` bent by the pattern. A bend that would turn it past the
    /// surface (`n'·n ≤ 0`) leaves it as it was.
    pub fn bend(&self, point: Vec3, n: Vec3) -> Vec3 {
        let g = self.pattern.slope(point, ACCURACY);
        let along = g - n * g.dot(n);
        let bent = (n - along * self.amount).normalize_or_zero();
        if bent.dot(n) > 0.0 { bent } else { n }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::{PatternKind, Wave};
    use glam::Affine3A;

    fn gradient_bump(amount: f32) -> Bump {
        Bump {
            pattern: Pattern {
                kind: PatternKind::Gradient(Vec3::X),
                to_pattern: Affine3A::from_scale(Vec3::splat(0.25)),
                wave: Wave::Ramp,
                frequency: 1.0,
                phase: 0.0,
                turbulence: None,
                map: Vec::new(),
            },
            amount,
        }
    }

    #[test]
    fn a_height_rising_along_x_leans_the_normal_back_along_x() {
        // h = x/4 (in the ramp's first cell): its slope in the pattern's own units is
        // (1, 0, 0), whatever the scale; the up normal leans to −x by twice that.
        let b = gradient_bump(2.0);
        let n = b.bend(Vec3::new(0.5, 0.0, 0.0), Vec3::Y);
        let want = Vec3::new(-2.0, 1.0, 0.0).normalize();
        assert!((n - want).length() < 1e-4, "{n}");
        // A normal along the slope is not bent: the gradient has no part along the surface.
        let n = b.bend(Vec3::new(0.5, 0.0, 0.0), Vec3::X);
        assert!((n - Vec3::X).length() < 1e-6, "{n}");
        // No amount, no bend.
        assert_eq!(
            gradient_bump(0.0).bend(Vec3::new(0.5, 0.0, 0.0), Vec3::Y),
            Vec3::Y
        );
    }

    #[test]
    fn a_bend_past_the_surface_is_refused() {
        let n = gradient_bump(1e6).bend(Vec3::new(0.5, 0.0, 0.0), Vec3::Y);
        assert!(n.dot(Vec3::Y) > 0.0, "{n}");
    }
}
