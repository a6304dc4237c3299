//! The wide BVH's packed triangle leaves give exactly the scalar watertight test's answers, on
//! the AVX2 path and the baseline (SSE) path alike.

use glam::Vec3;
use lucent_accel::triangle::watertight;
use lucent_accel::{Ray, TraversalStats, WideTriangleBvh};
use proptest::prelude::*;

fn vec3(r: f32) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-r..r).prop_map(Vec3::from_array)
}

/// The nearest hit by brute force with the scalar test, ties to the lower index, `t ≤ t_max`.
fn scalar_nearest(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    ray: &Ray,
    t_max: f32,
) -> Option<(u32, f32, [f32; 3])> {
    let mut best: Option<(u32, f32, [f32; 3])> = None;
    for (i, t) in triangles.iter().enumerate() {
        let v = t.map(|k| positions[k as usize]);
        if let Some(h) = watertight(ray, v, f32::INFINITY) {
            let better = h.t <= t_max && best.is_none_or(|(_, bt, _)| h.t < bt);
            if better {
                best = Some((i as u32, h.t, h.bary));
            }
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn packed_leaves_match_the_scalar_test_bit_for_bit(
        points in prop::collection::vec(prop_oneof![3 => vec3(4.0), 1 => prop::array::uniform3(-2i32..3).prop_map(|p| Vec3::from_array(p.map(|v| v as f32)))], 3..60),
        tris in prop::collection::vec(prop::array::uniform3(0usize..1000), 1..80),
        rays in prop::collection::vec((vec3(8.0), vec3(1.0), 0.5f32..30.0), 1..40),
    ) {
        let n = points.len();
        let triangles: Vec<[u32; 3]> = tris.iter().map(|t| t.map(|i| (i % n) as u32)).collect();
        let bvh = WideTriangleBvh::new(&points, &triangles);
        for (origin, dir, t_max) in rays {
            prop_assume!(dir.length() > 1e-3);
            let ray = Ray::new(origin, dir.normalize());
            let mut stats = TraversalStats::default();
            let want = scalar_nearest(&points, &triangles, &ray, t_max);
            let got = bvh.closest_hit(&ray, t_max, None, &mut stats).map(|(i, h, v)| {
                assert_eq!(v, triangles[i as usize].map(|k| points[k as usize]), "the packed hit's vertices");
                (i, h.t, h.bary)
            });
            // The baseline (SSE) path and the AVX2 path (where the processor has it) agree exactly.
            let baseline = bvh.closest_hit_baseline(&ray, t_max, None, &mut stats).map(|(i, h, _)| (i, h.t, h.bary));
            prop_assert_eq!(got.map(|(i, t, b)| (i, t.to_bits(), b.map(f32::to_bits))), baseline.map(|(i, t, b)| (i, t.to_bits(), b.map(f32::to_bits))));
            match (want, got) {
                (None, None) => {}
                (Some((_, wt, _)), Some((gi, gt, gb))) => {
                    // Same t bit for bit; the triangle may differ only in a tie of equal t,
                    // and then its own scalar answer must match exactly.
                    prop_assert_eq!(wt.to_bits(), gt.to_bits());
                    let v = triangles[gi as usize].map(|k| points[k as usize]);
                    let scalar = watertight(&ray, v, f32::INFINITY).expect("the scalar test agrees it is hit");
                    prop_assert_eq!(scalar.t.to_bits(), gt.to_bits());
                    prop_assert_eq!(scalar.bary.map(f32::to_bits), gb.map(f32::to_bits));
                }
                (w, g) => prop_assert!(false, "scalar {:?} vs packed {:?}", w, g),
            }
            // Any hit: the set of triangles blocking (0, t_max) is the scalar one.
            let mut blocked = Vec::new();
            bvh.any_hit(&ray, t_max, &mut stats, |i| { blocked.push(i); false });
            blocked.sort_unstable();
            let mut blocked_baseline = Vec::new();
            bvh.any_hit_baseline(&ray, t_max, &mut stats, |i| { blocked_baseline.push(i); false });
            blocked_baseline.sort_unstable();
            prop_assert_eq!(&blocked, &blocked_baseline);
            let want_blocked: Vec<u32> = (0..triangles.len() as u32)
                .filter(|&i| watertight(&ray, triangles[i as usize].map(|k| points[k as usize]), t_max).is_some())
                .collect();
            prop_assert_eq!(blocked, want_blocked);
        }
    }
}
