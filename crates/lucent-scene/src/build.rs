//! From `SceneDesc` to a render-time `Scene`: names resolved, ranges checked, meshes loaded.
//!
//! Every error points at the value at fault in the scene file (or at the line of a mesh file).

use crate::desc::light::FalloffName;
use crate::desc::settings::TriangleTestName;
use crate::desc::{IntegratorName, LightKind, ObjectDesc, ObjectKind, SceneDesc};
use crate::error::{LoadError, Source};
use crate::hash::Fingerprint;
use crate::mesh_file::read_mesh_fingerprinted;
use glam::{Affine3A, Mat3, Vec3};
use lucent::Rgb;
use lucent::accel::AccelKind;
use lucent::camera::Camera;
use lucent::integrator::{Integrator, Whitted};
use lucent::light::{DirectionalLight, Falloff, Light, PointLight};
use lucent::render::RenderSettings;
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Mesh, Plane, Sphere, TriangleTest, triangle};
use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;
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

/// A scene ready to render, with the render settings its file gives.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The scene.
    pub scene: Scene,
    /// Integrator, samples and seed from the file (threads: all).
    pub settings: RenderSettings,
    /// Fingerprint of the inputs: the scene text and every mesh file read.
    pub inputs: u64,
}

/// Builds `desc`, read from `source`; mesh files are found relative to `base_dir`.
pub fn build(desc: &SceneDesc, source: &Source, base_dir: &Path) -> Result<Loaded, LoadError> {
    let settings = render_settings(desc, source)?;
    let mut inputs = Fingerprint::default();
    inputs.add(source.text.as_bytes());
    let cam = desc.camera.get_ref();
    let (width, height) = (*desc.image.width.get_ref(), *desc.image.height.get_ref());
    let camera = Camera::new(cam.eye.0, cam.look_at.0, cam.up.0, cam.fov.0, width, height)
        .map_err(|e| source.error(desc.camera.span(), e.to_string()))?;
    let mut builder = SceneBuilder::new(camera);
    builder
        .background(desc.world.background.0)
        .ambient(desc.world.ambient.0);
    let accel = desc.render.accelerator.get_ref().parse::<AccelKind>();
    builder.accelerator(accel.map_err(|e| source.error(desc.render.accelerator.span(), e))?);
    builder.triangle_test(match desc.render.triangle_test {
        TriangleTestName::Watertight => TriangleTest::Watertight,
        TriangleTestName::Projection => TriangleTest::Projection,
    });

    let mut material_ids = HashMap::new();
    for m in &desc.materials {
        let name = m.get_ref().name.get_ref();
        if material_ids.contains_key(name.as_str()) {
            return Err(source.error(
                m.get_ref().name.span(),
                format!("a material named `{name}` already exists"),
            ));
        }
        let material = crate::materials::whitted_material(m.get_ref(), source)?;
        material_ids.insert(name.as_str(), builder.material(material));
    }

    for l in &desc.lights {
        builder.light(light(l, source)?);
    }

    let mut meshes = MeshCache::new();
    for o in &desc.objects {
        let d = o.get_ref();
        let name = d.material.get_ref();
        let Some(&material) = material_ids.get(name.as_str()) else {
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
            return Err(source.error(
                d.material.span(),
                format!("unknown material `{name}` ({hint})"),
            ));
        };
        add_object(
            &mut builder,
            &mut meshes,
            &mut inputs,
            o,
            material,
            source,
            base_dir,
        )?;
    }

    let scene = builder
        .build()
        .map_err(|e| LoadError::file(source.path, e.to_string()))?;
    Ok(Loaded {
        scene,
        settings,
        inputs: inputs.value(),
    })
}

fn check(source: &Source, span: Range<usize>, ok: bool, message: &str) -> Result<(), LoadError> {
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
        }),
    };
    Ok(RenderSettings {
        integrator,
        spp,
        seed: r.seed,
        ..RenderSettings::default()
    })
}

/// Refuses the keys of `present` that a `kind` does not take.
fn refuse_keys(
    source: &Source,
    kind: &str,
    present: &[(&str, Option<Range<usize>>)],
) -> Result<(), LoadError> {
    match present
        .iter()
        .find_map(|(k, span)| span.clone().map(|s| (k, s)))
    {
        Some((key, span)) => Err(source.error(span, format!("`{key}` does not apply to a {kind}"))),
        None => Ok(()),
    }
}

/// The value of a required key, or an error at the enclosing table.
fn required<'a, T>(
    source: &Source,
    table: Range<usize>,
    kind: &str,
    key: &str,
    v: &'a Option<Spanned<T>>,
) -> Result<&'a Spanned<T>, LoadError> {
    v.as_ref()
        .ok_or_else(|| source.error(table, format!("a {kind} needs `{key}`")))
}

fn span<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
    v.as_ref().map(|s| s.span())
}

fn light(l: &Spanned<crate::desc::LightDesc>, source: &Source) -> Result<Light, LoadError> {
    let d = l.get_ref();
    let intensity = d.intensity.map_or(Rgb::WHITE, |c| c.0);
    match d.kind {
        LightKind::Point => {
            refuse_keys(source, "point light", &[("direction", span(&d.direction))])?;
            let position = required(source, l.span(), "point light", "position", &d.position)?
                .get_ref()
                .0;
            let falloff = match d.falloff.as_ref().map(|f| *f.get_ref()) {
                None | Some(FalloffName::None) => Falloff::None,
                Some(FalloffName::Quadratic) => Falloff::Quadratic,
            };
            Ok(Light::Point(PointLight {
                position,
                intensity,
                falloff,
            }))
        }
        LightKind::Spot | LightKind::Environment => Err(source.error(
            l.span(),
            format!("{}s are not supported yet", d.kind.name()),
        )),
        LightKind::Directional => {
            let kind = "directional light";
            refuse_keys(
                source,
                kind,
                &[
                    ("position", span(&d.position)),
                    ("falloff", span(&d.falloff)),
                ],
            )?;
            let direction = required(source, l.span(), kind, "direction", &d.direction)?;
            let unit = direction.get_ref().0.try_normalize();
            let unit = unit.ok_or_else(|| {
                source.error(direction.span(), "the light's direction must not be zero")
            })?;
            Ok(Light::Directional(DirectionalLight {
                direction: unit,
                intensity,
            }))
        }
    }
}

/// Meshes already stored, by canonical file path.
type MeshCache = HashMap<std::path::PathBuf, u32>;

#[allow(clippy::too_many_arguments)]
fn add_object(
    builder: &mut SceneBuilder,
    meshes: &mut MeshCache,
    inputs: &mut Fingerprint,
    o: &Spanned<ObjectDesc>,
    material: u32,
    source: &Source,
    base_dir: &Path,
) -> Result<(), LoadError> {
    let d = o.get_ref();
    let kind = d.kind.name();
    let keys = [
        ("center", span(&d.center)),
        ("radius", span(&d.radius)),
        ("point", span(&d.point)),
        ("normal", span(&d.normal)),
        ("vertices", span(&d.vertices)),
        ("file", span(&d.file)),
        ("translate", span(&d.translate)),
        ("rotate", span(&d.rotate)),
        ("scale", span(&d.scale)),
    ];
    let takes: &[&str] = match d.kind {
        ObjectKind::Sphere => &["center", "radius"],
        ObjectKind::Plane => &["point", "normal"],
        ObjectKind::Triangle => &["vertices"],
        ObjectKind::Mesh => &["file", "translate", "rotate", "scale"],
        _ => {
            return Err(source.error(o.span(), format!("{kind}s are not supported yet")));
        }
    };
    let others: Vec<_> = keys
        .into_iter()
        .filter(|(k, _)| !takes.contains(k))
        .collect();
    refuse_keys(source, kind, &others)?;
    let table = o.span();
    match d.kind {
        ObjectKind::Sphere => {
            let center = required(source, table.clone(), kind, "center", &d.center)?
                .get_ref()
                .0;
            let radius = required(source, table, kind, "radius", &d.radius)?;
            let r = radius.get_ref().0;
            check(
                source,
                radius.span(),
                r > 0.0,
                &format!("a sphere's radius must be positive, got {r}"),
            )?;
            let (lo, hi) = (RADIUS_RANGE.start(), RADIUS_RANGE.end());
            let in_range = RADIUS_RANGE.contains(&r);
            check(
                source,
                radius.span(),
                in_range,
                &format!("a sphere's radius must be between {lo:e} and {hi:e}, got {r:e}"),
            )?;
            builder.sphere(Sphere { center, radius: r }, material);
        }
        ObjectKind::Plane => {
            let point = required(source, table.clone(), kind, "point", &d.point)?
                .get_ref()
                .0;
            let normal = required(source, table, kind, "normal", &d.normal)?;
            let n = normal.get_ref().0;
            check(
                source,
                normal.span(),
                n != Vec3::ZERO,
                "a plane's normal must not be zero",
            )?;
            builder.plane(Plane::new(point, n), material);
        }
        ObjectKind::Triangle => {
            let vertices = required(source, table, kind, "vertices", &d.vertices)?;
            let v = vertices.get_ref().map(|p| p.0);
            let ok = triangle::double_area(v) > 0.0;
            check(
                source,
                vertices.span(),
                ok,
                "the triangle's vertices are collinear: it has no area",
            )?;
            builder.mesh(Mesh::new(v.to_vec(), vec![[0, 1, 2]]), material);
        }
        ObjectKind::Mesh => {
            let file = required(source, table, kind, "file", &d.file)?;
            let path = base_dir.join(file.get_ref());
            if !path.is_file() {
                return Err(source.error(
                    file.span(),
                    format!("mesh file `{}` not found", path.display()),
                ));
            }
            // A file placed many times is read and stored once: the objects are instances of it.
            let key = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
            let mesh = match meshes.get(&key) {
                Some(&id) => id,
                None => {
                    let id = builder.add_mesh(read_mesh_fingerprinted(&path, inputs)?);
                    meshes.insert(key, id);
                    id
                }
            };
            builder.instance(mesh, mesh_transform(d), material);
        }
        _ => unreachable!("refused above"),
    }
    Ok(())
}

/// `p ↦ translate + Rz·Ry·Rx·(scale ∘ p)`: scale, then rotate about x, y, z in that order, then move.
fn mesh_transform(d: &ObjectDesc) -> Affine3A {
    let scale = d.scale.as_ref().map_or(Vec3::ONE, |s| s.get_ref().0);
    let deg = d.rotate.as_ref().map_or(Vec3::ZERO, |r| r.get_ref().0);
    let rotation = Mat3::from_rotation_z(deg.z.to_radians())
        * Mat3::from_rotation_y(deg.y.to_radians())
        * Mat3::from_rotation_x(deg.x.to_radians());
    let translate = d.translate.as_ref().map_or(Vec3::ZERO, |t| t.get_ref().0);
    Affine3A::from_translation(translate)
        * Affine3A::from_mat3(rotation)
        * Affine3A::from_scale(scale)
}
