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
mod tests {
    use super::*;
    use crate::light::{Falloff, LightSample};
    use crate::sampling::uniform;
    use crate::texture::ImageTexture;

    /// The box every test scene sits in: centre (1, 0, −1), bounding radius 2√3.
    fn bounds() -> Aabb {
        Aabb::new(Vec3::new(-1.0, -2.0, -3.0), Vec3::new(3.0, 2.0, 1.0))
    }

    fn radius() -> f32 {
        bounding_sphere(bounds()).unwrap().1
    }

    /// Emitters of `delta`, `area` and `env` for the test box.
    fn emitters(delta: &[Light], area: AreaLights, env: Option<EnvironmentLight>) -> Emitters {
        Emitters::new(delta, area, env, 8, radius())
    }

    /// Photon `i` of test `seed`, with its random numbers a pure function of `(seed, i)`.
    fn photon(
        e: &Emitters,
        delta: &[Light],
        env: &dyn Fn(Vec3) -> Rgb,
        seed: u64,
        i: u64,
    ) -> Option<Photon> {
        let u = |d| uniform(seed, i, 0, d);
        e.sample_photon(
            delta,
            bounds(),
            env,
            u(0),
            Vec2::new(u(1), u(2)),
            Vec2::new(u(3), u(4)),
        )
    }

    /// The mean power of `n` photons (a `None` counts as a photon of zero power), per channel.
    fn mean_power(
        e: &Emitters,
        delta: &[Light],
        env: &dyn Fn(Vec3) -> Rgb,
        seed: u64,
        n: u64,
    ) -> [f64; 3] {
        let mut sum = [0.0f64; 3];
        for i in 0..n {
            if let Some(p) = photon(e, delta, env, seed, i) {
                assert!(p.power.is_finite() && !p.power.is_black(), "{p:?}");
                assert!((p.dir.length() - 1.0).abs() < 1e-4, "{p:?}");
                for (s, c) in sum.iter_mut().zip(p.power.to_array()) {
                    *s += f64::from(c);
                }
            }
        }
        sum.map(|s| s / n as f64)
    }

    fn assert_close(name: &str, got: [f64; 3], want: [f64; 3], tol: f64) {
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= tol * w.abs(),
                "{name}: mean photon power {got:?}, flux {want:?}"
            );
        }
    }

    fn rgb64(c: Rgb) -> [f64; 3] {
        c.to_array().map(f64::from)
    }

    fn no_env(_: Vec3) -> Rgb {
        Rgb::BLACK
    }

    fn point(falloff: Falloff) -> PointLight {
        PointLight {
            position: Vec3::new(0.5, 1.0, -0.5),
            intensity: Rgb::new(3.0, 2.0, 0.5),
            falloff,
        }
    }

    fn spot(cos_cutoff: f32, cos_start: f32) -> SpotLight {
        SpotLight {
            point: point(Falloff::Quadratic),
            direction: Vec3::new(0.3, -1.0, 0.2).normalize(),
            cos_cutoff,
            cos_start,
        }
    }

    /// A unit square at y = 1 facing down (two triangles), radiance 2, object 5.
    fn square_light(lights: &mut AreaLights) {
        let (a, b, c, d) = (
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
        );
        lights.add_triangles(5, Rgb::gray(2.0), &[[a, b, c], [a, c, d]]);
    }

    /// A smooth, coloured, everywhere-positive lat-long image, brighter towards one side.
    fn sky_image() -> ImageTexture {
        let (w, h) = (64, 32);
        let mut texels = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let phi = 2.0 * PI * (x as f32 + 0.5) / w as f32;
                let theta = PI * (y as f32 + 0.5) / h as f32;
                let glow = 1.0 + 0.8 * phi.cos() * theta.sin();
                texels.push(Rgb::new(
                    2.0 * glow,
                    1.0 + 0.5 * theta.cos(),
                    0.5 * glow * glow,
                ));
            }
        }
        ImageTexture::new(w as u32, h as u32, texels).unwrap()
    }

    #[test]
    fn point_photons_carry_four_pi_intensity_under_either_falloff() {
        for falloff in [Falloff::Quadratic, Falloff::None] {
            let l = point(falloff);
            let delta = [Light::Point(l)];
            let e = emitters(&delta, AreaLights::default(), None);
            let got = mean_power(&e, &delta, &no_env, 1, 20_000);
            let want = rgb64(l.intensity * (4.0 * PI));
            assert_close("point", got, want, 0.01);
            assert_close(
                "point total",
                rgb64(e.total_power(&delta, bounds(), Rgb::BLACK)),
                want,
                1e-5,
            );
            let p = photon(&e, &delta, &no_env, 1, 7).unwrap();
            assert_eq!((p.origin, p.from_object), (l.position, None));
        }
        // The directions cover the sphere evenly: their mean is near zero.
        let delta = [Light::Point(point(Falloff::Quadratic))];
        let e = emitters(&delta, AreaLights::default(), None);
        let mean = (0..20_000u64)
            .map(|i| photon(&e, &delta, &no_env, 2, i).unwrap().dir)
            .sum::<Vec3>()
            / 20_000.0;
        assert!(mean.length() < 0.03, "{mean}");
    }

    #[test]
    fn a_hard_spot_sends_its_cone_and_stays_inside_it() {
        let cos = 30f32.to_radians().cos();
        let l = spot(cos, cos);
        let delta = [Light::Spot(l)];
        let e = emitters(&delta, AreaLights::default(), None);
        let n = 50_000;
        let want = rgb64(l.point.intensity * (2.0 * PI * (1.0 - cos)));
        assert_close(
            "hard spot",
            mean_power(&e, &delta, &no_env, 3, n),
            want,
            0.01,
        );
        assert_close(
            "hard spot total",
            rgb64(e.total_power(&delta, bounds(), Rgb::BLACK)),
            want,
            1e-5,
        );
        for i in 0..n {
            let p = photon(&e, &delta, &no_env, 3, i).unwrap();
            assert!(
                p.dir.dot(l.direction) >= cos - 1e-5,
                "{p:?} outside the cone"
            );
            assert_eq!(p.origin, l.point.position);
        }
    }

    #[test]
    fn a_soft_spot_sends_what_its_edge_lets_through() {
        let l = spot(40f32.to_radians().cos(), 15f32.to_radians().cos());
        let delta = [Light::Spot(l)];
        let e = emitters(&delta, AreaLights::default(), None);
        // Flux = 2π ∫ I(c) dc over the cosine c from the axis, with I(c) what `illuminate`
        // delivers at distance 1 in a direction at that cosine (midpoint rule).
        let frame = Frame::from_normal(l.direction);
        let m = 100_000;
        let mut integral = [0.0f64; 3];
        for k in 0..m {
            let c = -1.0 + 2.0 * (k as f64 + 0.5) / m as f64;
            let s = (1.0 - c * c).max(0.0).sqrt();
            let dir = frame.to_world(Vec3::new(s as f32, 0.0, c as f32));
            let at = l.point.position + dir;
            if let Some(LightSample { intensity, .. }) = l.illuminate(at) {
                for (acc, v) in integral.iter_mut().zip(rgb64(intensity)) {
                    *acc += v * 2.0 / m as f64;
                }
            }
        }
        let want = integral.map(|v| 2.0 * std::f64::consts::PI * v);
        // The fade matters: a hard edge at the cutoff would send almost twice as much.
        let hard = 2.0 * std::f64::consts::PI * (1.0 - f64::from(l.cos_cutoff));
        assert!(want[0] < 0.9 * hard * 3.0, "{want:?}");
        let got = mean_power(&e, &delta, &no_env, 4, 200_000);
        assert_close("soft spot", got, want, 0.01);
        assert_close(
            "soft spot total",
            rgb64(e.total_power(&delta, bounds(), Rgb::BLACK)),
            want,
            2e-3,
        );
    }

    #[test]
    fn directional_photons_cross_the_scene_from_outside() {
        let l = DirectionalLight {
            direction: Vec3::new(-0.2, -1.0, 0.4).normalize(),
            intensity: Rgb::new(1.5, 1.0, 0.25),
        };
        let delta = [Light::Directional(l)];
        let e = emitters(&delta, AreaLights::default(), None);
        let r = radius();
        let want = rgb64(l.intensity * (PI * r * r));
        assert_close(
            "directional",
            mean_power(&e, &delta, &no_env, 5, 20_000),
            want,
            0.01,
        );
        assert_close(
            "directional total",
            rgb64(e.total_power(&delta, bounds(), Rgb::BLACK)),
            want,
            1e-5,
        );
        let center = bounds().center();
        let mut offsets = Vec3::ZERO;
        for i in 0..20_000 {
            let p = photon(&e, &delta, &no_env, 5, i).unwrap();
            assert!((p.dir - l.direction).length() < 1e-6, "{p:?}");
            assert_crosses_sphere(&p, center, r);
            offsets += p.origin - (center - l.direction * r);
        }
        // The disc is centred on the sphere's axis along the light.
        assert!((offsets / 20_000.0).length() < 0.02 * r, "{offsets}");
    }

    /// `p` starts outside the sphere (or on it) and travels into it.
    fn assert_crosses_sphere(p: &Photon, center: Vec3, r: f32) {
        let to_center = center - p.origin;
        assert!(to_center.length() >= r * (1.0 - 1e-5), "{p:?} inside");
        let along = to_center.dot(p.dir);
        assert!(along > 0.0, "{p:?} leaves");
        let miss2 = to_center.length_squared() - along * along;
        assert!(miss2 <= r * r * (1.0 + 1e-4), "{p:?} misses the sphere");
    }

    #[test]
    fn triangle_photons_leave_the_front_of_the_surface() {
        let mut area = AreaLights::default();
        square_light(&mut area);
        // A third, smaller triangle tilted towards +x, so the pick by area matters.
        let tilted = [
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.5, 0.0, 1.0),
            Vec3::new(2.5, 1.0, 0.0),
        ];
        let [a, b, c] = tilted;
        let mut tris = area.triangles.clone();
        tris.push(tilted);
        let mut area = AreaLights::default();
        area.add_triangles(5, Rgb::new(2.0, 1.0, 0.5), &tris);
        let total_area = 1.0 + 0.5 * (b - a).cross(c - a).length();
        let e = emitters(&[], area.clone(), None);
        let want = rgb64(Rgb::new(2.0, 1.0, 0.5) * (PI * total_area));
        assert_close(
            "triangles",
            mean_power(&e, &[], &no_env, 6, 50_000),
            want,
            0.01,
        );
        assert_close(
            "triangles total",
            rgb64(e.total_power(&[], bounds(), Rgb::BLACK)),
            want,
            1e-5,
        );
        let mut on_tilted = 0;
        for i in 0..20_000 {
            let p = photon(&e, &[], &no_env, 6, i).unwrap();
            assert_eq!(p.from_object, Some(5));
            // On one of the triangles, on the side its winding faces.
            let on = tris.iter().find(|t| {
                let n = (t[1] - t[0]).cross(t[2] - t[0]);
                let inside = (0..3).all(|k| {
                    let (e0, e1) = (t[k], t[(k + 1) % 3]);
                    (e1 - e0).cross(p.origin - e0).dot(n) >= -1e-4 * n.length()
                });
                // Stepped off the surface to its front by the spawn offset, no further.
                let off = n.normalize().dot(p.origin - t[0]);
                inside && (0.0..1e-4).contains(&off)
            });
            let t = on.unwrap_or_else(|| panic!("{p:?} is on no triangle"));
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
            assert!(p.dir.dot(n) > 0.0, "{p:?} leaves the back");
            on_tilted += usize::from(t == &tilted);
        }
        // The tilted triangle's share of the area.
        let share = on_tilted as f32 / 20_000.0;
        let expected = (total_area - 1.0) / total_area;
        assert!((share - expected).abs() < 0.02, "{share} vs {expected}");
    }

    #[test]
    fn sphere_photons_leave_outwards_from_its_surface() {
        let (center, r) = (Vec3::new(1.0, 0.5, -1.0), 0.75);
        let mut area = AreaLights::default();
        area.add_sphere(2, Rgb::new(1.0, 3.0, 0.5), center, r);
        let e = emitters(&[], area, None);
        let want = rgb64(Rgb::new(1.0, 3.0, 0.5) * (PI * 4.0 * PI * r * r));
        assert_close(
            "sphere",
            mean_power(&e, &[], &no_env, 7, 20_000),
            want,
            0.01,
        );
        assert_close(
            "sphere total",
            rgb64(e.total_power(&[], bounds(), Rgb::BLACK)),
            want,
            1e-5,
        );
        let mut mean_cos = 0.0;
        for i in 0..20_000 {
            let p = photon(&e, &[], &no_env, 7, i).unwrap();
            let n = (p.origin - center) / r;
            assert!(
                (0.0..1e-4).contains(&(n.length() - 1.0)),
                "{p:?} off the sphere"
            );
            assert!(p.dir.dot(n) > 0.0, "{p:?} goes in");
            assert_eq!(p.from_object, Some(2));
            mean_cos += p.dir.dot(n) / 20_000.0;
        }
        // Cosine-weighted: E[cos θ] = 2/3 (a uniform hemisphere would give 1/2).
        assert!((mean_cos - 2.0 / 3.0).abs() < 0.01, "{mean_cos}");
    }

    #[test]
    fn a_constant_environment_sends_its_flux_into_the_bounding_sphere() {
        let c = Rgb::new(0.5, 1.0, 2.0);
        let e = emitters(&[], AreaLights::default(), EnvironmentLight::constant(c));
        let env = move |_: Vec3| c;
        let r = radius();
        // Each of the 4π directions lights the cross-section πr² with radiance L.
        let want = rgb64(c * (4.0 * PI * PI * r * r));
        assert_close(
            "constant environment",
            mean_power(&e, &[], &env, 8, 20_000),
            want,
            0.01,
        );
        assert_close(
            "constant environment total",
            rgb64(e.total_power(&[], bounds(), c)),
            want,
            1e-5,
        );
        let center = bounds().center();
        let mut mean_dir = Vec3::ZERO;
        for i in 0..20_000 {
            let p = photon(&e, &[], &env, 8, i).unwrap();
            assert_crosses_sphere(&p, center, r);
            mean_dir += p.dir / 20_000.0;
        }
        assert!(mean_dir.length() < 0.03, "{mean_dir}");
    }

    #[test]
    fn an_image_environment_sends_its_mean_radiance_into_the_bounding_sphere() {
        let image = sky_image();
        let e = emitters(&[], AreaLights::default(), EnvironmentLight::image(&image));
        let env = |d: Vec3| image.lookup_direction(d);
        let r = radius();
        let mean = image.latlong_mean();
        let want = rgb64(mean * (4.0 * PI * PI * r * r));
        assert_close(
            "image environment",
            mean_power(&e, &[], &env, 9, 200_000),
            want,
            0.01,
        );
        assert_close(
            "image environment total",
            rgb64(e.total_power(&[], bounds(), mean)),
            want,
            1e-5,
        );
        let center = bounds().center();
        for i in 0..5_000 {
            let p = photon(&e, &[], &env, 9, i).unwrap();
            assert_crosses_sphere(&p, center, r);
        }
    }

    #[test]
    fn several_lights_together_send_the_sum_of_their_fluxes() {
        let dir = DirectionalLight {
            direction: Vec3::new(0.0, -1.0, 0.3).normalize(),
            intensity: Rgb::new(0.2, 0.3, 0.1),
        };
        let soft = spot(50f32.to_radians().cos(), 20f32.to_radians().cos());
        let delta = [
            Light::Point(point(Falloff::Quadratic)),
            Light::Spot(soft),
            Light::Directional(dir),
        ];
        let mut area = AreaLights::default();
        square_light(&mut area);
        area.add_sphere(2, Rgb::new(1.0, 3.0, 0.5), Vec3::new(1.0, 0.5, -1.0), 0.5);
        let sky = Rgb::new(0.05, 0.1, 0.2);
        let e = emitters(&delta, area, EnvironmentLight::constant(sky));
        let env = move |_: Vec3| sky;
        let r = radius();
        let (c_cut, c_start) = (f64::from(soft.cos_cutoff), f64::from(soft.cos_start));
        let spot_share = (1.0 - c_start) + 0.5 * (c_start - c_cut);
        let mut want = [0.0f64; 3];
        let fluxes = [
            (point(Falloff::Quadratic).intensity, 4.0 * PI),
            (soft.point.intensity, 2.0 * PI * spot_share as f32),
            (dir.intensity, PI * r * r),
            (Rgb::gray(2.0), PI),
            (Rgb::new(1.0, 3.0, 0.5), PI * 4.0 * PI * 0.25),
            (sky, 4.0 * PI * PI * r * r),
        ];
        for (c, k) in fluxes {
            for (w, v) in want.iter_mut().zip(rgb64(c * k)) {
                *w += v;
            }
        }
        let got = mean_power(&e, &delta, &env, 10, 400_000);
        assert_close("all lights", got, want, 0.01);
        assert_close(
            "all lights total",
            rgb64(e.total_power(&delta, bounds(), sky)),
            want,
            1e-4,
        );
    }

    #[test]
    fn photons_and_next_event_estimation_agree_on_irradiance() {
        // The square light above a diffuse floor y = 0. Photons crossing a disc of radius ρ
        // around p give the mean irradiance over the disc (flux / area); next-event estimation
        // at points uniform over the same disc gives the same mean, E = Le·cos / pdf.
        let mut area = AreaLights::default();
        square_light(&mut area);
        let e = emitters(&[], area, None);
        let (p, rho) = (Vec3::new(0.3, 0.0, 0.6), 0.15f32);
        let n = 3_000_000u64;
        let mut flux = 0.0f64;
        for i in 0..n {
            let Some(ph) = photon(&e, &[], &no_env, 11, i) else {
                continue;
            };
            if ph.dir.y >= 0.0 {
                continue;
            }
            let x = ph.origin + ph.dir * (-ph.origin.y / ph.dir.y);
            if (x - p).length_squared() < rho * rho {
                flux += f64::from(ph.power.r);
            }
        }
        let disc = std::f64::consts::PI * f64::from(rho * rho);
        let by_photons = flux / n as f64 / disc;
        let m = 200_000u64;
        let mut by_nee = 0.0f64;
        for i in 0..m {
            let u = |d| uniform(12, i, 0, d);
            let q = square_to_concentric_disk(Vec2::new(u(0), u(1))) * rho;
            let x = p + Vec3::new(q.x, 0.0, q.y);
            if let Some(s) = e.sample(&[], x, u(2), Vec2::new(u(3), u(4))) {
                by_nee += f64::from(s.radiance.r * s.wi.y.max(0.0) / s.pdf);
            }
        }
        by_nee /= m as f64;
        assert!(
            (by_photons - by_nee).abs() < 0.025 * by_nee,
            "photons {by_photons} vs next-event estimation {by_nee}"
        );
    }

    #[test]
    fn degenerate_lights_send_nothing_and_never_nan() {
        let draw = |e: &Emitters, delta: &[Light], b: Aabb, u: f32| {
            e.sample_photon(
                delta,
                b,
                |_| Rgb::WHITE,
                u,
                Vec2::splat(u),
                Vec2::new(u, 1.0 - u),
            )
        };
        let us = [0.0, 1e-7, 0.5, 1.0 - f32::EPSILON / 2.0];
        // No lights at all.
        let none = emitters(&[], AreaLights::default(), None);
        assert!(us.iter().all(|&u| draw(&none, &[], bounds(), u).is_none()));
        // Lights at infinity over an empty, a NaN or a one-point scene.
        let dir = [Light::Directional(DirectionalLight {
            direction: Vec3::NEG_Y,
            intensity: Rgb::WHITE,
        })];
        let sky = emitters(
            &[],
            AreaLights::default(),
            EnvironmentLight::constant(Rgb::WHITE),
        );
        let flat = Aabb::new(Vec3::ONE, Vec3::ONE);
        let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE);
        for b in [Aabb::EMPTY, flat, nan] {
            for &u in &us {
                assert!(draw(&emitters(&dir, AreaLights::default(), None), &dir, b, u).is_none());
                assert!(draw(&sky, &[], b, u).is_none());
            }
            assert!(sky.total_power(&[], b, Rgb::WHITE).is_black());
        }
        // Black, zero-width and directionless lights.
        let black = PointLight {
            intensity: Rgb::BLACK,
            ..point(Falloff::Quadratic)
        };
        let needle = spot(1.0, 1.0);
        let aimless = SpotLight {
            direction: Vec3::ZERO,
            ..spot(0.5, 0.9)
        };
        let still = DirectionalLight {
            direction: Vec3::ZERO,
            intensity: Rgb::WHITE,
        };
        for l in [
            Light::Point(black),
            Light::Spot(needle),
            Light::Spot(aimless),
            Light::Directional(still),
        ] {
            let delta = [l.clone()];
            let e = emitters(&delta, AreaLights::default(), None);
            for &u in &us {
                assert!(draw(&e, &delta, bounds(), u).is_none(), "{l:?}");
            }
        }
        // Every light at the edges of the unit square: a photon is finite, or there is none.
        let mut area = AreaLights::default();
        square_light(&mut area);
        area.add_sphere(2, Rgb::WHITE, Vec3::ZERO, 0.5);
        let delta = [
            Light::Point(point(Falloff::None)),
            Light::Spot(spot(-1.0, 0.5)),
            dir[0].clone(),
        ];
        let image = sky_image();
        let e = emitters(&delta, area, EnvironmentLight::image(&image));
        for &a in &us {
            for &b in &us {
                for &c in &us {
                    let p = e.sample_photon(
                        &delta,
                        bounds(),
                        |d| image.lookup_direction(d),
                        a,
                        Vec2::new(b, c),
                        Vec2::new(c, b),
                    );
                    if let Some(p) = p {
                        assert!(p.power.is_finite() && p.origin.is_finite(), "{p:?}");
                        assert!((p.dir.length() - 1.0).abs() < 1e-4, "{p:?}");
                    }
                }
            }
        }
    }
}
