//! Integrators: the colour seen along a ray.
//!
//! Contract: `radiance(scene, ray, sampler, stats)` returns the linear RGB radiance arriving at
//! the ray's origin from direction `−ray.dir` (`ray.dir` of unit length), and counts the rays
//! it traces into `stats`; its random numbers come from `sampler` (the deterministic ones
//! draw none). It knows nothing of pixels or threads. To add one: a file with its
//! settings struct and `radiance`, a variant here, and its name in [`Integrator::name`].

mod crossings;
pub mod debug;
pub mod explain;
pub mod path;
pub mod path_lanes;
pub mod raycast;
pub mod record;
pub mod sppm;
pub mod vertex;
pub mod volpath;
pub mod whitted;
mod whitted_media;

pub use debug::DebugView;
pub use path::PathTracer;
pub use sppm::{MAX_PHOTONS_PER_ITERATION, Sppm};
pub use whitted::Whitted;

use crate::Rgb;
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
use lucent_accel::{Ray, TraversalStats};

/// Rays traced, by kind, and the accelerator work they cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayStats {
    /// Primary rays from the camera.
    pub camera: u64,
    /// Shadow rays towards lights.
    pub shadow: u64,
    /// Mirror-reflected rays (total internal reflection included).
    pub reflected: u64,
    /// Refracted (transmitted) rays.
    pub refracted: u64,
    /// Samples whose radiance was NaN or infinite, dropped from the film.
    pub nonfinite: u64,
    /// Secondary rays (reflected, refracted, shadow, photon) that could not be traced: a
    /// non-finite origin or direction, or a zero direction ([`Ray::is_traceable`]). Each
    /// ended its path untraced, and a camera sample it belonged to came out NaN: dropped, and
    /// counted in `nonfinite`.
    pub untraceable: u64,
    /// Rays of photons from the lights (the photon mapper): one per segment of a photon's path.
    pub photons: u64,
    /// Rays scattered in participating media (the volumetric path tracer).
    pub scattered: u64,
    /// Accelerator work over all rays.
    pub traversal: TraversalStats,
}

impl RayStats {
    /// All rays traced.
    pub fn total(&self) -> u64 {
        self.camera + self.shadow + self.reflected + self.refracted + self.photons + self.scattered
    }
}

impl std::ops::AddAssign for RayStats {
    fn add_assign(&mut self, o: Self) {
        self.camera += o.camera;
        self.shadow += o.shadow;
        self.reflected += o.reflected;
        self.refracted += o.refracted;
        self.nonfinite += o.nonfinite;
        self.untraceable += o.untraceable;
        self.photons += o.photons;
        self.scattered += o.scattered;
        self.traversal += o.traversal;
    }
}

/// The radiance of a camera sample with a ray that could not be traced (see
/// [`RayStats::untraceable`]): NaN, which every driver drops from the film and counts.
pub(crate) const UNTRACEABLE: Rgb = Rgb::gray(f32::NAN);

/// `radiance` unless `stats` counted an untraceable ray since it held `before`; then
/// [`UNTRACEABLE`].
#[inline]
pub(crate) fn unless_untraceable(radiance: Rgb, stats: &RayStats, before: u64) -> Rgb {
    if stats.untraceable == before {
        radiance
    } else {
        UNTRACEABLE
    }
}

/// Whether `ray`, made for a path, can be traced; counts it in `stats` when not.
#[inline]
pub(crate) fn traceable(ray: &Ray, stats: &mut RayStats) -> bool {
    let ok = ray.is_traceable();
    stats.untraceable += u64::from(!ok);
    ok
}

/// The light-transport method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integrator {
    /// Appel's ray casting: the flat diffuse colour of the nearest surface.
    Raycast,
    /// Whitted's recursive ray tracing: local shading, shadows, reflection and refraction.
    Whitted(Whitted),
    /// A debug view of what the camera ray finds.
    Debug(DebugView),
    /// Path tracing with next-event estimation and MIS: global illumination.
    Path(PathTracer),
    /// Stochastic progressive photon mapping: caustics, also from point lights.
    Sppm(Sppm),
}

impl Default for Integrator {
    fn default() -> Self {
        Integrator::Whitted(Whitted::default())
    }
}

impl Integrator {
    /// The name used in scene files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Raycast => "raycast",
            Integrator::Whitted(_) => "whitted",
            Integrator::Debug(view) => view.name(),
            Integrator::Path(_) => "path",
            Integrator::Sppm(_) => "sppm",
        }
    }

    /// True when the integrator draws random numbers: its samples differ, and only their mean
    /// converges (adaptive supersampling needs one that does not).
    pub fn is_stochastic(&self) -> bool {
        matches!(self, Integrator::Path(_) | Integrator::Sppm(_))
    }

    /// Radiance along `ray`; see the module's contract.
    #[inline]
    pub fn radiance(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        stats: &mut RayStats,
    ) -> Rgb {
        self.radiance_in(scene, None, ray, sampler, stats)
    }

    /// [`Integrator::radiance`] for a camera ray of `beam` (from its origin, inside it): the
    /// same value, its first hit found through the beam ([`Scene::intersect_in`]). The debug
    /// views trace from the root, since some of them show the traversal's own counts.
    #[inline]
    pub fn radiance_in(
        &self,
        scene: &Scene,
        beam: Option<&Beam>,
        ray: &Ray,
        sampler: &mut Sampler,
        stats: &mut RayStats,
    ) -> Rgb {
        // A camera ray that cannot be traced (a degenerate lens, overflowing values) gives no
        // radiance: NaN, which every driver drops from the film and counts as non-finite.
        if !ray.is_traceable() {
            return UNTRACEABLE;
        }
        match self {
            Integrator::Raycast => raycast::radiance(scene, beam, ray, stats),
            Integrator::Whitted(w) => w.radiance_in(scene, beam, ray, stats),
            Integrator::Debug(view) => debug::radiance(*view, scene, ray, stats),
            Integrator::Path(p) => p.radiance_in(scene, beam, ray, sampler, stats),
            // One ray alone cannot be photon mapped (the estimate needs every pixel's visible
            // point: the renderer runs the photon mapper's iterations); it is path traced.
            Integrator::Sppm(s) => PathTracer {
                max_depth: s.max_depth,
                ..PathTracer::default()
            }
            .radiance_in(scene, beam, ray, sampler, stats),
        }
    }
}
