//! Emission: photons leaving the lights, for photon mapping and other light-tracing methods.
//!
//! Where next-event estimation asks "how much light reaches this point?", emission asks "where
//! does light start and which way does it go?". [`Emitters::sample_photon`] draws one
//! [`Photon`] from all of a scene's lights: a light picked in proportion to its power (the same
//! pick as [`Emitters::sample`]), a point on it and a direction out of it. A photon's `power`
//! is a flux (watts-like): the light's emitted radiance or intensity times the cosine, over the
//! densities of every choice made,
//!
//! ```text
//! power = Le · |cos θ| / (p_pick · p_position · p_direction),
//! ```
//!
//! so that the mean power of many photons is the scene's total emitted flux (see
//! [`Emitters::total_power`]), and a photon map's estimate is the sum of the powers of the
//! photons found divided by **the number of photons drawn**, the ones that came back `None`
//! included (they carry nothing; leaving them out would bias the estimate upwards).
//!
//! Per kind (`r` is the radius of the scene's bounding sphere, see [`bounding_sphere`]):
//!
//! | light | origin | direction | power (before `/ p_pick`) |
//! | --- | --- | --- | --- |
//! | point | its position | uniform over the sphere | `4π·I` |
//! | spot | its position | uniform in the cone of `cos_cutoff` | `I · edge(cos) · 2π(1 − cos_cutoff)` |
//! | directional | uniform on a disc of radius `r` facing the light, `r` behind the sphere's centre | the light's | `E · πr²` |
//! | area triangles | a triangle by area, a uniform point on it | cosine-weighted about the front (winding) normal | `Le · π · A` |
//! | area sphere | uniform on the sphere | cosine-weighted about the outward normal | `Le · π · 4πr_s²` |
//! | environment | uniform on a disc of radius `r` perpendicular to the photon, `r` behind the centre | `−d`, `d` drawn as next-event estimation draws it | `L(d) · πr² / pdf(d)` |
//!
//! A point or spot light with [`Falloff::None`](super::Falloff::None) (the classic Whitted
//! model, where intensity does not fall off with distance) emits no finite flux; it is treated
//! here as [`Falloff::Quadratic`](super::Falloff::Quadratic) with the same intensity.
//!
//! Lights at infinity send their photons from the disc of the scene's bounding sphere that
//! faces them, so every photon crosses the sphere and the flux counted is the flux into it: a
//! constant environment `L` sends `4π · πr² · L` (each of the `4π` directions lights the
//! sphere's cross-section `πr²`). [`super::EnvironmentLight::power`], used only to pick lights,
//! counts `π · πr² · L` (the flux into one side of a disc); picking is unbiased whatever the
//! weights, so this only changes how often the environment is picked.
//!
//! Photons of area lights start just off the light's surface, to its front, moved by
//! [`crate::spawn::offset_origin`] (the crate's one offset: the point's rounding error along
//! the normal, then a few ulps), and name the light in [`Photon::from_object`]. Photons from
//! lights at infinity start on the disc of the bounding sphere of the scene's bounded shapes:
//! infinite planes beyond it get no photons from them (their direct light is next-event
//! estimation's, unaffected; only light they would bounce onto the scene is missed).
//!
//! Random numbers: `u_pick` picks the light and, rescaled, a light's triangle; `u_pos` the
//! point (on the shape, or on the disc of a light at infinity); `u_dir` the direction.

use super::Light;
use super::area::{AreaLights, EmitterShape};
use super::directional::DirectionalLight;
use super::emitters::{Emitters, Entry};
use super::environment::EnvironmentLight;
use super::image_light::ImageLight;
use super::photometric::PhotometricLight;
use super::point::PointLight;
use super::spot::SpotLight;
use crate::Rgb;
use crate::bsdf::Frame;
use crate::sampling::warp::{
    square_to_concentric_disk, square_to_cosine_hemisphere, square_to_uniform_cone,
    square_to_uniform_sphere, square_to_uniform_triangle,
};
use glam::{Vec2, Vec3};
use lucent_accel::Aabb;
use std::f32::consts::PI;

/// A photon leaving a light: where, which way, and the power it carries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Where it starts: on the light's surface, at a point light, or (lights at infinity) on a
    /// disc just outside the scene's bounding sphere.
    pub origin: Vec3,
    /// Unit direction it travels in.
    pub dir: Vec3,
    /// Its flux: `Le · |cos| / (p_pick · p_position · p_direction)` (see the module docs).
    /// Finite, and never black.
    pub power: Rgb,
    /// For a photon of an area light, the scene object it leaves (to step off it); `None`
    /// for the other lights.
    pub from_object: Option<u32>,
}

/// The scene's bounding sphere as the lights see it: the centre of `bounds` and half its
/// diagonal (the radius [`Emitters::new`] is given by the scene builder). `None` for an empty
/// box, a NaN or infinite one, or a single point.
pub fn bounding_sphere(bounds: Aabb) -> Option<(Vec3, f32)> {
    if bounds.is_empty() || bounds.has_nan() {
        return None;
    }
    let center = bounds.center();
    let radius = 0.5 * bounds.extent().length();
    (center.is_finite() && radius.is_finite() && radius > 0.0).then_some((center, radius))
}

impl Emitters {
    /// One photon from all the scene's lights: a light picked in proportion to its power (the
    /// same pick as [`Emitters::sample`]), a point on it and a direction.
    ///
    /// `delta` are the scene's point-like lights (`Scene::lights`, as given to
    /// [`Emitters::new`]); `bounds` the scene's box, whose bounding sphere the photons of lights
    /// at infinity start on, facing in; `env_radiance` the environment's radiance arriving
    /// from a unit direction (`Scene::background_along`). `u_pick` picks the light (and a
    /// triangle), `u_pos` the point, `u_dir` the direction, all in `[0, 1)`.
    ///
    /// `None` when the draw carries nothing: no lights, a light of zero power, a light at
    /// infinity with empty `bounds`, a direction of zero density or on the rim of the light's
    /// cone or hemisphere, a non-finite result. Such a draw still counts as a photon emitted
    /// (of zero power) when estimates divide by the number of photons.
    pub fn sample_photon(
        &self,
        delta: &[Light],
        bounds: Aabb,
        env_radiance: impl Fn(Vec3) -> Rgb,
        u_pick: f32,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<Photon> {
        let (entry, pmf, u_rest) = self.pick(u_pick)?;
        if pmf.is_nan() || pmf <= 0.0 {
            return None;
        }
        let mut photon = match entry {
            Entry::Delta(j) => match delta.get(j as usize)? {
                Light::Point(l) => point_photon(l, u_dir),
                Light::Spot(l) => spot_photon(l, u_dir),
                Light::Directional(l) => directional_photon(l, bounds, u_pos),
                Light::Photometric(l) => photometric_photon(l, u_dir),
                Light::Image(l) => image_photon(l, u_dir),
            },
            Entry::Area(j) => area_photon(&self.area, j as usize, u_rest, u_pos, u_dir),
            Entry::Environment => environment_photon(
                self.environment.as_ref()?,
                bounds,
                env_radiance,
                u_pos,
                u_dir,
            ),
        }?;
        photon.power = photon.power / pmf;
        let valid = photon.power.is_finite()
            && !photon.power.is_black()
            && photon.origin.is_finite()
            && photon.dir.is_finite();
        valid.then_some(photon)
    }

    /// The total flux the lights emit, as RGB (the mean power of
    /// [`Emitters::sample_photon`]'s photons): `4π·I` for a point light, `2π·I·∫edge(cos)
    /// dcos` for a spot light, `E·πr²` for a directional light, `π·Le·A` for an area light,
    /// and `4π·πr²·env_mean` for the environment (`env_mean` its mean radiance over
    /// directions, e.g. [`crate::texture::ImageTexture::latlong_mean`] or the background
    /// colour), where `r` is the radius of `bounds`' bounding sphere (lights at infinity send
    /// nothing into an empty scene).
    pub fn total_power(&self, delta: &[Light], bounds: Aabb, env_mean: Rgb) -> Rgb {
        let r2 = bounding_sphere(bounds).map_or(0.0, |(_, r)| r * r);
        let mut sum = Rgb::BLACK;
        for l in delta {
            sum += match l {
                Light::Point(p) => p.intensity * (4.0 * PI),
                Light::Spot(s) => s.point.intensity * (2.0 * PI * spot_cone_integral(s)),
                Light::Directional(d) => d.intensity * (PI * r2),
                Light::Photometric(l) => l.point.intensity * l.profile.total(),
                Light::Image(l) => l.power(),
            };
        }
        for l in &self.area.lights {
            sum += l.radiance * (PI * l.area);
        }
        if self.environment.is_some() {
            sum += env_mean * (4.0 * PI * PI * r2);
        }
        sum
    }
}

/// A photon of a point light: `I / (1/4π)` in a uniform direction.
fn point_photon(l: &PointLight, u_dir: Vec2) -> Option<Photon> {
    Some(Photon {
        origin: l.position,
        dir: square_to_uniform_sphere(u_dir),
        power: l.intensity * (4.0 * PI),
        from_object: None,
    })
}

/// A photon of a photometric light: a direction drawn in proportion to its profile's
/// tabulated intensity, carrying `I(ω) / p(ω)`.
fn photometric_photon(l: &PhotometricLight, u_dir: Vec2) -> Option<Photon> {
    let (local, pdf) = l.profile.sample(u_dir)?;
    let intensity = l.profile.intensity(local);
    if pdf <= 0.0 || intensity <= 0.0 {
        return None;
    }
    Some(Photon {
        origin: l.point.position,
        // The frame's inverse is its transpose (a rotation).
        dir: (l.to_luminaire.transpose() * local).normalize(),
        power: l.point.intensity * (intensity / pdf),
        from_object: None,
    })
}

/// A photon of an image light: a direction drawn from its image's distribution, carrying
/// `I(ω) / p(ω)`.
fn image_photon(l: &ImageLight, u_dir: Vec2) -> Option<Photon> {
    let (local, pdf) = l.image.sample(u_dir)?;
    let intensity = l.image.intensity(local);
    if intensity.is_black() {
        return None;
    }
    Some(Photon {
        origin: l.point.position,
        // The frame's inverse is its transpose (orthonormal).
        dir: (l.to_light.transpose() * local).normalize(),
        power: l.point.intensity * intensity * (1.0 / pdf),
        from_object: None,
    })
}

/// The smooth edge of a spot light at `cos` from its axis, exactly as
/// [`SpotLight::illuminate`] applies it.
fn spot_edge(l: &SpotLight, cos: f32) -> f32 {
    l.cone().edge(cos)
}

/// `∫ edge(c) dc` over the cosines `c ∈ [−1, 1]`: the spot light's flux is `2π·I` times this.
/// With the smoothstep's antiderivative `S(x) = x³ − x⁴/2` (`S(1) = 1/2`), a full fade
/// contributes half its width.
fn spot_cone_integral(l: &SpotLight) -> f32 {
    let lo = l.cos_cutoff.clamp(-1.0, 1.0);
    if l.cos_start <= l.cos_cutoff {
        return 1.0 - lo;
    }
    let start = l.cos_start.clamp(lo, 1.0);
    let width = l.cos_start - l.cos_cutoff;
    let s = |c: f32| {
        let x = (c - l.cos_cutoff) / width;
        x * x * x - 0.5 * x * x * x * x
    };
    width * (s(start) - s(lo)) + (1.0 - start)
}

/// A photon of a spot light: uniform in its cone (density `1 / 2π(1 − cos_cutoff)`), weighted
/// by the edge.
fn spot_photon(l: &SpotLight, u_dir: Vec2) -> Option<Photon> {
    let axis = l.direction.normalize_or_zero();
    let cos_max = l.cos_cutoff.clamp(-1.0, 1.0);
    let solid_angle = 2.0 * PI * (1.0 - cos_max);
    if axis == Vec3::ZERO || solid_angle.is_nan() || solid_angle <= 0.0 {
        return None;
    }
    let local = square_to_uniform_cone(u_dir, cos_max);
    let edge = spot_edge(l, local.z);
    if edge <= 0.0 {
        return None;
    }
    Some(Photon {
        origin: l.point.position,
        dir: Frame::from_normal(axis).to_world(local),
        power: l.point.intensity * (edge * solid_angle),
        from_object: None,
    })
}

/// A point uniform on the disc of radius `r` perpendicular to unit `travel`, centred `r`
/// behind `center`: the face of the bounding sphere that light travelling along `travel`
/// enters by.
fn disc_origin(center: Vec3, r: f32, travel: Vec3, u_pos: Vec2) -> Vec3 {
    let frame = Frame::from_normal(travel);
    let d = square_to_concentric_disk(u_pos) * r;
    center - travel * r + frame.s * d.x + frame.t * d.y
}

/// A photon of a directional light: uniform on the bounding sphere's disc (density `1/πr²`),
/// along the light.
fn directional_photon(l: &DirectionalLight, bounds: Aabb, u_pos: Vec2) -> Option<Photon> {
    let (center, r) = bounding_sphere(bounds)?;
    let dir = l.direction.normalize_or_zero();
    if dir == Vec3::ZERO {
        return None;
    }
    Some(Photon {
        origin: disc_origin(center, r, dir, u_pos),
        dir,
        power: l.intensity * (PI * r * r),
        from_object: None,
    })
}

/// A photon of area light `i`: a uniform point (density `1/A`), a cosine-weighted direction
/// about the front normal (density `cos/π`), so `Le·cos / (cos/π · 1/A) = Le·π·A`.
fn area_photon(
    area: &AreaLights,
    i: usize,
    u_tri: f32,
    u_pos: Vec2,
    u_dir: Vec2,
) -> Option<Photon> {
    let light = area.lights.get(i)?;
    let (origin, normal) = match &light.shape {
        EmitterShape::Triangles { first, areas } => {
            // The same choice of triangle as `AreaLights::sample`.
            let (k, _, _) = areas.sample_discrete(u_tri);
            let [a, b, c] = *area.triangles.get(*first as usize + k)?;
            let (b0, b1) = square_to_uniform_triangle(u_pos);
            let x = a * b0 + b * b1 + c * (1.0 - b0 - b1);
            (x, (b - a).cross(c - a).normalize_or_zero())
        }
        EmitterShape::Sphere { center, radius } => {
            let n = square_to_uniform_sphere(u_pos);
            (*center + n * radius.abs(), n)
        }
    };
    let local = square_to_cosine_hemisphere(u_dir);
    // The rim of the hemisphere (cos = 0) carries nothing and would not leave the surface.
    if normal == Vec3::ZERO || local.z.is_nan() || local.z <= 0.0 {
        return None;
    }
    // Off the surface by its rounding error and a few ulps (the one policy of
    // `crate::spawn`), to the front it leaves by: a photon does not meet its own light.
    let error = Vec3::splat(32.0 * f32::EPSILON) * (origin.abs() + Vec3::splat(light.area.sqrt()));
    Some(Photon {
        origin: crate::spawn::offset_origin(origin, normal, error),
        dir: Frame::from_normal(normal).to_world(local),
        power: light.radiance * (PI * light.area),
        from_object: Some(light.object),
    })
}

/// A photon of the environment: a direction of arrival `d` as next-event estimation draws it
/// (solid-angle density `pdf(d)`), the photon travelling along `−d` from the bounding sphere's
/// disc facing `d` (density `1/πr²`), so `L(d) · πr² / pdf(d)`.
fn environment_photon(
    env: &EnvironmentLight,
    bounds: Aabb,
    env_radiance: impl Fn(Vec3) -> Rgb,
    u_pos: Vec2,
    u_dir: Vec2,
) -> Option<Photon> {
    let (center, r) = bounding_sphere(bounds)?;
    let (d, pdf) = env.sample(u_dir)?;
    if pdf.is_nan() || pdf <= 0.0 || pdf.is_infinite() {
        return None;
    }
    let dir = -d;
    Some(Photon {
        origin: disc_origin(center, r, dir, u_pos),
        dir,
        power: env_radiance(d) * (PI * r * r / pdf),
        from_object: None,
    })
}

#[cfg(test)]
mod tests;
