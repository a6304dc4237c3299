//! From a `[[material]]` description to the renderer's material: the classic coefficients as
//! given, or the nearest classic equivalent of a physically based kind.

use crate::desc::{DiffuseDesc, MaterialDesc, MaterialKind};
use crate::error::{LoadError, Source};
use lucent::Rgb;
use lucent::material::Material;
use lucent::texture::Texture;

/// The renderer's material for `m`: missing coefficients 0, missing ior 1.
pub fn whitted_material(m: &MaterialDesc, source: &Source) -> Result<Material, LoadError> {
    if m.kind() != MaterialKind::Whitted {
        let span = m.kind.as_ref().map_or(m.name.span(), |k| k.span());
        return Err(source.error(
            span,
            format!("`{}` materials are not supported yet", m.kind().name()),
        ));
    }
    let c = |o: Option<crate::desc::Color>| o.map_or(Rgb::BLACK, |c| c.0);
    let kd = match &m.kd {
        None => Texture::Solid(Rgb::BLACK),
        Some(DiffuseDesc::Solid(c)) => Texture::Solid(*c),
        Some(DiffuseDesc::Checker(c)) => Texture::Checker(*c),
        Some(DiffuseDesc::Image(_)) => {
            return Err(source.error(m.name.span(), "image textures are not supported yet"));
        }
    };
    if let Some(s) = &m.shininess
        && s.get_ref().0 < 0.0
    {
        return Err(source.error(s.span(), "shininess must not be negative"));
    }
    if let Some(ior) = &m.ior
        && ior.get_ref().0 <= 0.0
    {
        return Err(source.error(ior.span(), "ior must be positive"));
    }
    Ok(Material {
        ka: c(m.ka),
        kd,
        ks: c(m.ks),
        shininess: m.shininess.as_ref().map_or(0.0, |s| s.get_ref().0),
        kr: c(m.kr),
        kt: c(m.kt),
        ior: m.ior.as_ref().map_or(1.0, |s| s.get_ref().0),
        ke: Rgb::BLACK,
    })
}
