//! Imported scenes through the command line: every shared mesh renders by itself, broken and
//! hostile files are refused with the file (and line) at fault, and `lucent convert` writes
//! TOML that renders the very same image as the original.

mod common;

use common::{assert_success, lucent, read_pfm};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `lucent args...` in `dir` and returns its stderr, which must be one clean error line.
fn refused_in(dir: &Path, args: &[&str]) -> String {
    refused_by(lucent().current_dir(dir).args(args))
}

fn refused_by(command: &mut Command) -> String {
    let output = command.output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("internal error"),
        "{stderr}"
    );
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "one error line: {stderr}");
    errors[0].to_string()
}

fn write(dir: &Path, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, contents).unwrap();
    path
}

fn render(scene: &Path, out: &Path, args: &[&str]) {
    let output = lucent()
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(out)
        .args(args)
        .output()
        .unwrap();
    assert_success(&output);
}

#[test]
fn every_shared_mesh_renders_by_itself() {
    let meshes = lucent_scene::data_dir().join("meshes");
    if !meshes.is_dir() {
        eprintln!("skipping: {} is not here", meshes.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut names: Vec<PathBuf> = std::fs::read_dir(&meshes)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    assert_eq!(names.len(), 7);
    for mesh in names {
        let out = dir.path().join("out.pfm");
        render(&mesh, &out, &["--width", "48", "--height", "36"]);
        let img = read_pfm(&out);
        // The framing camera puts the mesh in the middle, lit, over the grey background.
        let background = img.at(0, 0);
        let covered = img.pixels.iter().filter(|p| **p != background).count();
        let share = covered as f32 / img.pixels.len() as f32;
        assert!((0.05..0.9).contains(&share), "{}: {share}", mesh.display());
        assert!(
            img.center()[0] > background[0],
            "{}: the middle is lit",
            mesh.display()
        );
    }
}

/// A binary little-endian PLY holding `vertices` (claimed) and one triangle.
fn binary_ply(claimed_vertices: u64, body_vertices: usize) -> Vec<u8> {
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {claimed_vertices}\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    for v in 0..body_vertices {
        for c in [v as f32, (v % 2) as f32, 0.0] {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    bytes.push(3);
    for i in [0i32, 1, 2] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes
}

#[test]
fn a_truncated_binary_ply_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let full = binary_ply(3, 3);
    write(dir.path(), "whole.ply", &full);
    let output = lucent()
        .current_dir(dir.path())
        .args(["info", "whole.ply"])
        .output()
        .unwrap();
    assert_success(&output);
    for cut in [full.len() - 1, full.len() - 13, full.len() - 40] {
        write(dir.path(), "cut.ply", &full[..cut]);
        let e = refused_in(dir.path(), &["info", "cut.ply"]);
        assert!(e.starts_with("error: cut.ply:"), "{e}");
    }
}

#[test]
fn a_trillion_vertex_header_is_refused_before_allocating() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "huge.ply", binary_ply(1_000_000_000_000, 3));
    // Under a 2 GiB address-space limit, allocating for the claim would abort the process.
    let e = refused_by(
        Command::new("sh")
            .current_dir(dir.path())
            .args(["-c", "ulimit -v 2097152; exec \"$0\" info huge.ply"])
            .arg(env!("CARGO_BIN_EXE_lucent")),
    );
    assert!(
        e.starts_with("error: huge.ply: the header declares 1000000000000 `vertex` elements"),
        "{e}"
    );
}

#[test]
fn face_indices_out_of_range_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "a.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n",
    );
    let e = refused_in(dir.path(), &["info", "a.obj"]);
    assert_eq!(
        e,
        "error: a.obj:5:1: vertex index 4 is out of range (3 in the file)"
    );
    write(
        dir.path(),
        "a.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
    );
    let e = refused_in(dir.path(), &["info", "a.ply"]);
    assert!(e.starts_with("error: a.ply:"), "{e}");
    assert!(e.contains("uses vertex 3, but there are 3 vertices"), "{e}");
}

#[test]
fn nan_and_infinite_coordinates_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    for (value, word) in [("nan", "nan"), ("inf", "inf"), ("-1e39", "-1e39")] {
        write(
            dir.path(),
            "a.obj",
            format!("v 0 0 0\nv 1 {value} 0\nv 0 1 0\nf 1 2 3\n"),
        );
        let e = refused_in(dir.path(), &["info", "a.obj"]);
        assert_eq!(
            e,
            format!("error: a.obj:2:1: vertex: `{word}` is not finite")
        );
    }
}

#[test]
fn an_unknown_xml_plugin_names_its_place() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "s.xml",
        "<scene version=\"3.0.0\">\n    <bsdf type=\"hair\" id=\"h\"/>\n</scene>\n",
    );
    let e = refused_in(dir.path(), &["info", "s.xml"]);
    assert!(
        e.starts_with("error: s.xml:2:5: unknown bsdf type `hair`"),
        "{e}"
    );
}

#[test]
fn a_missing_referenced_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "s.xml",
        "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"gone.obj\"/>\n  </shape>\n</scene>\n",
    );
    let e = refused_in(dir.path(), &["info", "s.xml"]);
    assert!(e.starts_with("error: "), "{e}");
    assert!(e.contains("gone.obj"), "{e}");
    write(
        dir.path(),
        "s.toml",
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[material]]\nname = \"m\"\n[[object]]\ntype = \"mesh\"\nfile = \"gone.ply\"\nmaterial = \"m\"\n",
    );
    let e = refused_in(dir.path(), &["info", "s.toml"]);
    assert!(e.starts_with("error: s.toml:8:"), "{e}");
    assert!(e.contains("gone.ply"), "{e}");
}

#[test]
fn an_include_cycle_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "a.xml",
        "<scene version=\"3.0.0\">\n  <include filename=\"b.xml\"/>\n</scene>\n",
    );
    write(
        dir.path(),
        "b.xml",
        "<scene version=\"3.0.0\">\n\n  <include filename=\"a.xml\"/>\n</scene>\n",
    );
    let e = refused_in(dir.path(), &["info", "a.xml"]);
    assert!(e.starts_with("error: b.xml:3:3:"), "{e}");
    assert!(e.contains("a.xml"), "{e}");
}

#[test]
fn the_sandbox_keeps_files_inside_the_scenes_folder() {
    let dir = tempfile::tempdir().unwrap();
    let triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let outside = write(dir.path(), "outside.obj", triangle);
    let scene = |file: &str| {
        format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[material]]\nname = \"m\"\n[[object]]\ntype = \"mesh\"\nfile = \"{file}\"\nmaterial = \"m\"\n"
        )
    };
    let inner = dir.path().join("scene");
    for file in ["../outside.obj", &outside.display().to_string()] {
        write(&inner, "s.toml", scene(file));
        let output = lucent()
            .current_dir(&inner)
            .args(["info", "s.toml"])
            .output()
            .unwrap();
        assert_success(&output);
        let e = refused_in(&inner, &["info", "--sandbox", "s.toml"]);
        assert!(e.starts_with("error: s.toml:8:8:"), "{e}");
        assert!(e.contains("outside"), "{e}");
    }
    // An OBJ's material library is held to the same rule, at the line that names it.
    write(dir.path(), "lib.mtl", "newmtl m\nKd 1 0 0\n");
    write(
        &inner,
        "m.obj",
        format!("mtllib ../lib.mtl\nusemtl m\n{triangle}"),
    );
    let e = refused_in(&inner, &["info", "--sandbox", "m.obj"]);
    assert!(e.starts_with("error: m.obj:1:"), "{e}");
    // Inside in name only: a symbolic link in the folder to the file outside.
    std::os::unix::fs::symlink(&outside, inner.join("link.obj")).unwrap();
    write(&inner, "s.toml", scene("link.obj"));
    let e = refused_in(&inner, &["info", "--sandbox", "s.toml"]);
    assert!(e.starts_with("error: s.toml:8:8:"), "{e}");
    assert!(e.contains("through a symbolic link"), "{e}");
    // A linked folder on the way does the same.
    std::os::unix::fs::symlink(dir.path(), inner.join("up")).unwrap();
    write(&inner, "s.toml", scene("up/outside.obj"));
    let e = refused_in(&inner, &["info", "--sandbox", "s.toml"]);
    assert!(e.contains("through a symbolic link"), "{e}");
}

#[test]
fn special_files_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let scene = |file: &str| {
        format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[material]]\nname = \"m\"\n[[object]]\ntype = \"mesh\"\nfile = \"{file}\"\nmaterial = \"m\"\n"
        )
    };
    let fifo = dir.path().join("pipe.obj");
    let mut cases = vec![
        ("/dev/zero".to_string(), "not a regular file"),
        ("/proc/self/pagemap".to_string(), "pseudo-file"),
        (dir.path().display().to_string(), "a folder"),
    ];
    // A FIFO would block its reader until a writer came (left out where mkfifo is missing).
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        cases.push((fifo.display().to_string(), "not a regular file"));
    }
    for (file, why) in cases {
        write(dir.path(), "s.toml", scene(&file));
        let began = std::time::Instant::now();
        let e = refused_in(dir.path(), &["info", "s.toml"]);
        assert!(began.elapsed().as_secs_f32() < 1.0, "{file}: {e}");
        assert!(
            e.contains(why) && e.starts_with("error: s.toml:"),
            "{file}: {e}"
        );
    }
}

/// Converts `scene` into a TOML file in another folder and renders both: the images must be
/// identical to the bit.
fn assert_converts_exactly(scene: &Path, args: &[&str]) {
    let dir = scene.parent().unwrap();
    let original = dir.join("original.pfm");
    render(scene, &original, args);
    let converted = dir.join("converted/scene.toml");
    std::fs::create_dir_all(converted.parent().unwrap()).unwrap();
    let output = lucent()
        .arg("convert")
        .arg(scene)
        .arg(&converted)
        .output()
        .unwrap();
    assert_success(&output);
    let again = dir.join("again.pfm");
    render(&converted, &again, args);
    let (a, b) = (read_pfm(&original), read_pfm(&again));
    let lit = a
        .pixels
        .iter()
        .filter(|p| p.iter().any(|&c| c > 0.2))
        .count();
    assert!(lit > a.pixels.len() / 20, "the image shows something");
    assert!(
        a == b,
        "{}: the converted scene renders differently:\n{}",
        scene.display(),
        std::fs::read_to_string(&converted).unwrap()
    );
}

#[test]
fn obj_with_mtl_converts_to_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let texture = image::RgbImage::from_fn(4, 4, |x, y| {
        if (x + y) % 2 == 0 {
            image::Rgb([230, 40, 40])
        } else {
            image::Rgb([40, 40, 230])
        }
    });
    std::fs::create_dir_all(dir.path().join("maps")).unwrap();
    texture.save(dir.path().join("maps/check.png")).unwrap();
    write(
        dir.path(),
        "scene.mtl",
        "newmtl floor\nKd 1 1 1\nmap_Kd maps/check.png\nillum 1\n\nnewmtl mirror\nKd 0.1 0.1 0.1\nKs 0.9 0.9 0.9\nNs 200\nillum 3\n\nnewmtl glass\nKd 0 0 0\nKs 0.1 0.1 0.1\nTf 0.9 0.9 0.9\nNi 1.5\nillum 7\n",
    );
    write(
        dir.path(),
        "scene.obj",
        "mtllib scene.mtl\n\
         v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n\
         vt 0 0\nvt 4 0\nvt 4 4\nvt 0 4\nvn 0 1 0\n\
         usemtl floor\nf 1/1/1 4/4/1 3/3/1 2/2/1\n\
         v -1.5 0 -1\nv -0.5 0 -1\nv -1 1.5 -1\n\
         usemtl mirror\nf -3 -2 -1\n\
         v 0.2 0 0.5\nv 1.2 0 0.5\nv 0.7 0 -0.4\nv 0.7 1 0.2\n\
         usemtl glass\nf -4 -3 -1\nf -3 -2 -1\nf -2 -4 -1\nf -4 -2 -3\n",
    );
    assert_converts_exactly(
        &dir.path().join("scene.obj"),
        &["--width", "40", "--height", "30"],
    );
}

/// Standard base64 with padding, for a data URI.
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &b)| n | (u32::from(b) << (16 - 8 * i)));
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ABC[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[test]
fn gltf_converts_to_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut buffer = Vec::new();
    for p in [
        [-1.0f32, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ] {
        for c in p {
            buffer.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        buffer.extend_from_slice(&i.to_le_bytes());
    }
    let gltf = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "point", "intensity": 20000, "color": [1, 0.9, 0.8]}}]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 2, 3]}}],
  "nodes": [
    {{"children": [1], "rotation": [0, 0.3826834, 0, 0.9238795], "scale": [1.5, 1, 1]}},
    {{"mesh": 0, "translation": [0, 0, -0.5]}},
    {{"camera": 0, "translation": [0, 0, 4]}},
    {{"translation": [0.5, 1, 3], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1, "aspectRatio": 1.3333}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}}]}}],
  "materials": [{{"pbrMetallicRoughness": {{"baseColorFactor": [0.8, 0.3, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.9}}}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 12}}
  ],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{}"}}]
}}"#,
        buffer.len(),
        base64(&buffer)
    );
    let scene = write(dir.path(), "scene.gltf", gltf);
    assert_converts_exactly(&scene, &["--width", "40", "--height", "30"]);
}

/// Every material kind and texture slot the readers fill survives `convert`: a Mitsuba file
/// of the rough, layered and textured BSDFs, and a TOML file of glTF's `pbr` with its layers
/// (the thin film's thickness a mix of two numbers by a texture, as the glTF reader writes it)
/// and a cut-out, each converted and rendered again to the same bits.
#[test]
fn every_material_kind_converts_to_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let checker = image::RgbaImage::from_fn(8, 8, |x, y| {
        let on = (x / 2 + y / 2) % 2 == 0;
        image::Rgba([
            if on { 220 } else { 30 },
            128,
            255,
            if on { 255 } else { 40 },
        ])
    });
    checker.save(dir.path().join("checker.png")).unwrap();
    let scene = write(
        dir.path(),
        "scene.xml",
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="32"/></film>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    </sensor>
    <integrator type="path"><integer name="max_depth" value="5"/></integrator>
    <texture type="bitmap" id="tex"><string name="filename" value="checker.png"/></texture>
    <shape type="sphere">
        <point name="center" x="-1.6" y="0" z="0"/><float name="radius" value="0.5"/>
        <bsdf type="principled">
            <ref name="base_color" id="tex"/>
            <float name="metallic" value="0.3"/><float name="roughness" value="0.4"/>
            <float name="anisotropic" value="0.5"/><float name="clearcoat" value="0.5"/>
            <float name="sheen" value="0.3"/>
        </bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" x="-0.5" y="0" z="0"/><float name="radius" value="0.5"/>
        <bsdf type="roughconductor">
            <string name="distribution" value="beckmann"/>
            <float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/>
            <string name="material" value="Cu"/>
        </bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" x="0.6" y="0" z="0"/><float name="radius" value="0.5"/>
        <bsdf type="blendbsdf">
            <texture type="checkerboard" name="weight"/>
            <bsdf type="roughplastic"><boolean name="nonlinear" value="true"/><float name="alpha" value="0.3"/></bsdf>
            <bsdf type="roughdielectric"><float name="alpha" value="0.2"/></bsdf>
        </bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" x="1.7" y="0" z="0"/><float name="radius" value="0.5"/>
        <bsdf type="normalmap">
            <texture type="bitmap" name="normalmap"><string name="filename" value="checker.png"/><boolean name="raw" value="true"/></texture>
            <bsdf type="principledthin"><float name="spec_trans" value="0.5"/></bsdf>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/><translate y="-0.5"/></transform>
        <bsdf type="mask">
            <texture type="bitmap" name="opacity"><string name="filename" value="checker.png"/></texture>
            <bsdf type="bumpmap">
                <texture type="bitmap"><string name="filename" value="checker.png"/></texture>
                <bsdf type="thindielectric"/>
            </bsdf>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/><translate z="-2"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><ref name="reflectance" id="tex"/></bsdf></bsdf>
    </shape>
    <emitter type="directional"><vector name="direction" x="0.3" y="-1" z="-0.4"/><rgb name="irradiance" value="3"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.4"/></emitter>
</scene>
"#,
    );
    assert_converts_exactly(&scene, &[]);

    let toml = write(
        dir.path(),
        "pbr.toml",
        r#"
[image]
width = 48
height = 32
samples = 4

[camera]
eye = [0, 1, 5]
look_at = [0, 0, 0]
fov = 45

[render]
integrator = "path"

[[material]]
name = "helmet"
type = "pbr"
base_color = { image = "checker.png", wrap = ["mirror", "clamp"], filter = "nearest", scale = [2, 3], rotation = 30 }
metallic = { image = "checker.png", channel = "b", encoding = "linear" }
roughness = { image = "checker.png", channel = "g", encoding = "linear" }
normal_map = { image = "checker.png", encoding = "linear" }
normal_scale = 0.5
emission = { product = [{ image = "checker.png" }, [0.5, 0.2, 0.1]] }
opacity = { step = { image = "checker.png", channel = "a" }, cutoff = 0.5 }
clearcoat = 0.7
clearcoat_roughness = 0.1
sheen_color = [0.3, 0.1, 0.5]
sheen_roughness = 0.4
transmission = 0.2
ior = 1.4
anisotropy = 0.5
anisotropy_rotation = 0.7
iridescence = { product = [0.8, { image = "checker.png", channel = "a", encoding = "linear" }] }
iridescence_ior = 1.8
iridescence_thickness = { mix = [200, 600], amount = { image = "checker.png", channel = "r", encoding = "linear" } }

[[material]]
name = "floor"
type = "diffuse"
reflectance = { mix = [[0.8, 0.8, 0.8], { checkerboard = { even = 0.2, odd = 0.9 } }], amount = 0.5 }

[[light]]
type = "directional"
direction = [0.3, -1, -0.4]
intensity = 3

[[light]]
type = "environment"
intensity = 0.4

[[object]]
type = "sphere"
center = [0, 0, 0]
radius = 0.8
material = "helmet"

[[object]]
type = "rectangle"
scale = 3
rotate = [-90, 0, 0]
translate = [0, -0.8, 0]
flip_v = true
material = "floor"
"#,
    );
    assert_converts_exactly(&toml, &[]);
}

#[test]
fn mitsuba_xml_converts_to_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "meshes/quad.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n",
    );
    let scene = write(
        dir.path(),
        "scene.xml",
        r#"<scene version="3.0.0">
    <default name="res" value="30"/>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world">
            <lookat origin="0, 1, 4" target="0, 0, 0" up="0, 1, 0"/>
        </transform>
        <film type="hdrfilm">
            <integer name="width" value="40"/>
            <integer name="height" value="$res"/>
        </film>
    </sensor>
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
    <shape type="obj">
        <string name="filename" value="meshes/quad.obj"/>
        <transform name="to_world"><scale value="1.5"/><translate z="-1"/></transform>
        <ref id="red"/>
    </shape>
    <shape type="sphere">
        <point name="center" x="0.6" y="0" z="0"/>
        <float name="radius" value="0.5"/>
        <bsdf type="conductor"><string name="material" value="Au"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/><translate y="-0.6"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" x="-0.7" y="-0.1" z="0.5"/>
        <float name="radius" value="0.4"/>
        <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>
    </shape>
    <emitter type="point">
        <point name="position" x="1" y="3" z="3"/>
        <rgb name="intensity" value="12"/>
    </emitter>
    <emitter type="constant"><rgb name="radiance" value="0.1"/></emitter>
</scene>
"#,
    );
    assert_converts_exactly(&scene, &[]);
}

/// `lucent info FILE` in `dir` under a 256 MiB address-space limit (a bound on its peak
/// memory), refused within 5 s (none of these cases should come near it): the error line.
fn refused_small(dir: &Path, file: &str, extra: &[&str]) -> String {
    let began = std::time::Instant::now();
    let e = refused_by(
        Command::new("sh")
            .current_dir(dir)
            .args(["-c", "ulimit -v 262144; exec \"$0\" info \"$@\""])
            .arg(env!("CARGO_BIN_EXE_lucent"))
            .arg(file)
            .args(extra),
    );
    assert!(began.elapsed().as_secs_f32() < 5.0, "{file}: {e}");
    e
}

#[test]
fn a_thousand_includes_of_a_thousand_are_refused_within_the_xml_budget() {
    // 60 bytes included 10⁶ times: 57 MiB of XML from 90 KB of files (before the budget, 9 s
    // and 478 MB until the old 64 MiB cap refused it).
    let dir = tempfile::tempdir().unwrap();
    let includes = |file: &str| {
        let lines = format!("<include filename=\"{file}\"/>\n").repeat(1000);
        format!("<scene version=\"3.0.0\">\n{lines}</scene>\n")
    };
    write(dir.path(), "a.xml", includes("b.xml"));
    write(dir.path(), "b.xml", includes("c.xml"));
    write(
        dir.path(),
        "c.xml",
        "<scene version=\"3.0.0\"><bsdf type=\"diffuse\"/></scene>\n",
    );
    let e = refused_small(dir.path(), "a.xml", &[]);
    assert!(
        e.contains("MiB of XML, over the budget of 16 MiB (`--limit xml=N` raises it)"),
        "{e}"
    );
    // A lower budget refuses sooner; a scene within it is read.
    let e = refused_small(dir.path(), "a.xml", &["--limit", "xml=1"]);
    assert!(e.contains("over the budget of 1 MiB"), "{e}");
    write(dir.path(), "one.xml", includes("c.xml"));
    assert_success(
        &lucent()
            .current_dir(dir.path())
            .args(["info", "one.xml", "--limit", "xml=1"])
            .output()
            .unwrap(),
    );
}

#[test]
fn an_obj_of_too_many_parts_is_refused_before_its_objects_are_made() {
    // One triangle under 200,000 materials: an object each (before the budget, 4 s and
    // 1.3 GB for `info`).
    let dir = tempfile::tempdir().unwrap();
    let parts = |n: usize| {
        let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for i in 0..n {
            s.push_str(&format!("usemtl m{i}\nf 1 2 3\n"));
        }
        s
    };
    write(dir.path(), "many.obj", parts(200_000));
    let e = refused_small(dir.path(), "many.obj", &[]);
    assert!(
        e.contains("the file's faces use 200000 materials, an object each, over the budget of 100000 (`--limit objects=N` raises it)"),
        "{e}"
    );
    // The budget is the flag's: 300 parts over 200, and within 400.
    write(dir.path(), "some.obj", parts(300));
    let e = refused_small(dir.path(), "some.obj", &["--limit", "objects=200"]);
    assert!(e.contains("over the budget of 200"), "{e}");
    assert_success(
        &lucent()
            .current_dir(dir.path())
            .args(["info", "some.obj", "--limit", "objects=400"])
            .output()
            .unwrap(),
    );
}

#[test]
fn includes_that_multiply_are_refused() {
    // a.xml includes b.xml 100 times, b.xml includes c.xml 100 times, c.xml holds 10 KB: 100 MB
    // of XML from 30 KB of files.
    let dir = tempfile::tempdir().unwrap();
    let includes = |file: &str| {
        let lines = format!("    <include filename=\"{file}\"/>\n").repeat(100);
        format!("<scene version=\"3.0.0\">\n{lines}</scene>\n")
    };
    write(dir.path(), "a.xml", includes("b.xml"));
    write(dir.path(), "b.xml", includes("c.xml"));
    let padding = "<!-- padding -->\n".repeat(600);
    write(
        dir.path(),
        "c.xml",
        format!("<scene version=\"3.0.0\">\n{padding}</scene>\n"),
    );
    let e = refused_in(dir.path(), &["info", "a.xml"]);
    assert!(e.contains("MiB of XML"), "{e}");
    assert!(
        e.contains("b.xml:"),
        "the include that went over is named: {e}"
    );
}
