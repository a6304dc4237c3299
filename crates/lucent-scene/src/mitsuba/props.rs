//! The parameters of one Mitsuba plugin (`<bsdf type="diffuse">…</bsdf>`): typed reads that
//! point at the value at fault, and what was left unread.
//!
//! A plugin element holds properties (`<float name="alpha" value="0.1"/>`), nested plugins
//! (`<bsdf type="diffuse"/>`, optionally with a `name`) and references to plugins declared
//! elsewhere (`<ref id="white"/>`), which are resolved here so that readers see a nested and a
//! referenced plugin alike.
//!
//! Mitsuba refuses a property its plugin does not read. lucent cannot tell a parameter it does
//! not model (a film's `pixel_format`) from a misspelt one without Mitsuba's whole vocabulary,
//! so what is left unread becomes a warning, not an error.

use super::numbers::{number, numbers};
use super::spectrum::{self, Role};
use super::transform;
use super::xml::{Element, Loc};
use crate::error::LoadError;
use glam::{DMat4, DVec3};
use lucent::Rgb;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;

/// The tags of properties.
pub const PROPERTY_TAGS: &[&str] = &[
    "boolean",
    "integer",
    "float",
    "string",
    "point",
    "vector",
    "rgb",
    "spectrum",
    "transform",
];

/// The tags of plugins (the classes Mitsuba knows, whether or not lucent reads them).
pub const PLUGIN_TAGS: &[&str] = &[
    "bsdf",
    "shape",
    "emitter",
    "sensor",
    "film",
    "sampler",
    "rfilter",
    "integrator",
    "texture",
    "medium",
    "phase",
    "volume",
];

/// Elements with an `id`, by id.
pub type Ids<'a> = HashMap<&'a str, &'a Element>;

/// The type of a plugin element: its `type`, or the default Mitsuba's loader gives the few
/// classes that have one.
pub fn plugin_type(el: &Element) -> Option<&str> {
    el.value("type").or(match el.tag.as_str() {
        "film" => Some("hdrfilm"),
        "sampler" => Some("independent"),
        "rfilter" => Some("gaussian"),
        _ => None,
    })
}

/// A colour, or a texture plugin where one is allowed.
pub enum Colorish<'a> {
    /// A constant colour.
    Color(Rgb),
    /// A `<texture>` element (nested or referenced).
    Texture(&'a Element),
}

/// A nested or referenced plugin.
#[derive(Clone, Copy)]
pub struct Child<'a> {
    /// Its `name` (the parameter it fills), if any.
    pub name: Option<&'a str>,
    /// The plugin element (for a reference: the element referred to).
    pub el: &'a Element,
    /// Where it appears in this plugin (for a reference: the `<ref>`).
    pub at: &'a Loc,
}

struct Prop<'a> {
    name: &'a str,
    el: &'a Element,
    read: Cell<bool>,
}

/// One plugin's properties and children.
pub struct Plugin<'a> {
    /// The plugin element.
    pub el: &'a Element,
    /// Its type (`diffuse`, `perspective`, …).
    pub kind: &'a str,
    props: Vec<Prop<'a>>,
    children: Vec<(Child<'a>, Cell<bool>)>,
    warnings: RefCell<Vec<String>>,
}

impl<'a> Plugin<'a> {
    /// The plugin `el`, its references resolved through `ids`.
    pub fn new(el: &'a Element, ids: &Ids<'a>) -> Result<Self, LoadError> {
        el.allow_attrs(&["type", "id", "name"])?;
        let kind = plugin_type(el).ok_or_else(|| {
            el.loc
                .error(format!("<{}> needs a `type` attribute", el.tag))
        })?;
        let mut props = Vec::new();
        let mut children = Vec::new();
        let mut names: HashMap<&str, &Loc> = HashMap::new();
        for c in &el.children {
            let tag = c.tag.as_str();
            let (name, child) = if PROPERTY_TAGS.contains(&tag) {
                let name = c.require("name")?.value.as_str();
                props.push(Prop {
                    name,
                    el: c,
                    read: Cell::new(false),
                });
                (Some(name), None)
            } else if tag == "ref" {
                c.allow_attrs(&["id", "name"])?;
                let id = c.require("id")?;
                let target = ids.get(id.value.as_str()).ok_or_else(|| {
                    id.loc
                        .error(format!("unknown id `{}`: no element has this id", id.value))
                })?;
                let name = c.value("name");
                (
                    name,
                    Some(Child {
                        name,
                        el: target,
                        at: &c.loc,
                    }),
                )
            } else if PLUGIN_TAGS.contains(&tag) {
                let name = c.value("name");
                (
                    name,
                    Some(Child {
                        name,
                        el: c,
                        at: &c.loc,
                    }),
                )
            } else {
                return Err(c
                    .loc
                    .error(format!("unexpected <{tag}> inside <{}>", el.tag)));
            };
            if let Some(name) = name
                && let Some(first) = names.insert(name, &c.loc)
            {
                return Err(c
                    .loc
                    .error(format!("`{name}` is given twice (first at {first})")));
            }
            if let Some(child) = child {
                children.push((child, Cell::new(false)));
            }
        }
        Ok(Self {
            el,
            kind,
            props,
            children,
            warnings: RefCell::new(Vec::new()),
        })
    }

    /// What this plugin is, for messages: `diffuse bsdf`.
    pub fn what(&self) -> String {
        format!("{} {}", self.kind, self.el.tag)
    }

    /// Adds a warning about this plugin.
    pub fn warn(&self, loc: &Loc, message: impl std::fmt::Display) {
        self.warnings.borrow_mut().push(loc.warning(message));
    }

    /// The property `name`, marked read; an error when a plugin fills that parameter instead.
    fn prop(&self, name: &str) -> Result<Option<&Prop<'a>>, LoadError> {
        if let Some((c, _)) = self.children.iter().find(|(c, _)| c.name == Some(name)) {
            return Err(c.at.error(format!(
                "`{name}` of the {} as a <{}> is not read by lucent (give a value)",
                self.what(),
                c.el.tag
            )));
        }
        let p = self.props.iter().find(|p| p.name == name);
        if let Some(p) = p {
            p.read.set(true);
        }
        Ok(p)
    }

    /// An error unless `p` is one of `tags`.
    fn expect(&self, p: &Prop, tags: &[&str]) -> Result<(), LoadError> {
        if tags.contains(&p.el.tag.as_str()) {
            return Ok(());
        }
        let wanted: Vec<String> = tags.iter().map(|t| format!("<{t}>")).collect();
        Err(p.el.loc.error(format!(
            "`{}` must be a {}, not a <{}>",
            p.name,
            wanted.join(" or "),
            p.el.tag
        )))
    }

    /// A number (`<float>` or `<integer>`).
    pub fn float(&self, name: &str) -> Result<Option<f64>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["float", "integer"])?;
        p.el.allow_attrs(&["name", "value"])?;
        let v = p.el.require("value")?;
        number(&v.value, &v.loc).map(Some)
    }

    /// A number, or `default`.
    pub fn float_or(&self, name: &str, default: f64) -> Result<f64, LoadError> {
        Ok(self.float(name)?.unwrap_or(default))
    }

    /// An `<integer>`, with where its value is.
    pub fn integer(&self, name: &str) -> Result<Option<(i64, &'a Loc)>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["integer"])?;
        p.el.allow_attrs(&["name", "value"])?;
        let v = p.el.require("value")?;
        let i = v.value.trim().parse::<i64>().map_err(|_| {
            v.loc
                .error(format!("cannot read `{}` as an integer", v.value))
        })?;
        Ok(Some((i, &v.loc)))
    }

    /// A `<boolean>` (`true` or `false`, in any case).
    pub fn boolean(&self, name: &str) -> Result<Option<bool>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["boolean"])?;
        p.el.allow_attrs(&["name", "value"])?;
        let v = p.el.require("value")?;
        match v.value.to_lowercase().as_str() {
            "true" => Ok(Some(true)),
            "false" => Ok(Some(false)),
            _ => Err(v
                .loc
                .error(format!("a boolean is `true` or `false`, not `{}`", v.value))),
        }
    }

    /// A `<string>`, with where its value is.
    pub fn string(&self, name: &str) -> Result<Option<(&'a str, &'a Loc)>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["string"])?;
        p.el.allow_attrs(&["name", "value"])?;
        let v = p.el.require("value")?;
        Ok(Some((v.value.as_str(), &v.loc)))
    }

    /// The `<string>` `name`, or an error at the plugin.
    pub fn required_string(&self, name: &str) -> Result<(&'a str, &'a Loc), LoadError> {
        self.string(name)?.ok_or_else(|| {
            self.el
                .loc
                .error(format!("the {} needs a string `{name}`", self.what()))
        })
    }

    /// The property `name` as it is written: a number or a string (IORs take both).
    pub fn number_or_name(&self, name: &str) -> Result<Option<NumberOrName<'a>>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["float", "integer", "string"])?;
        p.el.allow_attrs(&["name", "value"])?;
        let v = p.el.require("value")?;
        Ok(Some(if p.el.tag == "string" {
            NumberOrName::Name(&v.value, &v.loc)
        } else {
            NumberOrName::Number(number(&v.value, &v.loc)?, &v.loc)
        }))
    }

    /// A colour that is not emitted (a reflectance, or a conductor's η or k): `<rgb>`,
    /// `<spectrum>`, or a number for grey.
    pub fn color(&self, name: &str) -> Result<Option<Rgb>, LoadError> {
        self.color_as(name, self.role(name))
    }

    /// A colour that is not emitted, or `default` grey.
    pub fn color_or(&self, name: &str, default: f32) -> Result<Rgb, LoadError> {
        Ok(self.color(name)?.unwrap_or(Rgb::gray(default)))
    }

    /// An emitted colour (an emitter's `radiance`, `intensity` or `irradiance`), or `default`
    /// grey: a `<spectrum>` becomes RGB as Mitsuba converts an emitted one, which differs from
    /// a reflectance (see `mitsuba/spectrum.rs`).
    pub fn emitted_color_or(&self, name: &str, default: f32) -> Result<Rgb, LoadError> {
        Ok(self
            .color_as(name, Role::Emitted)?
            .unwrap_or(Rgb::gray(default)))
    }

    fn color_as(&self, name: &str, role: Role) -> Result<Option<Rgb>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.color_of(p, role).map(Some)
    }

    /// The role of this plugin's colour `name` when it is not emitted. Mitsuba's conductors read
    /// `eta` and `k` as unbounded textures, which leaves a spectrum above 1 unclamped; every
    /// other such colour lucent reads is bounded. (The BSDF reader could say so at its call,
    /// as the emitters do; until it does, this keeps the rule in one place.)
    fn role(&self, name: &str) -> Role {
        let unbounded = (self.el.tag == "bsdf"
            && matches!(self.kind, "conductor" | "roughconductor")
            && matches!(name, "eta" | "k"))
            || (self.el.tag == "medium" && name == "sigma_t");
        if unbounded {
            Role::Unbounded
        } else {
            Role::Reflectance
        }
    }

    /// A colour or a `<texture>` plugin.
    pub fn color_or_texture(&self, name: &str) -> Result<Option<Colorish<'a>>, LoadError> {
        let child = self.children.iter().find(|(c, _)| c.name == Some(name));
        if let Some((c, read)) = child {
            read.set(true);
            if c.el.tag != "texture" {
                return Err(c.at.error(format!(
                    "`{name}` must be a colour or a <texture>, not a <{}>",
                    c.el.tag
                )));
            }
            return Ok(Some(Colorish::Texture(c.el)));
        }
        self.color(name).map(|c| c.map(Colorish::Color))
    }

    fn color_of(&self, p: &Prop, role: Role) -> Result<Rgb, LoadError> {
        self.expect(p, &["rgb", "spectrum", "float", "integer"])?;
        let rgb = match p.el.tag.as_str() {
            "rgb" => {
                p.el.allow_attrs(&["name", "value"])?;
                let v = p.el.require("value")?;
                match numbers(&v.value, &v.loc)?[..] {
                    [g] => Rgb::gray(g as f32),
                    [r, g, b] => Rgb::new(r as f32, g as f32, b as f32),
                    _ => {
                        return Err(v.loc.error(format!(
                            "an <rgb> takes one or three numbers, not `{}`",
                            v.value
                        )));
                    }
                }
            }
            "spectrum" => {
                let (rgb, warnings) = spectrum::read(p.el, p.name, role)?;
                self.warnings.borrow_mut().extend(warnings);
                rgb
            }
            _ => {
                p.el.allow_attrs(&["name", "value"])?;
                let v = p.el.require("value")?;
                Rgb::gray(number(&v.value, &v.loc)? as f32)
            }
        };
        if rgb.r < 0.0 || rgb.g < 0.0 || rgb.b < 0.0 {
            return Err(p
                .el
                .loc
                .error(format!("`{}`: colours must not be negative", p.name)));
        }
        Ok(rgb)
    }

    /// A `<point>` or `<vector>`: `x`, `y`, `z` (missing ones 0) or `value` (one or three
    /// numbers).
    pub fn vector(&self, name: &str) -> Result<Option<DVec3>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["point", "vector"])?;
        p.el.allow_attrs(&["name", "value", "x", "y", "z"])?;
        transform::xyz(p.el, 0.0).map(Some)
    }

    /// A `<transform>`, with where it is.
    pub fn transform(&self, name: &str) -> Result<Option<(DMat4, &'a Loc)>, LoadError> {
        let Some(p) = self.prop(name)? else {
            return Ok(None);
        };
        self.expect(p, &["transform"])?;
        Ok(Some((transform::parse(p.el)?, &p.el.loc)))
    }

    /// The nested or referenced plugins of class `tag` (marked read).
    pub fn take(&self, tag: &str) -> Vec<Child<'a>> {
        self.children
            .iter()
            .filter(|(c, _)| c.el.tag == tag)
            .map(|(c, read)| {
                read.set(true);
                *c
            })
            .collect()
    }

    /// The warnings gathered, then one for each property and plugin left unread, except the
    /// properties in `silent` (those that change nothing lucent renders, such as clip planes).
    pub fn finish(self, warnings: &mut Vec<String>, silent: &[&str]) {
        let what = self.what();
        warnings.append(&mut self.warnings.borrow_mut());
        for p in &self.props {
            if !p.read.get() && !silent.contains(&p.name) {
                warnings.push(
                    p.el.loc
                        .warning(format!("`{}` of the {what} is not read by lucent", p.name)),
                );
            }
        }
        for (c, read) in &self.children {
            if !read.get() {
                let kind = plugin_type(c.el).unwrap_or("?");
                warnings.push(c.at.warning(format!(
                    "the {kind} {} inside the {what} is not read by lucent",
                    c.el.tag
                )));
            }
        }
    }
}

/// A parameter given as a number or by name.
pub enum NumberOrName<'a> {
    /// A number, and where it is.
    Number(f64, &'a Loc),
    /// A name, and where it is.
    Name(&'a str, &'a Loc),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mitsuba::xml::parse_str;

    fn with<T>(body: &str, f: impl FnOnce(&Plugin) -> T) -> T {
        let text =
            format!("<scene version=\"3.0.0\">\n<bsdf type=\"x\">\n{body}\n</bsdf>\n</scene>");
        let root = parse_str("props.xml", &text).unwrap();
        let plugin = Plugin::new(&root.children[0], &Ids::new()).unwrap();
        f(&plugin)
    }

    fn message(e: LoadError) -> String {
        let (l, c) = e.position.unwrap();
        format!("{l}:{c} {}", e.message)
    }

    #[test]
    fn numbers_must_be_finite() {
        let e = with(r#"<float name="a" value="nan"/>"#, |p| {
            p.float("a").unwrap_err()
        });
        assert_eq!(message(e), "3:24 expected a finite number, found `nan`");
        let e = with(r#"<float name="a" value="-inf"/>"#, |p| {
            p.float("a").unwrap_err()
        });
        assert_eq!(message(e), "3:24 expected a finite number, found `-inf`");
        let e = with(r#"<float name="a" value="1e39"/>"#, |p| {
            p.float("a").unwrap_err()
        });
        assert!(message(e).starts_with("3:24 `1e39` is beyond single precision"));
        let e = with(r#"<rgb name="c" value="1, NaN, 0"/>"#, |p| {
            p.color("c").unwrap_err()
        });
        assert_eq!(message(e), "3:22 expected a finite number, found `NaN`");
        assert_eq!(
            with(r#"<integer name="a" value="3"/>"#, |p| p
                .float("a")
                .unwrap()),
            Some(3.0)
        );
    }

    #[test]
    fn colours_from_rgb_spectrum_and_numbers() {
        let c = with(r#"<rgb name="c" value="0.1, 0.2 0.3"/>"#, |p| {
            p.color("c").unwrap()
        });
        assert_eq!(c, Some(Rgb::new(0.1, 0.2, 0.3)));
        let c = with(r#"<rgb name="c" value="0.5"/>"#, |p| p.color("c").unwrap());
        assert_eq!(c, Some(Rgb::gray(0.5)));
        let c = with(r#"<spectrum name="c" value="2"/>"#, |p| {
            p.color("c").unwrap()
        });
        assert_eq!(c, Some(Rgb::gray(2.0)));
        // A flat list: grey as a reflectance, pinkish as a light (Mitsuba 3.9.1's colours; the
        // conversion's own tests are in spectrum.rs).
        let flat = r#"<spectrum name="c" value="400:0.5, 700:0.5"/>"#;
        let (c, warnings) = with(flat, |p| (p.color("c").unwrap(), p.warnings.take()));
        let c = c.unwrap();
        assert!(
            (c.r - 0.497671).abs() < 1e-6 && (c.g - 0.499878).abs() < 1e-6,
            "{c:?}"
        );
        assert!(warnings.is_empty(), "{warnings:?}");
        let c = with(flat, |p| p.emitted_color_or("c", 1.0).unwrap());
        assert!(
            (c.r - 0.599847).abs() < 1e-6 && (c.b - 0.451722).abs() < 1e-6,
            "{c:?}"
        );
        let c = with(r#"<spectrum name="c" value="2"/>"#, |p| {
            p.emitted_color_or("c", 1.0).unwrap()
        });
        assert!((c.r - 2.0 * 1.204794).abs() < 1e-6, "{c:?}");
        let c = with("", |p| p.emitted_color_or("c", 3.0).unwrap());
        assert_eq!(c, Rgb::gray(3.0));
        let e = with(r#"<rgb name="c" value="1 2"/>"#, |p| {
            p.color("c").unwrap_err()
        });
        assert!(message(e).starts_with("3:22 an <rgb> takes one or three numbers"));
        let e = with(r#"<rgb name="c" value="-1"/>"#, |p| {
            p.color("c").unwrap_err()
        });
        assert_eq!(message(e), "3:1 `c`: colours must not be negative");
    }

    #[test]
    fn types_are_checked() {
        let e = with(r#"<string name="a" value="x"/>"#, |p| {
            p.float("a").unwrap_err()
        });
        assert_eq!(
            message(e),
            "3:1 `a` must be a <float> or <integer>, not a <string>"
        );
        let e = with(r#"<float name="a" value="1"/>"#, |p| {
            p.integer("a").unwrap_err()
        });
        assert_eq!(message(e), "3:1 `a` must be a <integer>, not a <float>");
        let e = with(r#"<boolean name="a" value="yes"/>"#, |p| {
            p.boolean("a").unwrap_err()
        });
        assert_eq!(message(e), "3:26 a boolean is `true` or `false`, not `yes`");
        assert_eq!(
            with(r#"<boolean name="a" value="TRUE"/>"#, |p| p
                .boolean("a")
                .unwrap()),
            Some(true)
        );
    }

    #[test]
    fn vectors_take_xyz_or_value() {
        let v = with(r#"<point name="p" x="1" z="3"/>"#, |p| {
            p.vector("p").unwrap()
        });
        assert_eq!(v, Some(DVec3::new(1.0, 0.0, 3.0)));
        let v = with(r#"<vector name="p" value="1, 2, 3"/>"#, |p| {
            p.vector("p").unwrap()
        });
        assert_eq!(v, Some(DVec3::new(1.0, 2.0, 3.0)));
        let e = with(r#"<point name="p" value="1" x="2"/>"#, |p| {
            p.vector("p").unwrap_err()
        });
        assert!(message(e).starts_with("3:1 give either `value` or `x`, `y`, `z`"));
    }

    #[test]
    fn unread_properties_are_warnings_and_duplicates_errors() {
        let mut warnings = Vec::new();
        let text = "<scene version=\"3.0.0\">\n<bsdf type=\"x\">\n<float name=\"a\" value=\"1\"/><float name=\"b\" value=\"2\"/>\n</bsdf>\n</scene>";
        let root = parse_str("unread.xml", text).unwrap();
        let p = Plugin::new(&root.children[0], &Ids::new()).unwrap();
        p.float("a").unwrap();
        p.finish(&mut warnings, &[]);
        assert_eq!(warnings.len(), 1);
        assert!(
            warnings[0].ends_with("unread.xml:3:28: `b` of the x bsdf is not read by lucent"),
            "{}",
            warnings[0]
        );

        let text = "<scene version=\"3.0.0\">\n<bsdf type=\"x\">\n<float name=\"a\" value=\"1\"/>\n<rgb name=\"a\" value=\"1\"/>\n</bsdf>\n</scene>";
        let root = parse_str("dup.xml", text).unwrap();
        let e = Plugin::new(&root.children[0], &Ids::new()).err().unwrap();
        assert!(message(e).starts_with("4:1 `a` is given twice (first at "));
    }
}
