//! `[[medium]]` tables, objects' `interior` and `exterior`, the camera's `medium` and the
//! `null` material: what they render, and the errors for what makes no sense.

use lucent::render::{Hooks, render};
use lucent_scene::{LoadError, Loaded, SceneFile};
use std::path::PathBuf;

/// A 1-pixel camera looking through the centre of a unit sphere, on a white background.
const VIEW: &str = "[image]\nwidth = 1\nheight = 1\nsamples = 4096\n\
[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 0.01\n\
[world]\nbackground = 1.0\n[render]\nintegrator = \"path\"\n\
[[material]]\nname = \"boundary\"\ntype = \"null\"\n";

const SPHERE: &str =
    "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"boundary\"\n";

fn load(text: &str) -> Result<Loaded, LoadError> {
    SceneFile::parse(
        PathBuf::from("media.toml"),
        PathBuf::new(),
        text.to_string(),
    )?
    .build()
}

fn pixel(text: &str) -> [f32; 3] {
    let loaded = load(text).unwrap();
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    film.pixel(0, 0).to_array()
}

#[test]
fn an_absorbing_medium_named_by_an_object_dims_what_is_behind_it() {
    // A chord of 2 through σa = [0.1, 0.5, 1.0]·scale 2: exp(−4σa).
    let text = format!(
        "{VIEW}[[medium]]\nname = \"ink\"\nsigma_a = [0.1, 0.5, 1.0]\nscale = 2\n{SPHERE}interior = \"ink\"\n"
    );
    let got = pixel(&text);
    for (c, s) in [0.1f32, 0.5, 1.0].into_iter().enumerate() {
        let want = (-4.0 * s).exp();
        assert!(
            (got[c] - want).abs() < 0.01 * want,
            "channel {c}: {} against {want}",
            got[c]
        );
    }
}

#[test]
fn a_null_surface_alone_is_invisible_and_a_camera_in_fog_sees_the_fog() {
    let got = pixel(&format!("{VIEW}{SPHERE}"));
    assert_eq!(got, [1.0; 3]);
    // The camera in a purely absorbing fog that fills the world: the background, infinitely
    // far, is not seen at all.
    let text = format!("{VIEW}[[medium]]\nname = \"fog\"\nsigma_t = 0.5\nalbedo = 0\n")
        .replace("fov = 0.01\n", "fov = 0.01\nmedium = \"fog\"\n");
    assert_eq!(pixel(&text), [0.0; 3]);
}

#[test]
fn whitted_dims_by_media_and_the_photon_mapper_says_it_leaves_them_out() {
    let whitted = |text: String| text.replace("integrator = \"path\"", "integrator = \"whitted\"");
    // Through the absorbing sphere: exp(−4σa) exactly, no noise.
    let ink = format!(
        "{VIEW}[[medium]]\nname = \"ink\"\nsigma_a = [0.1, 0.5, 1.0]\nscale = 2\n{SPHERE}interior = \"ink\"\n"
    );
    let got = pixel(&whitted(ink.clone()));
    for (c, s) in [0.1f32, 0.5, 1.0].into_iter().enumerate() {
        let want = (-4.0 * s).exp();
        assert!(
            (got[c] - want).abs() < 1e-4 * want,
            "channel {c}: {} against {want}",
            got[c]
        );
    }
    assert!(load(&whitted(ink.clone())).unwrap().warnings.is_empty());
    // The camera in endless fog of albedo 1/2 under ambient light 0.4 sees its glow, 0.2, and
    // nothing of the background.
    let fog = format!("{VIEW}[[medium]]\nname = \"fog\"\nsigma_s = 0.5\nsigma_a = 0.5\n")
        .replace("fov = 0.01\n", "fov = 0.01\nmedium = \"fog\"\n")
        .replace("background = 1.0\n", "background = 1.0\nambient = 0.4\n");
    let got = pixel(&whitted(fog));
    for c in got {
        assert!((c - 0.2).abs() < 1e-5, "{got:?}");
    }
    let sppm = ink.replace("integrator = \"path\"", "integrator = \"sppm\"");
    let loaded = load(&sppm).unwrap();
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("sppm integrator renders no participating media")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn whitteds_shadow_rays_are_dimmed_by_the_media_they_cross() {
    // A white plane at z = 0 seen head-on at the origin, lit by a point light at (0, 4, 4)
    // whose shadow ray crosses a null sphere of radius 0.5 on its way (a chord of 1): with ink
    // of σa = (0.2, 0.7, 1.5) inside it, the pixel is exp(−σa) of the pixel without.
    let scene = |interior: &str| {
        format!(
            "[image]\nwidth = 1\nheight = 1\nsamples = 1\n\
             [camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 0.01\n\
             [render]\nintegrator = \"whitted\"\n\
             [[medium]]\nname = \"ink\"\nsigma_a = [0.2, 0.7, 1.5]\n\
             [[material]]\nname = \"boundary\"\ntype = \"null\"\n\
             [[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 0.8\n\
             [[light]]\ntype = \"point\"\nposition = [0, 4, 4]\nintensity = 30\n\
             [[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nmaterial = \"white\"\n\
             [[object]]\ntype = \"sphere\"\ncenter = [0, 2, 2]\nradius = 0.5\nmaterial = \"boundary\"\n{interior}"
        )
    };
    let clear = pixel(&scene(""));
    let dimmed = pixel(&scene("interior = \"ink\"\n"));
    assert!(clear[0] > 0.01, "{clear:?}");
    for (c, s) in [0.2f32, 0.7, 1.5].into_iter().enumerate() {
        let want = clear[c] * (-s).exp();
        assert!(
            (dimmed[c] - want).abs() < 1e-4 * clear[c],
            "channel {c}: {} against {want}",
            dimmed[c]
        );
    }
}

/// The error for `text`, checked to be at `line:column` and to mention `cause`.
fn assert_error(text: &str, line: usize, column: usize, cause: &str) {
    let shown = load(text)
        .expect_err("the scene should be refused")
        .to_string();
    assert!(
        shown.starts_with(&format!("media.toml:{line}:{column}: ")),
        "wrong place: {shown}"
    );
    assert!(
        shown.contains(cause),
        "`{shown}` does not mention `{cause}`"
    );
}

#[test]
fn bad_media_are_refused_at_their_place() {
    // VIEW is 15 lines; the medium table starts on line 16.
    let medium = |keys: &str| format!("{VIEW}[[medium]]\nname = \"m\"\n{keys}\n");
    assert_error(
        &medium("sigma_a = -1"),
        18,
        11,
        "colours must not be negative",
    );
    assert_error(&medium("sigma_s = nan"), 18, 11, "NaN");
    assert_error(
        &medium("sigma_a = 1\nsigma_t = 2"),
        16,
        1,
        "not keys of both",
    );
    assert_error(
        &medium("sigma_t = 1\nalbedo = 1.5"),
        19,
        10,
        "`albedo` must be at most 1",
    );
    assert_error(&medium("albedo = 0.5"), 16, 1, "`albedo` needs `sigma_t`");
    assert_error(
        &medium("sigma_s = 1\ng = 1"),
        19,
        5,
        "strictly between −1 and 1",
    );
    assert_error(
        &medium("sigma_s = 1\nscale = -2"),
        19,
        9,
        "`scale` must be at least 0",
    );
    assert_error(&medium("grid = 3"), 18, 1, "unknown field `grid`");
    let twice = format!("{}[[medium]]\nname = \"m\"\n", medium("sigma_s = 1"));
    assert_error(&twice, 20, 8, "a medium named `m` already exists");
}

#[test]
fn unknown_media_are_named_with_the_known_ones() {
    let text =
        format!("{VIEW}[[medium]]\nname = \"ink\"\nsigma_a = 1\n{SPHERE}interior = \"inc\"\n");
    assert_error(&text, 24, 12, "unknown medium `inc` (known: ink)");
    let text = format!("{VIEW}{SPHERE}exterior = \"fog\"\n");
    assert_error(&text, 21, 12, "no [[medium]] is defined");
    let text = VIEW.replace("fov = 0.01\n", "fov = 0.01\nmedium = \"fog\"\n");
    assert_error(&text, 9, 10, "unknown medium `fog`");
}
