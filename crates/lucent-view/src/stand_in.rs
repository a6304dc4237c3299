//! TEMPORARY: a stand-in for `lucent::schedule::frameless`, which the library is getting. It
//! has the same signatures and the least behaviour that lets the viewer run (every mode is a
//! frameless random order); it is deleted when the real schedules land.

use lucent::camera::Camera;
use lucent::integrator::{Integrator, RayStats};
use lucent::sampling::sobol::Sampler;
use lucent::scene::Scene;
use lucent::{Rgb, sampling};
use std::sync::Arc;

/// How the picture on screen is made from the samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DisplayMode {
    /// Whole frames, each shown once finished.
    DoubleBuffer,
    /// Every sample straight onto the screen.
    Frameless,
    /// Frameless, steered to where the picture changes.
    Adaptive,
}

impl DisplayMode {
    /// Every mode, in the order a key cycles through them.
    pub const ALL: [DisplayMode; 3] = [
        DisplayMode::Frameless,
        DisplayMode::DoubleBuffer,
        DisplayMode::Adaptive,
    ];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            DisplayMode::DoubleBuffer => "double-buffer",
            DisplayMode::Frameless => "frameless",
            DisplayMode::Adaptive => "adaptive",
        }
    }
}

/// One sample to trace.
#[derive(Clone, Copy, Debug)]
pub struct SampleRequest {
    /// `y * width + x`.
    pub pixel: u32,
    /// The instant it shows.
    pub time: f64,
}

/// A traced sample.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    /// `y * width + x`.
    pub pixel: u32,
    /// The instant it shows.
    pub time: f64,
    /// Its radiance.
    pub color: Rgb,
}

/// The mode's state.
pub struct Presenter {
    mode: DisplayMode,
    image: Vec<Rgb>,
    times: Vec<f64>,
    key: u64,
    next: u32,
}

impl Presenter {
    /// An empty screen of `width × height`.
    pub fn new(mode: DisplayMode, width: u32, height: u32, seed: u64) -> Self {
        let n = (width * height) as usize;
        Self {
            mode,
            image: vec![Rgb::BLACK; n],
            times: vec![f64::NEG_INFINITY; n],
            key: seed,
            next: 0,
        }
    }

    /// The mode.
    pub fn mode(&self) -> DisplayMode {
        self.mode
    }

    /// Appends `count` requests over `[t0, t1)`.
    pub fn plan(&mut self, count: usize, t0: f64, t1: f64, out: &mut Vec<SampleRequest>) {
        let n = self.image.len() as u32;
        for i in 0..count {
            let pixel = sampling::permute(self.next % n, n, self.key);
            self.next = self.next.wrapping_add(1);
            let time = t0 + (t1 - t0) * i as f64 / count as f64;
            out.push(SampleRequest { pixel, time });
        }
    }

    /// Writes samples onto the screen.
    pub fn accept(&mut self, samples: &[Sample]) {
        for s in samples {
            self.image[s.pixel as usize] = s.color;
            self.times[s.pixel as usize] = s.time;
        }
    }

    /// The screen.
    pub fn present(&mut self, _now: f64) -> &[Rgb] {
        &self.image
    }

    /// The oldest sample's instant.
    pub fn oldest_shown(&self) -> f64 {
        self.times.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// One sample of `pixel` through the pixel's centre.
pub fn trace_sample(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    pixel: u32,
    index: u32,
    seed: u64,
    stats: &mut RayStats,
) -> Rgb {
    let (x, y) = (pixel % camera.width(), pixel / camera.width());
    let ray = camera.ray(x as f32 + 0.5, y as f32 + 0.5);
    let mut sampler = Sampler::new(seed, u64::from(pixel), index);
    stats.camera += 1;
    integrator.radiance(scene, &ray, &mut sampler, stats)
}

/// The scene at an instant (a still scene: always the same).
pub struct Snapshots(Arc<Scene>);

impl Snapshots {
    /// Snapshots of `scene` every `step` seconds.
    pub fn new(scene: Arc<Scene>, _step: f64) -> Self {
        Self(scene)
    }

    /// The scene at `t`.
    pub fn at(&self, _t: f64) -> Arc<Scene> {
        Arc::clone(&self.0)
    }
}
