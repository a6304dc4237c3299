//! POV-Ray 3.7 scenes: read (includes from the scratch folder and POV-Ray's include folder,
//! when installed), converted, then built.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, write};
use lucent_scene::SceneFile;

fuzz_target!(|data: &[u8]| {
    let path = write("fuzz.pov", data);
    if let Ok(file) = SceneFile::read_with(&path, &OPTIONS) {
        let _ = file.build();
    }
});
