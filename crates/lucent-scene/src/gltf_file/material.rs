//! glTF's metallic-roughness materials as lucent's physically based kinds.
//!
//! | glTF | lucent |
//! | --- | --- |
//! | metallic ≥ 0.5, roughness ≤ 0.05 | `conductor`: `specular` = base colour (no `eta`/`k`: an ideal reflector tinted by it) |
//! | metallic ≥ 0.5 | `roughconductor`: as above, `roughness` α = roughness² |
//! | transmission ≥ 0.5, roughness ≤ 0.05 | `dielectric`: `ior`, `transmittance` = base colour |
//! | transmission ≥ 0.5 | `roughdielectric`: as above, `roughness` α |
//! | roughness ≥ 0.5 | `diffuse`: `reflectance` = base colour or texture |
//! | otherwise | `plastic`: `reflectance`, `ior`, and `roughness` α unless roughness ≤ 0.05 |
//!
//! The rows are tried in order: a metal is opaque whatever its transmission factor. `roughness`,
//! `metallic` and `transmission` are the factors (textures are not read); α = roughness² is the
//! usual remapping of glTF's perceptual roughness to GGX's. `ior` is KHR_materials_ior's
//! (default 1.5). Colours are linear in glTF, as in lucent, and are kept as they are. The
//! emissive factor times KHR_materials_emissive_strength becomes `emission` when it is not
//! black; `doubleSided` becomes `two_sided`.

use super::source::file_name_of_uri;
use crate::desc::{Finite, ImageMapDesc, MaterialDesc, MaterialKind, TextureDesc};
use crate::paths::{LoadOptions, resolve};
use gltf::material::AlphaMode;
use lucent::Rgb;
use std::path::Path;
use toml::Spanned;

/// A glTF roughness at or below this is taken for a smooth surface.
pub(super) const SMOOTH: f32 = 0.05;
/// A glTF roughness at or above this makes a dielectric surface `diffuse` rather than `plastic`.
pub(super) const DIFFUSE: f32 = 0.5;
/// The reflectance of the material given to primitives without one.
pub(super) const DEFAULT_REFLECTANCE: f32 = 0.8;

/// The material given to primitives without one: `diffuse` grey 0.8, one-sided. (glTF's own
/// default is a white rough metal, which lit by a few point lights looks much like this but
/// darker; most files without materials are geometry meant to be seen plainly.)
pub(super) fn default_material(name: &str) -> MaterialDesc {
    let mut d = MaterialDesc::named(name);
    d.kind = Some(Spanned::new(0..0, MaterialKind::Diffuse));
    d.reflectance = Some(TextureDesc::gray(DEFAULT_REFLECTANCE));
    d.two_sided = Some(false);
    d
}

/// Where image files are looked for, and how.
pub(super) struct Images<'a> {
    /// The document's JSON, for the images' URIs.
    pub root: &'a gltf::json::Root,
    /// The glTF file's folder.
    pub base_dir: &'a Path,
    /// `--sandbox` or not.
    pub options: &'a LoadOptions,
}

/// The description of material `m` named `name`, and notes on what it does not render as
/// written (sentences naming the material). An error when an image URI is refused.
pub(super) fn describe(
    m: &gltf::Material,
    name: &str,
    images: &Images,
) -> Result<(MaterialDesc, Vec<String>), String> {
    let label = match (m.index(), m.name()) {
        (Some(i), Some(n)) => format!("material {i} (`{n}`)"),
        (Some(i), None) => format!("material {i}"),
        (None, _) => "the default material".to_string(),
    };
    let mut notes = Vec::new();
    let mut note = |s: String| notes.push(format!("{label}: {s}"));
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _alpha] = pbr.base_color_factor();
    let base = color([r, g, b], "baseColorFactor", &mut note);
    let metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    let alpha = roughness * roughness;
    let transmission = m
        .transmission()
        .map_or(0.0, |t| t.transmission_factor())
        .clamp(0.0, 1.0);
    let ior = match m.ior() {
        None => 1.5,
        Some(v) if v >= 1.0 && v.is_finite() => v,
        Some(v) => {
            note(format!(
                "ior {v} is not an index of refraction ≥ 1; 1.5 is used"
            ));
            1.5
        }
    };
    let smooth = roughness <= SMOOTH;
    // A metal is opaque whatever its transmission (KHR_materials_transmission mixes the
    // transmissive dielectric with the metal by `metallic`), so metallic is decided first.
    let kind = if metallic >= 0.5 {
        if smooth {
            MaterialKind::Conductor
        } else {
            MaterialKind::RoughConductor
        }
    } else if transmission >= 0.5 {
        if smooth {
            MaterialKind::Dielectric
        } else {
            MaterialKind::RoughDielectric
        }
    } else if roughness >= DIFFUSE {
        MaterialKind::Diffuse
    } else {
        MaterialKind::Plastic
    };
    let metal = metallic >= 0.5;
    for (what, v) in [
        ("metallicFactor", metallic),
        ("transmissionFactor", transmission),
    ] {
        if v != 0.0 && v != 1.0 && !(metal && what == "transmissionFactor") {
            note(format!(
                "{what} {v} is rounded to {}: rendered as `{}`",
                v.round(),
                kind.name()
            ));
        }
    }
    if !matches!(m.alpha_mode(), AlphaMode::Opaque) {
        note(format!(
            "alpha mode {:?} is not rendered: opaque",
            m.alpha_mode()
        ));
    }
    let texture = match pbr.base_color_texture() {
        None => None,
        Some(info) => image_file(&info, images, &mut note)?,
    };
    let mut d = MaterialDesc::named(name);
    d.kind = Some(Spanned::new(0..0, kind));
    let finite = |v: f32| Some(Spanned::new(0..0, Finite(v)));
    match kind {
        MaterialKind::Dielectric | MaterialKind::RoughDielectric => {
            d.ior = finite(ior);
            d.transmittance = Some(TextureDesc::Solid(base));
        }
        MaterialKind::Conductor | MaterialKind::RoughConductor => {
            d.specular = Some(TextureDesc::Solid(base));
        }
        _ => {
            d.reflectance = Some(match &texture {
                Some(file) => {
                    if base != Rgb::WHITE {
                        note(format!(
                            "baseColorFactor {:?} times the texture: the factor is dropped",
                            base.to_array()
                        ));
                    }
                    TextureDesc::Image(ImageMapDesc::new(file.clone()))
                }
                None => TextureDesc::Solid(base),
            });
            if kind == MaterialKind::Plastic {
                d.ior = finite(ior);
            }
        }
    }
    if texture.is_some() && !matches!(kind, MaterialKind::Diffuse | MaterialKind::Plastic) {
        note(format!(
            "the base colour texture does not apply to `{}`; baseColorFactor is used",
            kind.name()
        ));
    }
    if matches!(
        kind,
        MaterialKind::RoughDielectric | MaterialKind::RoughConductor | MaterialKind::Plastic
    ) && !smooth
    {
        d.roughness = Some(Spanned::new(0..0, TextureDesc::gray(alpha)));
    }
    let strength = m.emissive_strength().unwrap_or(1.0);
    let [er, eg, eb] = m.emissive_factor();
    let emission = color(
        [er * strength, eg * strength, eb * strength],
        "emission",
        &mut note,
    );
    if !emission.is_black() {
        d.emission = Some(TextureDesc::Solid(emission));
    }
    d.two_sided = Some(m.double_sided());
    let ignored = [
        (
            "metallicRoughnessTexture",
            pbr.metallic_roughness_texture().is_some(),
        ),
        ("normalTexture", m.normal_texture().is_some()),
        ("emissiveTexture", m.emissive_texture().is_some()),
        (
            "transmissionTexture",
            m.transmission()
                .is_some_and(|t| t.transmission_texture().is_some()),
        ),
    ];
    for (what, _) in ignored.iter().filter(|(_, present)| *present) {
        note(format!("{what} is not read; the factors are used"));
    }
    Ok((d, notes))
}

/// `[r, g, b]` as a colour; negative or non-finite channels (which glTF does not allow) become 0.
fn color(v: [f32; 3], what: &str, note: &mut impl FnMut(String)) -> Rgb {
    let clean = v.map(|c| if c.is_finite() && c > 0.0 { c } else { 0.0 });
    if v.iter().any(|c| !c.is_finite() || *c < 0.0) {
        note(format!(
            "{what} {v:?} has negative or infinite channels, set to 0"
        ));
    }
    Rgb::from(clean)
}

/// The file name of a texture's image, relative to the glTF file's folder, when it is a file
/// (`None`, with a note, for images inside the glTF or GLB file, which are not extracted). An
/// error when `--sandbox` refuses the name.
fn image_file(
    info: &gltf::texture::Info,
    images: &Images,
    note: &mut impl FnMut(String),
) -> Result<Option<String>, String> {
    if info.tex_coord() != 0 {
        note(format!(
            "the base colour texture uses TEXCOORD_{}; TEXCOORD_0 is used",
            info.tex_coord()
        ));
    }
    // The JSON is read directly: the crate's `Image::source` panics on an image that has
    // neither a URI nor a buffer view with a MIME type, which validation lets through.
    let index = info.texture().source().index();
    let uri = images
        .root
        .images
        .get(index)
        .and_then(|i| i.uri.as_deref())
        .filter(|uri| !uri.starts_with("data:"));
    match uri {
        Some(uri) => {
            let name = file_name_of_uri(uri).map_err(|e| format!("image {index}: {e}"))?;
            resolve(images.base_dir, &name, images.options)
                .map_err(|e| format!("image {index}: {e}"))?;
            Ok(Some(name))
        }
        None => {
            note(format!(
                "image {index} is embedded in the glTF file and is not extracted; baseColorFactor is used"
            ));
            Ok(None)
        }
    }
}
