//! `KHR_materials_volume`'s attenuation as an absorbing medium inside the objects of its
//! material: light crossing a distance `d` inside keeps `attenuationColor^(d / attenuationDistance)`,
//! which is Beer–Lambert with `σa = −ln(attenuationColor) / attenuationDistance` per channel
//! (see `docs/media.md`). A material with zero thickness is thin-walled: no volume, no medium.

use crate::desc::{Color, MediumDesc, ObjectDesc};
use lucent::Rgb;
use toml::Spanned;

/// The least attenuation colour read: a channel of 0 (everything absorbed at once) is taken as
/// this, which absorbs all but a millionth over the attenuation distance.
const LEAST_COLOR: f32 = 1e-6;

/// The medium inside objects of material `m` (called `name` in the description), if its volume
/// attenuates.
pub fn medium(m: &gltf::Material, name: &str) -> Option<MediumDesc> {
    let v = m.volume()?;
    let (color, distance) = (v.attenuation_color(), v.attenuation_distance());
    let attenuates = distance.is_finite() && distance > 0.0 && color.iter().any(|&c| c < 1.0);
    if v.thickness_factor() <= 0.0 || !attenuates {
        return None;
    }
    let sigma_a = color.map(|c| -c.clamp(LEAST_COLOR, 1.0).ln() / distance);
    let mut d = MediumDesc::new(&format!("{name} volume"));
    d.sigma_a = Some(Spanned::new(0..0, Color(Rgb::from(sigma_a))));
    Some(d)
}

/// Puts each object whose material has a medium in `media` (material name, medium) inside it.
pub fn fill(objects: &mut [Spanned<ObjectDesc>], media: &[(String, MediumDesc)]) {
    for o in objects {
        let o = o.get_mut();
        if let Some((_, m)) = media.iter().find(|(name, _)| name == o.material.get_ref()) {
            o.interior = Some(Spanned::new(0..0, m.name.get_ref().clone()));
        }
    }
}
