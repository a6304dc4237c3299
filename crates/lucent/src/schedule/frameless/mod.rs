//! Display schedules for interactive rendering: which pixel to sample next and what the screen
//! shows, under a sample budget that arrives over time (Bishop, Fuchs, McMillan and Scher
//! Zagier, *Frameless rendering: double buffering considered harmful*, 1994; Dayal, Woolley,
//! Watson and Luebke, *Adaptive frameless rendering*, 2005).
//!
//! Three [`DisplayMode`]s share one interface, [`Presenter`]:
//! - **double buffering**: a whole frame is traced at one instant into a back buffer and shown
//!   when complete;
//! - **frameless**: single-pixel samples in a fresh random order every pass, each traced at its
//!   own instant and shown at once;
//! - **adaptive frameless**: samples steered to the tiles of the screen that change (and to
//!   edges), and a reconstruction that weighs each sample by its age and distance.
//!
//! A driver (the viewer's worker threads, or the simulated clock of `lucent study frameless`)
//! loops: [`Presenter::plan`] a batch of requests for a span of time, trace each with
//! [`trace_sample`] in the scene at the request's instant, [`Presenter::accept`] the results,
//! and at each display refresh [`Presenter::present`]. `plan` may return fewer requests than
//! asked (double buffering waits for the frame in flight to complete); the driver asks again
//! after accepting.
//!
//! Times are in seconds on the driver's clock, as `f64`. Pixels are indices `y · width + x`.

mod adaptive;
mod double_buffer;
// mod snapshots;
mod stochastic;

pub use adaptive::AdaptiveFrameless;
pub use double_buffer::DoubleBuffer;
// pub use snapshots::Snapshots;
pub use stochastic::Frameless;

use crate::Rgb;
use crate::camera::Camera;
use crate::integrator::{Integrator, RayStats};
use crate::sampling::sobol::Sampler;
use crate::scene::Scene;
use std::fmt;
use std::str::FromStr;

/// How samples reach the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DisplayMode {
    /// Whole frames at one instant, swapped when complete.
    DoubleBuffer,
    /// Pixels in stochastic order, each shown as soon as it is traced.
    Frameless,
    /// Frameless, with samples steered to change and an age-weighted reconstruction.
    Adaptive,
}

impl DisplayMode {
    /// Every mode, in the order tables list them.
    pub const ALL: [DisplayMode; 3] = [
        DisplayMode::DoubleBuffer,
        DisplayMode::Frameless,
        DisplayMode::Adaptive,
    ];

    /// The name used on the command line and in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            DisplayMode::DoubleBuffer => "double-buffer",
            DisplayMode::Frameless => "frameless",
            DisplayMode::Adaptive => "adaptive",
        }
    }

    /// The next mode in [`DisplayMode::ALL`], wrapping around (the viewer's mode key).
    pub fn next(self) -> Self {
        let i = Self::ALL.iter().position(|&m| m == self).unwrap_or(0);
        Self::ALL[(i + 1) % Self::ALL.len()]
    }
}

impl fmt::Display for DisplayMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DisplayMode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                format!("unknown display mode {s:?}: expected double-buffer, frameless or adaptive")
            })
    }
}

/// One sample to trace: a pixel at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleRequest {
    /// The pixel, `y · width + x`.
    pub pixel: u32,
    /// The instant to trace it at, in seconds.
    pub time: f64,
}

/// A traced sample: the radiance seen through a pixel at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The pixel, `y · width + x`.
    pub pixel: u32,
    /// The instant it was traced at.
    pub time: f64,
    /// Linear radiance.
    pub color: Rgb,
}

/// A display mode's state: what to sample next, and what the screen shows.
#[derive(Clone, Debug)]
pub enum Presenter {
    /// See [`DoubleBuffer`].
    DoubleBuffer(DoubleBuffer),
    /// See [`Frameless`].
    Frameless(Frameless),
    /// See [`AdaptiveFrameless`].
    Adaptive(AdaptiveFrameless),
}

impl Presenter {
    /// A black screen of `width × height` pixels in `mode`; `seed` chooses the random orders.
    pub fn new(mode: DisplayMode, width: u32, height: u32, seed: u64) -> Self {
        match mode {
            DisplayMode::DoubleBuffer => Presenter::DoubleBuffer(DoubleBuffer::new(width, height)),
            DisplayMode::Frameless => Presenter::Frameless(Frameless::new(width, height, seed)),
            DisplayMode::Adaptive => {
                Presenter::Adaptive(AdaptiveFrameless::new(width, height, seed))
            }
        }
    }

    /// Which mode this is.
    pub fn mode(&self) -> DisplayMode {
        match self {
            Presenter::DoubleBuffer(_) => DisplayMode::DoubleBuffer,
            Presenter::Frameless(_) => DisplayMode::Frameless,
            Presenter::Adaptive(_) => DisplayMode::Adaptive,
        }
    }

    /// The screen's size in pixels.
    pub fn size(&self) -> (u32, u32) {
        match self {
            Presenter::DoubleBuffer(p) => p.size(),
            Presenter::Frameless(p) => p.size(),
            Presenter::Adaptive(p) => p.size(),
        }
    }

    /// Appends at most `count` requests to `out`, for instants spread evenly over `[t0, t1)`
    /// (double buffering: the instant of the frame in flight). Fewer when double buffering
    /// has handed out its whole frame and waits for it.
    pub fn plan(&mut self, count: usize, t0: f64, t1: f64, out: &mut Vec<SampleRequest>) {
        match self {
            Presenter::DoubleBuffer(p) => p.plan(count, t0, out),
            Presenter::Frameless(p) => p.plan(count, t0, t1, out),
            Presenter::Adaptive(p) => p.plan(count, t0, t1, out),
        }
    }

    /// Takes traced samples, in any order (samples of one pixel: the latest instant wins).
    pub fn accept(&mut self, samples: &[Sample]) {
        match self {
            Presenter::DoubleBuffer(p) => p.accept(samples),
            Presenter::Frameless(p) => p.accept(samples),
            Presenter::Adaptive(p) => p.accept(samples),
        }
    }

    /// The picture to show at `now`: linear RGB, row-major, `width × height`.
    pub fn present(&mut self, now: f64) -> &[Rgb] {
        match self {
            Presenter::DoubleBuffer(p) => p.present(),
            Presenter::Frameless(p) => p.present(),
            Presenter::Adaptive(p) => p.present(now),
        }
    }

    /// Per pixel, the instant of the newest sample of that pixel on screen (`-∞`: none yet).
    /// Adaptive reconstruction also blends neighbours in; this is the pixel's own sample.
    pub fn shown_times(&self) -> &[f64] {
        match self {
            Presenter::DoubleBuffer(p) => p.shown_times(),
            Presenter::Frameless(p) => p.shown_times(),
            Presenter::Adaptive(p) => p.shown_times(),
        }
    }

    /// The instant of the oldest pixel on screen (`-∞` while a pixel has none).
    pub fn oldest_shown(&self) -> f64 {
        self.shown_times()
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }

    /// Fills the screen with a complete picture taken at `time` (a driver's first frame).
    pub fn prime(&mut self, image: &[Rgb], time: f64) {
        match self {
            Presenter::DoubleBuffer(p) => p.prime(image, time),
            Presenter::Frameless(p) => p.prime(image, time),
            Presenter::Adaptive(p) => p.prime(image, time),
        }
    }
}

/// The radiance of one sample of pixel `pixel` (of `camera`'s image) in `scene`: through the
/// pixel's centre for a deterministic integrator and a pinhole, so that a pixel traced twice
/// at one instant agrees with itself; jittered in the pixel (and over the lens) by the sampler
/// of (`seed`, pixel, `index`) otherwise. Non-finite radiance counts in `stats` and is black.
pub fn trace_sample(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    pixel: u32,
    index: u32,
    seed: u64,
    stats: &mut RayStats,
) -> Rgb {
    let width = camera.width();
    let (x, y) = ((pixel % width) as f32, (pixel / width) as f32);
    let mut sampler = Sampler::new(seed, u64::from(pixel), index);
    let ray = if integrator.is_stochastic() || camera.lens().0 > 0.0 {
        let (jitter, lens) = (sampler.next_2d(), sampler.next_2d());
        camera.ray_through_lens(x + jitter.x, y + jitter.y, lens)
    } else {
        camera.ray(x + 0.5, y + 0.5)
    };
    stats.camera += 1;
    let c = integrator.radiance(scene, &ray, &mut sampler, stats);
    if c.is_finite() {
        c
    } else {
        stats.nonfinite += 1;
        Rgb::BLACK
    }
}

/// Instants spread evenly over `[t0, t1)`: the `i`-th of `count`, at the middle of its share.
#[inline]
fn spread(t0: f64, t1: f64, i: usize, count: usize) -> f64 {
    t0 + (t1 - t0) * (i as f64 + 0.5) / count as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_round_trip_through_their_names() {
        for m in DisplayMode::ALL {
            assert_eq!(m.name().parse::<DisplayMode>(), Ok(m));
        }
        assert!("triple-buffer".parse::<DisplayMode>().is_err());
        assert_eq!(DisplayMode::Adaptive.next(), DisplayMode::DoubleBuffer);
    }

    #[test]
    fn spread_instants_stay_inside_their_span() {
        let t: Vec<f64> = (0..4).map(|i| spread(1.0, 2.0, i, 4)).collect();
        assert_eq!(t, vec![1.125, 1.375, 1.625, 1.875]);
    }
}
