//! Hostile rays: origins and directions with NaN, ±Inf, zero and subnormal components, through
//! every accelerator and every path of the wide triangle tree (scalar, baseline, from a beam's
//! cut, and packets mixed with ordinary rays). None may panic, and none may report a hit.

use glam::Vec3;
use lucent_accel::triangle::watertight;
use lucent_accel::{
    Aabb, AccelKind, Accelerator, Frustum, Ray, TraversalStats, WideTriangleBvh, wide_bvh::PACKET,
};
use proptest::prelude::*;

/// A component: mostly ordinary, often one of the hostile values.
fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -4.0f32..4.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => Just(f32::MIN_POSITIVE / 8.0),
        1 => Just(f32::MAX),
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(component()).prop_map(Vec3::from_array)
}

/// Whether a ray is one no query should trace: a non-finite origin or direction, or a zero
/// direction.
fn hostile(ray: &Ray) -> bool {
    !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == Vec3::ZERO
}

/// A grid of small triangles around the origin, so that the trees have several levels.
fn soup() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..12 {
        for j in 0..12 {
            for k in 0..3 {
                let c = Vec3::new(i as f32 - 6.0, j as f32 - 6.0, 2.0 * k as f32 - 2.0) * 0.6;
                let base = positions.len() as u32;
                positions.extend([
                    c,
                    c + Vec3::new(0.4, 0.0, 0.0),
                    c + Vec3::new(0.0, 0.4, 0.1),
                ]);
                triangles.push([base, base + 1, base + 2]);
            }
        }
    }
    (positions, triangles)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn hostile_rays_miss_everywhere_without_panicking(origin in vec3(), dir in vec3()) {
        let ray = Ray::new(origin, dir);
        prop_assume!(hostile(&ray));
        let (positions, triangles) = soup();
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::from_points(t.map(|i| positions[i as usize])))
            .collect();
        let mut stats = TraversalStats::default();
        for kind in AccelKind::ALL {
            let accel = kind.build(&boxes);
            let mut found = false;
            accel.closest_hit(&ray, f32::INFINITY, &mut stats, |i, t_max| {
                let v = triangles[i as usize].map(|k| positions[k as usize]);
                match watertight(&ray, v, *t_max) {
                    Some(h) => {
                        *t_max = h.t;
                        found = true;
                        true
                    }
                    None => false,
                }
            });
            prop_assert!(!found, "{kind}: closest hit for {ray:?}");
            let blocked = accel.any_hit(&ray, f32::INFINITY, &mut stats, |i| {
                let v = triangles[i as usize].map(|k| positions[k as usize]);
                watertight(&ray, v, f32::INFINITY).is_some()
            });
            prop_assert!(!blocked, "{kind}: any hit for {ray:?}");
        }

        let packed = WideTriangleBvh::new(&positions, &triangles);
        prop_assert!(packed.closest_hit(&ray, f32::INFINITY, None, &mut stats).is_none());
        prop_assert!(packed.closest_hit_baseline(&ray, f32::INFINITY, None, &mut stats).is_none());
        prop_assert!(!packed.any_hit(&ray, f32::INFINITY, &mut stats, |_| true));
        prop_assert!(!packed.any_hit_baseline(&ray, f32::INFINITY, &mut stats, |_| true));

        // A beam's cut over the whole soup, and a packet of the hostile ray among good ones.
        let eye = Vec3::new(0.0, 0.0, 9.0);
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(x, y)| Vec3::new(x, y, -1.0).normalize());
        let frustum = Frustum::new(eye, corners).expect("a valid beam");
        let cut = packed.cut(&frustum);
        prop_assert!(packed.closest_hit_in(&cut, &ray, f32::INFINITY, None, &mut stats).is_none());
        prop_assert!(!packed.any_hit_in(&cut, &ray, f32::INFINITY, &mut stats, |_| true));
        let good = Ray::new(eye, -Vec3::Z);
        let mut rays = vec![good; PACKET];
        rays[1] = ray;
        let hits = packed.closest_hits_in(&cut, &rays, &[f32::INFINITY; PACKET], &mut stats);
        prop_assert!(hits[1].is_none(), "packet lane of {ray:?}");
        prop_assert_eq!(hits[0], packed.closest_hit(&good, f32::INFINITY, None, &mut stats));
    }
}
