//! `serialized` shapes: a file written through Mitsuba's own zlib stream, and each of its shapes
//! as Mitsuba 3.9.1 loaded it and wrote it back as a PLY (`bench/peers/serialized.py` made the
//! three files in `tests/data/`). lucent's reading of the serialized file must give the
//! triangles Mitsuba's PLY holds.

use super::support::*;
use glam::{Vec2, Vec3};
use lucent_scene::desc::ObjectKind;
use lucent_scene::hash::Fingerprint;
use lucent_scene::mesh_file::{read_mesh, read_mesh_part};
use lucent_scene::{LoadOptions, SceneFile};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

const SERIALIZED: &str = "mitsuba-shapes.serialized";

/// The texture coordinates of a binary little-endian PLY whose vertices are `float`s, by the
/// properties `s`, `t` (as Mitsuba writes them) or `u`, `v`: lucent's PLY reader reads none.
fn ply_uvs(path: &Path) -> Vec<Vec2> {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap();
    let header = std::str::from_utf8(&bytes[..end]).unwrap();
    assert!(header.contains("format binary_little_endian 1.0"));
    let mut count = 0;
    let mut props = Vec::new();
    let mut in_vertex = false;
    for line in header.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["element", name, n] => {
                in_vertex = *name == "vertex";
                if in_vertex {
                    count = n.parse().unwrap();
                }
            }
            ["property", ty, name] if in_vertex => {
                assert_eq!(*ty, "float", "{line}");
                props.push(*name);
            }
            _ => {}
        }
    }
    let slot = |names: [&str; 2]| props.iter().position(|p| names.contains(p)).unwrap();
    let (s, t) = (slot(["s", "u"]), slot(["t", "v"]));
    let body = &bytes[end + 11..];
    (0..count)
        .map(|i| {
            let at = |k: usize| {
                let o = 4 * (i * props.len() + k);
                f32::from_le_bytes(body[o..o + 4].try_into().unwrap())
            };
            Vec2::new(at(s), at(t))
        })
        .collect()
}

#[test]
fn each_shape_reads_as_the_ply_mitsuba_wrote_of_it() {
    let path = data(SERIALIZED);
    // Shape 0: single precision; shape 1: double precision, with colours Mitsuba reads past.
    for k in 0..2 {
        let ours = read_mesh_part(
            &path,
            Some(&k.to_string()),
            &LoadOptions::default(),
            &mut Fingerprint::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let ply = data(&format!("mitsuba-shapes-{k}.ply"));
        let theirs = read_mesh(&ply).unwrap_or_else(|e| panic!("{e}"));
        let uvs = ply_uvs(&ply);
        assert!(!theirs.triangles.is_empty());
        assert_eq!(ours.triangles, theirs.triangles, "shape {k}");
        assert_eq!(ours.positions.len(), theirs.positions.len(), "shape {k}");
        let close = |a: Vec3, b: Vec3| a.abs_diff_eq(b, 1e-6);
        for (i, (a, b)) in ours.positions.iter().zip(&theirs.positions).enumerate() {
            assert!(
                close(*a, *b),
                "shape {k}, vertex {i}: {a} against Mitsuba's {b}"
            );
        }
        assert_eq!(ours.normals.len(), theirs.normals.len(), "shape {k}");
        for (i, (a, b)) in ours.normals.iter().zip(&theirs.normals).enumerate() {
            assert!(
                close(*a, *b),
                "shape {k}, normal {i}: {a} against Mitsuba's {b}"
            );
        }
        // Mitsuba keeps the coordinates as written (an OBJ's v it flips), and so does lucent:
        // an image lies on the mesh as in Mitsuba.
        assert_eq!(ours.uvs.len(), uvs.len(), "shape {k}");
        for (i, (a, b)) in ours.uvs.iter().zip(&uvs).enumerate() {
            assert!(
                a.abs_diff_eq(*b, 1e-6),
                "shape {k}, uv {i}: {a} against Mitsuba's {b}"
            );
        }
        assert_eq!(
            ours.colors.len(),
            if k == 1 { ours.positions.len() } else { 0 }
        );
    }
    // No part is shape 0.
    assert_eq!(
        read_mesh(&path).unwrap(),
        read_mesh_part(
            &path,
            Some("0"),
            &LoadOptions::default(),
            &mut Fingerprint::default()
        )
        .unwrap()
    );
}

#[test]
fn serialized_shapes_map_onto_mesh_objects_with_their_index_as_part() {
    let dir = Dir::new("serialized");
    dir.write(
        "meshes/shapes.serialized",
        std::fs::read(data(SERIALIZED)).unwrap(),
    );
    let text = scene(
        r#"    <shape type="serialized">
        <string name="filename" value="meshes/shapes.serialized"/>
    </shape>
    <shape type="serialized">
        <string name="filename" value="meshes/shapes.serialized"/>
        <integer name="shape_index" value="1"/>
        <boolean name="face_normals" value="true"/>
        <boolean name="flip_normals" value="true"/>
        <transform name="to_world"><translate x="3"/></transform>
    </shape>"#,
    );
    let path = dir.write("shapes.xml", &text);
    let imported = import(&path);
    let o = objects(&imported);
    assert!(o.iter().all(|o| o.kind == ObjectKind::Mesh));
    assert_eq!(
        o[0].file.as_ref().unwrap().get_ref(),
        "meshes/shapes.serialized"
    );
    assert_eq!(o[0].part.as_ref().unwrap().get_ref(), "0");
    assert_eq!((o[0].smooth, o[0].flip_normals), (None, None));
    assert_eq!(o[1].part.as_ref().unwrap().get_ref(), "1");
    assert_eq!((o[1].smooth, o[1].flip_normals), (Some(false), Some(true)));
    assert!(near(
        transform(o[1]).transform_point3(Vec3::ZERO),
        3.0 * Vec3::X
    ));
    let (file, loaded) = load(&path);
    let c = loaded.scene.counts();
    assert_eq!((c.instances, c.triangles), (2, 108 + 64));
    // `lucent convert` writes the shape index as the mesh's part.
    let toml = file.to_toml(&loaded).unwrap();
    assert!(toml.contains("part = \"1\""), "{toml}");
    let again = SceneFile::parse(path.clone(), dir.0.clone(), toml).unwrap();
    assert_eq!(again.build().unwrap().scene.counts().triangles, 108 + 64);
}

#[test]
fn a_bad_shape_index_is_refused() {
    let dir = Dir::new("serialized-index");
    dir.write(
        "shapes.serialized",
        std::fs::read(data(SERIALIZED)).unwrap(),
    );
    let shape = |index: &str| {
        scene(&format!(
            r#"    <shape type="serialized">
        <string name="filename" value="shapes.serialized"/>
        <integer name="shape_index" value="{index}"/>
    </shape>"#
        ))
    };
    let text = shape("-1");
    let path = dir.write("negative.xml", &text);
    let e = import_error(&path, &open());
    assert_error(
        &e,
        &path,
        after(&text, r#"shape_index" value=""#),
        "a shape index is a number of 0 or more",
    );
    // Past the file's shapes: the build says so, naming the file.
    let path = dir.write("past.xml", shape("2"));
    let e = SceneFile::read_with(&path, &open())
        .and_then(|f| f.build())
        .unwrap_err();
    assert_eq!(e.file, dir.path("shapes.serialized"));
    assert_eq!(
        e.message,
        "shape index 2 is out of range: the file holds 2 shapes (0 to 1)"
    );
}
