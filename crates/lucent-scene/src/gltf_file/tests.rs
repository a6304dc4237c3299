//! The mapping of materials, lights and cameras, and the document checks. Whole files (buffers,
//! nodes, broken inputs) are tested in `tests/gltf.rs`.

use super::*;
use crate::desc::{Color, MaterialKind, TextureDesc};
use std::f32::consts::FRAC_PI_2;

const MATERIALS: &str = r#"{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength",
                     "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                     "KHR_materials_volume", "KHR_texture_transform", "KHR_materials_iridescence"],
  "buffers": [{"byteLength": 4}],
  "bufferViews": [{"buffer": 0, "byteLength": 4}],
  "images": [{"uri": "base.png"}, {"uri": "orm.png"}, {"uri": "normal.png"}, {"uri": "glow.png"},
             {"bufferView": 0, "mimeType": "image/png"}],
  "samplers": [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728}],
  "textures": [{"source": 0}, {"source": 1, "sampler": 0}, {"source": 2}, {"source": 3}, {"source": 4}],
  "materials": [
    {"name": "Glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.95, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33},
                    "KHR_materials_volume": {"thicknessFactor": 0.5},
                    "KHR_materials_iridescence": {"iridescenceFactor": 0.5, "iridescenceIor": 0.9,
                                                  "iridescenceThicknessMaximum": 550,
                                                  "iridescenceThicknessMinimum": 550,
                                                  "iridescenceThicknessTexture": {"index": 1}}}},
    {"name": "Textured", "pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 1, 1, 1], "baseColorTexture": {"index": 0,
            "extensions": {"KHR_texture_transform": {"scale": [2, 3], "offset": [0.5, 0], "rotation": 0.5}}},
        "metallicFactor": 0.5, "metallicRoughnessTexture": {"index": 1}},
     "normalTexture": {"index": 2, "scale": 0.75},
     "emissiveFactor": [1, 0.5, 0], "emissiveTexture": {"index": 3},
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}},
     "doubleSided": true},
    {"name": "Layers", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
     "extensions": {
        "KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.1,
                                    "clearcoatNormalTexture": {"index": 2, "scale": 2}},
        "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.25, 1], "sheenRoughnessFactor": 0.4},
        "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.5]},
        "KHR_materials_iridescence": {"iridescenceFactor": 0.8, "iridescenceTexture": {"index": 1},
                                      "iridescenceIor": 1.8, "iridescenceThicknessMinimum": 200,
                                      "iridescenceThicknessTexture": {"index": 1}}}},
    {"name": "Cutout", "alphaMode": "MASK", "alphaCutoff": 0.25,
     "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.2]}},
    {"name": "Veil", "alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.4],
        "baseColorTexture": {"index": 4}}},
    {}
  ]
}"#;

fn number(t: &Option<Spanned<TextureDesc>>) -> Option<f32> {
    t.as_ref().map(|v| match v.get_ref() {
        TextureDesc::Solid(c) => c.r,
        other => panic!("a constant, got {other:?}"),
    })
}

use crate::desc::texture::Encoding;
use lucent::texture::{Channel, Filter, Wrap};

/// The image lookup `t` is, or is multiplied into.
fn image(t: &TextureDesc) -> &crate::desc::ImageMapDesc {
    match t {
        TextureDesc::Image(i) => i,
        TextureDesc::Product(_, b) => image(b),
        TextureDesc::Step(t, _) => image(t),
        other => panic!("an image, got {other:?}"),
    }
}

#[test]
fn materials_become_gltf_pbr_with_every_texture_and_layer() {
    let m = described(MATERIALS);
    let names: Vec<&str> = m.iter().map(|(d, _)| d.name.get_ref().as_str()).collect();
    assert_eq!(
        names,
        [
            "gltf:Glass",
            "gltf:Textured",
            "gltf:Layers",
            "gltf:Cutout",
            "gltf:Veil",
            "gltf:5"
        ]
    );
    assert!(m.iter().all(|(d, _)| d.kind() == MaterialKind::Pbr));

    let (glass, notes) = &m[0];
    assert_eq!(glass.ior.as_ref().map(|v| v.get_ref().0), Some(1.33));
    assert_eq!(number(&glass.transmission), Some(1.0));
    assert_eq!(glass.volume, Some(true));
    assert_eq!(
        (number(&glass.metallic), number(&glass.roughness)),
        (Some(0.0), Some(0.0))
    );
    assert_eq!(
        glass.base_color,
        Some(TextureDesc::Solid(Rgb::new(0.9, 0.95, 1.0)))
    );
    assert_eq!(glass.two_sided, Some(false));
    // A film of one thickness (the texture mixes equal ends, so it is not read), and an
    // index glTF does not allow, replaced.
    assert_eq!(number(&glass.iridescence), Some(0.5));
    assert_eq!(number(&glass.iridescence_thickness), Some(550.0));
    assert_eq!(glass.iridescence_ior, None);
    assert_eq!(
        notes,
        &[
            "material 0 (`Glass`): iridescenceIor 0.9 is not an index of refraction from 1 to 1000; 1.3 is used"
        ]
    );

    // Factors times textures; each texture read in its encoding and channel.
    let (t, notes) = &m[1];
    assert!(notes.is_empty(), "{notes:?}");
    let base = t.base_color.as_ref().unwrap();
    assert!(
        matches!(base, TextureDesc::Product(f, _) if **f == TextureDesc::Solid(Rgb::new(0.5, 1.0, 1.0)))
    );
    let b = image(base);
    assert_eq!(
        (b.file.as_str(), b.encoding),
        ("base.png", Some(Encoding::Srgb))
    );
    assert_eq!(b.placement.scale, Some([2.0, 3.0]));
    assert_eq!(b.placement.offset, Some([0.5, 0.0]));
    assert!((b.placement.rotation.unwrap() + 0.5f32.to_degrees()).abs() < 1e-4);
    let metallic = image(t.metallic.as_ref().unwrap().get_ref());
    assert_eq!(
        (metallic.file.as_str(), metallic.channel),
        ("orm.png", Some(Channel::B))
    );
    assert_eq!(metallic.wrap, Some([Wrap::Clamp, Wrap::Mirror]));
    assert_eq!(metallic.filter, Some(Filter::Nearest));
    // roughnessFactor 1 times green: the texture alone.
    let rough = t.roughness.as_ref().unwrap().get_ref();
    assert!(
        matches!(rough, TextureDesc::Image(i) if i.channel == Some(Channel::G) && i.encoding == Some(Encoding::Linear))
    );
    assert_eq!(
        image(t.normal_map.as_ref().unwrap().get_ref()).file,
        "normal.png"
    );
    assert_eq!(t.normal_scale.as_ref().map(|s| s.get_ref().0), Some(0.75));
    let glow = t.emission.as_ref().unwrap();
    assert!(
        matches!(glow, TextureDesc::Product(f, _) if **f == TextureDesc::Solid(Rgb::new(4.0, 2.0, 0.0)))
    );
    assert_eq!(image(glow).file, "glow.png");
    assert_eq!(t.two_sided, Some(true));

    let (layers, notes) = &m[2];
    assert_eq!(number(&layers.clearcoat), Some(1.0));
    assert_eq!(number(&layers.clearcoat_roughness), Some(0.1));
    assert_eq!(
        layers
            .clearcoat_normal_scale
            .as_ref()
            .map(|s| s.get_ref().0),
        Some(2.0)
    );
    assert_eq!(
        layers.sheen_color,
        Some(TextureDesc::Solid(Rgb::new(0.5, 0.25, 1.0)))
    );
    assert_eq!(number(&layers.sheen_roughness), Some(0.4));
    assert_eq!(layers.specular, Some(TextureDesc::gray(0.5)));
    assert_eq!(
        layers.specular_color,
        Some(TextureDesc::Solid(Rgb::new(1.0, 0.5, 0.5)))
    );
    // iridescenceFactor times red; thickness from the minimum to the (default) maximum by
    // green.
    let film = layers.iridescence.as_ref().unwrap().get_ref();
    assert!(matches!(film, TextureDesc::Product(f, _) if **f == TextureDesc::gray(0.8)));
    let weight = image(film);
    assert_eq!(
        (weight.file.as_str(), weight.channel, weight.encoding),
        ("orm.png", Some(Channel::R), Some(Encoding::Linear))
    );
    assert_eq!(
        layers.iridescence_ior.as_ref().map(|v| v.get_ref().0),
        Some(1.8)
    );
    match layers.iridescence_thickness.as_ref().map(|t| t.get_ref()) {
        Some(TextureDesc::Mix(thinnest, thickest, amount)) => {
            assert_eq!(
                (&**thinnest, &**thickest),
                (&TextureDesc::gray(200.0), &TextureDesc::gray(400.0))
            );
            let map = image(amount);
            assert_eq!(
                (map.file.as_str(), map.channel, map.encoding),
                ("orm.png", Some(Channel::G), Some(Encoding::Linear))
            );
        }
        other => panic!("a mix of the thicknesses, got {other:?}"),
    }
    assert!(notes.is_empty(), "{notes:?}");

    // MASK: the constant alpha 0.2 under the cutoff 0.25 is a hole everywhere.
    assert_eq!(
        m[3].0.opacity.as_ref().map(|o| o.get_ref().clone()),
        Some(TextureDesc::gray(0.0))
    );
    // BLEND: the alpha (the image in a buffer view, here without bytes to read, counts as
    // having none). The image is named by the glTF file and its index.
    let (veil, notes) = &m[4];
    assert_eq!(
        veil.opacity.as_ref().map(|o| o.get_ref().clone()),
        Some(TextureDesc::gray(0.4))
    );
    let base = image(
        veil.base_color
            .as_ref()
            .expect("the embedded image is read"),
    );
    assert_eq!(
        (base.file.as_str(), base.gltf_image),
        ("test.gltf", Some(4))
    );
    assert!(notes.is_empty(), "{notes:?}");

    // Single-sided materials cull their backs, except where light goes through them.
    let culled: Vec<Option<bool>> = m.iter().map(|(d, _)| d.cull_back).collect();
    assert_eq!(
        culled,
        [None, None, Some(true), Some(true), Some(true), Some(true)]
    );

    // glTF's defaults: a white rough metal.
    let (plain, _) = &m[5];
    assert_eq!(
        (
            plain.base_color.clone(),
            plain.metallic.clone(),
            plain.roughness.clone()
        ),
        (None, None, None)
    );
}

const MORE_MATERIALS: &str = r#"{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_anisotropy", "KHR_materials_diffuse_transmission", "KHR_materials_unlit"],
  "images": [{"uri": "aniso.png"}, {"uri": "leaf.png"}, {"uri": "tint.png"}],
  "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
  "materials": [
    {"name": "Brushed", "extensions": {"KHR_materials_anisotropy": {
        "anisotropyStrength": 0.6, "anisotropyRotation": 1.5707963, "anisotropyTexture": {"index": 0}}}},
    {"name": "Leaf", "pbrMetallicRoughness": {"metallicFactor": 0},
     "extensions": {"KHR_materials_diffuse_transmission": {
        "diffuseTransmissionFactor": 0.5, "diffuseTransmissionTexture": {"index": 1},
        "diffuseTransmissionColorFactor": [0.5, 1, 0.25], "diffuseTransmissionColorTexture": {"index": 2}}}},
    {"name": "Flat", "doubleSided": true, "alphaMode": "MASK",
     "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 0.2], "metallicFactor": 0},
     "extensions": {"KHR_materials_unlit": {}}},
    {"name": "Decal", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}},
     "extensions": {"KHR_materials_unlit": {}}}
  ]
}"#;

#[test]
fn anisotropy_directions_diffuse_transmission_and_unlit_are_read() {
    let m = described(MORE_MATERIALS);
    // The anisotropy's strength is the blue channel; its direction the red and green ones.
    let (brushed, notes) = &m[0];
    assert!(notes.is_empty(), "{notes:?}");
    let strength = brushed.anisotropy.as_ref().unwrap().get_ref();
    assert!(matches!(strength, TextureDesc::Product(f, _) if **f == TextureDesc::gray(0.6)));
    assert_eq!(image(strength).channel, Some(Channel::B));
    let direction = image(brushed.anisotropy_direction.as_ref().unwrap().get_ref());
    assert_eq!(
        (
            direction.file.as_str(),
            direction.channel,
            direction.encoding
        ),
        ("aniso.png", None, Some(Encoding::Linear))
    );
    assert!((brushed.anisotropy_rotation.as_ref().unwrap().get_ref().0 - 90.0).abs() < 1e-4);

    // Diffuse transmission: the factor times the alpha channel, the colour times an sRGB
    // image; a translucent single-sided surface is not culled (light comes through its back).
    let (leaf, notes) = &m[1];
    assert!(notes.is_empty(), "{notes:?}");
    let share = leaf.diffuse_transmission.as_ref().unwrap().get_ref();
    assert!(matches!(share, TextureDesc::Product(f, _) if **f == TextureDesc::gray(0.5)));
    assert_eq!(
        (image(share).file.as_str(), image(share).channel),
        ("leaf.png", Some(Channel::A))
    );
    let tint = leaf.diffuse_transmission_color.as_ref().unwrap();
    assert!(
        matches!(tint, TextureDesc::Product(f, _) if **f == TextureDesc::Solid(Rgb::new(0.5, 1.0, 0.25)))
    );
    assert_eq!(image(tint).encoding, Some(Encoding::Srgb));
    assert_eq!(leaf.cull_back, None);

    // Unlit: a black diffuse surface emitting its base colour times the vertex colours, from
    // both sides when double-sided; the alpha still cuts it out.
    let (flat, notes) = &m[2];
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(flat.kind(), MaterialKind::Diffuse);
    assert_eq!(flat.reflectance, Some(TextureDesc::gray(0.0)));
    assert_eq!(
        flat.emission,
        Some(TextureDesc::Product(
            Box::new(TextureDesc::Solid(Rgb::new(1.0, 0.5, 0.25))),
            Box::new(TextureDesc::VertexColor)
        ))
    );
    assert_eq!(flat.emits_back, Some(true));
    assert_eq!(
        flat.opacity.as_ref().map(|o| o.get_ref().clone()),
        Some(TextureDesc::gray(0.0))
    );
    let (decal, _) = &m[3];
    match decal.emission.as_ref() {
        Some(TextureDesc::Product(base, _)) => assert_eq!(image(base).file, "leaf.png"),
        other => panic!("the base colour texture as the emission, got {other:?}"),
    }
    assert_eq!((decal.emits_back, decal.cull_back), (None, Some(true)));
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
    assert_eq!(
        point.position.as_ref().unwrap().get_ref().0,
        glam::DVec3::new(1.0, 2.0, 3.0)
    );
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
    let (c, aspect) = camera_of(&camera.projection(), world).unwrap();
    assert_eq!((aspect, c.orthographic), (p.aspect_ratio(), None));
    assert_eq!(c.eye.0, glam::DVec3::new(0.0, 1.0, 10.0));
    // −z turned by 90° about y is −x.
    assert!(
        c.look_at
            .0
            .abs_diff_eq(glam::DVec3::new(-1.0, 1.0, 10.0), 1e-6)
    );
    assert!(c.up.0.abs_diff_eq(Vec3::Y, 1e-6));
    assert_eq!(c.fov.0, 0.5f32.to_degrees());
    assert_eq!(image_width(1.5), Some(900));
    assert_eq!(image_width(0.0), None);
    assert_eq!(image_width(f32::INFINITY), None);
    let flat = Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0));
    assert!(
        camera_of(&camera.projection(), flat)
            .unwrap_err()
            .contains("flattens")
    );

    // An orthographic camera: a view 2·ymag high, of aspect xmag / ymag.
    let doc = parse_document(
        br#"{"asset": {"version": "2.0"}, "cameras": [{"type": "orthographic",
            "orthographic": {"xmag": 3, "ymag": 2, "znear": 0.1, "zfar": 100}}]}"#,
        Path::new("t.gltf"),
        true,
    )
    .unwrap();
    let ortho = doc.cameras().next().unwrap();
    let (c, aspect) = camera_of(&ortho.projection(), world).unwrap();
    assert_eq!(
        (c.orthographic.map(|h| h.0), aspect),
        (Some(4.0), Some(1.5))
    );
    assert!(
        c.look_at
            .0
            .abs_diff_eq(glam::DVec3::new(-1.0, 1.0, 10.0), 1e-6)
    );
}

#[test]
fn primitives_keep_the_coordinate_set_their_textures_read() {
    let doc = parse_document(
        br#"{"asset": {"version": "2.0"},
            "images": [{"uri": "a.png"}], "textures": [{"source": 0}],
            "materials": [
              {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1},
                                        "metallicRoughnessTexture": {"index": 0, "texCoord": 1}},
               "normalTexture": {"index": 0},
               "occlusionTexture": {"index": 0, "texCoord": 0}},
              {"emissiveTexture": {"index": 0, "texCoord": 2,
                 "extensions": {"KHR_texture_transform": {"texCoord": 0}}}},
              {}
            ]}"#,
        Path::new("t.gltf"),
        true,
    )
    .unwrap();
    let root = doc.as_json();
    // Two textures read set 1, one set 0 (occlusion is not read): set 1. A transform's
    // texCoord replaces the texture's. No textures: set 0.
    assert_eq!(material::uv_set(root, Some(0)), 1);
    assert_eq!(material::uv_set(root, Some(1)), 0);
    assert_eq!(material::uv_set(root, Some(2)), 0);
    assert_eq!(material::uv_set(root, None), 0);
    let m = described_doc(&doc);
    assert!(
        m[0].1
            .iter()
            .any(|n| n.contains("normalTexture uses TEXCOORD_0; TEXCOORD_1")),
        "{:?}",
        m[0].1
    );
    assert!(m[1].1.is_empty(), "{:?}", m[1].1);
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
        r#"{"asset": {"version": "2.0"}, "extensionsRequired": ["EXT_meshopt_compression"], "extensionsUsed": ["EXT_meshopt_compression"]}"#,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.gltf: the file requires extension EXT_meshopt_compression, which is not supported"
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
