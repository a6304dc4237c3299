//! Lights whose intensity along each direction is read from an image: goniometric lights (an
//! image of intensity over the whole sphere, as pbrt's goniometric light takes it), projectors
//! (an image thrown through a frustum, pbrt's projection light) and spot lights with a texture
//! (a gobo: the image across the spot's cone, under its edge).
//!
//! An [`IntensityImage`] holds the texels (linear RGB, a factor on the light's intensity) and
//! how they lie on the sphere of directions of the light's own frame ([`Mapping`]); it answers
//! the intensity along a direction (bilinear between texel centres), its total `∫ I dω`, and
//! draws directions for photons in proportion to it. The light's frame: `+z` forward (a
//! projector's axis), `+y` up (a goniometric map's pole), `+x` to the image's right as seen from
//! behind a projector — so a projector's frame, like a camera's view, is left-handed
//! (`x = z × y`); a goniometric light's is right-handed. Either way it is orthonormal, and its
//! transpose takes directions back to the world.

use super::LightSample;
use super::point::PointLight;
use crate::Rgb;
use crate::sampling::distribution::Distribution2D;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::Arc;

/// How an image's texels lie on the sphere of directions, in the light's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mapping {
    /// The whole sphere on a square of equal areas (Clarberg's octahedral map, as pbrt-v4's
    /// goniometric light uses it): up (`+y`) at the centre, down at the four corners; `u`
    /// grows towards `+x` and `v` towards `+z`. Every texel is the same solid angle.
    EqualArea,
    /// Latitude and longitude: the top row looks up (`+y`), the bottom row down; the columns
    /// turn about `y` from `+x` (the left edge) through `+z` (a quarter across).
    LatLong,
    /// A frustum along `+z`: the image spans `tan_x` and `tan_y` either side of the axis (at
    /// unit distance), `+x` to the image's right and `+y` to its top; nothing outside.
    Projection {
        /// Tangent of half the horizontal angle.
        tan_x: f32,
        /// Tangent of half the vertical angle.
        tan_y: f32,
    },
}

/// The smooth edge of a spot light's cone about `+z`: full inside `cos_start`, fading
/// (smoothstep in the cosine) to nothing at `cos_cutoff`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Cosine of the half-angle beyond which nothing is sent.
    pub cos_cutoff: f32,
    /// Cosine of the half-angle where the fade starts (`≥ cos_cutoff`).
    pub cos_start: f32,
}

impl Cone {
    /// The share sent at `cos` from the axis.
    pub fn edge(&self, cos: f32) -> f32 {
        if cos <= self.cos_cutoff {
            0.0
        } else if cos < self.cos_start {
            let x = (cos - self.cos_cutoff) / (self.cos_start - self.cos_cutoff);
            x * x * (3.0 - 2.0 * x)
        } else {
            1.0
        }
    }
}

impl Mapping {
    /// The image coordinates in `[0, 1]²` (`v` down) of unit direction `d` of the light's
    /// frame; `None` outside a projection's frustum.
    pub fn uv(self, d: Vec3) -> Option<Vec2> {
        match self {
            Mapping::EqualArea => Some(equal_area_sphere_to_square(Vec3::new(d.x, d.z, d.y))),
            Mapping::LatLong => {
                let theta = d.y.clamp(-1.0, 1.0).acos();
                let phi = d.z.atan2(d.x).rem_euclid(2.0 * PI);
                Some(Vec2::new(phi / (2.0 * PI), theta / PI))
            }
            Mapping::Projection { tan_x, tan_y } => {
                if d.z <= 0.0 {
                    return None;
                }
                let (sx, sy) = (d.x / d.z / tan_x, d.y / d.z / tan_y);
                ((-1.0..=1.0).contains(&sx) && (-1.0..=1.0).contains(&sy))
                    .then(|| Vec2::new(0.5 * (sx + 1.0), 0.5 * (1.0 - sy)))
            }
        }
    }

    /// The unit direction at image coordinates `uv`, and the solid angle per unit area of the
    /// image there (`dω / du dv`).
    pub fn direction(self, uv: Vec2) -> (Vec3, f32) {
        match self {
            Mapping::EqualArea => {
                let w = equal_area_square_to_sphere(uv);
                (Vec3::new(w.x, w.z, w.y), 4.0 * PI)
            }
            Mapping::LatLong => {
                let (theta, phi) = (uv.y * PI, uv.x * 2.0 * PI);
                let d = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                (d, 2.0 * PI * PI * theta.sin())
            }
            Mapping::Projection { tan_x, tan_y } => {
                let (x, y) = ((2.0 * uv.x - 1.0) * tan_x, (1.0 - 2.0 * uv.y) * tan_y);
                let r2 = 1.0 + x * x + y * y;
                let d = Vec3::new(x, y, 1.0) / r2.sqrt();
                (d, 4.0 * tan_x * tan_y / (r2 * r2.sqrt()))
            }
        }
    }
}

/// Clarberg's equal-area map of the unit sphere onto `[0, 1]²`: `+z` at the centre, `−z` at the
/// corners, each octant a triangle of the square.
pub fn equal_area_sphere_to_square(d: Vec3) -> Vec2 {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let (a, b) = (x.max(y), x.min(y));
    let ratio = if a == 0.0 { 0.0 } else { b / a };
    let mut phi = ratio.atan() * 2.0 / PI;
    if x < y {
        phi = 1.0 - phi;
    }
    let mut v = phi * r;
    let mut u = r - v;
    if d.z < 0.0 {
        (u, v) = (1.0 - v, 1.0 - u);
    }
    let (u, v) = (u.copysign(d.x), v.copysign(d.y));
    Vec2::new(0.5 * (u + 1.0), 0.5 * (v + 1.0))
}

/// The inverse of [`equal_area_sphere_to_square`].
pub fn equal_area_square_to_sphere(p: Vec2) -> Vec3 {
    let (u, v) = (2.0 * p.x - 1.0, 2.0 * p.y - 1.0);
    let (up, vp) = (u.abs(), v.abs());
    let signed_distance = 1.0 - (up + vp);
    let r = 1.0 - signed_distance.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * PI / 4.0;
    let z = (1.0 - r * r).copysign(signed_distance);
    let s = r * (2.0 - r * r).max(0.0).sqrt();
    Vec3::new(phi.cos().copysign(u) * s, phi.sin().copysign(v) * s, z)
}

/// Sub-samples per texel side when the total `∫ I dω` is integrated.
const TOTAL_SUBSAMPLES: usize = 4;

/// An image of intensities over directions: see the module's documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct IntensityImage {
    mapping: Mapping,
    cone: Option<Cone>,
    width: usize,
    height: usize,
    texels: Vec<Rgb>,
    total: Rgb,
    /// Over the texels, each weighted by the largest luminance of it and its neighbours (what
    /// the bilinear lookup may reach) times its solid angle; `None` when all are black.
    distribution: Option<Distribution2D>,
}

/// Why texels are no intensity image.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntensityImageError {
    /// The size is zero or does not match the texels.
    #[error("an intensity image of {width}×{height} needs that many texels, not {texels}")]
    Size {
        /// Across.
        width: usize,
        /// Down.
        height: usize,
        /// Given.
        texels: usize,
    },
    /// A texel that is negative, NaN or infinite.
    #[error("texel ({x}, {y}) is {value:?}: intensities must be finite and not negative")]
    Texel {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// Its value.
        value: [f32; 3],
    },
}

impl IntensityImage {
    /// `width × height` texels, row by row from the top, laid on the sphere by `mapping` and
    /// (a textured spot) under `cone`'s edge.
    pub fn new(
        mapping: Mapping,
        cone: Option<Cone>,
        width: usize,
        height: usize,
        texels: Vec<Rgb>,
    ) -> Result<Self, IntensityImageError> {
        if width == 0 || height == 0 || width.checked_mul(height) != Some(texels.len()) {
            return Err(IntensityImageError::Size {
                width,
                height,
                texels: texels.len(),
            });
        }
        for (i, t) in texels.iter().enumerate() {
            let c = [t.r, t.g, t.b];
            if !c.iter().all(|v| v.is_finite() && *v >= 0.0) {
                let (x, y) = (i % width, i / width);
                return Err(IntensityImageError::Texel { x, y, value: c });
            }
        }
        let mut image = Self {
            mapping,
            cone,
            width,
            height,
            texels,
            total: Rgb::BLACK,
            distribution: None,
        };
        image.total = image.integrate();
        image.distribution = image.sampling_distribution();
        Ok(image)
    }

    /// How the texels lie on the sphere.
    pub fn mapping(&self) -> Mapping {
        self.mapping
    }

    /// The spot's edge, for a textured spot light.
    pub fn cone(&self) -> Option<Cone> {
        self.cone
    }

    /// Texels across and down.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The texel at column `x`, row `y`, clamped to the image (and wrapped across a lat-long
    /// map's seam).
    fn texel(&self, x: i64, y: i64) -> Rgb {
        let (w, h) = (self.width as i64, self.height as i64);
        let x = match self.mapping {
            Mapping::LatLong => x.rem_euclid(w),
            _ => x.clamp(0, w - 1),
        };
        self.texels[(y.clamp(0, h - 1) * w + x) as usize]
    }

    /// The image at `uv`, bilinear between texel centres.
    fn lookup(&self, uv: Vec2) -> Rgb {
        let (fx, fy) = (
            uv.x * self.width as f32 - 0.5,
            uv.y * self.height as f32 - 0.5,
        );
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = self.texel(x0, y0) * (1.0 - tx) + self.texel(x0 + 1, y0) * tx;
        let bottom = self.texel(x0, y0 + 1) * (1.0 - tx) + self.texel(x0 + 1, y0 + 1) * tx;
        top * (1.0 - ty) + bottom * ty
    }

    /// The intensity (a factor on the light's) along unit direction `d` of the light's frame.
    pub fn intensity(&self, d: Vec3) -> Rgb {
        let Some(uv) = self.mapping.uv(d) else {
            return Rgb::BLACK;
        };
        let edge = self.cone.map_or(1.0, |c| c.edge(d.z));
        if edge == 0.0 {
            return Rgb::BLACK;
        }
        self.lookup(uv) * edge
    }

    /// `∫ I dω` over the sphere, per channel.
    pub fn total(&self) -> Rgb {
        self.total
    }

    /// The integral of the bilinear image over the sphere: `TOTAL_SUBSAMPLES²` points per
    /// texel, each weighing its solid angle.
    fn integrate(&self) -> Rgb {
        let n = TOTAL_SUBSAMPLES;
        let (w, h) = (self.width, self.height);
        let du = 1.0 / (w * n) as f32;
        let dv = 1.0 / (h * n) as f32;
        let mut sum = [0.0f64; 3];
        for j in 0..h * n {
            for i in 0..w * n {
                let uv = Vec2::new((i as f32 + 0.5) * du, (j as f32 + 0.5) * dv);
                let (d, jacobian) = self.mapping.direction(uv);
                let edge = self.cone.map_or(1.0, |c| c.edge(d.z));
                let c = self.lookup(uv) * (edge * jacobian * du * dv);
                for (s, v) in sum.iter_mut().zip([c.r, c.g, c.b]) {
                    *s += f64::from(v);
                }
            }
        }
        Rgb::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
    }

    /// The distribution photons are drawn from (see the field).
    fn sampling_distribution(&self) -> Option<Distribution2D> {
        let (w, h) = (self.width as i64, self.height as i64);
        let mut weights = Vec::with_capacity(self.texels.len());
        for y in 0..h {
            for x in 0..w {
                let mut most = 0.0f32;
                for (dx, dy) in (-1..=1).flat_map(|dx| (-1..=1).map(move |dy| (dx, dy))) {
                    most = most.max(self.texel(x + dx, y + dy).luminance());
                }
                let centre = Vec2::new(
                    (x as f32 + 0.5) / self.width as f32,
                    (y as f32 + 0.5) / self.height as f32,
                );
                // The solid angle at the texel's centre; a lat-long map's poles keep a little,
                // so that the texels there can still be drawn.
                let (_, jacobian) = self.mapping.direction(centre);
                weights.push(most * jacobian.max(1e-4));
            }
        }
        Distribution2D::new(&weights, self.width, self.height)
    }

    /// A direction of the light's frame drawn in proportion (roughly) to the intensity, and
    /// its density over solid angle; `None` for a black image or a draw of zero density.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let (uv, pdf_uv) = self.distribution.as_ref()?.sample(u);
        let (d, jacobian) = self.mapping.direction(uv);
        let pdf = pdf_uv / jacobian;
        (pdf.is_finite() && pdf > 0.0).then_some((d, pdf))
    }

    /// The density of [`IntensityImage::sample`] along `d`, over solid angle.
    pub fn pdf(&self, d: Vec3) -> f32 {
        let (Some(dist), Some(uv)) = (&self.distribution, self.mapping.uv(d)) else {
            return 0.0;
        };
        let uv = uv.min(Vec2::splat(1.0 - f32::EPSILON));
        let (_, jacobian) = self.mapping.direction(uv);
        dist.pdf(uv) / jacobian
    }
}

/// A point light whose intensity along each direction an [`IntensityImage`] scales.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageLight {
    /// Position, intensity (the image's unit) and falloff.
    pub point: PointLight,
    /// Takes world directions to the light's frame (a rotation).
    pub to_light: Mat3,
    /// The image.
    pub image: Arc<IntensityImage>,
}

impl ImageLight {
    /// The light reaching `p`, if any goes its way.
    pub fn illuminate(&self, p: Vec3) -> Option<LightSample> {
        let mut s = self.point.illuminate(p)?;
        let i = self.image.intensity(self.to_light * -s.to_light);
        if i.is_black() {
            return None;
        }
        s.intensity *= i;
        Some(s)
    }

    /// `∫ I dω` of the light, per channel: its flux.
    pub fn power(&self) -> Rgb {
        self.point.intensity * self.image.total()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(w: usize, h: usize) -> Vec<Rgb> {
        vec![Rgb::WHITE; w * h]
    }

    #[test]
    fn the_equal_area_map_is_its_own_inverse_and_keeps_areas() {
        for i in 0..200 {
            let u = Vec2::new(
                (i as f32 * 0.618_034).fract(),
                (i as f32 * 0.381_966 + 0.1).fract(),
            );
            let d = equal_area_square_to_sphere(u);
            assert!((d.length() - 1.0).abs() < 1e-5, "{d}");
            let back = equal_area_sphere_to_square(d);
            assert!((back - u).length() < 1e-4, "{u} -> {d} -> {back}");
        }
        // Up at the centre, down at a corner.
        assert!((equal_area_square_to_sphere(Vec2::splat(0.5)) - Vec3::Z).length() < 1e-6);
        assert!((equal_area_square_to_sphere(Vec2::ZERO) + Vec3::Z).length() < 1e-6);
        // Equal areas: a quarter of the square around the centre is a quarter of the sphere
        // (the cap above z = 1/2 is exactly that).
        let n = 200;
        let above = (0..n * n)
            .filter(|k| {
                let u = Vec2::new(
                    ((k % n) as f32 + 0.5) / n as f32,
                    ((k / n) as f32 + 0.5) / n as f32,
                );
                equal_area_square_to_sphere(u).z > 0.5
            })
            .count();
        let share = above as f32 / (n * n) as f32;
        assert!((share - 0.25).abs() < 0.01, "{share}");
    }

    #[test]
    fn a_white_image_sends_its_solid_angle() {
        let total = |m: Mapping, cone: Option<Cone>| {
            IntensityImage::new(m, cone, 32, 16, grey(32, 16))
                .unwrap()
                .total()
                .g
        };
        let sphere = 4.0 * PI;
        assert!((total(Mapping::EqualArea, None) - sphere).abs() < sphere * 1e-4);
        assert!((total(Mapping::LatLong, None) - sphere).abs() < sphere * 1e-3);
        // A frustum of ±45° both ways: the solid angle of a face of the cube, 4π/6.
        let face = Mapping::Projection {
            tan_x: 1.0,
            tan_y: 1.0,
        };
        assert!((total(face, None) - sphere / 6.0).abs() < sphere / 6.0 * 1e-3);
        // A hard cone of 30° inside it: 2π(1 − cos 30°).
        let cos = 30f32.to_radians().cos();
        let cone = Cone {
            cos_cutoff: cos,
            cos_start: cos,
        };
        let exact = 2.0 * PI * (1.0 - cos);
        let t = total(face, Some(cone));
        assert!((t - exact).abs() < exact * 0.01, "{t} {exact}");
    }

    #[test]
    fn a_projection_throws_its_texels_where_they_belong() {
        // 2 × 2: red top left, green top right, blue bottom left, white bottom right.
        let texels = vec![
            Rgb::new(1.0, 0.0, 0.0),
            Rgb::new(0.0, 1.0, 0.0),
            Rgb::new(0.0, 0.0, 1.0),
            Rgb::WHITE,
        ];
        let m = Mapping::Projection {
            tan_x: 0.5,
            tan_y: 0.5,
        };
        let image = IntensityImage::new(m, None, 2, 2, texels).unwrap();
        let at = |x: f32, y: f32| image.intensity(Vec3::new(x, y, 1.0).normalize());
        assert_eq!(at(-0.4, 0.4), Rgb::new(1.0, 0.0, 0.0)); // up and to the left
        assert_eq!(at(0.4, 0.4), Rgb::new(0.0, 1.0, 0.0));
        assert_eq!(at(-0.4, -0.4), Rgb::new(0.0, 0.0, 1.0));
        assert_eq!(at(0.6, 0.0), Rgb::BLACK); // outside the frustum
        assert_eq!(image.intensity(-Vec3::Z), Rgb::BLACK); // behind it
    }

    #[test]
    fn draws_follow_the_intensity_and_their_density_is_the_pdf() {
        // Bright on the left half of a lat-long map, a tenth as bright on the right.
        let (w, h) = (16, 8);
        let texels: Vec<Rgb> = (0..w * h)
            .map(|i| {
                if i % w < w / 2 {
                    Rgb::WHITE
                } else {
                    Rgb::WHITE * 0.1
                }
            })
            .collect();
        let image = IntensityImage::new(Mapping::LatLong, None, w, h, texels).unwrap();
        // The photon estimate of the total, I/p averaged, equals the integral.
        let n = 512;
        let mut sum = 0.0f64;
        for j in 0..n {
            for i in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let (d, pdf) = image.sample(u).unwrap();
                assert!(
                    (image.pdf(d) - pdf).abs() <= pdf * 1e-3,
                    "{} {pdf}",
                    image.pdf(d)
                );
                sum += f64::from(image.intensity(d).g / pdf);
            }
        }
        let estimate = sum / f64::from(n * n);
        let total = f64::from(image.total().g);
        assert!(
            (estimate - total).abs() < total * 0.01,
            "{estimate} {total}"
        );
    }

    #[test]
    fn bad_texels_are_refused() {
        let mut texels = grey(2, 2);
        texels[3] = Rgb::new(0.0, f32::NAN, 0.0);
        let e = IntensityImage::new(Mapping::EqualArea, None, 2, 2, texels).unwrap_err();
        assert!(e.to_string().contains("texel (1, 1)"), "{e}");
        assert!(IntensityImage::new(Mapping::EqualArea, None, 3, 2, grey(2, 2)).is_err());
    }
}
