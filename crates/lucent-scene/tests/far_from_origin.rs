//! The same scene moved far from the origin, or scaled down or up, renders as it does at the
//! origin (issue 26, class 6): a unit sphere on a floor under a point light, by the Whitted
//! integrator, whose hard shadow shows any secondary ray that starts in the wrong place.
//!
//! Before ray origins were offset in proportion to the hit's own error bound (`spawn.rs`), the
//! floor's shadow vanished at an offset of 1e5 (190 of 4,096 pixels more than 10% off: shadow
//! rays started 2 units up, over the sphere) and a scene scaled to 1e-6 had 145 such pixels (a
//! fixed offset near the origin larger than the scene). Offsets of 1e7 are out of reach in
//! single precision world coordinates (a unit sphere there is two ulps wide).

use lucent::render::{Hooks, render};
use lucent_scene::SceneFile;
use std::path::PathBuf;

/// The scene moved by `offset` on every axis and scaled by `scale` about the origin (the
/// camera, the light's position and, under quadratic falloff, its intensity with it).
fn scene(offset: f32, scale: f32) -> String {
    let v = |x: f32, y: f32, z: f32| {
        format!(
            "[{}, {}, {}]",
            x * scale + offset,
            y * scale + offset,
            z * scale + offset
        )
    };
    format!(
        "[image]\nwidth = 64\nheight = 64\nsamples = 1\n\
         [render]\nintegrator = \"whitted\"\n\
         [camera]\neye = {}\nlook_at = {}\n\
         [[material]]\nname = \"m\"\ntype = \"diffuse\"\nreflectance = 0.7\n\
         [[object]]\ntype = \"sphere\"\ncenter = {}\nradius = {}\nmaterial = \"m\"\n\
         [[object]]\ntype = \"rectangle\"\nscale = {}\nrotate = [-90, 0, 0]\ntranslate = {}\nmaterial = \"m\"\n\
         [[light]]\ntype = \"point\"\nposition = {}\nintensity = {}\nfalloff = \"quadratic\"\n",
        v(0.0, 1.0, 5.0),
        v(0.0, 0.5, 0.0),
        v(0.0, 1.0, 0.0),
        scale,
        10.0 * scale,
        v(0.0, 0.0, 0.0),
        v(2.0, 5.0, 3.0),
        30.0 * scale * scale,
    )
}

/// The rendered pixels of the scene.
fn pixels(offset: f32, scale: f32) -> Vec<[f32; 3]> {
    let loaded = SceneFile::parse(
        PathBuf::from("far.toml"),
        PathBuf::new(),
        scene(offset, scale),
    )
    .and_then(|f| f.build())
    .unwrap_or_else(|e| panic!("offset {offset}, scale {scale}: {e}"));
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y).to_array())
        .collect()
}

/// How many pixels of `b` differ from `a` by more than a tenth (of the brighter channel, or of
/// 1e-3 for black ones).
fn pixels_off(a: &[[f32; 3]], b: &[[f32; 3]]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(p, q)| {
            let scale = p.iter().copied().fold(1e-3, f32::max);
            (0..3).any(|k| (p[k] - q[k]).abs() > 0.1 * scale)
        })
        .count()
}

#[test]
fn offsets_and_scales_keep_the_shadow_and_shading() {
    let at_origin = pixels(0.0, 1.0);
    // The shadow is there to lose: a good share of the floor is dark.
    let dark = at_origin.iter().filter(|p| p[0] == 0.0).count();
    assert!(dark > 200, "{dark} dark pixels");
    // (offset, scale, most pixels off): at 1e5 a coordinate's ulp is 0.008, and the sphere's
    // silhouette and the shadow's edge move by it.
    for (offset, scale, most) in [
        (1e3, 1.0, 0),
        (1e5, 1.0, 41),
        (0.0, 1e-6, 0),
        (0.0, 1e-3, 0),
        (0.0, 1e3, 0),
        (0.0, 1e6, 0),
    ] {
        let off = pixels_off(&at_origin, &pixels(offset, scale));
        println!("offset {offset:e}, scale {scale:e}: {off} of 4096 pixels more than 10% off");
        assert!(
            off <= most,
            "offset {offset}, scale {scale}: {off} pixels off"
        );
    }
}
