//! Broken glTF files: each refused with a message naming the file and the cause, never a panic,
//! and no allocation a file merely claims.

use super::*;

/// The error from reading `path` whole, checked to name the file and to say `cause`; the
/// importer must give the same error.
fn assert_refused(path: &Path, options: &LoadOptions, cause: &str) {
    let e = read_gltf_part(path, None, options, &mut Fingerprint::default()).unwrap_err();
    let shown = e.to_string();
    assert!(shown.starts_with(&path.display().to_string()), "{shown}");
    assert!(shown.contains(cause), "`{shown}` does not say `{cause}`");
    let again = import_gltf(path, options, &mut Fingerprint::default()).unwrap_err();
    assert_eq!(again, e);
}

#[test]
fn a_truncated_glb_is_refused_at_every_length() {
    let dir = Dir::new("truncated");
    let (a, rest) = hierarchy();
    let bytes = a.glb(&rest);
    let path = dir.path("cut.glb");
    for cut in 4..bytes.len() {
        std::fs::write(&path, &bytes[..cut]).unwrap();
        let e = read_gltf_part(&path, None, &open(), &mut Fingerprint::default()).unwrap_err();
        assert!(
            e.to_string().starts_with(&path.display().to_string()),
            "{e}"
        );
        assert!(e.message.contains("truncated"), "cut at {cut}: {e}");
    }
    std::fs::write(&path, &bytes[..bytes.len() - 4]).unwrap();
    assert_refused(
        &path,
        &open(),
        &format!(
            "the GLB file is truncated: its header says {} bytes, the file has {}",
            bytes.len(),
            bytes.len() - 4
        ),
    );
}

/// A triangle primitive with `positions` and `indices`, in an embedded .gltf; `edit` may
/// change the JSON text.
fn broken(
    dir: &Dir,
    positions: &[[f32; 3]],
    indices: &[u32],
    edit: impl Fn(String) -> String,
) -> PathBuf {
    let mut a = Asset::default();
    let pos = a.positions(positions);
    let idx = a.indices(indices, U16);
    let rest = format!(
        r#""nodes": [{{"mesh": 0}}], "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}}}, "indices": {idx}}}]}}]"#
    );
    let uri = format!("data:application/octet-stream;base64,{}", base64(&a.bin));
    let path = dir.path("broken.gltf");
    std::fs::write(&path, edit(a.json(Some(&uri), &rest))).unwrap();
    path
}

const TRIANGLE: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

#[test]
fn an_accessor_claiming_a_trillion_elements_is_refused_before_allocating() {
    let dir = Dir::new("huge");
    let path = broken(&dir, &TRIANGLE, &[0, 1, 2], |j| {
        j.replacen(
            r#""count": 3, "type": "VEC3""#,
            r#""count": 1000000000000, "type": "VEC3""#,
            1,
        )
    });
    assert_refused(
        &path,
        &open(),
        "mesh 0 primitive 0: accessor 0 claims 1000000000000 elements (12000000000000 bytes from byte 0), more than the 36 bytes of its buffer view hold",
    );
    // A sparse accessor without a buffer view has only its count to go by: capped, at far
    // less than the 2^28 elements of a merged mesh (with that cap, a 500-byte file made the
    // reader ask for 3 GiB of zero positions at once, and 20 GiB by the end of the build).
    for count in [1_000_000_000_000u64, 1 << 28, (1 << 20) + 1] {
        let path = broken(&dir, &TRIANGLE, &[0, 1, 2], |j| {
            j.replacen(r#""bufferView": 0, "#, "", 1).replacen(
                r#""count": 3, "type": "VEC3""#,
                &format!(r#""count": {count}, "type": "VEC3", {SPARSE}"#),
                1,
            )
        });
        assert_refused(
            &path,
            &open(),
            &format!(
                "accessor 0 has no buffer view and claims {count} elements; at most 1048576 are supported without one"
            ),
        );
    }
}

/// Vertex 2 replaced by vertex 1's position: the index 2 is the third u16 of view 1, the
/// value the second vector of view 0.
const SPARSE: &str = r#""sparse": {"count": 1, "indices": {"bufferView": 1, "byteOffset": 4, "componentType": 5123}, "values": {"bufferView": 0, "byteOffset": 12}}"#;

#[test]
fn sparse_accessors_replace_their_elements() {
    let dir = Dir::new("sparse");
    let on_base = broken(&dir, &TRIANGLE, &[0, 1, 2], |j| {
        j.replacen(
            r#""type": "VEC3""#,
            &format!(r#""type": "VEC3", {SPARSE}"#),
            1,
        )
    });
    assert_eq!(
        part(&on_base, "0/0").positions,
        [Vec3::ZERO, Vec3::X, Vec3::X]
    );
    let on_zeros = broken(&dir, &TRIANGLE, &[0, 1, 2], |j| {
        j.replacen(r#""bufferView": 0, "#, "", 1).replacen(
            r#""type": "VEC3""#,
            &format!(r#""type": "VEC3", {SPARSE}"#),
            1,
        )
    });
    assert_eq!(
        part(&on_zeros, "0/0").positions,
        [Vec3::ZERO, Vec3::ZERO, Vec3::X]
    );
    let outside = broken(&dir, &TRIANGLE, &[0, 1, 7], |j| {
        j.replacen(
            r#""type": "VEC3""#,
            &format!(r#""type": "VEC3", {SPARSE}"#),
            1,
        )
    });
    assert_refused(
        &outside,
        &open(),
        "the sparse indices of accessor 0: index 7 out of range (3 elements)",
    );
}

#[test]
fn an_index_out_of_range_is_refused() {
    let dir = Dir::new("index");
    let path = broken(&dir, &TRIANGLE, &[0, 1, 99], |j| j);
    assert_refused(
        &path,
        &open(),
        "mesh 0 primitive 0: index 99 out of range (3 vertices)",
    );
}

#[test]
fn a_nan_position_is_refused() {
    let dir = Dir::new("nan");
    let path = broken(
        &dir,
        &[[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[0, 1, 2],
        |j| j.replace("NaN", "0"),
    );
    assert_refused(
        &path,
        &open(),
        "mesh 0 primitive 0: position 1 is not finite: [NaN, 0, 0]",
    );
}

#[test]
fn a_missing_bin_file_is_named() {
    let dir = Dir::new("missing");
    let (a, rest) = hierarchy();
    let path = a.write_external(&dir, "s.gltf", "s.bin", &rest);
    std::fs::remove_file(dir.path("s.bin")).unwrap();
    let bin = dir.path("s.bin").display().to_string();
    assert_refused(&path, &open(), &format!("buffer 0: cannot read `{bin}`: "));
}

#[test]
fn the_sandbox_refuses_a_buffer_outside_the_folder() {
    let dir = Dir::new("sandbox");
    let (a, rest) = hierarchy();
    std::fs::create_dir(dir.path("scenes")).unwrap();
    std::fs::write(dir.path("x.bin"), &a.bin).unwrap();
    let path = dir.path("scenes/escape.gltf");
    std::fs::write(&path, a.json(Some("../x.bin"), &rest)).unwrap();
    let sandbox = LoadOptions {
        sandbox: true,
        ..LoadOptions::default()
    };
    assert_refused(
        &path,
        &sandbox,
        "buffer 0: `../x.bin` leaves the scene's folder, refused by --sandbox",
    );
    // The same file reads without the sandbox: the refusal is the sandbox's.
    assert_eq!(whole(&path).triangles.len(), 2);
    // An image outside the folder is refused too.
    let (b, rest) = hierarchy();
    let rest = rest.replace(r#""indices": 1}"#, r#""indices": 1, "material": 0}"#)
        + r#", "images": [{"uri": "..%2Fsecret.png"}], "textures": [{"source": 0}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}]"#;
    let path = b.write_glb(&dir, "image.glb", &rest);
    let e = import_gltf(&path, &sandbox, &mut Fingerprint::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: image 0: `../secret.png` leaves the scene's folder, refused by --sandbox",
            path.display()
        )
    );
    import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
}

#[test]
fn a_buffer_must_be_a_regular_file() {
    let dir = Dir::new("not-a-file");
    let (a, rest) = hierarchy();
    std::fs::create_dir(dir.path("folder.bin")).unwrap();
    let path = dir.path("s.gltf");
    std::fs::write(&path, a.json(Some("folder.bin"), &rest)).unwrap();
    let folder = dir.path("folder.bin").display().to_string();
    assert_refused(
        &path,
        &open(),
        &format!("buffer 0: cannot read `{folder}`: a folder: refused"),
    );
    // A FIFO would block the reader until a writer came: refused before it is opened.
    let fifo = dir.path("pipe.bin");
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        std::fs::write(&path, a.json(Some("pipe.bin"), &rest)).unwrap();
        let fifo = fifo.display().to_string();
        assert_refused(
            &path,
            &open(),
            &format!("buffer 0: cannot read `{fifo}`: not a regular file"),
        );
    }
}

#[test]
fn singular_nodes_are_skipped_with_a_warning_and_keep_their_light() {
    let dir = Dir::new("singular");
    let mut a = Asset::default();
    let pos = a.positions(&TRIANGLE);
    let rest = format!(
        r#""extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "point"}}]}}}},
  "nodes": [
    {{"mesh": 0, "scale": [1, 0, 1], "translation": [0, 3, 0], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
    {{"mesh": 0, "translation": [0, 0, 2]}}
  ],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}}}}}]}}]"#
    );
    let path = a.write_glb(&dir, "flat.glb", &rest);
    let imported = import_gltf(&path, &open(), &mut Fingerprint::default()).unwrap();
    assert_eq!(imported.desc.objects.len(), 1);
    assert_eq!(
        imported.desc.lights[0]
            .get_ref()
            .position
            .as_ref()
            .unwrap()
            .get_ref()
            .0,
        glam::DVec3::new(0.0, 3.0, 0.0)
    );
    assert_eq!(
        imported.warnings,
        [format!(
            "{}: node 0: its world matrix is singular, projective or not finite; its mesh 0 is skipped",
            path.display()
        )]
    );
    assert_eq!(
        whole(&path).positions,
        [
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0)
        ]
    );
}

#[test]
fn parts_are_checked() {
    let dir = Dir::new("parts");
    let (a, rest) = quads();
    let file = a.write_glb(&dir, "q.glb", &rest);
    let read = |p: &str| read_gltf_part(&file, Some(p), &open(), &mut Fingerprint::default());
    assert!(
        read("0")
            .unwrap_err()
            .message
            .contains("is not MESH/PRIMITIVE")
    );
    assert_eq!(
        read("1/0").unwrap_err().message,
        "part `1/0`: there is no mesh 1 (the file has 1)"
    );
    assert_eq!(
        read("0/6").unwrap_err().message,
        "part `0/6`: mesh 0 has no primitive 6 (it has 6)"
    );
}

#[test]
fn mangled_files_never_panic() {
    // Every byte of a small GLB and of a .gltf, changed in turn: whatever the reader makes of
    // each, it answers with a mesh or an error.
    let dir = Dir::new("mangled");
    let (a, rest) = hierarchy();
    let glb = a.glb(&rest);
    let gltf = a.json(
        Some(&format!(
            "data:application/octet-stream;base64,{}",
            base64(&a.bin)
        )),
        &rest,
    );
    let path = dir.path("m.glb");
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for (k, original) in [glb, gltf.into_bytes()].into_iter().enumerate() {
        for i in 0..original.len() {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mut bytes = original.clone();
            bytes[i] = if k == 0 {
                bytes[i] ^ (1 << (state % 8))
            } else {
                b"0123456789-e.,]}"[(state % 16) as usize]
            };
            std::fs::write(&path, &bytes).unwrap();
            let _ = read_gltf_part(&path, None, &open(), &mut Fingerprint::default());
            let _ = import_gltf(&path, &open(), &mut Fingerprint::default());
        }
    }
}
