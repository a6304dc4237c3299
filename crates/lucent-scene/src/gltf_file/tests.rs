//! The mapping of materials, lights and cameras, and the document checks. Whole files (buffers,
//! nodes, broken inputs) are tested in `tests/gltf.rs`.

use super::*;
use crate::desc::{Color, MaterialKind, TextureDesc};
use std::f32::consts::FRAC_PI_2;

const MATERIALS: &str = r#"{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
  "materials": [
    {"name": "Glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.95, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33}}},
    {"name": "Frosted", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.75}}},
    {"name": "Gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.25, 1], "metallicFactor": 1, "roughnessFactor": 0.02}},
    {"name": "Brushed", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.4},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}},
    {"name": "Chalk", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0, "roughnessFactor": 0.9}, "doubleSided": true},
    {"name": "Shiny", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.3}},
    {"name": "Lamp", "emissiveFactor": [1, 0.5, 0], "pbrMetallicRoughness": {"metallicFactor": 0.25},
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
    {"name": "Shiny", "alphaMode": "BLEND"},
    {}
  ]
}"#;

fn ior(d: &MaterialDesc) -> Option<f32> {
    d.ior.as_ref().map(|v| v.get_ref().0)
}

fn roughness(d: &MaterialDesc) -> Option<f32> {
    d.roughness.as_ref().map(|v| match v.get_ref() {
        TextureDesc::Solid(c) => c.r,
        other => panic!("a constant roughness, got {other:?}"),
    })
}

use crate::desc::MaterialDesc;

#[test]
fn metallic_roughness_maps_to_lucent_kinds() {
    let m = described(MATERIALS);
    let names: Vec<&str> = m.iter().map(|(d, _)| d.name.get_ref().as_str()).collect();
    assert_eq!(
        names,
        [
            "gltf:Glass",
            "gltf:Frosted",
            "gltf:Gold",
            "gltf:Brushed",
            "gltf:Chalk",
            "gltf:Shiny",
            "gltf:Lamp",
            "gltf:Shiny#2",
            "gltf:8"
        ]
    );
    let kinds: Vec<MaterialKind> = m.iter().map(|(d, _)| d.kind()).collect();
    use MaterialKind::*;
    assert_eq!(
        kinds,
        [
            Dielectric,
            RoughDielectric,
            Conductor,
            RoughConductor,
            Diffuse,
            Plastic,
            Diffuse,
            RoughConductor, // glTF's defaults: metallic 1, roughness 1
            RoughConductor,
        ]
    );

    let (glass, notes) = &m[0];
    assert_eq!(ior(glass), Some(1.33));
    assert_eq!(
        glass.transmittance,
        Some(TextureDesc::Solid(Rgb::new(0.9, 0.95, 1.0)))
    );
    assert_eq!(roughness(glass), None);
    assert_eq!(glass.two_sided, Some(false));
    assert!(notes.is_empty(), "{notes:?}");

    let (frosted, notes) = &m[1];
    assert_eq!(ior(frosted), Some(1.5));
    assert_eq!(roughness(frosted), Some(0.25));
    assert_eq!(frosted.transmittance, Some(TextureDesc::Solid(Rgb::WHITE)));
    assert_eq!(
        notes,
        &[
            "material 1 (`Frosted`): transmissionFactor 0.75 is rounded to 1: rendered as `roughdielectric`"
        ]
    );

    let (gold, _) = &m[2];
    assert_eq!(
        gold.specular,
        Some(TextureDesc::Solid(Rgb::new(1.0, 0.8, 0.25)))
    );
    assert_eq!(
        (gold.eta.clone(), gold.k.clone(), roughness(gold)),
        (None, None, None)
    );
    assert_eq!(gold.transmittance, None);

    // A metal is opaque: its transmission is not a note, and not a dielectric.
    let (brushed, notes) = &m[3];
    assert_eq!(roughness(brushed), Some(0.4f32 * 0.4));
    assert!(notes.is_empty(), "{notes:?}");

    let (chalk, _) = &m[4];
    assert_eq!(
        chalk.reflectance,
        Some(TextureDesc::Solid(Rgb::new(0.5, 0.25, 0.125)))
    );
    assert_eq!((ior(chalk), roughness(chalk)), (None, None));
    assert_eq!(chalk.two_sided, Some(true));

    let (shiny, _) = &m[5];
    assert_eq!(
        shiny.reflectance,
        Some(TextureDesc::Solid(Rgb::new(0.2, 0.4, 0.6)))
    );
    assert_eq!(ior(shiny), Some(1.5));
    assert_eq!(roughness(shiny), Some(0.3f32 * 0.3));

    let (lamp, notes) = &m[6];
    assert_eq!(
        lamp.emission,
        Some(TextureDesc::Solid(Rgb::new(4.0, 2.0, 0.0)))
    );
    assert_eq!(
        notes,
        &["material 6 (`Lamp`): metallicFactor 0.25 is rounded to 0: rendered as `diffuse`"]
    );
    assert_eq!(m[5].0.emission, None);

    let (_, notes) = &m[7];
    assert_eq!(
        notes,
        &["material 7 (`Shiny`): alpha mode Blend is not rendered: opaque"]
    );
    assert_eq!(roughness(&m[8].0), Some(1.0));
}

#[test]
fn the_default_material_name_stays_unique() {
    let doc = parse_document(
        br#"{"asset": {"version": "2.0"}, "materials": [{"name": "default"}, {"name": ""}]}"#,
        Path::new("t.gltf"),
        true,
    )
    .unwrap();
    let (names, default) = material_names(&doc);
    assert_eq!(names, ["gltf:default", "gltf:1"]);
    assert_eq!(default, "gltf:default#2");
    let d = material::default_material(&default);
    assert_eq!(d.kind(), MaterialKind::Diffuse);
    assert_eq!(d.reflectance, Some(TextureDesc::Solid(Rgb::gray(0.8))));
}

const LIGHTS: &str = r#"{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "point", "color": [1, 0.5, 0.25], "intensity": 683, "range": 10},
    {"type": "spot", "intensity": 1366, "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
    {"type": "directional", "intensity": 68.3},
    {"type": "point", "intensity": -1}
  ]}},
  "cameras": [
    {"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}},
    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}
  ]
}"#;

fn lights() -> Vec<Result<(LightDesc, Vec<String>), String>> {
    let doc = parse_document(LIGHTS.as_bytes(), Path::new("t.gltf"), true).unwrap();
    // Moved to (1, 2, 3) and turned to look down −y (−z turned by −90° about x).
    let world = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
        * Mat4::from_rotation_x(-FRAC_PI_2)
        * Mat4::from_scale(Vec3::splat(2.0));
    doc.lights().unwrap().map(|l| light(&l, world)).collect()
}

fn vector(v: &Option<Spanned<Vector>>) -> Vec3 {
    v.as_ref().unwrap().get_ref().0
}

#[test]
fn lights_are_placed_and_converted_from_photometric_units() {
    let l = lights();
    let (point, notes) = l[0].as_ref().unwrap();
    assert_eq!(point.kind, LightKind::Point);
    assert_eq!(point.intensity, Some(Color(Rgb::new(1.0, 0.5, 0.25))));
    assert_eq!(vector(&point.position), Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(
        point.falloff.as_ref().map(|f| *f.get_ref()),
        Some(FalloffName::Quadratic)
    );
    assert!(point.direction.is_none());
    assert_eq!(
        notes,
        &["range 10 is not rendered: the light reaches everywhere"]
    );

    let (spot, notes) = l[1].as_ref().unwrap();
    assert_eq!(spot.kind, LightKind::Spot);
    assert_eq!(spot.intensity, Some(Color(Rgb::gray(2.0))));
    assert!(vector(&spot.direction).abs_diff_eq(Vec3::NEG_Y, 1e-6));
    assert_eq!(
        spot.cutoff.as_ref().unwrap().get_ref().0,
        0.5f32.to_degrees()
    );
    assert_eq!(
        spot.cutoff_start.as_ref().unwrap().get_ref().0,
        0.25f32.to_degrees()
    );
    assert!(notes.is_empty());

    let (sun, _) = l[2].as_ref().unwrap();
    assert_eq!(sun.kind, LightKind::Directional);
    assert_eq!(sun.intensity, Some(Color(Rgb::gray(68.3 / 683.0))));
    assert!(vector(&sun.direction).abs_diff_eq(Vec3::NEG_Y, 1e-6));
    assert!(sun.position.is_none() && sun.falloff.is_none());

    assert!(l[3].as_ref().unwrap_err().contains("negative"));
}

#[test]
fn a_perspective_camera_looks_down_its_nodes_minus_z() {
    let doc = parse_document(LIGHTS.as_bytes(), Path::new("t.gltf"), true).unwrap();
    let camera = doc.cameras().next().unwrap();
    let gltf::camera::Projection::Perspective(p) = camera.projection() else {
        panic!("camera 0 is perspective");
    };
    let world = Mat4::from_translation(Vec3::new(0.0, 1.0, 10.0))
        * Mat4::from_rotation_y(FRAC_PI_2)
        * Mat4::from_scale(Vec3::splat(3.0));
    let c = perspective(&p, world).unwrap();
    assert_eq!(c.eye.0, Vec3::new(0.0, 1.0, 10.0));
    // −z turned by 90° about y is −x.
    assert!(c.look_at.0.abs_diff_eq(Vec3::new(-1.0, 1.0, 10.0), 1e-6));
    assert!(c.up.0.abs_diff_eq(Vec3::Y, 1e-6));
    assert_eq!(c.fov.0, 0.5f32.to_degrees());
    assert_eq!(image_width(1.5), Some(900));
    assert_eq!(image_width(0.0), None);
    assert_eq!(image_width(f32::INFINITY), None);
    let flat = Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0));
    assert!(perspective(&p, flat).unwrap_err().contains("flattens"));
}

#[test]
fn node_transforms_are_matrix_or_translation_rotation_scale() {
    let trs = gltf::scene::Transform::Decomposed {
        translation: [1.0, 2.0, 3.0],
        // 90° about z, given not quite normalised as writers round.
        rotation: [0.0, 0.0, 0.7072, 0.7072],
        scale: [2.0, 2.0, 2.0],
    };
    let m = local_matrix(trs);
    // Scale, then rotate (x → y), then translate.
    assert!(
        m.transform_point3(Vec3::X)
            .abs_diff_eq(Vec3::new(1.0, 4.0, 3.0), 1e-5)
    );
    let cols = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [5.0, 6.0, 7.0, 1.0],
    ];
    let m = local_matrix(gltf::scene::Transform::Matrix { matrix: cols });
    assert_eq!(m.transform_point3(Vec3::ZERO), Vec3::new(5.0, 6.0, 7.0));
    let zero = gltf::scene::Transform::Decomposed {
        translation: [0.0; 3],
        rotation: [0.0; 4],
        scale: [1.0; 3],
    };
    assert!(!primitive::placeable(&local_matrix(zero)));
}

#[test]
fn documents_are_checked_before_the_crate_sees_them() {
    let parse = |json: &str| parse_document(json.as_bytes(), Path::new("t.gltf"), true);
    let e = parse("{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [\n}").unwrap_err();
    assert_eq!(e.position, Some((4, 1)), "{e}");
    assert!(e.message.starts_with("not valid glTF JSON: "), "{e}");
    let e = parse(
        r#"{"asset": {"version": "2.0"}, "extensionsRequired": ["KHR_draco_mesh_compression"], "extensionsUsed": ["KHR_draco_mesh_compression"]}"#,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.gltf: the file requires extension KHR_draco_mesh_compression, which is not supported"
    );
    // The crate's validation would index out of bounds here.
    let e = parse(
        r#"{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}]}"#,
    )
    .unwrap_err();
    assert_eq!(
        e.message,
        "mesh 0 primitive 0: POSITION names accessor 7, but the file has 0"
    );
    let e = parse(r#"{"asset": {"version": "2.0"}, "nodes": [{"mesh": 3}]}"#).unwrap_err();
    assert!(
        e.message
            .starts_with("the glTF document is invalid: nodes[0].mesh"),
        "{e}"
    );
    // POSITION without min and max is forgiven.
    parse(
        r#"{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}"#,
    )
    .unwrap();
}
