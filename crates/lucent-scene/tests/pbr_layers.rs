//! The `pbr` keys that glTF's `KHR_materials_diffuse_transmission`, `KHR_materials_unlit` and
//! `KHR_materials_anisotropy`'s direction texture become, rendered: a square facing the camera
//! head on, lit from behind, from in front or not at all.
//!
//! Head on, with the light along the view, the half vector of the specular layer is the normal
//! and its Fresnel weight is `f0 = 0.04` exactly: a translucent square of colour `c` lit from
//! behind by a directional light of irradiance `π` shows `(1 − 0.04)·c`. Tolerances: 1% on
//! those (the light is a delta, the square's points all see it the same way, so only the
//! camera's pixel filter varies).

use lucent::Rgb;
use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::SceneFile;
use std::path::PathBuf;

/// The mean colour of the image of a square `[-1, 1]²` in z = 0 seen from `eye_z` on the z
/// axis (its material `material`, lights `lights`), filling the frame.
fn square(material: &str, lights: &str, eye_z: f32, integrator: &str) -> Rgb {
    let text = format!(
        r#"
[image]
width = 8
height = 8
samples = 16

[camera]
eye = [0, 0, {eye_z}]
look_at = [0, 0, 0]
fov = 20

[render]
integrator = "{integrator}"

{lights}

[[material]]
name = "m"
{material}

[[object]]
type = "rectangle"
material = "m"
"#
    );
    let file = SceneFile::parse(PathBuf::from("square.toml"), PathBuf::from("."), text).unwrap();
    let loaded = file.build().unwrap();
    let settings = RenderSettings {
        seed: 3,
        ..loaded.settings
    };
    let film = render(&loaded.scene, &settings, None, &Hooks::none())
        .unwrap()
        .film;
    let mut sum = Rgb::BLACK;
    for y in 0..8 {
        for x in 0..8 {
            sum += film.pixel(x, y);
        }
    }
    sum * (1.0 / 64.0)
}

fn assert_close(got: Rgb, want: Rgb, tol: f32) {
    for (g, w) in got.to_array().into_iter().zip(want.to_array()) {
        assert!((g - w).abs() <= tol * w.max(0.05), "{got:?} vs {want:?}");
    }
}

/// A directional light of irradiance π travelling along `z`.
fn light(z: f32) -> String {
    format!("[[light]]\ntype = \"directional\"\ndirection = [0, 0, {z}]\nintensity = 3.14159265")
}

#[test]
fn a_translucent_square_passes_its_colour_to_the_far_side() {
    let leaf = r#"type = "pbr"
metallic = 0
base_color = [0.9, 0.9, 0.9]
diffuse_transmission = 1
diffuse_transmission_color = [1.0, 0.5, 0.25]"#;
    // Lit from behind (the light travels +z, towards the camera's side).
    let through = square(leaf, &light(1.0), 3.0, "path");
    assert_close(through, Rgb::new(1.0, 0.5, 0.25) * 0.96, 0.01);
    // Half the diffuse light passes; the other half is reflected.
    let half = leaf.replace("diffuse_transmission = 1", "diffuse_transmission = 0.5");
    let through_half = square(&half, &light(1.0), 3.0, "path");
    assert_close(through_half, Rgb::new(1.0, 0.5, 0.25) * 0.48, 0.01);
    // Lit from the front, the reflected half: the diffuse (1 − 0.04)·0.9/2, plus the
    // specular's head-on reflection of a delta light, which a rough square spreads thin.
    let front = square(&half, &light(-1.0), 3.0, "path");
    let opaque = square(
        leaf.split("diffuse_transmission").next().unwrap(),
        &light(-1.0),
        3.0,
        "path",
    );
    let diffuse = Rgb::gray(0.96 * 0.9 * 0.5);
    assert_close(front - (opaque - diffuse * 2.0), diffuse, 0.01);
    // Without the extension nothing comes through.
    let plain = square(
        leaf.split("diffuse_transmission").next().unwrap(),
        &light(1.0),
        3.0,
        "path",
    );
    assert_eq!(plain, Rgb::BLACK);
}

#[test]
fn an_unlit_two_sided_square_shows_its_colour_from_both_sides_under_every_integrator() {
    let unlit = r#"type = "diffuse"
reflectance = 0
emission = [0.2, 0.4, 0.6]
emits_back = true"#;
    for integrator in ["whitted", "path"] {
        for eye in [3.0, -3.0] {
            let seen = square(unlit, "", eye, integrator);
            assert_close(seen, Rgb::new(0.2, 0.4, 0.6), 1e-4);
        }
    }
    // One-sided emission (lucent's default, Mitsuba's) is black from behind.
    let front_only = unlit.replace("emits_back = true", "");
    assert_eq!(square(&front_only, "", -3.0, "path"), Rgb::BLACK);
}

#[test]
fn a_direction_map_turns_the_anisotropy_as_the_rotation_does() {
    let brushed = |turn: &str| {
        format!("type = \"pbr\"\nmetallic = 1\nroughness = 0.5\nanisotropy = 0.9\n{turn}")
    };
    let lit = "[[light]]\ntype = \"point\"\nposition = [0.7, 0.2, 1.5]\nintensity = 3";
    let by_map = square(
        &brushed("anisotropy_direction = [0.5, 1.0, 0.0]"),
        lit,
        3.0,
        "path",
    );
    let by_rotation = square(&brushed("anisotropy_rotation = 90"), lit, 3.0, "path");
    let unturned = square(&brushed(""), lit, 3.0, "path");
    assert_close(by_map, by_rotation, 1e-4);
    assert!(
        (by_map - unturned).max_channel().abs() > 0.01 * unturned.max_channel(),
        "the turn shows: {by_map:?} vs {unturned:?}"
    );
}
