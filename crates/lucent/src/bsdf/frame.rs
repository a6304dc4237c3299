//! An orthonormal shading frame: world directions to the local frame the BSDFs work in and back.

use glam::Vec3;

use crate::lanes::{Mask, Real, V3};

/// A right-handed orthonormal basis `(s, t, n)` with `s × t = n`; in local coordinates `n` is
/// `z`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent (local `x`).
    pub s: Vec3,
    /// Second tangent (local `y`).
    pub t: Vec3,
    /// The normal (local `z`).
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit normal `n`, by Duff et al. 2017, "Building an Orthonormal Basis,
    /// Revisited" (JCGT 6(1)): branch-free but for the sign of `n.z`, and accurate for every
    /// `n`, including `n.z ≈ −1`, where the older Frisvad construction lost precision.
    ///
    /// With `σ = sign(n.z)`, `a = −1/(σ + n.z)` and `b = n.x·n.y·a`:
    /// `s = (1 + σ·n.x²·a, σ·b, −σ·n.x)`, `t = (b, σ + n.y²·a, −n.y)`.
    pub fn from_normal(n: Vec3) -> Self {
        FrameOf::from_normal(n.into()).into()
    }

    /// A frame around the unit normal `n` whose first tangent follows `tangent` (a surface's
    /// `∂p/∂u`, projected onto the plane of `n`), as Mitsuba builds its shading frame, so that
    /// anisotropic roughness and tangent-space normal maps line up with the texture. Falls back
    /// to [`Frame::from_normal`] when `tangent` is (nearly) parallel to `n`, zero or not finite.
    pub fn from_normal_tangent(n: Vec3, tangent: Vec3) -> Self {
        FrameOf::from_normal_tangent(n.into(), tangent.into()).into()
    }

    /// The same frame seen from the other side: `(s, −t, −n)`, still right-handed.
    pub fn flipped(&self) -> Self {
        Self {
            s: self.s,
            t: -self.t,
            n: -self.n,
        }
    }

    /// `v` (world) in this frame's coordinates: `(v·s, v·t, v·n)`.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// `v` (local) back in world coordinates: `v.x·s + v.y·t + v.z·n`.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// [`Frame`] over any [`Real`]: the constructors and changes of coordinates written once, for
/// one path (`FrameOf<f32>`, which gives `Frame`'s bits) and for lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameOf<R> {
    /// First tangent (local `x`).
    pub s: V3<R>,
    /// Second tangent (local `y`).
    pub t: V3<R>,
    /// The normal (local `z`).
    pub n: V3<R>,
}

impl<R: Real> FrameOf<R> {
    /// [`Frame::from_normal`].
    #[inline(always)]
    pub fn from_normal(n: V3<R>) -> Self {
        // The sign bit of n.z, so that −0.0 takes the negative branch and σ + n.z never
        // cancels to 0.
        let sign = n.z.sign_one();
        let a = -R::splat(1.0) / (sign + n.z);
        let b = n.x * n.y * a;
        let one = R::splat(1.0);
        Self {
            s: V3::new(one + sign * n.x * n.x * a, sign * b, -sign * n.x),
            t: V3::new(b, sign + n.y * n.y * a, -n.y),
            n,
        }
    }

    /// [`Frame::from_normal_tangent`].
    #[inline(always)]
    pub fn from_normal_tangent(n: V3<R>, tangent: V3<R>) -> Self {
        let s = tangent - n * n.dot(tangent);
        let len2 = s.length_squared();
        let usable = len2.finite() & !len2.le(R::splat(1e-12) * tangent.length_squared());
        let fallback = Self::from_normal(n);
        if !usable.any() {
            return fallback;
        }
        let s = s / len2.sqrt();
        let t = n.cross(s);
        Self {
            s: V3::select(usable, s, fallback.s),
            t: V3::select(usable, t, fallback.t),
            n,
        }
    }

    /// [`Frame::to_local`].
    #[inline(always)]
    pub fn to_local(&self, v: V3<R>) -> V3<R> {
        V3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// [`Frame::to_world`].
    #[inline(always)]
    pub fn to_world(&self, v: V3<R>) -> V3<R> {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

impl From<FrameOf<f32>> for Frame {
    #[inline(always)]
    fn from(f: FrameOf<f32>) -> Self {
        Self {
            s: f.s.into(),
            t: f.t.into(),
            n: f.n.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Normals over the sphere, with the poles and the awkward near-−z ones included.
    fn normals() -> Vec<Vec3> {
        let mut v = vec![
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            -Vec3::Y,
            Vec3::new(1e-4, 0.0, -1.0).normalize(),
            Vec3::new(0.0, -1e-7, -1.0).normalize(),
            // A tangent normal whose z is −0.0 takes the negative branch.
            Vec3::new(1.0, 0.0, -0.0),
        ];
        for i in 0..200 {
            let z = -1.0 + (i as f32 + 0.5) / 100.0;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            v.push(Vec3::new(r * phi.cos(), r * phi.sin(), z));
        }
        v
    }

    #[test]
    fn the_basis_is_orthonormal_and_right_handed() {
        for n in normals() {
            let f = Frame::from_normal(n);
            for (a, b) in [(f.s, f.t), (f.t, f.n), (f.n, f.s)] {
                assert!(a.dot(b).abs() < 1e-5, "{n}: not orthogonal");
            }
            for a in [f.s, f.t] {
                assert!((a.length() - 1.0).abs() < 1e-5, "{n}: tangent not unit");
            }
            assert!((f.s.cross(f.t) - f.n).length() < 1e-5, "{n}: left-handed");
        }
    }

    #[test]
    fn a_tangent_frame_follows_its_tangent_and_falls_back_when_it_cannot() {
        for n in normals() {
            let tangent = Vec3::new(0.3, 0.9, -0.2);
            let f = Frame::from_normal_tangent(n, tangent);
            assert!((f.s.cross(f.t) - f.n).length() < 1e-4, "{n}: left-handed");
            assert!(f.s.dot(n).abs() < 1e-4 && (f.s.length() - 1.0).abs() < 1e-4);
            if n.cross(tangent.normalize()).length() > 0.1 {
                assert!(
                    f.s.dot(tangent) > 0.0,
                    "{n}: s turned away from the tangent"
                );
            }
            let back = f.flipped();
            assert!((back.s.cross(back.t) - back.n).length() < 1e-4 && back.n == -n);
        }
        assert_eq!(
            Frame::from_normal_tangent(Vec3::Z, Vec3::Z * 2.0),
            Frame::from_normal(Vec3::Z)
        );
        assert_eq!(
            Frame::from_normal_tangent(Vec3::Z, Vec3::NAN),
            Frame::from_normal(Vec3::Z)
        );
    }

    #[test]
    fn local_and_world_are_inverse() {
        for n in normals() {
            let f = Frame::from_normal(n);
            assert!((f.to_local(n) - Vec3::Z).length() < 1e-5);
            let v = Vec3::new(0.3, -0.5, 0.81).normalize();
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
            assert!((f.to_local(f.to_world(v)) - v).length() < 1e-5);
        }
    }
}
