//! Double buffering: a whole frame traced at one instant into the back buffer, shown when
//! complete. What the screen shows is at least one frame time old, and the newest change
//! waits for the frame after the one in flight.

use super::{Sample, SampleRequest};
use crate::Rgb;

/// The double-buffered display.
#[derive(Clone, Debug)]
pub struct DoubleBuffer {
    width: u32,
    height: u32,
    front: Vec<Rgb>,
    /// The instant of the frame on screen, for every pixel (one value, kept as a slice for
    /// [`super::Presenter::shown_times`]).
    front_times: Vec<f64>,
    back: Vec<Rgb>,
    /// The instant of the frame in flight, once one has started.
    frame: Option<f64>,
    /// Pixels of the frame in flight handed out, and traced.
    planned: u32,
    done: u32,
}

impl DoubleBuffer {
    /// A black screen of `width × height`.
    pub fn new(width: u32, height: u32) -> Self {
        let n = (width as usize) * (height as usize);
        Self {
            width,
            height,
            front: vec![Rgb::BLACK; n],
            front_times: vec![f64::NEG_INFINITY; n],
            back: vec![Rgb::BLACK; n],
            frame: None,
            planned: 0,
            done: 0,
        }
    }

    /// The screen's size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The next at most `count` pixels of the frame in flight, in reading order, all at its
    /// instant; a new frame starts at `t0` when none is in flight. Nothing once the whole
    /// frame is handed out and not yet complete.
    pub fn plan(&mut self, count: usize, t0: f64, out: &mut Vec<SampleRequest>) {
        let n = self.width * self.height;
        let instant = *self.frame.get_or_insert(t0);
        let take = (count as u64).min(u64::from(n - self.planned)) as u32;
        out.extend(
            (self.planned..self.planned + take).map(|pixel| SampleRequest {
                pixel,
                time: instant,
            }),
        );
        self.planned += take;
    }

    /// Writes samples of the frame in flight into the back buffer; the last one swaps.
    pub fn accept(&mut self, samples: &[Sample]) {
        let Some(instant) = self.frame else { return };
        // Every request handed out belongs to the frame in flight (the next one starts only
        // after the swap), whatever instant the driver resolved it to.
        for s in samples {
            if let Some(slot) = self.back.get_mut(s.pixel as usize) {
                *slot = s.color;
                self.done += 1;
            }
        }
        if self.done >= self.width * self.height {
            std::mem::swap(&mut self.front, &mut self.back);
            self.front_times.fill(instant);
            self.frame = None;
            self.planned = 0;
            self.done = 0;
        }
    }

    /// The last complete frame.
    pub fn present(&self) -> &[Rgb] {
        &self.front
    }

    /// The instant of the frame on screen, per pixel.
    pub fn shown_times(&self) -> &[f64] {
        &self.front_times
    }

    /// Shows `image` as a complete frame of instant `time`.
    pub fn prime(&mut self, image: &[Rgb], time: f64) {
        self.front.copy_from_slice(image);
        self.front_times.fill(time);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trace(requests: &[SampleRequest], v: f32) -> Vec<Sample> {
        requests
            .iter()
            .map(|r| Sample {
                pixel: r.pixel,
                time: r.time,
                color: Rgb::gray(v),
            })
            .collect()
    }

    #[test]
    fn a_frame_shows_only_when_complete_and_at_its_instant() {
        let mut d = DoubleBuffer::new(3, 2);
        let mut out = Vec::new();
        d.plan(4, 1.0, &mut out);
        d.accept(&trace(&out, 0.5));
        assert_eq!(
            d.present(),
            &[Rgb::BLACK; 6],
            "a partial frame is not shown"
        );
        out.clear();
        d.plan(4, 1.5, &mut out);
        assert_eq!(out.len(), 2, "only the rest of the frame");
        assert!(
            out.iter().all(|r| r.time == 1.0),
            "every pixel at the frame's instant"
        );
        let mut more = Vec::new();
        d.plan(4, 1.6, &mut more);
        assert!(more.is_empty(), "nothing more until the frame completes");
        d.accept(&trace(&out, 0.5));
        assert_eq!(d.present(), &[Rgb::gray(0.5); 6]);
        assert_eq!(d.shown_times(), &[1.0; 6]);
        d.plan(1, 2.0, &mut more);
        assert_eq!(
            more[0],
            SampleRequest {
                pixel: 0,
                time: 2.0
            },
            "the next frame starts"
        );
    }
}
