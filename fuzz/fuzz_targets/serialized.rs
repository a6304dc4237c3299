//! Mitsuba serialized meshes: the first shapes of the file parsed (and one index past them);
//! what each gives must be a consistent mesh of finite numbers.
//!
//! An input starting with `raw` is one shape's inflated stream instead: it is deflated and put
//! in a file of its own (version 3 or 4 by the byte after `raw`), so that the fuzzer reaches the
//! flags, counts and arrays without having to write zlib.
#![no_main]

use flate2::Compression;
use flate2::write::ZlibEncoder;
use libfuzzer_sys::fuzz_target;
use lucent_scene::serialized::{FORMAT_ID, parse_serialized, shape_count};
use std::io::Write;
use std::path::Path;

/// A file of one shape: `stream` deflated, after the header, before the dictionary.
fn wrap(version: u16, stream: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(&FORMAT_ID.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    let mut z = ZlibEncoder::new(out, Compression::fast());
    z.write_all(stream).expect("writing to memory");
    let mut out = z.finish().expect("writing to memory");
    out.extend_from_slice(&vec![0; if version == 3 { 4 } else { 8 }]);
    out.extend_from_slice(&1u32.to_le_bytes());
    out
}

fuzz_target!(|data: &[u8]| {
    let wrapped;
    let bytes = match data.strip_prefix(b"raw") {
        Some([v, stream @ ..]) => {
            wrapped = wrap(if v & 1 == 0 { 4 } else { 3 }, stream);
            &wrapped[..]
        }
        _ => data,
    };
    let path = Path::new("fuzz.serialized");
    let Ok(count) = shape_count(bytes, path) else {
        return;
    };
    for index in 0..=count.min(4) {
        let Ok(shape) = parse_serialized(bytes, index, path) else {
            continue;
        };
        assert!(index < count, "shape {index} of {count} read");
        let m = shape.mesh;
        m.validate().expect("a parsed shape gives a valid mesh");
        assert!(m.positions.iter().all(|p| p.is_finite()));
        assert!(
            m.normals
                .iter()
                .all(|n| n.is_finite() && n.length() < 1.001)
        );
        assert!(m.uvs.iter().all(|uv| uv.is_finite()));
        assert!(m.colors.iter().all(|c| c.is_finite()));
    }
});
