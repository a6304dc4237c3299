//! The value types of scene files: numbers that must be finite, vectors and colours.
//!
//! Each checks itself while it is read, so a bad value is reported at its own line and column.

use glam::{DVec3, Vec3};
use lucent::Rgb;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// A finite number (integers are accepted); NaN and infinities are refused.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Finite(pub f32);

/// Three finite numbers `[x, y, z]`: a direction or a displacement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vector(pub Vec3);

/// A position `[x, y, z]`, kept in double precision: the build subtracts the scene's origin
/// (near the camera) before rounding to the renderer's single precision, so that a scene far
/// from the world's origin keeps its detail (see `docs/design.md`, "Far from the origin").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point(pub DVec3);

/// A linear RGB colour: one non-negative number for grey, or `[r, g, b]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Color(pub Rgb);

/// A scale: one number for all axes, or `[x, y, z]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale(pub Vec3);

/// A 4 × 4 affine transform: 16 finite numbers, row by row (the last row `[0, 0, 0, 1]`),
/// applied to column vectors: `p' = M·p`; in double precision, as [`Point`]s are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Matrix(pub glam::DMat4);

/// `v` if it is finite and within single precision's range (every value ends up there).
fn finite_wide<E: de::Error>(v: f64) -> Result<f64, E> {
    if (v as f32).is_finite() {
        Ok(v)
    } else if v.is_nan() {
        Err(E::custom("expected a finite number, found NaN"))
    } else {
        // A number beyond f32's range: shown in scientific notation, not with 300 digits.
        Err(E::custom(format!(
            "expected a finite number (at most about 3.4e38), found {v:e}"
        )))
    }
}

/// Reads a number or an array of exactly `N` numbers.
struct Numbers<const N: usize> {
    what: &'static str,
    scalar_ok: bool,
}

enum Read<const N: usize> {
    Scalar(f64),
    Array([f64; N]),
}

impl<'de, const N: usize> Visitor<'de> for Numbers<N> {
    type Value = Read<N>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.what)
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
        if !self.scalar_ok {
            return Err(E::invalid_type(de::Unexpected::Float(v), &self));
        }
        finite_wide(v).map(Read::Scalar)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
        if !self.scalar_ok {
            return Err(E::invalid_type(de::Unexpected::Signed(v), &self));
        }
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
        if !self.scalar_ok {
            return Err(E::invalid_type(de::Unexpected::Unsigned(v), &self));
        }
        self.visit_f64(v as f64)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut out = [0.0; N];
        for (i, slot) in out.iter_mut().enumerate() {
            let Some(Wide(v)) = seq.next_element()? else {
                return Err(de::Error::invalid_length(i, &self));
            };
            *slot = v;
        }
        let mut extra = 0;
        while seq.next_element::<de::IgnoredAny>()?.is_some() {
            extra += 1;
        }
        if extra > 0 {
            return Err(de::Error::invalid_length(N + extra, &self));
        }
        Ok(Read::Array(out))
    }
}

/// A finite number kept in double precision (an element of a [`Point`] or [`Matrix`]).
struct Wide(f64);

impl<'de> Deserialize<'de> for Wide {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FiniteVisitor).map(Wide)
    }
}

struct FiniteVisitor;

impl Visitor<'_> for FiniteVisitor {
    type Value = f64;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a finite number")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        finite_wide(v)
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        self.visit_f64(v as f64)
    }
}

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FiniteVisitor).map(|v| Finite(v as f32))
    }
}

/// Three finite numbers `[x, y, z]`, in double precision (for [`Vector`] and [`Point`]).
fn three<'de, D: Deserializer<'de>>(d: D) -> Result<DVec3, D::Error> {
    match d.deserialize_any(Numbers::<3> {
        what: "a vector [x, y, z] of finite numbers",
        scalar_ok: false,
    })? {
        Read::Array(v) => Ok(DVec3::from_array(v)),
        Read::Scalar(_) => unreachable!("the visitor refuses scalars"),
    }
}

impl<'de> Deserialize<'de> for Vector {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        three(d).map(|v| Vector(v.as_vec3()))
    }
}

impl Point {
    /// The point at single-precision `v`, each coordinate the shortest decimal that reads back
    /// as it (so that a converted scene says `0.8`, not `0.800000011920929`).
    pub fn from_single(v: Vec3) -> Self {
        Point(DVec3::from_array(v.to_array().map(shortest)))
    }
}

impl Matrix {
    /// The transform `m`, its entries as [`Point::from_single`] takes them.
    pub fn from_single(m: glam::Mat4) -> Self {
        Matrix(glam::DMat4::from_cols_array(
            &m.to_cols_array().map(shortest),
        ))
    }
}

impl<'de> Deserialize<'de> for Point {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        three(d).map(Point)
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = match d.deserialize_any(Numbers::<3> {
            what: "a scale: a number or [x, y, z]",
            scalar_ok: true,
        })? {
            Read::Scalar(s) => Vec3::splat(s as f32),
            Read::Array(v) => DVec3::from_array(v).as_vec3(),
        };
        if v.cmpeq(Vec3::ZERO).any() {
            return Err(de::Error::custom("a scale of zero flattens the object"));
        }
        Ok(Scale(v))
    }
}

impl<'de> Deserialize<'de> for Color {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let what = "a colour: a number or [r, g, b]";
        let rgb = match d.deserialize_any(Numbers::<3> {
            what,
            scalar_ok: true,
        })? {
            Read::Scalar(v) => Rgb::gray(v as f32),
            Read::Array(v) => Rgb::from(v.map(|c| c as f32)),
        };
        if rgb.r < 0.0 || rgb.g < 0.0 || rgb.b < 0.0 {
            return Err(de::Error::custom("colours must not be negative"));
        }
        if rgb.max_channel() > lucent::texture::MAX_VALUE {
            return Err(de::Error::custom(format!(
                "colour components must be at most {:e}",
                lucent::texture::MAX_VALUE
            )));
        }
        Ok(Color(rgb))
    }
}

impl<'de> Deserialize<'de> for Matrix {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let rows = match d.deserialize_any(Numbers::<16> {
            what: "a matrix: 16 finite numbers, row by row",
            scalar_ok: false,
        })? {
            Read::Array(v) => v,
            Read::Scalar(_) => unreachable!("the visitor refuses scalars"),
        };
        if rows[12..] != [0.0, 0.0, 0.0, 1.0] {
            return Err(de::Error::custom(
                "a transform's last row must be [0, 0, 0, 1] (no projection)",
            ));
        }
        let m = glam::DMat4::from_cols_array(&rows).transpose();
        // Judged as the renderer will hold it (its linear part; the translation is rebased).
        let det = m.as_mat4().determinant();
        if det == 0.0 || !det.is_finite() {
            return Err(de::Error::custom(
                "the transform is singular (it flattens the object), or so large that its determinant overflows",
            ));
        }
        Ok(Matrix(m))
    }
}

/// A number written with the fewest digits that read back as the same `f32` (`0.8`, not
/// `0.800000011920929`).
fn shortest(v: f32) -> f64 {
    format!("{v}").parse().unwrap_or(f64::from(v))
}

impl Serialize for Finite {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(shortest(self.0))
    }
}

impl Serialize for Vector {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.to_array().map(shortest).serialize(s)
    }
}

impl Serialize for Point {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.to_array().serialize(s)
    }
}

impl Serialize for Scale {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0.x == self.0.y && self.0.y == self.0.z {
            s.serialize_f64(shortest(self.0.x))
        } else {
            self.0.to_array().map(shortest).serialize(s)
        }
    }
}

impl Serialize for Color {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let Rgb { r, g, b } = self.0;
        if r == g && g == b {
            s.serialize_f64(shortest(r))
        } else {
            [r, g, b].map(shortest).serialize(s)
        }
    }
}

impl Serialize for Matrix {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.transpose().to_cols_array().serialize(s)
    }
}
