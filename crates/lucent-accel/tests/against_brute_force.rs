//! Every accelerator gives the same answers as brute force, on random and degenerate inputs.
//!
//! The primitives here are the crate's own currency: solid boxes (a ray hits a box where it
//! enters it) and spheres, written out in the test. Among them: flat boxes (zero extent on an
//! axis), points, boxes stacked exactly on top of each other (ties), NaN and infinite boxes.

use glam::Vec3;
use lucent_accel::{Aabb, AccelKind, Accelerator, Ray, TraversalStats};
use proptest::prelude::*;

#[derive(Clone, Copy, Debug)]
enum Prim {
    Box(Aabb),
    Sphere(Vec3, f32),
}

impl Prim {
    fn bounds(&self) -> Aabb {
        match *self {
            Prim::Box(b) => b,
            Prim::Sphere(c, r) => Aabb::new(c - Vec3::splat(r), c + Vec3::splat(r)),
        }
    }

    /// The nearest hit in `(0, t_max]` (inclusive, so that the caller can break ties).
    fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        // Like every real shape, one with a NaN in its definition is never hit.
        if self.bounds().has_nan() {
            return None;
        }
        let t = match *self {
            Prim::Box(b) => {
                let (enter, _) = b.hit_interval(ray, f32::INFINITY)?;
                // A ray starting inside a box hits it at its exit; keep it simple: at entry > 0.
                (enter > 0.0).then_some(enter)?
            }
            Prim::Sphere(c, r) => {
                let f = ray.origin - c;
                let (a, b, cc) = (ray.dir.dot(ray.dir), ray.dir.dot(f), f.dot(f) - r * r);
                let disc = b * b - a * cc;
                if disc.is_nan() || disc < 0.0 {
                    return None;
                }
                let s = disc.sqrt();
                [(-b - s) / a, (-b + s) / a]
                    .into_iter()
                    .find(|&t| t > 0.0)?
            }
        };
        (t <= t_max).then_some(t)
    }
}

/// The closest hit as (t, primitive), ties broken towards the lower index; and the occlusion
/// answer for a segment of length `segment`.
fn query(
    accel: &impl Accelerator,
    prims: &[Prim],
    ray: &Ray,
    segment: f32,
) -> (Option<(f32, u32)>, bool, Vec<u32>) {
    let mut stats = TraversalStats::default();
    let mut best: Option<(f32, u32)> = None;
    accel.closest_hit(ray, f32::INFINITY, &mut stats, |i, t_max| {
        match prims[i as usize].hit(ray, *t_max) {
            Some(t) if t < *t_max || best.is_some_and(|(bt, bi)| t == bt && i < bi) => {
                *t_max = t;
                best = Some((t, i));
                true
            }
            _ => false,
        }
    });
    let mut blockers = Vec::new();
    let occluded = accel.any_hit(ray, segment, &mut stats, |i| {
        let blocks = prims[i as usize]
            .hit(ray, segment)
            .is_some_and(|t| t < segment);
        if blocks {
            blockers.push(i);
        }
        blocks
    });
    // Every candidate is reported at most once: the any-hit leaf test never sees a duplicate.
    let mut all = Vec::new();
    accel.any_hit(ray, f32::INFINITY, &mut stats, |i| {
        all.push(i);
        false
    });
    (best, occluded, all)
}

fn vec3(range: std::ops::Range<f32>) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(range).prop_map(Vec3::from_array)
}

fn prim() -> impl Strategy<Value = Prim> {
    prop_oneof![
        4 => (vec3(-10.0..10.0), vec3(0.0..3.0)).prop_map(|(c, e)| Prim::Box(Aabb::new(c, c + e))),
        // Flat in one axis: a rectangle, the box of an axis-aligned triangle.
        2 => (vec3(-10.0..10.0), vec3(0.0..3.0), 0..3usize).prop_map(|(c, mut e, axis)| {
            e[axis] = 0.0;
            Prim::Box(Aabb::new(c, c + e))
        }),
        // On a coarse grid, so that faces, planes and corners coincide exactly.
        2 => (prop::array::uniform3(-4i32..4), prop::array::uniform3(0i32..3)).prop_map(|(c, e)| {
            let c = Vec3::from_array(c.map(|v| v as f32));
            Prim::Box(Aabb::new(c, c + Vec3::from_array(e.map(|v| v as f32))))
        }),
        3 => (vec3(-10.0..10.0), 0.0f32..3.0).prop_map(|(c, r)| Prim::Sphere(c, r)),
        1 => Just(Prim::Sphere(Vec3::new(f32::NAN, 0.0, 0.0), 1.0)),
        1 => Just(Prim::Box(Aabb::new(Vec3::splat(f32::NAN), Vec3::splat(f32::NAN)))),
        1 => Just(Prim::Box(Aabb::new(Vec3::new(0.0, 0.0, f32::NEG_INFINITY), Vec3::new(0.5, 0.5, f32::INFINITY)))),
    ]
}

fn scene() -> impl Strategy<Value = Vec<Prim>> {
    prop::collection::vec(prim(), 0..120)
        .prop_flat_map(|prims| {
            // Duplicate some primitives exactly: ties in t between different indices.
            let n = prims.len();
            (
                Just(prims),
                prop::collection::vec(0..n.max(1), 0..(n / 4 + 1)),
            )
        })
        .prop_map(|(mut prims, dups)| {
            for d in dups {
                if let Some(&p) = prims.get(d) {
                    prims.push(p);
                }
            }
            prims
        })
}

fn ray() -> impl Strategy<Value = Ray> {
    let axis_dir = (0..6usize).prop_map(|k| {
        let mut d = Vec3::ZERO;
        d[k % 3] = if k < 3 { 1.0 } else { -1.0 };
        d
    });
    let dir = prop_oneof![
        3 => vec3(-1.0..1.0).prop_filter("non-zero", |d| d.length() > 1e-3).prop_map(|d| d.normalize()),
        1 => axis_dir,
    ];
    // Origins on the grid coordinates too: rays running exactly in the planes of box faces.
    let origin = prop_oneof![
        3 => vec3(-15.0..15.0),
        1 => prop::array::uniform3(-5i32..5).prop_map(|c| Vec3::from_array(c.map(|v| v as f32))),
    ];
    (origin, dir).prop_map(|(o, d)| Ray::new(o, d))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn every_accelerator_answers_like_brute_force(prims in scene(), rays in prop::collection::vec((ray(), 0.0f32..30.0), 1..40)) {
        let boxes: Vec<Aabb> = prims.iter().map(Prim::bounds).collect();
        let oracle = AccelKind::BruteForce.build(&boxes);
        for kind in AccelKind::ALL {
            let accel = kind.build(&boxes);
            match &accel {
                lucent_accel::AnyAccelerator::Bvh(bvh) => prop_assert_eq!(bvh.validate(&boxes), Ok(())),
                lucent_accel::AnyAccelerator::Wide(wide) => prop_assert_eq!(wide.validate(&boxes), Ok(())),
                _ => {}
            }
            for (ray, segment) in &rays {
                let (want_hit, want_occluded, mut want_all) = query(&oracle, &prims, ray, *segment);
                let (hit, occluded, mut all) = query(&accel, &prims, ray, *segment);
                prop_assert_eq!(hit, want_hit, "{} closest hit differs for {:?}", kind, ray);
                prop_assert_eq!(occluded, want_occluded, "{} occlusion differs for {:?}", kind, ray);
                // Candidates: no duplicates, and every primitive the ray can hit is among them.
                all.sort_unstable();
                let len = all.len();
                all.dedup();
                prop_assert_eq!(all.len(), len, "{} reported a primitive twice", kind);
                want_all.retain(|&i| prims[i as usize].hit(ray, f32::INFINITY).is_some());
                for i in want_all {
                    prop_assert!(all.binary_search(&i).is_ok(), "{} never offered primitive {} that the ray hits", kind, i);
                }
            }
        }
    }
}

#[test]
fn empty_and_single_primitive_builds() {
    for kind in AccelKind::ALL {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        let mut stats = TraversalStats::default();
        let empty = kind.build(&[]);
        assert!(
            !empty.closest_hit(&ray, f32::INFINITY, &mut stats, |_, _| true),
            "{kind}"
        );
        assert!(
            !empty.any_hit(&ray, f32::INFINITY, &mut stats, |_| true),
            "{kind}"
        );
        let one = kind.build(&[Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0))]);
        let mut seen = vec![];
        one.any_hit(&ray, f32::INFINITY, &mut stats, |i| {
            seen.push(i);
            false
        });
        assert_eq!(seen, [0], "{kind}");
    }
}
