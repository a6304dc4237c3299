//! Partial films and checkpoints (one format, one reader): the header read alone, as
//! `--resume` first does, then the whole film, as `lucent merge` and `--resume` do. What is
//! accepted must be a film of finite pixels and a shard within its count.
//!
//! The `film` budget is 16 MiB here, so that no execution allocates more than a small film.
//!
//! `read_film` refuses a file on which the `exr` crate panics (its debug assertions fire on
//! inconsistent blocks) by catching the panic. libFuzzer's panic hook would abort before the
//! catch, so the target replaces it by a silent one: a panic `read_film` does not catch still
//! reaches libfuzzer-sys, which reports it as a crash.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lucent_cli::film_file::{read_film, read_meta};
use lucent_fuzz::write;
use lucent_scene::Limits;

const LIMITS: Limits = Limits {
    film_bytes: 16 << 20,
    ..Limits::DEFAULT
};

static QUIET_PANICS: std::sync::Once = std::sync::Once::new();

fuzz_target!(|data: &[u8]| {
    QUIET_PANICS.call_once(|| std::panic::set_hook(Box::new(|_| {})));
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
