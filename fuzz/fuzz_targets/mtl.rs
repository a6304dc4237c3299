//! Wavefront MTL material libraries: parsed, then every material described (with and without
//! its texture).
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_scene::mtl::parse_mtl;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(materials) = parse_mtl(data, Path::new("fuzz.mtl")) else {
        return;
    };
    let mut warnings = Vec::new();
    for m in &materials {
        let texture = m.texture().map(str::to_string);
        let _ = m.to_desc(&m.name, texture, &mut warnings);
        let _ = m.to_desc("plain", None, &mut warnings);
    }
});
