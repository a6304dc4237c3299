//! Mathematical solids: boxes, cylinders, cones, discs, ellipsoids, superellipsoids, tori and
//! algebraic surfaces, each the canonical
//! shape of its file placed in the world by an affine transform.
//!
//! A ray is taken into the solid's own space in `f64` and met there with the shape's equation
//! (a slab test, a quadratic, a quartic); the hit comes back to the world in `f32` with a
//! bound on its error, as [`crate::spawn`] needs. Because the roots are found in `f64` from an
//! origin that [`crate::spawn::offset_origin`] has put on the right side of the surface, a ray
//! leaving a solid needs no rule of its own: the crossing it starts from lies at `t ≤ 0`, and
//! a torus or a cone can still be met again further on.
//!
//! Every crossing a ray makes is reported, in order ([`Solid::crossings`]), as constructive
//! solid geometry will need; a closed solid's crossings alternate between entering and leaving.

pub mod algebraic;
pub mod cone;
pub mod csg;
#[cfg(test)]
mod csg_tests;
pub mod cuboid;
pub mod cylinder;
pub mod disc;
pub mod ellipsoid;
pub mod poly;
pub mod superellipsoid;
#[cfg(test)]
mod tests;
pub mod torus;

use super::gamma;
use arrayvec::ArrayVec;
use glam::{Affine3A, DAffine3, DMat3, DVec2, DVec3, Vec2, Vec3};
use lucent_accel::{Aabb, Ray};

/// A reproducible stream of numbers in `[-1, 1)` for the tests' random rays (a linear
/// congruential generator's top bits).
#[cfg(test)]
pub(crate) fn test_stream(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// Crossings of a line with a shape's surface: the ray parameter and which part of the surface
/// (a box's face, a cylinder's side or cap). At most four for a torus, two elsewhere.
pub type Crossings = ArrayVec<(f64, u8), 8>;

/// Texture coordinates at a point and their derivatives, in the shape's own space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// `(u, v)`.
    pub uv: DVec2,
    /// `∂p/∂u`.
    pub dpdu: DVec3,
    /// `∂p/∂v`.
    pub dpdv: DVec3,
}

/// A cap's or a disc's coordinates: `(x, y)` mapped from `[-1, 1]` to `[0, 1]`.
fn cap_frame(p: DVec3) -> Frame {
    Frame {
        uv: DVec2::new((p.x + 1.0) / 2.0, (p.y + 1.0) / 2.0),
        dpdu: DVec3::new(2.0, 0.0, 0.0),
        dpdv: DVec3::new(0.0, 2.0, 0.0),
    }
}

/// Which canonical shape, and its own proportions.
// An algebraic surface's 35 coefficients are held inline: a solid stays `Copy` and its
// intersection reads no second allocation.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolidShape {
    /// The cube `[-1, 1]³` ([`cuboid`]).
    Box,
    /// Radius 1 about z from `z = 0` to 1 ([`cylinder`]); `open`: without its caps.
    Cylinder {
        /// Without caps.
        open: bool,
    },
    /// About z from radius `radii[0]` at `z = 0` to `radii[1]` at `z = 1` ([`cone`]).
    Cone {
        /// The radii at the two ends, ≥ 0, not both 0.
        radii: [f64; 2],
        /// Without caps.
        open: bool,
    },
    /// Radius 1 in `z = 0`, facing `+z`, with a hole of radius `hole` ([`disc`]).
    Disc {
        /// The hole's radius, in `[0, 1)`.
        hole: f64,
    },
    /// The unit sphere, an ellipsoid once placed ([`ellipsoid`]).
    Ellipsoid,
    /// Barr's superellipsoid in the cube `[-1, 1]³` ([`superellipsoid`]).
    Superellipsoid {
        /// `[e, n]`: the exponents across and along z, > 0.
        exponents: [f64; 2],
    },
    /// Major radius 1 about z, tube radius `minor` ([`torus`]).
    Torus {
        /// The tube's radius, > 0.
        minor: f64,
    },
    /// Where a polynomial of degree ≤ 4 is zero ([`algebraic`]), found only within `bounds`
    /// (its own space's box) when given: without them it is unbounded and only a
    /// combination can hold it.
    Algebraic {
        /// The polynomial, in [`algebraic::POWERS`]' order.
        coefficients: algebraic::Coefficients,
        /// The box it is cut to, `[min, max]`.
        bounds: Option<[DVec3; 2]>,
    },
}

impl SolidShape {
    /// The name used in scene files.
    pub fn name(&self) -> &'static str {
        match self {
            SolidShape::Box => "box",
            SolidShape::Cylinder { .. } => "cylinder",
            SolidShape::Cone { .. } => "cone",
            SolidShape::Disc { .. } => "disc",
            SolidShape::Ellipsoid => "ellipsoid",
            SolidShape::Superellipsoid { .. } => "superellipsoid",
            SolidShape::Torus { .. } => "torus",
            SolidShape::Algebraic { .. } => "algebraic surface",
        }
    }

    /// The box about the shape in its own space; infinite for an unbounded one.
    fn bounds(&self) -> (DVec3, DVec3) {
        match *self {
            SolidShape::Algebraic { bounds, .. } => match bounds {
                Some([lo, hi]) => (lo, hi),
                None => (DVec3::NEG_INFINITY, DVec3::INFINITY),
            },
            SolidShape::Box => (DVec3::splat(-1.0), DVec3::ONE),
            SolidShape::Cylinder { .. } => (DVec3::new(-1.0, -1.0, 0.0), DVec3::ONE),
            SolidShape::Cone { radii, .. } => {
                let r = radii[0].max(radii[1]);
                (DVec3::new(-r, -r, 0.0), DVec3::new(r, r, 1.0))
            }
            SolidShape::Disc { .. } => (DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)),
            SolidShape::Ellipsoid | SolidShape::Superellipsoid { .. } => {
                (DVec3::splat(-1.0), DVec3::ONE)
            }
            SolidShape::Torus { minor } => torus::bounds(minor),
        }
    }

    /// The crossings of the line `o + t·d` with the surface, `t` in `range` at least.
    fn crossings(&self, o: DVec3, d: DVec3, range: [f64; 2], out: &mut Crossings) {
        match *self {
            SolidShape::Box => cuboid::crossings(o, d, out),
            SolidShape::Cylinder { open } => cylinder::crossings(o, d, open, out),
            SolidShape::Cone { radii, open } => cone::crossings(o, d, radii, open, out),
            SolidShape::Disc { hole } => disc::crossings(o, d, hole, out),
            SolidShape::Ellipsoid => ellipsoid::crossings(o, d, out),
            SolidShape::Superellipsoid { exponents } => {
                superellipsoid::crossings(o, d, exponents, range, out)
            }
            SolidShape::Torus { minor } => torus::crossings(o, d, minor, range, out),
            SolidShape::Algebraic {
                ref coefficients, ..
            } => algebraic::crossings(coefficients, o, d, range, out),
        }
    }

    /// The outward normal (not of unit length) at `p` on `part`.
    fn normal(&self, p: DVec3, part: u8) -> DVec3 {
        match *self {
            SolidShape::Box => cuboid::normal(part),
            SolidShape::Cylinder { .. } => cylinder::normal(p, part),
            SolidShape::Cone { radii, .. } => cone::normal(p, radii, part),
            SolidShape::Disc { .. } => DVec3::Z,
            SolidShape::Ellipsoid => p,
            SolidShape::Superellipsoid { exponents } => superellipsoid::normal(p, exponents),
            SolidShape::Torus { minor } => torus::normal(p, minor),
            // By reference: the 35 coefficients are not copied per call.
            SolidShape::Algebraic {
                ref coefficients, ..
            } => algebraic::normal(coefficients, p),
        }
    }

    fn frame(&self, p: DVec3, part: u8) -> Frame {
        match *self {
            SolidShape::Box => cuboid::frame(p, part),
            SolidShape::Cylinder { .. } => cylinder::frame(p, part),
            SolidShape::Cone { radii, .. } => cone::frame(p, radii, part),
            SolidShape::Disc { .. } => disc::frame(p),
            SolidShape::Ellipsoid => ellipsoid::frame(p),
            SolidShape::Superellipsoid { exponents } => superellipsoid::frame(p, exponents),
            SolidShape::Torus { .. } => torus::frame(p),
            SolidShape::Algebraic {
                ref coefficients, ..
            } => algebraic::frame(coefficients, p),
        }
    }

    /// Whether `p` lies inside (the capped volume for an open cylinder or cone; never for a
    /// disc).
    fn contains(&self, p: DVec3) -> bool {
        match *self {
            SolidShape::Box => cuboid::contains(p),
            SolidShape::Cylinder { .. } => cylinder::contains(p),
            SolidShape::Cone { radii, .. } => cone::contains(p, radii),
            SolidShape::Disc { .. } => false,
            SolidShape::Ellipsoid => ellipsoid::contains(p),
            SolidShape::Superellipsoid { exponents } => superellipsoid::contains(p, exponents),
            SolidShape::Torus { minor } => torus::contains(p, minor),
            SolidShape::Algebraic {
                ref coefficients, ..
            } => algebraic::contains(coefficients, p),
        }
    }
}

/// A canonical shape placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solid {
    /// The shape in its own space.
    pub shape: SolidShape,
    to_world: DAffine3,
    to_object: DAffine3,
    /// The inverse transpose of `to_world`'s linear part: normals to the world.
    normal_to_world: DMat3,
}

/// A point on a solid's surface in the world, as a hit needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidPoint {
    /// The point.
    pub point: Vec3,
    /// The outward unit normal.
    pub normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// `∂p/∂u` in the world.
    pub dpdu: Vec3,
    /// `∂p/∂v` in the world.
    pub dpdv: Vec3,
    /// A bound on the absolute error of `point`, per axis.
    pub error: Vec3,
}

impl Solid {
    /// `shape` placed by `to_world`; `None` when the transform is singular or not finite.
    pub fn new(shape: SolidShape, to_world: Affine3A) -> Option<Self> {
        let m = DAffine3 {
            matrix3: glam::Mat3::from(to_world.matrix3).as_dmat3(),
            translation: to_world.translation.as_dvec3(),
        };
        let det = m.matrix3.determinant();
        if !(det.is_finite() && det != 0.0 && m.translation.is_finite()) {
            return None;
        }
        Some(Self {
            shape,
            to_world: m,
            to_object: m.inverse(),
            normal_to_world: m.matrix3.inverse().transpose(),
        })
    }

    /// Whether it lies in a finite box (an algebraic surface given none, or one infinite on
    /// some axis, does not).
    pub fn is_bounded(&self) -> bool {
        let (lo, hi) = self.shape.bounds();
        lo.is_finite() && hi.is_finite()
    }

    /// The box about it in the world; all of space when it is unbounded.
    pub fn bounds(&self) -> Aabb {
        if !self.is_bounded() {
            return Aabb::new(Vec3::NEG_INFINITY, Vec3::INFINITY);
        }
        let (lo, hi) = self.shape.bounds();
        let mut b = Aabb::EMPTY;
        for i in 0..8 {
            let corner = DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let w = self.to_world.transform_point3(corner).as_vec3();
            // Widened by far more than the rounding to f32, so the box holds the f64 one.
            let pad = w.abs() * 1e-6 + Vec3::splat(f32::MIN_POSITIVE);
            b = b.union(Aabb::new(w - pad, w + pad));
        }
        b
    }

    /// The ray in the solid's own space (the same parameter `t`).
    fn local(&self, ray: &Ray) -> (DVec3, DVec3) {
        (
            self.to_object.transform_point3(ray.origin.as_dvec3()),
            self.to_object.transform_vector3(ray.dir.as_dvec3()),
        )
    }

    /// Every crossing of `ray` with the surface in `(0, t_max)`, nearest first.
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> Crossings {
        self.crossings_in(ray, 0.0, f64::from(t_max))
    }

    /// Every crossing of `ray`'s line with the surface in `(lo, hi)`, in order (`lo` may be
    /// −∞: what lies behind the origin tells whether it is inside).
    pub fn crossings_in(&self, ray: &Ray, lo: f64, hi: f64) -> Crossings {
        let mut out = Crossings::new();
        let (o, d) = self.local(ray);
        let Some(range) = self.range(o, d, lo, hi) else {
            return out;
        };
        self.shape.crossings(o, d, range, &mut out);
        out.retain(|c| c.0 > lo && c.0 < hi);
        out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        out
    }

    /// The nearest crossing in `(0, t_max)`.
    pub fn nearest(&self, ray: &Ray, t_max: f32) -> Option<(f64, u8)> {
        self.crossings(ray, t_max).first().copied()
    }

    /// Where the line `o + t·d` (own space) lies in the shape's box (widened by a hair) within
    /// `[t_lo, t_hi]`; `None` when it misses.
    fn range(&self, o: DVec3, d: DVec3, t_lo: f64, t_hi: f64) -> Option<[f64; 2]> {
        let (lo, hi) = self.shape.bounds();
        // Widened by the finite extents only (an algebraic surface's box may be infinite on
        // some axes).
        let size = (hi - lo).to_array();
        let pad = size
            .into_iter()
            .filter(|x| x.is_finite())
            .fold(0.0, f64::max)
            * 1e-9;
        let (lo, hi) = (lo - pad, hi + pad);
        let (mut near, mut far) = (t_lo, t_hi);
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if o[axis] < lo[axis] || o[axis] > hi[axis] {
                    return None;
                }
                continue;
            }
            let (a, b) = (
                (lo[axis] - o[axis]) / d[axis],
                (hi[axis] - o[axis]) / d[axis],
            );
            near = near.max(a.min(b));
            far = far.min(a.max(b));
        }
        (near <= far).then_some([near, far])
    }

    /// The surface where `ray` crosses it at `t` on `part` (from [`Solid::crossings`]).
    pub fn surface(&self, ray: &Ray, t: f64, part: u8) -> SolidPoint {
        let (o, d) = self.local(ray);
        let p = o + d * t;
        let world = self.to_world.transform_point3(p);
        let normal = (self.normal_to_world * self.shape.normal(p, part)).normalize_or(DVec3::Z);
        let frame = self.shape.frame(p, part);
        // The f64 point is exact to far below f32's precision; what remains is the sum that
        // places it (three products and the translation) and the rounding to f32.
        let magnitude = self.to_world.translation.abs() + self.to_world.matrix3.abs() * p.abs();
        let error = (magnitude + world.abs()) * f64::from(gamma(4));
        SolidPoint {
            point: world.as_vec3(),
            normal: normal.as_vec3(),
            uv: frame.uv.as_vec2(),
            dpdu: (self.to_world.matrix3 * frame.dpdu).as_vec3(),
            dpdv: (self.to_world.matrix3 * frame.dpdv).as_vec3(),
            error: error.as_vec3(),
        }
    }

    /// Whether the shape encloses a volume (a disc, an open cylinder or cone do not).
    pub fn is_closed(&self) -> bool {
        !matches!(
            self.shape,
            SolidShape::Disc { .. }
                | SolidShape::Cylinder { open: true }
                | SolidShape::Cone { open: true, .. }
        )
    }

    /// Whether `ray`'s origin lies inside, from the line's crossings `all` in `(−∞, t_max)`
    /// of which the first `behind` lie at `t ≤ 0`. A closed bounded shape's crossings
    /// alternate, so their count behind says it (robust for a ray starting on the surface);
    /// an algebraic surface may be crossed an odd number of times along a whole line (a
    /// paraboloid), so its sign is taken between the crossings about the origin.
    pub fn starts_inside(&self, ray: &Ray, all: &Crossings, behind: usize, t_max: f64) -> bool {
        let SolidShape::Algebraic { coefficients, .. } = &self.shape else {
            return behind % 2 == 1;
        };
        let before = behind.checked_sub(1).map(|i| all[i].0);
        let after = all.get(behind).map(|c| c.0);
        let t = match (before, after) {
            (Some(a), Some(b)) => 0.5 * (a + b),
            (Some(a), None) if t_max.is_finite() => 0.5 * (a + t_max),
            (Some(a), None) => a + a.abs().max(1.0),
            (None, Some(b)) => b - b.abs().max(1.0),
            (None, None) => 0.0,
        };
        let (o, d) = self.local(ray);
        algebraic::contains(coefficients, o + d * t)
    }

    /// Whether `p` lies inside.
    pub fn contains(&self, p: Vec3) -> bool {
        self.shape
            .contains(self.to_object.transform_point3(p.as_dvec3()))
    }
}
