//! `[[material]]` tables.

use super::{Color, Finite};
use lucent::Rgb;
use lucent::texture::{Checker, Texture};
use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use std::fmt;
use toml::Spanned;

/// One `[[material]]`; a missing coefficient is 0, a missing `ior` is 1.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// The name objects refer to it by; unique.
    pub name: Spanned<String>,
    /// Ambient coefficient.
    #[serde(default)]
    pub ka: Option<Color>,
    /// Diffuse coefficient: a colour or a checkerboard.
    #[serde(default)]
    pub kd: Option<DiffuseDesc>,
    /// Specular coefficient.
    #[serde(default)]
    pub ks: Option<Color>,
    /// Phong exponent, ≥ 0.
    #[serde(default)]
    pub shininess: Option<Spanned<Finite>>,
    /// Mirror reflection coefficient.
    #[serde(default)]
    pub kr: Option<Color>,
    /// Transmission coefficient.
    #[serde(default)]
    pub kt: Option<Color>,
    /// Index of refraction, > 0.
    #[serde(default)]
    pub ior: Option<Spanned<Finite>>,
}

/// `kd`: a colour, or `{ checker = { even = C, odd = C, size = S } }`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiffuseDesc(pub Texture);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckerDesc {
    even: Color,
    odd: Color,
    size: Finite,
}

struct DiffuseVisitor;

impl<'de> Visitor<'de> for DiffuseVisitor {
    type Value = DiffuseDesc;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a colour (a number or [r, g, b]) or { checker = { even, odd, size } }")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<DiffuseDesc, E> {
        let Color(c) = Color::deserialize(de::value::F64Deserializer::new(v))?;
        Ok(DiffuseDesc(Texture::Solid(c)))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<DiffuseDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<DiffuseDesc, E> {
        self.visit_f64(v as f64)
    }

    fn visit_seq<A: de::SeqAccess<'de>>(self, seq: A) -> Result<DiffuseDesc, A::Error> {
        let Color(c) = Color::deserialize(de::value::SeqAccessDeserializer::new(seq))?;
        Ok(DiffuseDesc(Texture::Solid(c)))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<DiffuseDesc, A::Error> {
        let Some(key) = map.next_key::<String>()? else {
            return Err(de::Error::custom(
                "an empty table is not a texture; expected { checker = ... }",
            ));
        };
        if key != "checker" {
            return Err(de::Error::unknown_field(&key, &["checker"]));
        }
        let c: CheckerDesc = map.next_value()?;
        if c.size.0 <= 0.0 {
            return Err(de::Error::custom(format!(
                "the checker size must be positive, got {}",
                c.size.0
            )));
        }
        if let Some(extra) = map.next_key::<String>()? {
            return Err(de::Error::custom(format!(
                "a texture has one kind; unexpected `{extra}` after `checker`"
            )));
        }
        Ok(DiffuseDesc(Texture::Checker(Checker {
            even: c.even.0,
            odd: c.odd.0,
            size: c.size.0,
        })))
    }
}

impl<'de> Deserialize<'de> for DiffuseDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(DiffuseVisitor)
    }
}

impl MaterialDesc {
    /// A material with only a name, every coefficient missing.
    pub fn named(name: &str) -> Self {
        Self {
            name: Spanned::new(0..0, name.to_string()),
            ka: None,
            kd: None,
            ks: None,
            shininess: None,
            kr: None,
            kt: None,
            ior: None,
        }
    }

    /// The renderer's material: missing coefficients 0, missing ior 1 (ranges checked in build).
    pub fn to_material(&self) -> lucent::material::Material {
        let c = |o: Option<Color>| o.map_or(Rgb::BLACK, |c| c.0);
        lucent::material::Material {
            ka: c(self.ka),
            kd: self.kd.map_or(Texture::Solid(Rgb::BLACK), |d| d.0),
            ks: c(self.ks),
            shininess: self.shininess.as_ref().map_or(0.0, |s| s.get_ref().0),
            kr: c(self.kr),
            kt: c(self.kt),
            ior: self.ior.as_ref().map_or(1.0, |s| s.get_ref().0),
        }
    }
}
