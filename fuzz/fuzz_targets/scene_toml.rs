//! lucent's TOML scene format: parsed, then built (names resolved, values checked, the mesh
//! files it names read from the scratch folder, the accelerator built), then written back.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, scratch};
use lucent_scene::SceneFile;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // read_with refuses non-UTF-8 before parsing
    };
    let dir = scratch();
    let Ok(mut file) = SceneFile::parse(dir.join("fuzz.toml"), dir.to_path_buf(), text.into())
    else {
        return;
    };
    file.options = OPTIONS;
    if let Ok(loaded) = file.build() {
        let _ = file.to_toml(&loaded);
    }
});
