//! Mitsuba 3 scene files made here — the Cornell box as Mitsuba publishes it, and small scenes
//! for each feature — read back: the camera, transforms, shapes, BSDFs and emitters described
//! as Mitsuba means them, the box rendered with each wall in its place, and broken or hostile
//! files refused with one line naming the file, line and column, never a panic.

#[path = "mitsuba/cbox.rs"]
mod cbox;
#[path = "mitsuba/errors.rs"]
mod errors;
#[path = "mitsuba/hostile.rs"]
mod hostile;
#[path = "mitsuba/media.rs"]
mod media;
#[path = "mitsuba/placement.rs"]
mod placement;
#[path = "mitsuba/plugins.rs"]
mod plugins;
#[path = "mitsuba/references.rs"]
mod references;
#[path = "mitsuba/serialized.rs"]
mod serialized;
#[path = "mitsuba/support.rs"]
mod support;
