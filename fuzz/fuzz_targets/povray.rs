//! POV-Ray 3.7 scenes: read (includes from the scratch folder and POV-Ray's include folder,
//! when installed), converted, then built. The object budget is a tenth of the default, so
//! that a loop making objects without end stops well inside the fuzzer's timeout under its
//! instrumentation (about 1.3 s at the default budget in a release build, over 5 s here).
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_fuzz::{OPTIONS, write};
use lucent_scene::{Limits, LoadOptions, SceneFile};

const POVRAY: LoadOptions = LoadOptions {
    limits: Limits {
        objects: 10_000,
        ..Limits::DEFAULT
    },
    ..OPTIONS
};

fuzz_target!(|data: &[u8]| {
    let path = write("fuzz.pov", data);
    if let Ok(file) = SceneFile::read_with(&path, &POVRAY) {
        let _ = file.build();
    }
});
