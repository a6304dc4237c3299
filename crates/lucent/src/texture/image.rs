//! Image textures: linear RGB texels looked up by texture coordinates, or by direction for a
//! lat-long environment.

use crate::Rgb;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// An image in linear RGB, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTexture {
    width: u32,
    height: u32,
    texels: Vec<Rgb>,
}

impl ImageTexture {
    /// The image of `texels` (row by row from the top), or `None` when the count does not
    /// match the size or the size is zero.
    pub fn new(width: u32, height: u32, texels: Vec<Rgb>) -> Option<Self> {
        let n = width as usize * height as usize;
        (n > 0 && texels.len() == n).then_some(Self {
            width,
            height,
            texels,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The image with every texel multiplied by `scale`.
    pub fn scaled(mut self, scale: Rgb) -> Self {
        for t in &mut self.texels {
            *t *= scale;
        }
        self
    }

    /// The mean of every texel.
    pub fn mean(&self) -> Rgb {
        let sum = self.texels.iter().fold(Rgb::BLACK, |a, &t| a + t);
        sum / self.texels.len() as f32
    }

    /// The mean over all directions of the image as a lat-long environment: rows weighted by
    /// the solid angle they cover (`sin θ`), so the poles count as little as they should.
    pub fn latlong_mean(&self) -> Rgb {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut sum = Rgb::BLACK;
        let mut weights = 0.0;
        for y in 0..h {
            let theta = std::f32::consts::PI * (y as f32 + 0.5) / h as f32;
            let weight = theta.sin();
            let row = self.texels[y * w..(y + 1) * w]
                .iter()
                .fold(Rgb::BLACK, |a, &t| a + t);
            sum += row * weight;
            weights += weight * w as f32;
        }
        if weights > 0.0 {
            sum / weights
        } else {
            Rgb::BLACK
        }
    }

    /// The texel at `(x, y)`, repeating sideways, and up and down unless `clamp_rows`.
    fn texel(&self, x: i64, y: i64, clamp_rows: bool) -> Rgb {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = if clamp_rows {
            y.clamp(0, i64::from(self.height) - 1) as usize
        } else {
            y.rem_euclid(i64::from(self.height)) as usize
        };
        self.texels[y * self.width as usize + x]
    }

    /// Bilinear lookup at `(u, v)`: `(0, 0)` is the top-left corner of the image, `(1, 1)` the
    /// bottom-right; the image repeats outside.
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        self.bilinear(uv, false)
    }

    fn bilinear(&self, uv: Vec2, clamp_rows: bool) -> Rgb {
        if !uv.is_finite() {
            return Rgb::BLACK;
        }
        // Texel centres sit at half-integers.
        let x = f64::from(uv.x) * f64::from(self.width) - 0.5;
        let y = f64::from(uv.y) * f64::from(self.height) - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let t = |x, y| self.texel(x, y, clamp_rows);
        let top = t(x0, y0) * (1.0 - fx) + t(x0 + 1, y0) * fx;
        let bottom = t(x0, y0 + 1) * (1.0 - fx) + t(x0 + 1, y0 + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The lat-long (equirectangular) lookup along unit direction `d`: +y is the top row, the
    /// centre column looks along −z, u grows towards +x.
    pub fn lookup_direction(&self, d: Vec3) -> Rgb {
        // Sideways the image wraps around; the poles do not meet.
        self.bilinear(latlong_uv(d), true)
    }
}

/// Texture coordinates of unit direction `d` in a lat-long image (see
/// [`ImageTexture::lookup_direction`]).
pub fn latlong_uv(d: Vec3) -> Vec2 {
    let u = 0.5 + d.x.atan2(-d.z) / (2.0 * PI);
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_by_two() -> ImageTexture {
        let t = vec![
            Rgb::gray(0.0),
            Rgb::gray(1.0),
            Rgb::gray(2.0),
            Rgb::gray(3.0),
        ];
        ImageTexture::new(2, 2, t).unwrap()
    }

    #[test]
    fn texel_centres_give_texels_and_between_blends() {
        let img = two_by_two();
        assert_eq!(img.lookup(Vec2::new(0.25, 0.25)), Rgb::gray(0.0));
        assert_eq!(img.lookup(Vec2::new(0.75, 0.75)), Rgb::gray(3.0));
        assert_eq!(img.lookup(Vec2::new(0.5, 0.25)), Rgb::gray(0.5));
        assert_eq!(img.lookup(Vec2::new(0.5, 0.5)), Rgb::gray(1.5));
        // Repeats: one period over is the same.
        assert_eq!(img.lookup(Vec2::new(1.25, -0.75)), Rgb::gray(0.0));
        assert_eq!(img.mean(), Rgb::gray(1.5));
        // As an environment, a bright band at a pole counts for little: of a 1 × 10 map lit
        // only in its top row, the solid angle share is sin(π/20) / Σ sin(π(k+0.5)/10) ≈ 0.0245.
        let mut texels = vec![Rgb::BLACK; 10];
        texels[0] = Rgb::WHITE;
        let polar = ImageTexture::new(1, 10, texels).unwrap();
        assert!(
            (polar.latlong_mean().r - 0.0245).abs() < 1e-3,
            "{:?}",
            polar.latlong_mean()
        );
        assert!((polar.mean().r - 0.1).abs() < 1e-6);
        assert!(ImageTexture::new(2, 2, vec![Rgb::BLACK]).is_none());
    }

    #[test]
    fn latlong_directions() {
        assert_eq!(latlong_uv(Vec3::new(0.0, 0.0, -1.0)), Vec2::new(0.5, 0.5));
        assert!((latlong_uv(Vec3::X) - Vec2::new(0.75, 0.5)).length() < 1e-6);
        assert_eq!(latlong_uv(Vec3::Y).y, 0.0);
        assert_eq!(latlong_uv(-Vec3::Y).y, 1.0);
    }
}
