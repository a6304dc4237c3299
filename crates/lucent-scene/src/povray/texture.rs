//! `pigment`, `finish`, `normal`, `interior` and `texture` blocks, read into the values the
//! conversion maps onto lucent's materials.

use super::lexer::{Loc, Tok};
use super::parser::Parser;
use super::value::{Value, Vect};
use crate::error::LoadError;
use glam::{DAffine3, DVec3};
use std::rc::Rc;

/// A colour map: `[value colour]` entries in increasing value.
pub type ColorMap = Vec<(f64, Vect)>;

/// What a pigment's colour follows.
#[derive(Clone, Debug)]
pub enum Pattern {
    /// One colour.
    Solid(Vect),
    /// Unit cubes alternating between two pigments.
    Checker(Box<[Pigment; 2]>),
    /// Hexagonal columns along y in three pigments.
    Hexagon(Box<[Pigment; 3]>),
    /// A pattern lucent reads and maps by its colour map: the pattern's name and the map.
    Mapped(Rc<str>, DVec3, Rc<ColorMap>),
}

/// How a pattern's value is shaped: POV-Ray's wave, frequency, phase and turbulence.
#[derive(Clone, Debug, Default)]
pub struct Shaping {
    /// `ramp_wave`, `triangle_wave`, `sine_wave`, `scallop_wave`, `cubic_wave`, `poly_wave`
    /// (with its exponent); `None`: the pattern's own.
    pub wave: Option<(Rc<str>, f64)>,
    /// `frequency`.
    pub frequency: Option<f64>,
    /// `phase`.
    pub phase: Option<f64>,
    /// `turbulence`.
    pub turbulence: Option<DVec3>,
    /// `octaves`, `omega`, `lambda`.
    pub octaves: Option<f64>,
    /// See `octaves`.
    pub omega: Option<f64>,
    /// See `octaves`.
    pub lambda: Option<f64>,
}

/// A pigment: its pattern, placed by `transform` (pattern space to object space).
#[derive(Clone, Debug)]
pub struct Pigment {
    /// What it is.
    pub pattern: Pattern,
    /// Its value's shaping.
    pub shaping: Shaping,
    /// Its transforms, composed.
    pub transform: DAffine3,
    /// Where it was written.
    pub loc: Loc,
}

impl Pigment {
    /// One colour everywhere.
    pub fn solid(c: Vect, loc: Loc) -> Self {
        Self {
            pattern: Pattern::Solid(c),
            shaping: Shaping::default(),
            transform: DAffine3::IDENTITY,
            loc,
        }
    }

    /// Its colour averaged over the pattern (what a solid stand-in shows).
    pub fn average(&self) -> Vect {
        let mean = |cs: &[Vect]| {
            let mut m = Vect::splat(0.0, 5);
            for c in cs {
                for i in 0..5 {
                    m.c[i] += c.c[i] / cs.len() as f64;
                }
            }
            m
        };
        match &self.pattern {
            Pattern::Solid(c) => *c,
            Pattern::Checker(p) => mean(&[p[0].average(), p[1].average()]),
            Pattern::Hexagon(p) => mean(&[p[0].average(), p[1].average(), p[2].average()]),
            Pattern::Mapped(_, _, map) => {
                let cs: Vec<Vect> = map.iter().map(|e| e.1).collect();
                if cs.is_empty() {
                    Vect::splat(0.0, 5)
                } else {
                    mean(&cs)
                }
            }
        }
    }
}

/// A finish: every term POV-Ray's lighting takes; `None` is the default's (`#default` or
/// POV-Ray's own).
#[derive(Clone, Debug, Default)]
pub struct Finish {
    /// `ambient`: a colour (a number is grey).
    pub ambient: Option<DVec3>,
    /// `emission`.
    pub emission: Option<DVec3>,
    /// `diffuse`.
    pub diffuse: Option<f64>,
    /// `brilliance`: the exponent of `N·L`.
    pub brilliance: Option<f64>,
    /// `specular`: Blinn's highlight.
    pub specular: Option<f64>,
    /// `roughness`: the highlight's size (exponent 1/roughness).
    pub roughness: Option<f64>,
    /// `phong`: Phong's highlight.
    pub phong: Option<f64>,
    /// `phong_size`: its exponent.
    pub phong_size: Option<f64>,
    /// `reflection`: the mirror's colour (least and most, with `fresnel`… read as the most).
    pub reflection: Option<DVec3>,
    /// `metallic` reflection and highlights take the pigment's colour.
    pub metallic: Option<f64>,
    /// `conserve_energy`.
    pub conserve_energy: Option<bool>,
    /// What was read and is not applied, for warnings: (what, where).
    pub unread: Vec<(String, Loc)>,
}

impl Finish {
    /// Every term set: what is not, POV-Ray's default.
    pub fn resolved(&self) -> Finish {
        Finish {
            ambient: Some(self.ambient.unwrap_or(DVec3::splat(0.1))),
            emission: Some(self.emission.unwrap_or(DVec3::ZERO)),
            diffuse: Some(self.diffuse.unwrap_or(0.6)),
            brilliance: Some(self.brilliance.unwrap_or(1.0)),
            specular: Some(self.specular.unwrap_or(0.0)),
            roughness: Some(self.roughness.unwrap_or(0.05)),
            phong: Some(self.phong.unwrap_or(0.0)),
            phong_size: Some(self.phong_size.unwrap_or(40.0)),
            reflection: Some(self.reflection.unwrap_or(DVec3::ZERO)),
            metallic: Some(self.metallic.unwrap_or(0.0)),
            conserve_energy: Some(self.conserve_energy.unwrap_or(false)),
            unread: self.unread.clone(),
        }
    }

    /// `self` with what `over` sets taken from it.
    pub fn overlaid(&self, over: &Finish) -> Finish {
        Finish {
            ambient: over.ambient.or(self.ambient),
            emission: over.emission.or(self.emission),
            diffuse: over.diffuse.or(self.diffuse),
            brilliance: over.brilliance.or(self.brilliance),
            specular: over.specular.or(self.specular),
            roughness: over.roughness.or(self.roughness),
            phong: over.phong.or(self.phong),
            phong_size: over.phong_size.or(self.phong_size),
            reflection: over.reflection.or(self.reflection),
            metallic: over.metallic.or(self.metallic),
            conserve_energy: over.conserve_energy.or(self.conserve_energy),
            unread: self.unread.iter().chain(&over.unread).cloned().collect(),
        }
    }
}

/// `interior { ior … }`.
#[derive(Clone, Debug, Default)]
pub struct Interior {
    /// The index of refraction.
    pub ior: Option<f64>,
    /// What was read and is not applied.
    pub unread: Vec<(String, Loc)>,
}

/// A texture: pigment, finish, and whether a normal perturbation was given.
#[derive(Clone, Debug, Default)]
pub struct Texture {
    /// The pigment (`None`: the default's).
    pub pigment: Option<Rc<Pigment>>,
    /// The finish (over the default's).
    pub finish: Finish,
    /// Its normal perturbation.
    pub normal: Option<Rc<super::normal::Normal>>,
    /// Transforms after the texture's start, applied to its pigment.
    pub transform: DAffine3,
    /// A texture layered under this one (read, not applied).
    pub layered: Option<Loc>,
}

impl Parser {
    /// `{ … }` of a pigment (the word `pigment` read).
    pub fn pigment_block(&mut self) -> Result<Pigment, LoadError> {
        self.expect_symbol("{")?;
        let loc = self.loc();
        let mut p = Pigment::solid(Vect::splat(0.0, 5), loc.clone());
        // An identifier first: the pigment (or colour) it names.
        if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone()) {
            match self.lookup(&w).cloned() {
                Some(Value::Vector(_) | Value::Float(_)) => {
                    p.pattern = Pattern::Solid(self.color_body()?)
                }
                _ => {
                    if let Some(Value::Pigment(q)) =
                        self.take_named("a pigment", |v| matches!(v, Value::Pigment(_)))?
                    {
                        p = (*q).clone();
                    }
                }
            }
        }
        loop {
            let t = self.expect_any("`}`")?;
            let w = match &t.tok {
                Tok::Symbol("}") => return Ok(p),
                Tok::Word(w) => w.clone(),
                Tok::Symbol("<") | Tok::Number(_) => {
                    return Err(t
                        .loc
                        .error("a pigment's colour needs `color` or `rgb` before it"));
                }
                _ => {
                    return Err(t
                        .loc
                        .error(format!("expected a pigment's contents, found {}", t.tok)));
                }
            };
            match &*w {
                "color" | "colour" => p.pattern = Pattern::Solid(self.color_body()?),
                "rgb" | "rgbf" | "rgbt" | "rgbft" | "srgb" | "srgbf" | "srgbt" | "srgbft"
                | "red" | "green" | "blue" | "filter" | "transmit" => {
                    self.push_back(t);
                    p.pattern = Pattern::Solid(self.color_body()?);
                }
                "checker" => {
                    let [a, b] = self.pattern_entries::<2>(&t.loc, [0.0, 1.0])?;
                    p.pattern = Pattern::Checker(Box::new([a, b]));
                }
                "hexagon" => {
                    let e = self.pattern_entries::<3>(&t.loc, [0.0, 1.0, 0.5])?;
                    p.pattern = Pattern::Hexagon(Box::new(e));
                }
                "gradient" => {
                    let axis = self.vec3()?;
                    p.pattern = Pattern::Mapped(w.clone(), axis, Rc::new(default_map()));
                }
                "bozo" | "spotted" | "marble" | "wood" | "granite" | "agate" | "leopard"
                | "onion" | "radial" | "ripples" | "waves" | "wrinkles" | "bumps" | "dents"
                | "crackle" | "spiral1" | "spiral2" | "brick" | "boxed" | "spherical"
                | "cylindrical" | "planar" | "mandel" | "quilted" | "cells" | "granite2" => {
                    p.pattern = Pattern::Mapped(w.clone(), DVec3::ZERO, Rc::new(default_map()));
                    if matches!(&*w, "spiral1" | "spiral2" | "mandel") {
                        self.float()?;
                    }
                    if w.as_ref() == "brick" {
                        self.skip_entries()?;
                    }
                }
                "color_map" | "colour_map" => {
                    let map = Rc::new(self.color_map()?);
                    match &mut p.pattern {
                        Pattern::Mapped(_, _, m) => *m = map,
                        _ => p.pattern = Pattern::Mapped("gradient".into(), DVec3::X, map),
                    }
                }
                "image_map" | "pigment_map" | "uv_mapping" | "function" | "object" | "average"
                | "density_file" | "slope" | "aoi" | "pavement" | "tiling" => {
                    p.pattern = Pattern::Mapped(w.clone(), DVec3::ZERO, Rc::new(default_map()));
                    if self.peek()?.is_some_and(|t| t.is_symbol("{")) {
                        self.skip_braces()?;
                    }
                }
                // Agate's own turbulence (lucent's agate has a fixed one).
                "agate_turb" => {
                    self.float()?;
                }
                w if self.shaping_word(w, &mut p.shaping)? => {}
                "warp" => self.skip_braces()?,
                "quick_color" | "quick_colour" => {
                    self.color_body()?;
                }
                _ => {
                    self.push_back(t.clone());
                    if let Some(m) = self.transform_item()? {
                        p.transform = m * p.transform;
                    } else {
                        return Err(t.loc.error(format!("`{w}` is not part of a pigment")));
                    }
                }
            }
        }
    }

    /// Reads the shaping modifier `w` (its word read) into `shaping`: turbulence and its
    /// octaves, the wave, frequency and phase; `false` when `w` is none of them.
    pub fn shaping_word(&mut self, w: &str, shaping: &mut Shaping) -> Result<bool, LoadError> {
        match w {
            "turbulence" => shaping.turbulence = Some(self.vec3()?),
            "octaves" => shaping.octaves = Some(self.float()?),
            "omega" => shaping.omega = Some(self.float()?),
            "lambda" => shaping.lambda = Some(self.float()?),
            "frequency" => shaping.frequency = Some(self.float()?),
            "phase" => shaping.phase = Some(self.float()?),
            "ramp_wave" | "triangle_wave" | "sine_wave" | "scallop_wave" | "cubic_wave" => {
                shaping.wave = Some((w.into(), 1.0));
            }
            "poly_wave" => {
                let e = if self.starts_value()? {
                    self.float()?
                } else {
                    1.0
                };
                shaping.wave = Some((w.into(), e));
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The entries of `checker` or `hexagon`: colours or pigments, `n` of them at most
    /// (defaults: the grey values given).
    fn pattern_entries<const N: usize>(
        &mut self,
        loc: &Loc,
        grays: [f64; N],
    ) -> Result<[Pigment; N], LoadError> {
        let mut out: [Pigment; N] = std::array::from_fn(|i| {
            let mut c = Vect::splat(grays[i], 5);
            c.c[3] = 0.0;
            c.c[4] = 0.0;
            Pigment::solid(c, loc.clone())
        });
        for slot in out.iter_mut() {
            let Some(t) = self.peek()?.cloned() else {
                break;
            };
            match &t.tok {
                Tok::Word(w) if &**w == "pigment" => {
                    self.next_token()?;
                    *slot = self.pigment_block()?;
                }
                Tok::Word(w) if matches!(&**w, "color" | "colour") => {
                    self.next_token()?;
                    *slot = Pigment::solid(self.color_body()?, t.loc.clone());
                }
                Tok::Word(w)
                    if w.starts_with("rgb")
                        || w.starts_with("srgb")
                        || matches!(self.lookup(w), Some(Value::Vector(_))) =>
                {
                    *slot = Pigment::solid(self.color_body()?, t.loc.clone());
                }
                _ => break,
            }
            self.eat_symbol(",")?;
        }
        Ok(out)
    }

    /// `{ [v colour] … }` (the word `color_map` read), or a map's identifier.
    pub fn color_map(&mut self) -> Result<ColorMap, LoadError> {
        self.expect_symbol("{")?;
        if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone())
            && let Some(Value::ColorMap(m)) = self.lookup(&w).cloned()
        {
            self.next_token()?;
            self.expect_symbol("}")?;
            return Ok((*m).clone());
        }
        let mut map = ColorMap::new();
        while !self.eat_symbol("}")? {
            self.expect_symbol("[")?;
            let v = self.float()?;
            self.eat_symbol(",")?;
            // `[a b color c1 color c2]` (the old form) or `[a color c]`.
            if !self.peek()?.is_some_and(|t| {
                matches!(&t.tok, Tok::Word(w) if matches!(&**w, "color" | "colour") || w.starts_with("rgb") || w.starts_with("srgb"))
            }) && !self.peek()?.is_some_and(|t| matches!(&t.tok, Tok::Word(_)))
            {
                let v2 = self.float()?;
                self.eat_word("color")?;
                self.eat_word("colour")?;
                let c1 = self.color_body()?;
                self.eat_word("color")?;
                self.eat_word("colour")?;
                let c2 = self.color_body()?;
                map.push((v, c1));
                map.push((v2, c2));
            } else {
                self.eat_word("color")?;
                self.eat_word("colour")?;
                map.push((v, self.color_body()?));
            }
            self.expect_symbol("]")?;
        }
        Ok(map)
    }

    /// `{ … }` of a finish (the word `finish` read).
    pub fn finish_block(&mut self) -> Result<Finish, LoadError> {
        self.expect_symbol("{")?;
        let mut f = Finish::default();
        if let Some(Value::Finish(q)) =
            self.take_named("a finish", |v| matches!(v, Value::Finish(_)))?
        {
            f = (*q).clone();
        }
        loop {
            let Some((w, t)) = self.block_word("a finish's contents")? else {
                return Ok(f);
            };
            match &*w {
                "ambient" => f.ambient = Some(self.color_body()?.v3()),
                "emission" => f.emission = Some(self.color_body()?.v3()),
                "diffuse" => {
                    self.eat_word("albedo")?;
                    f.diffuse = Some(self.float()?);
                    // `diffuse a, b`: the back side's (not read).
                    if self.eat_symbol(",")? {
                        self.float()?;
                    }
                }
                "brilliance" => f.brilliance = Some(self.float()?),
                "specular" => {
                    self.eat_word("albedo")?;
                    f.specular = Some(self.float()?);
                }
                "roughness" => f.roughness = Some(self.float()?),
                "phong" => {
                    self.eat_word("albedo")?;
                    f.phong = Some(self.float()?);
                }
                "phong_size" => f.phong_size = Some(self.float()?),
                "metallic" => {
                    let v = if self.starts_value()? {
                        self.float()?
                    } else {
                        1.0
                    };
                    f.metallic = Some(v);
                }
                "conserve_energy" => f.conserve_energy = Some(true),
                "reflection" => {
                    if self.eat_symbol("{")? {
                        let lo = self.color_body()?.v3();
                        let mut hi = lo;
                        self.eat_symbol(",")?;
                        if self.starts_value()? {
                            hi = self.color_body()?.v3();
                        }
                        loop {
                            let t = self.expect_any("`}`")?;
                            match &t.tok {
                                Tok::Symbol("}") => break,
                                Tok::Word(k) if &**k == "metallic" => {
                                    let v = if self.starts_value()? {
                                        self.float()?
                                    } else {
                                        1.0
                                    };
                                    f.metallic = Some(v);
                                }
                                Tok::Word(k) if matches!(&**k, "falloff" | "exponent") => {
                                    f.unread
                                        .push((format!("reflection's `{k}`"), t.loc.clone()));
                                    self.float()?;
                                }
                                Tok::Word(k) if &**k == "fresnel" => {
                                    f.unread
                                        .push(("reflection's `fresnel`".into(), t.loc.clone()));
                                    if self.starts_value()? {
                                        self.float()?;
                                    }
                                }
                                _ => {
                                    return Err(t
                                        .loc
                                        .error(format!("{} is not part of a reflection", t.tok)));
                                }
                            }
                        }
                        if lo != hi {
                            f.unread.push((
                                "a reflection varying with angle (its largest value is used)"
                                    .into(),
                                t.loc.clone(),
                            ));
                        }
                        f.reflection = Some(lo.max(hi));
                    } else {
                        f.reflection = Some(self.color_body()?.v3());
                    }
                }
                "reflection_exponent" => {
                    f.unread
                        .push(("`reflection_exponent`".into(), t.loc.clone()));
                    self.float()?;
                }
                "crand" | "irid_wavelength" => {
                    f.unread.push((format!("`{w}`"), t.loc.clone()));
                    self.expression()?;
                }
                "irid" | "subsurface" => {
                    f.unread.push((format!("`{w}`"), t.loc.clone()));
                    self.skip_braces()?;
                }
                _ => return Err(t.loc.error(format!("`{w}` is not part of a finish"))),
            }
        }
    }

    /// `{ … }` of an interior (the word `interior` read).
    pub fn interior_block(&mut self) -> Result<Interior, LoadError> {
        self.expect_symbol("{")?;
        let mut i = Interior::default();
        if let Some(Tok::Word(w)) = self.peek()?.map(|t| t.tok.clone())
            && let Some(Value::Interior(q)) = self.lookup(&w).cloned()
        {
            self.next_token()?;
            i = (*q).clone();
        }
        loop {
            let Some((w, t)) = self.block_word("an interior's contents")? else {
                return Ok(i);
            };
            match &*w {
                "ior" => i.ior = Some(self.float()?),
                "caustics" | "dispersion" | "dispersion_samples" | "fade_distance"
                | "fade_power" => {
                    i.unread.push((format!("interior's `{w}`"), t.loc.clone()));
                    self.float()?;
                }
                "fade_color" | "fade_colour" => {
                    i.unread
                        .push(("interior's `fade_color`".into(), t.loc.clone()));
                    self.color_body()?;
                }
                "media" => {
                    i.unread.push(("a media".into(), t.loc.clone()));
                    self.skip_braces()?;
                }
                _ => return Err(t.loc.error(format!("`{w}` is not part of an interior"))),
            }
        }
    }

    /// `{ … }` of a texture (the word `texture` read).
    pub fn texture_block(&mut self) -> Result<Texture, LoadError> {
        self.expect_symbol("{")?;
        let mut tex = Texture {
            transform: DAffine3::IDENTITY,
            ..Texture::default()
        };
        if let Some(Value::Texture(q)) =
            self.take_named("a texture", |v| matches!(v, Value::Texture(_)))?
        {
            tex = (*q).clone();
        }
        loop {
            let Some((w, t)) = self.block_word("a texture's contents")? else {
                return Ok(tex);
            };
            match &*w {
                "pigment" => tex.pigment = Some(Rc::new(self.pigment_block()?)),
                "finish" => {
                    let f = self.finish_block()?;
                    tex.finish = tex.finish.overlaid(&f);
                }
                "normal" => tex.normal = Some(Rc::new(self.normal_block()?)),
                "material_map" | "texture_map" | "image_map" | "uv_mapping" | "checker"
                | "hexagon" | "gradient" | "bozo" | "marble" | "wood" | "granite" | "agate"
                | "spotted" | "brick" | "leopard" | "onion" | "radial" => {
                    self.warn(&t.loc, format!("a texture pattern (`{w}`) is not read by lucent; its first texture stands in"));
                    self.skip_texture_pattern(&mut tex)?;
                }
                _ => {
                    self.push_back(t.clone());
                    if let Some(m) = self.transform_item()? {
                        tex.transform = m * tex.transform;
                        if let Some(p) = &mut tex.pigment {
                            Rc::make_mut(p).transform = m * p.transform;
                        }
                        if let Some(n) = &mut tex.normal {
                            let n = Rc::make_mut(n);
                            n.pattern.transform = m * n.pattern.transform;
                        }
                    } else {
                        return Err(t.loc.error(format!("`{w}` is not part of a texture")));
                    }
                }
            }
        }
    }

    /// Reads a texture pattern's arguments and map, keeping the first texture.
    fn skip_texture_pattern(&mut self, tex: &mut Texture) -> Result<(), LoadError> {
        loop {
            let Some(t) = self.peek()?.cloned() else {
                return Ok(());
            };
            match &t.tok {
                Tok::Symbol("}") => return Ok(()),
                Tok::Symbol("{") => self.skip_braces()?,
                Tok::Word(w) if &**w == "texture" => {
                    self.next_token()?;
                    let inner = self.texture_block()?;
                    if tex.pigment.is_none() {
                        *tex = inner;
                    }
                }
                Tok::Word(w) if matches!(&**w, "texture_map" | "material_map") => {
                    self.next_token()?;
                    self.expect_symbol("{")?;
                    while !self.eat_symbol("}")? {
                        self.expect_symbol("[")?;
                        self.float()?;
                        self.eat_symbol(",")?;
                        if self.peek()?.is_some_and(|t| t.is_word("texture")) {
                            self.next_token()?;
                        }
                        let inner = if self.peek()?.is_some_and(|t| t.is_symbol("{")) {
                            self.texture_block()?
                        } else {
                            match self.next_token()? {
                                Some(Token {
                                    tok: Tok::Word(n),
                                    loc,
                                }) => match self.lookup(&n) {
                                    Some(Value::Texture(t)) => (**t).clone(),
                                    _ => return Err(loc.error(format!("`{n}` is not a texture"))),
                                },
                                _ => return Err(t.loc.error("expected a texture in the map")),
                            }
                        };
                        if tex.pigment.is_none() {
                            *tex = inner;
                        }
                        self.expect_symbol("]")?;
                    }
                }
                _ => {
                    self.next_token()?;
                }
            }
        }
    }

    /// Whether the next token starts a value (a number, vector, or an identifier of one).
    pub fn starts_value(&mut self) -> Result<bool, LoadError> {
        Ok(match self.peek()?.map(|t| t.tok.clone()) {
            Some(Tok::Number(_)) => true,
            Some(Tok::Symbol(s)) => matches!(s, "<" | "(" | "-" | "+"),
            Some(Tok::Word(w)) => {
                matches!(self.lookup(&w), Some(Value::Float(_) | Value::Vector(_)))
                    || w.starts_with("rgb")
                    || matches!(
                        &*w,
                        "color"
                            | "colour"
                            | "pi"
                            | "x"
                            | "y"
                            | "z"
                            | "on"
                            | "off"
                            | "true"
                            | "false"
                            | "yes"
                            | "no"
                    )
            }
            _ => false,
        })
    }

    /// Skips `{ … }` (the `{` next), nested braces and all.
    pub fn skip_braces(&mut self) -> Result<(), LoadError> {
        self.expect_symbol("{")?;
        let mut depth = 1;
        while depth > 0 {
            let t = self.expect_any("`}`")?;
            if t.is_symbol("{") {
                depth += 1;
            } else if t.is_symbol("}") {
                depth -= 1;
            }
        }
        Ok(())
    }

    /// Skips a `brick` pattern's colour entries.
    fn skip_entries(&mut self) -> Result<(), LoadError> {
        self.pattern_entries::<2>(&self.loc(), [0.0, 1.0])
            .map(|_| ())
    }
}

use super::lexer::Token;

/// POV-Ray's map when a pattern has none: black to white.
fn default_map() -> ColorMap {
    vec![
        (0.0, Vect::splat(0.0, 5)),
        (
            1.0,
            Vect {
                c: [1.0, 1.0, 1.0, 0.0, 0.0],
                n: 5,
            },
        ),
    ]
}
