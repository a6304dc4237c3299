//! Partial films and checkpoints (one format, one reader): the header read alone, as
//! `--resume` first does, then the whole film, as `lucent merge` and `--resume` do. What is
//! accepted must be a film of finite pixels and a shard within its count.
//!
//! The `film` budget is 16 MiB here, so that no execution allocates more than a small film.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_cli::film_file::{read_film, read_meta};
use lucent_fuzz::write;
use lucent_scene::Limits;

const LIMITS: Limits = Limits {
    film_bytes: 16 << 20,
    ..Limits::DEFAULT
};

fuzz_target!(|data: &[u8]| {
    let path = write("fuzz.exr", data);
    let header = read_meta(&path, &LIMITS);
    let Ok((film, meta)) = read_film(&path, &LIMITS) else {
        return;
    };
    assert!(header.is_ok(), "a film whose header alone is refused was read whole");
    assert!(meta.shard.index < meta.shard.count);
    for y in 0..film.height() {
        for x in 0..film.width() {
            assert!(film.pixel(x, y).is_finite(), "pixel ({x}, {y})");
        }
    }
});
