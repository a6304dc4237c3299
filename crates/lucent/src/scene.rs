//! The render-time scene: flat arrays of shapes, materials and lights, and an accelerator.
//!
//! Built once with a [`SceneBuilder`] and immutable afterwards; every query takes `&self`, so
//! threads share one scene.

use crate::Rgb;
use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;
use crate::shape::{
    Mesh, Plane, Primitive, Sphere, SurfaceHit, TriangleHit, TriangleTest, triangle,
};
use lucent_accel::{Aabb, AccelKind, Accelerator, AnyAccelerator, Ray, TraversalStats};
use thiserror::Error;

/// Which material a shape wears and which scene object it belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ObjectTag {
    /// Index into [`Scene::materials`].
    pub material: u32,
    /// The object's id, in the order objects were added.
    pub object: u32,
}

/// Why a scene cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SceneError {
    /// A shape names a material that does not exist.
    #[error("object {object} uses material {material}, but the scene has {count} materials")]
    NoSuchMaterial {
        /// The object's id.
        object: u32,
        /// The material index it gave.
        material: u32,
        /// How many materials exist.
        count: usize,
    },
    /// More primitives than indices can address.
    #[error("the scene has {0} primitives; at most {max} are supported", max = u32::MAX)]
    TooManyPrimitives(usize),
    /// A mesh index points past its vertex array.
    #[error(
        "mesh of object {object}: triangle {triangle} uses vertex {vertex}, but it has {count}"
    )]
    VertexOutOfRange {
        /// The object's id.
        object: u32,
        /// The triangle's index.
        triangle: usize,
        /// The bad vertex index.
        vertex: u32,
        /// How many vertices exist.
        count: usize,
    },
}

/// Collects the parts of a scene, then builds it.
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    scene: SceneParts,
}

#[derive(Clone, Debug)]
struct SceneParts {
    camera: Camera,
    background: Rgb,
    ambient: Rgb,
    materials: Vec<Material>,
    lights: Vec<Light>,
    spheres: Vec<(Sphere, ObjectTag)>,
    planes: Vec<(Plane, ObjectTag)>,
    meshes: Vec<(Mesh, ObjectTag)>,
    objects: u32,
    accelerator: AccelKind,
    triangle_test: TriangleTest,
}

impl SceneBuilder {
    /// An empty scene seen by `camera`: black background, no ambient light.
    pub fn new(camera: Camera) -> Self {
        Self {
            scene: SceneParts {
                camera,
                background: Rgb::BLACK,
                ambient: Rgb::BLACK,
                materials: vec![],
                lights: vec![],
                spheres: vec![],
                planes: vec![],
                meshes: vec![],
                objects: 0,
                accelerator: AccelKind::default(),
                triangle_test: TriangleTest::default(),
            },
        }
    }

    /// The colour of rays that hit nothing.
    pub fn background(&mut self, c: Rgb) -> &mut Self {
        self.scene.background = c;
        self
    }

    /// The ambient light `Ia`.
    pub fn ambient(&mut self, c: Rgb) -> &mut Self {
        self.scene.ambient = c;
        self
    }

    /// Which accelerator to build.
    pub fn accelerator(&mut self, kind: AccelKind) -> &mut Self {
        self.scene.accelerator = kind;
        self
    }

    /// Which ray–triangle test to use.
    pub fn triangle_test(&mut self, test: TriangleTest) -> &mut Self {
        self.scene.triangle_test = test;
        self
    }

    /// Adds a material; returns its index.
    pub fn material(&mut self, m: Material) -> u32 {
        self.scene.materials.push(m);
        self.scene.materials.len() as u32 - 1
    }

    /// Adds a light.
    pub fn light(&mut self, l: Light) -> &mut Self {
        self.scene.lights.push(l);
        self
    }

    fn next_tag(&mut self, material: u32) -> ObjectTag {
        self.scene.objects += 1;
        ObjectTag {
            material,
            object: self.scene.objects - 1,
        }
    }

    /// Adds a sphere; returns its object id.
    pub fn sphere(&mut self, s: Sphere, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.scene.spheres.push((s, tag));
        tag.object
    }

    /// Adds an infinite plane; returns its object id.
    pub fn plane(&mut self, p: Plane, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.scene.planes.push((p, tag));
        tag.object
    }

    /// Adds a triangle mesh (a single triangle is a mesh of one); returns its object id.
    pub fn mesh(&mut self, m: Mesh, material: u32) -> u32 {
        let tag = self.next_tag(material);
        self.scene.meshes.push((m, tag));
        tag.object
    }

    /// Checks the parts and builds the accelerator.
    pub fn build(self) -> Result<Scene, SceneError> {
        let p = self.scene;
        let tags = p
            .spheres
            .iter()
            .map(|s| s.1)
            .chain(p.planes.iter().map(|s| s.1));
        for tag in tags.chain(p.meshes.iter().map(|m| m.1)) {
            if tag.material as usize >= p.materials.len() {
                return Err(SceneError::NoSuchMaterial {
                    object: tag.object,
                    material: tag.material,
                    count: p.materials.len(),
                });
            }
        }
        for (mesh, tag) in &p.meshes {
            let count = mesh.positions.len();
            for (triangle, tri) in mesh.triangles.iter().enumerate() {
                if let Some(&vertex) = tri.iter().find(|&&v| v as usize >= count) {
                    return Err(SceneError::VertexOutOfRange {
                        object: tag.object,
                        triangle,
                        vertex,
                        count,
                    });
                }
            }
        }
        let triangles: usize = p.meshes.iter().map(|(m, _)| m.triangles.len()).sum();
        let total = p.spheres.len() + triangles;
        if total > u32::MAX as usize {
            return Err(SceneError::TooManyPrimitives(total));
        }

        let mut primitives = Vec::with_capacity(total);
        let mut boxes = Vec::with_capacity(total);
        for (i, (s, _)) in p.spheres.iter().enumerate() {
            primitives.push(Primitive::Sphere(i as u32));
            boxes.push(s.bounds());
        }
        for (mi, (m, _)) in p.meshes.iter().enumerate() {
            for ti in 0..m.triangles.len() as u32 {
                primitives.push(Primitive::Triangle {
                    mesh: mi as u32,
                    index: ti,
                });
                boxes.push(m.triangle_bounds(ti));
            }
        }
        let accel = p.accelerator.build(&boxes);
        let bounds = boxes.iter().fold(Aabb::EMPTY, |b, x| b.union(*x));
        Ok(Scene {
            camera: p.camera,
            background: p.background,
            ambient: p.ambient,
            materials: p.materials,
            lights: p.lights,
            spheres: p.spheres,
            planes: p.planes,
            meshes: p.meshes,
            objects: p.objects,
            primitives,
            accel,
            bounds,
            triangle_test: p.triangle_test,
        })
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
    /// Materials, referred to by index.
    pub materials: Vec<Material>,
    /// Light sources.
    pub lights: Vec<Light>,
    spheres: Vec<(Sphere, ObjectTag)>,
    planes: Vec<(Plane, ObjectTag)>,
    meshes: Vec<(Mesh, ObjectTag)>,
    objects: u32,
    primitives: Vec<Primitive>,
    accel: AnyAccelerator,
    bounds: Aabb,
    triangle_test: TriangleTest,
}

/// The nearest hit found so far, before its surface is worked out.
#[derive(Clone, Copy)]
enum Candidate {
    Plane(u32, f32),
    Sphere(u32, f32),
    Triangle(u32, u32, TriangleHit),
}

/// Counts of what a scene holds, for `lucent info` and statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneCounts {
    /// Objects as the scene file lists them.
    pub objects: u32,
    /// Spheres.
    pub spheres: usize,
    /// Infinite planes.
    pub planes: usize,
    /// Triangle meshes (single triangles included).
    pub meshes: usize,
    /// Triangles over all meshes.
    pub triangles: usize,
    /// Light sources.
    pub lights: usize,
    /// Materials.
    pub materials: usize,
}

impl Scene {
    /// What the scene holds.
    pub fn counts(&self) -> SceneCounts {
        SceneCounts {
            objects: self.objects,
            spheres: self.spheres.len(),
            planes: self.planes.len(),
            meshes: self.meshes.len(),
            triangles: self.meshes.iter().map(|(m, _)| m.triangles.len()).sum(),
            lights: self.lights.len(),
            materials: self.materials.len(),
        }
    }

    /// The bounding box of every bounded shape (infinite planes are left out).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The accelerator in use.
    pub fn accelerator(&self) -> AccelKind {
        self.accel.kind()
    }

    /// The ray–triangle test in use.
    pub fn triangle_test(&self) -> TriangleTest {
        self.triangle_test
    }

    /// The nearest surface along `ray` (`t > 0`), if any.
    pub fn intersect(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        let mut best = None;
        let mut t_max = f32::INFINITY;
        for (i, (plane, _)) in self.planes.iter().enumerate() {
            if let Some(t) = plane.intersect(ray, t_max) {
                t_max = t;
                best = Some(Candidate::Plane(i as u32, t));
            }
        }
        let test = self.triangle_test;
        self.accel.closest_hit(ray, t_max, stats, |prim, t_max| {
            match self.primitives[prim as usize] {
                Primitive::Sphere(i) => match self.spheres[i as usize].0.intersect(ray, *t_max) {
                    Some(t) => {
                        *t_max = t;
                        best = Some(Candidate::Sphere(i, t));
                        true
                    }
                    None => false,
                },
                Primitive::Triangle { mesh, index } => {
                    let v = self.meshes[mesh as usize].0.vertices(index);
                    match test.intersect(ray, v, *t_max) {
                        Some(hit) => {
                            *t_max = hit.t;
                            best = Some(Candidate::Triangle(mesh, index, hit));
                            true
                        }
                        None => false,
                    }
                }
            }
        });
        best.map(|c| self.surface(ray, c))
    }

    fn surface(&self, ray: &Ray, candidate: Candidate) -> SurfaceHit {
        match candidate {
            Candidate::Plane(i, t) => {
                let (plane, tag) = &self.planes[i as usize];
                // Remove the along-normal rounding error of o + t·d.
                let p = ray.at(t);
                let point = p - plane.normal * plane.normal.dot(p - plane.point);
                let texture_coords = plane.surface_coords(point);
                SurfaceHit {
                    t,
                    point,
                    normal: plane.normal,
                    texture_coords,
                    material: tag.material,
                    object: tag.object,
                }
            }
            Candidate::Sphere(i, t) => {
                let (sphere, tag) = &self.spheres[i as usize];
                let point = sphere.project_to_surface(ray.at(t));
                let normal = sphere.normal_at(point);
                SurfaceHit {
                    t,
                    point,
                    normal,
                    texture_coords: point,
                    material: tag.material,
                    object: tag.object,
                }
            }
            Candidate::Triangle(mesh, index, hit) => {
                let (m, tag) = &self.meshes[mesh as usize];
                let v = m.vertices(index);
                let point = hit.point(v);
                // A triangle that was hit has an area, so its normal exists.
                let normal = triangle::normal(v).unwrap_or(-ray.dir);
                SurfaceHit {
                    t: hit.t,
                    point,
                    normal,
                    texture_coords: point,
                    material: tag.material,
                    object: tag.object,
                }
            }
        }
    }

    /// Walks the shapes that block `ray` in `(0, t_max)`, calling `blocker(material, crossings)`
    /// for each (`crossings`: how many times the segment passes its surface) until it returns
    /// `true`; returns whether it did. Each shape is reported at most once.
    pub fn occlusion<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut blocker: F,
    ) -> bool
    where
        F: FnMut(u32, u32) -> bool,
    {
        for (plane, tag) in &self.planes {
            if plane.intersect(ray, t_max).is_some() && blocker(tag.material, 1) {
                return true;
            }
        }
        let test = self.triangle_test;
        self.accel.any_hit(ray, t_max, stats, |prim| {
            match self.primitives[prim as usize] {
                Primitive::Sphere(i) => {
                    let (sphere, tag) = &self.spheres[i as usize];
                    match sphere.crossings(ray, t_max) {
                        0 => false,
                        n => blocker(tag.material, n),
                    }
                }
                Primitive::Triangle { mesh, index } => {
                    let (m, tag) = &self.meshes[mesh as usize];
                    test.intersect(ray, m.vertices(index), t_max).is_some()
                        && blocker(tag.material, 1)
                }
            }
        })
    }

    /// True when anything lies on `ray` in `(0, t_max)`.
    pub fn occluded(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats) -> bool {
        self.occlusion(ray, t_max, stats, |_, _| true)
    }
}
