//! Every source of light in a scene, as the path tracer samples them: the point, spot and
//! directional lights, the area lights, and the environment, one of them picked per shadow
//! ray in proportion to its power.
//!
//! Densities are solid-angle densities at the shaded point and include the probability of
//! picking the light, so that multiple importance sampling can weigh a light sample against a
//! BSDF sample that found the same light ([`Emitters::pdf_area`], [`Emitters::pdf_environment`]).

use super::area::{AreaLights, EmitterSample, luminance, triangle_light_sample};
use super::environment::EnvironmentLight;
use super::{Light, spot::SpotLight};
use crate::Rgb;
use crate::lanes::{LANES, V3};
use crate::sampling::distribution::Distribution1D;
use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use wide::f32x8;

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
        let s = match entry {
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
        with_pick(s, pmf)
    }

    /// [`Emitters::sample`] for up to [`LANES`] points at once (`p[i]` with `u_pick[i]` and
    /// `u[i]`): the same samples, bit for bit. The points of triangle lights are found in
    /// lanes ([`triangle_light_sample`]), the other lights' per point.
    #[inline(always)]
    pub fn sample_lanes(
        &self,
        delta: &[Light],
        p: &[Vec3],
        u_pick: &[f32],
        u: &[Vec2],
    ) -> ArrayVec<Option<EmitterSample>, LANES> {
        let n = p.len();
        assert!(n <= LANES && u_pick.len() == n && u.len() == n);
        let mut out: ArrayVec<Option<EmitterSample>, LANES> = (0..n).map(|_| None).collect();
        // (lane, area light, triangle, pick probability) of the lanes that picked a triangle.
        let mut on_triangles = ArrayVec::<(usize, usize, usize, f32), LANES>::new();
        for i in 0..n {
            let Some((entry, pmf, u_rest)) = self.pick(u_pick[i]) else {
                continue;
            };
            match entry {
                Entry::Area(j) => match self.area.triangle_picked(j as usize, u_rest) {
                    Some(t) => on_triangles.push((i, j as usize, t, pmf)),
                    None => out[i] = self.sample(delta, p[i], u_pick[i], u[i]),
                },
                _ => out[i] = self.sample(delta, p[i], u_pick[i], u[i]),
            }
        }
        if on_triangles.is_empty() {
            return out;
        }
        // Lanes past those repeat the first; their results are not read.
        let of = |k: usize| on_triangles[if k < on_triangles.len() { k } else { 0 }];
        let corners: [([Vec3; 3], Vec3); LANES] =
            std::array::from_fn(|k| self.area.triangle(of(k).2));
        let corner = |c: usize| V3::gather(&std::array::from_fn(|k| corners[k].0[c]));
        let lane = |f: &dyn Fn(usize) -> f32| f32x8::new(std::array::from_fn(f));
        let (ok, wi, distance, pdf) = triangle_light_sample(
            [corner(0), corner(1), corner(2)],
            V3::gather(&std::array::from_fn(|k| corners[k].1)),
            V3::gather(&std::array::from_fn(|k| p[of(k).0])),
            (lane(&|k| u[of(k).0].x), lane(&|k| u[of(k).0].y)),
            lane(&|k| self.area.lights[of(k).1].area),
        );
        let ok = ok.to_bitmask();
        for (k, &(i, j, _, pmf)) in on_triangles.iter().enumerate() {
            if ok & (1 << k) == 0 {
                continue;
            }
            let s = EmitterSample {
                wi: wi.lane(k),
                distance: distance.as_array()[k],
                radiance: self.area.lights[j].radiance,
                pdf: pdf.as_array()[k],
                delta: false,
            };
            out[i] = with_pick(s, pmf);
        }
        out
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

/// Light sample `s` of a light picked with probability `pmf`: its density times `pmf`, if that
/// is positive and finite.
#[inline(always)]
fn with_pick(mut s: EmitterSample, pmf: f32) -> Option<EmitterSample> {
    s.pdf *= pmf;
    (s.pdf > 0.0 && s.pdf.is_finite()).then_some(s)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::point::{Falloff, PointLight};

    #[test]
    fn samples_in_lanes_are_the_samples_one_at_a_time() {
        // Two triangle lights (one of two triangles), a sphere light and a point light, seen
        // from points around them, some behind the lights.
        let mut area = AreaLights::default();
        let quad = [
            [
                Vec3::new(-1.0, 2.0, -1.0),
                Vec3::new(1.0, 2.0, -1.0),
                Vec3::new(1.0, 2.0, 1.0),
            ],
            [
                Vec3::new(-1.0, 2.0, -1.0),
                Vec3::new(1.0, 2.0, 1.0),
                Vec3::new(-1.0, 2.0, 1.0),
            ],
        ];
        area.add_triangles(0, Rgb::new(5.0, 4.0, 3.0), &quad);
        area.add_triangles(1, Rgb::gray(2.0), &[[Vec3::X, Vec3::Y * 3.0, Vec3::Z]]);
        area.add_sphere(2, Rgb::gray(1.0), Vec3::new(0.0, -3.0, 0.0), 0.5);
        let delta = [Light::Point(PointLight {
            position: Vec3::new(2.0, 1.0, 0.0),
            intensity: Rgb::gray(3.0),
            falloff: Falloff::Quadratic,
        })];
        let emitters = Emitters::new(&delta, area, None, 3, 5.0);
        let mut seed = 1u64;
        let mut next = || {
            seed = crate::sampling::mix64(seed);
            crate::sampling::to_unit_float(seed)
        };
        let mut found = 0;
        for n in (1..=LANES).cycle().take(200) {
            let p: Vec<Vec3> = (0..n)
                .map(|_| Vec3::new(next() * 6.0 - 3.0, next() * 6.0 - 3.0, next() * 6.0 - 3.0))
                .collect();
            let u_pick: Vec<f32> = (0..n).map(|_| next()).collect();
            let u: Vec<Vec2> = (0..n).map(|_| Vec2::new(next(), next())).collect();
            let lanes = emitters.sample_lanes(&delta, &p, &u_pick, &u);
            for i in 0..n {
                let alone = emitters.sample(&delta, p[i], u_pick[i], u[i]);
                assert_eq!(lanes[i], alone, "{:?} {} {:?}", p[i], u_pick[i], u[i]);
                found += usize::from(alone.is_some());
            }
        }
        assert!(found > 300, "{found}");
    }
}
