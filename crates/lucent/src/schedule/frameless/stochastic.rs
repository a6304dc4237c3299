//! Frameless rendering (Bishop et al. 1994): pixels in a stochastic order, each shown as soon
//! as it is traced.
//!
//! The order is a fresh pseudo-random permutation of the screen every pass
//! ([`crate::sampling::permute`] keyed by the pass), so every pixel is sampled once per pass —
//! the screen is covered evenly, with no visible crawl of a regular pattern — and no pixel
//! waits longer than two passes.

use super::{Sample, SampleRequest, spread};
use crate::Rgb;
use crate::sampling::{mix64, permute};

/// The stochastic order of the pixels of a screen: a new permutation every pass.
#[derive(Clone, Debug)]
pub(super) struct Order {
    pixels: u32,
    seed: u64,
    /// Passes over the screen handed out so far, and the position in the current one.
    pass: u64,
    cursor: u32,
}

impl Order {
    /// The order of `pixels` pixels chosen by `seed`.
    pub(super) fn new(pixels: u32, seed: u64) -> Self {
        Self {
            pixels,
            seed,
            pass: 0,
            cursor: 0,
        }
    }

    /// The next pixel (`None` for an empty screen).
    pub(super) fn next(&mut self) -> Option<u32> {
        if self.pixels == 0 {
            return None;
        }
        let key = mix64(self.seed ^ mix64(self.pass));
        let pixel = permute(self.cursor, self.pixels, key);
        self.cursor += 1;
        if self.cursor == self.pixels {
            self.cursor = 0;
            self.pass += 1;
        }
        Some(pixel)
    }
}

/// The frameless display: one buffer, written by every sample and shown as it is.
#[derive(Clone, Debug)]
pub struct Frameless {
    width: u32,
    height: u32,
    order: Order,
    image: Vec<Rgb>,
    times: Vec<f64>,
}

impl Frameless {
    /// A black screen of `width × height`; `seed` chooses the orders.
    pub fn new(width: u32, height: u32, seed: u64) -> Self {
        let n = (width as usize) * (height as usize);
        Self {
            width,
            height,
            order: Order::new(width * height, seed),
            image: vec![Rgb::BLACK; n],
            times: vec![f64::NEG_INFINITY; n],
        }
    }

    /// The screen's size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The next `count` pixels of the order, at instants spread over `[t0, t1)`.
    pub fn plan(&mut self, count: usize, t0: f64, t1: f64, out: &mut Vec<SampleRequest>) {
        out.extend((0..count).map_while(|i| {
            Some(SampleRequest {
                pixel: self.order.next()?,
                time: spread(t0, t1, i, count),
            })
        }));
    }

    /// Writes the samples straight into the displayed buffer.
    pub fn accept(&mut self, samples: &[Sample]) {
        for s in samples {
            let p = s.pixel as usize;
            if p < self.image.len() && s.time >= self.times[p] {
                self.image[p] = s.color;
                self.times[p] = s.time;
            }
        }
    }

    /// The displayed buffer.
    pub fn present(&self) -> &[Rgb] {
        &self.image
    }

    /// Per pixel, the instant of its sample on screen.
    pub fn shown_times(&self) -> &[f64] {
        &self.times
    }

    /// Shows `image`, as if every pixel had been sampled at `time`.
    pub fn prime(&mut self, image: &[Rgb], time: f64) {
        self.image.copy_from_slice(image);
        self.times.fill(time);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pass_covers_the_screen_once_in_a_new_order() {
        let mut f = Frameless::new(13, 7, 5);
        let mut out = Vec::new();
        f.plan(91, 0.0, 1.0, &mut out);
        f.plan(91, 1.0, 2.0, &mut out);
        let (first, second) = out.split_at(91);
        for pass in [first, second] {
            let mut seen = vec![0; 91];
            for r in pass {
                seen[r.pixel as usize] += 1;
            }
            assert!(seen.iter().all(|&c| c == 1));
        }
        let same = first
            .iter()
            .zip(second)
            .filter(|(a, b)| a.pixel == b.pixel)
            .count();
        assert!(same < 10, "{same} pixels in the same place in both passes");
        // Not scanline order either.
        let ordered = first
            .windows(2)
            .filter(|w| w[1].pixel == w[0].pixel + 1)
            .count();
        assert!(ordered < 10, "{ordered} steps to the next pixel");
    }

    #[test]
    fn samples_show_at_once_and_the_latest_wins() {
        let mut f = Frameless::new(2, 1, 0);
        let c = |v| Rgb::gray(v);
        f.accept(&[
            Sample {
                pixel: 1,
                time: 2.0,
                color: c(0.5),
            },
            Sample {
                pixel: 1,
                time: 1.0,
                color: c(0.9),
            },
        ]);
        assert_eq!(f.present(), &[Rgb::BLACK, c(0.5)]);
        assert_eq!(f.shown_times(), &[f64::NEG_INFINITY, 2.0]);
    }
}
