//! `KHR_materials_volume`'s attenuation: an absorbing medium inside the material's objects.

use super::*;
use lucent::render::{Hooks, render};
use lucent_scene::SceneFile;
use lucent_scene::desc::{CameraDesc, Color, Finite, Point, Vector};

/// The cube `[-1, 1]³`, its triangles wound counter-clockwise seen from outside.
fn cube(a: &mut Asset) -> (usize, usize) {
    let mut p = Vec::new();
    for i in 0..8 {
        p.push([
            (i & 1) as f32 * 2.0 - 1.0,
            (i >> 1 & 1) as f32 * 2.0 - 1.0,
            (i >> 2) as f32 * 2.0 - 1.0,
        ]);
    }
    #[rustfmt::skip]
    let faces: [u32; 36] = [
        0, 2, 3, 0, 3, 1, // −z
        4, 5, 7, 4, 7, 6, // +z
        0, 4, 6, 0, 6, 2, // −x
        1, 3, 7, 1, 7, 5, // +x
        0, 1, 5, 0, 5, 4, // −y
        2, 6, 7, 2, 7, 3, // +y
    ];
    (a.positions(&p), a.indices(&faces, U16))
}

/// A clear glass cube (ior 1.5, smooth) whose volume halves, quarters and keeps 0.8 of the light
/// over 2 units.
fn attenuating_cube(dir: &Dir) -> PathBuf {
    let mut a = Asset::default();
    let (pos, idx) = cube(&mut a);
    let rest = format!(
        r#""extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
  "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "materials": [{{"name": "Tinted", "pbrMetallicRoughness": {{"metallicFactor": 0, "roughnessFactor": 0}},
    "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}, "KHR_materials_ior": {{"ior": 1.5}},
      "KHR_materials_volume": {{"thicknessFactor": 1, "attenuationColor": [0.5, 0.25, 0.8], "attenuationDistance": 2}}}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}}}, "indices": {idx}, "material": 0}}]}}]"#
    );
    a.write_embedded(dir, "tinted.gltf", &rest)
}

#[test]
fn a_volume_s_attenuation_is_an_absorbing_medium_inside_its_objects() {
    let dir = Dir::new("volume-attenuation");
    let path = attenuating_cube(&dir);
    let imported = import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    let media = &imported.desc.media;
    assert_eq!(media.len(), 1);
    let m = media[0].get_ref();
    let sigma_a = m.sigma_a.as_ref().unwrap().get_ref().0.to_array();
    for (got, c) in sigma_a.into_iter().zip([0.5f32, 0.25, 0.8]) {
        assert!((got + c.ln() / 2.0).abs() < 1e-6, "σa {got} for colour {c}");
    }
    let o = imported.desc.objects[0].get_ref();
    assert_eq!(o.interior.as_ref().unwrap().get_ref(), m.name.get_ref());
}

#[test]
fn light_through_the_volume_keeps_the_attenuation_colour_per_attenuation_distance() {
    // Straight through the cube's middle: 2 units, one attenuation distance, so the crossing
    // keeps c, the attenuation colour. Seen against a white background through two faces of
    // reflectance F = 0.04 (ior 1.5 at normal incidence): transmitted (1 − F)²·c, and the front
    // face's reflection of the white background, F (glTF's surface reflects on its front only:
    // no inner reflections). (An ior of exactly 1 would make the cube index-matched; lucent's
    // glTF transmission renders that black: noted in docs/media.md.)
    let dir = Dir::new("volume-render");
    let path = attenuating_cube(&dir);
    let mut file = SceneFile::read_with(&path, &open()).unwrap();
    file.camera_given = true;
    file.desc.camera = lucent_scene::Spanned::new(
        0..0,
        CameraDesc {
            eye: Point(glam::DVec3::new(0.0, 0.0, 5.0)),
            look_at: Point(glam::DVec3::ZERO),
            up: Vector(Vec3::Y),
            fov: Finite(0.01),
            aperture: None,
            focus_distance: None,
            orthographic: None,
            motion: None,
            shutter: None,
            medium: None,
        },
    );
    file.desc.image.width = lucent_scene::Spanned::new(0..0, 1);
    file.desc.image.height = lucent_scene::Spanned::new(0..0, 1);
    file.desc.image.samples = lucent_scene::Spanned::new(0..0, 1024);
    file.desc.world.background = Color(lucent::Rgb::WHITE);
    file.desc.lights.clear();
    let loaded = file.build().unwrap();
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    let got = film.pixel(0, 0).to_array();
    let f = 0.04f32;
    for (g, c) in got.into_iter().zip([0.5f32, 0.25, 0.8]) {
        let want = f + (1.0 - f) * (1.0 - f) * c;
        assert!(
            (g - want).abs() < 0.005 * want,
            "{got:?}: {g} against {want}"
        );
    }
}
