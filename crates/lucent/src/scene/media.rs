//! The scene's participating media ([`crate::medium`]) and where they are: which objects
//! bound them and which one the camera sits in.

use super::{Scene, SceneBuilder};
use crate::medium::{Medium, MediumInterface};
use thiserror::Error;

/// Why a scene's media cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MediaError {
    /// A coefficient is negative, NaN or infinite.
    #[error("medium {medium}: {what} must be finite and at least 0 in every channel")]
    BadCoefficient {
        /// The medium's index.
        medium: u32,
        /// Which coefficient.
        what: &'static str,
    },
    /// An albedo grid without a density grid.
    #[error("medium {medium}: an albedo grid needs a density grid")]
    AlbedoWithoutDensity {
        /// The medium's index.
        medium: u32,
    },
    /// An object or the camera names a medium that does not exist.
    #[error("{user} names medium {medium}, but the scene has {count} media")]
    NoSuchMedium {
        /// Who names it ("object 3", "the camera").
        user: String,
        /// The index given.
        medium: u32,
        /// How many media exist.
        count: usize,
    },
    /// Media are given for an object that does not exist.
    #[error("media are given for object {object}, but the scene has {count} objects")]
    NoSuchObject {
        /// The object id given.
        object: u32,
        /// How many objects exist.
        count: u32,
    },
}

/// The media of a scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneMedia {
    media: Vec<Medium>,
    /// Each object's interface, by object id (objects past the end have none).
    interfaces: Vec<MediumInterface>,
    camera: Option<u32>,
}

impl SceneMedia {
    /// Adds a medium; returns its index.
    pub fn add(&mut self, m: Medium) -> u32 {
        self.media.push(m);
        (self.media.len() - 1) as u32
    }

    /// Sets the media inside and outside object `object`.
    pub fn bound_by(&mut self, object: u32, interface: MediumInterface) -> &mut Self {
        let i = object as usize;
        if self.interfaces.len() <= i {
            self.interfaces.resize(i + 1, MediumInterface::default());
        }
        self.interfaces[i] = interface;
        self
    }

    /// Puts the camera in medium `medium` (none: in vacuum).
    pub fn camera_in(&mut self, medium: Option<u32>) -> &mut Self {
        self.camera = medium;
        self
    }

    /// Whether there are any media.
    pub fn is_empty(&self) -> bool {
        self.media.is_empty()
    }

    /// Checks the coefficients and every index, for a scene of `objects` objects.
    pub(super) fn check(&self, objects: u32) -> Result<(), MediaError> {
        for (i, m) in self.media.iter().enumerate() {
            if m.albedo_grid.is_some() && m.density.is_none() {
                return Err(MediaError::AlbedoWithoutDensity { medium: i as u32 });
            }
            for (what, c) in [("sigma_a", m.sigma_a), ("sigma_s", m.sigma_s)] {
                if !c.is_finite() || c.to_array().iter().any(|&x| x < 0.0) {
                    return Err(MediaError::BadCoefficient {
                        medium: i as u32,
                        what,
                    });
                }
            }
        }
        let count = self.media.len();
        let named = |user: String, m: Option<u32>| match m {
            Some(medium) if medium as usize >= count => Err(MediaError::NoSuchMedium {
                user,
                medium,
                count,
            }),
            _ => Ok(()),
        };
        named("the camera".into(), self.camera)?;
        for (object, f) in self.interfaces.iter().enumerate() {
            if f.is_transition() && object as u32 >= objects {
                return Err(MediaError::NoSuchObject {
                    object: object as u32,
                    count: objects,
                });
            }
            named(format!("object {object}"), f.inside)?;
            named(format!("object {object}"), f.outside)?;
        }
        Ok(())
    }
}

impl SceneBuilder {
    /// The participating media, to add to.
    pub fn media(&mut self) -> &mut SceneMedia {
        &mut self.media
    }

    /// How many objects have been added (the next one's id).
    pub fn objects(&self) -> u32 {
        self.objects
    }
}

impl Scene {
    /// Whether the scene has participating media (then the path tracer tracks them).
    pub fn has_media(&self) -> bool {
        !self.media.is_empty()
    }

    /// Medium `i`.
    pub fn medium(&self, i: u32) -> &Medium {
        &self.media.media[i as usize]
    }

    /// The media on either side of object `object`'s surface.
    pub fn medium_interface(&self, object: u32) -> MediumInterface {
        self.media
            .interfaces
            .get(object as usize)
            .copied()
            .unwrap_or_default()
    }

    /// The medium the camera sits in.
    pub fn camera_medium(&self) -> Option<u32> {
        self.media.camera
    }
}
