//! Geometry shared between primitives, quantized attributes, morph targets, skins and Draco
//! compression: each decoded to the triangles its plain form gives.

use super::*;

#[test]
fn primitives_of_the_same_accessors_are_stored_once() {
    // 300 meshes whose one primitive reads the same positions and indices, each on its node:
    // one mesh stored, 300 instances of it, whatever their materials.
    let dir = Dir::new("shared");
    let mut a = Asset::default();
    let pos = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = a.indices(&[0, 1, 2], U16);
    // A second accessor over the same data is the same geometry too.
    a.accessors.push(a.accessors[idx].clone());
    let idx2 = a.accessors.len() - 1;
    let n = 300;
    let nodes: Vec<String> = (0..n)
        .map(|i| format!(r#"{{"mesh": {i}, "translation": [{i}, 0, 0]}}"#))
        .collect();
    let meshes: Vec<String> = (0..n)
        .map(|i| {
            let material = i % 2;
            let idx = if i % 3 == 0 { idx2 } else { idx };
            format!(
                r#"{{"primitives": [{{"attributes": {{"POSITION": {pos}}}, "indices": {idx}, "material": {material}}}]}}"#
            )
        })
        .collect();
    let roots: Vec<String> = (0..n).map(|i| i.to_string()).collect();
    let rest = format!(
        r#""scene": 0, "scenes": [{{"nodes": [{}]}}], "nodes": [{}], "meshes": [{}],
  "materials": [{{"name": "a"}}, {{"name": "b"}}]"#,
        roots.join(", "),
        nodes.join(", "),
        meshes.join(", ")
    );
    let file = a.write_embedded(&dir, "shared.gltf", &rest);
    let imported = import_gltf(&file, &open(), &mut Fingerprint::default()).unwrap();
    let parts: std::collections::HashSet<&String> = imported
        .desc
        .objects
        .iter()
        .map(|o| o.get_ref().part.as_ref().unwrap().get_ref())
        .collect();
    assert_eq!(imported.desc.objects.len(), n);
    assert_eq!(parts.len(), 1, "{parts:?}");
    let loaded = lucent_scene::SceneFile::read(&file)
        .unwrap()
        .build()
        .unwrap();
    let counts = loaded.scene.counts();
    assert_eq!((counts.meshes, counts.instances), (1, n));
    assert_eq!((counts.triangles, counts.unique_triangles), (n, 1));
}

/// `KHR_mesh_quantization`: positions as normalised shorts, normals as normalised bytes and
/// texture coordinates as unsigned shorts, dequantized by the node's scale.
#[test]
fn quantized_attributes_are_read_and_placed_by_their_node() {
    let dir = Dir::new("quantized");
    let mut a = Asset::default();
    let shorts = |v: &[i16]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    // (0, 0, 0), (1, 0, 0), (0, 1, 0) as shorts normalised by 32767, each padded to 8 bytes.
    let position = a.accessor(
        &shorts(&[0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0]),
        5122,
        3,
        "VEC3",
        r#", "normalized": true, "min": [0, 0, 0], "max": [32767, 32767, 0]"#,
    );
    a.views[position] = a.views[position].replace("}", r#", "byteStride": 8}"#);
    let normal = a.accessor(
        &[0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0],
        5120,
        3,
        "VEC3",
        r#", "normalized": true"#,
    );
    a.views[normal] = a.views[normal].replace("}", r#", "byteStride": 4}"#);
    let uv = a.accessor(
        &[0, 0, 0, 0, 255, 255, 0, 0, 0, 0, 255, 255],
        U16,
        3,
        "VEC2",
        r#", "normalized": true"#,
    );
    let rest = format!(
        r#""extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {position}, "NORMAL": {normal}, "TEXCOORD_0": {uv}}}}}]}}],
  "nodes": [{{"mesh": 0, "scale": [2, 2, 2]}}],
  "scenes": [{{"nodes": [0]}}]"#
    );
    let path = a.write_embedded(&dir, "quantized.gltf", &rest);
    let mesh = whole(&path);
    assert_near(
        &mesh.positions,
        &[
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ],
    );
    assert!(
        mesh.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6),
        "{:?}",
        mesh.normals
    );
    assert_eq!(
        mesh.uvs,
        [
            glam::Vec2::ZERO,
            glam::Vec2::new(1.0, 0.0),
            glam::Vec2::new(0.0, 1.0)
        ]
    );
}

/// Morph targets are posed at the mesh's default weights (its `weights`), positions and normals.
#[test]
fn morph_targets_are_posed_at_the_mesh_s_default_weights() {
    let dir = Dir::new("morph");
    let mut a = Asset::default();
    let position = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let normal = a.floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0], 3);
    let lift = a.floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0], 3);
    let tilt = a.floats(&[1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0], 3);
    let shift = a.floats(&[5.0, 0.0, 0.0, 5.0, 0.0, 0.0, 5.0, 0.0, 0.0], 3);
    let rest = format!(
        r#""meshes": [{{"primitives": [{{"attributes": {{"POSITION": {position}, "NORMAL": {normal}}},
      "targets": [{{"POSITION": {lift}, "NORMAL": {tilt}}}, {{"POSITION": {shift}}}]}}],
    "weights": [0.5, 0.0]}}],
  "nodes": [{{"mesh": 0}}, {{"mesh": 0, "weights": [1.0, 1.0], "translation": [3, 0, 0]}}],
  "scenes": [{{"nodes": [0, 1]}}]"#
    );
    let path = a.write_embedded(&dir, "morph.gltf", &rest);
    let mesh = part(&path, "0/0");
    // The first target at 0.5 lifts the third vertex by 1; the second, at 0, moves nothing.
    assert_near(
        &mesh.positions,
        &[Vec3::ZERO, Vec3::X, Vec3::new(0.0, 2.0, 0.0)],
    );
    let tilted = Vec3::new(0.5, 0.0, 1.0).normalize();
    assert!(
        mesh.normals.iter().all(|n| (*n - tilted).length() < 1e-6),
        "{:?}",
        mesh.normals
    );
    // A node's own weights are not applied, with a warning naming it.
    let imported = import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
    assert!(
        imported.warnings.iter().any(|w| w
            .contains("node 1: its morph weights are not applied; mesh 0's default weights are")),
        "{:?}",
        imported.warnings
    );
}

/// A skinned mesh is posed by its joints as the nodes place them, in world space: its own
/// node's transform is not applied (glTF 2.0 §3.7.3).
#[test]
fn skins_pose_their_meshes_by_their_joints() {
    let dir = Dir::new("skin");
    let mut a = Asset::default();
    let position = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    // Vertices 0 and 1 follow joint 0 (at rest), vertex 2 half joint 0, half joint 1.
    let joints = a.accessor(&[0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0], U8, 3, "VEC4", "");
    let weights = a.floats(
        &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0],
        4,
    );
    // Inverse bind matrices: identity for joint 0; joint 1 bound at y = 1 (its inverse moves
    // down by 1), so that at rest, placed at y = 1, it moves nothing.
    let mut ibm: Vec<f32> = Mat4::IDENTITY.to_cols_array().to_vec();
    ibm.extend(Mat4::from_translation(Vec3::new(0.0, -1.0, 0.0)).to_cols_array());
    let bytes: Vec<u8> = ibm.iter().flat_map(|v| v.to_le_bytes()).collect();
    let inverse_binds = a.accessor(&bytes, FLOAT, 2, "MAT4", "");
    let rest = format!(
        r#""meshes": [{{"primitives": [{{"attributes": {{"POSITION": {position}, "JOINTS_0": {joints}, "WEIGHTS_0": {weights}}}}}]}}],
  "skins": [{{"joints": [1, 2], "inverseBindMatrices": {inverse_binds}}}],
  "nodes": [{{"mesh": 0, "skin": 0, "translation": [100, 0, 0]}},
            {{"children": [2]}},
            {{"translation": [0, 1, 4]}}],
  "scenes": [{{"nodes": [0, 1]}}]"#
    );
    let path = a.write_embedded(&dir, "skin.gltf", &rest);
    // Joint 1 stands 4 along z from where it was bound: vertex 2 moves half of that.
    let expected = [Vec3::ZERO, Vec3::X, Vec3::new(0.0, 1.0, 2.0)];
    assert_near(&part(&path, "0/0/0").positions, &expected);
    assert_near(&whole(&path).positions, &expected);
    let imported = import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
    let o = imported.desc.objects[0].get_ref();
    assert_eq!(o.part.as_ref().unwrap().get_ref(), "0/0/0");
    assert!(o.transform.is_none(), "posed in world space");
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);

    // Without WEIGHTS_0 the skin cannot be applied: the mesh is shown unposed, with a warning.
    let broken = rest.replace(&format!(r#", "WEIGHTS_0": {weights}"#), "");
    let path = a.write_embedded(&dir, "unweighted.gltf", &broken);
    let imported = import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
    assert!(
        imported.warnings.iter().any(|w| w
            .contains("node 0: its skin 0 is not applied (mesh 0 primitive 0: it is skinned but has no WEIGHTS_0); the mesh is shown unposed")),
        "{:?}",
        imported.warnings
    );
    assert_eq!(
        imported.desc.objects[0]
            .get_ref()
            .part
            .as_ref()
            .unwrap()
            .get_ref(),
        "0/0"
    );
}

/// `KHR_draco_mesh_compression`: a sphere compressed by Google's Draco encoder (through DracoPy,
/// `bench/peers/draco.py`) decodes to the same triangles as its plain copy in the same file, its
/// positions within the 14-bit quantization's half step.
#[test]
fn draco_compressed_primitives_decode_to_their_plain_copies() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/draco-sphere.gltf");
    let (draco, plain) = (part(&path, "0/0"), part(&path, "1/0"));
    assert_eq!(draco.triangles, plain.triangles);
    assert_eq!(draco.positions.len(), plain.positions.len());
    let half_step = 2.0 / ((1 << 14) - 1) as f32 / 2.0;
    for (a, b) in draco.positions.iter().zip(&plain.positions) {
        assert!(
            (*a - *b).abs().max_element() <= half_step * 1.01,
            "{a} vs {b}"
        );
    }
    // A stream cut short is refused with a message, not a panic.
    let text = std::fs::read_to_string(&path).unwrap();
    let dir = Dir::new("draco");
    let cut = dir.path("cut.gltf");
    let shortened = text.replacen(r#""byteLength": 520"#, r#""byteLength": 100"#, 1);
    assert_ne!(shortened, text, "the Draco view's length is in the file");
    std::fs::write(&cut, shortened).unwrap();
    let e = read_gltf_part(&cut, Some("0/0"), &open(), &mut Fingerprint::default()).unwrap_err();
    assert!(
        e.to_string()
            .contains("mesh 0 primitive 0: its Draco stream cannot be decoded"),
        "{e}"
    );
}
