//! Stanford PLY, ASCII and binary: parsed; what it gives must be a consistent mesh.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent::shape::Mesh;
use lucent_scene::ply::parse_ply;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(m) = parse_ply(data, Path::new("fuzz.ply")) else {
        return;
    };
    let n = m.positions.len();
    assert!(m.normals.as_ref().is_none_or(|v| v.len() == n));
    assert!(m.colors.as_ref().is_none_or(|v| v.len() == n));
    assert!(m.positions.iter().all(|p| p.is_finite()));
    Mesh::new(m.positions, m.triangles)
        .validate()
        .expect("a parsed file gives a valid mesh");
});
