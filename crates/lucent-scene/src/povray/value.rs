//! The values POV-Ray's language computes with: numbers, vectors and colours, strings, arrays,
//! and the scene's pieces (objects, textures, lights, cameras, transforms) that identifiers may
//! name.

use super::lexer::{Loc, Token};
use super::scene::{Camera, Light, Object};
use super::texture::{ColorMap, Finish, Interior, Pigment, Texture};
use glam::DAffine3;
use std::cell::RefCell;
use std::rc::Rc;

/// A vector of 2 to 5 components; colours are 5 (red, green, blue, filter, transmit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vect {
    /// The components; those past `n` are 0.
    pub c: [f64; 5],
    /// How many there are.
    pub n: usize,
}

impl Vect {
    /// A vector of `n` components all `v`.
    pub fn splat(v: f64, n: usize) -> Self {
        let mut c = [0.0; 5];
        c[..n].fill(v);
        Self { c, n }
    }

    /// A 3-vector.
    pub fn xyz(x: f64, y: f64, z: f64) -> Self {
        Self {
            c: [x, y, z, 0.0, 0.0],
            n: 3,
        }
    }

    /// Its first three components.
    pub fn v3(&self) -> glam::DVec3 {
        glam::DVec3::new(self.c[0], self.c[1], self.c[2])
    }
}

/// A macro: where its body is and what its parameters are called.
#[derive(Debug)]
pub struct Macro {
    /// The parameters' names, in order.
    pub params: Vec<Rc<str>>,
    /// The tokens of the file it is in.
    pub tokens: Rc<Vec<Token>>,
    /// The first token of its body, and the `#end` after it.
    pub body: (usize, usize),
    /// Where it was declared.
    pub loc: Loc,
}

/// A value an identifier can hold.
#[derive(Clone, Debug)]
pub enum Value {
    /// A number (also a boolean: 0 is false).
    Float(f64),
    /// A vector or a colour.
    Vector(Vect),
    /// A string.
    Str(Rc<str>),
    /// An array (elements may be unset); shared, as POV-Ray's are, so that an element can be
    /// assigned.
    Array(Rc<RefCell<Array>>),
    /// A shape or a combination.
    Object(Rc<Object>),
    /// A texture.
    Texture(Rc<Texture>),
    /// A pigment.
    Pigment(Rc<Pigment>),
    /// A finish.
    Finish(Rc<Finish>),
    /// A normal perturbation.
    Normal(Rc<super::normal::Normal>),
    /// An interior.
    Interior(Rc<Interior>),
    /// A colour map.
    ColorMap(Rc<ColorMap>),
    /// A camera.
    Camera(Rc<Camera>),
    /// A light source.
    Light(Rc<Light>),
    /// A transform.
    Transform(DAffine3),
    /// A macro.
    Macro(Rc<Macro>),
    /// Something read but not modelled (a function, a spline, a media): what it is and where.
    Unread(Rc<str>, Loc),
}

/// An array's elements and its sizes (one per dimension).
#[derive(Clone, Debug)]
pub struct Array {
    /// The size of each dimension.
    pub dims: Vec<usize>,
    /// The elements, row-major; `None` until assigned.
    pub items: Vec<Option<Value>>,
}

impl Value {
    /// What kind of value it is, for error messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Float(_) => "a number",
            Value::Vector(_) => "a vector",
            Value::Str(_) => "a string",
            Value::Array(_) => "an array",
            Value::Object(_) => "an object",
            Value::Texture(_) => "a texture",
            Value::Pigment(_) => "a pigment",
            Value::Finish(_) => "a finish",
            Value::Normal(_) => "a normal",
            Value::Interior(_) => "an interior",
            Value::ColorMap(_) => "a colour map",
            Value::Camera(_) => "a camera",
            Value::Light(_) => "a light source",
            Value::Transform(_) => "a transform",
            Value::Macro(_) => "a macro",
            Value::Unread(..) => "something lucent does not read",
        }
    }
}
