//! What of the `lucent` command other programs may use: its film files (partial films and
//! checkpoints, `film_file`) and image output (`output`). The fuzz targets read films through
//! it; the command itself is `main.rs`.

pub mod film_file;
pub mod output;
