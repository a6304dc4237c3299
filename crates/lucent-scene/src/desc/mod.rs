//! `SceneDesc`: a scene as plain data, exactly as a scene file gives it.
//!
//! Values carry their location in the file (`Spanned`) wherever a later check may need to
//! point at them; everything that can be checked while reading (types, finite numbers, unknown
//! keys) is checked by serde as the file is read. Name resolution and the checks that need the
//! whole scene happen in [`crate::build`].

pub mod camera;
pub mod light;
pub mod material;
pub mod medium;
pub mod motion;
pub mod object;
pub mod settings;
pub mod texture;
pub mod values;

pub use camera::CameraDesc;
pub use light::{FalloffName, LightDesc, LightKind, MappingName, TexelsName};
pub use material::{BumpDesc, MaterialDesc, MaterialKind};
pub use medium::MediumDesc;
pub use motion::{KeyDesc, MotionDesc, OrbitDesc, OscillateDesc, RepeatName};
pub use object::{ObjectDesc, ObjectKind};
pub use settings::{ImageDesc, IntegratorName, RenderDesc, WorldDesc};
pub use texture::{ImageMapDesc, TextureDesc};
pub use values::{Color, Finite, Matrix, Point, Scale, Vector};

use serde::{Deserialize, Serialize};
use toml::Spanned;

/// A whole scene file.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// `[image]`: resolution and samples.
    #[serde(default)]
    pub image: ImageDesc,
    /// `[camera]`: the pinhole camera.
    pub camera: Spanned<CameraDesc>,
    /// `[world]`: background and ambient light.
    #[serde(default)]
    pub world: WorldDesc,
    /// `[render]`: integrator and its limits.
    #[serde(default)]
    pub render: RenderDesc,
    /// `[[material]]` tables.
    #[serde(default, rename = "material", skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<Spanned<MaterialDesc>>,
    /// `[[light]]` tables.
    #[serde(default, rename = "light", skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<Spanned<LightDesc>>,
    /// `[[object]]` tables.
    #[serde(default, rename = "object", skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<Spanned<ObjectDesc>>,
    /// `[[medium]]` tables.
    #[serde(default, rename = "medium", skip_serializing_if = "Vec::is_empty")]
    pub media: Vec<Spanned<MediumDesc>>,
}
