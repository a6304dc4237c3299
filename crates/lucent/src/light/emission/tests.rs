//! Tests of photon emission: every kind of light, its photons' power and directions.

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
