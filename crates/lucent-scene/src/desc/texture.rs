//! Textures in scene files: any material parameter that varies over a surface.
//!
//! A texture is written where its value would be:
//!
//! ```toml
//! reflectance = 0.5                                   # a number: grey
//! reflectance = [0.8, 0.2, 0.1]                       # a colour
//! reflectance = { image = "wood.jpg", scale = [4, 4] } # an image (see below)
//! reflectance = { checker = { even = 1, odd = 0.1, size = 0.5 } }   # a 3D checkerboard
//! reflectance = { checkerboard = { even = 0.4, odd = 0.2 }, scale = [8, 8] }  # over uv
//! reflectance = { vertex_color = true }               # the mesh's vertex colours
//! reflectance = { product = [{ vertex_color = true }, 0.8] }
//! roughness = { mix = [0.1, 0.6], amount = { image = "mask.png" } }
//! opacity = { step = { image = "leaf.png", channel = "a" }, cutoff = 0.5 }   # 1 from 0.5 on
//! ```
//!
//! An image takes `encoding` (`"srgb"` or `"linear"`; by default 8- and 16-bit files are sRGB
//! where the parameter is a colour and linear where it is a number or a normal map; float files
//! are always linear), `channel` (`"r"`, `"g"`, `"b"`, `"a"` or `"rgb"`), `wrap` (`"repeat"`,
//! `"mirror"`, `"clamp"`, or one per axis `["repeat", "clamp"]`), `filter` (`"nearest"`,
//! `"bilinear"`, `"trilinear"` — MIP-mapped, `"anisotropic"` — MIP-mapped with up to 8 lookups
//! along a stretched footprint, the default) and a placement of its texture
//! coordinates, `uv' = offset + R(rotation)·(scale ∘ uv)` (`scale`, `offset` as `[u, v]`,
//! `rotation` in degrees). A uv checkerboard takes the same placement. `gltf_image = N` reads
//! image `N` held inside the glTF or GLB file `image` names (a buffer view or a `data:` URI).

use super::{Color, Finite};
use lucent::Rgb;
use lucent::texture::{Channel, Checker, Filter, Wrap};
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// How an image file's 8- and 16-bit values become linear numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Encoding {
    /// The sRGB transfer curve (colour images).
    Srgb,
    /// Taken as they are, scaled to `[0, 1]` (data: roughness, normals, heights).
    Linear,
}

/// Where texture coordinates are moved before a lookup: `uv' = offset + R(rotation)·(scale ∘ uv)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Placement {
    /// `[u, v]` factors (default 1).
    pub scale: Option<[f32; 2]>,
    /// `[u, v]` offset (default 0).
    pub offset: Option<[f32; 2]>,
    /// Degrees from +u towards +v (default 0).
    pub rotation: Option<f32>,
}

impl Placement {
    /// The transform.
    pub fn transform(&self) -> lucent::texture::UvTransform {
        let s = self.scale.unwrap_or([1.0, 1.0]);
        let o = self.offset.unwrap_or([0.0, 0.0]);
        lucent::texture::UvTransform::new(
            glam::Vec2::from(s),
            self.rotation.unwrap_or(0.0).to_radians(),
            glam::Vec2::from(o),
        )
    }

    fn is_default(&self) -> bool {
        *self == Placement::default()
    }
}

/// An image file looked up by texture coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageMapDesc {
    /// The file, relative to the scene file's folder.
    pub file: String,
    /// `None`: by the parameter (sRGB for colours, linear for data).
    pub encoding: Option<Encoding>,
    /// The channels read (default: all).
    pub channel: Option<Channel>,
    /// Along u and v (default repeat).
    pub wrap: Option<[Wrap; 2]>,
    /// Interpolation (default anisotropic).
    pub filter: Option<Filter>,
    /// Placement of the coordinates.
    pub placement: Placement,
    /// The index of an image held inside `file`, a glTF or GLB file (in a buffer view or a
    /// `data:` URI), rather than `file` itself.
    pub gltf_image: Option<u32>,
}

impl ImageMapDesc {
    /// An image with every setting at its default.
    pub fn new(file: impl Into<String>) -> Self {
        Self {
            file: file.into(),
            encoding: None,
            channel: None,
            wrap: None,
            filter: None,
            placement: Placement::default(),
            gltf_image: None,
        }
    }
}

/// A value over a surface, as a file gives it (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum TextureDesc {
    /// One value: a number (grey) or a colour.
    Solid(Rgb),
    /// A 3D checkerboard.
    Checker(Checker),
    /// A solid pattern of POV-Ray's (read from `.pov` files; it has no TOML form yet).
    Pattern(Box<lucent::texture::Pattern>),
    /// A checkerboard over texture coordinates (period 1 after the placement).
    Checkerboard {
        /// Where `u` and `v` fall in the same half of the unit.
        even: Rgb,
        /// Elsewhere.
        odd: Rgb,
        /// Placement of the coordinates.
        placement: Placement,
    },
    /// An image.
    Image(ImageMapDesc),
    /// The mesh's vertex colours (white elsewhere).
    VertexColor,
    /// The product of two textures.
    Product(Box<TextureDesc>, Box<TextureDesc>),
    /// `a·(1 − amount) + b·amount`.
    Mix(Box<TextureDesc>, Box<TextureDesc>, Box<TextureDesc>),
    /// 1 where the texture reaches the cutoff, 0 below (glTF's alpha `MASK`).
    Step(Box<TextureDesc>, f32),
}

impl TextureDesc {
    /// A grey value.
    pub fn gray(v: f32) -> Self {
        TextureDesc::Solid(Rgb::gray(v))
    }

    /// The image files it names, mutably (for rebasing paths).
    pub fn files_mut(&mut self, f: &mut impl FnMut(&mut String)) {
        match self {
            TextureDesc::Image(i) => f(&mut i.file),
            TextureDesc::Product(a, b) => {
                a.files_mut(f);
                b.files_mut(f);
            }
            TextureDesc::Mix(a, b, t) => {
                a.files_mut(f);
                b.files_mut(f);
                t.files_mut(f);
            }
            TextureDesc::Step(t, _) => t.files_mut(f),
            _ => {}
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckerDesc {
    even: Color,
    odd: Color,
    size: Finite,
    /// In world coordinates on planes too (POV-Ray's checker), not the plane's own frame.
    #[serde(default)]
    world: bool,
    /// The world placed in the checker's space (implies `world`).
    #[serde(default)]
    transform: Option<super::Matrix>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckerboardDesc {
    even: Color,
    odd: Color,
}

/// A wrap mode, or one per axis: `"clamp"` or `["repeat", "clamp"]`.
struct WrapDesc([Wrap; 2]);

const WRAPS: [(&str, Wrap); 3] = [
    ("repeat", Wrap::Repeat),
    ("mirror", Wrap::Mirror),
    ("clamp", Wrap::Clamp),
];

struct WrapVisitor;

impl<'de> Visitor<'de> for WrapVisitor {
    type Value = WrapDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a wrap mode (\"repeat\", \"mirror\", \"clamp\") or one per axis [u, v]")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<WrapDesc, E> {
        Ok(WrapDesc([parse_name("wrap mode", v, &WRAPS)?; 2]))
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<WrapDesc, A::Error> {
        let mut out = [Wrap::Repeat; 2];
        for (i, slot) in out.iter_mut().enumerate() {
            let Some(name) = seq.next_element::<String>()? else {
                return Err(de::Error::invalid_length(i, &self));
            };
            *slot = parse_name("wrap mode", &name, &WRAPS)?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(3, &self));
        }
        Ok(WrapDesc(out))
    }
}

impl<'de> Deserialize<'de> for WrapDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(WrapVisitor)
    }
}

fn wrap_name(w: Wrap) -> &'static str {
    match w {
        Wrap::Repeat => "repeat",
        Wrap::Mirror => "mirror",
        Wrap::Clamp => "clamp",
    }
}

fn filter_name(f: Filter) -> &'static str {
    match f {
        Filter::Nearest => "nearest",
        Filter::Bilinear => "bilinear",
        Filter::Trilinear => "trilinear",
        Filter::Anisotropic => "anisotropic",
    }
}

fn channel_name(c: Channel) -> &'static str {
    match c {
        Channel::Rgb => "rgb",
        Channel::R => "r",
        Channel::G => "g",
        Channel::B => "b",
        Channel::A => "a",
    }
}

fn parse_name<T: Copy, E: de::Error>(
    what: &str,
    name: &str,
    table: &[(&'static str, T)],
) -> Result<T, E> {
    table
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let known: Vec<_> = table.iter().map(|(n, _)| format!("`{n}`")).collect();
            E::custom(format!(
                "unknown {what} `{name}` (known: {})",
                known.join(", ")
            ))
        })
}

const KINDS: &[&str] = &[
    "image",
    "checker",
    "checkerboard",
    "vertex_color",
    "product",
    "mix",
    "step",
];

struct TextureVisitor;

impl<'de> Visitor<'de> for TextureVisitor {
    type Value = TextureDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, a colour [r, g, b], or a texture table such as { image = \"file\" }")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<TextureDesc, E> {
        let Color(c) = Color::deserialize(de::value::F64Deserializer::new(v))?;
        Ok(TextureDesc::Solid(c))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<TextureDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<TextureDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, seq: A) -> Result<TextureDesc, A::Error> {
        let Color(c) = Color::deserialize(de::value::SeqAccessDeserializer::new(seq))?;
        Ok(TextureDesc::Solid(c))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TextureDesc, A::Error> {
        let mut kind: Option<&'static str> = None;
        let mut file = None;
        let mut checker = None;
        let mut checkerboard = None;
        let mut pair: Option<Vec<TextureDesc>> = None;
        let mut amount = None;
        let mut stepped: Option<TextureDesc> = None;
        let mut cutoff: Option<f32> = None;
        let mut image = ImageMapDesc::new("");
        let mut placement = Placement::default();
        let mut set_kind = |k: &'static str| -> Result<(), A::Error> {
            match kind {
                Some(other) => Err(de::Error::custom(format!(
                    "a texture has one kind; `{k}` after `{other}`"
                ))),
                None => {
                    kind = Some(k);
                    Ok(())
                }
            }
        };
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "image" => {
                    set_kind("image")?;
                    let f: String = map.next_value()?;
                    if f.is_empty() {
                        return Err(de::Error::custom("the image's file name is empty"));
                    }
                    file = Some(f);
                }
                "checker" => {
                    set_kind("checker")?;
                    let c: CheckerDesc = map.next_value()?;
                    if c.size.0 <= 0.0 {
                        return Err(de::Error::custom(format!(
                            "the checker size must be positive, got {}",
                            c.size.0
                        )));
                    }
                    checker = Some(c);
                }
                "checkerboard" => {
                    set_kind("checkerboard")?;
                    checkerboard = Some(map.next_value::<CheckerboardDesc>()?);
                }
                "vertex_color" => {
                    set_kind("vertex_color")?;
                    if !map.next_value::<bool>()? {
                        return Err(de::Error::custom(
                            "`vertex_color = false` is not a texture; leave it out",
                        ));
                    }
                }
                "product" | "mix" => {
                    set_kind(if key == "product" { "product" } else { "mix" })?;
                    let v: Vec<TextureDesc> = map.next_value()?;
                    if v.len() != 2 {
                        return Err(de::Error::custom(format!(
                            "`{key}` takes two textures, got {}",
                            v.len()
                        )));
                    }
                    pair = Some(v);
                }
                "amount" => amount = Some(map.next_value::<TextureDesc>()?),
                "step" => {
                    set_kind("step")?;
                    stepped = Some(map.next_value::<TextureDesc>()?);
                }
                "cutoff" => cutoff = Some(map.next_value::<Finite>()?.0),
                "encoding" => image.encoding = Some(map.next_value()?),
                "channel" => {
                    let name: String = map.next_value()?;
                    let table = [
                        ("rgb", Channel::Rgb),
                        ("r", Channel::R),
                        ("g", Channel::G),
                        ("b", Channel::B),
                        ("a", Channel::A),
                    ];
                    image.channel = Some(parse_name("channel", &name, &table)?);
                }
                "wrap" => image.wrap = Some(map.next_value::<WrapDesc>()?.0),
                "filter" => {
                    let name: String = map.next_value()?;
                    let table = [
                        ("nearest", Filter::Nearest),
                        ("bilinear", Filter::Bilinear),
                        ("trilinear", Filter::Trilinear),
                        ("anisotropic", Filter::Anisotropic),
                    ];
                    image.filter = Some(parse_name("filter", &name, &table)?);
                }
                "scale" => {
                    let [u, v]: [Finite; 2] = map.next_value()?;
                    placement.scale = Some([u.0, v.0]);
                }
                "offset" => {
                    let [u, v]: [Finite; 2] = map.next_value()?;
                    placement.offset = Some([u.0, v.0]);
                }
                "rotation" => placement.rotation = Some(map.next_value::<Finite>()?.0),
                "gltf_image" => image.gltf_image = Some(map.next_value()?),
                other => {
                    return Err(de::Error::custom(format!(
                        "unknown texture key `{other}` (kinds: {}; an image also takes encoding, channel, wrap, filter, scale, offset, rotation, gltf_image)",
                        KINDS.join(", ")
                    )));
                }
            }
        }
        let Some(kind) = kind else {
            return Err(de::Error::custom(format!(
                "a texture table needs its kind: one of {}",
                KINDS.join(", ")
            )));
        };
        let image_only = image.encoding.is_some()
            || image.channel.is_some()
            || image.wrap.is_some()
            || image.filter.is_some()
            || image.gltf_image.is_some();
        let placed = !placement.is_default();
        if image_only && kind != "image" {
            return Err(de::Error::custom(format!(
                "encoding, channel, wrap, filter and gltf_image are an image's keys, not a {kind}'s"
            )));
        }
        if placed && !matches!(kind, "image" | "checkerboard") {
            return Err(de::Error::custom(format!(
                "scale, offset and rotation place an image or a checkerboard, not a {kind}"
            )));
        }
        if amount.is_some() != (kind == "mix") {
            return Err(de::Error::custom(
                "`amount` goes with `mix` (and a mix needs it)",
            ));
        }
        if cutoff.is_some() != (kind == "step") {
            return Err(de::Error::custom(
                "`cutoff` goes with `step` (and a step needs it)",
            ));
        }
        Ok(match kind {
            "step" => TextureDesc::Step(
                Box::new(stepped.expect("the kind was set with its value")),
                cutoff.expect("checked above"),
            ),
            "image" => {
                image.file = file.unwrap_or_default();
                image.placement = placement;
                TextureDesc::Image(image)
            }
            "checker" => {
                let c = checker.expect("the kind was set with its value");
                TextureDesc::Checker(Checker {
                    even: c.even.0,
                    odd: c.odd.0,
                    size: c.size.0,
                    world: match c.transform {
                        Some(m) => Some(glam::Affine3A::from_mat4(m.0.as_mat4())),
                        None => c.world.then_some(glam::Affine3A::IDENTITY),
                    },
                })
            }
            "checkerboard" => {
                let c = checkerboard.expect("the kind was set with its value");
                TextureDesc::Checkerboard {
                    even: c.even.0,
                    odd: c.odd.0,
                    placement,
                }
            }
            "vertex_color" => TextureDesc::VertexColor,
            _ => {
                let mut v = pair.expect("the kind was set with its value");
                let b = Box::new(v.pop().expect("two"));
                let a = Box::new(v.pop().expect("two"));
                match amount {
                    Some(t) => TextureDesc::Mix(a, b, Box::new(t)),
                    None => TextureDesc::Product(a, b),
                }
            }
        })
    }
}

impl<'de> Deserialize<'de> for TextureDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(TextureVisitor)
    }
}

#[derive(Serialize)]
struct CheckerOut {
    even: Color,
    odd: Color,
    size: Finite,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    world: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    transform: Option<super::Matrix>,
}

#[derive(Serialize)]
struct CheckerboardOut {
    even: Color,
    odd: Color,
}

fn placement_entries<M: SerializeMap>(m: &mut M, p: &Placement) -> Result<(), M::Error> {
    if let Some([u, v]) = p.scale {
        m.serialize_entry("scale", &[Finite(u), Finite(v)])?;
    }
    if let Some([u, v]) = p.offset {
        m.serialize_entry("offset", &[Finite(u), Finite(v)])?;
    }
    if let Some(r) = p.rotation {
        m.serialize_entry("rotation", &Finite(r))?;
    }
    Ok(())
}

impl Serialize for TextureDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            TextureDesc::Solid(c) => Color(*c).serialize(s),
            TextureDesc::Pattern(p) => Err(serde::ser::Error::custom(format!(
                "a POV-Ray `{:?}` pattern has no TOML form yet",
                p.kind
            ))),
            TextureDesc::Checker(c) => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry(
                    "checker",
                    &CheckerOut {
                        even: Color(c.even),
                        odd: Color(c.odd),
                        size: Finite(c.size),
                        world: c.world == Some(glam::Affine3A::IDENTITY),
                        transform: c
                            .world
                            .filter(|m| *m != glam::Affine3A::IDENTITY)
                            .map(|m| super::Matrix(glam::Mat4::from(m).as_dmat4())),
                    },
                )?;
                m.end()
            }
            TextureDesc::Checkerboard {
                even,
                odd,
                placement,
            } => {
                let mut m = s.serialize_map(None)?;
                m.serialize_entry(
                    "checkerboard",
                    &CheckerboardOut {
                        even: Color(*even),
                        odd: Color(*odd),
                    },
                )?;
                placement_entries(&mut m, placement)?;
                m.end()
            }
            TextureDesc::Image(i) => {
                let mut m = s.serialize_map(None)?;
                m.serialize_entry("image", &i.file)?;
                if let Some(index) = i.gltf_image {
                    m.serialize_entry("gltf_image", &index)?;
                }
                if let Some(e) = i.encoding {
                    m.serialize_entry("encoding", &e)?;
                }
                if let Some(c) = i.channel {
                    m.serialize_entry("channel", channel_name(c))?;
                }
                if let Some([u, v]) = i.wrap {
                    if u == v {
                        m.serialize_entry("wrap", wrap_name(u))?;
                    } else {
                        m.serialize_entry("wrap", &[wrap_name(u), wrap_name(v)])?;
                    }
                }
                if let Some(f) = i.filter {
                    m.serialize_entry("filter", filter_name(f))?;
                }
                placement_entries(&mut m, &i.placement)?;
                m.end()
            }
            TextureDesc::VertexColor => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry("vertex_color", &true)?;
                m.end()
            }
            TextureDesc::Product(a, b) => {
                let mut m = s.serialize_map(Some(1))?;
                m.serialize_entry("product", &[a.as_ref(), b.as_ref()])?;
                m.end()
            }
            TextureDesc::Mix(a, b, t) => {
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry("mix", &[a.as_ref(), b.as_ref()])?;
                m.serialize_entry("amount", t.as_ref())?;
                m.end()
            }
            TextureDesc::Step(t, cutoff) => {
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry("step", t.as_ref())?;
                m.serialize_entry("cutoff", &Finite(*cutoff))?;
                m.end()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize)]
    struct T {
        t: TextureDesc,
    }

    fn parse(text: &str) -> Result<TextureDesc, String> {
        toml::from_str::<T>(text)
            .map(|t| t.t)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn every_kind_reads_and_writes_back() {
        for text in [
            "t = 0.5",
            "t = [0.1, 0.2, 0.3]",
            "t = { image = \"m.glb\", gltf_image = 3, channel = \"b\" }",
            "t = { image = \"a.png\", encoding = \"linear\", channel = \"g\", wrap = [\"clamp\", \"mirror\"], filter = \"nearest\", scale = [4, 2], offset = [0.5, 0], rotation = 30 }",
            "t = { checker = { even = 1, odd = 0, size = 2 } }",
            "t = { checkerboard = { even = 0.4, odd = 0.2 }, scale = [8, 8] }",
            "t = { vertex_color = true }",
            "t = { product = [{ vertex_color = true }, 0.8] }",
            "t = { mix = [0.1, { image = \"m.png\" }], amount = 0.25 }",
        ] {
            let t = parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
            let back = toml::to_string(&T { t: t.clone() }).unwrap();
            assert_eq!(parse(&back).unwrap(), t, "{text} → {back}");
        }
        let TextureDesc::Image(i) =
            parse("t = { image = \"a.png\", wrap = \"clamp\", channel = \"a\" }").unwrap()
        else {
            panic!("an image");
        };
        assert_eq!(i.wrap, Some([Wrap::Clamp; 2]));
        assert_eq!(i.channel, Some(Channel::A));
    }

    #[test]
    fn mistakes_are_named() {
        for (text, says) in [
            ("t = {}", "needs its kind"),
            (
                "t = { image = \"a.png\", checker = { even = 1, odd = 0, size = 1 } }",
                "one kind",
            ),
            (
                "t = { image = \"a.png\", colour = 1 }",
                "unknown texture key `colour`",
            ),
            (
                "t = { image = \"a.png\", wrap = \"tile\" }",
                "unknown wrap mode `tile`",
            ),
            (
                "t = { image = \"a.png\", filter = \"ewa\" }",
                "unknown filter `ewa`",
            ),
            (
                "t = { checker = { even = 1, odd = 0, size = 1 }, filter = \"nearest\" }",
                "an image's keys",
            ),
            (
                "t = { vertex_color = true, scale = [2, 2] }",
                "place an image",
            ),
            ("t = { mix = [0, 1] }", "amount"),
            ("t = { product = [0, 1, 2] }", "two textures"),
            ("t = { image = \"\" }", "empty"),
            ("t = -1", "negative"),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
