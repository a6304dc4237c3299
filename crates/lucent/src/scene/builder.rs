//! Collecting a scene's parts, checking them, and building the accelerators.

use super::animation::{Animation, moved_sphere};
use super::{
    MaterialNeeds, Merged, MeshAccel, MeshEntry, ObjectTag, Scene, SceneError, SceneMedia,
};
use crate::Rgb;
use crate::camera::Camera;
use crate::light::{AreaLights, Emitters, EnvironmentLight, Light};
use crate::material::Material;
use crate::motion::Motion;
use crate::shape::{
    Csg, Instance, Mesh, Plane, Primitive, Solid, Sphere, SphereMap, Transform, TriangleTest,
    triangle,
};
use crate::texture::ImageTexture;
use crate::texture::image::LatLongTexels;
use glam::{Affine3A, Vec3};
use lucent_accel::{Aabb, AccelKind, WideTriangleBvh};
use std::sync::Arc;
use std::time::Instant;

/// Collects the parts of a scene, then builds it.
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    camera: Camera,
    background: Rgb,
    ambient: Rgb,
    materials: Vec<Material>,
    lights: Vec<Light>,
    images: Vec<ImageTexture>,
    environment: Option<u32>,
    environment_to_image: glam::Mat3,
    environment_texels: LatLongTexels,
    spheres: Vec<(Sphere, ObjectTag)>,
    sphere_maps: Vec<SphereMap>,
    pub(super) solids: Vec<(Solid, ObjectTag)>,
    pub(super) csgs: Vec<(Csg, ObjectTag)>,
    planes: Vec<(Plane, ObjectTag)>,
    meshes: Vec<Mesh>,
    instances: Vec<(u32, Affine3A, ObjectTag)>,
    motions: Vec<(u32, Motion)>,
    camera_motion: Option<Motion>,
    pub(super) objects: u32,
    accelerator: AccelKind,
    triangle_test: TriangleTest,
    origin: glam::DVec3,
    pub(super) media: SceneMedia,
}

impl SceneBuilder {
    /// An empty scene seen by `camera`: black background, no ambient light.
    pub fn new(camera: Camera) -> Self {
        Self {
            camera,
            background: Rgb::BLACK,
            ambient: Rgb::BLACK,
            materials: vec![],
            lights: vec![],
            images: vec![],
            environment: None,
            environment_to_image: glam::Mat3::IDENTITY,
            environment_texels: LatLongTexels::Cells,
            spheres: vec![],
            sphere_maps: vec![],
            solids: vec![],
            csgs: vec![],
            planes: vec![],
            meshes: vec![],
            instances: vec![],
            motions: vec![],
            camera_motion: None,
            objects: 0,
            accelerator: AccelKind::default(),
            triangle_test: TriangleTest::default(),
            origin: glam::DVec3::ZERO,
            media: SceneMedia::default(),
        }
    }

    /// Where this scene's coordinates have their zero in the world the scene was described in
    /// (default the world's origin): a scene far out is built relative to a point near its
    /// camera, and solid textures, which are defined in the world, add it back.
    pub fn origin(&mut self, origin: glam::DVec3) -> &mut Self {
        self.origin = origin;
        self
    }

    /// The colour of rays that hit nothing.
    pub fn background(&mut self, c: Rgb) -> &mut Self {
        self.background = c;
        self
    }

    /// The ambient light `Ia`.
    pub fn ambient(&mut self, c: Rgb) -> &mut Self {
        self.ambient = c;
        self
    }

    /// Adds `c` to the ambient light `Ia`.
    pub fn add_ambient(&mut self, c: Rgb) -> &mut Self {
        self.ambient += c;
        self
    }

    /// Which accelerator to build (at both levels).
    pub fn accelerator(&mut self, kind: AccelKind) -> &mut Self {
        self.accelerator = kind;
        self
    }

    /// Which ray–triangle test to use.
    pub fn triangle_test(&mut self, test: TriangleTest) -> &mut Self {
        self.triangle_test = test;
        self
    }

    /// Adds a material; returns its index.
    pub fn material(&mut self, m: Material) -> u32 {
        self.materials.push(m);
        self.materials.len() as u32 - 1
    }

    /// Adds an image for textures to refer to; returns its index.
    pub fn image(&mut self, image: ImageTexture) -> u32 {
        self.images.push(image);
        self.images.len() as u32 - 1
    }

    /// The images added so far, by index.
    pub fn images(&self) -> &[ImageTexture] {
        &self.images
    }

    /// Stored image `id` (from [`SceneBuilder::image`]).
    pub fn stored_image(&self, id: u32) -> Option<&ImageTexture> {
        self.images.get(id as usize)
    }

    /// The lat-long image (by index) that rays hitting nothing see, instead of the background
    /// colour.
    pub fn environment(&mut self, image: Option<u32>) -> &mut Self {
        self.environment = image;
        self
    }

    /// The environment image's orientation: the rotation taking a world direction to the
    /// image's frame (+y up, the centre column along −z). Identity by default.
    pub fn environment_rotation(&mut self, to_image: glam::Mat3) -> &mut Self {
        self.environment_to_image = to_image;
        self
    }

    /// Where the environment image's texels lie on the sphere: centred in their cells (the
    /// default) or on the points of the grid (Mitsuba's `envmap`).
    pub fn environment_texels(&mut self, texels: LatLongTexels) -> &mut Self {
        self.environment_texels = texels;
        self
    }

    /// Adds a light.
    pub fn light(&mut self, l: Light) -> &mut Self {
        self.lights.push(l);
        self
    }

    pub(super) fn next_tag(&mut self, material: u32) -> ObjectTag {
        self.objects += 1;
        ObjectTag {
            material,
            object: self.objects - 1,
        }
    }

    /// Material `i`, if there is one.
    pub(super) fn material_at(&self, i: u32) -> Option<&Material> {
        self.materials.get(i as usize)
    }

    /// How many materials there are.
    pub(super) fn material_count(&self) -> usize {
        self.materials.len()
    }

    /// The motion given for object `object`, if any.
    pub(super) fn motion_of(&self, object: u32) -> Option<&Motion> {
        self.motions
            .iter()
            .rev()
            .find(|(o, _)| *o == object)
            .map(|(_, m)| m)
    }

    /// Adds a sphere; returns its object id.
    pub fn sphere(&mut self, s: Sphere, material: u32) -> u32 {
        self.sphere_mapped(s, material, SphereMap::default())
    }

    /// Adds a sphere whose texture coordinates lie on it as `map` says; returns its object id.
    pub fn sphere_mapped(&mut self, s: Sphere, material: u32, map: SphereMap) -> u32 {
        let tag = self.next_tag(material);
        self.spheres.push((s, tag));
        self.sphere_maps.push(map);
        tag.object
    }

    /// Adds an infinite plane; returns its object id.
    pub fn plane(&mut self, p: Plane, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.planes.push((p, tag));
        tag.object
    }

    /// Stores a mesh without placing it; returns its index for [`SceneBuilder::instance`].
    pub fn add_mesh(&mut self, m: Mesh) -> u32 {
        self.meshes.push(m);
        self.meshes.len() as u32 - 1
    }

    /// Stored mesh `id` (from [`SceneBuilder::add_mesh`]).
    pub fn stored_mesh(&self, id: u32) -> Option<&Mesh> {
        self.meshes.get(id as usize)
    }

    /// Places stored mesh `mesh` by `to_world` (object to world space); returns its object id.
    pub fn instance(&mut self, mesh: u32, to_world: Affine3A, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.instances.push((mesh, to_world, tag));
        tag.object
    }

    /// Adds a mesh placed as it is (a single triangle is a mesh of one); returns its object id.
    pub fn mesh(&mut self, m: Mesh, material: u32) -> u32 {
        let id = self.add_mesh(m);
        self.instance(id, Affine3A::IDENTITY, material)
    }

    /// Moves object `object` (an id from [`SceneBuilder::sphere`], [`SceneBuilder::instance`]
    /// or [`SceneBuilder::mesh`]) by `motion`: at time `t` it is at `motion.at(t) · its
    /// placement` (a sphere's centre is carried, its radius scaled). A later call for the same
    /// object replaces the motion. Planes cannot move, nor objects that emit light (unless the
    /// motion is static), and a sphere's motion must scale alike on every axis: [`build`]
    /// refuses them.
    ///
    /// [`build`]: SceneBuilder::build
    pub fn motion(&mut self, object: u32, motion: Motion) -> &mut Self {
        self.motions.push((object, motion));
        self
    }

    /// Moves the camera by `motion` (see [`crate::camera::Camera::moved`]).
    pub fn camera_motion(&mut self, motion: Motion) -> &mut Self {
        self.camera_motion = Some(motion);
        self
    }

    /// Each object's motion (the last given), checked; `None` where it stands still.
    fn motions(&self) -> Result<Vec<Option<Motion>>, SceneError> {
        let mut of = vec![None; self.objects as usize];
        for (object, motion) in &self.motions {
            let Some(slot) = of.get_mut(*object as usize) else {
                return Err(SceneError::NoSuchObject {
                    object: *object,
                    count: self.objects,
                });
            };
            *slot = Some(motion.clone());
        }
        for (_, tag) in &self.planes {
            if of[tag.object as usize].is_some() {
                return Err(SceneError::PlaneCannotMove(tag.object));
            }
        }
        for (_, tag) in &self.spheres {
            if of[tag.object as usize]
                .as_ref()
                .is_some_and(|m| !m.scales_uniformly())
            {
                return Err(SceneError::SphereScaleNotUniform(tag.object));
            }
        }
        let tags = self.spheres.iter().map(|s| s.1);
        for tag in tags.chain(self.instances.iter().map(|i| i.2)) {
            let moves = of[tag.object as usize]
                .as_ref()
                .is_some_and(|m| !m.is_static());
            if moves && !self.materials[tag.material as usize].ke.is_black() {
                return Err(SceneError::EmitterCannotMove(tag.object));
            }
        }
        Ok(of)
    }

    fn check(&self) -> Result<(), SceneError> {
        self.check_solids()?;
        let tags = self
            .spheres
            .iter()
            .map(|s| s.1)
            .chain(self.planes.iter().map(|s| s.1))
            .chain(self.solids.iter().map(|s| s.1))
            .chain(self.csgs.iter().map(|s| s.1));
        for tag in tags.chain(self.instances.iter().map(|i| i.2)) {
            if tag.material as usize >= self.materials.len() {
                let count = self.materials.len();
                return Err(SceneError::NoSuchMaterial {
                    object: tag.object,
                    material: tag.material,
                    count,
                });
            }
        }
        for &(mesh, _, tag) in &self.instances {
            if mesh as usize >= self.meshes.len() {
                return Err(SceneError::NoSuchMesh {
                    object: tag.object,
                    mesh,
                    count: self.meshes.len(),
                });
            }
        }
        for (i, mesh) in self.meshes.iter().enumerate() {
            let count = mesh.positions.len();
            for (triangle, tri) in mesh.triangles.iter().enumerate() {
                if let Some(&vertex) = tri.iter().find(|&&v| v as usize >= count) {
                    return Err(SceneError::VertexOutOfRange {
                        mesh: i as u32,
                        triangle,
                        vertex,
                        count,
                    });
                }
            }
            let per_vertex = [
                mesh.normals.len(),
                mesh.uvs.len(),
                mesh.colors.len(),
                mesh.tangents.len(),
            ];
            if per_vertex.iter().any(|&n| n != 0 && n != count) {
                let why = mesh.validate().err().unwrap_or_default();
                return Err(SceneError::BadVertexData {
                    mesh: i as u32,
                    why,
                });
            }
            if mesh.triangles.len() > u32::MAX as usize {
                return Err(SceneError::TooManyPrimitives(mesh.triangles.len()));
            }
        }
        let mut textures = Vec::new();
        for m in &self.materials {
            m.kd.images(&mut textures);
            m.surface.visit_textures(&mut |t| t.images(&mut textures));
            for t in m.emission_map.iter().chain(m.opacity.iter()) {
                t.images(&mut textures);
            }
        }
        for image in textures.into_iter().chain(self.environment) {
            if image as usize >= self.images.len() {
                let count = self.images.len();
                return Err(SceneError::NoSuchImage { image, count });
            }
        }
        let top = self.spheres.len() + self.instances.len() + self.solids.len() + self.csgs.len();
        if top > u32::MAX as usize {
            return Err(SceneError::TooManyPrimitives(top));
        }
        Ok(())
    }

    /// Checks the parts and builds the accelerators.
    pub fn build(mut self) -> Result<Scene, SceneError> {
        self.check()?;
        self.media.check(self.objects)?;
        let motions = self.motions()?;
        let start = Instant::now();
        // Static motions are applied once; the others are kept with the objects' rest state,
        // and the objects are put at t = 0 (their boxes then count in the scene's bounds, as
        // the light tables need).
        let mut moving_spheres = Vec::new();
        for (i, (s, tag)) in self.spheres.iter_mut().enumerate() {
            let Some(motion) = motions[tag.object as usize].clone() else {
                continue;
            };
            let rest = *s;
            *s = moved_sphere(&rest, &motion, 0.0);
            if !motion.is_static() {
                moving_spheres.push((i as u32, rest, motion));
            }
        }
        let mut moving_instances = Vec::new();
        for (k, (_, to_world, tag)) in self.instances.iter_mut().enumerate() {
            let Some(motion) = motions[tag.object as usize].clone() else {
                continue;
            };
            let placement = *to_world;
            *to_world = motion.at(0.0) * placement;
            if !motion.is_static() {
                moving_instances.push((k as u32, placement, motion));
            }
        }
        let mut sphere_moves = vec![false; self.spheres.len()];
        for (i, _, _) in &moving_spheres {
            sphere_moves[*i as usize] = true;
        }
        let mut instance_moves = vec![false; self.instances.len()];
        for (k, _, _) in &moving_instances {
            instance_moves[*k as usize] = true;
        }
        let camera_motion = self.camera_motion.take();
        if let Some(m) = camera_motion.as_ref().filter(|m| m.is_static()) {
            self.camera = self.camera.moved(m.at(0.0));
        }
        let camera_motion = camera_motion.filter(|m| !m.is_static());
        let kind = self.accelerator;
        let packed = kind == AccelKind::Wide && self.triangle_test == TriangleTest::Watertight;
        let mesh_accel = |mesh: &Mesh| -> MeshAccel {
            if packed {
                return MeshAccel::Packed(WideTriangleBvh::new(&mesh.positions, &mesh.triangles));
            }
            let boxes: Vec<Aabb> = (0..mesh.triangles.len() as u32)
                .map(|t| mesh.triangle_bounds(t))
                .collect();
            MeshAccel::Generic(kind.build(&boxes))
        };
        // Placements merged into one world-space mesh: of meshes placed once, and of small
        // ones (where the second level costs more than the copy).
        let mut placements = vec![0u32; self.meshes.len()];
        for &(mesh, _, _) in &self.instances {
            placements[mesh as usize] += 1;
        }
        // Within a budget of copied triangles: past it, placements stay instances.
        let mut budget = MERGE_BUDGET;
        // A moving instance is never merged: its triangles move with their transform.
        let merge: Vec<bool> = self
            .instances
            .iter()
            .zip(&instance_moves)
            .map(|(&(mesh, _, _), &moves)| {
                let n = self.meshes[mesh as usize].triangles.len();
                let wanted = !moves && (placements[mesh as usize] == 1 || n <= MERGE_TRIANGLES);
                let fits = n <= budget;
                if wanted && fits {
                    budget -= n;
                }
                wanted && fits
            })
            .collect();
        let mut kept = vec![false; self.meshes.len()];
        for (&(mesh, _, _), &m) in self.instances.iter().zip(&merge) {
            kept[mesh as usize] |= !m;
        }
        let meshes: Vec<MeshEntry> = self
            .meshes
            .into_iter()
            .zip(&kept)
            .map(|(mesh, &kept)| {
                let bounds = (0..mesh.triangles.len() as u32)
                    .fold(Aabb::EMPTY, |a, t| a.union(mesh.triangle_bounds(t)));
                let accel = if kept {
                    mesh_accel(&mesh)
                } else {
                    MeshAccel::Unused
                };
                MeshEntry {
                    accel,
                    bounds,
                    mesh,
                }
            })
            .collect();
        let mut instances = Vec::with_capacity(self.instances.len());
        for (mesh, to_world, tag) in self.instances {
            let transform = if to_world == Affine3A::IDENTITY {
                None
            } else {
                Some(Transform::new(to_world).ok_or(SceneError::SingularTransform(tag.object))?)
            };
            instances.push((Instance { mesh, transform }, tag));
        }
        let merged = merged(&meshes, &instances, &merge, mesh_accel)?;

        let mut primitives = Vec::with_capacity(self.spheres.len() + instances.len());
        let mut boxes = Vec::with_capacity(primitives.capacity());
        // The boxes of the moving objects at t = 0.
        let mut moving_bounds = Aabb::EMPTY;
        for (i, (s, _)) in self.spheres.iter().enumerate() {
            if sphere_moves[i] {
                moving_bounds = moving_bounds.union(s.bounds());
                continue;
            }
            primitives.push(Primitive::Sphere(i as u32));
            boxes.push(s.bounds());
        }
        for (i, (inst, _)) in instances.iter().enumerate() {
            let local = meshes[inst.mesh as usize].bounds;
            let world = inst.transform.map_or(local, |t| t.bounds_to_world(local));
            if instance_moves[i] {
                moving_bounds = moving_bounds.union(world);
                continue;
            }
            if merge[i] {
                continue;
            }
            primitives.push(Primitive::Instance(i as u32));
            boxes.push(world);
        }
        for (j, (s, _)) in self.solids.iter().enumerate() {
            primitives.push(Primitive::Solid(j as u32));
            boxes.push(s.bounds());
        }
        for (j, (c, _)) in self.csgs.iter().enumerate() {
            primitives.push(Primitive::Csg(j as u32));
            boxes.push(c.bounds());
        }
        if let Some(m) = &merged {
            primitives.push(Primitive::Merged);
            boxes.push(m.entry.bounds);
        }
        let accel = kind.build(&boxes);
        let build_time = start.elapsed();
        let static_bounds = boxes.iter().fold(Aabb::EMPTY, |b, x| b.union(*x));
        let bounds = static_bounds.union(moving_bounds);
        let emitters = emitters(
            &self.materials,
            &self.spheres,
            &meshes,
            &instances,
            EnvironmentSource {
                background: self.background,
                image: self.environment.map(|i| &self.images[i as usize]),
                to_image: self.environment_to_image,
            },
            &self.lights,
            self.objects,
            bounds,
        );
        let animated =
            !(moving_spheres.is_empty() && moving_instances.is_empty() && camera_motion.is_none());
        let animation = animated.then(|| {
            Arc::new(Animation {
                spheres: moving_spheres,
                instances: moving_instances,
                camera: camera_motion.map(|m| (self.camera, m)),
                static_bounds,
                kind,
            })
        });
        let has_cutouts = self
            .materials
            .iter()
            .any(|m| m.opacity.is_some() || m.cull_back);
        let material_needs = Arc::new(self.materials.iter().map(MaterialNeeds::of).collect());
        let mut scene = Scene {
            has_cutouts,
            material_needs,
            camera: self.camera,
            background: self.background,
            ambient: self.ambient,
            materials: self.materials,
            lights: self.lights,
            images: Arc::new(self.images),
            environment: self.environment,
            environment_to_image: self.environment_to_image,
            environment_texels: self.environment_texels,
            spheres: Arc::new(self.spheres),
            sphere_maps: Arc::new(self.sphere_maps),
            solids: Arc::new(self.solids),
            csgs: Arc::new(self.csgs),
            planes: Arc::new(self.planes),
            meshes: Arc::new(meshes),
            instances: Arc::new(instances),
            merged: merged.map(Arc::new),
            objects: self.objects,
            primitives: Arc::new(primitives),
            primitive_bounds: Arc::new(boxes),
            accel: Arc::new(accel),
            moving: None,
            animation,
            shutter: None,
            blur: None,
            bounds,
            triangle_test: self.triangle_test,
            origin: self.origin,
            build_time,
            emitters: Arc::new(emitters),
            media: Arc::new(self.media),
        };
        scene.place(0.0);
        Ok(scene)
    }
}

/// Meshes of at most this many triangles are merged into world space wherever they are placed.
const MERGE_TRIANGLES: usize = 64;
/// The most triangles copied into the merged world-space mesh (about 50 MB with its
/// accelerator): a scene of millions of small placements keeps the rest as instances.
const MERGE_BUDGET: usize = 1 << 20;

/// The world-space mesh of the instances marked in `merge` (in instance order), with its
/// accelerator from `accel`; `None` when none is.
fn merged(
    meshes: &[MeshEntry],
    instances: &[(Instance, ObjectTag)],
    merge: &[bool],
    accel: impl Fn(&Mesh) -> MeshAccel,
) -> Result<Option<Merged>, SceneError> {
    if !merge.contains(&true) {
        return Ok(None);
    }
    let mut world = Mesh::default();
    let mut owner = Vec::new();
    let mut first = vec![u32::MAX; instances.len()];
    for (k, ((inst, _), _)) in instances
        .iter()
        .zip(merge)
        .enumerate()
        .filter(|(_, (_, m))| **m)
    {
        let mesh = &meshes[inst.mesh as usize].mesh;
        let base = world.positions.len();
        if base + mesh.positions.len() > u32::MAX as usize
            || owner.len() + mesh.triangles.len() > u32::MAX as usize
        {
            return Err(SceneError::TooManyPrimitives(
                owner.len() + mesh.triangles.len(),
            ));
        }
        first[k] = owner.len() as u32;
        world.positions.extend(
            mesh.positions
                .iter()
                .map(|&p| inst.transform.map_or(p, |t| t.point_to_world(p))),
        );
        let base = base as u32;
        world
            .triangles
            .extend(mesh.triangles.iter().map(|t| t.map(|v| v + base)));
        owner.extend(std::iter::repeat_n(k as u32, mesh.triangles.len()));
    }
    let bounds = (0..world.triangles.len() as u32)
        .fold(Aabb::EMPTY, |a, t| a.union(world.triangle_bounds(t)));
    let transformed = |(inst, _): &(Instance, ObjectTag)| inst.transform.is_some();
    let normals = if instances
        .iter()
        .zip(merge)
        .any(|(i, m)| *m && transformed(i))
    {
        placed_normals(meshes, instances, merge)
    } else {
        Vec::new()
    };
    Ok(Some(Merged {
        entry: MeshEntry {
            accel: accel(&world),
            bounds,
            mesh: world,
        },
        single: (merge.iter().filter(|&&m| m).count() == 1)
            .then(|| first.iter().position(|&f| f != u32::MAX))
            .flatten()
            .map(|k| k as u32),
        owner,
        first,
        normals,
    }))
}

/// The world normals of the merged triangles (see `Merged::normals`), in merged order.
fn placed_normals(
    meshes: &[MeshEntry],
    instances: &[(Instance, ObjectTag)],
    merge: &[bool],
) -> Vec<Vec3> {
    let mut normals = Vec::new();
    for ((inst, _), _) in instances.iter().zip(merge).filter(|(_, m)| **m) {
        let mesh = &meshes[inst.mesh as usize].mesh;
        normals.extend(
            (0..mesh.triangles.len() as u32).map(|tri| match inst.transform {
                // As the surface query computes it from the object's corners.
                Some(t) => {
                    t.normal_to_world(triangle::normal(mesh.vertices(tri)).unwrap_or(Vec3::Z))
                }
                None => Vec3::ZERO,
            }),
        );
    }
    normals
}

/// What rays that miss the scene see: the environment light of the path tracer.
struct EnvironmentSource<'a> {
    background: Rgb,
    image: Option<&'a ImageTexture>,
    to_image: glam::Mat3,
}

/// The lights of the path tracer: every emitting sphere and mesh instance (in world space),
/// the environment, and the point-like `lights`.
#[allow(clippy::too_many_arguments)]
fn emitters(
    materials: &[Material],
    spheres: &[(Sphere, ObjectTag)],
    meshes: &[MeshEntry],
    instances: &[(Instance, ObjectTag)],
    environment: EnvironmentSource,
    lights: &[Light],
    objects: u32,
    bounds: Aabb,
) -> Emitters {
    // A textured emission is not sampled as a light: it is found by the rays that hit it.
    let emits = |tag: &ObjectTag| {
        let m = &materials[tag.material as usize];
        (!m.ke.is_black() && m.emission_map.is_none()).then_some(m.ke)
    };
    let mut area = AreaLights::default();
    for (s, tag) in spheres {
        if let Some(ke) = emits(tag) {
            area.add_sphere(tag.object, ke, s.center, s.radius);
        }
    }
    for (inst, tag) in instances {
        let Some(ke) = emits(tag) else { continue };
        let mesh = &meshes[inst.mesh as usize].mesh;
        // A mirroring placement reverses the winding; the front side stays the front.
        let mirrored = inst
            .transform
            .is_some_and(|t| t.to_world().matrix3.determinant() < 0.0);
        let triangles: Vec<[glam::Vec3; 3]> = (0..mesh.triangles.len() as u32)
            .map(|t| {
                let v = mesh.vertices(t);
                let [a, b, c] = inst
                    .transform
                    .map_or(v, |tr| v.map(|p| tr.point_to_world(p)));
                if mirrored { [a, c, b] } else { [a, b, c] }
            })
            .collect();
        area.add_triangles(tag.object, ke, &triangles);
    }
    let environment = match environment.image {
        Some(image) => EnvironmentLight::image(image).map(|e| e.rotated(environment.to_image)),
        None => EnvironmentLight::constant(environment.background),
    };
    let radius = if bounds.is_empty() {
        1.0
    } else {
        0.5 * (bounds.max - bounds.min).length()
    };
    Emitters::new(lights, area, environment, objects, radius)
}
