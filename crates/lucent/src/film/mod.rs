//! The film: per pixel, the running sum of radiance, the sum of sample weights, and the number
//! of samples taken, in linear RGB.
//!
//! A pixel's samples are added in the order of their indices, so a render stopped and resumed,
//! or split over machines by pixels, gives the same bits as one done at once. Films of disjoint
//! pixels merge by adding (each pixel's values come from one film, plus zeros); tone mapping and
//! encoding happen only on output ([`tonemap`]).

pub mod filter;
pub mod splat;
pub mod tonemap;

use crate::Rgb;
use lucent_accel::memory::zeroed_vec;

/// Linear radiance sums, weights and sample counts for a `width × height` image, row 0 at the
/// top.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    sums: Vec<[f32; 3]>,
    weights: Vec<f32>,
    samples: Vec<u32>,
}

/// A film's raw channels, for files (partial films, checkpoints).
#[derive(Clone, Debug, PartialEq)]
pub struct FilmData {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Radiance sums, row by row from the top.
    pub sums: Vec<[f32; 3]>,
    /// Weight sums.
    pub weights: Vec<f32>,
    /// Samples taken (NaN or infinite samples count, with no weight).
    pub samples: Vec<u32>,
}

/// How a film's values become an image's bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Display {
    /// Linear light, encoded as sRGB (lucent's own).
    #[default]
    Srgb,
    /// Values in a space of this gamma (POV-Ray's `assumed_gamma`): `v^gamma` is linear light,
    /// encoded as sRGB.
    Gamma(f32),
    /// Values written as they are, without gamma correction (POV-Ray's scenes older than 3.7
    /// without `assumed_gamma`).
    Raw,
}

impl Display {
    /// The linear light of value `v` (an EXR's value).
    pub fn linear(self, v: f32) -> f32 {
        match self {
            Display::Srgb => v,
            Display::Gamma(g) => v.max(0.0).powf(g),
            Display::Raw => tonemap::srgb_to_linear(v),
        }
    }

    /// The byte of value `v` (clamped to [0, 1]; NaN as 0).
    pub fn byte(self, v: f32) -> u8 {
        match self {
            Display::Srgb => tonemap::srgb8(v),
            Display::Gamma(g) => tonemap::srgb8(if v > 0.0 { v.powf(g) } else { 0.0 }),
            Display::Raw => {
                let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
                (v * 255.0 + 0.5) as u8
            }
        }
    }
}

impl Film {
    /// An empty film (no samples).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            sums: zeroed_vec(n),
            weights: zeroed_vec(n),
            samples: zeroed_vec(n),
        }
    }

    /// The film held by `data`, or `None` when its arrays do not match its size.
    pub fn from_data(data: FilmData) -> Option<Self> {
        let n = data.width as usize * data.height as usize;
        if data.sums.len() != n || data.weights.len() != n || data.samples.len() != n {
            return None;
        }
        Some(Self {
            width: data.width,
            height: data.height,
            sums: data.sums,
            weights: data.weights,
            samples: data.samples,
        })
    }

    /// The raw channels.
    pub fn to_data(&self) -> FilmData {
        FilmData {
            width: self.width,
            height: self.height,
            sums: self.sums.clone(),
            weights: self.weights.clone(),
            samples: self.samples.clone(),
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Adds the next sample of pixel `(x, y)`: its radiance with weight `weight`, or `None` for a
    /// sample that came out NaN or infinite (counted, not added).
    pub fn add_sample(&mut self, x: u32, y: u32, value: Option<Rgb>, weight: f32) {
        let i = self.index(x, y);
        if let Some(v) = value {
            add_to(&mut self.sums[i], v * weight);
            self.weights[i] += weight;
        }
        self.samples[i] += 1;
    }

    /// Adds `value·weight` and `weight` at pixel `(x, y)` without counting a sample there: a
    /// sample's share in a pixel its filter reaches ([`splat`]).
    pub fn add_splat(&mut self, x: u32, y: u32, value: Rgb, weight: f32) {
        let i = self.index(x, y);
        add_to(&mut self.sums[i], value * weight);
        self.weights[i] += weight;
    }

    /// Counts one more sample taken in pixel `(x, y)` (its value splatted apart).
    pub fn count_sample(&mut self, x: u32, y: u32) {
        self.count_samples(x, y, 1);
    }

    /// Counts `n` more samples taken in pixel `(x, y)` (an estimate made of them, added apart).
    pub fn count_samples(&mut self, x: u32, y: u32, n: u32) {
        let i = self.index(x, y);
        self.samples[i] += n;
    }

    /// Adds a radiance sum, a weight sum and a sample count at pixel `(x, y)`, which may be
    /// outside the film: there it is dropped (a tile's splats reaching past the image).
    pub fn add_totals(&mut self, (x, y): (i64, i64), sum: Rgb, weight: f32, samples: u32) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let i = self.index(x as u32, y as u32);
        add_to(&mut self.sums[i], sum);
        self.weights[i] += weight;
        self.samples[i] += samples;
    }

    /// Samples taken at pixel `(x, y)` so far.
    pub fn samples(&self, x: u32, y: u32) -> u32 {
        self.samples[self.index(x, y)]
    }

    /// Fewest and most samples over all pixels (`(0, 0)` for an empty image).
    pub fn sample_range(&self) -> (u32, u32) {
        let min = self.samples.iter().copied().min().unwrap_or(0);
        (min, self.samples.iter().copied().max().unwrap_or(0))
    }

    /// The pixel's estimate: the weighted mean of its samples, black when it has none.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb {
        let i = self.index(x, y);
        let w = self.weights[i];
        if w > 0.0 {
            // The last guard: finite samples near f32::MAX can still sum past it, and an image
            // never holds NaN or ∞ (see `overflowed_pixels`).
            (Rgb::from(self.sums[i]) / w).map(|c| {
                if c.is_nan() {
                    0.0
                } else {
                    c.clamp(-f32::MAX, f32::MAX)
                }
            })
        } else {
            Rgb::BLACK
        }
    }

    /// Pixels whose sums overflowed single precision (NaN or ∞): [`Film::pixel`] gives them
    /// clamped to ±`f32::MAX` (NaN as 0). Only inputs near `f32::MAX` do this.
    pub fn overflowed_pixels(&self) -> usize {
        use rayon::prelude::*;
        self.sums
            .par_iter()
            .zip(&self.weights)
            .filter(|(s, w)| !(s.iter().all(|c| c.is_finite()) && w.is_finite()))
            .count()
    }

    /// The sum of weights at pixel `(x, y)` (the sample count under a box filter).
    pub fn weight(&self, x: u32, y: u32) -> f32 {
        self.weights[self.index(x, y)]
    }

    /// Every pixel's estimate, row by row from the top, as linear RGB triples.
    pub fn to_linear_rgb(&self) -> Vec<[f32; 3]> {
        use rayon::prelude::*;
        let width = self.width as usize;
        (0..self.sums.len())
            .into_par_iter()
            .map(|i| {
                self.pixel((i % width) as u32, (i / width) as u32)
                    .to_array()
            })
            .collect()
    }

    /// The image in 8-bit sRGB (r, g, b bytes), row by row from the top: [`Film::to_linear_rgb`]
    /// encoded by [`tonemap::srgb8`], made in parallel without the linear image.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.to_8bit(Display::Srgb)
    }

    /// The image in 8-bit bytes as `display` says its values are shown.
    pub fn to_8bit(&self, display: Display) -> Vec<u8> {
        use rayon::prelude::*;
        let width = self.width as usize;
        let mut bytes = zeroed_vec(3 * self.sums.len());
        bytes
            .par_chunks_mut(3 * width.max(1))
            .enumerate()
            .for_each(|(y, row)| {
                for (x, out) in row.chunks_exact_mut(3).enumerate() {
                    let p = self.pixel(x as u32, y as u32).to_array();
                    out.copy_from_slice(&p.map(|v| display.byte(v)));
                }
            });
        bytes
    }

    /// A copy of the region `[x0, x0 + w) × [y0, y0 + h)`.
    ///
    /// # Panics
    /// If the region does not fit inside this film.
    pub fn region(&self, x0: u32, y0: u32, w: u32, h: u32) -> Film {
        assert!(
            x0 + w <= self.width && y0 + h <= self.height,
            "region outside the film"
        );
        let mut part = Film::new(w, h);
        part.copy_rect(self, (x0, y0), (0, 0), (w, h));
        part
    }

    /// Writes `part` over the region whose top-left pixel is `(x0, y0)`.
    ///
    /// # Panics
    /// If the region does not fit inside this film.
    pub fn store_region(&mut self, part: &Film, x0: u32, y0: u32) {
        assert!(
            x0 + part.width <= self.width && y0 + part.height <= self.height,
            "region outside the film"
        );
        self.copy_rect(part, (0, 0), (x0, y0), (part.width, part.height));
    }

    /// Copies the `w × h` pixels of `from` at `(fx, fy)` here, to `(tx, ty)`, row by row.
    fn copy_rect(
        &mut self,
        from: &Film,
        (fx, fy): (u32, u32),
        (tx, ty): (u32, u32),
        (w, h): (u32, u32),
    ) {
        for y in 0..h {
            let (src, dst) = (from.index(fx, fy + y), self.index(tx, ty + y));
            let (src, dst) = (src..src + w as usize, dst..dst + w as usize);
            self.sums[dst.clone()].copy_from_slice(&from.sums[src.clone()]);
            self.weights[dst.clone()].copy_from_slice(&from.weights[src.clone()]);
            self.samples[dst].copy_from_slice(&from.samples[src]);
        }
    }

    /// Adds another film of the same size into this one (sums, weights and sample counts).
    ///
    /// # Panics
    /// If the sizes differ; callers check that their films come from the same render.
    pub fn merge(&mut self, other: &Film) {
        assert_eq!(
            (self.width, self.height),
            (other.width, other.height),
            "film sizes differ"
        );
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            add_to(a, Rgb::from(*b));
        }
        for (a, b) in self.weights.iter_mut().zip(&other.weights) {
            *a += *b;
        }
        for (a, b) in self.samples.iter_mut().zip(&other.samples) {
            *a += *b;
        }
    }
}

/// `sum += v`, channel by channel.
#[inline]
fn add_to(sum: &mut [f32; 3], v: Rgb) {
    *sum = (Rgb::from(*sum) + v).to_array();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_srgb_bytes_encode_the_linear_image() {
        let mut film = Film::new(7, 5);
        for y in 0..5 {
            for x in 0..7 {
                let v = Rgb::new(x as f32 / 6.0, y as f32 / 4.0, 0.3 * (x + y) as f32);
                film.add_sample(x, y, Some(v), 0.5 + x as f32);
            }
        }
        film.add_sample(3, 2, Some(Rgb::new(f32::MAX, 1.0, 2.0)), f32::MAX);
        let bytes = film.to_srgb8();
        let expected: Vec<u8> = film
            .to_linear_rgb()
            .iter()
            .flat_map(|p| p.map(tonemap::srgb8))
            .collect();
        assert_eq!(bytes, expected);
        assert_eq!(bytes.len(), 7 * 5 * 3);
    }

    #[test]
    fn sums_past_single_precision_give_finite_pixels_and_are_counted() {
        let mut f = Film::new(2, 1);
        for _ in 0..4 {
            f.add_sample(0, 0, Some(Rgb::new(3e38, 1.0, 0.0)), 1.0);
            f.add_sample(1, 0, Some(Rgb::gray(0.5)), 1.0);
        }
        assert_eq!(f.pixel(0, 0), Rgb::new(f32::MAX, 1.0, 0.0));
        assert_eq!(f.pixel(1, 0), Rgb::gray(0.5));
        assert_eq!(f.overflowed_pixels(), 1);
    }

    #[test]
    fn a_pixel_is_the_mean_of_its_samples() {
        let mut f = Film::new(2, 1);
        f.add_sample(1, 0, Some(Rgb::gray(1.0)), 1.0);
        f.add_sample(1, 0, Some(Rgb::gray(3.0)), 1.0);
        f.add_sample(1, 0, None, 1.0);
        assert_eq!(f.pixel(1, 0), Rgb::gray(2.0));
        assert_eq!(f.samples(1, 0), 3);
        assert_eq!(f.pixel(0, 0), Rgb::BLACK);
        assert_eq!(f.to_linear_rgb(), vec![[0.0; 3], [2.0; 3]]);
        assert_eq!(f.sample_range(), (0, 3));
    }

    #[test]
    fn merged_films_equal_one_film_with_all_samples() {
        let (mut a, mut b, mut all) = (Film::new(1, 1), Film::new(1, 1), Film::new(1, 1));
        a.add_sample(0, 0, Some(Rgb::gray(1.0)), 1.0);
        b.add_sample(0, 0, Some(Rgb::gray(4.0)), 1.0);
        all.add_sample(0, 0, Some(Rgb::gray(1.0)), 1.0);
        all.add_sample(0, 0, Some(Rgb::gray(4.0)), 1.0);
        a.merge(&b);
        assert_eq!(a, all);
    }

    #[test]
    fn regions_copy_out_and_back_and_data_round_trips() {
        let mut f = Film::new(4, 3);
        f.add_sample(2, 1, Some(Rgb::new(1.0, 2.0, 3.0)), 0.5);
        let part = f.region(1, 1, 2, 2);
        assert_eq!(part.samples(1, 0), 1);
        let mut g = Film::new(4, 3);
        g.store_region(&part, 1, 1);
        assert_eq!(g, f);
        assert_eq!(Film::from_data(f.to_data()), Some(f.clone()));
        let mut bad = f.to_data();
        bad.samples.pop();
        assert_eq!(Film::from_data(bad), None);
    }
}
