//! Image textures: linear RGB texels (and an optional alpha channel) looked up by texture
//! coordinates — nearest, bilinear, trilinear over a MIP pyramid by the footprint of the
//! lookup, or anisotropic (several trilinear lookups along it) — or by direction for a
//! lat-long environment.

use crate::Rgb;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::OnceLock;

/// What happens outside `[0, 1]` along one texture axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The image tiles the plane, every other copy mirrored (glTF's `MIRRORED_REPEAT`).
    Mirror,
    /// The edge texels extend outwards (glTF's `CLAMP_TO_EDGE`, Mitsuba's `clamp`).
    Clamp,
}

/// How texels are interpolated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel the point falls in.
    Nearest,
    /// The four nearest texels, weighted by distance.
    Bilinear,
    /// Bilinear lookups in the two MIP levels whose texels are nearest the lookup's footprint,
    /// blended: distant textures neither alias nor shimmer (but blur where the footprint is
    /// long and thin, as on a plane seen at a grazing angle).
    Trilinear,
    /// Up to [`MAX_PROBES`] trilinear lookups spread along the footprint's long axis, in the
    /// level its short axis picks (what GPUs' anisotropic filtering does; a cheap stand-in for
    /// EWA): no aliasing, and grazing textures stay sharp across the view.
    #[default]
    Anisotropic,
}

/// The most trilinear lookups of one [`Filter::Anisotropic`] lookup: footprints longer than
/// this many times their width are blurred along their width.
pub const MAX_PROBES: usize = 8;

/// One texel: colour and alpha.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texel {
    /// Linear RGB.
    pub rgb: Rgb,
    /// Coverage in `[0, 1]`; 1 for images without alpha.
    pub alpha: f32,
}

impl Texel {
    fn scale(self, w: f32) -> Texel {
        Texel {
            rgb: self.rgb * w,
            alpha: self.alpha * w,
        }
    }

    fn add(self, o: Texel) -> Texel {
        Texel {
            rgb: self.rgb + o.rgb,
            alpha: self.alpha + o.alpha,
        }
    }
}

/// One level of the pyramid.
#[derive(Clone, Debug, PartialEq)]
struct Level {
    width: u32,
    height: u32,
    texels: Vec<Rgb>,
    /// Empty when the image has no alpha.
    alpha: Vec<f32>,
}

impl Level {
    fn texel(&self, x: usize, y: usize) -> Texel {
        let i = y * self.width as usize + x;
        Texel {
            rgb: self.texels[i],
            alpha: self.alpha.get(i).copied().unwrap_or(1.0),
        }
    }

    /// The next level down: each texel the mean of (up to) 2 × 2 texels of this one.
    fn halved(&self) -> Level {
        let (w, h) = (
            self.width.div_ceil(2).max(1),
            self.height.div_ceil(2).max(1),
        );
        let (sw, sh) = (self.width as usize, self.height as usize);
        let mut texels = Vec::with_capacity(w as usize * h as usize);
        let mut alpha = Vec::with_capacity(if self.alpha.is_empty() {
            0
        } else {
            texels.capacity()
        });
        for y in 0..h as usize {
            for x in 0..w as usize {
                let mut sum = Texel {
                    rgb: Rgb::BLACK,
                    alpha: 0.0,
                };
                let mut n = 0.0;
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (sx, sy) = (2 * x + dx, 2 * y + dy);
                    if sx < sw && sy < sh {
                        sum = sum.add(self.texel(sx, sy));
                        n += 1.0;
                    }
                }
                let mean = sum.scale(1.0 / n);
                texels.push(mean.rgb);
                if !self.alpha.is_empty() {
                    alpha.push(mean.alpha);
                }
            }
        }
        Level {
            width: w,
            height: h,
            texels,
            alpha,
        }
    }
}

/// An image in linear RGB, row 0 at the top, with its MIP pyramid built on first need.
#[derive(Debug)]
pub struct ImageTexture {
    base: Level,
    /// Levels 1, 2, … down to 1 × 1.
    pyramid: OnceLock<Vec<Level>>,
}

impl Clone for ImageTexture {
    fn clone(&self) -> Self {
        Self {
            base: self.base.clone(),
            pyramid: OnceLock::new(),
        }
    }
}

impl PartialEq for ImageTexture {
    fn eq(&self, other: &Self) -> bool {
        self.base == other.base
    }
}

/// `c` mapped into `[0, n)` by the wrap mode.
fn wrap_index(c: i64, n: u32, wrap: Wrap) -> usize {
    let n = i64::from(n);
    // Inside the image every mode keeps the index (and a lookup is spared two divisions).
    if (0..n).contains(&c) {
        return c as usize;
    }
    let i = match wrap {
        Wrap::Repeat => c.rem_euclid(n),
        Wrap::Clamp => c.clamp(0, n - 1),
        Wrap::Mirror => {
            let period = c.rem_euclid(2 * n);
            if period < n {
                period
            } else {
                2 * n - 1 - period
            }
        }
    };
    i as usize
}

impl ImageTexture {
    /// The image of `texels` (row by row from the top), or `None` when the count does not
    /// match the size or the size is zero.
    pub fn new(width: u32, height: u32, texels: Vec<Rgb>) -> Option<Self> {
        let n = width as usize * height as usize;
        (n > 0 && texels.len() == n).then_some(Self {
            base: Level {
                width,
                height,
                texels,
                alpha: Vec::new(),
            },
            pyramid: OnceLock::new(),
        })
    }

    /// The image with an alpha channel (one value per texel, in `[0, 1]`), or `None` when the
    /// count does not match.
    pub fn with_alpha(mut self, alpha: Vec<f32>) -> Option<Self> {
        (alpha.len() == self.base.texels.len()).then(|| {
            self.base.alpha = alpha;
            self.pyramid = OnceLock::new();
            self
        })
    }

    /// Whether the image has an alpha channel.
    pub fn has_alpha(&self) -> bool {
        !self.base.alpha.is_empty()
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.base.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.base.height
    }

    /// The texels, row by row from the top.
    pub fn texels(&self) -> &[Rgb] {
        &self.base.texels
    }

    /// The image with every texel multiplied by `scale`.
    pub fn scaled(mut self, scale: Rgb) -> Self {
        for t in &mut self.base.texels {
            *t *= scale;
        }
        self.pyramid = OnceLock::new();
        self
    }

    /// The mean of every texel.
    pub fn mean(&self) -> Rgb {
        let sum = self.base.texels.iter().fold(Rgb::BLACK, |a, &t| a + t);
        sum / self.base.texels.len() as f32
    }

    /// The mean of the alpha channel (1 without one).
    pub fn mean_alpha(&self) -> f32 {
        if self.base.alpha.is_empty() {
            return 1.0;
        }
        self.base.alpha.iter().sum::<f32>() / self.base.alpha.len() as f32
    }

    /// The mean over all directions of the image as a lat-long environment: rows weighted by
    /// the solid angle they cover (`sin θ`), so the poles count as little as they should.
    pub fn latlong_mean(&self) -> Rgb {
        let (w, h) = (self.width() as usize, self.height() as usize);
        let mut sum = Rgb::BLACK;
        let mut weights = 0.0;
        for y in 0..h {
            let theta = std::f32::consts::PI * (y as f32 + 0.5) / h as f32;
            let weight = theta.sin();
            let row = self.base.texels[y * w..(y + 1) * w]
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

    /// The number of MIP levels, the full image included.
    pub fn levels(&self) -> usize {
        1 + self.pyramid().len()
    }

    fn pyramid(&self) -> &[Level] {
        self.pyramid.get_or_init(|| {
            let mut levels: Vec<Level> = Vec::new();
            loop {
                let last = levels.last().unwrap_or(&self.base);
                if last.width == 1 && last.height == 1 {
                    break levels;
                }
                let next = last.halved();
                levels.push(next);
            }
        })
    }

    fn level(&self, i: usize) -> &Level {
        if i == 0 {
            &self.base
        } else {
            &self.pyramid()[i - 1]
        }
    }

    /// Bilinear lookup at `(u, v)`: `(0, 0)` is the top-left corner of the image, `(1, 1)` the
    /// bottom-right; the image repeats outside.
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        bilinear(&self.base, uv, [Wrap::Repeat; 2]).rgb
    }

    /// The filtered texel at `uv` (`(0, 0)` the top-left corner) for a lookup whose footprint
    /// spans `duvdx` and `duvdy` (the change of `uv` from one pixel to the next; zero for a
    /// point), with `wrap` along u and v.
    pub fn sample(&self, uv: Vec2, duv: [Vec2; 2], wrap: [Wrap; 2], filter: Filter) -> Texel {
        if !uv.is_finite() {
            return Texel {
                rgb: Rgb::BLACK,
                alpha: 0.0,
            };
        }
        match filter {
            Filter::Nearest => nearest(&self.base, uv, wrap),
            Filter::Bilinear => bilinear(&self.base, uv, wrap),
            Filter::Trilinear => {
                // The footprint's width in texels of the full image (pbrt's convention: twice
                // the largest differential).
                let size = self.size();
                let width = 2.0
                    * (duv[0] * size)
                        .abs()
                        .max_element()
                        .max((duv[1] * size).abs().max_element());
                self.trilinear(uv, width, wrap)
            }
            Filter::Anisotropic => {
                let size = self.size();
                let (a, b) = (duv[0] * size, duv[1] * size);
                let (major, minor) = if a.length_squared() >= b.length_squared() {
                    (duv[0], b.length())
                } else {
                    (duv[1], a.length())
                };
                let long = 2.0 * (major * size).length();
                if !long.is_finite() || long <= 1.0 {
                    return self.trilinear(uv, long, wrap);
                }
                // Probes cover the long axis (±major) in steps no longer than the short one.
                let n = (long / (2.0 * minor).max(1e-6))
                    .ceil()
                    .clamp(1.0, MAX_PROBES as f32);
                let width = (long / n).max(2.0 * minor);
                let count = n as usize;
                let mut sum = Texel {
                    rgb: Rgb::BLACK,
                    alpha: 0.0,
                };
                for i in 0..count {
                    let t = (2.0 * i as f32 + 1.0) / n - 1.0;
                    sum = sum.add(self.trilinear(uv + major * t, width, wrap));
                }
                sum.scale(1.0 / n)
            }
        }
    }

    /// The image's size in texels, as a vector.
    fn size(&self) -> Vec2 {
        Vec2::new(self.width() as f32, self.height() as f32)
    }

    /// The lookup at `uv` blended from the two levels around the one where a footprint `width`
    /// texels (of the full image) wide is one texel wide.
    fn trilinear(&self, uv: Vec2, width: f32, wrap: [Wrap; 2]) -> Texel {
        if width.is_nan() || width <= 1.0 {
            return bilinear(&self.base, uv, wrap);
        }
        let level = width.log2().min((self.levels() - 1) as f32);
        let lo = level.floor() as usize;
        let t = level - lo as f32;
        let a = bilinear(self.level(lo), uv, wrap);
        if t <= 0.0 || lo + 1 >= self.levels() {
            return a;
        }
        let b = bilinear(self.level(lo + 1), uv, wrap);
        a.scale(1.0 - t).add(b.scale(t))
    }

    /// The lat-long (equirectangular) lookup along unit direction `d`: +y is the top row, the
    /// centre column looks along −z, u grows towards +x.
    pub fn lookup_direction(&self, d: Vec3) -> Rgb {
        // Sideways the image wraps around; the poles do not meet.
        bilinear(&self.base, latlong_uv(d), [Wrap::Repeat, Wrap::Clamp]).rgb
    }

    /// [`ImageTexture::lookup_direction`] with the texels placed as `texels` says.
    pub fn lookup_direction_with(&self, d: Vec3, texels: LatLongTexels) -> Rgb {
        match texels {
            LatLongTexels::Cells => self.lookup_direction(d),
            LatLongTexels::Poles => {
                // Row y at v = y/(h − 1): in cell coordinates, where row centres sit at
                // (y + ½)/h, that is (v·(h − 1) + ½)/h.
                let uv = latlong_uv(d);
                let h = self.height() as f32;
                let cells = Vec2::new(uv.x, (uv.y * (h - 1.0) + 0.5) / h);
                bilinear(&self.base, cells, [Wrap::Repeat, Wrap::Clamp]).rgb
            }
        }
    }
}

/// The texel holding `uv`.
fn nearest(level: &Level, uv: Vec2, wrap: [Wrap; 2]) -> Texel {
    let x = (f64::from(uv.x) * f64::from(level.width)).floor() as i64;
    let y = (f64::from(uv.y) * f64::from(level.height)).floor() as i64;
    level.texel(
        wrap_index(x, level.width, wrap[0]),
        wrap_index(y, level.height, wrap[1]),
    )
}

/// The four texels around `uv`, weighted by distance; texel centres sit at half-integers.
fn bilinear(level: &Level, uv: Vec2, wrap: [Wrap; 2]) -> Texel {
    if !uv.is_finite() {
        return Texel {
            rgb: Rgb::BLACK,
            alpha: 0.0,
        };
    }
    let x = f64::from(uv.x) * f64::from(level.width) - 0.5;
    let y = f64::from(uv.y) * f64::from(level.height) - 0.5;
    // Beyond 2⁵² texels a coordinate has no fraction left, and the texel after the last
    // representable one would overflow: keep far coordinates where wrapping still works.
    const FAR: f64 = (1u64 << 52) as f64;
    let (x, y) = (x.clamp(-FAR, FAR), y.clamp(-FAR, FAR));
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let t = |x: i64, y: i64| {
        level.texel(
            wrap_index(x, level.width, wrap[0]),
            wrap_index(y, level.height, wrap[1]),
        )
    };
    let top = t(x0, y0).scale(1.0 - fx).add(t(x0 + 1, y0).scale(fx));
    let bottom = t(x0, y0 + 1)
        .scale(1.0 - fx)
        .add(t(x0 + 1, y0 + 1).scale(fx));
    top.scale(1.0 - fy).add(bottom.scale(fy))
}

/// Where a lat-long image's texels lie on the sphere.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LatLongTexels {
    /// Each texel is the centre of its cell of a `w × h` grid over `u` and `v` (lucent's default):
    /// texel `(x, y)` at `u = (x + ½)/w`, `v = (y + ½)/h`.
    #[default]
    Cells,
    /// The columns as in `Cells`, the rows from pole to pole, as Mitsuba 3's `envmap` has them:
    /// texel `(x, y)` at `u = (x + ½)/w`, `v = y/(h − 1)`, the first and last rows on the poles.
    Poles,
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
    fn with_rows_on_the_poles_the_first_and_last_rows_are_the_poles() {
        use crate::light::environment::latlong_direction;
        // Texel (x, y) = 10·y + x of a 4 × 3 image.
        let t: Vec<Rgb> = (0..12)
            .map(|i| Rgb::gray((10 * (i / 4) + i % 4) as f32))
            .collect();
        let img = ImageTexture::new(4, 3, t).unwrap();
        let at = |u: f32, v: f32| {
            let (d, _) = latlong_direction(Vec2::new(u, v));
            img.lookup_direction_with(d, LatLongTexels::Poles).r
        };
        let close = |a: f32, b: f32| assert!((a - b).abs() < 1e-3, "{a} vs {b}");
        // Row 1 on the equator (v = 1/2), column x at its cell's centre.
        for x in 0..4 {
            close(at((x as f32 + 0.5) / 4.0, 0.5), 10.0 + x as f32);
        }
        // Rows 0 and 2 on the poles, approached along column 1.
        close(at(0.375, 1e-5), 1.0);
        close(at(0.375, 1.0 - 1e-5), 21.0);
        // At the seam the last column and the first blend.
        close(at(0.0, 0.5), 0.5 * (13.0 + 10.0));
        // Halfway between rows, their mean.
        close(at(0.625, 0.75), 0.5 * (12.0 + 22.0));
        // The default centres the rows in their cells instead: v = 1/2 is row 1 there too,
        // but v = 1/6 is row 0's centre, where the poles' rows blend it with row 1.
        let (d, _) = latlong_direction(Vec2::new(0.375, 1.0 / 6.0));
        close(img.lookup_direction_with(d, LatLongTexels::Cells).r, 1.0);
        close(at(0.375, 1.0 / 6.0), 1.0 + 10.0 / 3.0);
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
    fn wrap_modes_repeat_mirror_and_clamp() {
        let img = two_by_two();
        let at = |u: f32, wrap| {
            img.sample(
                Vec2::new(u, 0.25),
                [Vec2::ZERO; 2],
                [wrap, Wrap::Repeat],
                Filter::Nearest,
            )
            .rgb
            .r
        };
        // Texels along the top row: 0, 1. One image to the right:
        assert_eq!(at(1.25, Wrap::Repeat), 0.0);
        assert_eq!(at(1.25, Wrap::Mirror), 1.0);
        assert_eq!(at(1.75, Wrap::Mirror), 0.0);
        assert_eq!(at(1.25, Wrap::Clamp), 1.0);
        assert_eq!(at(-3.0, Wrap::Clamp), 0.0);
        assert_eq!(at(-0.25, Wrap::Mirror), 0.0);
    }

    #[test]
    fn the_pyramid_averages_down_to_one_texel() {
        // A 4 × 2 image with alpha: levels 4×2, 2×1, 1×1.
        let texels: Vec<Rgb> = (0..8).map(|i| Rgb::gray(i as f32)).collect();
        let img = ImageTexture::new(4, 2, texels)
            .unwrap()
            .with_alpha(vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0])
            .unwrap();
        assert_eq!(img.levels(), 3);
        let top = img.level(2).texel(0, 0);
        assert!((top.rgb.r - 3.5).abs() < 1e-6 && (top.alpha - 0.5).abs() < 1e-6);
        // A footprint of the whole image reads the top level; a point reads the base.
        let whole = img.sample(
            Vec2::new(0.3, 0.6),
            [Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)],
            [Wrap::Repeat; 2],
            Filter::Trilinear,
        );
        assert!((whole.rgb.r - 3.5).abs() < 1e-5, "{whole:?}");
        let point = img.sample(
            Vec2::new(0.125, 0.25),
            [Vec2::ZERO; 2],
            [Wrap::Repeat; 2],
            Filter::Trilinear,
        );
        assert_eq!(point.rgb.r, 0.0);
        assert_eq!(point.alpha, 1.0);
        // Between levels the two are blended.
        let half = img.sample(
            Vec2::new(0.125, 0.25),
            [Vec2::new(0.5 * 2f32.powf(0.5) / 4.0, 0.0), Vec2::ZERO],
            [Wrap::Repeat; 2],
            Filter::Trilinear,
        );
        assert!(half.rgb.r > 0.0 && half.rgb.r < 3.5, "{half:?}");
    }

    #[test]
    fn latlong_directions() {
        assert_eq!(latlong_uv(Vec3::new(0.0, 0.0, -1.0)), Vec2::new(0.5, 0.5));
        assert!((latlong_uv(Vec3::X) - Vec2::new(0.75, 0.5)).length() < 1e-6);
        assert_eq!(latlong_uv(Vec3::Y).y, 0.0);
        assert_eq!(latlong_uv(-Vec3::Y).y, 1.0);
    }
}
