//! Participating media: what fills the space between surfaces (fog, smoke, coloured liquids,
//! the inside of marble) and how light is absorbed and scattered on its way through.
//!
//! A medium has, per RGB channel, an absorption coefficient `σa` and a scattering coefficient
//! `σs` (per unit of scene length); their sum is the extinction `σt`. Light crossing a
//! distance `d` keeps the share `Tr(d) = exp(−σt·d)` (Beer–Lambert), and at each point the
//! share `σs/σt` of what is taken out is scattered into new directions by the phase function.
//!
//! A *heterogeneous* medium scales its coefficients at every point by a grid's density
//! ([`grid`]), and may take its albedo `σs/σt` from a grid too ([`albedo_grid`]); distances
//! through it are drawn by delta tracking and its transmittance estimated by ratio tracking
//! (`track.rs`), or integrated by quadrature where no noise is wanted
//! ([`Medium::fog_along`]).
//!
//! Where a ray is: every object may carry a [`MediumInterface`], the medium on its inside and
//! on its outside (the side its geometric normal points to); a ray that crosses the surface
//! enters the one on the side it goes to. The camera sits in the scene's own medium (fog), or
//! in none. A surface that only bounds a medium is a *null* material (fully cut away,
//! `opacity = 0`): rays cross it without scattering.
//!
//! Distance sampling in colour: each path picks a *hero* channel and draws every distance from
//! that channel's exponential; the path's estimate is then divided by the density of its
//! distances averaged over the three channels (one-sample MIS with the balance heuristic over
//! the channels, over the whole path — the scheme of Mitsuba's `volpathmis` and pbrt-v4's
//! `r_u`), so a medium whose extinction differs per channel needs no channel's paths to be
//! rare. [`Interaction`] gives both factors a distance sample contributes: the throughput's
//! (`f/p_hero`) and the channels' densities relative to the hero's (`p_c/p_hero`).

pub mod albedo_grid;
pub mod grid;
pub mod phase;
mod track;

pub use albedo_grid::AlbedoGrid;
pub use grid::DensityGrid;
pub use phase::HenyeyGreenstein;

use crate::Rgb;
use crate::sampling::Rng;
use glam::Vec3;
use std::sync::Arc;

/// A medium: homogeneous (the same coefficients everywhere inside it), or heterogeneous, its
/// coefficients scaled at every point by a grid's density.
#[derive(Clone, Debug, PartialEq)]
pub struct Medium {
    /// Absorption per unit length, per channel (at density 1 in a heterogeneous medium).
    pub sigma_a: Rgb,
    /// Scattering per unit length, per channel (at density 1 in a heterogeneous medium).
    pub sigma_s: Rgb,
    /// How it scatters.
    pub phase: HenyeyGreenstein,
    /// The density at each point, if the medium is heterogeneous.
    pub density: Option<Arc<DensityGrid>>,
    /// The albedo at each point, if it varies: then `σs = σt·albedo(x)` there, whatever
    /// `sigma_a` and `sigma_s` divide `σt` into.
    pub albedo_grid: Option<Arc<AlbedoGrid>>,
}

/// Which media lie on either side of an object's surface (indices into the scene's media).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MediumInterface {
    /// The medium behind the surface: on the side opposite its geometric normal.
    pub inside: Option<u32>,
    /// The medium in front: on the side its geometric normal points to.
    pub outside: Option<u32>,
}

impl MediumInterface {
    /// Whether crossing the surface can change the medium (an object with no media leaves a
    /// ray in the medium it was in, as Mitsuba does).
    pub fn is_transition(&self) -> bool {
        self.inside.is_some() || self.outside.is_some()
    }

    /// The medium a ray leaving the surface along `dir` is in, given the surface's geometric
    /// normal `ng` and the medium `current` it was in before.
    pub fn towards(&self, ng: glam::Vec3, dir: glam::Vec3, current: Option<u32>) -> Option<u32> {
        if !self.is_transition() {
            return current;
        }
        if ng.dot(dir) < 0.0 {
            self.inside
        } else {
            self.outside
        }
    }
}

/// Where a distance sample along a segment fell, and what it contributes: the throughput's
/// factor `weight` (the sampled value over the hero channel's density) and `ratio`, each
/// channel's density of the same sample over the hero's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Interaction {
    /// In the medium, at distance `t` along the ray: the path scatters there.
    /// `weight = σs·Tr(t) / p_hero(t)`, `ratio = σt·Tr(t) / p_hero(t)`.
    Scatter {
        /// Distance along the ray.
        t: f32,
        /// The throughput's factor.
        weight: Rgb,
        /// The channels' densities over the hero's.
        ratio: Rgb,
    },
    /// Past the segment's end: the surface there is reached.
    /// `weight = ratio = Tr(end) / P_hero(end)`; in a medium that only absorbs, no distance is
    /// drawn and the segment is passed for sure: `weight = Tr(end)`, `ratio = 1`.
    Pass {
        /// The throughput's factor.
        weight: Rgb,
        /// The channels' probabilities of passing over the hero's.
        ratio: Rgb,
    },
}

impl Medium {
    /// A medium from its absorption and scattering coefficients and its phase function's
    /// mean cosine.
    pub fn new(sigma_a: Rgb, sigma_s: Rgb, g: f32) -> Self {
        Self {
            sigma_a,
            sigma_s,
            phase: HenyeyGreenstein::new(g),
            density: None,
            albedo_grid: None,
        }
    }

    /// This medium with its albedo varying as `grid` says (its extinction unchanged); for a
    /// heterogeneous medium only (a homogeneous one's albedo is its own).
    pub fn with_albedo(self, grid: Arc<AlbedoGrid>) -> Self {
        Self {
            albedo_grid: Some(grid),
            ..self
        }
    }

    /// Whether it scatters anywhere (else it only absorbs).
    pub fn scatters(&self) -> bool {
        self.albedo_grid.is_some() || !self.sigma_s.is_black()
    }

    /// The scattering coefficient at `p` (at density 1 in a heterogeneous medium).
    pub fn sigma_s_at(&self, p: Vec3) -> Rgb {
        match &self.albedo_grid {
            None => self.sigma_s,
            Some(grid) => self.sigma_t() * grid.albedo(p),
        }
    }

    /// This medium made heterogeneous: its coefficients scaled by `grid`'s density.
    pub fn with_density(self, grid: Arc<DensityGrid>) -> Self {
        Self {
            density: Some(grid),
            ..self
        }
    }

    /// A medium from its extinction `σt` and single-scattering albedo `σs/σt` (Mitsuba's and
    /// glTF's terms).
    pub fn from_albedo(sigma_t: Rgb, albedo: Rgb, g: f32) -> Self {
        let sigma_s = sigma_t * albedo;
        Self::new(sigma_t - sigma_s, sigma_s, g)
    }

    /// The extinction `σa + σs`.
    pub fn sigma_t(&self) -> Rgb {
        self.sigma_a + self.sigma_s
    }

    /// The share of light that crosses distance `d` unabsorbed and unscattered:
    /// `exp(−σt·d)` per channel (0 at infinite distance unless `σt` is 0 there).
    pub fn transmittance(&self, d: f32) -> Rgb {
        self.sigma_t().map(|s| transmit(s, d))
    }

    /// The transmittance along `origin + t·dir` (unit `dir`) over `[0, end]`: exact in a
    /// homogeneous medium, an unbiased estimate by ratio tracking (randomness from `rng`) in a
    /// heterogeneous one.
    pub fn transmittance_along(&self, ray: (Vec3, Vec3), end: f32, rng: &mut Rng) -> Rgb {
        match &self.density {
            None => self.transmittance(end),
            Some(grid) => track::transmittance(self, grid, ray, end, rng),
        }
    }

    /// What a stretch `[0, end]` of `origin + t·dir` (unit `dir`) in the medium does, without
    /// noise: its transmittance, and the share `∫ Tr(t)·σs(t) dt` of light it scatters towards
    /// the origin from a uniform radiance 1. Exact in a homogeneous medium (the share is then
    /// `albedo·(1 − Tr)`); by the midpoint rule through a grid ([`DensityGrid::quadrature`]).
    pub fn fog_along(&self, (origin, dir): (Vec3, Vec3), end: f32) -> (Rgb, Rgb) {
        let Some(grid) = &self.density else {
            let tr = self.transmittance(end);
            return (tr, self.albedo() * (Rgb::WHITE - tr));
        };
        let st = self.sigma_t();
        let (mut tr, mut scattered) = (Rgb::WHITE, Rgb::BLACK);
        grid.quadrature(origin, dir, end, |p, h, density| {
            let step = st.map(|s| transmit(s, density * h));
            let albedo = match &self.albedo_grid {
                None => self.albedo(),
                Some(g) => g.albedo(p),
            };
            scattered += tr * albedo * (Rgb::WHITE - step);
            tr *= step;
        });
        (tr, scattered)
    }

    /// The single-scattering albedo `σs/σt` per channel (0 where nothing is taken out).
    pub fn albedo(&self) -> Rgb {
        let (s, t) = (self.sigma_s.to_array(), self.sigma_t().to_array());
        Rgb::from(std::array::from_fn::<f32, 3, _>(|c| {
            if t[c] > 0.0 { s[c] / t[c] } else { 0.0 }
        }))
    }

    /// A distance sample along `origin + t·dir` (unit `dir`) for a segment of length `end`
    /// (infinite for a ray that escapes), by channel `hero` (0, 1, 2): the homogeneous
    /// medium's [`Medium::sample_distance`] with `u`, or delta tracking through a grid, its
    /// first collision drawn from `u` and the rest from `rng`.
    pub fn sample_along(
        &self,
        ray: (Vec3, Vec3),
        end: f32,
        hero: usize,
        u: f32,
        rng: &mut Rng,
    ) -> Interaction {
        match &self.density {
            None => self.sample_distance(end, hero, u),
            Some(grid) => track::sample_distance(self, grid, ray, end, hero, u, rng),
        }
    }

    /// A distance sample along a segment of length `end` (infinite for a ray that escapes)
    /// in a homogeneous medium, drawn from the exponential of channel `hero` (0, 1, 2) with `u`
    /// uniform in `[0, 1)`.
    pub fn sample_distance(&self, end: f32, hero: usize, u: f32) -> Interaction {
        if self.sigma_s.is_black() {
            // Nothing scatters: the transmittance itself, with no noise.
            return Interaction::Pass {
                weight: self.transmittance(end),
                ratio: Rgb::WHITE,
            };
        }
        let st = self.sigma_t();
        let s_hero = st.to_array()[hero];
        let t = if s_hero > 0.0 {
            -(1.0 - u).ln() / s_hero
        } else {
            f32::INFINITY
        };
        if t < end {
            let tr = self.transmittance(t);
            let pdf = s_hero * tr.to_array()[hero];
            if !(pdf > 0.0 && pdf.is_finite()) {
                // Underflow far out: nothing comes back from there.
                return Interaction::Scatter {
                    t,
                    weight: Rgb::BLACK,
                    ratio: Rgb::WHITE,
                };
            }
            return Interaction::Scatter {
                t,
                weight: self.sigma_s * tr / pdf,
                ratio: st * tr / pdf,
            };
        }
        let tr = self.transmittance(end);
        let p_pass = tr.to_array()[hero];
        let weight = if p_pass > 0.0 {
            tr / p_pass
        } else {
            Rgb::BLACK
        };
        Interaction::Pass {
            weight,
            ratio: weight,
        }
    }
}

/// `exp(−σ·d)`, 1 for no extinction even over an infinite distance.
fn transmit(sigma: f32, d: f32) -> f32 {
    if sigma == 0.0 {
        1.0
    } else {
        (-sigma * d).exp()
    }
}

#[cfg(test)]
mod grid_tests;
#[cfg(test)]
mod tests;
