//! glTF 2.0 files — `.gltf` with external or embedded (`data:`) buffers, and binary `.glb` —
//! as scene descriptions ([`import_gltf`]) and as triangle meshes ([`read_gltf_part`]).
//!
//! A mesh of a glTF file is referred to from a description by the file's name and a part:
//!
//! ```toml
//! [[object]]
//! type = "mesh"
//! file = "car.glb"
//! part = "2/0"          # mesh 2, primitive 0, in the mesh's own space
//! material = "gltf:Paint"
//! transform = [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]   # the node's world matrix
//! ```
//!
//! What becomes what:
//!
//! - **Scene**: the default scene, else scene 0, else every root node. A node's world matrix
//!   is its parent's times its own (`matrix`, or `T·R·S`).
//! - **Meshes**: one object per (node, triangle primitive), placed by the node's world matrix;
//!   a mesh instanced on several nodes gives several objects with the same part. Triangle lists,
//!   strips and fans are read, indexed (8, 16, 32 bits) or not; `POSITION`, `NORMAL`,
//!   `TANGENT`, `TEXCOORD_n` (the set its material reads; glTF's convention, kept) and
//!   `COLOR_0` (alpha dropped); sparse
//!   accessors.
//!   Points and lines are skipped with a warning.
//! - **Materials**: named `gltf:<name or index>`, made unique; `gltf:default` (diffuse grey
//!   0.8) for primitives without one. Each becomes lucent's `pbr` kind, glTF's own BRDF, with
//!   every texture slot (base colour, metallic-roughness, normal, emissive, alpha `MASK` and
//!   `BLEND` as opacity) and the `KHR_materials_*` layers: the table in `gltf_file/material.rs`.
//!   A primitive whose material has a normal map keeps its `TANGENT`s, or gets MikkTSpace's.
//! - **Lights** (KHR_lights_punctual): photometric to radiometric by [`LUMENS_PER_WATT`]; at
//!   the node's origin, shining down its −z; quadratic falloff for point and spot lights; spot
//!   cone angles → `cutoff` (outer) and `cutoff_start` (inner) in degrees.
//! - **Camera**: the first camera met in the node tree (depth first): eye at the node's
//!   origin, looking down its −z with +y up; perspective (`yfov` in degrees) or orthographic
//!   (`2·ymag` high); the aspect ratio sets the image to [`IMAGE_HEIGHT`] pixels high and as
//!   wide as the ratio says.
//! - **Morph targets** at the mesh's default weights; **skins** posed by their joints as the
//!   nodes place them (part `MESH/PRIMITIVE/SKIN`, in world space); quantized attributes
//!   (`KHR_mesh_quantization`).
//!
//! Not rendered (each gives a warning naming the file): a node's own morph weights,
//! animations, light `range`, extensions other than those above. Nodes whose world matrix is
//! singular are skipped with a warning.
//!
//! Safety: every URI naming a file goes through [`crate::paths::resolve`], so `--sandbox`
//! holds; the glTF crate never opens a file by itself. Every length and index in the file is
//! checked against the bytes really there before anything is allocated; an accessor without a
//! buffer view is capped at 2^20 elements, and a merged mesh (a whole scene as one part) at
//! 2^28 triangles.

mod accessor;
mod asset;
mod draco;
mod material;
mod primitive;
mod skin;
mod source;
mod volume;

use crate::desc::{
    CameraDesc, FalloffName, Finite, IntegratorName, LightDesc, LightKind, Matrix, ObjectDesc,
    ObjectKind, Point, SceneDesc, Vector,
};
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::import::{Imported, placeholder_camera};
use crate::paths::LoadOptions;
use asset::Asset;
use glam::{Mat4, Quat, Vec3, Vec4};
use lucent::Rgb;
use lucent::shape::Mesh;
use primitive::Decoded;
use std::collections::hash_map::Entry;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use toml::Spanned;

/// Lumens per watt: the luminous efficacy of 555 nm light, by which the candela is defined.
///
/// glTF's lights are photometric: point and spot intensities in candela (lm/sr), directional
/// ones in lux (lm/m²). lucent's are radiometric: W/sr for point and spot lights (irradiance
/// `I / d²` with quadratic falloff), W/m² for directional ones. Each glTF intensity, times its
/// colour, is divided by this: a 683 cd white point light is a lucent point light of intensity
/// 1 with `falloff = "quadratic"`.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// Image height in pixels when a camera gives an aspect ratio (the width follows from it).
pub const IMAGE_HEIGHT: u32 = 600;

/// Samples per pixel of a glTF scene, rendered by the path tracer: a clean first look at a
/// model in a few seconds.
pub const DEFAULT_SAMPLES: u32 = 16;

/// The extensions read (others listed in `extensionsUsed` give a warning; others listed in
/// `extensionsRequired` make the file unreadable).
const SUPPORTED_EXTENSIONS: [&str; 15] = [
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_draco_mesh_compression",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_emissive_strength",
    "KHR_materials_specular",
    "KHR_materials_volume",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    "KHR_materials_anisotropy",
    "KHR_materials_iridescence",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_unlit",
    "KHR_texture_transform",
];

/// The scene of a .gltf/.glb file as a description: camera, lights, materials, and one mesh
/// object per (node, primitive).
///
/// Every primitive placed in the scene is read (and then dropped), so that broken geometry is
/// reported here rather than when the scene is built. The bytes of the file and of every
/// external buffer (up to its declared length) are added to `inputs`.
pub fn import_gltf(
    path: &Path,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Imported, LoadError> {
    let asset = Asset::open(path, options, inputs)?;
    let file_name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| LoadError::file(path, "the file's name is not UTF-8 text"))?
        .to_string();
    let mut warnings = Vec::new();
    let mut warn = |s: String| warnings.push(format!("{}: {s}", path.display()));
    let doc = &asset.doc;
    for ext in doc.extensions_used() {
        if !SUPPORTED_EXTENSIONS.contains(&ext) {
            warn(format!("extension {ext} is not supported; ignored"));
        }
    }
    if doc.scenes().len() > 1 {
        let used = doc.default_scene().map_or(0, |s| s.index());
        warn(format!(
            "the file has {} scenes; only scene {used} is imported",
            doc.scenes().len()
        ));
    }
    if doc.animations().len() > 0 {
        warn("animations are not rendered; the nodes' own transforms are used".into());
    }
    let (placed, notes) = asset.placed_nodes();
    notes.into_iter().for_each(&mut warn);

    let (names, default_name) = material_names(doc);
    let mut used = vec![false; names.len()];
    let mut default_used = false;
    let mut decoded: HashMap<(usize, usize), bool> = HashMap::new();
    let mut same_geometry: HashMap<Geometry, (usize, usize)> = HashMap::new();
    let mut objects = Vec::new();
    let mut lights = Vec::new();
    let mut camera: Option<(CameraDesc, Option<f32>)> = None;
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    // Each placed triangle primitive is an object: held to the budget before any is decoded.
    let placed_primitives: u64 = placed
        .iter()
        .filter_map(|&(i, _)| nodes[i].mesh())
        .flat_map(|m| m.primitives())
        .filter(|p| {
            use gltf::mesh::Mode;
            matches!(
                p.mode(),
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            )
        })
        .count() as u64;
    options
        .limits
        .check(crate::limits::Limit::Objects, placed_primitives, |n| {
            format!("the scene places {n} triangle primitives, an object each")
        })
        .map_err(|e| LoadError::file(path, e))?;
    for &(i, world) in &placed {
        let node = &nodes[i];
        if let Some(mesh) = node.mesh() {
            // A skinned mesh is posed by its joints, in world space; one whose skin cannot be
            // applied is shown unposed, placed by its node.
            let skin = node.skin().filter(|s| {
                let posed = mesh.primitives().try_for_each(|prim| {
                    asset
                        .primitive(&mesh, mesh.index(), &prim, Some(s))
                        .map(|_| ())
                });
                if let Err(why) = &posed {
                    warn(format!(
                        "node {i}: its skin {} is not applied ({why}); the mesh is shown unposed",
                        s.index()
                    ));
                }
                posed.is_ok()
            });
            // Morph targets are posed at the mesh's default weights; a node's own differ.
            if node.weights().is_some_and(|w| Some(w) != mesh.weights()) {
                warn(format!(
                    "node {i}: its morph weights are not applied; mesh {}'s default weights are",
                    mesh.index()
                ));
            }
            let placeable = primitive::placeable(&world);
            if !placeable {
                warn(format!(
                    "node {i}: its world matrix is singular, projective or not finite; its mesh {} is skipped",
                    mesh.index()
                ));
            }
            for prim in mesh.primitives().filter(|_| placeable) {
                // Primitives of the same accessors are one part: the build stores it once and
                // places it as instances (a small file cannot multiply a large buffer).
                let key = *same_geometry
                    .entry(geometry(&prim, asset.uv_set(&prim), weights(&mesh)))
                    .or_insert((mesh.index(), prim.index()));
                let triangles = match decoded.get(&key) {
                    Some(&t) => t,
                    None => {
                        let t = match primitive::decode(
                            &asset.buffers,
                            key.0,
                            &prim,
                            asset.uv_set(&prim),
                            weights(&mesh),
                        )
                        .map_err(|e| asset.error(e))?
                        {
                            Decoded::Triangles(_, notes) => {
                                notes.into_iter().for_each(&mut warn);
                                true
                            }
                            Decoded::Skipped(why) => {
                                warn(why);
                                false
                            }
                        };
                        decoded.insert(key, t);
                        t
                    }
                };
                if !triangles {
                    continue;
                }
                let material = match prim.material().index() {
                    Some(k) => {
                        used[k] = true;
                        &names[k]
                    }
                    None => {
                        default_used = true;
                        &default_name
                    }
                };
                let mut o = ObjectDesc::new(ObjectKind::Mesh, material);
                o.file = Some(Spanned::new(0..0, file_name.clone()));
                match &skin {
                    // Posed in world space: the node's transform is not applied.
                    Some(s) => {
                        let part = format!("{}/{}/{}", key.0, key.1, s.index());
                        o.part = Some(Spanned::new(0..0, part));
                    }
                    None => {
                        o.part = Some(Spanned::new(0..0, format!("{}/{}", key.0, key.1)));
                        o.transform = Some(Spanned::new(0..0, Matrix::from_single(world)));
                    }
                }
                objects.push(Spanned::new(0..0, o));
            }
        }
        if let Some(l) = node.light() {
            match light(&l, world) {
                Ok((d, notes)) => {
                    notes
                        .into_iter()
                        .for_each(|n| warn(format!("node {i}: light {}: {n}", l.index())));
                    lights.push(Spanned::new(0..0, d));
                }
                Err(why) => warn(format!("node {i}: light {}: {why}; skipped", l.index())),
            }
        }
        if let Some(c) = node.camera() {
            if camera.is_some() {
                warn(format!(
                    "node {i}: camera {} ignored: the first camera is used",
                    c.index()
                ));
            } else {
                match camera_of(&c.projection(), world) {
                    Ok(d) => camera = Some(d),
                    Err(why) => warn(format!("node {i}: camera {}: {why}; ignored", c.index())),
                }
            }
        }
    }

    let images = material::Images {
        root: doc.as_json(),
        base_dir: &asset.base_dir,
        file_name: &file_name,
        asset: Some(&asset),
        options,
    };
    let mut materials = Vec::new();
    let mut media = Vec::new();
    for m in doc.materials() {
        let Some(k) = m.index().filter(|&k| used[k]) else {
            continue;
        };
        let (d, notes) = material::describe(&m, &names[k], &images).map_err(|e| asset.error(e))?;
        notes.into_iter().for_each(&mut warn);
        if let Some(medium) = volume::medium(&m, &names[k]) {
            media.push((names[k].clone(), medium));
        }
        materials.push(Spanned::new(0..0, d));
    }
    volume::fill(&mut objects, &media);
    if default_used {
        materials.push(Spanned::new(
            0..0,
            material::default_material(&default_name),
        ));
    }

    let mut desc = SceneDesc {
        image: Default::default(),
        camera: placeholder_camera(),
        world: Default::default(),
        render: Default::default(),
        materials,
        lights,
        objects,
        media: media
            .into_iter()
            .map(|(_, m)| Spanned::new(0..0, m))
            .collect(),
    };
    // glTF's materials are physically based: the path tracer renders them as written, at
    // enough samples for a first look (`--spp`, `--time-limit` choose otherwise).
    desc.render.integrator = IntegratorName::Path;
    desc.image.samples = Spanned::new(0..0, DEFAULT_SAMPLES);
    let camera_given = camera.is_some();
    if let Some((c, aspect)) = camera {
        desc.camera = Spanned::new(0..0, c);
        if let Some(a) = aspect {
            match image_width(a) {
                Some(width) => {
                    desc.image.width = Spanned::new(0..0, width);
                    desc.image.height = Spanned::new(0..0, IMAGE_HEIGHT);
                }
                None => warn(format!(
                    "the camera's aspect ratio {a} is out of range; the default image size is used"
                )),
            }
        }
    }
    if desc.objects.is_empty() {
        warn("the scene has no triangles".into());
    }
    Ok(Imported {
        desc,
        camera_given,
        warnings,
        lit_as_given: false,
    })
}

/// What makes a primitive's triangles: its topology and where its accessors read — the same
/// data through two accessors is the same geometry.
type Geometry = (String, Option<String>, Vec<(String, String)>, u32, Vec<u32>);

/// The default weights of `mesh`'s morph targets (none: no morph targets are applied).
fn weights<'a>(mesh: &gltf::Mesh<'a>) -> &'a [f32] {
    mesh.weights().unwrap_or(&[])
}

fn geometry(prim: &gltf::Primitive, uv_set: u32, weights: &[f32]) -> Geometry {
    let source = |a: &gltf::Accessor| match (a.view(), a.sparse()) {
        (Some(view), None) => format!(
            "view {} +{} {}×{:?} {:?} {}",
            view.index(),
            a.offset(),
            a.count(),
            a.dimensions(),
            a.data_type(),
            a.normalized()
        ),
        // Sparse or zero-filled data: the accessor alone says what it holds.
        _ => format!("accessor {}", a.index()),
    };
    let mut attributes: Vec<(String, String)> = prim
        .attributes()
        .map(|(semantic, accessor)| (format!("{semantic:?}"), source(&accessor)))
        .collect();
    for (k, t) in prim.morph_targets().enumerate() {
        for (what, a) in [
            ("position", t.positions()),
            ("normal", t.normals()),
            ("tangent", t.tangents()),
        ] {
            if let Some(a) = a {
                attributes.push((format!("target {k} {what}"), source(&a)));
            }
        }
    }
    attributes.sort();
    (
        format!("{:?}", prim.mode()),
        prim.indices().map(|a| source(&a)),
        attributes,
        uv_set,
        weights.iter().map(|w| w.to_bits()).collect(),
    )
}

/// The triangles of `part` (`"MESH/PRIMITIVE"`, indices into the file's meshes, in the mesh's
/// own space, no node transform), or with `part == None` every primitive of every node of the
/// file's scene, placed by the node transforms (world space), merged into one mesh.
///
/// In the merged mesh, normals are moved by the inverse transpose of the node's matrix, the
/// triangles of mirroring nodes (negative determinant) are turned around so that their front
/// stays their front, normals and texture coordinates are kept only when every primitive has
/// them, and colours are kept when any has them (white for the others). Nodes whose matrix is
/// singular are left out, as [`import_gltf`] leaves them out.
///
/// The bytes of the file and of every external buffer (up to its declared length) are added to
/// `inputs`.
pub fn read_gltf_part(
    path: &Path,
    part: Option<&str>,
    options: &LoadOptions,
    inputs: &mut Fingerprint,
) -> Result<Mesh, LoadError> {
    GltfFile::open(path, options, inputs)?.part(part)
}

/// A glTF file read once (its document and buffers), whose parts are decoded as asked: a
/// scene of many primitives reads its buffers once, not once per primitive.
pub struct GltfFile {
    asset: Asset,
}

impl GltfFile {
    /// Reads the file at `path` and its buffers, adding their bytes to `inputs`.
    pub fn open(
        path: &Path,
        options: &LoadOptions,
        inputs: &mut Fingerprint,
    ) -> Result<Self, LoadError> {
        Ok(Self {
            asset: Asset::open(path, options, inputs)?,
        })
    }

    /// The triangles of `part`, as [`read_gltf_part`] gives them.
    pub fn part(&self, part: Option<&str>) -> Result<Mesh, LoadError> {
        part_of(&self.asset, part)
    }

    /// The encoded bytes (PNG, JPEG …) of image `index`, which the file holds itself: in a
    /// buffer view (as `.glb` files do) or a `data:` URI.
    pub fn embedded_image(&self, index: u32) -> Result<Vec<u8>, LoadError> {
        self.asset
            .embedded_image(index as usize)
            .map_err(|e| self.asset.error(format!("image {index}: {e}")))
    }
}

fn part_of(asset: &Asset, part: Option<&str>) -> Result<Mesh, LoadError> {
    let doc = &asset.doc;
    if let Some(part) = part {
        let numbers: Option<Vec<usize>> = part.split('/').map(|n| n.trim().parse().ok()).collect();
        let (m, p, s) = match numbers.as_deref() {
            Some(&[m, p]) => (m, p, None),
            Some(&[m, p, s]) => (m, p, Some(s)),
            _ => {
                return Err(asset.error(format!(
                    "part `{part}` is not MESH/PRIMITIVE or MESH/PRIMITIVE/SKIN (indices, like `0/1`)"
                )));
            }
        };
        let skin = match s {
            Some(s) => Some(doc.skins().nth(s).ok_or_else(|| {
                asset.error(format!(
                    "part `{part}`: there is no skin {s} (the file has {})",
                    doc.skins().len()
                ))
            })?),
            None => None,
        };
        let mesh = doc.meshes().nth(m).ok_or_else(|| {
            asset.error(format!(
                "part `{part}`: there is no mesh {m} (the file has {})",
                doc.meshes().len()
            ))
        })?;
        let prim = mesh.primitives().nth(p).ok_or_else(|| {
            asset.error(format!(
                "part `{part}`: mesh {m} has no primitive {p} (it has {})",
                mesh.primitives().len()
            ))
        })?;
        return match asset
            .primitive(&mesh, m, &prim, skin.as_ref())
            .map_err(|e| asset.error(e))?
        {
            Decoded::Triangles(mesh, _) => Ok(mesh),
            Decoded::Skipped(why) => Err(asset.error(why)),
        };
    }
    let (placed, _) = asset.placed_nodes();
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let mut meshes: HashMap<(usize, usize, Option<usize>), Option<Mesh>> = HashMap::new();
    let mut parts = Vec::new();
    for &(i, world) in &placed {
        let Some(mesh) = nodes[i].mesh() else {
            continue;
        };
        if !primitive::placeable(&world) {
            continue; // as import_gltf does (with a warning there)
        }
        // A skinned mesh is posed in world space (one whose skin fails is shown unposed,
        // as import_gltf shows it).
        let skin = nodes[i].skin().filter(|s| {
            mesh.primitives()
                .all(|prim| asset.primitive(&mesh, mesh.index(), &prim, Some(s)).is_ok())
        });
        let world = if skin.is_some() {
            Mat4::IDENTITY
        } else {
            world
        };
        for prim in mesh.primitives() {
            let key = (
                mesh.index(),
                prim.index(),
                skin.as_ref().map(gltf::Skin::index),
            );
            let mesh = match meshes.entry(key) {
                Entry::Occupied(e) => e.into_mut(),
                Entry::Vacant(e) => e.insert(
                    match asset
                        .primitive(&mesh, key.0, &prim, skin.as_ref())
                        .map_err(|e| asset.error(e))?
                    {
                        Decoded::Triangles(m, _) => Some(m),
                        Decoded::Skipped(_) => None,
                    },
                ),
            };
            if mesh.is_some() {
                parts.push((key, world));
            }
        }
    }
    if parts.is_empty() {
        return Err(asset.error("the file's scene has no triangles"));
    }
    let placed: Vec<(&Mesh, Mat4)> = parts
        .iter()
        .filter_map(|(key, world)| Some((meshes[key].as_ref()?, *world)))
        .collect();
    primitive::merge(&placed).map_err(|e| asset.error(e))
}

/// A node's own transform: its `matrix` (column by column), or `T·R·S`. The rotation is
/// normalised (writers round); a zero or non-finite one makes the matrix NaN, so the node and
/// its children are skipped as not placeable.
fn local_matrix(t: gltf::scene::Transform) -> Mat4 {
    match t {
        gltf::scene::Transform::Matrix { matrix } => Mat4::from_cols_array_2d(&matrix),
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => match Vec4::from_array(rotation).try_normalize() {
            Some(q) => Mat4::from_scale_rotation_translation(
                Vec3::from_array(scale),
                Quat::from_vec4(q),
                Vec3::from_array(translation),
            ),
            None => Mat4::NAN,
        },
    }
}

/// Material names, `gltf:<name or index>`, made unique with `#2`, `#3`, …; and the default
/// material's name, unique too.
fn material_names(doc: &gltf::Document) -> (Vec<String>, String) {
    let mut taken = HashSet::new();
    let mut unique = |base: String| {
        let mut name = base.clone();
        let mut n = 1;
        while !taken.insert(name.clone()) {
            n += 1;
            name = format!("{base}#{n}");
        }
        name
    };
    let names = doc
        .materials()
        .map(|m| match m.name().filter(|n| !n.is_empty()) {
            Some(n) => unique(format!("gltf:{n}")),
            None => unique(format!("gltf:{}", m.index().unwrap_or(0))),
        })
        .collect();
    (names, unique("gltf:default".into()))
}

/// A punctual light placed by `world`, with notes on what is not rendered; or why it cannot be.
///
/// Point and spot lights sit at the node's origin, spot and directional lights shine down the
/// node's −z. Intensities are divided by [`LUMENS_PER_WATT`]; point and spot lights fall off
/// quadratically; spot cone angles (radians, from the axis) become `cutoff` (outer) and
/// `cutoff_start` (inner) in degrees.
fn light(
    l: &gltf::khr_lights_punctual::Light,
    world: Mat4,
) -> Result<(LightDesc, Vec<String>), String> {
    use gltf::khr_lights_punctual::Kind;
    let mut notes = Vec::new();
    let color = l.color();
    let intensity = l.intensity();
    if !(intensity.is_finite() && intensity >= 0.0)
        || color.iter().any(|c| !(c.is_finite() && *c >= 0.0))
    {
        return Err(format!(
            "its colour {color:?} or intensity {intensity} is negative or not finite"
        ));
    }
    let radiometric = Rgb::from(color) * (intensity / LUMENS_PER_WATT);
    if !radiometric.is_finite() {
        return Err(format!("its intensity {intensity} is out of range"));
    }
    let kind = match l.kind() {
        Kind::Point => LightKind::Point,
        Kind::Spot { .. } => LightKind::Spot,
        Kind::Directional => LightKind::Directional,
    };
    let mut d = LightDesc::new(kind);
    d.intensity = Some(crate::desc::Color(radiometric));
    let position = world.w_axis.truncate();
    let direction = world.transform_vector3(Vec3::NEG_Z).try_normalize();
    if kind != LightKind::Directional {
        if !position.is_finite() {
            return Err("its node's position is not finite".into());
        }
        d.position = Some(Spanned::new(0..0, Point::from_single(position)));
        d.falloff = Some(Spanned::new(0..0, FalloffName::Quadratic));
        if let Some(range) = l.range() {
            notes.push(format!(
                "range {range} is not rendered: the light reaches everywhere"
            ));
        }
    }
    if kind != LightKind::Point {
        let direction = direction.ok_or("its node's transform flattens its direction")?;
        d.direction = Some(Spanned::new(0..0, Vector(direction)));
    }
    if let Kind::Spot {
        inner_cone_angle,
        outer_cone_angle,
    } = l.kind()
    {
        let outer = outer_cone_angle.to_degrees();
        if !(outer > 0.0 && outer.is_finite()) {
            return Err(format!(
                "its outer cone angle {outer_cone_angle} is not positive"
            ));
        }
        let cutoff = outer.min(90.0);
        if cutoff < outer {
            notes.push(format!("outer cone angle {outer}° is cut to 90°"));
        }
        let inner = inner_cone_angle.to_degrees();
        let start = if inner.is_finite() {
            inner.clamp(0.0, cutoff)
        } else {
            0.0
        };
        if start != inner {
            notes.push(format!("inner cone angle {inner}° is taken as {start}°"));
        }
        d.cutoff = Some(Spanned::new(0..0, Finite(cutoff)));
        d.cutoff_start = Some(Spanned::new(0..0, Finite(start)));
    }
    Ok((d, notes))
}

/// A camera placed by `world`, and the aspect ratio it asks for: the eye at the node's
/// origin, looking down its −z, its +y up. Perspective: `yfov` in degrees. Orthographic: a view
/// `2·ymag` high, of aspect `xmag / ymag`.
fn camera_of(
    projection: &gltf::camera::Projection,
    world: Mat4,
) -> Result<(CameraDesc, Option<f32>), String> {
    let (fov, orthographic, aspect) = match projection {
        gltf::camera::Projection::Perspective(p) => {
            let fov = p.yfov().to_degrees();
            if !(fov > 0.0 && fov < 180.0) {
                return Err(format!(
                    "its vertical field of view {} rad is not between 0 and π",
                    p.yfov()
                ));
            }
            (fov, None, p.aspect_ratio())
        }
        gltf::camera::Projection::Orthographic(o) => {
            let (x, y) = (o.xmag().abs(), o.ymag().abs());
            if !(x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite()) {
                return Err(format!(
                    "its orthographic magnifications {} and {} are not positive and finite",
                    o.xmag(),
                    o.ymag()
                ));
            }
            (45.0, Some(Finite(2.0 * y)), Some(x / y))
        }
    };
    let eye = world.w_axis.truncate();
    let forward = world.transform_vector3(Vec3::NEG_Z).try_normalize();
    let up = world.transform_vector3(Vec3::Y).try_normalize();
    let (Some(forward), Some(up)) = (forward, up) else {
        return Err("its node's transform flattens the view".into());
    };
    if !eye.is_finite() || forward.cross(up).length_squared() < 1e-12 {
        return Err("its node's transform is degenerate".into());
    }
    let camera = CameraDesc {
        eye: Point::from_single(eye),
        look_at: Point::from_single(eye + forward),
        up: Vector(up),
        fov: Finite(fov),
        aperture: None,
        focus_distance: None,
        orthographic,
        motion: None,
        shutter: None,
        medium: None,
    };
    Ok((camera, aspect))
}

/// The image width for `aspect` (width / height) at [`IMAGE_HEIGHT`] pixels high, when it is
/// a size the renderer takes.
fn image_width(aspect: f32) -> Option<u32> {
    let width = (IMAGE_HEIGHT as f32 * aspect).round();
    (width >= 1.0 && width <= crate::build::MAX_IMAGE_SIDE as f32).then_some(width as u32)
}

/// Descriptions of the materials used, for tests of the mapping.
#[cfg(test)]
use asset::parse_document;

#[cfg(test)]
fn described(json: &str) -> Vec<(crate::desc::MaterialDesc, Vec<String>)> {
    described_doc(&parse_document(json.as_bytes(), Path::new("t.gltf"), true).unwrap())
}

/// The materials of `doc` described, with their notes.
#[cfg(test)]
fn described_doc(doc: &gltf::Document) -> Vec<(crate::desc::MaterialDesc, Vec<String>)> {
    let (names, _) = material_names(doc);
    let images = material::Images {
        root: doc.as_json(),
        base_dir: Path::new(""),
        file_name: "test.gltf",
        asset: None,
        options: &LoadOptions::default(),
    };
    doc.materials()
        .map(|m| material::describe(&m, &names[m.index().unwrap()], &images).unwrap())
        .collect()
}

#[cfg(test)]
mod tests;
