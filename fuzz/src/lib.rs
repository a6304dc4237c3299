//! What the fuzz targets share: a scratch folder per process for the path-based readers, with a
//! few small valid mesh files in it that fuzzed scenes can name, and the load options they run
//! under.
//!
//! Every target loads with `--sandbox` on, so a fuzzed file can name only files inside the
//! scratch folder: the runs stay deterministic and cannot read `/dev/zero` or the host's files.
//! (What the sandbox refuses is tested in `crates/lucent-scene`.)

use lucent_scene::LoadOptions;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The options every target loads with: sandboxed.
pub const OPTIONS: LoadOptions = LoadOptions {
    sandbox: true,
    limits: lucent_scene::Limits::DEFAULT,
    image_size: None,
};

/// A triangle as OBJ, with a material library, texture coordinates and normals.
pub const TRI_OBJ: &str = "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0 1 0 0\nvt 0 0\nvt 1 0\nvn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3//1\nusemtl glass\nf -3 -2 -1\n";
/// The library `tri.obj` names.
pub const TRI_MTL: &str = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.2\nNs 20\nillum 2\nnewmtl glass\nNi 1.5\nTf 0.9 0.9 1\nillum 7\n";
/// A triangle as ASCII PLY, with colours.
pub const TRI_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n";
/// A triangle as glTF with an external buffer, `tri.bin` (see [`tri_bin`]).
pub const TRI_GLTF: &str = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,-1]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"buffers":[{"uri":"tri.bin","byteLength":44}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]}"#;

/// The buffer of [`TRI_GLTF`]: three positions, three 16-bit indices, two bytes of padding.
pub fn tri_bin() -> Vec<u8> {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// This process's scratch folder, made (with the small mesh files in it) on first use.
///
/// It is left behind when libFuzzer exits (it exits without unwinding); it holds a few hundred
/// bytes, under the system's temporary folder.
pub fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("lucent-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("the scratch folder can be made");
        let files: [(&str, &[u8]); 5] = [
            ("tri.obj", TRI_OBJ.as_bytes()),
            ("tri.mtl", TRI_MTL.as_bytes()),
            ("tri.ply", TRI_PLY.as_bytes()),
            ("tri.gltf", TRI_GLTF.as_bytes()),
            ("tri.bin", &tri_bin()),
        ];
        for (name, bytes) in files {
            std::fs::write(dir.join(name), bytes).expect("the scratch folder is writable");
        }
        dir
    })
}

/// Writes `bytes` to the file `name` of the scratch folder and returns its path.
pub fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, bytes).expect("the scratch folder is writable");
    path
}
