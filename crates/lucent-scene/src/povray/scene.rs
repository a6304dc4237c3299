//! The scene's statements: camera, lights, objects and their modifiers, transforms,
//! `background`, `sky_sphere`, `global_settings` and `#default`; and what `#declare` may hold.

use super::functions::rotation;
use super::lexer::{Loc, Tok, Token};
use super::parser::Parser;
use super::texture::{Finish, Interior, Pigment, Texture};
use super::value::{Value, Vect};
use crate::error::LoadError;
use glam::{DAffine3, DMat3, DVec3};
use lucent::shape::solid::algebraic;
use std::rc::Rc;

/// A camera as written (POV-Ray's space); see `convert` for how its vectors combine.
#[derive(Clone, Debug)]
pub struct Camera {
    /// `perspective` or `orthographic`.
    pub orthographic: bool,
    /// `location`.
    pub location: DVec3,
    /// `direction`.
    pub direction: DVec3,
    /// `right`.
    pub right: DVec3,
    /// `up`.
    pub up: DVec3,
    /// `sky`.
    pub sky: DVec3,
    /// `angle`, degrees (horizontal).
    pub angle: Option<f64>,
    /// `look_at`.
    pub look_at: Option<DVec3>,
    /// Whether `right` or `up` was given (an orthographic view's size).
    pub sized: bool,
    /// Transforms applied after.
    pub transform: DAffine3,
    /// Where it was written.
    pub loc: Loc,
}

/// A light source (POV-Ray's space).
#[derive(Clone, Debug)]
pub struct Light {
    /// Where it is.
    pub position: DVec3,
    /// Its colour.
    pub color: DVec3,
    /// `spotlight`, `parallel` or a point.
    pub kind: LightKind,
    /// `point_at`.
    pub point_at: DVec3,
    /// `radius`, `falloff` (degrees), `tightness`.
    pub spot: (f64, f64, f64),
    /// `fade_distance`, `fade_power`.
    pub fade: Option<(f64, f64)>,
    /// `area_light`: its axes and samples.
    pub area: Option<(DVec3, DVec3, u32, u32)>,
    /// `shadowless`.
    pub shadowless: bool,
    /// Where it was written.
    pub loc: Loc,
}

impl Light {
    /// A point light of POV-Ray's defaults (a spotlight's angles 30° and 45°, tightness 0).
    pub fn point(position: DVec3, color: DVec3, loc: &Loc) -> Self {
        Self {
            position,
            color,
            kind: LightKind::Point,
            point_at: DVec3::Z,
            spot: (30.0, 45.0, 0.0),
            fade: None,
            area: None,
            shadowless: false,
            loc: loc.clone(),
        }
    }
}

impl Camera {
    /// POV-Ray's default camera (the right vector exactly 1.33 long, as POV-Ray's is).
    pub fn default_at(loc: &Loc) -> Self {
        Self {
            orthographic: false,
            location: DVec3::ZERO,
            direction: DVec3::Z,
            right: DVec3::new(1.33, 0.0, 0.0),
            up: DVec3::Y,
            sky: DVec3::Y,
            angle: None,
            look_at: None,
            sized: false,
            transform: DAffine3::IDENTITY,
            loc: loc.clone(),
        }
    }
}

/// A light's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightKind {
    /// A point light.
    Point,
    /// A spotlight.
    Spot,
    /// A parallel light (sun): from `position` towards `point_at`.
    Parallel,
}

/// A shape.
#[derive(Clone, Debug)]
pub enum Shape {
    /// `sphere { centre, radius }`.
    Sphere(DVec3, f64),
    /// `plane { normal, distance }`.
    Plane(DVec3, f64),
    /// `box { corner, corner }`.
    Box(DVec3, DVec3),
    /// `cylinder { base, cap, radius [open] }`.
    Cylinder(DVec3, DVec3, f64, bool),
    /// `cone { base, radius, cap, radius [open] }`.
    Cone(DVec3, f64, DVec3, f64, bool),
    /// `torus { major, minor }`.
    Torus(f64, f64),
    /// `disc { centre, normal, radius [, hole] }`.
    Disc(DVec3, DVec3, f64, f64),
    /// `superellipsoid { <e, n> }`.
    Superellipsoid(f64, f64),
    /// `quadric`, `cubic`, `quartic`, `poly` of degree ≤ 4: the polynomial's coefficients.
    Algebraic(Box<algebraic::Coefficients>),
    /// Triangles (a `triangle`, `smooth_triangle`, `mesh`, `mesh2` or `polygon`): corners,
    /// normals (when smooth), and a texture per triangle when the mesh gives them.
    Mesh(Rc<Mesh>),
    /// A combination of objects.
    Csg(CsgKind, Vec<Object>),
    /// A light source inside a combination.
    Light(Rc<Light>),
    /// A shape lucent does not read: its name.
    Unread(Rc<str>),
}

/// Triangles.
#[derive(Debug, Default)]
pub struct Mesh {
    /// Corners, three per triangle.
    pub points: Vec<DVec3>,
    /// Normals, three per triangle, when smooth.
    pub normals: Option<Vec<DVec3>>,
    /// The texture of each triangle, when the mesh gives them.
    pub textures: Option<Vec<Option<Rc<Texture>>>>,
}

/// How a combination combines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgKind {
    /// All surfaces.
    Union,
    /// Where all children are.
    Intersection,
    /// The first without the rest.
    Difference,
    /// Where any is, only outer surfaces.
    Merge,
}

/// An object: a shape, its placement and its looks.
#[derive(Clone, Debug)]
pub struct Object {
    /// What it is.
    pub shape: Shape,
    /// Its placement (object space to POV-Ray's world).
    pub transform: DAffine3,
    /// Its texture, if given.
    pub texture: Option<Rc<Texture>>,
    /// Its interior, if given.
    pub interior: Option<Rc<Interior>>,
    /// `inverse`.
    pub inverse: bool,
    /// `no_shadow`.
    pub no_shadow: bool,
    /// The box of its `bounded_by` or `clipped_by` in its own space (read for the algebraic
    /// shapes, which have no box of their own).
    pub bounds: Option<[DVec3; 2]>,
    /// Where it was written.
    pub loc: Loc,
}

/// `#default`'s texture.
#[derive(Clone, Debug, Default)]
pub struct Defaults {
    /// Its pigment (POV-Ray's own: black).
    pub pigment: Option<Rc<Pigment>>,
    /// Its finish, over POV-Ray's.
    pub finish: Finish,
}

/// What the whole file gives.
#[derive(Debug, Default)]
pub struct PovScene {
    /// The last camera.
    pub camera: Option<Rc<Camera>>,
    /// The lights.
    pub lights: Vec<Rc<Light>>,
    /// The objects.
    pub objects: Vec<Object>,
    /// `background`.
    pub background: Option<Vect>,
    /// `sky_sphere`'s pigment.
    pub sky: Option<Rc<Pigment>>,
    /// `global_settings`: `ambient_light`.
    pub ambient_light: Option<DVec3>,
    /// `max_trace_level`.
    pub max_trace_level: Option<u32>,
    /// `adc_bailout`.
    pub adc_bailout: Option<f64>,
    /// `assumed_gamma`.
    pub assumed_gamma: Option<f64>,
}

const SHAPES: [&str; 23] = [
    "sphere",
    "plane",
    "box",
    "cylinder",
    "cone",
    "torus",
    "disc",
    "superellipsoid",
    "triangle",
    "smooth_triangle",
    "mesh",
    "mesh2",
    "union",
    "intersection",
    "difference",
    "merge",
    "object",
    "polygon",
    "light_source",
    "quadric",
    "cubic",
    "quartic",
    "poly",
];

const UNREAD_SHAPES: [&str; 17] = [
    "blob",
    "height_field",
    "isosurface",
    "julia_fractal",
    "lathe",
    "sor",
    "prism",
    "text",
    "parametric",
    "sphere_sweep",
    "bicubic_patch",
    "ovus",
    "lemon",
    "fractal",
    "polynomial",
    "light_group",
    "isosurface_",
];

/// Whether `w` begins an object (a shape, a combination, `object`, a light in a union).
pub fn is_shape_word(w: &str) -> bool {
    SHAPES.contains(&w) || UNREAD_SHAPES.contains(&w)
}

impl Parser {
    /// Puts `t` back to be read next.
    pub fn push_back(&mut self, t: Token) {
        debug_assert!(self.peeked_is_empty(), "one token of look-ahead");
        self.set_peeked(t);
    }

    /// The whole file's statements.
    pub fn scene(&mut self) -> Result<PovScene, LoadError> {
        let mut s = PovScene::default();
        while let Some(t) = self.next_token()? {
            let Tok::Word(w) = &t.tok else {
                if t.is_symbol(";") {
                    continue;
                }
                return Err(t
                    .loc
                    .error(format!("expected a scene statement, found {}", t.tok)));
            };
            match &**w {
                "camera" => s.camera = Some(Rc::new(self.camera_block(&t.loc)?)),
                "light_source" => s.lights.push(Rc::new(self.light_block(&t.loc)?)),
                "background" => {
                    self.expect_symbol("{")?;
                    s.background = Some(self.color_body()?);
                    self.expect_symbol("}")?;
                }
                "sky_sphere" => s.sky = Some(Rc::new(self.sky_sphere()?)),
                "global_settings" => self.global_settings(&mut s)?,
                // POV-Ray 3.0's `default` without the `#`.
                "default" => self.default_block()?,
                "fog" | "rainbow" | "media" | "photons" | "radiosity" => {
                    self.warn(&t.loc, format!("`{w}` is not read by lucent"));
                    self.skip_braces()?;
                }
                w if SHAPES.contains(&w) || UNREAD_SHAPES.contains(&w) => {
                    self.push_back(t.clone());
                    let mut o = self.object()?;
                    if o.texture.is_none() {
                        o.texture = Some(Rc::new(self.default_texture()));
                    }
                    match o.shape {
                        Shape::Light(l) => s.lights.push(Rc::new(placed_light(&l, &o.transform))),
                        _ => {
                            let most = self.options.limits.objects;
                            if s.objects.len() as u64 >= most {
                                return Err(t.loc.error(format!("the scene has more than {most} objects (`--limit objects=N` raises it)")));
                            }
                            s.objects.push(o)
                        }
                    }
                }
                _ => {
                    return Err(t.loc.error(format!(
                        "expected an object, light_source, camera or other scene statement, found `{w}`"
                    )));
                }
            }
        }
        Ok(s)
    }

    /// What `#declare X =` (or a macro's argument) gives.
    pub fn declared_value(&mut self) -> Result<Value, LoadError> {
        let t = self.expect_any("a value")?;
        let loc = t.loc.clone();
        if let Tok::Word(w) = &t.tok {
            match &**w {
                "texture" => {
                    let mut tex = self.texture_block()?;
                    // Layers: `texture {…} texture {…}`; the first is kept.
                    while self.raw_peek_is_word("texture") {
                        let layer = self.expect_any("a texture")?;
                        self.texture_block()?;
                        tex.layered.get_or_insert(layer.loc);
                    }
                    tex.finish = self.defaults.finish.overlaid(&tex.finish).resolved();
                    return Ok(Value::Texture(Rc::new(tex)));
                }
                "pigment" => return Ok(Value::Pigment(Rc::new(self.pigment_block()?))),
                // A declared finish or texture takes the defaults of its time (`#default`
                // later does not change it), as POV-Ray's do.
                "finish" => {
                    let f = self.finish_block()?;
                    return Ok(Value::Finish(Rc::new(
                        self.defaults.finish.overlaid(&f).resolved(),
                    )));
                }
                "interior" => return Ok(Value::Interior(Rc::new(self.interior_block()?))),
                "normal" => return Ok(Value::Normal(Rc::new(self.normal_block()?))),
                "color_map" | "colour_map" => {
                    return Ok(Value::ColorMap(Rc::new(self.color_map()?)));
                }
                "camera" => return Ok(Value::Camera(Rc::new(self.camera_block(&loc)?))),
                // A sky sphere is kept as its pigment.
                "sky_sphere" => return Ok(Value::Pigment(Rc::new(self.sky_sphere()?))),
                "light_source" => return Ok(Value::Light(Rc::new(self.light_block(&loc)?))),
                "transform" => {
                    self.push_back(t.clone());
                    let m = self.transform_item()?.expect("a transform");
                    return Ok(Value::Transform(m));
                }
                "array" => return self.array(&loc),
                "material" => {
                    let (tex, interior) = self.material_block()?;
                    return Ok(Value::Object(Rc::new(Object {
                        shape: Shape::Unread("material".into()),
                        transform: DAffine3::IDENTITY,
                        texture: tex.map(Rc::new),
                        interior: interior.map(Rc::new),
                        inverse: false,
                        no_shadow: false,
                        bounds: None,
                        loc,
                    })));
                }
                "function" | "spline" | "media" | "density" | "pigment_map" | "normal_map"
                | "slope_map" | "texture_map" | "material_map" | "density_map" | "rainbow"
                | "fog" | "isosurface_" => {
                    if self.peek()?.is_some_and(|t| t.is_symbol("(")) {
                        self.skip_parens()?;
                    }
                    self.skip_braces()?;
                    return Ok(Value::Unread(w.clone(), loc));
                }
                w if SHAPES.contains(&w) || UNREAD_SHAPES.contains(&w) => {
                    self.push_back(t.clone());
                    return Ok(Value::Object(Rc::new(self.object()?)));
                }
                _ => {}
            }
            // An identifier of a non-numeric value stands for itself.
            if let Some(v) = self.lookup(w).cloned()
                && !matches!(
                    v,
                    Value::Float(_) | Value::Vector(_) | Value::Str(_) | Value::Array(_)
                )
            {
                return Ok(v);
            }
        }
        self.push_back(t);
        Ok(match self.expression()? {
            super::expr::Scalar::F(v) => Value::Float(v),
            super::expr::Scalar::V(v) => Value::Vector(v),
            super::expr::Scalar::S(s) => Value::Str(s),
        })
    }

    fn skip_parens(&mut self) -> Result<(), LoadError> {
        self.expect_symbol("(")?;
        let mut depth = 1;
        while depth > 0 {
            let t = self.expect_any("`)`")?;
            if t.is_symbol("(") {
                depth += 1;
            } else if t.is_symbol(")") {
                depth -= 1;
            }
        }
        Ok(())
    }

    /// A transform keyword and its argument, if the next token is one; `None` (nothing read)
    /// otherwise.
    pub fn transform_item(&mut self) -> Result<Option<DAffine3>, LoadError> {
        let Some(t) = self.peek()?.cloned() else {
            return Ok(None);
        };
        let Tok::Word(w) = &t.tok else {
            return Ok(None);
        };
        let m = match &**w {
            "translate" => {
                self.next_token()?;
                DAffine3::from_translation(self.vec3()?)
            }
            "rotate" => {
                self.next_token()?;
                rotation(self.vec3()?)
            }
            "scale" => {
                self.next_token()?;
                let s = self.vec3()?;
                if s.x == 0.0 || s.y == 0.0 || s.z == 0.0 {
                    self.warn(
                        &t.loc,
                        "a scale by 0 is taken as 1 on that axis, as POV-Ray does",
                    );
                }
                let s = DVec3::select(s.cmpeq(DVec3::ZERO), DVec3::ONE, s);
                DAffine3::from_scale(s)
            }
            "matrix" => {
                self.next_token()?;
                self.expect_symbol("<")?;
                let mut v = [0.0; 12];
                for (i, x) in v.iter_mut().enumerate() {
                    if i > 0 {
                        self.expect_symbol(",")?;
                    }
                    *x = self.float()?;
                }
                self.expect_symbol(">")?;
                // POV-Ray's rows are the images of x, y, z, then the translation.
                DAffine3::from_mat3_translation(
                    DMat3::from_cols(
                        DVec3::new(v[0], v[1], v[2]),
                        DVec3::new(v[3], v[4], v[5]),
                        DVec3::new(v[6], v[7], v[8]),
                    ),
                    DVec3::new(v[9], v[10], v[11]),
                )
            }
            "transform" => {
                self.next_token()?;
                self.transform_body(&t.loc)?
            }
            _ => return Ok(None),
        };
        if m.matrix3.determinant() == 0.0 {
            return Err(t
                .loc
                .error("this transform flattens space (its matrix is singular)"));
        }
        Ok(Some(m))
    }

    /// `transform Name`, `transform { … }`, with `inverse`.
    fn transform_body(&mut self, loc: &Loc) -> Result<DAffine3, LoadError> {
        if !self.eat_symbol("{")? {
            return match self.expect_any("a transform")? {
                Token {
                    tok: Tok::Word(n),
                    loc,
                } => match self.lookup(&n) {
                    Some(Value::Transform(m)) => Ok(*m),
                    _ => Err(loc.error(format!("`{n}` is not a transform"))),
                },
                t => Err(t
                    .loc
                    .error(format!("expected a transform, found {}", t.tok))),
            };
        }
        let mut m = DAffine3::IDENTITY;
        let mut inverse = false;
        loop {
            if self.eat_symbol("}")? {
                break;
            }
            if self.eat_word("inverse")? {
                inverse = true;
                continue;
            }
            if let Some(Tok::Word(n)) = self.peek()?.map(|t| t.tok.clone())
                && let Some(Value::Transform(t)) = self.lookup(&n).cloned()
            {
                self.next_token()?;
                m = t * m;
                continue;
            }
            match self.transform_item()? {
                Some(t) => m = t * m,
                None => {
                    let t = self.expect_any("`}`")?;
                    return Err(t.loc.error(format!("{} is not part of a transform", t.tok)));
                }
            }
        }
        let _ = loc;
        Ok(if inverse { m.inverse() } else { m })
    }

    /// `material { texture {…} interior {…} }` (the word read).
    fn material_block(&mut self) -> Result<(Option<Texture>, Option<Interior>), LoadError> {
        self.expect_symbol("{")?;
        let (mut tex, mut interior) = (None, None);
        if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone())
            && let Some(Value::Object(o)) = self.lookup(&w).cloned()
            && matches!(&o.shape, Shape::Unread(n) if &**n == "material")
        {
            self.next_token()?;
            tex = o.texture.as_deref().cloned();
            interior = o.interior.as_deref().cloned();
        }
        loop {
            let t = self.expect_any("`}`")?;
            match &t.tok {
                Tok::Symbol("}") => return Ok((tex, interior)),
                Tok::Word(w) if &**w == "texture" => tex = Some(self.texture_block()?),
                Tok::Word(w) if &**w == "interior" => interior = Some(self.interior_block()?),
                _ => {
                    self.push_back(t.clone());
                    if self.transform_item()?.is_none() {
                        return Err(t.loc.error(format!("{} is not part of a material", t.tok)));
                    }
                }
            }
        }
    }

    fn camera_block(&mut self, loc: &Loc) -> Result<Camera, LoadError> {
        self.expect_symbol("{")?;
        let mut c = Camera::default_at(loc);
        if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone())
            && let Some(Value::Camera(q)) = self.lookup(&w).cloned()
        {
            self.next_token()?;
            c = (*q).clone();
        }
        loop {
            let Some((w, t)) = self.block_word("a camera's contents")? else {
                return Ok(c);
            };
            match &*w {
                "perspective" => c.orthographic = false,
                "orthographic" => c.orthographic = true,
                "location" => c.location = self.vec3()?,
                "direction" => c.direction = self.vec3()?,
                "right" => {
                    c.right = self.vec3()?;
                    c.sized = true;
                }
                "up" => {
                    c.up = self.vec3()?;
                    c.sized = true;
                }
                "sky" => c.sky = self.vec3()?,
                "angle" => c.angle = Some(self.float()?),
                "look_at" => c.look_at = Some(self.vec3()?),
                "aperture" | "blur_samples" | "focal_point" | "confidence" | "variance" => {
                    self.warn(
                        &t.loc,
                        format!("the camera's `{w}` (focal blur) is not read by lucent"),
                    );
                    self.expression()?;
                    if w.as_ref() == "blur_samples" && self.eat_symbol(",")? {
                        self.float()?;
                    }
                }
                "fisheye" | "ultra_wide_angle" | "omnimax" | "panoramic" | "cylinder"
                | "spherical" | "mesh_camera" => {
                    return Err(t.loc.error(format!(
                        "the `{w}` camera is not read by lucent (perspective and orthographic are)"
                    )));
                }
                "normal" => {
                    self.warn(&t.loc, "the camera's `normal` is not read by lucent");
                    self.skip_braces()?;
                }
                _ => {
                    self.push_back(t.clone());
                    match self.transform_item()? {
                        Some(m) => c.transform = m * c.transform,
                        None => return Err(t.loc.error(format!("`{w}` is not part of a camera"))),
                    }
                }
            }
        }
    }

    fn light_block(&mut self, loc: &Loc) -> Result<Light, LoadError> {
        self.expect_symbol("{")?;
        let position = if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone())
            && let Some(Value::Light(q)) = self.lookup(&w).cloned()
        {
            self.next_token()?;
            return self.light_rest((*q).clone());
        } else {
            self.vec3()?
        };
        self.eat_symbol(",")?;
        let color = if self.starts_value()?
            || self
                .peek()?
                .is_some_and(|t| matches!(&t.tok, Tok::Word(w) if !super::expr::is_keyword(w)))
        {
            self.color_body()?.v3()
        } else {
            DVec3::ONE
        };
        self.light_rest(Light::point(position, color, loc))
    }

    fn light_rest(&mut self, mut l: Light) -> Result<Light, LoadError> {
        let mut fade_power = None;
        let mut fade_distance = None;
        while let Some((w, t)) = self.block_word("a light's contents")? {
            match &*w {
                "color" | "colour" => l.color = self.color_body()?.v3(),
                "rgb" | "srgb" => {
                    self.push_back(t.clone());
                    l.color = self.color_body()?.v3();
                }
                "spotlight" => l.kind = LightKind::Spot,
                "parallel" => l.kind = LightKind::Parallel,
                "point_at" => l.point_at = self.vec3()?,
                "radius" => l.spot.0 = self.float()?,
                "falloff" => l.spot.1 = self.float()?,
                "tightness" => l.spot.2 = self.float()?,
                "fade_distance" => fade_distance = Some(self.float()?),
                "fade_power" => fade_power = Some(self.float()?),
                "shadowless" => l.shadowless = true,
                "area_light" => {
                    let a = self.vec3()?;
                    self.eat_symbol(",")?;
                    let b = self.vec3()?;
                    self.eat_symbol(",")?;
                    let n = self.float()?;
                    self.eat_symbol(",")?;
                    let m = self.float()?;
                    l.area = Some((a, b, n.max(1.0) as u32, m.max(1.0) as u32));
                }
                "adaptive" | "jitter" | "circular" | "orient" | "area_illumination" => {
                    if w.as_ref() == "adaptive" {
                        self.float()?;
                    }
                    if w.as_ref() == "area_illumination" && self.starts_value()? {
                        self.float()?;
                    }
                }
                "looks_like" | "projected_through" => {
                    self.warn(&t.loc, format!("a light's `{w}` is not read by lucent"));
                    self.skip_braces()?;
                }
                "media_interaction" | "media_attenuation" => {
                    if self.starts_value()? {
                        self.float()?;
                    }
                }
                "photons" => self.skip_braces()?,
                "cylinder" => {
                    self.warn(&t.loc, "a cylindrical light is read as a spotlight");
                    l.kind = LightKind::Spot;
                }
                _ => {
                    self.push_back(t.clone());
                    match self.transform_item()? {
                        Some(m) => {
                            l.position = m.transform_point3(l.position);
                            l.point_at = m.transform_point3(l.point_at);
                            if let Some(a) = &mut l.area {
                                a.0 = m.transform_vector3(a.0);
                                a.1 = m.transform_vector3(a.1);
                            }
                        }
                        None => {
                            return Err(t
                                .loc
                                .error(format!("`{w}` is not part of a light_source")));
                        }
                    }
                }
            }
        }
        if let Some(d) = fade_distance {
            l.fade = Some((d, fade_power.unwrap_or(0.0)));
        } else if fade_power.is_some() {
            // A fade power without a distance fades nothing (POV-Ray's default distance is
            // 0: no fading).
        }
        Ok(l)
    }

    fn sky_sphere(&mut self) -> Result<Pigment, LoadError> {
        self.expect_symbol("{")?;
        let mut pigment = None;
        if let Some(Value::Pigment(q)) =
            self.take_named("a sky_sphere", |v| matches!(v, Value::Pigment(_)))?
        {
            pigment = Some((*q).clone());
        }
        loop {
            let t = self.expect_any("`}`")?;
            match &t.tok {
                Tok::Symbol("}") => break,
                Tok::Word(w) if &**w == "pigment" => {
                    if pigment.is_some() {
                        self.warn(
                            &t.loc,
                            "a sky_sphere's later pigments are not read by lucent",
                        );
                        self.skip_braces()?;
                    } else {
                        pigment = Some(self.pigment_block()?);
                    }
                }
                Tok::Word(w) if &**w == "emission" => {
                    self.color_body()?;
                }
                _ => {
                    self.push_back(t.clone());
                    if self.transform_item()?.is_none() {
                        return Err(t
                            .loc
                            .error(format!("{} is not part of a sky_sphere", t.tok)));
                    }
                }
            }
        }
        let loc = self.loc();
        Ok(pigment.unwrap_or_else(|| Pigment::solid(Vect::splat(0.0, 5), loc)))
    }

    fn global_settings(&mut self, s: &mut PovScene) -> Result<(), LoadError> {
        self.expect_symbol("{")?;
        loop {
            let Some((w, t)) = self.block_word("a global setting")? else {
                return Ok(());
            };
            match &*w {
                "ambient_light" => s.ambient_light = Some(self.color_body()?.v3()),
                "max_trace_level" => s.max_trace_level = Some(self.float()?.max(1.0) as u32),
                "adc_bailout" => s.adc_bailout = Some(self.float()?),
                "assumed_gamma" => s.assumed_gamma = Some(self.float()?),
                "radiosity" | "photons" | "subsurface" => {
                    self.warn(&t.loc, format!("`{w}` is not read by lucent"));
                    self.skip_braces()?;
                }
                "irid_wavelength" => {
                    self.color_body()?;
                }
                "charset" => {
                    self.next_token()?;
                }
                "max_intersections" | "number_of_waves" | "noise_generator" | "hf_gray_16"
                | "mm_per_unit" => {
                    if self.starts_value()? {
                        self.float()?;
                    }
                }
                _ => return Err(t.loc.error(format!("`{w}` is not a global setting"))),
            }
        }
    }

    /// `#default { texture {…} pigment {…} finish {…} }` (the directive read).
    pub fn default_block(&mut self) -> Result<(), LoadError> {
        self.expect_symbol("{")?;
        loop {
            let t = self.expect_any("`}`")?;
            match &t.tok {
                Tok::Symbol("}") => return Ok(()),
                Tok::Word(w) if &**w == "finish" => {
                    let f = self.finish_block()?;
                    self.defaults.finish = self.defaults.finish.overlaid(&f);
                }
                Tok::Word(w) if &**w == "pigment" => {
                    self.defaults.pigment = Some(Rc::new(self.pigment_block()?));
                }
                Tok::Word(w) if &**w == "texture" => {
                    let tex = self.texture_block()?;
                    if tex.pigment.is_some() {
                        self.defaults.pigment = tex.pigment.clone();
                    }
                    self.defaults.finish = self.defaults.finish.overlaid(&tex.finish);
                }
                Tok::Word(w) if &**w == "normal" => self.skip_braces()?,
                _ => return Err(t.loc.error(format!("{} is not part of `#default`", t.tok))),
            }
        }
    }

    /// An object statement: its shape's keyword and braces, then its modifiers.
    pub fn object(&mut self) -> Result<Object, LoadError> {
        let t = self.expect_any("an object")?;
        let loc = t.loc.clone();
        let Tok::Word(w) = &t.tok else {
            return Err(loc.error(format!("expected an object, found {}", t.tok)));
        };
        let w = w.clone();
        self.expect_symbol("{")?;
        let mut o = Object {
            shape: Shape::Unread(w.clone()),
            transform: DAffine3::IDENTITY,
            texture: None,
            interior: None,
            inverse: false,
            no_shadow: false,
            bounds: None,
            loc: loc.clone(),
        };
        match &*w {
            "object" => {
                let name = self.expect_any("an object's identifier")?;
                let found = match &name.tok {
                    Tok::Word(n) => match self.lookup(n) {
                        Some(Value::Object(q)) => Some((**q).clone()),
                        Some(Value::Light(l)) => Some(Object {
                            shape: Shape::Light(l.clone()),
                            ..o.clone()
                        }),
                        _ => None,
                    },
                    _ => None,
                };
                if let Some(found) = found {
                    o = found;
                    o.loc = loc.clone();
                } else if let Tok::Word(n) = &name.tok
                    && SHAPES.contains(&&**n) | UNREAD_SHAPES.contains(&&**n)
                {
                    self.push_back(name.clone());
                    o = self.object()?;
                } else {
                    return Err(name.loc.error(format!(
                        "expected an object's identifier, found {}",
                        name.tok
                    )));
                }
            }
            "light_source" => {
                o.shape = Shape::Light(Rc::new(self.light_body(&loc)?));
                return Ok(o);
            }
            _ => o.shape = self.shape(&w, &loc)?,
        }
        self.modifiers(&mut o)?;
        // The texture written here takes the defaults in force now.
        if let Some(t) = &mut o.texture {
            let t = Rc::make_mut(t);
            t.finish = self.defaults.finish.overlaid(&t.finish).resolved();
            if t.pigment.is_none() {
                t.pigment = self.defaults.pigment.clone();
            }
        }
        Ok(o)
    }

    /// The texture an object without one wears: `#default`'s now.
    pub fn default_texture(&self) -> Texture {
        Texture {
            pigment: self.defaults.pigment.clone(),
            finish: self.defaults.finish.resolved(),
            ..blank_texture()
        }
    }

    /// A light inside a combination: `light_source { … }` with its `{` read.
    fn light_body(&mut self, loc: &Loc) -> Result<Light, LoadError> {
        let position = self.vec3()?;
        self.eat_symbol(",")?;
        let color = self.color_body()?.v3();
        self.light_rest(Light::point(position, color, loc))
    }

    /// Modifiers up to the object's `}`: transforms, texture, pigment, finish, interior, …
    fn modifiers(&mut self, o: &mut Object) -> Result<(), LoadError> {
        loop {
            let Some((w, t)) = self.block_word("an object's modifiers")? else {
                return Ok(());
            };
            match &*w {
                "texture" => {
                    let tex = self.texture_block()?;
                    match &mut o.texture {
                        // A texture over the object's own `pigment`/`finish`: a layer.
                        Some(own) => {
                            Rc::make_mut(own).layered.get_or_insert(t.loc.clone());
                        }
                        None => o.texture = Some(Rc::new(tex)),
                    }
                }
                "pigment" => {
                    let p = self.pigment_block()?;
                    Rc::make_mut(o.texture.get_or_insert_with(|| Rc::new(blank_texture())))
                        .pigment = Some(Rc::new(p));
                }
                "finish" => {
                    let f = self.finish_block()?;
                    let tex =
                        Rc::make_mut(o.texture.get_or_insert_with(|| Rc::new(blank_texture())));
                    tex.finish = tex.finish.overlaid(&f);
                }
                "normal" => {
                    let n = self.normal_block()?;
                    Rc::make_mut(o.texture.get_or_insert_with(|| Rc::new(blank_texture())))
                        .normal = Some(Rc::new(n));
                }
                "interior" => o.interior = Some(Rc::new(self.interior_block()?)),
                "material" => {
                    let (tex, interior) = self.material_block()?;
                    if let Some(tex) = tex {
                        o.texture = Some(Rc::new(tex));
                    }
                    if let Some(i) = interior {
                        o.interior = Some(Rc::new(i));
                    }
                }
                "inverse" => o.inverse = !o.inverse,
                "no_shadow" => o.no_shadow = true,
                "hollow" | "no_image" | "no_reflection" | "no_radiosity" | "double_illuminate"
                | "open" | "sturm" | "smooth" => {
                    if matches!(&*w, "no_image" | "no_reflection") {
                        self.warn(&t.loc, format!("`{w}` is not read by lucent"));
                    }
                    if self.starts_value()? && w.as_ref() == "hollow" {
                        self.float()?;
                    }
                }
                "bounded_by" | "clipped_by" => self.bounds_block(o, &w, &t.loc)?,
                "photons" | "radiosity" => self.skip_braces()?,
                "interior_texture" => {
                    self.warn(&t.loc, "`interior_texture` is not read by lucent");
                    self.skip_braces()?;
                }
                "uv_mapping" => {}
                _ => {
                    self.push_back(t.clone());
                    match self.transform_item()? {
                        Some(m) => apply_transform(o, m),
                        None => {
                            return Err(t.loc.error(format!("`{w}` is not an object modifier")));
                        }
                    }
                }
            }
        }
    }
}

/// A texture with nothing set, to which an object's `pigment` or `finish` is added.
pub fn blank_texture() -> Texture {
    Texture {
        transform: DAffine3::IDENTITY,
        ..Texture::default()
    }
}

/// Moves `o` (and the texture it already has) by `m`.
pub fn apply_transform(o: &mut Object, m: DAffine3) {
    o.transform = m * o.transform;
    if let Some(t) = &mut o.texture {
        let t = Rc::make_mut(t);
        t.transform = m * t.transform;
        if let Some(p) = &mut t.pigment {
            Rc::make_mut(p).transform = m * p.transform;
        }
        if let Some(n) = &mut t.normal {
            let n = Rc::make_mut(n);
            n.pattern.transform = m * n.pattern.transform;
        }
    }
}

/// A light from a combination, placed by the combination's transform.
fn placed_light(l: &Light, m: &DAffine3) -> Light {
    let mut l = l.clone();
    l.position = m.transform_point3(l.position);
    l.point_at = m.transform_point3(l.point_at);
    l
}
