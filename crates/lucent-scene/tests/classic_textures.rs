//! The classic integrators (ray casting, Whitted) honour the texture slots that are not
//! colours of the shading formula: a cut-out's opacity (camera rays and shadow rays pass
//! where it is cut away) and a textured emission (seen as the texture, not as its white
//! scale).

use lucent::render::{Hooks, render};
use lucent_scene::{LoadOptions, SceneFile};
use std::sync::atomic::AtomicBool;

/// The 32×32 linear image of scene `text`.
fn render_text(name: &str, text: &str) -> Vec<[f32; 3]> {
    let dir = std::env::temp_dir().join(format!("lucent-classic-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let loaded = SceneFile::read_with(&path, &LoadOptions::default())
        .unwrap()
        .build()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let cancel = AtomicBool::new(false);
    let hooks = Hooks {
        cancel: &cancel,
        progress: &|_, _| {},
        checkpoint: None,
    };
    let film = render(&loaded.scene, &loaded.settings, None, &hooks)
        .unwrap()
        .film;
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y).to_array())
        .collect()
}

/// A camera looking down −z at a green wall (z = −2) behind a red card (z = −1) that covers
/// the view, with `card` extra keys on the card's material.
fn card_scene(integrator: &str, card: &str) -> String {
    format!(
        r#"
[image]
width = 32
height = 32
samples = 4

[camera]
eye = [0, 0, 0]
look_at = [0, 0, -1]
fov = 40

[world]
ambient = 1

[render]
integrator = "{integrator}"

[[material]]
name = "wall"
ka = [0, 1, 0]
kd = [0, 1, 0]

[[material]]
name = "card"
ka = [1, 0, 0]
kd = [1, 0, 0]
{card}

[[object]]
type = "rectangle"
scale = 5
translate = [0, 0, -2]
material = "wall"

[[object]]
type = "rectangle"
scale = 5
translate = [0, 0, -1]
material = "card"
"#
    )
}

fn mean(pixels: &[[f32; 3]]) -> [f32; 3] {
    let n = pixels.len() as f32;
    pixels.iter().fold([0.0; 3], |a, p| {
        [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n]
    })
}

#[test]
fn camera_rays_see_through_cut_away_surfaces_under_the_classic_integrators() {
    for integrator in ["raycast", "whitted"] {
        let solid = mean(&render_text("solid", &card_scene(integrator, "")));
        assert!(solid[0] > 0.5 && solid[1] < 0.05, "{integrator}: {solid:?}");
        let cut = mean(&render_text("cut", &card_scene(integrator, "opacity = 0")));
        assert!(cut[0] < 0.05 && cut[1] > 0.5, "{integrator}: {cut:?}");
        // Half cut away (u < 0.5 is the image's left): the left half sees the wall.
        let half = render_text(
            "half",
            &card_scene(
                integrator,
                "opacity = { checkerboard = { even = 0, odd = 1 }, scale = [1, 0.001] }",
            ),
        );
        let (left, right): (Vec<_>, Vec<_>) =
            half.iter().enumerate().partition(|(i, _)| i % 32 < 16);
        let left = mean(&left.iter().map(|(_, p)| **p).collect::<Vec<_>>());
        let right = mean(&right.iter().map(|(_, p)| **p).collect::<Vec<_>>());
        assert!(
            left[1] > 0.5 && left[0] < 0.05,
            "{integrator}: left {left:?}"
        );
        assert!(
            right[0] > 0.5 && right[1] < 0.05,
            "{integrator}: right {right:?}"
        );
    }
}

/// A floor lit by a point light straight above, with a card between them; `card` extra keys.
fn shadow_scene(card: &str) -> String {
    format!(
        r#"
[image]
width = 32
height = 32
samples = 1

[camera]
eye = [0, 3, 0.01]
look_at = [0, 0, 0]
fov = 20

[render]
integrator = "whitted"

[[material]]
name = "floor"
kd = 0.8

[[material]]
name = "card"
kd = 0.5
{card}

[[light]]
type = "point"
position = [0, 10, 0]
intensity = 1

[[object]]
type = "rectangle"
scale = 5
rotate = [-90, 0, 0]
material = "floor"

[[object]]
type = "rectangle"
scale = 5
rotate = [90, 0, 0]
translate = [0, 5, 0]
material = "card"
"#
    )
}

#[test]
fn whitted_shadow_rays_pass_cut_away_surfaces() {
    let shadowed = mean(&render_text("shadowed", &shadow_scene("")));
    let cut = mean(&render_text("cut-shadow", &shadow_scene("opacity = 0")));
    assert!(shadowed[0] < 0.01, "{shadowed:?}");
    assert!((cut[0] - 0.8).abs() < 0.05, "{cut:?}");
}

#[test]
fn whitted_sees_a_textured_emission_as_its_texture() {
    let text = r#"
[image]
width = 32
height = 32
samples = 4

[camera]
eye = [0, 0, 0]
look_at = [0, 0, -1]
fov = 40

[render]
integrator = "whitted"

[[material]]
name = "sign"
emission = { checkerboard = { even = [2, 0, 0], odd = 0 }, scale = [4, 4] }

[[object]]
type = "rectangle"
scale = 5
translate = [0, 0, -1]
material = "sign"
"#;
    let image = render_text("emission", text);
    let lit = image.iter().filter(|p| p[0] > 1.5 && p[1] < 0.01).count();
    let dark = image.iter().filter(|p| p[0] < 0.01).count();
    // About half and half; nothing white.
    assert!(lit > 300 && dark > 300, "{lit} lit, {dark} dark");
    assert!(
        image.iter().all(|p| p[1] < 0.01),
        "a channel the texture has not"
    );
}
