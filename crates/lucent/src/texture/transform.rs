//! An affine map of texture coordinates: scale, rotate and offset `uv` before a lookup
//! (Mitsuba's `to_uv`, glTF's `KHR_texture_transform`, a TOML texture's `scale`, `rotation`
//! and `offset`).

use glam::Vec2;

/// `uv' = M·uv + t`, with `M` a 2 × 2 matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// The rows of `M`.
    pub m: [[f32; 2]; 2],
    /// The offset `t`.
    pub t: Vec2,
}

impl UvTransform {
    /// The identity.
    pub const IDENTITY: UvTransform = UvTransform {
        m: [[1.0, 0.0], [0.0, 1.0]],
        t: Vec2::ZERO,
    };

    /// Scale by `scale`, then rotate by `rotation` radians (from +u towards +v), then offset
    /// by `offset`: `uv' = offset + R(rotation)·(scale ∘ uv)`.
    pub fn new(scale: Vec2, rotation: f32, offset: Vec2) -> Self {
        let (s, c) = rotation.sin_cos();
        Self {
            m: [[c * scale.x, -s * scale.y], [s * scale.x, c * scale.y]],
            t: offset,
        }
    }

    /// The transform of a point.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.apply_vector(uv) + self.t
    }

    /// The transform of a difference of points (no offset), for footprints.
    #[inline]
    pub fn apply_vector(&self, d: Vec2) -> Vec2 {
        Vec2::new(
            self.m[0][0] * d.x + self.m[0][1] * d.y,
            self.m[1][0] * d.x + self.m[1][1] * d.y,
        )
    }

    /// `self` after `first`: `self.apply(first.apply(uv))`.
    pub fn after(&self, first: &UvTransform) -> UvTransform {
        let a = self.m;
        let b = first.m;
        UvTransform {
            m: [
                [
                    a[0][0] * b[0][0] + a[0][1] * b[1][0],
                    a[0][0] * b[0][1] + a[0][1] * b[1][1],
                ],
                [
                    a[1][0] * b[0][0] + a[1][1] * b[1][0],
                    a[1][0] * b[0][1] + a[1][1] * b[1][1],
                ],
            ],
            t: self.apply(first.t),
        }
    }

    /// Whether it is the identity.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_then_rotate_then_offset() {
        let t = UvTransform::new(
            Vec2::new(2.0, 1.0),
            std::f32::consts::FRAC_PI_2,
            Vec2::new(0.5, 0.0),
        );
        // (1, 0) → scaled (2, 0) → rotated (0, 2) → offset (0.5, 2).
        assert!((t.apply(Vec2::new(1.0, 0.0)) - Vec2::new(0.5, 2.0)).length() < 1e-6);
        assert!((t.apply_vector(Vec2::new(1.0, 0.0)) - Vec2::new(0.0, 2.0)).length() < 1e-6);
        let twice = t.after(&t);
        let p = Vec2::new(0.3, -0.7);
        assert!((twice.apply(p) - t.apply(t.apply(p))).length() < 1e-5);
        assert!(UvTransform::default().is_identity() && !t.is_identity());
    }
}
