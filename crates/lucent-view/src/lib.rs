//! lucent-view: a window that shows a scene while it is traced.
//!
//! The library decides which pixels get samples and what the screen shows (its display
//! schedules: frameless, double-buffered, adaptive) and traces each sample; this crate only
//! drives them. Worker threads take batches of samples from the mode's presenter, trace them
//! at the scene and camera of each sample's own instant and hand them back; the display
//! thread shows the presenter's picture at the refresh rate, tone mapped as the library's PNG
//! output, into a CPU framebuffer (softbuffer) in a window (winit, X11 loaded at run time).
//!
//! The mouse and keys move the camera ([`HELP`]); the title bar reads the mode, samples per
//! second and the age of the oldest pixel on screen.

mod app;
pub mod clock;
pub mod display;
mod input;
pub mod pose;
pub mod readout;
pub mod workers;

pub use lucent::schedule::frameless::DisplayMode;
pub use pose::Pose;

use lucent::integrator::Integrator;
use lucent::scene::Scene;
use std::fmt;

/// The keys and the mouse, as printed on start.
pub const HELP: &str = "\
keys: left-drag orbit, right-drag or wheel dolly, W/A/S/D/Q/E fly, arrows turn,
      R reset the camera, M next mode, Space pause, Esc quit";

/// How to view.
#[derive(Clone, Debug)]
pub struct Options {
    /// The display mode to start in.
    pub mode: DisplayMode,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
    /// Window pixels per rendered pixel, a side (at least 1).
    pub scale: u32,
    /// The window's starting inner size in pixels.
    pub size: (u32, u32),
    /// Redraws per second.
    pub refresh: f64,
    /// Close by itself after this many seconds (for measurements and tests).
    pub exit_after: Option<f64>,
    /// Seed of the sample order and of the samples.
    pub seed: u64,
    /// The scene's name, for the title.
    pub name: String,
}

/// What a viewing session did.
#[derive(Clone, Debug)]
pub struct Summary {
    /// The mode at the end.
    pub mode: DisplayMode,
    /// The render resolution at the end.
    pub resolution: (u32, u32),
    /// Worker threads.
    pub threads: usize,
    /// Samples traced.
    pub samples: u64,
    /// Seconds of running (unpaused) time.
    pub seconds: f64,
}

impl Summary {
    /// Samples traced per second of running time.
    pub fn samples_per_second(&self) -> f64 {
        self.samples as f64 / self.seconds.max(1e-9)
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} samples in {:.2} s: {:.3} M samples/s ({}, {}×{}, {} threads)",
            self.samples,
            self.seconds,
            self.samples_per_second() / 1e6,
            self.mode.name(),
            self.resolution.0,
            self.resolution.1,
            self.threads
        )
    }
}

/// Why the viewer could not run.
#[derive(Debug)]
pub enum ViewError {
    /// No window could be opened (no display, or no X libraries at run time).
    Window(String),
    /// A worker thread panicked.
    Worker,
}

impl fmt::Display for ViewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ViewError::Window(e) => write!(f, "cannot open a window: {e}"),
            ViewError::Worker => write!(f, "a render thread failed"),
        }
    }
}

impl std::error::Error for ViewError {}

/// Opens a window on `scene`, seen from `pose` until the user moves the camera, traced by
/// `integrator`; returns when the window is closed (or `exit_after` has passed), the workers
/// joined.
pub fn run(
    scene: Scene,
    pose: Pose,
    integrator: Integrator,
    options: &Options,
) -> Result<Summary, ViewError> {
    app::run(scene, pose, integrator, options)
}
