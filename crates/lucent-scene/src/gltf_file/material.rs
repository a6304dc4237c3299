//! glTF's metallic-roughness materials, with their textures and extensions, as lucent's `pbr`
//! kind (the specification's BRDF, appendix B; see `lucent::bsdf::gltf_pbr`).
//!
//! | glTF | lucent `pbr` |
//! | --- | --- |
//! | `baseColorFactor` × `baseColorTexture` (sRGB) | `base_color` |
//! | `metallicFactor` × blue, `roughnessFactor` × green of `metallicRoughnessTexture` | `metallic`, `roughness` |
//! | `normalTexture` (`scale`) | `normal_map` (`normal_scale`), in the mesh's `TANGENT` frame or MikkTSpace's |
//! | `emissiveFactor` × `emissiveTexture` × `KHR_materials_emissive_strength` | `emission` |
//! | `alphaMode` `MASK` (`alphaCutoff`) / `BLEND`: base colour alpha × texture alpha | `opacity`: a `step` at the cutoff / the alpha itself |
//! | `doubleSided` | `two_sided` |
//! | `KHR_materials_ior`, `_specular`, `_transmission`, `_volume` (a thickness: refracting; an attenuation: an absorbing medium inside, `volume.rs`) | `ior`, `specular`, `specular_color`, `transmission`, `volume`; the objects' `interior` |
//! | `KHR_materials_clearcoat`, `_sheen`, `_anisotropy` | `clearcoat`, `clearcoat_roughness`, `clearcoat_normal_map`; `sheen_color`, `sheen_roughness`; `anisotropy`, `anisotropy_rotation`, `anisotropy_direction` |
//! | `KHR_materials_diffuse_transmission`: factor × alpha, colour × texture | `diffuse_transmission`, `diffuse_transmission_color` |
//! | `KHR_materials_unlit` | `diffuse` black with `emission` = base colour × vertex colour (`emits_back` when double-sided) |
//! | `KHR_materials_iridescence`: `iridescenceFactor` × red of `iridescenceTexture`, `iridescenceIor`, thickness `mix(iridescenceThicknessMinimum, iridescenceThicknessMaximum, green of iridescenceThicknessTexture)` (the maximum without the texture) | `iridescence`, `iridescence_ior`, `iridescence_thickness` (a `mix` of the two numbers by the texture) |
//! | a sampler's `wrapS`/`wrapT`, `magFilter` `NEAREST`; `KHR_texture_transform` | an image's `wrap`, `filter`; its `scale`, `rotation`, `offset` |
//!
//! Images held inside the glTF or GLB file (buffer views, `data:` URIs) are named by the file
//! and their index (`gltf_image`), and decoded by the build.
//!
//! A primitive keeps the coordinate set most of its material's textures read ([`uv_set`]).
//!
//! Not read (each a note naming the material): a texture reading another coordinate set,
//! `KHR_materials_dispersion`, specular-glossiness materials.
//! `occlusionTexture` is a rasteriser's stand-in for the shadowing a path tracer computes, and
//! is left out on purpose.

use super::source::file_name_of_uri;
use crate::desc::texture::{Encoding, Placement};
use crate::desc::{Finite, ImageMapDesc, MaterialDesc, MaterialKind, TextureDesc};
use crate::paths::{LoadOptions, resolve};
use gltf::json::validation::Checked;
use gltf::material::AlphaMode;
use gltf::texture::{MagFilter, WrappingMode};
use lucent::Rgb;
use lucent::texture::{Channel, Filter, Wrap};
use serde_json::Value;
use std::path::Path;
use toml::Spanned;

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
    /// The document's JSON, for the textures, samplers and images.
    pub root: &'a gltf::json::Root,
    /// The glTF file's folder.
    pub base_dir: &'a Path,
    /// The glTF file's name in that folder: images held inside it are named by it.
    pub file_name: &'a str,
    /// The file with its buffers, where the images held inside it are read (`None` in tests
    /// of the description alone).
    pub asset: Option<&'a super::Asset>,
    /// `--sandbox` or not.
    pub options: &'a LoadOptions,
}

/// A texture slot as a material gives it: which texture, which coordinates, its scale or
/// strength (normal and occlusion maps), and its `KHR_texture_transform`.
#[derive(Clone)]
struct Slot {
    texture: usize,
    tex_coord: u32,
    scale: f32,
    transform: Option<Value>,
}

impl Slot {
    fn of_info(info: &gltf::texture::Info) -> Self {
        Slot {
            texture: info.texture().index(),
            tex_coord: info.tex_coord(),
            scale: 1.0,
            transform: info.extension_value("KHR_texture_transform").cloned(),
        }
    }

    /// A texture slot inside an extension's JSON (`{"index": 3, "texCoord": 0, ...}`).
    fn of_json(v: Option<&Value>) -> Option<Self> {
        let v = v?;
        Some(Slot {
            texture: v.get("index")?.as_u64()? as usize,
            tex_coord: v.get("texCoord").and_then(Value::as_u64).unwrap_or(0) as u32,
            scale: number(v, "scale", 1.0),
            transform: v
                .get("extensions")
                .and_then(|e| e.get("KHR_texture_transform"))
                .cloned(),
        })
    }
}

/// `v[key]` as a number, or `default`.
fn number(v: &Value, key: &str, default: f32) -> f32 {
    v.get(key)
        .and_then(Value::as_f64)
        .map_or(default, |x| x as f32)
}

/// `v[key]` as a colour of three numbers, or `default`.
fn color_of(v: &Value, key: &str, default: Rgb) -> Rgb {
    match v.get(key).and_then(Value::as_array) {
        Some(a) if a.len() == 3 => {
            let c = |i: usize| a[i].as_f64().unwrap_or(0.0) as f32;
            Rgb::new(c(0), c(1), c(2))
        }
        _ => default,
    }
}

/// Reads one material, collecting notes on what it does not render as written.
struct Reader<'a, 'b> {
    images: &'b Images<'a>,
    label: String,
    notes: Vec<String>,
    /// The coordinate set the material's primitives keep ([`uv_set`]).
    uv_set: u32,
}

impl Reader<'_, '_> {
    /// Notes `s` once (a texture read for two parameters, as metallicRoughnessTexture is, would
    /// say it twice).
    fn note(&mut self, s: impl std::fmt::Display) {
        let note = format!("{}: {s}", self.label);
        if !self.notes.contains(&note) {
            self.notes.push(note);
        }
    }

    /// The image lookup of `slot` reading `channel` (`None` when the image cannot be read,
    /// with a note). An error when `--sandbox` refuses the file.
    fn image(
        &mut self,
        slot: &Slot,
        what: &str,
        encoding: Encoding,
        channel: Channel,
    ) -> Result<Option<TextureDesc>, String> {
        let root = self.images.root;
        let Some(texture) = root.textures.get(slot.texture) else {
            self.note(format!(
                "{what}: texture {} does not exist; ignored",
                slot.texture
            ));
            return Ok(None);
        };
        let index = texture.source.value();
        // The JSON is read directly: the crate's `Image::source` panics on an image that has
        // neither a URI nor a buffer view with a MIME type, which validation lets through.
        let Some(json) = root.images.get(index) else {
            self.note(format!(
                "{what}: image {index} does not exist; the factor alone is used"
            ));
            return Ok(None);
        };
        // An image in a buffer view or a data: URI is read from the glTF file itself.
        let (file, gltf_image) = match json.uri.as_deref() {
            Some(uri) if !uri.starts_with("data:") => {
                let file = file_name_of_uri(uri).map_err(|e| format!("image {index}: {e}"))?;
                resolve(self.images.base_dir, &file, self.images.options)
                    .map_err(|e| format!("image {index}: {e}"))?;
                (file, None)
            }
            _ => (self.images.file_name.to_string(), Some(index as u32)),
        };
        let mut tex_coord = slot.tex_coord;
        let mut placement = Placement::default();
        if let Some(t) = &slot.transform {
            let pair = |key: &str, default: [f32; 2]| match t.get(key).and_then(Value::as_array) {
                Some(a) if a.len() == 2 => [
                    a[0].as_f64().unwrap_or(default[0] as f64) as f32,
                    a[1].as_f64().unwrap_or(default[1] as f64) as f32,
                ],
                _ => default,
            };
            placement.scale = Some(pair("scale", [1.0, 1.0]));
            placement.offset = Some(pair("offset", [0.0, 0.0]));
            // glTF turns uv by −rotation in lucent's sense (from +u towards +v).
            placement.rotation = Some(-number(t, "rotation", 0.0).to_degrees());
            if let Some(k) = t.get("texCoord").and_then(Value::as_u64) {
                tex_coord = k as u32;
            }
        }
        if tex_coord != self.uv_set {
            let set = self.uv_set;
            self.note(format!(
                "{what} uses TEXCOORD_{tex_coord}; TEXCOORD_{set}, which the material's other textures use, is used"
            ));
        }
        let mut image = ImageMapDesc::new(file);
        image.gltf_image = gltf_image;
        image.encoding = Some(encoding);
        if channel != Channel::Rgb {
            image.channel = Some(channel);
        }
        image.placement = placement;
        if let Some(s) = texture.sampler.and_then(|s| root.samplers.get(s.value())) {
            let wrap = |w: Checked<WrappingMode>| match w {
                Checked::Valid(WrappingMode::ClampToEdge) => Wrap::Clamp,
                Checked::Valid(WrappingMode::MirroredRepeat) => Wrap::Mirror,
                _ => Wrap::Repeat,
            };
            let wraps = [wrap(s.wrap_s), wrap(s.wrap_t)];
            if wraps != [Wrap::Repeat; 2] {
                image.wrap = Some(wraps);
            }
            if s.mag_filter == Some(Checked::Valid(MagFilter::Nearest)) {
                image.filter = Some(Filter::Nearest);
            }
        }
        Ok(Some(TextureDesc::Image(image)))
    }

    /// `factor` times the texture of `slot` (if any), as one texture.
    fn scaled(
        &mut self,
        factor: Rgb,
        slot: Option<Slot>,
        what: &str,
        encoding: Encoding,
        channel: Channel,
    ) -> Result<TextureDesc, String> {
        let factor = self.clean(factor, what);
        let texture = match slot {
            Some(s) if !factor.is_black() => self.image(&s, what, encoding, channel)?,
            _ => None,
        };
        Ok(match texture {
            None => TextureDesc::Solid(factor),
            Some(t) if factor == Rgb::WHITE => t,
            Some(t) => TextureDesc::Product(Box::new(TextureDesc::Solid(factor)), Box::new(t)),
        })
    }

    /// Extension `ext`'s number `factor` (default 0, clamped to [0, 1]) times the linear
    /// `channel` of its texture `texture`, if any; `None` where that is 0 everywhere.
    fn unit_factor(
        &mut self,
        ext: &Value,
        factor: &str,
        texture: &str,
        channel: Channel,
    ) -> Result<Option<Spanned<TextureDesc>>, String> {
        let t = self.scaled(
            Rgb::gray(number(ext, factor, 0.0).clamp(0.0, 1.0)),
            Slot::of_json(ext.get(texture)),
            texture,
            Encoding::Linear,
            channel,
        )?;
        Ok(unless_default(t, 0.0))
    }

    /// A colour with negative or non-finite channels (which glTF does not allow) set to 0.
    fn clean(&mut self, c: Rgb, what: &str) -> Rgb {
        let v = c.to_array();
        if v.iter().all(|x| x.is_finite() && *x >= 0.0) {
            return c;
        }
        self.note(format!(
            "{what} {v:?} has negative or infinite channels, set to 0"
        ));
        Rgb::from(v.map(|x| if x.is_finite() && x > 0.0 { x } else { 0.0 }))
    }
}

fn spanned<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

/// A number as a grey texture, kept only where it is not the default.
fn unless_default(t: TextureDesc, default: f32) -> Option<Spanned<TextureDesc>> {
    (t != TextureDesc::gray(default)).then(|| spanned(t))
}

/// The texture coordinate set (`TEXCOORD_n`) a primitive of material `index` keeps as its
/// texture coordinates: the one most of the material's textures read (a `KHR_texture_transform`
/// `texCoord` counted for its texture), the lower on a tie; 0 without textures. A mesh carries
/// one set, so textures reading another are noted by [`describe`].
pub(super) fn uv_set(root: &gltf::json::Root, index: Option<usize>) -> u32 {
    let Some(json) = index
        .and_then(|i| root.materials.get(i))
        .and_then(|m| serde_json::to_value(m).ok())
    else {
        return 0;
    };
    let mut counts: Vec<(u32, usize)> = Vec::new();
    texture_sets(
        &json,
        &mut |set| match counts.iter_mut().find(|(s, _)| *s == set) {
            Some((_, n)) => *n += 1,
            None => counts.push((set, 1)),
        },
    );
    counts
        .into_iter()
        .max_by_key(|&(set, n)| (n, std::cmp::Reverse(set)))
        .map_or(0, |(set, _)| set)
}

/// Calls `f` with the coordinate set of every texture slot (`...Texture` objects with an
/// `index`) in a material's JSON, extensions included, `occlusionTexture` (not read) excluded.
fn texture_sets(v: &Value, f: &mut impl FnMut(u32)) {
    let Some(map) = v.as_object() else {
        return;
    };
    for (key, value) in map {
        if key.ends_with("Texture") && key != "occlusionTexture" && value.get("index").is_some() {
            let set = value
                .get("extensions")
                .and_then(|e| e.get("KHR_texture_transform"))
                .and_then(|t| t.get("texCoord"))
                .or_else(|| value.get("texCoord"))
                .and_then(Value::as_u64)
                .unwrap_or(0);
            f(u32::try_from(set).unwrap_or(u32::MAX));
        } else {
            texture_sets(value, f);
        }
    }
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
    let mut r = Reader {
        images,
        label,
        notes: Vec::new(),
        uv_set: uv_set(images.root, m.index()),
    };
    let mut d = MaterialDesc::named(name);
    d.kind = Some(spanned(MaterialKind::Pbr));
    d.two_sided = Some(m.double_sided());
    // A single-sided material's back faces are culled (glTF 2.0 §3.9.5), unless light goes
    // through it: a transmitting surface is met from behind by the light inside it.
    let translucent = m
        .extension_value("KHR_materials_diffuse_transmission")
        .is_some();
    if !m.double_sided() && m.transmission().is_none() && m.volume().is_none() && !translucent {
        d.cull_back = Some(true);
    }
    let pbr = m.pbr_metallic_roughness();
    let [br, bg, bb, alpha] = pbr.base_color_factor();
    let base_slot = pbr.base_color_texture().map(|i| Slot::of_info(&i));
    let base = r.scaled(
        Rgb::new(br, bg, bb),
        base_slot.clone(),
        "baseColorTexture",
        Encoding::Srgb,
        Channel::Rgb,
    )?;
    if base != TextureDesc::gray(1.0) {
        d.base_color = Some(base);
    }
    let mr = || pbr.metallic_roughness_texture().map(|i| Slot::of_info(&i));
    let metallic = r.scaled(
        Rgb::gray(pbr.metallic_factor().clamp(0.0, 1.0)),
        mr(),
        "metallicRoughnessTexture",
        Encoding::Linear,
        Channel::B,
    )?;
    d.metallic = unless_default(metallic, 1.0);
    let roughness = r.scaled(
        Rgb::gray(pbr.roughness_factor().clamp(0.0, 1.0)),
        mr(),
        "metallicRoughnessTexture",
        Encoding::Linear,
        Channel::G,
    )?;
    d.roughness = unless_default(roughness, 1.0);
    if let Some(n) = m.normal_texture() {
        let slot = Slot {
            texture: n.texture().index(),
            tex_coord: n.tex_coord(),
            scale: n.scale(),
            transform: n.extension_value("KHR_texture_transform").cloned(),
        };
        if let Some(t) = r.image(&slot, "normalTexture", Encoding::Linear, Channel::Rgb)? {
            d.normal_map = Some(spanned(t));
            if slot.scale != 1.0 && slot.scale.is_finite() {
                d.normal_scale = Some(spanned(Finite(slot.scale)));
            }
        }
    }
    let strength = m.emissive_strength().unwrap_or(1.0);
    let [er, eg, eb] = m.emissive_factor();
    let emission = r.scaled(
        Rgb::new(er, eg, eb) * strength,
        m.emissive_texture().map(|i| Slot::of_info(&i)),
        "emissiveTexture",
        Encoding::Srgb,
        Channel::Rgb,
    )?;
    if emission != TextureDesc::Solid(Rgb::BLACK) {
        d.emission = Some(emission);
    }
    alpha_mode(&mut r, m, alpha, base_slot, &mut d)?;
    if m.extension_value("KHR_materials_unlit").is_some() {
        return Ok((unlit(d, m.double_sided()), r.notes));
    }
    extensions(&mut r, m, &mut d)?;
    Ok((d, r.notes))
}

/// `KHR_materials_unlit`: the base colour (times the vertex colours) shown whatever the light,
/// as an emission that nothing else reflects, from both sides when the material is
/// double-sided. The lighting parameters of the rest of the material are dropped; its alpha
/// and culling are kept.
fn unlit(pbr: MaterialDesc, double_sided: bool) -> MaterialDesc {
    let mut d = MaterialDesc::named(pbr.name.get_ref());
    d.kind = Some(spanned(MaterialKind::Diffuse));
    d.reflectance = Some(TextureDesc::gray(0.0));
    let base = pbr.base_color.unwrap_or(TextureDesc::gray(1.0));
    d.emission = Some(TextureDesc::Product(
        Box::new(base),
        Box::new(TextureDesc::VertexColor),
    ));
    d.emits_back = double_sided.then_some(true);
    d.two_sided = pbr.two_sided;
    d.cull_back = pbr.cull_back;
    d.opacity = pbr.opacity;
    d
}

/// `MASK` and `BLEND`: the base colour's alpha (factor times texture) as the opacity.
fn alpha_mode(
    r: &mut Reader,
    m: &gltf::Material,
    alpha: f32,
    base: Option<Slot>,
    d: &mut MaterialDesc,
) -> Result<(), String> {
    let mode = m.alpha_mode();
    if mode == AlphaMode::Opaque {
        return Ok(());
    }
    // A texture without an alpha channel has an alpha of 1 (glTF 2.0 §3.9.2).
    let base = base.filter(|s| r.has_alpha(s));
    let coverage = r.scaled(
        Rgb::gray(alpha.clamp(0.0, 1.0)),
        base,
        "baseColorTexture's alpha",
        Encoding::Srgb,
        Channel::A,
    )?;
    let opacity = match mode {
        AlphaMode::Mask => {
            let cutoff = m.alpha_cutoff().unwrap_or(0.5);
            match coverage {
                TextureDesc::Solid(c) => TextureDesc::gray(if c.r >= cutoff { 1.0 } else { 0.0 }),
                t => TextureDesc::Step(Box::new(t), cutoff),
            }
        }
        _ => coverage,
    };
    if opacity != TextureDesc::gray(1.0) {
        d.opacity = Some(spanned(opacity));
    }
    Ok(())
}

impl Reader<'_, '_> {
    /// Whether the image of `slot` is a file with an alpha channel (its header read).
    fn has_alpha(&self, slot: &Slot) -> bool {
        let root = self.images.root;
        let Some(index) = root.textures.get(slot.texture).map(|t| t.source.value()) else {
            return false;
        };
        let Some(image) = root.images.get(index) else {
            return false;
        };
        fn header_has_alpha<R: std::io::BufRead + std::io::Seek>(
            r: std::io::Result<image::ImageReader<R>>,
        ) -> bool {
            r.and_then(|r| r.with_guessed_format())
                .ok()
                .and_then(|r| r.into_decoder().ok())
                .is_some_and(|dec| image::ImageDecoder::color_type(&dec).has_alpha())
        }
        match image.uri.as_deref() {
            Some(uri) if !uri.starts_with("data:") => {
                let Ok(file) = file_name_of_uri(uri) else {
                    return false;
                };
                let Ok(path) = resolve(self.images.base_dir, &file, self.images.options) else {
                    return false;
                };
                header_has_alpha(
                    crate::input::open(&path)
                        .map(|(file, _)| image::ImageReader::new(std::io::BufReader::new(file))),
                )
            }
            _ => self
                .images
                .asset
                .and_then(|a| a.embedded_image(index).ok())
                .is_some_and(|bytes| {
                    header_has_alpha(Ok(image::ImageReader::new(std::io::Cursor::new(bytes))))
                }),
        }
    }
}

/// The `KHR_materials_*` layers.
fn extensions(r: &mut Reader, m: &gltf::Material, d: &mut MaterialDesc) -> Result<(), String> {
    match m.ior() {
        None => {}
        Some(v) if v >= 1.0 && v.is_finite() => d.ior = Some(spanned(Finite(v))),
        Some(v) => r.note(format!(
            "ior {v} is not an index of refraction ≥ 1; 1.5 is used"
        )),
    }
    if let Some(s) = m.specular() {
        let t = r.scaled(
            Rgb::gray(s.specular_factor().clamp(0.0, 1.0)),
            s.specular_texture().map(|i| Slot::of_info(&i)),
            "specularTexture",
            Encoding::Linear,
            Channel::A,
        )?;
        if t != TextureDesc::gray(1.0) {
            d.specular = Some(t);
        }
        let c = r.scaled(
            Rgb::from(s.specular_color_factor()),
            s.specular_color_texture().map(|i| Slot::of_info(&i)),
            "specularColorTexture",
            Encoding::Srgb,
            Channel::Rgb,
        )?;
        if c != TextureDesc::gray(1.0) {
            d.specular_color = Some(c);
        }
    }
    if let Some(t) = m.transmission() {
        let tr = r.scaled(
            Rgb::gray(t.transmission_factor().clamp(0.0, 1.0)),
            t.transmission_texture().map(|i| Slot::of_info(&i)),
            "transmissionTexture",
            Encoding::Linear,
            Channel::R,
        )?;
        d.transmission = unless_default(tr, 0.0);
    }
    if let Some(v) = m.volume()
        && v.thickness_factor() > 0.0
    {
        d.volume = Some(true);
    }
    if let Some(c) = m.extension_value("KHR_materials_clearcoat") {
        d.clearcoat = r.unit_factor(c, "clearcoatFactor", "clearcoatTexture", Channel::R)?;
        d.clearcoat_roughness = r.unit_factor(
            c,
            "clearcoatRoughnessFactor",
            "clearcoatRoughnessTexture",
            Channel::G,
        )?;
        if let Some(slot) = Slot::of_json(c.get("clearcoatNormalTexture"))
            && d.clearcoat.is_some()
            && let Some(t) = r.image(
                &slot,
                "clearcoatNormalTexture",
                Encoding::Linear,
                Channel::Rgb,
            )?
        {
            d.clearcoat_normal_map = Some(spanned(t));
            if slot.scale != 1.0 && slot.scale.is_finite() {
                d.clearcoat_normal_scale = Some(spanned(Finite(slot.scale)));
            }
        }
    }
    if let Some(s) = m.extension_value("KHR_materials_sheen") {
        let color = r.scaled(
            color_of(s, "sheenColorFactor", Rgb::BLACK),
            Slot::of_json(s.get("sheenColorTexture")),
            "sheenColorTexture",
            Encoding::Srgb,
            Channel::Rgb,
        )?;
        if color != TextureDesc::Solid(Rgb::BLACK) {
            d.sheen_color = Some(color);
            d.sheen_roughness = r.unit_factor(
                s,
                "sheenRoughnessFactor",
                "sheenRoughnessTexture",
                Channel::A,
            )?;
        }
    }
    if let Some(a) = m.extension_value("KHR_materials_anisotropy") {
        let slot = Slot::of_json(a.get("anisotropyTexture"));
        let strength = r.scaled(
            Rgb::gray(number(a, "anisotropyStrength", 0.0).clamp(0.0, 1.0)),
            slot.clone(),
            "anisotropyTexture",
            Encoding::Linear,
            Channel::B,
        )?;
        d.anisotropy = unless_default(strength, 0.0);
        // Its red and green channels turn the direction, where there is anisotropy at all.
        if let Some(slot) = slot.filter(|_| d.anisotropy.is_some()) {
            d.anisotropy_direction = r
                .image(&slot, "anisotropyTexture", Encoding::Linear, Channel::Rgb)?
                .map(spanned);
        }
        let rotation = number(a, "anisotropyRotation", 0.0);
        if rotation != 0.0 && rotation.is_finite() {
            d.anisotropy_rotation = Some(spanned(Finite(rotation.to_degrees())));
        }
    }
    if let Some(i) = m.extension_value("KHR_materials_iridescence") {
        iridescence(r, i, d)?;
    }
    if let Some(t) = m.extension_value("KHR_materials_diffuse_transmission") {
        d.diffuse_transmission = r.unit_factor(
            t,
            "diffuseTransmissionFactor",
            "diffuseTransmissionTexture",
            Channel::A,
        )?;
        if d.diffuse_transmission.is_some() {
            let color = r.scaled(
                color_of(t, "diffuseTransmissionColorFactor", Rgb::WHITE),
                Slot::of_json(t.get("diffuseTransmissionColorTexture")),
                "diffuseTransmissionColorTexture",
                Encoding::Srgb,
                Channel::Rgb,
            )?;
            if color != TextureDesc::gray(1.0) {
                d.diffuse_transmission_color = Some(color);
            }
        }
    }
    for (ext, what) in [
        (
            "KHR_materials_pbrSpecularGlossiness",
            "a specular-glossiness material (its metallic-roughness fallback is used)",
        ),
        ("KHR_materials_dispersion", "dispersion"),
    ] {
        if m.extension_value(ext).is_some() {
            r.note(format!("{ext}: {what} is not rendered"));
        }
    }
    Ok(())
}

/// `KHR_materials_iridescence`: the film's weight, index and thickness (nanometres).
fn iridescence(r: &mut Reader, i: &Value, d: &mut MaterialDesc) -> Result<(), String> {
    d.iridescence = r.unit_factor(i, "iridescenceFactor", "iridescenceTexture", Channel::R)?;
    if d.iridescence.is_none() {
        return Ok(());
    }
    let ior = number(i, "iridescenceIor", 1.3);
    if !(1.0..=1e3).contains(&ior) {
        r.note(format!(
            "iridescenceIor {ior} is not an index of refraction from 1 to 1000; 1.3 is used"
        ));
    } else if ior != 1.3 {
        d.iridescence_ior = Some(spanned(Finite(ior)));
    }
    let mut thickness = |key: &str, default: f32| {
        let v = number(i, key, default);
        if (0.0..=f32::from(u16::MAX)).contains(&v) {
            v
        } else {
            let t = if v > 0.0 { f32::from(u16::MAX) } else { 0.0 };
            r.note(format!(
                "{key} {v} is not a thickness in [0, 65535] nm; {t} is used"
            ));
            t
        }
    };
    let (thinnest, thickest) = (
        thickness("iridescenceThicknessMinimum", 100.0),
        thickness("iridescenceThicknessMaximum", 400.0),
    );
    // Without a texture the film is the maximum thick (as it is where the texture cannot be
    // read, with a note).
    let map = match Slot::of_json(i.get("iridescenceThicknessTexture")) {
        Some(slot) if thinnest != thickest => r.image(
            &slot,
            "iridescenceThicknessTexture",
            Encoding::Linear,
            Channel::G,
        )?,
        _ => None,
    };
    let t = match map {
        Some(m) => TextureDesc::Mix(
            Box::new(TextureDesc::gray(thinnest)),
            Box::new(TextureDesc::gray(thickest)),
            Box::new(m),
        ),
        None => TextureDesc::gray(thickest),
    };
    d.iridescence_thickness = unless_default(t, 400.0);
    Ok(())
}
