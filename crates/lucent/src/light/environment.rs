//! The environment: light arriving from infinitely far away in every direction, a constant
//! colour or a lat-long image ([`crate::texture::image::latlong_uv`]'s mapping).
//!
//! Under the path tracer every ray that escapes the scene sees it, and next-event estimation
//! samples it: uniformly over the sphere for a constant colour, and for an image in proportion
//! to each texel's luminance times the solid angle it covers (`sin θ` of its row), so that a
//! small bright sun is found by nearly every shadow ray.

use super::area::luminance;
use crate::Rgb;
use crate::sampling::distribution::Distribution2D;
use crate::sampling::warp::square_to_uniform_sphere;
use crate::texture::ImageTexture;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// How directions are sampled.
#[derive(Clone, Debug)]
enum Directions {
    /// Uniformly over the sphere.
    Uniform,
    /// By the image's texels, luminance × sin θ.
    Image(Distribution2D),
}

/// The environment seen by escaping rays, prepared for sampling.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    directions: Directions,
    /// Mean radiance over directions (for the light's power).
    mean: f32,
    /// The rotation taking a world direction to the image's frame.
    to_image: glam::Mat3,
}

impl EnvironmentLight {
    /// The environment of a constant radiance `c`, or `None` when it is black.
    pub fn constant(c: Rgb) -> Option<Self> {
        (!c.is_black() && c.is_finite()).then_some(Self {
            directions: Directions::Uniform,
            mean: luminance(c),
            to_image: glam::Mat3::IDENTITY,
        })
    }

    /// The environment of a lat-long image, or `None` when it is black everywhere.
    pub fn image(image: &ImageTexture) -> Option<Self> {
        let (w, h) = (image.width() as usize, image.height() as usize);
        let lum: Vec<f32> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let uv = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
                luminance(image.lookup(uv)).max(0.0)
            })
            .collect();
        // Radiance is interpolated between texel centres, so a black texel beside a bright one
        // still sends light: each cell is weighted by the brightest texel it blends (its 3 × 3
        // neighbourhood, wrapping sideways), so no direction that shows light has density 0 —
        // the photon mapper samples the environment with no second technique to make up for it.
        let mut weights = Vec::with_capacity(w * h);
        for y in 0..h {
            let sin_theta = (PI * (y as f32 + 0.5) / h as f32).sin();
            for x in 0..w {
                let mut m = 0.0f32;
                for dy in -1i64..=1 {
                    let yy = (y as i64 + dy).clamp(0, h as i64 - 1) as usize;
                    for dx in -1i64..=1 {
                        let xx = (x as i64 + dx).rem_euclid(w as i64) as usize;
                        m = m.max(lum[yy * w + xx]);
                    }
                }
                weights.push(m * sin_theta);
            }
        }
        let dist = Distribution2D::new(&weights, w, h)?;
        Some(Self {
            directions: Directions::Image(dist),
            mean: luminance(image.latlong_mean()),
            to_image: glam::Mat3::IDENTITY,
        })
    }

    /// This environment turned: `to_image` (a rotation) takes a world direction to the
    /// image's frame.
    pub fn rotated(self, to_image: glam::Mat3) -> Self {
        Self { to_image, ..self }
    }

    /// A direction drawn from `u`, with its solid-angle density.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32)> {
        match &self.directions {
            Directions::Uniform => Some((square_to_uniform_sphere(u), 1.0 / (4.0 * PI))),
            Directions::Image(dist) => {
                let (uv, pdf_uv) = dist.sample(u);
                let (dir, sin_theta) = latlong_direction(uv);
                // A rotation's inverse is its transpose.
                let dir = self.to_image.transpose() * dir;
                (pdf_uv > 0.0 && sin_theta > 0.0)
                    .then(|| (dir, pdf_uv / (2.0 * PI * PI * sin_theta)))
            }
        }
    }

    /// The solid-angle density of `sample` drawing unit direction `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match &self.directions {
            Directions::Uniform => 1.0 / (4.0 * PI),
            Directions::Image(dist) => {
                let dir = self.to_image * dir;
                let uv = crate::texture::image::latlong_uv(dir);
                let sin_theta = (1.0 - dir.y * dir.y).max(0.0).sqrt();
                if sin_theta > 0.0 {
                    dist.pdf(uv) / (2.0 * PI * PI * sin_theta)
                } else {
                    0.0
                }
            }
        }
    }

    /// Power through a scene of bounding radius `radius`: a disc of that radius lit from one
    /// side by the mean radiance receives `π·L` per unit area.
    pub fn power(&self, radius: f32) -> f32 {
        PI * radius * radius * PI * self.mean
    }
}

/// The unit direction at lat-long coordinates `uv` (the inverse of
/// [`crate::texture::image::latlong_uv`]), and `sin θ` there.
pub fn latlong_direction(uv: Vec2) -> (Vec3, f32) {
    let theta = uv.y * PI;
    let phi = (uv.x - 0.5) * 2.0 * PI;
    let (sin_theta, cos_theta) = theta.sin_cos();
    let (sin_phi, cos_phi) = phi.sin_cos();
    (
        Vec3::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi),
        sin_theta,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::image::latlong_uv;

    #[test]
    fn latlong_direction_inverts_latlong_uv() {
        for &(u, v) in &[(0.5, 0.5), (0.1, 0.3), (0.9, 0.8), (0.25, 0.01)] {
            let (d, _) = latlong_direction(Vec2::new(u, v));
            assert!((d.length() - 1.0).abs() < 1e-5);
            let back = latlong_uv(d);
            assert!(
                (back - Vec2::new(u, v)).length() < 1e-4,
                "{u},{v} -> {back}"
            );
        }
    }

    #[test]
    fn an_image_is_sampled_where_it_is_bright() {
        // An 8 × 4 black map with one bright texel: every sample lands in it or in the cells
        // its light is blended into (its neighbours), and the pdf of the sampled direction
        // agrees with pdf().
        let mut texels = vec![Rgb::BLACK; 32];
        texels[8 + 5] = Rgb::gray(10.0);
        let image = ImageTexture::new(8, 4, texels).unwrap();
        let env = EnvironmentLight::image(&image).unwrap();
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.06, (k / 8) as f32 / 8.0 + 0.06);
            let (d, pdf) = env.sample(u).unwrap();
            let uv = latlong_uv(d);
            let (cx, cy) = ((uv.x * 8.0) as i32, (uv.y * 4.0) as i32);
            assert!((cx - 5).abs() <= 1 && (cy - 1).abs() <= 1, "{uv}");
            assert!((env.pdf(d) - pdf).abs() <= 1e-3 * pdf);
        }
        // Where the image is black beyond the blend, nothing is sampled.
        let far = latlong_direction(Vec2::new(1.5 / 8.0, 3.5 / 4.0)).0;
        assert_eq!(env.pdf(far), 0.0);
        assert!(
            EnvironmentLight::image(&ImageTexture::new(1, 1, vec![Rgb::BLACK]).unwrap()).is_none()
        );
    }

    #[test]
    fn the_pdf_integrates_to_one_over_the_sphere() {
        let texels: Vec<Rgb> = (0..64).map(|i| Rgb::gray((i % 7) as f32 + 0.5)).collect();
        let env = EnvironmentLight::image(&ImageTexture::new(16, 4, texels).unwrap()).unwrap();
        let n = 200;
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let d = square_to_uniform_sphere(u);
                sum += f64::from(env.pdf(d)) * 4.0 * std::f64::consts::PI / f64::from(n * n);
            }
        }
        assert!((sum - 1.0).abs() < 0.02, "{sum}");
    }
}
