//! From `SceneDesc` to a render-time `Scene`: names resolved, ranges checked, meshes loaded.
//!
//! Every error points at the value at fault in the scene file (or at the line of a mesh file).

mod csg;
mod image_lights;
mod lights;
mod material_keys;
pub mod materials;
mod media;
mod motion;
mod objects;
mod photometric;
pub mod shapes;
mod solids;
pub mod textures;

use crate::desc::settings::{
    FilterName, FilterSamplingName, RenderDesc, SamplingName, TriangleTestName,
};
use crate::desc::texture::Encoding;
use crate::desc::{IntegratorName, SceneDesc};
use crate::error::{LoadError, Source};
use crate::hash::Fingerprint;
use crate::mesh_file::MeshFiles;
use crate::paths::LoadOptions;
use glam::DVec3;
use lucent::Rgb;
use lucent::accel::AccelKind;
use lucent::camera::Camera;
use lucent::film::Display;
use lucent::film::filter::Filter;
use lucent::film::splat::FilterSampling;
use lucent::integrator::{DebugView, Integrator, PathTracer, Sppm, Whitted};
use lucent::render::{RenderSettings, Sampling};
use lucent::scene::Shutter;
use lucent::scene::{Scene, SceneBuilder};
use lucent::schedule::adaptive::{Adaptive, MAX_DEPTH as ADAPTIVE_MAX_DEPTH};
use lucent::shape::TriangleTest;
use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Largest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 65_536;
/// Largest number of pixels in an image: 8192 × 8192. A render holds about 32 bytes per pixel
/// at its peak (the film's sums and weights, then the linear image and its encoding while the
/// file is written), 2 GiB at this size.
pub const MAX_PIXELS: u64 = 1 << 26;
/// Sphere radii outside this range are refused: in single precision, the square of the radius
/// would underflow or overflow and the sphere would silently vanish.
pub const RADIUS_RANGE: std::ops::RangeInclusive<f32> = 1e-8..=1e15;
/// Largest number of samples per pixel.
pub const MAX_SAMPLES: u32 = 1 << 20;
/// Deepest recursion allowed.
pub const MAX_DEPTH: u32 = 1000;
/// Largest `aa_block` (a quadtree block of 2^4 = 16 pixels on a side).
pub const MAX_AA_BLOCK: u32 = 4;
/// The narrowest reconstruction filter, in pixels. A narrower one weighs little but the
/// pixel's centre, and in single precision it stops working at all: a Gaussian (σ 0.5) of
/// radius below about 2·10⁻⁴ is zero at its centre, and a Mitchell filter of radius 10⁻⁴⁵ has
/// no integral to sample from.
pub const MIN_FILTER_RADIUS: f32 = 0.01;
/// The widest reconstruction filter, in pixels.
pub const MAX_FILTER_RADIUS: f32 = lucent::film::filter::MAX_RADIUS;
/// The longest time limit, in seconds: a year.
pub const MAX_TIME_LIMIT: f32 = 365.0 * 24.0 * 3600.0;

/// A scene ready to render, with the render settings its file gives.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The scene.
    pub scene: Scene,
    /// Integrator, samples and seed from the file (threads: all).
    pub settings: RenderSettings,
    /// Fingerprint of the inputs: the scene text and every file read.
    pub inputs: u64,
    /// What is rendered other than as written (one line each, naming the file).
    pub warnings: Vec<String>,
    /// How the image's values are written as pixels (`[image] gamma`, `raw`).
    pub display: Display,
}

/// What building needs besides the description: where files are, what was read, and the
/// scene being assembled.
pub struct Context<'a> {
    /// The scene file, for errors.
    pub source: &'a Source<'a>,
    /// The folder relative file names start from.
    pub base_dir: &'a Path,
    /// Path rules (`--sandbox`).
    pub options: &'a LoadOptions,
    /// Fingerprint of everything read.
    pub inputs: Fingerprint,
    /// Warnings so far.
    pub warnings: Vec<String>,
    /// The scene being assembled.
    pub builder: SceneBuilder,
    /// Mesh files parsed so far.
    pub mesh_files: crate::mesh_file::MeshFiles,
    images: HashMap<(PathBuf, Option<u32>, [u32; 3], Encoding), u32>,
    /// Rough coats already integrated, by (distribution, α, η) bits.
    pub coats: HashMap<(u8, u32, u32), std::sync::Arc<lucent::bsdf::RoughCoat>>,
    sheen_albedo: Option<std::sync::Arc<lucent::bsdf::SheenAlbedo>>,
    /// Where the built scene's zero is in the file's world ([`scene_origin`]).
    pub origin: DVec3,
}

impl Context<'_> {
    /// The file's world point `p` in the built scene's coordinates.
    pub fn local(&self, p: DVec3) -> glam::Vec3 {
        (p - self.origin).as_vec3()
    }

    /// The sheen's albedo table, tabulated once for every material with sheen.
    pub fn sheen_albedo(&mut self) -> std::sync::Arc<lucent::bsdf::SheenAlbedo> {
        self.sheen_albedo
            .get_or_insert_with(|| std::sync::Arc::new(lucent::bsdf::SheenAlbedo::new()))
            .clone()
    }

    /// Resolves a file name from the scene (relative to its folder, within `--sandbox`), or an
    /// error at `span`.
    pub fn path(&self, name: &str, span: Range<usize>) -> Result<PathBuf, LoadError> {
        crate::paths::resolve(self.base_dir, name, self.options)
            .map_err(|e| self.source.error(span, e))
    }

    /// The path and bytes of the file the key `file` names (a `what` file: "IES file"),
    /// counted among the scene's inputs; an error at the key when it cannot be read.
    pub fn read_named(
        &mut self,
        file: &Spanned<String>,
        what: &str,
    ) -> Result<(PathBuf, Vec<u8>), LoadError> {
        let path = self.path(file.get_ref(), file.span())?;
        let bytes = crate::input::read(&path).map_err(|e| {
            self.source
                .error(file.span(), format!("{what} `{}`: {e}", path.display()))
        })?;
        self.inputs.add(&bytes);
        Ok((path, bytes))
    }

    /// The scene's index of the image file `name`, decoded by `encoding` and scaled by
    /// `scale`, read once.
    pub fn image(
        &mut self,
        name: &str,
        span: Range<usize>,
        scale: Rgb,
        encoding: Encoding,
    ) -> Result<u32, LoadError> {
        self.image_in(name, None, span, scale, encoding)
    }

    /// [`Context::image`] of the file `name`, or of image `gltf_image` held inside it (a glTF
    /// or GLB file).
    pub fn image_in(
        &mut self,
        name: &str,
        gltf_image: Option<u32>,
        span: Range<usize>,
        scale: Rgb,
        encoding: Encoding,
    ) -> Result<u32, LoadError> {
        let path = self.path(name, span.clone())?;
        if let Err(why) = crate::input::refused(&path) {
            return Err(self
                .source
                .error(span, format!("image file `{}` {why}", path.display())));
        }
        let key = (
            std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone()),
            gltf_image,
            [scale.r, scale.g, scale.b].map(f32::to_bits),
            encoding,
        );
        if let Some(&id) = self.images.get(&key) {
            return Ok(id);
        }
        let mut image = match gltf_image {
            None => crate::images::read_image(&path, encoding, &mut self.inputs)?,
            Some(index) => {
                if !matches!(
                    crate::mesh_file::extension(&path).as_deref(),
                    Some("gltf" | "glb")
                ) {
                    return Err(self.source.error(
                        span,
                        format!(
                            "`gltf_image` reads an image inside a glTF or GLB file; `{name}` is not one"
                        ),
                    ));
                }
                let file = self
                    .mesh_files
                    .gltf(&path, self.options, &mut self.inputs)?;
                let bytes = file.embedded_image(index)?;
                crate::images::decode_image(&bytes, encoding)
                    .map_err(|e| LoadError::file(&path, format!("image {index}: {e}")))?
            }
        };
        if scale != Rgb::WHITE {
            image = image.scaled(scale);
        }
        let id = self.builder.image(image);
        self.images.insert(key, id);
        Ok(id)
    }
}

/// Builds `desc`, read from `source`; files are found relative to `base_dir`.
pub fn build(desc: &SceneDesc, source: &Source, base_dir: &Path) -> Result<Loaded, LoadError> {
    build_with(desc, source, base_dir, &LoadOptions::default())
}

/// [`build`] with path rules.
pub fn build_with(
    desc: &SceneDesc,
    source: &Source,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<Loaded, LoadError> {
    build_with_files(desc, source, base_dir, options, MeshFiles::default())
}

/// [`build_with`], taking meshes from `files` (already parsed) before reading their files.
pub fn build_with_files(
    desc: &SceneDesc,
    source: &Source,
    base_dir: &Path,
    options: &LoadOptions,
    files: MeshFiles,
) -> Result<Loaded, LoadError> {
    let mut settings = render_settings(desc, source)?;
    let cam = desc.camera.get_ref();
    let (width, height) = (*desc.image.width.get_ref(), *desc.image.height.get_ref());
    let up = rescaled(cam.up.0);
    let origin = scene_origin(cam.eye.0);
    let (eye, look_at) = (
        (cam.eye.0 - origin).as_vec3(),
        (cam.look_at.0 - origin).as_vec3(),
    );
    let camera = Camera::new(eye, look_at, up, cam.fov.0, width, height)
        .and_then(|c| match cam.aperture {
            None => Ok(c),
            Some(a) => {
                let focus = cam.focus_distance.map_or((look_at - eye).length(), |f| f.0);
                c.with_lens(a.0, focus)
            }
        })
        .and_then(|c| match cam.orthographic {
            None => Ok(c),
            Some(h) => c.orthographic(h.0),
        })
        .map_err(|e| source.error(desc.camera.span(), e.to_string()))?;
    if cam.orthographic.is_some() && cam.aperture.is_some() {
        return Err(source.error(
            desc.camera.span(),
            "an orthographic camera has no lens: `aperture` cannot go with `orthographic`",
        ));
    }
    if cam.aperture.is_some_and(|a| a.0 > 0.0) && settings.sampling != Sampling::Uniform {
        return Err(source.error(
            desc.camera.span(),
            "a thin lens (`aperture`) needs uniform sampling: adaptive corners are traced through a pinhole",
        ));
    }
    if cam.focus_distance.is_some() && cam.aperture.is_none() {
        return Err(source.error(
            desc.camera.span(),
            "`focus_distance` needs an `aperture` (a pinhole is in focus everywhere)",
        ));
    }
    let mut builder = SceneBuilder::new(camera);
    builder.origin(origin);
    if let Some(m) = &cam.motion {
        builder.camera_motion(motion::motion(source, m, origin)?);
    }
    builder
        .background(desc.world.background.0)
        .ambient(desc.world.ambient.0);
    let accel = desc.render.accelerator.get_ref().parse::<AccelKind>();
    builder.accelerator(accel.map_err(|e| source.error(desc.render.accelerator.span(), e))?);
    builder.triangle_test(match desc.render.triangle_test {
        TriangleTestName::Watertight => TriangleTest::Watertight,
        TriangleTestName::Projection => TriangleTest::Projection,
    });
    let mut early_warnings = Vec::new();
    if matches!(settings.integrator, Integrator::Sppm(_)) && settings.filter != Filter::default() {
        early_warnings.push(format!(
            "{}: the {} filter is rendered as the box by the sppm integrator (its estimate stays in each pixel)",
            source.path.display(),
            settings.filter.name()
        ));
        settings.filter = Filter::default();
    }
    let mut ctx = Context {
        source,
        base_dir,
        options,
        inputs: Fingerprint::default(),
        warnings: early_warnings,
        builder,
        mesh_files: files,
        images: HashMap::new(),
        coats: HashMap::new(),
        sheen_albedo: None,
        origin,
    };
    ctx.inputs.add(source.text.as_bytes());

    let mut material_ids = HashMap::new();
    let mut approximated: Vec<(lucent::material::Approximation, &str)> = Vec::new();
    for m in &desc.materials {
        let name = m.get_ref().name.get_ref();
        if material_ids.contains_key(name.as_str()) {
            return Err(source.error(
                m.get_ref().name.span(),
                format!("a material named `{name}` already exists"),
            ));
        }
        material_ids.insert(name.as_str(), (0, Rgb::BLACK, false));
    }
    let mut table = materials::Materials::new(&desc.materials);
    for m in &desc.materials {
        let name = m.get_ref().name.get_ref();
        let (material, approx) = table.material(m, &mut ctx)?;
        if let Some(a) = approx {
            approximated.push((a, name));
        }
        let emission = if material.emission_map.is_none() {
            material.ke
        } else {
            Rgb::BLACK
        };
        // A textured emission is no area light, but it glows: its objects cannot move either.
        let glows = !material.ke.is_black();
        let id = ctx.builder.material(material);
        material_ids.insert(name.as_str(), (id, emission, glows));
    }
    // The physically based integrators render area lights, environments and rough materials
    // as they are.
    let path = matches!(
        settings.integrator,
        Integrator::Path(_) | Integrator::Sppm(_)
    );
    if !path {
        approximation_warnings(&mut ctx, &approximated, settings.integrator.name());
    }

    let sppm = matches!(settings.integrator, Integrator::Sppm(_));
    lights::add_lights(desc, &mut ctx, path, sppm)?;
    let media = media::Media::add(desc, &mut ctx)?;
    if let Some(name) = &cam.medium {
        let id = media.named(&ctx, name)?;
        ctx.builder.media().camera_in(Some(id));
    }
    let renders_media = matches!(
        settings.integrator,
        Integrator::Path(_) | Integrator::Whitted(_)
    );
    if !desc.media.is_empty() && !renders_media {
        ctx.warnings.push(format!(
            "{}: the {} integrator renders no participating media (the path tracer does, and Whitted's dims by them): they are left out",
            source.path.display(),
            settings.integrator.name()
        ));
    }

    let mut meshes = objects::MeshCache::new();
    let mut emitters = Vec::new();
    let lookup = |named: &Spanned<String>| -> Result<(u32, Rgb, bool), LoadError> {
        let name = named.get_ref();
        if let Some(&found) = material_ids.get(name.as_str()) {
            return Ok(found);
        }
        let known: Vec<_> = desc
            .materials
            .iter()
            .map(|m| m.get_ref().name.get_ref().as_str())
            .collect();
        let hint = if known.is_empty() {
            "none are defined".to_string()
        } else {
            format!("known: {}", known.join(", "))
        };
        Err(source.error(named.span(), format!("unknown material `{name}` ({hint})")))
    };
    for o in &desc.objects {
        let d = o.get_ref();
        if d.material.get_ref().is_empty() && d.material.span().is_empty() {
            let kind = d.kind.name();
            return Err(source.error(o.span(), format!("a {kind} needs `material`")));
        }
        let (material, ke, glows) = lookup(&d.material)?;
        let emissive = !ke.is_black();
        let object = ctx.builder.objects();
        let added = if csg::operation(d.kind).is_some() {
            let resolve = |m: &Spanned<String>| lookup(m).map(|(id, ke, _)| (id, !ke.is_black()));
            csg::add_csg(&mut ctx, o, material, &resolve)?;
            None
        } else {
            objects::add_object(&mut ctx, &mut meshes, o, material, emissive, glows)?
        };
        let interface = media.interface(&ctx, &d.interior, &d.exterior)?;
        if interface.is_transition() {
            ctx.builder.media().bound_by(object, interface);
        }
        if let Some(surface) = added {
            emitters.push((ke, surface));
        }
    }
    // The path tracer samples the emitting surfaces themselves.
    if !path {
        lights::area_lights_as_points(&mut ctx, &emitters, settings.integrator.name());
    }

    let Context {
        builder,
        inputs,
        warnings,
        ..
    } = ctx;
    let mut scene = builder
        .build()
        .map_err(|e| LoadError::file(source.path, e.to_string()))?;
    if let Some(shutter) = &cam.shutter {
        let [open, close] = shutter.get_ref().map(|t| f64::from(t.0));
        let s =
            Shutter::new(open, close).map_err(|e| source.error(shutter.span(), e.to_string()))?;
        scene = scene.with_shutter(s);
    }
    let display = display(&desc.image, source)?;
    Ok(Loaded {
        scene,
        settings,
        inputs: inputs.value(),
        warnings,
        display,
    })
}

/// How the image's values are written: `[image] raw` and `gamma`.
fn display(image: &crate::desc::ImageDesc, source: &Source) -> Result<Display, LoadError> {
    if image.raw == Some(true) {
        return Ok(Display::Raw);
    }
    match &image.gamma {
        None => Ok(Display::Srgb),
        Some(g) => {
            let v = g.get_ref().0;
            check(
                source,
                g.span(),
                v > 0.0 && v <= 10.0,
                "the image's gamma must be in (0, 10]",
            )?;
            Ok(if v == 1.0 {
                Display::Srgb
            } else {
                Display::Gamma(v)
            })
        }
    }
}

/// The spacing of the points a scene may be rebased to: a power of two, so that every scene
/// whose eye is within half of it of the world's origin is built exactly as written.
const ORIGIN_GRID: f64 = 1024.0;

/// Where the built scene's coordinates have their zero in the file's world, for a camera at
/// `eye`: the multiple of [`ORIGIN_GRID`] nearest it. The file's positions are read in double
/// precision and moved by it before they are rounded to single, so that what the camera sees is
/// within about a grid step of the renderer's origin, where single precision is finest: a scene
/// 1e7 from the world's origin (where a single-precision coordinate's step is 1) renders as it
/// does at the origin.
pub fn scene_origin(eye: DVec3) -> DVec3 {
    (eye / ORIGIN_GRID).round() * ORIGIN_GRID
}

/// One warning per reason the classic integrators draw materials other than as written.
fn approximation_warnings(
    ctx: &mut Context,
    approximated: &[(lucent::material::Approximation, &str)],
    integrator: &str,
) {
    use lucent::material::Approximation;
    for (reason, what) in [
        (
            Approximation::Rough,
            "rendered smooth (glass) or with a Phong highlight (the other kinds)",
        ),
        (
            Approximation::Blend,
            "a blend of two surfaces, rendered with the mean of their coefficients",
        ),
        (
            Approximation::NormalMap,
            "normal- or bump-mapped, rendered with the surface's own normal",
        ),
    ] {
        let names: Vec<String> = approximated
            .iter()
            .filter(|(a, _)| *a == reason)
            .map(|(_, n)| format!("`{n}`"))
            .collect();
        if names.is_empty() {
            continue;
        }
        let kind = if reason == Approximation::Rough {
            "rough material"
        } else {
            "material"
        };
        ctx.warnings.push(format!(
            "{}: {kind}{} {} {} {what} by the {integrator} integrator",
            ctx.source.path.display(),
            if names.len() == 1 { "" } else { "s" },
            names.join(", "),
            if names.len() == 1 { "is" } else { "are" },
        ));
    }
}

/// `v` divided by its largest magnitude, so that its largest component is ±1 (zero stays
/// zero): a direction "of any length" (a light's `direction`, a plane's `normal`, the camera's
/// `up`, an orbit's `axis`) then normalises in single precision, where the squared length of
/// `[1e-30, 0, 0]` underflows to 0 and that of `[1e20, 0, 0]` overflows to infinity.
pub(crate) fn rescaled(v: glam::Vec3) -> glam::Vec3 {
    let largest = v.abs().max_element();
    if largest > 0.0 { v / largest } else { v }
}

pub(crate) fn check(
    source: &Source,
    span: Range<usize>,
    ok: bool,
    message: &str,
) -> Result<(), LoadError> {
    if ok {
        Ok(())
    } else {
        Err(source.error(span, message))
    }
}

fn render_settings(desc: &SceneDesc, source: &Source) -> Result<RenderSettings, LoadError> {
    let image = &desc.image;
    for (v, what) in [(&image.width, "width"), (&image.height, "height")] {
        let ok = (1..=MAX_IMAGE_SIDE).contains(v.get_ref());
        check(
            source,
            v.span(),
            ok,
            &format!("the image {what} must be between 1 and {MAX_IMAGE_SIDE} pixels"),
        )?;
    }
    let pixels = u64::from(*image.width.get_ref()) * u64::from(*image.height.get_ref());
    let too_many = format!("the image has {pixels} pixels; at most {MAX_PIXELS} are supported");
    check(source, image.width.span(), pixels <= MAX_PIXELS, &too_many)?;
    let spp = *image.samples.get_ref();
    let ok = (1..=MAX_SAMPLES).contains(&spp);
    check(
        source,
        image.samples.span(),
        ok,
        &format!("samples must be between 1 and {MAX_SAMPLES}"),
    )?;

    let r = &desc.render;
    let max_depth = *r.max_depth.get_ref();
    check(
        source,
        r.max_depth.span(),
        max_depth <= MAX_DEPTH,
        &format!("max_depth must be at most {MAX_DEPTH}"),
    )?;
    let min_weight = r.min_weight.get_ref().0;
    check(
        source,
        r.min_weight.span(),
        (0.0..=1.0).contains(&min_weight),
        "min_weight must be between 0 and 1",
    )?;
    let integrator = match r.integrator {
        IntegratorName::Raycast => Integrator::Raycast,
        IntegratorName::Whitted => Integrator::Whitted(Whitted {
            max_depth,
            min_weight,
            shadows: r.shadows.as_ref().is_none_or(|s| *s.get_ref()),
        }),
        IntegratorName::DebugNormals => Integrator::Debug(DebugView::Normals),
        IntegratorName::DebugDepth => Integrator::Debug(DebugView::Depth),
        IntegratorName::DebugAlbedo => Integrator::Debug(DebugView::Albedo),
        IntegratorName::DebugId => Integrator::Debug(DebugView::Id),
        IntegratorName::DebugBarycentrics => Integrator::Debug(DebugView::Barycentrics),
        IntegratorName::DebugCost => Integrator::Debug(DebugView::Cost),
        IntegratorName::Sppm => Integrator::Sppm(Sppm {
            max_depth,
            photons: match &r.photons {
                Some(p) if *p.get_ref() == 0 => {
                    return Err(source.error(p.span(), "photons must be at least 1"));
                }
                Some(p) if *p.get_ref() > lucent::integrator::MAX_PHOTONS_PER_ITERATION => {
                    return Err(source.error(
                        p.span(),
                        format!(
                            "photons must be at most {} per iteration (more iterations: `[image] samples`)",
                            lucent::integrator::MAX_PHOTONS_PER_ITERATION
                        ),
                    ));
                }
                Some(p) => *p.get_ref(),
                None => 0,
            },
            radius: match &r.photon_radius {
                Some(p) if p.get_ref().0.is_nan() || p.get_ref().0 <= 0.0 => {
                    return Err(source.error(p.span(), "photon_radius must be positive"));
                }
                Some(p) => p.get_ref().0,
                None => 0.0,
            },
        }),
        IntegratorName::Path => Integrator::Path(PathTracer {
            max_depth,
            rr_depth: r
                .rr_depth
                .as_ref()
                .map_or(PathTracer::default().rr_depth, |d| *d.get_ref()),
        }),
    };
    if let Some(d) = &r.rr_depth
        && r.integrator != IntegratorName::Path
    {
        return Err(source.error(d.span(), "`rr_depth` applies to the path integrator only"));
    }
    let sppm_only = [
        ("photons", r.photons.as_ref().map(|p| p.span())),
        ("photon_radius", r.photon_radius.as_ref().map(|p| p.span())),
    ];
    if r.integrator != IntegratorName::Sppm
        && let Some((key, span)) = sppm_only.iter().find_map(|(k, s)| Some((k, s.clone()?)))
    {
        return Err(source.error(span, format!("`{key}` applies to the sppm integrator only")));
    }
    if let Some(s) = &r.shadows
        && r.integrator != IntegratorName::Whitted
    {
        return Err(source.error(s.span(), "`shadows` applies to the whitted integrator only"));
    }
    let sampling = sampling(r, source)?;
    if integrator.is_stochastic() && sampling != Sampling::Uniform {
        return Err(source.error(
            0..0,
            format!(
                "adaptive and quadtree sampling compare corners traced once: they need a deterministic integrator (raycast, whitted or a debug view), not {}",
                integrator.name()
            ),
        ));
    }
    let time_limit = match &r.time_limit {
        Some(t) if !(t.get_ref().0 > 0.0 && t.get_ref().0 <= MAX_TIME_LIMIT) => {
            return Err(source.error(
                t.span(),
                "time_limit must be a positive number of seconds, at most a year",
            ));
        }
        Some(t) if sampling != Sampling::Uniform => {
            return Err(source.error(t.span(), "time_limit needs uniform sampling"));
        }
        Some(t) => Some(std::time::Duration::from_secs_f32(t.get_ref().0)),
        None => None,
    };
    Ok(RenderSettings {
        integrator,
        // An adaptive pixel is one film sample.
        spp: if sampling == Sampling::Uniform {
            spp
        } else {
            1
        },
        seed: r.seed,
        sampling,
        filter: filter(r, source)?,
        filter_sampling: match r.filter_sampling.as_ref().map(|f| *f.get_ref()) {
            None | Some(FilterSamplingName::Splat) => FilterSampling::Splat,
            Some(FilterSamplingName::Importance) => FilterSampling::Importance,
        },
        time_limit,
        ..RenderSettings::default()
    })
}

/// `[render] filter` and `filter_radius`, checked.
fn filter(r: &RenderDesc, source: &Source) -> Result<Filter, LoadError> {
    let name = r.filter.as_ref().map_or(FilterName::Box, |f| *f.get_ref());
    let mut f = match name {
        FilterName::Box => Filter::Box { radius: 0.5 },
        FilterName::Tent => Filter::Tent { radius: 1.0 },
        FilterName::Gaussian => Filter::Gaussian {
            radius: 2.0,
            sigma: 0.5,
        },
        FilterName::Mitchell => Filter::Mitchell {
            radius: 2.0,
            b: 1.0 / 3.0,
            c: 1.0 / 3.0,
        },
    };
    if let Some(radius) = &r.filter_radius {
        let v = radius.get_ref().0;
        check(
            source,
            radius.span(),
            (MIN_FILTER_RADIUS..=MAX_FILTER_RADIUS).contains(&v),
            &format!(
                "filter_radius must be between {MIN_FILTER_RADIUS} and {MAX_FILTER_RADIUS} pixels"
            ),
        )?;
        match &mut f {
            Filter::Box { radius }
            | Filter::Tent { radius }
            | Filter::Gaussian { radius, .. }
            | Filter::Mitchell { radius, .. } => *radius = v,
        }
        // The renderer's own check, so that what it would refuse is refused here, in place.
        f.validate().map_err(|e| source.error(radius.span(), e))?;
    }
    Ok(f)
}

/// `[render] aa` and its settings, checked.
fn sampling(r: &RenderDesc, source: &Source) -> Result<Sampling, LoadError> {
    let threshold = r.aa_threshold.as_ref().map(|t| (t.get_ref().0, t.span()));
    let depth = r.aa_depth.as_ref().map(|d| (*d.get_ref(), d.span()));
    let block = r.aa_block.as_ref().map(|b| (*b.get_ref(), b.span()));
    let block = match r.aa {
        SamplingName::Uniform => {
            let given = [
                ("aa_threshold", threshold.as_ref().map(|t| &t.1)),
                ("aa_depth", depth.as_ref().map(|d| &d.1)),
                ("aa_block", block.as_ref().map(|b| &b.1)),
            ];
            return match given.into_iter().find_map(|(k, s)| Some((k, s?.clone()))) {
                Some((key, span)) => Err(source.error(
                    span,
                    format!("`{key}` needs `aa = \"adaptive\"` or `\"quadtree\"`"),
                )),
                None => Ok(Sampling::Uniform),
            };
        }
        SamplingName::Adaptive => match block {
            Some((_, span)) => {
                return Err(source.error(span, "`aa_block` needs `aa = \"quadtree\"`"));
            }
            None => 0,
        },
        SamplingName::Quadtree => match block {
            Some((b, span)) => {
                check(
                    source,
                    span,
                    (1..=MAX_AA_BLOCK).contains(&b),
                    &format!("aa_block must be between 1 and {MAX_AA_BLOCK}"),
                )?;
                b
            }
            None => 3,
        },
    };
    let d = Adaptive::default();
    if let Some((t, span)) = &threshold {
        check(
            source,
            span.clone(),
            *t >= 0.0,
            "aa_threshold must be at least 0",
        )?;
    }
    if let Some((v, span)) = &depth {
        let message = format!("aa_depth must be at most {ADAPTIVE_MAX_DEPTH}");
        check(source, span.clone(), *v <= ADAPTIVE_MAX_DEPTH, &message)?;
    }
    Ok(Sampling::Adaptive(Adaptive {
        threshold: threshold.map_or(d.threshold, |t| t.0),
        depth: depth.map_or(d.depth, |v| v.0),
        block,
    }))
}

/// Refuses the keys of `present` that a `kind` does not take.
pub(crate) fn refuse_keys(
    source: &Source,
    kind: &str,
    present: &[(&str, Option<Range<usize>>)],
) -> Result<(), LoadError> {
    match present
        .iter()
        .find_map(|(k, span)| span.clone().map(|s| (k, s)))
    {
        Some((key, span)) => {
            let article = if kind.starts_with(['a', 'e', 'i', 'o', 'u']) {
                "an"
            } else {
                "a"
            };
            Err(source.error(span, format!("`{key}` does not apply to {article} {kind}")))
        }
        None => Ok(()),
    }
}

/// The value of a required key, or an error at the enclosing table.
pub(crate) fn required<'a, T>(
    source: &Source,
    table: Range<usize>,
    kind: &str,
    key: &str,
    v: &'a Option<Spanned<T>>,
) -> Result<&'a Spanned<T>, LoadError> {
    v.as_ref()
        .ok_or_else(|| source.error(table, format!("a {kind} needs `{key}`")))
}

pub(crate) fn span<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
    v.as_ref().map(|s| s.span())
}
