//! glTF files made here, byte by byte — a `.gltf` with an embedded base64 buffer, one with an
//! external `.bin`, a `.glb` — read back: triangles placed where the node transforms say,
//! materials, lights and cameras described, and broken files refused with a message naming the
//! file, never a panic.

use glam::{Mat4, Quat, Vec3};
use lucent::shape::Mesh;
use lucent_scene::LoadOptions;
use lucent_scene::desc::{MaterialKind, ObjectDesc};
use lucent_scene::gltf_file::{import_gltf, read_gltf_part};
use lucent_scene::hash::Fingerprint;
use std::path::{Path, PathBuf};

const FLOAT: u32 = 5126;
const U8: u32 = 5121;
const U16: u32 = 5123;
const U32: u32 = 5125;

/// A folder of its own for one test, removed when the test ends.
struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("lucent-gltf-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A glTF asset being made: one buffer, with its views and accessors as JSON.
#[derive(Default)]
struct Asset {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
}

impl Asset {
    /// A view of `bytes`, appended to the buffer at a 4-byte boundary.
    fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.views.push(format!(
            r#"{{"buffer": 0, "byteOffset": {offset}, "byteLength": {}}}"#,
            bytes.len()
        ));
        self.views.len() - 1
    }

    /// An accessor of `count` elements of `ty` over a new view of `bytes`; `extra` JSON members.
    fn accessor(
        &mut self,
        bytes: &[u8],
        component: u32,
        count: usize,
        ty: &str,
        extra: &str,
    ) -> usize {
        let view = self.view(bytes);
        self.accessors.push(format!(
            r#"{{"bufferView": {view}, "componentType": {component}, "count": {count}, "type": "{ty}"{extra}}}"#
        ));
        self.accessors.len() - 1
    }

    /// Positions, with the `min` and `max` the specification asks for.
    fn positions(&mut self, points: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = points
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in points {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let extra = format!(r#", "min": {lo:?}, "max": {hi:?}"#);
        self.accessor(&bytes, FLOAT, points.len(), "VEC3", &extra)
    }

    fn floats(&mut self, values: &[f32], width: usize) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let ty = ["SCALAR", "VEC2", "VEC3", "VEC4"][width - 1];
        self.accessor(&bytes, FLOAT, values.len() / width, ty, "")
    }

    fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = match component {
            U8 => indices.iter().map(|&i| i as u8).collect(),
            U16 => indices
                .iter()
                .flat_map(|&i| (i as u16).to_le_bytes())
                .collect(),
            _ => indices.iter().flat_map(|&i| i.to_le_bytes()).collect(),
        };
        self.accessor(&bytes, component, indices.len(), "SCALAR", "")
    }

    /// The document; `uri` is the buffer's (none: the GLB's BIN chunk); `rest` holds the other
    /// top-level members (scenes, nodes, meshes, ...), without a leading comma.
    fn json(&self, uri: Option<&str>, rest: &str) -> String {
        let uri = uri.map_or(String::new(), |u| format!(r#", "uri": "{u}""#));
        format!(
            r#"{{"asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {}{uri}}}],
  "bufferViews": [{}],
  "accessors": [{}],
  {rest}}}"#,
            self.bin.len(),
            self.views.join(", "),
            self.accessors.join(", ")
        )
    }

    fn write_embedded(&self, dir: &Dir, name: &str, rest: &str) -> PathBuf {
        let uri = format!("data:application/octet-stream;base64,{}", base64(&self.bin));
        let path = dir.path(name);
        std::fs::write(&path, self.json(Some(&uri), rest)).unwrap();
        path
    }

    fn write_external(&self, dir: &Dir, name: &str, bin_name: &str, rest: &str) -> PathBuf {
        std::fs::write(dir.path(bin_name), &self.bin).unwrap();
        let path = dir.path(name);
        std::fs::write(&path, self.json(Some(bin_name), rest)).unwrap();
        path
    }

    fn write_glb(&self, dir: &Dir, name: &str, rest: &str) -> PathBuf {
        let path = dir.path(name);
        std::fs::write(&path, self.glb(rest)).unwrap();
        path
    }

    /// A GLB file: a 12-byte header, the JSON chunk padded with spaces, the BIN chunk padded
    /// with zeros.
    fn glb(&self, rest: &str) -> Vec<u8> {
        let mut json = self.json(None, rest).into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        assert_eq!(out.len(), total);
        out
    }
}

fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn open() -> LoadOptions {
    LoadOptions::default()
}

fn whole(path: &Path) -> Mesh {
    read_gltf_part(path, None, &open(), &mut Fingerprint::default()).unwrap()
}

fn part(path: &Path, part: &str) -> Mesh {
    read_gltf_part(path, Some(part), &open(), &mut Fingerprint::default()).unwrap()
}

fn assert_near(got: &[Vec3], want: &[Vec3]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(g.abs_diff_eq(*w, 1e-5), "{got:?} vs {want:?}");
    }
}

/// The hierarchy of the acceptance test: one triangle (0,0,0), (1,0,0), (0,1,0), placed
/// twice: by node 1 (90° about z, moved by (0, 0, 1)) under node 0 (scaled by 2, moved by
/// (1, 2, 3)); and by node 2, a matrix that mirrors x and moves by (10, 0, 0).
fn hierarchy() -> (Asset, String) {
    let mut a = Asset::default();
    let pos = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let idx = a.indices(&[0, 1, 2], U16);
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let rest = format!(
        r#""scene": 0,
  "scenes": [{{"nodes": [0, 2]}}],
  "nodes": [
    {{"translation": [1, 2, 3], "scale": [2, 2, 2], "children": [1]}},
    {{"rotation": [0, 0, {s}, {s}], "translation": [0, 0, 1], "mesh": 0}},
    {{"matrix": [-1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  10, 0, 0, 1], "mesh": 0}}
  ],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}}}, "indices": {idx}}}]}}]"#
    );
    (a, rest)
}

/// Worked by hand: node 1's world matrix is T(1,2,3)·S(2)·T(0,0,1)·Rz(90°), so (x, y, z) goes
/// to (1 − 2y, 2 + 2x, 5 + 2z); node 2's sends (x, y, z) to (10 − x, y, z).
fn hierarchy_world_positions() -> Vec<Vec3> {
    vec![
        Vec3::new(1.0, 2.0, 5.0),
        Vec3::new(1.0, 4.0, 5.0),
        Vec3::new(-1.0, 2.0, 5.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(9.0, 0.0, 0.0),
        Vec3::new(10.0, 1.0, 0.0),
    ]
}

fn transform(o: &ObjectDesc) -> Mat4 {
    o.transform.as_ref().unwrap().get_ref().0.as_mat4()
}

#[test]
fn placed_primitives_are_held_to_the_objects_budget_before_any_is_decoded() {
    // One triangle placed by 300 nodes: 300 objects.
    let dir = Dir::new("objects-budget");
    let mut a = Asset::default();
    let pos = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let nodes: Vec<String> = (0..300)
        .map(|i| format!(r#"{{"mesh": 0, "translation": [{i}, 0, 0]}}"#))
        .collect();
    let roots: Vec<String> = (0..300).map(|i| i.to_string()).collect();
    let rest = format!(
        r#""scene": 0, "scenes": [{{"nodes": [{}]}}], "nodes": [{}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}}}}}]}}]"#,
        roots.join(", "),
        nodes.join(", ")
    );
    let file = a.write_embedded(&dir, "many.gltf", &rest);
    let limited = |n: u64| LoadOptions {
        limits: lucent_scene::Limits {
            objects: n,
            ..Default::default()
        },
        ..LoadOptions::default()
    };
    let Err(e) = import_gltf(&file, &limited(200), &mut Fingerprint::default()) else {
        panic!("300 objects are over a budget of 200");
    };
    assert!(
        e.message.contains(
            "the scene places 300 triangle primitives, an object each, over the budget of 200"
        ),
        "{e}"
    );
    let imported = import_gltf(&file, &limited(300), &mut Fingerprint::default()).unwrap();
    assert_eq!(imported.desc.objects.len(), 300);
}

#[test]
fn a_hierarchy_places_its_triangles_where_the_transforms_say() {
    let dir = Dir::new("hierarchy");
    let (a, rest) = hierarchy();
    let files = [
        a.write_embedded(&dir, "embedded.gltf", &rest),
        a.write_external(&dir, "external.gltf", "external.bin", &rest),
        a.write_glb(&dir, "binary.glb", &rest),
    ];
    let want = hierarchy_world_positions();
    for file in &files {
        let m = whole(file);
        assert_near(&m.positions, &want);
        // Node 2 mirrors: its triangle is turned around, so its front stays its front.
        assert_eq!(
            m.triangles,
            vec![[0, 1, 2], [3, 5, 4]],
            "{}",
            file.display()
        );

        let local = part(file, "0/0");
        assert_eq!(
            local.positions,
            vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            "the part is in the mesh's own space"
        );
        assert_eq!(local.triangles, vec![[0, 1, 2]]);

        let imported = import_gltf(file, &open(), &mut Fingerprint::default()).unwrap();
        let objects: Vec<&ObjectDesc> = imported.desc.objects.iter().map(|o| o.get_ref()).collect();
        assert_eq!(objects.len(), 2, "one object per placed primitive");
        let name = file.file_name().unwrap().to_str().unwrap();
        let mut placed = Vec::new();
        for o in &objects {
            assert_eq!(o.file.as_ref().unwrap().get_ref(), name);
            assert_eq!(o.part.as_ref().unwrap().get_ref(), "0/0");
            assert_eq!(o.material.get_ref(), "gltf:default");
            let t = transform(o);
            placed.extend(local.positions.iter().map(|&p| t.transform_point3(p)));
        }
        assert_near(&placed, &want);
        assert!(!imported.camera_given);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let m = &imported.desc.materials;
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].get_ref().kind(), MaterialKind::Diffuse);
    }
    // Node 1's matrix, computed independently of the importer's composition.
    let imported = import_gltf(&files[0], &open(), &mut Fingerprint::default()).unwrap();
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let node1 = Mat4::from_scale_rotation_translation(
        Vec3::splat(2.0),
        Quat::IDENTITY,
        Vec3::new(1.0, 2.0, 3.0),
    ) * Mat4::from_rotation_translation(Quat::from_xyzw(0.0, 0.0, s, s), Vec3::Z);
    assert!(transform(imported.desc.objects[0].get_ref()).abs_diff_eq(node1, 1e-6));
}

#[test]
fn the_description_survives_a_trip_through_toml() {
    let dir = Dir::new("toml");
    let (a, rest) = hierarchy();
    let file = a.write_glb(&dir, "scene.glb", &rest);
    let imported = import_gltf(&file, &open(), &mut Fingerprint::default()).unwrap();
    let text = toml::to_string(&imported.desc).unwrap();
    let back = lucent_scene::SceneFile::parse(PathBuf::from("back.toml"), PathBuf::new(), text)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.desc.objects.len(), 2);
    assert_eq!(
        transform(back.desc.objects[1].get_ref()),
        transform(imported.desc.objects[1].get_ref())
    );
}

#[test]
fn the_inputs_fingerprint_covers_the_file_and_its_buffers() {
    let dir = Dir::new("fingerprint");
    let (a, rest) = hierarchy();
    let file = a.write_external(&dir, "s.gltf", "s.bin", &rest);
    let mut want = Fingerprint::default();
    want.add(&std::fs::read(&file).unwrap());
    want.add(&a.bin);
    let mut got = Fingerprint::default();
    read_gltf_part(&file, None, &open(), &mut got).unwrap();
    assert_eq!(got, want);
    let mut imported = Fingerprint::default();
    import_gltf(&file, &open(), &mut imported).unwrap();
    assert_eq!(imported, want);
}

/// The same quad, (0,0,0) (1,0,0) (1,1,0) (0,1,0), as indexed lists of three index widths, a
/// non-indexed list, a strip and a fan: six primitives of mesh 0.
fn quads() -> (Asset, String) {
    let mut a = Asset::default();
    let corners = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let shared = a.positions(&corners);
    let list = [0, 1, 2, 0, 2, 3];
    let i8 = a.indices(&list, U8);
    let i16 = a.indices(&list, U16);
    let i32 = a.indices(&list, U32);
    let unrolled = a.positions(&list.map(|i| corners[i as usize]));
    // The strip 1, 2, 0, 3: triangles (1, 2, 0) and, odd, (2, 3, 0).
    let strip = a.positions(&[corners[1], corners[2], corners[0], corners[3]]);
    let fan = a.indices(&[0, 1, 2, 3], U8);
    let p = |pos: usize, extra: &str| format!(r#"{{"attributes": {{"POSITION": {pos}}}{extra}}}"#);
    let prims = [
        p(shared, &format!(r#", "indices": {i8}"#)),
        p(shared, &format!(r#", "indices": {i16}"#)),
        p(shared, &format!(r#", "indices": {i32}"#)),
        p(unrolled, ""),
        p(strip, r#", "mode": 5"#),
        p(shared, &format!(r#", "indices": {fan}, "mode": 6"#)),
    ];
    let rest = format!(
        r#""nodes": [{{"mesh": 0}}], "meshes": [{{"primitives": [{}]}}]"#,
        prims.join(", ")
    );
    (a, rest)
}

/// Each triangle's corners, rotated to start at its smallest (so the same triangle, with the
/// same winding, compares equal whichever corner is first).
fn corner_triples(m: &Mesh) -> Vec<[[i32; 3]; 3]> {
    let mut out: Vec<[[i32; 3]; 3]> = m
        .triangles
        .iter()
        .map(|t| {
            let c = t.map(|i| m.positions[i as usize].to_array().map(|v| v as i32));
            let first = (0..3).min_by_key(|&k| c[k]).unwrap();
            [c[first], c[(first + 1) % 3], c[(first + 2) % 3]]
        })
        .collect();
    out.sort();
    out
}

#[test]
fn indexed_unindexed_strips_and_fans_give_the_same_triangles() {
    let dir = Dir::new("quads");
    let (a, rest) = quads();
    let file = a.write_embedded(&dir, "quads.gltf", &rest);
    let reference = corner_triples(&part(&file, "0/0"));
    assert_eq!(
        reference,
        vec![
            [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
            [[0, 0, 0], [1, 1, 0], [0, 1, 0]]
        ]
    );
    for p in 1..6 {
        assert_eq!(
            corner_triples(&part(&file, &format!("0/{p}"))),
            reference,
            "primitive {p}"
        );
    }
    assert_eq!(part(&file, "0/3").positions.len(), 6);
    // The whole scene: all six merged, one node at the origin.
    assert_eq!(whole(&file).triangles.len(), 12);
}

#[test]
fn attributes_are_read_and_kept_in_the_mesh() {
    let dir = Dir::new("attributes");
    let mut a = Asset::default();
    let pos = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let normals = a.floats(&[0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0], 3);
    let uvs = a.floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], 2);
    // Normalised unsigned bytes, RGBA.
    let colors = a.accessor(
        &[255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 51, 255],
        U8,
        3,
        "VEC4",
        r#", "normalized": true"#,
    );
    let rest = format!(
        r#""nodes": [{{"mesh": 0, "translation": [0, 0, 5], "scale": [1, 1, -1]}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {pos}, "NORMAL": {normals}, "TEXCOORD_0": {uvs}, "COLOR_0": {colors}}}}}]}}]"#
    );
    let file = a.write_embedded(&dir, "attributes.gltf", &rest);
    let m = part(&file, "0/0");
    assert_eq!(m.normals, vec![Vec3::Z; 3], "normalised");
    assert_eq!(
        m.uvs[1],
        glam::Vec2::new(1.0, 0.0),
        "glTF's convention, as is"
    );
    assert_eq!(m.colors[0], lucent::Rgb::new(1.0, 0.0, 0.0));
    assert_eq!(m.colors[2], lucent::Rgb::new(0.0, 0.0, 0.2));
    let w = whole(&file);
    assert_eq!(w.positions[1], Vec3::new(1.0, 0.0, 5.0));
    // The normal follows the mirror; the winding is turned around with it.
    assert_eq!(w.normals[0], -Vec3::Z);
    assert_eq!(w.triangles, vec![[0, 2, 1]]);
    assert_eq!(w.uvs.len(), 3);
}

#[test]
fn materials_lights_and_camera_are_described() {
    let dir = Dir::new("described");
    std::fs::write(dir.path("wood grain.png"), b"not read by the importer").unwrap();
    let mut a = Asset::default();
    let pos = a.positions(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let rest = format!(
        r#""extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_dispersion"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "color": [1, 0.5, 0.25], "intensity": 683}},
    {{"type": "spot", "intensity": 1366, "spot": {{"innerConeAngle": 0.25, "outerConeAngle": 0.5}}}}
  ]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2, 3, 4]}}],
  "nodes": [
    {{"mesh": 0}},
    {{"translation": [0, 5, 0], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
    {{"translation": [0, 4, 0], "rotation": [{neg}, 0, 0, {s}], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
    {{"translation": [0, 1, 10], "camera": 0}},
    {{"camera": 1}}
  ],
  "cameras": [
    {{"type": "perspective", "perspective": {{"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}}},
    {{"type": "orthographic", "orthographic": {{"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}}}
  ],
  "images": [{{"uri": "wood%20grain.png"}}, {{"uri": "data:image/png;base64,AAAA"}}],
  "textures": [{{"source": 0}}, {{"source": 1}}],
  "materials": [
    {{"name": "Wood", "pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}, "metallicFactor": 0}}}},
    {{"name": "Glass", "pbrMetallicRoughness": {{"metallicFactor": 0, "roughnessFactor": 0.3}}, "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}}}}},
    {{"name": "Decal", "pbrMetallicRoughness": {{"baseColorTexture": {{"index": 1}}, "baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}}}},
    {{"name": "Unused"}}
  ],
  "meshes": [{{"primitives": [
    {{"attributes": {{"POSITION": {pos}}}, "material": 0}},
    {{"attributes": {{"POSITION": {pos}}}, "material": 1}},
    {{"attributes": {{"POSITION": {pos}}}, "material": 2}},
    {{"attributes": {{"POSITION": {pos}}}, "mode": 1}}
  ]}}]"#,
        neg = -s
    );
    let file = a.write_glb(&dir, "described.glb", &rest);
    let imported = import_gltf(&file, &open(), &mut Fingerprint::default()).unwrap();
    let d = &imported.desc;

    let materials: Vec<_> = d.materials.iter().map(|m| m.get_ref()).collect();
    let names: Vec<&str> = materials
        .iter()
        .map(|m| m.name.get_ref().as_str())
        .collect();
    assert_eq!(
        names,
        ["gltf:Wood", "gltf:Glass", "gltf:Decal"],
        "only the used ones"
    );
    assert!(materials.iter().all(|m| m.kind() == MaterialKind::Pbr));
    let mut wood = lucent_scene::desc::ImageMapDesc::new("wood grain.png");
    wood.encoding = Some(lucent_scene::desc::texture::Encoding::Srgb);
    assert_eq!(
        materials[0].base_color,
        Some(lucent_scene::desc::TextureDesc::Image(wood))
    );
    assert!(materials[1].transmission.is_some());
    // An image held in the file is named by the file and its index, times the factor.
    let mut decal = lucent_scene::desc::ImageMapDesc::new("described.glb");
    decal.encoding = Some(lucent_scene::desc::texture::Encoding::Srgb);
    decal.gltf_image = Some(1);
    assert_eq!(
        materials[2].base_color,
        Some(lucent_scene::desc::TextureDesc::Product(
            Box::new(lucent_scene::desc::TextureDesc::Solid(lucent::Rgb::gray(
                0.5
            ))),
            Box::new(lucent_scene::desc::TextureDesc::Image(decal))
        ))
    );
    let objects: Vec<(&str, &str)> = d
        .objects
        .iter()
        .map(|o| {
            let o = o.get_ref();
            (
                o.part.as_ref().unwrap().get_ref().as_str(),
                o.material.get_ref().as_str(),
            )
        })
        .collect();
    // The three primitives read the same accessors: one part, three materials.
    assert_eq!(
        objects,
        [
            ("0/0", "gltf:Wood"),
            ("0/0", "gltf:Glass"),
            ("0/0", "gltf:Decal")
        ],
        "the line primitive is skipped"
    );

    assert_eq!(d.lights.len(), 2);
    let point = d.lights[0].get_ref();
    assert_eq!(point.kind, lucent_scene::desc::LightKind::Point);
    assert_eq!(
        point.intensity.unwrap().0,
        lucent::Rgb::new(1.0, 0.5, 0.25),
        "683 cd is 1 W/sr"
    );
    assert_eq!(
        point.position.as_ref().unwrap().get_ref().0,
        glam::DVec3::new(0.0, 5.0, 0.0)
    );
    let spot = d.lights[1].get_ref();
    assert!(
        spot.direction
            .as_ref()
            .unwrap()
            .get_ref()
            .0
            .abs_diff_eq(Vec3::NEG_Y, 1e-6)
    );
    assert_eq!(
        spot.cutoff.as_ref().unwrap().get_ref().0,
        0.5f32.to_degrees()
    );

    assert!(imported.camera_given);
    let c = d.camera.get_ref();
    assert_eq!(c.eye.0, glam::DVec3::new(0.0, 1.0, 10.0));
    assert_eq!(c.look_at.0, glam::DVec3::new(0.0, 1.0, 9.0));
    assert_eq!(c.up.0, Vec3::Y);
    assert_eq!(c.fov.0, 0.8f32.to_degrees());
    assert_eq!(
        (*d.image.width.get_ref(), *d.image.height.get_ref()),
        (900, 600)
    );

    let shown = file.display().to_string();
    let w = &imported.warnings;
    for expected in [
        "extension KHR_materials_dispersion is not supported; ignored",
        "mesh 0 primitive 3 is drawn as Lines, not triangles; skipped",
        "node 4: camera 1 ignored: the first camera is used",
    ] {
        assert!(
            w.contains(&format!("{shown}: {expected}")),
            "missing `{expected}` in {w:#?}"
        );
    }
    assert_eq!(w.len(), 3, "{w:#?}");
}

// Broken files refused, each with a message naming the file and the cause.
#[path = "gltf/refused.rs"]
mod refused;

// Shared geometry, quantized attributes, morph targets, skins and Draco.
#[path = "gltf/geometry.rs"]
mod geometry;

// KHR_materials_volume's attenuation as a medium.
#[path = "gltf/volume.rs"]
mod volume;
