//! Schedules: which pixel gets which sample, in what order.
//!
//! The render driver asks a schedule for work and knows nothing of the order. The batch
//! renderer uses [`tiles()`]: square tiles, each traced whole (all of its samples) by one thread;
//! with [`adaptive`] supersampling, a tile's pixels take Whitted's corners instead of samples.

pub mod adaptive;
pub mod frameless;
pub mod tiles;

pub use tiles::{Tile, tiles};
