//! Combinations of solids: known hits, surfaces that alternate with the inside test, and normals
//! that face out of the result.

use super::csg::{Csg, CsgError, CsgOp, CsgTree};
use super::{Solid, SolidShape};
use glam::{Affine3A, Quat, Vec3};
use lucent_accel::Ray;
use proptest::prelude::*;

fn leaf(shape: SolidShape, to_world: Affine3A) -> CsgTree {
    CsgTree::Leaf {
        solid: Solid::new(shape, to_world).unwrap(),
        material: 0,
        inverse: false,
    }
}

fn node(op: CsgOp, children: Vec<CsgTree>) -> CsgTree {
    CsgTree::Node {
        op,
        children,
        inverse: false,
    }
}

/// A box of half-size 1 with a cylinder of radius 0.5 bored through it along z.
fn bored_box() -> Csg {
    let bore = Affine3A::from_translation(Vec3::new(0.0, 0.0, -2.0))
        * Affine3A::from_scale(Vec3::new(0.5, 0.5, 4.0));
    let tree = node(
        CsgOp::Difference,
        vec![
            leaf(SolidShape::Box, Affine3A::IDENTITY),
            leaf(SolidShape::Cylinder { open: false }, bore),
        ],
    );
    Csg::new(&tree).unwrap()
}

#[test]
fn a_ray_down_a_bore_passes_through_and_one_beside_it_meets_the_box() {
    let c = bored_box();
    assert_eq!(
        c.nearest(&Ray::new(Vec3::new(0.1, 0.0, 5.0), -Vec3::Z), f32::INFINITY),
        None
    );
    let hit = c
        .nearest(&Ray::new(Vec3::new(0.7, 0.0, 5.0), -Vec3::Z), f32::INFINITY)
        .unwrap();
    assert!((hit.t - 4.0).abs() < 1e-12 && hit.leaf == 0 && !hit.flip);
}

#[test]
fn the_bores_wall_faces_into_the_bore() {
    let c = bored_box();
    // Across the bore at z = 0: the box's face at x = −1, the wall at x = −0.5 (leaving the
    // material into the bore), the wall at 0.5, the face at 1.
    let ray = Ray::new(Vec3::new(-3.0, 0.0, 0.0), Vec3::X);
    let hit = c.nearest(&ray, f32::INFINITY).unwrap();
    assert!((hit.t - 2.0).abs() < 1e-12);
    assert_eq!(c.crossings(&ray, f32::INFINITY), 4);
    let inner = Ray::new(Vec3::new(-0.75, 0.0, 0.0), Vec3::X);
    let wall = c.nearest(&inner, f32::INFINITY).unwrap();
    assert!((wall.t - 0.25).abs() < 1e-12 && wall.leaf == 1 && wall.flip);
    let s = c.surface(&inner, &wall);
    assert!(
        (s.normal - Vec3::X).length() < 1e-6,
        "out of the material, into the bore: {}",
        s.normal
    );
}

#[test]
fn two_overlapping_balls_intersect_in_a_lens() {
    let ball = |x: f32| {
        leaf(
            SolidShape::Ellipsoid,
            Affine3A::from_translation(Vec3::new(x, 0.0, 0.0)),
        )
    };
    let lens = Csg::new(&node(CsgOp::Intersection, vec![ball(-0.5), ball(0.5)])).unwrap();
    let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
    // The lens spans x in [−0.5, 0.5]: the right ball's left side, then the left ball's right.
    let hit = lens.nearest(&ray, f32::INFINITY).unwrap();
    assert!((hit.t - 4.5).abs() < 1e-12 && hit.leaf == 1);
    assert_eq!(lens.crossings(&ray, f32::INFINITY), 2);
    assert!((lens.bounds().min.x + 0.5).abs() < 1e-5 && (lens.bounds().max.x - 0.5).abs() < 1e-5);
    // Merged, the inner surfaces go; as a union, they stay.
    let merged = Csg::new(&node(CsgOp::Merge, vec![ball(-0.5), ball(0.5)])).unwrap();
    let union = Csg::new(&node(CsgOp::Union, vec![ball(-0.5), ball(0.5)])).unwrap();
    assert_eq!(merged.crossings(&ray, f32::INFINITY), 2);
    assert_eq!(union.crossings(&ray, f32::INFINITY), 4);
}

#[test]
fn open_leaves_single_children_and_unbounded_results_are_refused() {
    let disc = leaf(SolidShape::Disc { hole: 0.0 }, Affine3A::IDENTITY);
    let ball = leaf(SolidShape::Ellipsoid, Affine3A::IDENTITY);
    let tree = node(CsgOp::Union, vec![disc, ball.clone()]);
    assert_eq!(Csg::new(&tree), Err(CsgError::Open("disc")));
    assert_eq!(
        Csg::new(&node(CsgOp::Merge, vec![ball.clone()])),
        Err(CsgError::TooFew("merge"))
    );
    let outside = CsgTree::Node {
        op: CsgOp::Union,
        children: vec![ball.clone(), ball],
        inverse: true,
    };
    assert_eq!(Csg::new(&outside), Err(CsgError::Unbounded));
}

/// The closed solids, by number.
fn solid(kind: usize) -> SolidShape {
    [
        SolidShape::Box,
        SolidShape::Cylinder { open: false },
        SolidShape::Cone {
            radii: [1.0, 0.2],
            open: false,
        },
        SolidShape::Ellipsoid,
        SolidShape::Torus { minor: 0.4 },
        SolidShape::Superellipsoid {
            exponents: [0.3, 2.5],
        },
    ][kind]
}

fn placed() -> impl Strategy<Value = CsgTree> {
    (
        0usize..6,
        proptest::array::uniform3(-1.0f32..1.0),
        0.0f32..6.3,
        proptest::array::uniform3(0.4f32..1.5),
        proptest::array::uniform3(-0.8f32..0.8),
        proptest::bool::weighted(0.15),
    )
        .prop_map(|(kind, axis, angle, scale, at, inverse)| {
            let axis = Vec3::from(axis).try_normalize().unwrap_or(Vec3::Y);
            let to_world = Affine3A::from_scale_rotation_translation(
                scale.into(),
                Quat::from_axis_angle(axis, angle),
                at.into(),
            );
            CsgTree::Leaf {
                solid: Solid::new(solid(kind), to_world).unwrap(),
                material: 0,
                inverse,
            }
        })
}

fn op() -> impl Strategy<Value = CsgOp> {
    prop_oneof![
        Just(CsgOp::Merge),
        Just(CsgOp::Intersection),
        Just(CsgOp::Difference)
    ]
}

/// Trees of up to two levels over two or three children, whose first leaf is never inside out
/// (so that the whole stays bounded).
fn tree() -> impl Strategy<Value = CsgTree> {
    let inner = (op(), proptest::collection::vec(placed(), 2..4))
        .prop_map(|(op, children)| node(op, children));
    (
        op(),
        placed(),
        proptest::collection::vec(prop_oneof![placed(), inner], 1..3),
    )
        .prop_map(|(op, first, rest)| {
            let first = match first {
                CsgTree::Leaf {
                    solid, material, ..
                } => CsgTree::Leaf {
                    solid,
                    material,
                    inverse: false,
                },
                other => other,
            };
            node(op, std::iter::once(first).chain(rest).collect())
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Along random rays through random combinations (merge, intersection, difference, parts
    /// inside out): the surfaces alternate between entering and leaving as the inside test
    /// says at every midpoint, and each normal faces out of the result.
    #[test]
    fn surfaces_alternate_with_the_inside_test_and_face_out(
        tree in tree(),
        from in proptest::array::uniform3(-6.0f32..6.0),
        to in proptest::array::uniform3(-1.0f32..1.0),
    ) {
        let Ok(csg) = Csg::new(&tree) else { return Ok(()) };
        let o = Vec3::from(from) + Vec3::new(0.0, 0.0, 9.0);
        let ray = Ray::new(o, (Vec3::from(to) - o).normalize());
        let hits = csg.surfaces(&ray, f32::INFINITY);
        prop_assert_eq!(hits.len() as u32, csg.crossings(&ray, f32::INFINITY));
        let at = |t: f64| (ray.origin.as_dvec3() + ray.dir.as_dvec3() * t).as_vec3();
        let mut inside = csg.contains(ray.origin);
        for (i, h) in hits.iter().enumerate() {
            let before = if i == 0 { 0.0 } else { hits[i - 1].t };
            let after = hits.get(i + 1).map_or(h.t + 2.0, |n| n.t);
            // Surfaces closer than f32 resolves at this scale say nothing of the inside test.
            if h.t - before > 1e-3 && after - h.t > 1e-3 {
                prop_assert_eq!(csg.contains(at(0.5 * (h.t + after))), !inside, "after {} of {:?}", i, hits);
                let s = csg.surface(&ray, h);
                let eps = 2e-4;
                let out = csg.contains(s.point + s.normal * eps);
                let into = csg.contains(s.point - s.normal * eps);
                prop_assert!(!out && into, "normal {} at {} ({:?})", s.normal, s.point, h);
            }
            inside = !inside;
        }
    }
}

#[test]
fn an_unbounded_half_space_cuts_a_ball_into_a_dome() {
    // y < 0.25 as the algebraic surface y − 0.25 = 0, unbounded, intersected with the unit
    // ball: the combination takes the ball's box below the cut (the box stays the ball's).
    let below = super::algebraic::from_terms(&[(1.0, [0, 1, 0]), (-0.25, [0, 0, 0])]).unwrap();
    let half = SolidShape::Algebraic {
        coefficients: below,
        bounds: None,
    };
    let cut = || leaf(half, Affine3A::IDENTITY);
    let ball = || leaf(SolidShape::Ellipsoid, Affine3A::IDENTITY);
    let dome = Csg::new(&node(CsgOp::Intersection, vec![ball(), cut()])).unwrap();
    assert!(dome.bounds().max.y <= 1.0 + 1e-5 && dome.bounds().min.y >= -1.0 - 1e-5);
    // Down from above: the flat cut at y = 0.25, then the ball's bottom.
    let down = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
    let hit = dome.nearest(&down, f32::INFINITY).unwrap();
    assert!((hit.t - 4.75).abs() < 1e-12 && hit.leaf == 1, "{hit:?}");
    assert_eq!(dome.crossings(&down, f32::INFINITY), 2);
    let s = dome.surface(&down, &hit);
    assert!((s.normal - Vec3::Y).length() < 1e-6, "{}", s.normal);
    // Beside the cap, above the cut, nothing.
    let beside = Ray::new(Vec3::new(-5.0, 0.5, 0.0), Vec3::X);
    assert_eq!(dome.nearest(&beside, f32::INFINITY), None);
    assert!(dome.contains(Vec3::new(0.0, 0.0, 0.0)) && !dome.contains(Vec3::new(0.0, 0.5, 0.0)));
    // Alone, or in a union, it has no bounds.
    assert!(!Solid::new(half, Affine3A::IDENTITY).unwrap().is_bounded());
    assert_eq!(
        Csg::new(&node(CsgOp::Union, vec![ball(), cut()])),
        Err(CsgError::Unbounded)
    );
}
