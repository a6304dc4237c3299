//! Mitsuba 3 XML: imported as a scene (includes and meshes come from the scratch folder, the
//! input itself included), then built.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, write};
use lucent_scene::SceneFile;

fuzz_target!(|data: &[u8]| {
    let path = write("fuzz.xml", data);
    if let Ok(file) = SceneFile::read_with(&path, &OPTIONS) {
        let _ = file.build();
    }
});
