//! Mitsuba 3 scene files (XML) read into a [`SceneDesc`].
//!
//! ```xml
//! <scene version="3.0.0">
//!     <default name="spp" value="64"/>
//!     <sensor type="perspective">
//!         <float name="fov" value="39.3"/>
//!         <transform name="to_world">
//!             <lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/>
//!         </transform>
//!         <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
//!         <film type="hdrfilm"><integer name="width" value="256"/><integer name="height" value="256"/></film>
//!     </sensor>
//!     <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8"/></bsdf>
//!     <shape type="rectangle">
//!         <transform name="to_world"><rotate x="1" angle="-90"/><translate y="-1"/></transform>
//!         <ref id="white"/>
//!     </shape>
//!     <shape type="sphere">
//!         <float name="radius" value="0.3"/>
//!         <emitter type="area"><rgb name="radiance" value="10"/></emitter>
//!     </shape>
//! </scene>
//! ```
//!
//! The reading goes in stages, as Mitsuba's own loader does:
//!
//! 1. [`xml`]: the files are read into one tree, `<include>`s spliced in and `$name`s
//!    substituted from the `<default>`s;
//! 2. every plugin's type is checked and every `id` indexed, so that an unknown type is an
//!    error wherever it stands, even inside something lucent would otherwise skip;
//! 3. the scene's children are read in document order: [`sensor`] (camera, film, sampler)
//!    and the integrator, [`shape`]s (with their [`bsdf`]s as materials and their media),
//!    [`emitter`]s; a `<medium>` is read where a shape or the sensor first names it
//!    (`medium.rs`).
//!
//! Conventions: file names start from the main XML file's folder (`<include>`s too, as with
//! Mitsuba's file resolver) and are kept as written, so the description's relative names start
//! there; every one passes [`crate::paths::resolve`], which enforces `--sandbox`, and must name
//! an existing file. Errors name the file, line and column of the element or value at fault, in
//! the included file when that is where it is; so what the build would refuse (a radius, a
//! resolution, a camera out of its range) is refused here first. What lucent reads but cannot
//! render as Mitsuba would (an approximation, an unread parameter) becomes a warning naming the
//! place, one line per plugin and reason.
//! The description itself carries no positions (its spans are empty): one description may come
//! from several files.
//!
//! Not read: heterogeneous media and grids, textures other than `bitmap`, `checkerboard` and
//! `mesh_attribute`, spectra from files, sensors other than `perspective`, `thinlens` and
//! `orthographic`, BSDFs, shapes and emitters beyond those listed in each module, `<alias>`, and
//! Mitsuba 0.x files (version < 2, whose parameter names differ). `<path>` folders are searched
//! for the files that shapes, textures and emitters name (not for `<include>`s).

pub mod bsdf;
pub mod emitter;
pub mod ior;
mod medium;
mod numbers;
pub mod props;
pub mod sensor;
pub mod shape;
mod spectrum;
pub mod texture;
pub mod transform;
pub mod xml;

use crate::desc::{ImageDesc, IntegratorName, RenderDesc, SceneDesc, WorldDesc};
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::import::{Imported, placeholder_camera};
use crate::paths::{LoadOptions, resolve};
use props::{Ids, PLUGIN_TAGS, PROPERTY_TAGS, Plugin, plugin_type};
use std::collections::hash_map::Entry;
use std::path::{Path, PathBuf};
use toml::Spanned;
use xml::{Element, Loc};

/// The scene of a Mitsuba 3 XML file as a description; relative file names in it start from
/// the XML file's folder.
///
/// The bytes of every XML file read (the scene and its includes) are added to `inputs`; mesh
/// and image files are read later, by the build. Without a `<sensor>`, `camera_given` is false
/// and the camera a placeholder.
pub fn import_mitsuba(
    path: &Path,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Imported, LoadError> {
    let root = xml::load(path, options, inputs)?;
    let base_dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    convert_scene(&root, base_dir, options)
}

/// [`import_mitsuba`] of XML given as text: `label` names it in errors, and relative file names
/// start from `base_dir`.
pub fn import_mitsuba_text(
    label: &Path,
    base_dir: PathBuf,
    text: String,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Imported, LoadError> {
    let root = xml::load_text(label, base_dir.clone(), text, options, inputs)?;
    convert_scene(&root, base_dir, options)
}

/// The description of a loaded `<scene>`.
fn convert_scene(
    root: &Element,
    base_dir: PathBuf,
    options: &LoadOptions,
) -> Result<Imported, LoadError> {
    let mut ids = Ids::new();
    index(root, &mut ids)?;
    let mut cx = Convert {
        materials: bsdf::Materials::new(ids.keys().copied()),
        ids,
        options: *options,
        base_dir,
        warnings: Vec::new(),
        environment: None,
        search: Vec::new(),
        used_area_emitters: Vec::new(),
        media: medium::Media::default(),
    };
    // `<path>` folders, where relative file names are also looked for: gathered first, so that
    // they hold for the whole file.
    for el in root.children.iter().filter(|el| el.tag == "path") {
        el.allow_attrs(&["value"])?;
        let folder = el.require("value")?;
        resolve(&cx.base_dir, &folder.value, &cx.options)
            .map_err(|message| folder.loc.error(message))?;
        cx.search
            .push(folder.value.trim_end_matches('/').to_string());
    }
    let mut declared_emitters = Vec::new();
    let (width, height) = sensor::DEFAULT_FILM;
    let mut desc = SceneDesc {
        image: ImageDesc {
            width: Spanned::new(0..0, width),
            height: Spanned::new(0..0, height),
            samples: Spanned::new(0..0, sensor::DEFAULT_SAMPLES),
            gamma: None,
            raw: None,
        },
        camera: placeholder_camera(),
        world: WorldDesc::default(),
        render: RenderDesc::default(),
        materials: Vec::new(),
        lights: Vec::new(),
        objects: Vec::new(),
        media: Vec::new(),
    };
    let mut first_sensor: Option<&Loc> = None;
    let mut first_integrator: Option<&Loc> = None;
    let mut declared = Vec::new();
    for el in &root.children {
        match el.tag.as_str() {
            "sensor" => match first_sensor {
                Some(first) => cx.warnings.push(el.loc.warning(format!(
                    "another sensor: lucent renders the first one (at {first})"
                ))),
                None => {
                    sensor::read(&mut cx, el, &mut desc)?;
                    first_sensor = Some(&el.loc);
                }
            },
            "integrator" => {
                if let Some(first) = first_integrator {
                    return Err(el
                        .loc
                        .error(format!("a second integrator (the first is at {first})")));
                }
                sensor::integrator(&mut cx, el, &mut desc)?;
                first_integrator = Some(&el.loc);
            }
            "shape" => {
                let object = shape::read(&mut cx, el)?;
                desc.objects.push(Spanned::new(0..0, object));
            }
            // An area emitter with an id is declared for shapes to refer to.
            "emitter" if plugin_type(el) == Some("area") && el.value("id").is_some() => {
                declared_emitters.push(el);
            }
            "emitter" => {
                let light = emitter::read(&mut cx, el)?;
                desc.lights.push(Spanned::new(0..0, light));
            }
            "path" => {} // read above
            "bsdf" | "texture" | "medium" => declared.push(el),
            "film" | "sampler" => {
                return Err(el
                    .loc
                    .error(format!("a <{}> belongs inside a <sensor>", el.tag)));
            }
            "rfilter" => return Err(el.loc.error("an <rfilter> belongs inside a <film>")),
            tag if PROPERTY_TAGS.contains(&tag) => {
                let name = el.value("name").unwrap_or("?");
                cx.warnings.push(
                    el.loc
                        .warning(format!("`{name}` of the scene is not read by lucent")),
                );
            }
            tag => {
                return Err(el
                    .loc
                    .error(format!("<{tag}> directly in <scene> is not read by lucent")));
            }
        }
    }
    // Without an <integrator> Mitsuba uses its path tracer, unbounded; so does lucent.
    if first_integrator.is_none() {
        desc.render.integrator = IntegratorName::Path;
    }
    // Declarations no shape used are still checked, as Mitsuba instantiates them all.
    for el in declared {
        if el.value("id").is_none() {
            cx.warnings.push(el.loc.warning(format!(
                "a <{}> without an id at the top of the scene is never used",
                el.tag
            )));
        } else if cx.materials.seen(el) {
            // Checked where it was used.
        } else if el.tag == "medium" {
            medium::named(&mut cx, el)?;
        } else if el.tag == "bsdf" {
            bsdf::describe(&mut cx, el, 0)?;
        } else {
            texture::texture(&mut cx, el)?;
        }
    }
    for el in declared_emitters {
        if !cx.used_area_emitters.contains(&std::ptr::from_ref(el)) {
            cx.warnings.push(el.loc.warning(
                "an area emitter declared at the top of the scene that no shape refers to emits nothing",
            ));
        }
    }
    // A plugin read twice (a referenced texture, a BSDF used alone and inside a twosided)
    // would repeat its warnings word for word.
    let mut said = std::collections::HashSet::new();
    cx.warnings.retain(|w| said.insert(w.clone()));
    desc.media = std::mem::take(&mut cx.media.list)
        .into_iter()
        .map(|m| Spanned::new(0..0, m))
        .collect();
    desc.materials = cx
        .materials
        .list
        .into_iter()
        .map(|m| Spanned::new(0..0, m))
        .collect();
    Ok(Imported {
        desc,
        camera_given: first_sensor.is_some(),
        warnings: cx.warnings,
        lit_as_given: false,
    })
}

/// What the readers share.
pub struct Convert<'a> {
    /// Elements by `id`.
    pub ids: Ids<'a>,
    /// Sandboxing of file names.
    pub options: LoadOptions,
    /// The main XML file's folder.
    pub base_dir: PathBuf,
    /// Warnings so far, one line each.
    pub warnings: Vec<String>,
    /// The materials made so far.
    pub materials: bsdf::Materials,
    /// Where the environment emitter is, once one has been read.
    pub environment: Option<Loc>,
    /// The `<path>` folders (relative to `base_dir`), where file names are looked for after
    /// `base_dir` itself.
    pub search: Vec<String>,
    /// The area emitters shapes have taken, declared at the top of the scene or not.
    pub used_area_emitters: Vec<*const Element>,
    /// The media read so far.
    pub media: medium::Media,
}

impl<'a> Convert<'a> {
    /// The plugin `el`, its references resolved.
    pub fn plugin(&self, el: &'a Element) -> Result<Plugin<'a>, LoadError> {
        Plugin::new(el, &self.ids)
    }

    /// The file name `name` (at `loc`) as the description keeps it, after `--sandbox`'s check;
    /// the file must exist. `what` names it in messages (`mesh`, `image`).
    ///
    /// The build reads the file later, but its errors cannot point into the XML (the
    /// description carries no positions), so a missing file is refused here, at its name.
    pub fn file_name(&self, name: &str, loc: &Loc, what: &str) -> Result<String, LoadError> {
        if name.trim().is_empty() {
            return Err(loc.error(format!("the {what} file name is empty")));
        }
        let path =
            resolve(&self.base_dir, name, &self.options).map_err(|message| loc.error(message))?;
        if path.is_file() {
            return Ok(name.to_string());
        }
        for folder in &self.search {
            let candidate = format!("{folder}/{name}");
            let found = resolve(&self.base_dir, &candidate, &self.options)
                .map_err(|message| loc.error(message))?;
            if found.is_file() {
                return Ok(candidate);
            }
        }
        let also = if self.search.is_empty() {
            String::new()
        } else {
            format!(" (nor in the <path> folders {})", self.search.join(", "))
        };
        Err(loc.error(format!("{what} file `{}` not found{also}", path.display())))
    }
}

/// The types lucent reads for plugins of class `tag`; `None` for classes it does not read.
fn known_types(tag: &str) -> Option<&'static [&'static str]> {
    Some(match tag {
        "bsdf" => bsdf::TYPES,
        "shape" => shape::TYPES,
        "emitter" => emitter::TYPES,
        "sensor" => sensor::SENSORS,
        "film" => sensor::FILMS,
        "sampler" => sensor::SAMPLERS,
        "rfilter" => sensor::FILTERS,
        "integrator" => sensor::INTEGRATORS,
        "texture" => texture::TYPES,
        "medium" => medium::TYPES,
        "phase" => medium::PHASES,
        "volume" => medium::VOLUMES,
        _ => return None,
    })
}

/// The error for the plugin `el` of a type lucent does not read.
pub fn unknown_type(el: &Element, kind: &str) -> LoadError {
    let known = known_types(&el.tag).unwrap_or(&[]);
    el.loc.error(format!(
        "unknown {} type `{kind}` (lucent reads: {})",
        el.tag,
        known.join(", ")
    ))
}

/// Checks the type of every plugin under `el` and indexes the `id`s, refusing duplicates.
fn index<'a>(el: &'a Element, ids: &mut Ids<'a>) -> Result<(), LoadError> {
    for c in &el.children {
        if PLUGIN_TAGS.contains(&c.tag.as_str()) {
            let Some(known) = known_types(&c.tag) else {
                return Err(c.loc.error(format!("<{}> is not read by lucent", c.tag)));
            };
            let kind = plugin_type(c)
                .ok_or_else(|| c.loc.error(format!("<{}> needs a `type` attribute", c.tag)))?;
            if !known.contains(&kind) {
                return Err(unknown_type(c, kind));
            }
            if let Some(id) = c.attr("id") {
                match ids.entry(id.value.as_str()) {
                    Entry::Occupied(first) => {
                        return Err(id.loc.error(format!(
                            "the id `{}` is given twice (first at {})",
                            id.value,
                            first.get().loc
                        )));
                    }
                    Entry::Vacant(slot) => {
                        slot.insert(c);
                    }
                }
            }
        }
        index(c, ids)?;
    }
    Ok(())
}
