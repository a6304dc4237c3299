//! Area lights: the surfaces of objects whose material emits (`ke`), sampled by the path
//! tracer for next-event estimation.
//!
//! An emitter radiates `ke` from its front side only (a triangle's winding normal, a sphere's
//! outside), as Mitsuba's `area` emitter does. Triangles are sampled uniformly by area over the
//! whole object (a triangle picked in proportion to its area, then a uniform point in it), so
//! the area density is `1 / A` everywhere on it; spheres seen from outside are sampled
//! uniformly over the cone of directions they cover, which wastes no sample on the far side.

use crate::Rgb;
use crate::lanes::{Real, V3};
use crate::sampling::distribution::Distribution1D;
use crate::sampling::warp::{square_to_uniform_cone, uniform_triangle};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The shape of one area light, in world space.
#[derive(Clone, Debug)]
pub enum EmitterShape {
    /// Triangles `first..first + count` of [`AreaLights::triangles`], picked by area.
    Triangles {
        /// The first triangle.
        first: u32,
        /// Areas of the triangles, for picking one.
        areas: Distribution1D,
    },
    /// A sphere.
    Sphere {
        /// Its centre.
        center: Vec3,
        /// Its radius.
        radius: f32,
    },
}

/// One emitting object.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// The scene object it is.
    pub object: u32,
    /// Radiance leaving its front side.
    pub radiance: Rgb,
    /// Its surface.
    pub shape: EmitterShape,
    /// Its area.
    pub area: f32,
}

/// A point on a light as seen from a shaded point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterSample {
    /// Unit direction from the shaded point to the light.
    pub wi: Vec3,
    /// Distance to the sampled point (infinite for lights at infinity).
    pub distance: f32,
    /// Radiance arriving along `wi` from the light (not divided by the pdf).
    pub radiance: Rgb,
    /// Solid-angle density of `wi` (for a delta light, the probability of picking it).
    pub pdf: f32,
    /// True for point-like and directional lights: no other technique can find them.
    pub delta: bool,
}

/// Every area light of a scene, with the world-space triangles they are made of.
#[derive(Clone, Debug, Default)]
pub struct AreaLights {
    /// The lights.
    pub lights: Vec<AreaLight>,
    /// World-space triangles of the triangle emitters, counter-clockwise from the front.
    pub triangles: Vec<[Vec3; 3]>,
    /// Their unit front normals (zero for a degenerate one), worked out once.
    normals: Vec<Vec3>,
}

impl AreaLights {
    /// Adds an emitting object made of world-space `triangles` (degenerate ones are never
    /// sampled); nothing when their area is zero.
    pub fn add_triangles(&mut self, object: u32, radiance: Rgb, triangles: &[[Vec3; 3]]) {
        let areas: Vec<f32> = triangles.iter().map(triangle_area).collect();
        let Some(dist) = Distribution1D::new(&areas) else {
            return;
        };
        let area = areas.iter().map(|&a| f64::from(a)).sum::<f64>() as f32;
        let first = self.triangles.len() as u32;
        self.triangles.extend_from_slice(triangles);
        self.normals.extend(
            triangles
                .iter()
                .map(|[a, b, c]| (*b - *a).cross(*c - *a).normalize_or_zero()),
        );
        self.lights.push(AreaLight {
            object,
            radiance,
            shape: EmitterShape::Triangles { first, areas: dist },
            area,
        });
    }

    /// Adds an emitting sphere.
    pub fn add_sphere(&mut self, object: u32, radiance: Rgb, center: Vec3, radius: f32) {
        self.lights.push(AreaLight {
            object,
            radiance,
            shape: EmitterShape::Sphere { center, radius },
            area: 4.0 * PI * radius * radius,
        });
    }

    /// A point on light `i` seen from `p`, from two uniform numbers `u` (and `u_pick`, which
    /// picks a triangle); `None` when the light shows `p` only its back. `pdf` is the
    /// solid-angle density within this light.
    pub fn sample(&self, i: usize, p: Vec3, u_pick: f32, u: Vec2) -> Option<EmitterSample> {
        let light = &self.lights[i];
        match &light.shape {
            EmitterShape::Triangles { first, areas } => {
                let (k, _, _) = areas.sample_discrete(u_pick);
                let t = *first as usize + k;
                let [a, b, c] = self.triangles[t].map(V3::from);
                let (ok, wi, distance, pdf) = triangle_light_sample(
                    [a, b, c],
                    self.normals[t].into(),
                    p.into(),
                    (u.x, u.y),
                    light.area,
                );
                ok.then(|| EmitterSample {
                    wi: wi.into(),
                    distance,
                    radiance: light.radiance,
                    pdf,
                    delta: false,
                })
            }
            EmitterShape::Sphere { center, radius } => {
                let to_center = *center - p;
                let d2 = to_center.length_squared();
                let r2 = radius * radius;
                // From inside, only the sphere's back is seen, which does not emit.
                if d2.is_nan() || d2 <= r2 {
                    return None;
                }
                let d = d2.sqrt();
                let axis = to_center / d;
                let cos_max = (1.0 - r2 / d2).max(0.0).sqrt();
                let local = square_to_uniform_cone(u, cos_max);
                let wi = crate::bsdf::Frame::from_normal(axis).to_world(local);
                // Distance to the near side along wi (the tangent distance at the rim).
                let b = wi.dot(to_center);
                let disc = (r2 - (d2 - b * b)).max(0.0);
                let distance = (b - disc.sqrt()).max(0.0);
                Some(EmitterSample {
                    wi,
                    distance,
                    radiance: light.radiance,
                    pdf: cone_pdf(cos_max),
                    delta: false,
                })
            }
        }
    }

    /// The triangle that light `i` picks with `u_pick` ([`AreaLights::sample`]'s choice): its
    /// index in [`AreaLights::triangles`]; `None` for a light that is not made of triangles.
    pub(super) fn triangle_picked(&self, i: usize, u_pick: f32) -> Option<usize> {
        match &self.lights[i].shape {
            EmitterShape::Triangles { first, areas } => {
                Some(*first as usize + areas.sample_discrete(u_pick).0)
            }
            EmitterShape::Sphere { .. } => None,
        }
    }

    /// Triangle `t`'s corners and unit front normal.
    pub(super) fn triangle(&self, t: usize) -> ([Vec3; 3], Vec3) {
        (self.triangles[t], self.normals[t])
    }

    /// The solid-angle density with which [`AreaLights::sample`] picks the direction from `p`
    /// to the point `x` (geometric normal `n`) of light `i`.
    pub fn pdf(&self, i: usize, p: Vec3, x: Vec3, n: Vec3) -> f32 {
        let light = &self.lights[i];
        match &light.shape {
            EmitterShape::Triangles { .. } => {
                let offset = x - p;
                let d2 = offset.length_squared();
                let cos_light = n.dot(offset).abs() / d2.sqrt();
                if cos_light > 0.0 && light.area > 0.0 {
                    d2 / (cos_light * light.area)
                } else {
                    0.0
                }
            }
            EmitterShape::Sphere { center, radius } => {
                let d2 = (*center - p).length_squared();
                let r2 = radius * radius;
                if d2 > r2 {
                    cone_pdf((1.0 - r2 / d2).max(0.0).sqrt())
                } else {
                    0.0
                }
            }
        }
    }

    /// Power of light `i`: `π·L·A` for a one-sided Lambertian emitter (luminance).
    pub fn power(&self, i: usize) -> f32 {
        let l = &self.lights[i];
        PI * luminance(l.radiance) * l.area
    }
}

/// The density of uniform directions in a cone of half-angle `acos(cos_max)`.
fn cone_pdf(cos_max: f32) -> f32 {
    let solid_angle = 2.0 * PI * (1.0 - cos_max);
    if solid_angle > 0.0 {
        1.0 / solid_angle
    } else {
        0.0
    }
}

/// The area of a triangle.
pub fn triangle_area(t: &[Vec3; 3]) -> f32 {
    let a = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
    if a.is_finite() { a } else { 0.0 }
}

/// Rec. 709 luminance of a linear colour.
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b
}

/// A point of a triangle light, seen from `p`, for any [`Real`] (written once for one path and
/// for lanes): the triangle's corners, its unit front normal `n`, two uniform numbers, its
/// light's whole area. Where the point is away from `p` and the front faces `p` (the mask), the
/// unit direction to it, its distance and the solid-angle density `d²/(cos θ_light · A)`.
#[inline(always)]
pub fn triangle_light_sample<R: Real>(
    [a, b, c]: [V3<R>; 3],
    n: V3<R>,
    p: V3<R>,
    (ux, uy): (R, R),
    area: R,
) -> (R::Mask, V3<R>, R, R) {
    let (b0, b1) = uniform_triangle(ux, uy);
    let x = a * b0 + b * b1 + c * (R::splat(1.0) - b0 - b1);
    let offset = x - p;
    let d2 = offset.length_squared();
    let distance = d2.sqrt();
    let wi = offset / distance;
    // The light's front must face p.
    let cos_light = -n.dot(wi);
    let zero = R::splat(0.0);
    let ok = distance.gt(zero) & cos_light.gt(zero);
    (ok, wi, distance, d2 / (cos_light * area))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_light() -> AreaLights {
        // A unit square at y = 1 facing down (−y), radiance 2.
        let (a, b, c, d) = (
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
        );
        let mut lights = AreaLights::default();
        lights.add_triangles(0, Rgb::gray(2.0), &[[a, b, c], [a, c, d]]);
        lights
    }

    #[test]
    fn a_square_lights_a_point_below_with_its_solid_angle() {
        // E = ∫ L cos θ dω over the square; estimate it by sampling and compare with a fine
        // quadrature of the same integral.
        let lights = square_light();
        assert!((lights.lights[0].area - 1.0).abs() < 1e-6);
        let p = Vec3::new(0.3, 0.0, 0.6);
        let n = 200_000u32;
        let mut estimate = 0.0f64;
        for k in 0..n {
            let r = |d| crate::sampling::uniform(3, u64::from(k), 0, d);
            let s = lights.sample(0, p, r(0), Vec2::new(r(1), r(2))).unwrap();
            assert!(s.wi.y > 0.0);
            let x = p + s.wi * s.distance;
            assert!((x.y - 1.0).abs() < 1e-5);
            let pdf = lights.pdf(0, p, x, Vec3::NEG_Y);
            assert!((pdf - s.pdf).abs() <= 1e-4 * pdf, "{pdf} vs {}", s.pdf);
            estimate += f64::from(s.radiance.r * s.wi.y / s.pdf);
        }
        estimate /= f64::from(n);
        let m = 400;
        let mut quad = 0.0f64;
        for i in 0..m {
            for j in 0..m {
                let x = Vec3::new(
                    (i as f32 + 0.5) / m as f32,
                    1.0,
                    (j as f32 + 0.5) / m as f32,
                );
                let v = x - p;
                let d2 = v.length_squared();
                let cos = v.y / d2.sqrt();
                quad += f64::from(2.0 * cos * cos / d2) / f64::from(m * m);
            }
        }
        assert!(
            (estimate - quad).abs() < 5e-3 * quad,
            "{estimate} vs {quad}"
        );
        // From above, the light shows its back: nothing.
        assert!(
            lights
                .sample(0, Vec3::new(0.5, 2.0, 0.5), 0.3, Vec2::splat(0.5))
                .is_none()
        );
    }

    #[test]
    fn a_sphere_is_sampled_over_its_cone() {
        let mut lights = AreaLights::default();
        lights.add_sphere(3, Rgb::WHITE, Vec3::new(0.0, 0.0, -4.0), 1.0);
        let p = Vec3::ZERO;
        let cos_max = (1.0f32 - 1.0 / 16.0).sqrt();
        for k in 0..100 {
            let u = Vec2::new((k % 10) as f32 / 10.0 + 0.05, (k / 10) as f32 / 10.0 + 0.05);
            let s = lights.sample(0, p, 0.0, u).unwrap();
            assert!(s.wi.dot(Vec3::NEG_Z) >= cos_max - 1e-5);
            let x = p + s.wi * s.distance;
            assert!(((x - Vec3::new(0.0, 0.0, -4.0)).length() - 1.0).abs() < 1e-3);
            assert!((s.pdf - 1.0 / (2.0 * PI * (1.0 - cos_max))).abs() < 1e-3 * s.pdf);
        }
        // Inside, nothing is seen of the outside.
        assert!(
            lights
                .sample(0, Vec3::new(0.0, 0.0, -4.2), 0.0, Vec2::splat(0.5))
                .is_none()
        );
        assert!((lights.power(0) - PI * 4.0 * PI).abs() < 1e-3);
    }
}
