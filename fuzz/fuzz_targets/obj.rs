//! Wavefront OBJ: parsed, every part made a mesh (which must be valid), then imported as a
//! scene with its `mtllib`s (from the scratch folder) and built.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, write};
use lucent_scene::SceneFile;
use lucent_scene::obj::parse_obj;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(obj) = parse_obj(data, Path::new("fuzz.obj")) else {
        return;
    };
    let all = obj.mesh(None).expect("the whole file is a mesh");
    all.validate().expect("a parsed file gives a valid mesh");
    for name in obj.used_materials() {
        let part = obj.mesh(Some(name)).expect("a used material is a part");
        part.validate().expect("a parsed file gives valid parts");
    }
    let path = write("fuzz.obj", data);
    if let Ok(file) = SceneFile::read_with(&path, &OPTIONS) {
        let _ = file.build();
    }
});
