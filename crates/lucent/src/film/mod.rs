//! The film: per-pixel running sums of radiance and of sample weights, in linear RGB.
//!
//! Films of the same scene and settings merge by adding their sums; tone mapping and encoding
//! happen only on output ([`tonemap`]).

pub mod tonemap;

use crate::Rgb;

/// Linear radiance sums and weights for a `width × height` image, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    sums: Vec<Rgb>,
    weights: Vec<f32>,
}

impl Film {
    /// An empty film (all sums and weights zero).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            sums: vec![Rgb::BLACK; n],
            weights: vec![0.0; n],
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

    /// Adds a sample of radiance `value` with weight `weight` to pixel `(x, y)`.
    pub fn add(&mut self, x: u32, y: u32, value: Rgb, weight: f32) {
        let i = self.index(x, y);
        self.sums[i] += value * weight;
        self.weights[i] += weight;
    }

    /// The pixel's estimate: the weighted mean of its samples, black when it has none.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb {
        let i = self.index(x, y);
        let w = self.weights[i];
        if w > 0.0 {
            self.sums[i] / w
        } else {
            Rgb::BLACK
        }
    }

    /// The sum of weights at pixel `(x, y)` (the sample count under a box filter).
    pub fn weight(&self, x: u32, y: u32) -> f32 {
        self.weights[self.index(x, y)]
    }

    /// Every pixel's estimate, row by row from the top, as linear RGB triples.
    pub fn to_linear_rgb(&self) -> Vec<[f32; 3]> {
        (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| self.pixel(x, y).to_array())
            .collect()
    }

    /// Adds `part`, a film covering the region whose top-left pixel is `(x0, y0)`, into this one.
    ///
    /// # Panics
    /// If the region does not fit inside this film.
    pub fn merge_region(&mut self, part: &Film, x0: u32, y0: u32) {
        assert!(
            x0 + part.width <= self.width && y0 + part.height <= self.height,
            "region outside the film"
        );
        for y in 0..part.height {
            for x in 0..part.width {
                let (src, dst) = (part.index(x, y), self.index(x0 + x, y0 + y));
                self.sums[dst] += part.sums[src];
                self.weights[dst] += part.weights[src];
            }
        }
    }

    /// Adds another film of the same size into this one.
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
            *a += *b;
        }
        for (a, b) in self.weights.iter_mut().zip(&other.weights) {
            *a += *b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_is_the_mean_of_its_samples() {
        let mut f = Film::new(2, 1);
        f.add(1, 0, Rgb::gray(1.0), 1.0);
        f.add(1, 0, Rgb::gray(3.0), 1.0);
        assert_eq!(f.pixel(1, 0), Rgb::gray(2.0));
        assert_eq!(f.pixel(0, 0), Rgb::BLACK);
        assert_eq!(f.to_linear_rgb(), vec![[0.0; 3], [2.0; 3]]);
    }

    #[test]
    fn merged_films_equal_one_film_with_all_samples() {
        let (mut a, mut b, mut all) = (Film::new(1, 1), Film::new(1, 1), Film::new(1, 1));
        a.add(0, 0, Rgb::gray(1.0), 1.0);
        b.add(0, 0, Rgb::gray(4.0), 1.0);
        all.add(0, 0, Rgb::gray(1.0), 1.0);
        all.add(0, 0, Rgb::gray(4.0), 1.0);
        a.merge(&b);
        assert_eq!(a, all);
    }
}
