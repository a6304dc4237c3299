//! glTF 2.0, `.gltf` (JSON) or `.glb` (binary, when the input starts with `glTF`): imported as
//! a scene and built (which reads each primitive as a part), and read whole as one mesh. The
//! scratch folder holds `tri.bin` and other small files a fuzzed file may name.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, write};
use lucent_scene::SceneFile;
use lucent_scene::gltf_file::read_gltf_part;
use lucent_scene::hash::Fingerprint;

fuzz_target!(|data: &[u8]| {
    let name = if data.starts_with(b"glTF") {
        "fuzz.glb"
    } else {
        "fuzz.gltf"
    };
    let path = write(name, data);
    if let Ok(mesh) = read_gltf_part(&path, None, &OPTIONS, &mut Fingerprint::default()) {
        mesh.validate().expect("a read file gives a valid mesh");
    }
    if let Ok(file) = SceneFile::read_with(&path, &OPTIONS) {
        let _ = file.build();
    }
});
