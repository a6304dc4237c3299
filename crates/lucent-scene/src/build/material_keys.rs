//! Which keys each kind of `[[material]]` takes: the rest are refused, naming the key and the
//! kind, and a scale without its map is an error.

use super::{Context, refuse_keys, span};
use crate::desc::{MaterialDesc, MaterialKind};
use crate::error::LoadError;
use toml::Spanned;

/// The keys every kind takes.
const COMMON: &[&str] = &[
    "emission",
    "opacity",
    "normal_map",
    "normal_scale",
    "bump_map",
    "bump_scale",
    "two_sided",
    "back",
    "vertex_colors",
    "cull_back",
    "emits_back",
];

/// The keys of each kind besides [`COMMON`].
fn takes(kind: MaterialKind) -> &'static [&'static str] {
    const ROUGH: [&str; 4] = ["roughness", "roughness_u", "roughness_v", "distribution"];
    match kind {
        MaterialKind::Whitted => &[
            "ka",
            "ka_map",
            "bump",
            "kd",
            "ks",
            "shininess",
            "highlight",
            "brilliance",
            "kr",
            "kt",
            "ior",
        ],
        MaterialKind::Diffuse => &["reflectance"],
        MaterialKind::Null => &[],
        MaterialKind::Conductor => &["specular", "eta", "k", "metal"],
        MaterialKind::RoughConductor => &[
            "specular", "eta", "k", "metal", ROUGH[0], ROUGH[1], ROUGH[2], ROUGH[3],
        ],
        MaterialKind::Dielectric | MaterialKind::ThinDielectric => {
            &["ior", "ext_ior", "specular", "transmittance"]
        }
        MaterialKind::RoughDielectric => &[
            "ior",
            "ext_ior",
            "specular",
            "transmittance",
            ROUGH[0],
            ROUGH[1],
            ROUGH[2],
            ROUGH[3],
        ],
        MaterialKind::Plastic | MaterialKind::RoughPlastic => &[
            "reflectance",
            "ior",
            "ext_ior",
            "specular",
            "nonlinear",
            "roughness",
            "distribution",
        ],
        MaterialKind::Blend => &["materials", "weight"],
        MaterialKind::Principled => &[
            "base_color",
            "roughness",
            "anisotropic",
            "metallic",
            "spec_trans",
            "spec_tint",
            "sheen",
            "sheen_tint",
            "flatness",
            "clearcoat",
            "clearcoat_gloss",
            "ior",
            "specular",
        ],
        MaterialKind::PrincipledThin => &[
            "base_color",
            "roughness",
            "anisotropic",
            "spec_trans",
            "diff_trans",
            "spec_tint",
            "sheen",
            "sheen_tint",
            "flatness",
            "ior",
        ],
        MaterialKind::Pbr => &[
            "base_color",
            "metallic",
            "roughness",
            "ior",
            "specular",
            "specular_color",
            "transmission",
            "volume",
            "clearcoat",
            "clearcoat_roughness",
            "clearcoat_normal_map",
            "clearcoat_normal_scale",
            "sheen_color",
            "sheen_roughness",
            "anisotropy",
            "anisotropy_rotation",
            "anisotropy_direction",
            "diffuse_transmission",
            "diffuse_transmission_color",
            "iridescence",
            "iridescence_ior",
            "iridescence_thickness",
        ],
    }
}

/// Refuses the keys the material's kind does not take.
pub(super) fn check_keys(m: &Spanned<MaterialDesc>, ctx: &Context) -> Result<(), LoadError> {
    let table = m.span();
    let d = m.get_ref();
    let kind = d.kind();
    let at = |present: bool| present.then(|| table.clone());
    let keys = [
        ("ka", at(d.ka.is_some())),
        ("ka_map", at(d.ka_map.is_some())),
        ("bump", at(d.bump.is_some())),
        ("kd", at(d.kd.is_some())),
        ("ks", at(d.ks.is_some())),
        ("shininess", span(&d.shininess)),
        ("highlight", span(&d.highlight)),
        ("brilliance", span(&d.brilliance)),
        ("kr", at(d.kr.is_some())),
        ("kt", at(d.kt.is_some())),
        ("ior", span(&d.ior)),
        ("ext_ior", span(&d.ext_ior)),
        ("reflectance", at(d.reflectance.is_some())),
        ("specular", at(d.specular.is_some())),
        ("transmittance", at(d.transmittance.is_some())),
        ("eta", at(d.eta.is_some())),
        ("k", at(d.k.is_some())),
        ("metal", span(&d.metal)),
        ("roughness", span(&d.roughness)),
        ("roughness_u", span(&d.roughness_u)),
        ("roughness_v", span(&d.roughness_v)),
        ("distribution", span(&d.distribution)),
        ("nonlinear", at(d.nonlinear.is_some())),
        ("materials", span(&d.materials)),
        ("weight", span(&d.weight)),
        ("base_color", at(d.base_color.is_some())),
        ("metallic", span(&d.metallic)),
        ("anisotropic", span(&d.anisotropic)),
        ("spec_trans", span(&d.spec_trans)),
        ("spec_tint", span(&d.spec_tint)),
        ("sheen", span(&d.sheen)),
        ("sheen_tint", span(&d.sheen_tint)),
        ("flatness", span(&d.flatness)),
        ("clearcoat", span(&d.clearcoat)),
        ("clearcoat_gloss", span(&d.clearcoat_gloss)),
        ("diff_trans", span(&d.diff_trans)),
        ("specular_color", at(d.specular_color.is_some())),
        ("transmission", span(&d.transmission)),
        ("volume", at(d.volume.is_some())),
        ("clearcoat_roughness", span(&d.clearcoat_roughness)),
        ("clearcoat_normal_map", span(&d.clearcoat_normal_map)),
        ("clearcoat_normal_scale", span(&d.clearcoat_normal_scale)),
        ("sheen_color", at(d.sheen_color.is_some())),
        ("sheen_roughness", span(&d.sheen_roughness)),
        ("anisotropy", span(&d.anisotropy)),
        ("anisotropy_rotation", span(&d.anisotropy_rotation)),
        ("anisotropy_direction", span(&d.anisotropy_direction)),
        ("diffuse_transmission", span(&d.diffuse_transmission)),
        (
            "diffuse_transmission_color",
            at(d.diffuse_transmission_color.is_some()),
        ),
        ("iridescence", span(&d.iridescence)),
        ("iridescence_ior", span(&d.iridescence_ior)),
        ("iridescence_thickness", span(&d.iridescence_thickness)),
    ];
    let takes = takes(kind);
    let others: Vec<_> = keys
        .into_iter()
        .filter(|(k, _)| !takes.contains(k) && !COMMON.contains(k))
        .collect();
    refuse_keys(ctx.source, &format!("{} material", kind.name()), &others)?;
    if d.normal_scale.is_some() && d.normal_map.is_none() {
        return Err(ctx.source.error(
            d.normal_scale.as_ref().map_or(table.clone(), Spanned::span),
            "`normal_scale` needs a `normal_map`",
        ));
    }
    if d.clearcoat_normal_scale.is_some() && d.clearcoat_normal_map.is_none() {
        return Err(ctx.source.error(
            d.clearcoat_normal_scale
                .as_ref()
                .map_or(table.clone(), Spanned::span),
            "`clearcoat_normal_scale` needs a `clearcoat_normal_map`",
        ));
    }
    if d.bump_scale.is_some() && d.bump_map.is_none() {
        return Err(ctx.source.error(
            d.bump_scale.as_ref().map_or(table, Spanned::span),
            "`bump_scale` needs a `bump_map`",
        ));
    }
    Ok(())
}
