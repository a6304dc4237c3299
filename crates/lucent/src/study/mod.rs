//! Studies: simulations that measure a claim of the literature under controlled conditions.
//!
//! [`frameless`] replays the display modes of [`crate::schedule::frameless`] under a fixed
//! sample budget per display refresh, so that its figures do not depend on the machine's speed.

pub mod frameless;
