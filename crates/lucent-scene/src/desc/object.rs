//! `[[object]]` tables.

use super::{Finite, Matrix, MotionDesc, Point, Scale, Vector};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// The kinds of object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ObjectKind {
    /// `center`, `radius`.
    Sphere,
    /// `point`, `normal`.
    Plane,
    /// `vertices` (three points).
    Triangle,
    /// `positions`, `indices` (three per triangle), `normals` (one per position, for smooth
    /// shading): a mesh written in the scene file.
    Triangles,
    /// `file` (OBJ, PLY, glTF), `part`, `smooth`, and a placement.
    Mesh,
    /// The square `[-1, 1]²` in the plane z = 0, facing +z, and a placement.
    Rectangle,
    /// The cube `[-1, 1]³`, facing out, and a placement.
    Cube,
    /// The disk of radius 1 in the plane z = 0, facing +z, and a placement.
    Disk,
    /// A box from `min` to `max` (an exact solid, not triangles), and a placement.
    Box,
    /// `base`, `cap`, `radius`, `open`, and a placement.
    Cylinder,
    /// `base`, `cap`, `base_radius`, `cap_radius`, `open`, and a placement.
    Cone,
    /// `center`, `normal`, `radius`, `hole` (an exact disc), and a placement.
    Disc,
    /// `major`, `minor` about the y axis at the origin (POV-Ray's), and a placement.
    Torus,
    /// `center`, `radii` (along x, y, z), and a placement.
    Ellipsoid,
    /// `exponents` (`[e, n]`, POV-Ray's) in the cube `[-1, 1]³`, and a placement.
    Superellipsoid,
    /// `terms` (`[coefficient, i, j, k]` for each `c·xⁱ·yʲ·zᵏ`, of degree ≤ 4): where the
    /// polynomial is zero, inside where it is negative; `bounds` (`[min, max]`) to cut it to a
    /// box, and a placement. Unbounded, it can only be part of a combination.
    Algebraic,
    /// `children` (two or more), all their surfaces; a placement.
    Union,
    /// `children`: where all of them are; a placement.
    Intersection,
    /// `children`: the first without the others; a placement.
    Difference,
    /// `children`: where any of them is, only the outer surfaces; a placement.
    Merge,
}

impl ObjectKind {
    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            ObjectKind::Sphere => "sphere",
            ObjectKind::Plane => "plane",
            ObjectKind::Triangle => "triangle",
            ObjectKind::Triangles => "triangles",
            ObjectKind::Mesh => "mesh",
            ObjectKind::Rectangle => "rectangle",
            ObjectKind::Cube => "cube",
            ObjectKind::Disk => "disk",
            ObjectKind::Box => "box",
            ObjectKind::Cylinder => "cylinder",
            ObjectKind::Cone => "cone",
            ObjectKind::Disc => "disc",
            ObjectKind::Torus => "torus",
            ObjectKind::Ellipsoid => "ellipsoid",
            ObjectKind::Superellipsoid => "superellipsoid",
            ObjectKind::Algebraic => "algebraic",
            ObjectKind::Union => "union",
            ObjectKind::Intersection => "intersection",
            ObjectKind::Difference => "difference",
            ObjectKind::Merge => "merge",
        }
    }
}

/// One `[[object]]`. Which keys apply depends on `type`; the others are refused in build.
///
/// A placement (meshes, rectangles, cubes, disks) is either `transform` or any of `scale`,
/// `rotate`, `translate` (applied in that order).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// What it is.
    #[serde(rename = "type")]
    pub kind: ObjectKind,
    /// The name of its material (a combination's child without one wears its parent's; at the
    /// top level it is required, which the build checks: empty here when not given).
    #[serde(default = "no_material", skip_serializing_if = "is_unnamed")]
    pub material: Spanned<String>,
    /// Sphere: centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center: Option<Spanned<Point>>,
    /// Sphere: radius, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<Spanned<Finite>>,
    /// Sphere: how its texture coordinates lie on it: the directions of `u = 0` and `u = ¼` on
    /// the equator and of the pole `v = 0` (default `[[0, 0, 1], [-1, 0, 0], [0, 1, 0]]`: the
    /// pole up, `u = ½` facing −z, as an environment map; Mitsuba's spheres are
    /// `[[1, 0, 0], [0, 1, 0], [0, 0, 1]]` turned by their `to_world`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uv_axes: Option<Spanned<[Vector; 3]>>,
    /// Box: the corner of least coordinates.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<Spanned<Point>>,
    /// Box: the corner of greatest coordinates.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<Spanned<Point>>,
    /// Cylinder, cone: the centre of the first end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base: Option<Spanned<Point>>,
    /// Cylinder, cone: the centre of the other end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cap: Option<Spanned<Point>>,
    /// Cone: the radius at `base`, ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_radius: Option<Spanned<Finite>>,
    /// Cone: the radius at `cap`, ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cap_radius: Option<Spanned<Finite>>,
    /// Cylinder, cone: without the end caps (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub open: Option<bool>,
    /// Disc: the radius of a hole about its centre (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hole: Option<Spanned<Finite>>,
    /// Union, intersection, difference, merge: the objects combined (inline tables of the
    /// exact solids, spheres and combinations).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub children: Option<Spanned<Vec<Spanned<ObjectDesc>>>>,
    /// A combination's child: turned inside out (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inverse: Option<bool>,
    /// Superellipsoid: `[e, n]`, the exponents across and along z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exponents: Option<Spanned<[Finite; 2]>>,
    /// Algebraic: the polynomial's terms, `[coefficient, i, j, k]` each.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terms: Option<Spanned<Vec<[f64; 4]>>>,
    /// Algebraic: the box it is cut to, `[min, max]`, before its placement.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bounds: Option<Spanned<[Point; 2]>>,
    /// Ellipsoid: its radii along x, y and z, each > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radii: Option<Spanned<Vector>>,
    /// Torus: the radius of the circle the tube follows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub major: Option<Spanned<Finite>>,
    /// Torus: the tube's radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub minor: Option<Spanned<Finite>>,
    /// Plane: a point on it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point: Option<Spanned<Point>>,
    /// Plane: its normal (non-zero; the front side).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<Spanned<Vector>>,
    /// Triangle: three corners, counter-clockwise seen from the front.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vertices: Option<Spanned<[Point; 3]>>,
    /// Triangles: the vertices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<Spanned<Vec<Point>>>,
    /// Triangles: three indices into `positions` per triangle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indices: Option<Spanned<Vec<[u32; 3]>>>,
    /// Triangles: a normal per position (smooth shading); default none (flat).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normals: Option<Spanned<Vec<Vector>>>,
    /// Mesh: an OBJ, PLY, glTF or GLB file, relative to the scene file's folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<Spanned<String>>,
    /// Mesh: which part of the file (OBJ: the faces of one `usemtl` material; glTF:
    /// `"MESH/PRIMITIVE"`, indices, with no node transform). Default: the whole file (glTF:
    /// every node of its scene, placed by the node transforms).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub part: Option<Spanned<String>>,
    /// Mesh: shade with the file's vertex normals where it has them (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub smooth: Option<bool>,
    /// Mesh and shapes: turn the front side to the back (reverse every triangle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flip_normals: Option<bool>,
    /// Rectangle, cube, disk: `v` grows with the shape's `y` (Mitsuba's uvs, where an image
    /// appears upside down) instead of against it (an image upright; the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flip_v: Option<bool>,
    /// Placement: a whole affine transform (instead of scale, rotate, translate).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transform: Option<Spanned<Matrix>>,
    /// Placement: moved by this after rotating.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<Spanned<Point>>,
    /// Placement: rotated by these angles in degrees about x, then y, then z, after scaling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<Spanned<Vector>>,
    /// Placement: scaled by this first (a number or per axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<Spanned<Scale>>,
    /// Every kind but planes: how it moves (see [`MotionDesc`]), after its placement.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Spanned<MotionDesc>>,
    /// The `[[medium]]` inside (behind the surface's front); default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interior: Option<Spanned<String>>,
    /// The `[[medium]]` outside (in front of the surface); default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exterior: Option<Spanned<String>>,
}

impl ObjectDesc {
    /// An object of `kind` with `material` and every other key missing.
    pub fn new(kind: ObjectKind, material: &str) -> Self {
        Self {
            kind,
            material: Spanned::new(0..0, material.to_string()),
            center: None,
            radius: None,
            uv_axes: None,
            min: None,
            max: None,
            base: None,
            cap: None,
            base_radius: None,
            cap_radius: None,
            open: None,
            hole: None,
            children: None,
            inverse: None,
            radii: None,
            exponents: None,
            terms: None,
            bounds: None,
            major: None,
            minor: None,
            point: None,
            normal: None,
            vertices: None,
            positions: None,
            indices: None,
            normals: None,
            file: None,
            part: None,
            smooth: None,
            flip_normals: None,
            flip_v: None,
            transform: None,
            translate: None,
            rotate: None,
            scale: None,
            motion: None,
            interior: None,
            exterior: None,
        }
    }
}

/// A missing `material`: empty, at no place.
fn no_material() -> Spanned<String> {
    Spanned::new(0..0, String::new())
}

/// Whether no material is named (a child wearing its parent's).
fn is_unnamed(m: &Spanned<String>) -> bool {
    m.get_ref().is_empty()
}
