//! The render-time scene: flat arrays of shapes, materials and lights, and accelerators.
//!
//! Built once with a [`SceneBuilder`] and immutable afterwards; every query takes `&self`, so
//! threads share one scene.
//!
//! Queries go through two levels: a top-level accelerator over spheres and mesh instances, and
//! one accelerator per mesh over its triangles, entered with the ray carried into the mesh's
//! object space. Infinite planes are tested beside them.
//!
//! Objects that move (see [`crate::motion`]) sit in a second, small top level that
//! [`Scene::at_time`] rebuilds for each instant; everything else is shared between the
//! instants, so cloning a scene or taking it at another time copies only small arrays. A
//! render through a shutter (see `shutter.rs`) builds that level once, over the boxes the
//! objects sweep, and moves the objects under it for each sample.
//!
//! Ties: when two surfaces are hit at exactly the same `t`, the one added first wins (planes
//! before spheres, spheres before meshes, lower triangle index first), whatever the
//! accelerator, so that every accelerator renders the same image.

mod animation;
mod beam;
mod builder;
mod cutout;
mod error;
mod media;
mod packet;
mod query;
mod shutter;
mod solids;

pub use beam::Beam;
pub use builder::SceneBuilder;
pub use error::SceneError;
pub use media::{MediaError, SceneMedia};
pub use shutter::{Shutter, ShutterError};

use crate::Rgb;
use crate::camera::Camera;
use crate::light::{Emitters, Light};
use crate::material::Material;
use crate::shape::SurfaceHit;
use crate::shape::{Csg, Instance, Mesh, Plane, Primitive, Solid, Sphere, SphereMap, TriangleTest};
use crate::texture::{ImageTexture, TexCoords};
use animation::{Animation, Moving};
use lucent_accel::{Aabb, AccelInfo, AccelKind, AnyAccelerator, WideTriangleBvh};
use std::sync::Arc;
use std::time::Duration;

/// Which material a shape wears and which scene object it belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ObjectTag {
    /// Index into [`Scene::materials`].
    pub material: u32,
    /// The object's id, in the order objects were added.
    pub object: u32,
}

/// A mesh with the accelerator over its triangles (in object space).
#[derive(Clone, Debug)]
struct MeshEntry {
    mesh: Mesh,
    accel: MeshAccel,
    bounds: Aabb,
}

/// The accelerator of one mesh: any structure with a per-triangle leaf test, or the wide BVH
/// with its triangles stored in SIMD packs (used for the watertight test, whose SIMD version
/// gives the same hits bit for bit); none for a mesh whose every placement is merged.
#[derive(Clone, Debug)]
enum MeshAccel {
    Generic(AnyAccelerator),
    Packed(WideTriangleBvh),
    Unused,
}

/// Placements stored in world space, together in one mesh with one accelerator: meshes placed
/// once and small meshes (rectangles, cubes, single triangles). A ray meets them without a
/// transform or a level per placement; a scene of a few dozen such objects traces about twice
/// as fast as with one accelerator per object. Hits still name their instance and its own
/// triangle index, so ids, materials, the tie rule and the self-intersection policy are those
/// of the instances.
#[derive(Clone, Debug)]
struct Merged {
    /// World-space positions and triangles, and their accelerator.
    entry: MeshEntry,
    /// For each merged triangle, its instance.
    owner: Vec<u32>,
    /// For each instance, its first merged triangle (`u32::MAX`: not merged).
    first: Vec<u32>,
    /// The instance, when only one is merged (a scene of one mesh): its hits need no lookup
    /// in `owner`, which for a large mesh is a cache miss per hit.
    single: Option<u32>,
    /// For each merged triangle of a placement with a transform, its world normal as the
    /// surface query computes it (the object's face normal through the placement's normal
    /// matrix; zero for the others); empty when no merged placement has a transform. The
    /// Mitsuba scenes' rectangles and cubes are such placements.
    normals: Vec<glam::Vec3>,
}

impl Merged {
    /// The merged index of triangle `tri` of instance `k`, if `k` is merged.
    #[inline]
    fn index(&self, k: u32, tri: u32) -> Option<u32> {
        let first = *self.first.get(k as usize)?;
        (first != u32::MAX).then(|| first + tri)
    }

    /// The instance and its own triangle index of merged triangle `i`.
    #[inline]
    fn source(&self, i: u32) -> (u32, u32) {
        match self.single {
            Some(k) => (k, i),
            None => {
                let k = self.owner[i as usize];
                (k, i - self.first[k as usize])
            }
        }
    }

    /// The world normal of triangle `tri` of instance `k`, if it is merged with a transform.
    #[inline]
    fn normal(&self, k: u32, tri: u32) -> Option<glam::Vec3> {
        let n = *self.normals.get(self.index(k, tri)? as usize)?;
        (n != glam::Vec3::ZERO).then_some(n)
    }

    /// The instance of merged triangle `i`.
    #[inline]
    fn owner_of(&self, i: u32) -> u32 {
        self.single.unwrap_or_else(|| self.owner[i as usize])
    }
}

impl MeshAccel {
    fn info(&self) -> AccelInfo {
        match self {
            MeshAccel::Generic(a) => a.info(),
            MeshAccel::Packed(a) => {
                let (nodes, depth, bytes) = a.info();
                AccelInfo {
                    nodes,
                    depth,
                    bytes,
                }
            }
            MeshAccel::Unused => AccelInfo {
                nodes: 0,
                depth: 0,
                bytes: 0,
            },
        }
    }
}

/// The change of texture coordinates `(du, dv)` that moves a point by `dp` in the tangent
/// plane spanned by `dpdu` and `dpdv`: the least-squares solution of `dpdu·du + dpdv·dv = dp`
/// (pbrt's `ComputeDifferentials`), zero where the tangents are degenerate, clamped to ±10⁸.
fn uv_step(dpdu: glam::Vec3, dpdv: glam::Vec3, dp: glam::Vec3) -> glam::Vec2 {
    let (a00, a01, a11) = (dpdu.dot(dpdu), dpdu.dot(dpdv), dpdv.dot(dpdv));
    let det = a00 * a11 - a01 * a01;
    if !det.is_finite() || det.abs() <= 1e-30 {
        return glam::Vec2::ZERO;
    }
    let (b0, b1) = (dpdu.dot(dp), dpdv.dot(dp));
    let d = glam::Vec2::new(a11 * b0 - a01 * b1, a00 * b1 - a01 * b0) / det;
    if d.is_finite() {
        d.clamp(glam::Vec2::splat(-1e8), glam::Vec2::splat(1e8))
    } else {
        glam::Vec2::ZERO
    }
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The camera and image resolution.
    pub camera: Camera,
    /// The colour of rays that hit nothing.
    pub background: Rgb,
    /// The ambient light `Ia`.
    pub ambient: Rgb,
    /// Materials, referred to by index; not to be changed once the scene is built (what
    /// their hits need is worked out then: [`Scene::material_needs`]).
    pub materials: Vec<Material>,
    /// What a hit on each material needs worked out (parallel to `materials`).
    material_needs: Arc<Vec<MaterialNeeds>>,
    /// Light sources.
    pub lights: Vec<Light>,
    /// Images that textures refer to by index (shared between clones).
    pub images: Arc<Vec<ImageTexture>>,
    /// A lat-long image (an index into `images`) that rays hitting nothing see instead of
    /// `background`.
    pub environment: Option<u32>,
    /// The rotation taking a world direction to the environment image's frame.
    pub environment_to_image: glam::Mat3,
    /// Where the environment image's texels lie on the sphere.
    pub environment_texels: crate::texture::image::LatLongTexels,
    spheres: Arc<Vec<(Sphere, ObjectTag)>>,
    /// How each sphere's texture coordinates lie on it (parallel to `spheres`).
    sphere_maps: Arc<Vec<SphereMap>>,
    /// Boxes, cylinders, cones, discs and tori.
    solids: Arc<Vec<(Solid, ObjectTag)>>,
    /// Solids combined.
    csgs: Arc<Vec<(Csg, ObjectTag)>>,
    planes: Arc<Vec<(Plane, ObjectTag)>>,
    meshes: Arc<Vec<MeshEntry>>,
    instances: Arc<Vec<(Instance, ObjectTag)>>,
    merged: Option<Arc<Merged>>,
    objects: u32,
    /// Top-level primitives that stand still: spheres first, then the instances not merged,
    /// then the merged mesh.
    primitives: Arc<Vec<Primitive>>,
    /// The world-space box of each of them (what `accel` was built from; beams test them).
    primitive_bounds: Arc<Vec<Aabb>>,
    accel: Arc<AnyAccelerator>,
    /// The top level over the moving objects at this scene's instant.
    moving: Option<Arc<Moving>>,
    /// What moves, and how; `None` for a static scene.
    animation: Option<Arc<Animation>>,
    /// The interval a render sees (see [`Scene::with_shutter`]); `None`: one instant.
    shutter: Option<Shutter>,
    /// What a render through the shutter traces; `None` unless something moves.
    blur: Option<Arc<shutter::Blur>>,
    bounds: Aabb,
    triangle_test: TriangleTest,
    /// See [`SceneBuilder::origin`].
    origin: glam::DVec3,
    build_time: Duration,
    /// The lights as the path tracer samples them (area lights and the environment too),
    /// shared between clones.
    pub emitters: Arc<Emitters>,
    /// Whether any material is partly cut away (`Material::opacity`): queries then look past
    /// the surfaces a ray passes through ([`Scene::intersect_opaque`]).
    has_cutouts: bool,
    /// Participating media and the objects that bound them.
    media: Arc<SceneMedia>,
}

/// What a hit on a material needs worked out, decided once when the scene is built: these are
/// asked at every hit, and the material trees are walked to answer them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialNeeds {
    /// Texture coordinates ([`Material::uses_uv`]).
    pub uv: bool,
    /// The surface's tangents ([`Material::needs_tangents`]).
    pub tangents: bool,
}

impl MaterialNeeds {
    /// What `m`'s hits need.
    pub fn of(m: &Material) -> Self {
        Self {
            uv: m.uses_uv(),
            tangents: m.needs_tangents(),
        }
    }
}

/// Counts of what a scene holds, for `lucent info` and statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneCounts {
    /// Objects as the scene file lists them.
    pub objects: u32,
    /// Spheres.
    pub spheres: usize,
    /// Boxes, cylinders, cones, discs, ellipsoids and tori.
    pub solids: usize,
    /// Combinations of solids.
    pub csgs: usize,
    /// Infinite planes.
    pub planes: usize,
    /// Distinct triangle meshes stored (single triangles included).
    pub meshes: usize,
    /// Placements of meshes.
    pub instances: usize,
    /// Triangles as rendered, over all instances.
    pub triangles: usize,
    /// Triangles stored, over the distinct meshes.
    pub unique_triangles: usize,
    /// Light sources.
    pub lights: usize,
    /// Materials.
    pub materials: usize,
}

/// The accelerators of a scene, measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelReport {
    /// Which structure.
    pub kind: AccelKind,
    /// Wall time of building every level.
    pub build_time: Duration,
    /// Nodes or cells over all levels.
    pub nodes: usize,
    /// Deepest path: top level plus the deepest mesh level.
    pub depth: usize,
    /// Bytes of all the structures (not of the geometry).
    pub bytes: usize,
    /// Primitives indexed: top-level primitives plus stored triangles.
    pub primitives: usize,
}

impl Scene {
    /// What the scene holds.
    pub fn counts(&self) -> SceneCounts {
        SceneCounts {
            objects: self.objects,
            spheres: self.spheres.len(),
            solids: self.solids.len(),
            csgs: self.csgs.len(),
            planes: self.planes.len(),
            meshes: self.meshes.len(),
            instances: self.instances.len(),
            triangles: self
                .instances
                .iter()
                .map(|(i, _)| self.meshes[i.mesh as usize].mesh.triangles.len())
                .sum(),
            unique_triangles: self.meshes.iter().map(|m| m.mesh.triangles.len()).sum(),
            lights: self.lights.len(),
            materials: self.materials.len(),
        }
    }

    /// What a ray going in unit direction `dir` sees when it hits nothing: the environment
    /// image, or the background colour.
    #[inline]
    pub fn background_along(&self, dir: glam::Vec3) -> Rgb {
        match self.environment.and_then(|i| self.images.get(i as usize)) {
            Some(image) => {
                let d = (self.environment_to_image * dir).normalize_or_zero();
                image.lookup_direction_with(d, self.environment_texels)
            }
            None => self.background,
        }
    }

    /// The ambient coefficient of `m` at `hit`: `ka`, times `ka_map` looked up there.
    pub fn ambient_coefficient(&self, m: &Material, hit: &SurfaceHit) -> Rgb {
        match &m.ka_map {
            Some(t) => m.ka * t.eval(&self.tex_coords(m, hit, 1.0), &self.images),
            None => m.ka,
        }
    }

    /// The diffuse colour of `m` at `hit`: its texture there filtered over the camera's
    /// one-pixel footprint (the classic integrators trace no ray differentials, and take
    /// pbrt-v4's camera approximation at every bounce; a pixel's few samples then see the
    /// texture's average over it rather than aliasing), times the mesh's vertex colour where
    /// the material takes it.
    #[inline]
    pub fn diffuse(&self, m: &Material, hit: &SurfaceHit) -> Rgb {
        let at = self.tex_coords(m, hit, 1.0);
        let kd = m.kd.eval(&at, &self.images);
        if m.vertex_colors { kd * hit.color } else { kd }
    }

    /// Where `m`'s textures are looked up at `hit`: its texture coordinates (worked out only
    /// when the material reads them) and their footprint, the camera's one-pixel footprint
    /// ([`Camera::footprint`]) times `footprint` (0 for point lookups; pbrt-v4 narrows it to
    /// `1/√spp`, at least 1/8, as samples accumulate).
    pub fn tex_coords(&self, m: &Material, hit: &SurfaceHit, footprint: f32) -> TexCoords {
        let mut at = TexCoords {
            p: hit.texture_coords,
            world: self.in_world(hit.point),
            uv: glam::Vec2::ZERO,
            duv: [glam::Vec2::ZERO; 2],
            color: hit.color,
        };
        if !self.material_needs_of(m, hit.material).uv {
            return at;
        }
        at.uv = hit.uv();
        if footprint > 0.0 {
            let dp = self.camera.footprint(hit.point, hit.normal);
            at.duv = dp.map(|d| uv_step(hit.dpdu, hit.dpdv, d * footprint));
        }
        at
    }

    /// What a hit on material `index` needs; an unknown index needs everything.
    #[inline]
    pub fn material_needs(&self, index: u32) -> MaterialNeeds {
        self.material_needs
            .get(index as usize)
            .copied()
            .unwrap_or(MaterialNeeds {
                uv: true,
                tangents: true,
            })
    }

    /// [`Scene::material_needs`] of `m`, which should be material `index`; worked out from `m`
    /// itself when it is not (a material from elsewhere).
    #[inline]
    fn material_needs_of(&self, m: &Material, index: u32) -> MaterialNeeds {
        match self.materials.get(index as usize) {
            Some(own) if std::ptr::eq(own, m) => self.material_needs(index),
            _ => MaterialNeeds::of(m),
        }
    }

    /// The bounding box of every bounded shape (infinite planes are left out).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Where this scene's coordinates have their zero in the world it was described in (see
    /// [`SceneBuilder::origin`]).
    pub fn origin(&self) -> glam::DVec3 {
        self.origin
    }

    /// Where the scene's point `p` is in the world it was described in.
    pub fn world_point(&self, p: glam::Vec3) -> glam::DVec3 {
        p.as_dvec3() + self.origin
    }

    /// [`Scene::world_point`] in single precision (solid textures are defined there).
    #[inline]
    pub(crate) fn in_world(&self, p: glam::Vec3) -> glam::Vec3 {
        if self.origin == glam::DVec3::ZERO {
            p
        } else {
            self.world_point(p).as_vec3()
        }
    }

    /// The accelerator in use.
    pub fn accelerator(&self) -> AccelKind {
        self.accel.kind()
    }

    /// Size, shape and build time of the accelerators.
    pub fn accel_report(&self) -> AccelReport {
        let top = self.accel.info();
        let merged = self.merged.iter().map(|m| m.entry.accel.info());
        let moving = self.moving.iter().map(|m| m.accel.info());
        let levels = self.meshes.iter().map(|m| m.accel.info()).chain(merged);
        let (mut nodes, mut bytes) = (0, 0);
        for info in moving {
            nodes += info.nodes;
            bytes += info.bytes;
        }
        let moving_primitives = self.moving.as_ref().map_or(0, |m| m.primitives.len());
        let (mut nodes, mut bytes, mut mesh_depth) = (top.nodes + nodes, top.bytes + bytes, 0);
        for info in levels {
            nodes += info.nodes;
            bytes += info.bytes;
            mesh_depth = mesh_depth.max(info.depth);
        }
        AccelReport {
            kind: self.accel.kind(),
            build_time: self.build_time,
            nodes,
            depth: top.depth + mesh_depth,
            bytes,
            primitives: self.primitives.len() + moving_primitives + self.counts().unique_triangles,
        }
    }

    /// Every triangle of every instance, in world space (for comparisons with other ray
    /// tracers, which take a triangle soup).
    pub fn world_triangles(&self) -> Vec<[glam::Vec3; 3]> {
        let mut out = Vec::with_capacity(self.counts().triangles);
        for (instance, _) in self.instances.iter() {
            let mesh = &self.meshes[instance.mesh as usize].mesh;
            for t in 0..mesh.triangles.len() as u32 {
                let v = mesh.vertices(t);
                out.push(match instance.transform {
                    Some(tr) => v.map(|p| tr.point_to_world(p)),
                    None => v,
                });
            }
        }
        out
    }

    /// Bytes of the geometry itself: vertex and index arrays, spheres, solids, planes,
    /// instances.
    pub fn geometry_bytes(&self) -> usize {
        let meshes: usize = self
            .meshes
            .iter()
            .map(|m| m.mesh.positions.len() * 12 + m.mesh.triangles.len() * 12)
            .sum();
        let merged = self.merged.as_ref().map_or(0, |m| {
            m.entry.mesh.positions.len() * 12
                + m.entry.mesh.triangles.len() * 16
                + m.first.len() * 4
                + m.normals.len() * 12
        });
        meshes
            + merged
            + self.spheres.len() * size_of::<(Sphere, ObjectTag)>()
            + self.solids.len() * size_of::<(Solid, ObjectTag)>()
            + self
                .csgs
                .iter()
                .map(|c| c.0.leaves() * size_of::<Solid>())
                .sum::<usize>()
            + self.planes.len() * size_of::<(Plane, ObjectTag)>()
            + self.instances.len() * size_of::<(Instance, ObjectTag)>()
            + self.primitives.len() * size_of::<Primitive>()
    }

    /// The ray–triangle test in use.
    pub fn triangle_test(&self) -> TriangleTest {
        self.triangle_test
    }
}
