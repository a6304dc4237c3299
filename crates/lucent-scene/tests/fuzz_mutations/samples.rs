//! Small valid files of every format, written here, and the files they name.

use std::path::Path;

pub const TRI_OBJ: &str = "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0 1 0 0\nvt 0 0\nvt 1 0\nvn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3//1\nusemtl glass\nf -3 -2 -1\n";
pub const TRI_MTL: &str = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.2\nNs 20\nillum 2\nnewmtl glass\nNi 1.5\nTf 0.9 0.9 1\nillum 7\n";
pub const TRI_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n";

/// A triangle as glTF whose buffer is the file `bin`.
pub fn tri_gltf(bin: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0,"translation":[0,0,-1]}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],"buffers":[{{"uri":"{bin}","byteLength":44}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]}}"#
    )
}

/// The buffer of [`tri_gltf`]: three positions, three 16-bit indices, padding.
pub fn tri_bin() -> Vec<u8> {
    let mut b: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    b.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    b
}

/// The files the samples name, beside the input in `dir`.
pub fn write_neighbours(dir: &Path) {
    let files: [(&str, Vec<u8>); 5] = [
        ("tri.obj", TRI_OBJ.into()),
        ("tri.mtl", TRI_MTL.into()),
        ("tri.ply", TRI_PLY.into()),
        ("tri.gltf", tri_gltf("tri.bin").into()),
        ("tri.bin", tri_bin()),
    ];
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

pub const SCENE_SPHERES: &str = r#"
[image]
width = 64
height = 48
samples = 2

[camera]
eye = [0.0, 1.3, 6.0]
look_at = [0.0, 0.9, 0.0]
up = [0.0, 1.0, 0.0]
fov = 38

[world]
background = [0.15, 0.35, 0.85]
ambient = 0.15

[render]
integrator = "whitted"
max_depth = 10
min_weight = 0.00390625
accelerator = "bvh"
triangle_test = "projection"

[[material]]
name = "checker"
ka = [0.6, 0.45, 0.1]
kd = { checker = { even = [0.85, 0.1, 0.05], odd = [0.95, 0.8, 0.1], size = 1.0 } }
ks = 0.1
shininess = 20

[[material]]
name = "glass"
kr = 0.1
kt = 0.88
ior = 1.5

[[light]]
type = "point"
position = [-4.0, 7.0, 6.0]
intensity = 0.75
falloff = "quadratic"

[[object]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "checker"

[[object]]
type = "sphere"
center = [0.9, 1.2, -1.6]
radius = 1.2
material = "glass"

[[object]]
type = "triangle"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
material = "glass"
"#;

pub const SCENE_MESHES: &str = r#"
[camera]
eye = [0, 1, 4]
look_at = [0, 0, 0]

[[material]]
name = "lamp"
type = "diffuse"
reflectance = 0.5
emission = [4, 4, 3]
two_sided = true

[[material]]
name = "gold"
type = "roughconductor"
metal = "Au"
roughness = 0.1

[[material]]
name = "water"
type = "dielectric"
ior = 1.33
transmittance = [0.9, 0.95, 1]

[[material]]
name = "paint"
type = "plastic"
reflectance = [0.2, 0.4, 0.6]

[[light]]
type = "spot"
position = [0, 3, 0]
direction = [0, -1, 0]
cutoff = 30
cutoff_start = 20

[[light]]
type = "directional"
direction = [1, -1, 0]

[[object]]
type = "mesh"
file = "tri.obj"
part = "red"
material = "gold"
scale = [1, 2, 1]
rotate = [0, 45, 0]
translate = [0, 0, -1]

[[object]]
type = "mesh"
file = "tri.ply"
smooth = false
flip_normals = true
material = "water"

[[object]]
type = "mesh"
file = "tri.gltf"
part = "0/0"
material = "paint"
transform = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]

[[object]]
type = "rectangle"
material = "lamp"
translate = [0, 2, 0]
rotate = [90, 0, 0]

[[object]]
type = "disk"
material = "lamp"
"#;

pub const OBJ_QUAD: &str = "mtllib tri.mtl\n# a quad and two triangles\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 0.5 0.5 0.5\nvt 0 0\nvt 1 1\nvn 0 0 1\ng quad\no thing\ns 1\nusemtl red\nf 1/1/1 2//1 3/2/1 4/1/1\nusemtl glass\nf -4 -3 -2\nf 1 3 4\n";

pub const MTL_THREE: &str = "newmtl mirror\nKa 0.1 0.1 0.1\nKd 0.1 0.2 0.3\nKs 0.9\nNs 50\nillum 3\n\nnewmtl glass\nKs 0.1\nNi 1.45\nTf 0.9 0.9 1\nd 0.5\nillum 7\n# comment\nnewmtl lamp\nKe 4 4 4\nTr 0.25\nmap_Kd -s 1 1 1 wood.png\nillum 10\n";

pub const PLY_QUAD: &str = "ply\nformat ascii 1.0\ncomment a quad\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nelement extra 1\nproperty list uchar float values\nend_header\n0 0 0 0 0 1 255 0 0\n1 0 0 0 0 1 0 255 0\n1 1 0 0 0 1 0 0 255\n0 1 0 0 0 1 255 255 255\n4 0 1 2 3\n2 0.5 1.5\n";

pub const PLY_STRIPS: &str = "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 1 0\n8 0 1 2 3 -1 2 3 4\n";

/// A binary PLY triangle (with normals, an extra face property and a skipped element).
pub fn ply_binary(big: bool) -> Vec<u8> {
    let order = if big { "big" } else { "little" };
    let mut b = format!("ply\nformat binary_{order}_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty short z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\nproperty list uchar uint vertex_indices\nproperty int flags\nelement note 1\nproperty double v\nend_header\n").into_bytes();
    let put =
        |b: &mut Vec<u8>, le: &[u8], be: &[u8]| b.extend_from_slice(if big { be } else { le });
    for (x, y, z) in [(0.0f32, 0.0f32, 0i16), (1.0, 0.0, 0), (0.0, 2.0, -3)] {
        put(&mut b, &x.to_le_bytes(), &x.to_be_bytes());
        put(&mut b, &y.to_le_bytes(), &y.to_be_bytes());
        put(&mut b, &z.to_le_bytes(), &z.to_be_bytes());
        for n in [0.0f32, 0.0, 1.0] {
            put(&mut b, &n.to_le_bytes(), &n.to_be_bytes());
        }
    }
    b.push(3);
    for i in [0u32, 1, 2, 7] {
        put(&mut b, &i.to_le_bytes(), &i.to_be_bytes());
    }
    put(&mut b, &0.5f64.to_le_bytes(), &0.5f64.to_be_bytes());
    b
}

/// The head of a binary PLY file with its `vertex` count lowered to the vertices the head holds
/// whole and every other element emptied, so that it reads: the real bytes get past the size
/// checks. `None` when the head is not laid out so (ASCII, or properties other than scalars).
pub fn ply_head_that_reads(head: &[u8]) -> Option<Vec<u8>> {
    let end = head.windows(11).position(|w| w == b"end_header\n")? + 11;
    let text = std::str::from_utf8(&head[..end]).ok()?;
    let size = |t: &str| match t {
        "char" | "uchar" | "int8" | "uint8" => Some(1),
        "short" | "ushort" | "int16" | "uint16" => Some(2),
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => Some(4),
        "double" | "float64" => Some(8),
        _ => None,
    };
    let mut vertex = 0;
    let mut in_vertex = false;
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", "ascii", ..] => return None,
            ["element", name, _] => in_vertex = *name == "vertex",
            ["property", ty, _] if in_vertex => vertex += size(ty)?,
            ["property", ..] if in_vertex => return None,
            _ => {}
        }
    }
    let fits = (head.len() - end) / vertex.max(1);
    let mut header = String::new();
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["element", "vertex", _] => header += &format!("element vertex {fits}\n"),
            ["element", name, _] => header += &format!("element {name} 0\n"),
            _ => header += &format!("{line}\n"),
        }
    }
    let mut out = header.into_bytes();
    out.extend_from_slice(&head[end..end + fits * vertex]);
    Some(out)
}

/// A glTF scene: a strip with every attribute and a sparse edit, a node hierarchy with a
/// mirroring node, a camera, every light, a material; as `.gltf` text with its buffer in a
/// `data:` URI, and as `.glb`.
pub fn gltf_samples() -> [Vec<u8>; 2] {
    let f32s = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let parts: [Vec<u8>; 7] = [
        f32s(&[0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.]),
        f32s(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]),
        f32s(&[0., 0., 1., 0., 0., 1., 1., 1.]),
        vec![
            255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255,
        ],
        vec![0, 1, 2, 3],
        vec![3, 0, 0, 0],
        f32s(&[1.5, 1.5, 0.]),
    ];
    let mut bin = Vec::new();
    let mut views = Vec::new();
    for p in &parts {
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            bin.len(),
            p.len()
        ));
        bin.extend_from_slice(p);
    }
    let json = |buffer: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},
"extensionsUsed":["KHR_lights_punctual","KHR_materials_ior"],
"extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":683,"color":[1,1,1]}},{{"type":"spot","intensity":100,"spot":{{"innerConeAngle":0.2,"outerConeAngle":0.5}}}},{{"type":"directional","intensity":2}}]}}}},
"scene":0,"scenes":[{{"nodes":[0,3]}}],
"nodes":[{{"children":[1,2],"rotation":[0,0.7071068,0,0.7071068],"scale":[2,2,2]}},{{"mesh":0,"translation":[0,0,-1]}},{{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,-1,0,0,0,0,1]}},{{"camera":0,"translation":[0,0,5],"children":[4]}},{{"extensions":{{"KHR_lights_punctual":{{"light":1}}}}}}],
"cameras":[{{"type":"perspective","perspective":{{"yfov":0.8,"aspectRatio":1.5,"znear":0.1}}}}],
"materials":[{{"name":"Paint","pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.2,0.2,1],"metallicFactor":0,"roughnessFactor":0.3}},"extensions":{{"KHR_materials_ior":{{"ior":1.4}}}},"doubleSided":true}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2,"COLOR_0":3}},"indices":4,"mode":5,"material":0}}]}}],
"buffers":[{buffer}],
"bufferViews":[{views}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0],"sparse":{{"count":1,"indices":{{"bufferView":5,"componentType":5125}},"values":{{"bufferView":6}}}}}},
{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"}},{{"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"}},
{{"bufferView":3,"componentType":5121,"normalized":true,"count":4,"type":"VEC4"}},{{"bufferView":4,"componentType":5121,"count":4,"type":"SCALAR"}}]}}"#,
            views = views.join(",")
        )
    };
    let text = json(&format!(
        r#"{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}"#,
        bin.len(),
        base64(&bin)
    ));
    let mut js = json(&format!(r#"{{"byteLength":{}}}"#, bin.len())).into_bytes();
    while js.len() % 4 != 0 {
        js.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let mut glb = b"glTF".to_vec();
    let total = 12 + 8 + js.len() + 8 + bin.len();
    for w in [2, total as u32, js.len() as u32, 0x4E4F_534A] {
        glb.extend_from_slice(&w.to_le_bytes());
    }
    glb.extend_from_slice(&js);
    for w in [bin.len() as u32, 0x004E_4942] {
        glb.extend_from_slice(&w.to_le_bytes());
    }
    glb.extend_from_slice(&bin);
    [text.into_bytes(), glb]
}

/// Standard base64 with padding.
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

pub const MITSUBA_SCENE: &str = r#"<scene version="3.0.0">
    <default name="spp" value="16"/>
    <integrator type="path"><integer name="max_depth" value="8"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="39.3"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/></film>
    </sensor>
    <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8"/></bsdf>
    <bsdf type="twosided" id="red"><bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.1, 0.1"/></bsdf></bsdf>
    <bsdf type="roughconductor" id="gold"><string name="material" value="Au"/><float name="alpha" value="0.1"/></bsdf>
    <bsdf type="dielectric" id="glass"><string name="int_ior" value="bk7"/></bsdf>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="2"/><translate y="-1"/></transform>
        <ref id="white"/>
    </shape>
    <shape type="cube">
        <transform name="to_world"><matrix value="0.3 0 0 0.5  0 0.3 0 -0.7  0 0 0.3 0  0 0 0 1"/></transform>
        <ref id="red"/>
    </shape>
    <shape type="obj"><string name="filename" value="tri.obj"/><ref id="gold"/></shape>
    <shape type="ply"><string name="filename" value="tri.ply"/><ref id="glass"/></shape>
    <shape type="sphere">
        <point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.3"/>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter>
    </shape>
    <emitter type="point"><point name="position" value="0, 0.9, 0"/><rgb name="intensity" value="5"/></emitter>
    <emitter type="directional"><vector name="direction" value="0, -1, 0"/></emitter>
</scene>
"#;

/// Includes itself (a cycle, refused) once mutated into doing so; as written, a sibling.
pub const MITSUBA_INCLUDE: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<scene version="3.0.0">
    <default name="r" value="0.5"/>
    <include filename="other.xml"/>
    <shape type="sphere"><float name="radius" value="$r"/><bsdf type="conductor"/></shape>
</scene>
"#;

/// A POV-Ray scene of the language: declarations, a macro, loops, conditionals (the fuzz
/// target's seed).
pub const POV_LANGUAGE: &str = include_str!("../../../../fuzz/seeds/povray/language.pov");
/// A POV-Ray scene of shapes, CSG, an algebraic surface, patterns and lights (the fuzz
/// target's seed).
pub const POV_SHAPES: &str = include_str!("../../../../fuzz/seeds/povray/shapes.pov");
