//! Every source of light in a scene, as the path tracer samples them: the point, spot and
//! directional lights, the area lights, and the environment, one of them picked per shadow
//! ray in proportion to its power.
//!
//! Densities are solid-angle densities at the shaded point and include the probability of
//! picking the light, so that multiple importance sampling can weigh a light sample against a
//! BSDF sample that found the same light ([`Emitters::pdf_area`], [`Emitters::pdf_environment`]).

use super::area::{AreaLights, EmitterSample, luminance};
use super::environment::EnvironmentLight;
use super::{Light, spot::SpotLight};
use crate::Rgb;
use crate::sampling::distribution::Distribution1D;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// One light, as the picking distribution lists them ([`Emitters::pick`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// `Scene::lights[i]`.
    Delta(u32),
    /// `AreaLights::lights[i]`.
    Area(u32),
    /// The environment.
    Environment,
}

/// The lights of a scene, prepared for sampling.
#[derive(Clone, Debug, Default)]
pub struct Emitters {
    /// The area lights.
    pub area: AreaLights,
    /// The environment, when it is not black.
    pub environment: Option<EnvironmentLight>,
    entries: Vec<Entry>,
    pick: Option<Distribution1D>,
    /// For each scene object, its area light's index (`u32::MAX`: it does not emit).
    by_object: Vec<u32>,
    /// The entry of area light 0 (they follow the point-like lights).
    first_area: usize,
}

impl Emitters {
    /// Prepares `delta` (the scene's point-like lights), `area` and `environment` for a scene
    /// of `objects` objects whose bounding sphere has radius `radius`.
    pub fn new(
        delta: &[Light],
        area: AreaLights,
        environment: Option<EnvironmentLight>,
        objects: u32,
        radius: f32,
    ) -> Self {
        let mut entries = Vec::new();
        let mut power = Vec::new();
        for (i, l) in delta.iter().enumerate() {
            entries.push(Entry::Delta(i as u32));
            power.push(delta_power(l, radius));
        }
        let mut by_object = vec![u32::MAX; objects as usize];
        for (i, l) in area.lights.iter().enumerate() {
            entries.push(Entry::Area(i as u32));
            power.push(area.power(i));
            if let Some(slot) = by_object.get_mut(l.object as usize) {
                *slot = i as u32;
            }
        }
        if let Some(env) = &environment {
            entries.push(Entry::Environment);
            power.push(env.power(radius));
        }
        // A power too large for a float still gets the largest share (capped so that the sum
        // stays finite), a NaN or negative one none; when no light has a measurable power they
        // share alike, so that a scene of them does not go dark.
        let power: Vec<f32> = power
            .iter()
            .map(|&p| if p > 0.0 { p.min(f32::MAX / 1e6) } else { 0.0 })
            .collect();
        let pick =
            Distribution1D::new(&power).or_else(|| Distribution1D::new(&vec![1.0; entries.len()]));
        Self {
            area,
            environment,
            entries,
            pick,
            by_object,
            first_area: delta.len(),
        }
    }

    /// True when there is nothing to sample.
    pub fn is_empty(&self) -> bool {
        self.pick.is_none()
    }

    /// The area light that object `object` is, if it emits.
    pub fn area_light_of(&self, object: u32) -> Option<usize> {
        match self.by_object.get(object as usize) {
            Some(&i) if i != u32::MAX => Some(i as usize),
            _ => None,
        }
    }

    /// The light that `u_pick` chooses, in proportion to its power, as [`Emitters::sample`]
    /// chooses it: which light, the probability of choosing it, and `u_pick` rescaled to
    /// `[0, 1)` within its share (uniform and independent of the choice, for reuse). `None`
    /// when there are no lights.
    pub fn pick(&self, u_pick: f32) -> Option<(Entry, f32, f32)> {
        let (i, pmf, u_rest) = self.pick.as_ref()?.sample_discrete(u_pick);
        Some((self.entries[i], pmf, u_rest))
    }

    /// A light sample for the point `p`: `u_pick` chooses the light, `u` the point on it;
    /// `delta` lights are the scene's `lights`. `None` when the chosen light sends nothing
    /// towards `p`.
    pub fn sample(&self, delta: &[Light], p: Vec3, u_pick: f32, u: Vec2) -> Option<EmitterSample> {
        let (entry, pmf, u_rest) = self.pick(u_pick)?;
        let mut s = match entry {
            Entry::Delta(j) => {
                let l = delta[j as usize].illuminate(p)?;
                EmitterSample {
                    wi: l.to_light,
                    distance: l.distance,
                    radiance: l.intensity,
                    pdf: 1.0,
                    delta: true,
                }
            }
            Entry::Area(j) => self.area.sample(j as usize, p, u_rest, u)?,
            Entry::Environment => {
                let env = self.environment.as_ref()?;
                let (wi, pdf) = env.sample(u)?;
                EmitterSample {
                    wi,
                    distance: f32::INFINITY,
                    // The caller looks the radiance up: the environment is the scene's.
                    radiance: Rgb::WHITE,
                    pdf,
                    delta: false,
                }
            }
        };
        s.pdf *= pmf;
        (s.pdf > 0.0 && s.pdf.is_finite()).then_some(s)
    }

    /// The density with which [`Emitters::sample`] reaches point `x` (geometric normal `n`)
    /// of area light `light` from `p`, picking included.
    pub fn pdf_area(&self, light: usize, p: Vec3, x: Vec3, n: Vec3) -> f32 {
        let Some(pick) = &self.pick else { return 0.0 };
        pick.pmf(self.first_area + light) * self.area.pdf(light, p, x, n)
    }

    /// The density with which [`Emitters::sample`] picks the environment along `dir`.
    pub fn pdf_environment(&self, dir: Vec3) -> f32 {
        match (&self.pick, &self.environment, self.entries.last()) {
            (Some(pick), Some(env), Some(Entry::Environment)) => {
                pick.pmf(self.entries.len() - 1) * env.pdf(dir)
            }
            _ => 0.0,
        }
    }
}

/// The power of a point-like light, for picking: a point light sends `4π·I`, a spot light
/// `2π·I` times its cone's share, a directional light `π·r²·I` through the scene's disc, a
/// photometric light its colour's `I` times its profile's `∫ I dω`, an image light its
/// `∫ I dω` per channel.
fn delta_power(l: &Light, radius: f32) -> f32 {
    match l {
        Light::Point(p) => 4.0 * PI * luminance(p.intensity),
        Light::Spot(SpotLight {
            point,
            cos_cutoff,
            cos_start,
            ..
        }) => 2.0 * PI * luminance(point.intensity) * (1.0 - 0.5 * (cos_cutoff + cos_start)),
        Light::Directional(d) => PI * radius * radius * luminance(d.intensity),
        Light::Photometric(l) => l.profile.total() * luminance(l.point.intensity),
        Light::Image(l) => luminance(l.power()),
    }
}
