//! Beams: a ray of a beam traced from the beam's cut finds exactly the hit it finds from the
//! root — random scenes, random pinhole cameras, random tiles, rays anywhere in the tile
//! (its corners and edges included); and a shadow ray of a shadow beam (from points of a box
//! towards a point light) traced from its cut meets exactly the blockers it meets from the
//! root.

use glam::{Vec2, Vec3};
use lucent_accel::triangle::watertight;
use lucent_accel::{Accelerator, Frustum, Ray, TraversalStats, WideBvh, WideTriangleBvh};
use proptest::prelude::*;

fn vec3(r: f32) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-r..r).prop_map(Vec3::from_array)
}

/// Small triangles scattered in a cube of side 8, so that the trees have several levels.
fn soup(centres: &[Vec3], offsets: &[[Vec3; 3]]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (i, c) in centres.iter().enumerate() {
        let o = offsets[i % offsets.len()];
        let base = positions.len() as u32;
        positions.extend(o.map(|d| *c + d));
        triangles.push([base, base + 1, base + 2]);
    }
    (positions, triangles)
}

/// A pinhole camera's basis: (forward, right, up), the latter two scaled to the half image.
fn basis(eye: Vec3, target: Vec3, half: f32) -> Option<(Vec3, Vec3, Vec3)> {
    let f = (target - eye).try_normalize()?;
    let r = f.cross(Vec3::Y).try_normalize()?;
    let u = r.cross(f);
    Some((f, r * half, u * half))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn rays_from_the_cut_find_the_hits_rays_from_the_root_find(
        centres in prop::collection::vec(vec3(4.0), 50..1200),
        offsets in prop::collection::vec(prop::array::uniform3(vec3(0.4)), 1..8),
        eye in vec3(9.0),
        target in vec3(1.0),
        half in 0.05f32..1.5,
        tile in (-1.0f32..1.0, -1.0f32..1.0, 0.0f32..0.5, 0.0f32..0.5),
        samples in prop::collection::vec((0.0f32..=1.0, 0.0f32..=1.0), 1..48),
    ) {
        let (positions, triangles) = soup(&centres, &offsets);
        let Some((f, r, u)) = basis(eye, target, half) else { return Ok(()) };
        let (x0, y0) = (tile.0, tile.1);
        let (x1, y1) = (x0 + tile.2 + 1e-3, y0 + tile.3 + 1e-3);
        let dir = |p: Vec2| (f + p.x * r + p.y * u).normalize();
        let corners = [Vec2::new(x0, y0), Vec2::new(x1, y0), Vec2::new(x1, y1), Vec2::new(x0, y1)];
        let Some(frustum) = Frustum::new(eye, corners.map(dir)) else { return Ok(()) };

        let packed = WideTriangleBvh::new(&positions, &triangles);
        let cut = packed.cut(&frustum);
        let boxes: Vec<_> = triangles
            .iter()
            .map(|t| lucent_accel::Aabb::from_points(t.map(|i| positions[i as usize])))
            .collect();
        let generic = WideBvh::new(&boxes);
        let generic_cut = generic.cut(&frustum);

        let points = corners.into_iter().chain(
            samples.iter().map(|&(a, b)| Vec2::new(x0 + a * (x1 - x0), y0 + b * (y1 - y0))),
        );
        for p in points {
            let ray = Ray::new(eye, dir(p));
            let mut stats = TraversalStats::default();
            let key = |h: Option<lucent_accel::wide_bvh::PackedHit>| {
                h.map(|(i, h, _)| (i, h.t.to_bits(), h.bary.map(f32::to_bits)))
            };
            let root = key(packed.closest_hit(&ray, f32::INFINITY, None, &mut stats));
            let from_cut = key(packed.closest_hit_in(&cut, &ray, f32::INFINITY, None, &mut stats));
            prop_assert_eq!(root, from_cut, "packed leaves, cut {:?}", cut.virtual_nodes());

            // The generic leaf test, nearest by (t, index).
            let nearest = |from_cut: bool| {
                let mut best: Option<(f32, u32)> = None;
                let leaf = |i: u32, t_max: &mut f32| {
                    let v = triangles[i as usize].map(|k| positions[k as usize]);
                    match watertight(&ray, v, t_max.next_up()) {
                        Some(h) if best.is_none_or(|(bt, bi)| (h.t, i) < (bt, bi)) => {
                            best = Some((h.t, i));
                            *t_max = h.t;
                            true
                        }
                        _ => false,
                    }
                };
                let mut stats = TraversalStats::default();
                if from_cut {
                    generic.closest_hit_in(&generic_cut, &ray, f32::INFINITY, &mut stats, leaf);
                } else {
                    generic.closest_hit(&ray, f32::INFINITY, &mut stats, leaf);
                }
                best.map(|(t, i)| (t.to_bits(), i))
            };
            prop_assert_eq!(nearest(false), nearest(true), "generic leaves");
        }

        // Packets of the same rays, eight at a time and a partial one at the end (a tile's edge),
        // some with a finite t_max (rays that must miss what lies beyond).
        let rays: Vec<Ray> = corners
            .into_iter()
            .chain(samples.iter().map(|&(a, b)| Vec2::new(x0 + a * (x1 - x0), y0 + b * (y1 - y0))))
            .map(|p| Ray::new(eye, dir(p)))
            .collect();
        let limits: Vec<f32> = (0..rays.len())
            .map(|i| if i % 3 == 2 { 6.0 + i as f32 * 0.25 } else { f32::INFINITY })
            .collect();
        let key = |h: Option<lucent_accel::wide_bvh::PackedHit>| {
            h.map(|(i, h, v)| (i, h.t.to_bits(), h.bary.map(f32::to_bits), v))
        };
        for (chunk, limit) in rays.chunks(8).zip(limits.chunks(8)) {
            let mut stats = TraversalStats::default();
            let hits = packed.closest_hits_in(&cut, chunk, limit, &mut stats);
            for (i, ray) in chunk.iter().enumerate() {
                let alone = packed.closest_hit(ray, limit[i], None, &mut stats);
                prop_assert_eq!(key(alone), key(hits[i]), "packet ray {}", i);
            }
            prop_assert!(hits[chunk.len()..].iter().all(Option::is_none));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn shadow_rays_from_the_cut_meet_the_blockers_rays_from_the_root_meet(
        centres in prop::collection::vec(vec3(4.0), 50..1200),
        offsets in prop::collection::vec(prop::array::uniform3(vec3(0.4)), 1..8),
        light in vec3(9.0),
        corner in vec3(4.0),
        size in vec3(1.5),
        samples in prop::collection::vec(prop::array::uniform3(0.0f32..=1.0), 1..48),
    ) {
        let (positions, triangles) = soup(&centres, &offsets);
        let lo = corner.min(corner + size);
        let targets = lucent_accel::Aabb::new(lo, corner.max(corner + size) + 1e-3);
        let Some(frustum) = Frustum::from_point_over(light, &targets) else { return Ok(()) };
        let packed = WideTriangleBvh::new(&positions, &triangles);
        let cut = packed.cut(&frustum);
        let boxes: Vec<_> = triangles
            .iter()
            .map(|t| lucent_accel::Aabb::from_points(t.map(|i| positions[i as usize])))
            .collect();
        let generic = WideBvh::new(&boxes);
        let generic_cut = generic.cut(&frustum);
        let size = targets.max - targets.min;
        // The box's corners (as shadow rays start there too) and points inside it.
        let corners = (0..8).map(|i| {
            let pick = |bit: usize| ((i >> bit) & 1) as f32;
            targets.min + size * Vec3::new(pick(0), pick(1), pick(2))
        });
        let inside = samples.iter().map(|s| targets.min + size * Vec3::from_array(*s));
        // Vertices of the soup inside the box: rays from them graze their own triangles.
        let vertices = positions.iter().copied().filter(|p| {
            p.cmpge(targets.min).all() && p.cmple(targets.max).all()
        });
        // Points level with the light on an axis: a direction component exactly zero, where
        // the slab test meets 0 · ∞.
        let level = samples.iter().flat_map(|s| {
            let p = targets.min + size * Vec3::from_array(*s);
            (0..3).filter_map(move |a| {
                let mut q = p;
                q[a] = light[a];
                (q[a] >= targets.min[a] && q[a] <= targets.max[a]).then_some(q)
            })
        });
        for origin in corners.chain(inside).chain(vertices.take(32)).chain(level) {
            let offset = light - origin;
            let distance = offset.length();
            if distance <= 0.0 {
                continue;
            }
            let ray = Ray::new(origin, offset / distance);
            let mut stats = TraversalStats::default();
            let all = |from_cut: bool| {
                let mut met = Vec::new();
                let leaf = |i: u32| {
                    met.push(i);
                    false
                };
                let mut stats = TraversalStats::default();
                if from_cut {
                    packed.any_hit_in(&cut, &ray, distance, &mut stats, leaf);
                } else {
                    packed.any_hit(&ray, distance, &mut stats, leaf);
                }
                met.sort_unstable();
                met
            };
            let met = all(false);
            prop_assert_eq!(&met, &all(true), "packed leaves: every blocker");
            let blocked = packed.any_hit(&ray, distance, &mut stats, |_| true);
            prop_assert_eq!(blocked, !met.is_empty());
            prop_assert_eq!(blocked, packed.any_hit_in(&cut, &ray, distance, &mut stats, |_| true));

            let generic_met = |from_cut: bool| {
                let mut met = Vec::new();
                let leaf = |i: u32| {
                    let v = triangles[i as usize].map(|k| positions[k as usize]);
                    if watertight(&ray, v, distance).is_some() {
                        met.push(i);
                    }
                    false
                };
                let mut stats = TraversalStats::default();
                if from_cut {
                    generic.any_hit_in(&generic_cut, &ray, distance, &mut stats, leaf);
                } else {
                    generic.any_hit(&ray, distance, &mut stats, leaf);
                }
                met.sort_unstable();
                met
            };
            prop_assert_eq!(generic_met(false), generic_met(true), "generic leaves");
        }
    }
}

#[test]
fn a_beam_beside_the_scene_misses_it_and_a_narrow_one_skips_levels() {
    let centres: Vec<Vec3> = (0..4096)
        .map(|i| Vec3::new((i % 16) as f32, ((i / 16) % 16) as f32, (i / 256) as f32) * 0.5)
        .collect();
    let (positions, triangles) = soup(&centres, &[[Vec3::ZERO, Vec3::X * 0.2, Vec3::Y * 0.2]]);
    let bvh = WideTriangleBvh::new(&positions, &triangles);
    let eye = Vec3::new(3.55, 3.55, -10.0);
    let beam = |dx: f32, dy: f32, w: f32| {
        let c = |x: f32, y: f32| Vec3::new(x, y, 1.0);
        Frustum::new(
            eye,
            [c(dx, dy), c(dx + w, dy), c(dx + w, dy + w), c(dx, dy + w)],
        )
        .unwrap()
    };
    assert!(bvh.cut(&beam(2.0, 2.0, 0.01)).misses());
    let narrow = bvh.cut(&beam(0.0, 0.0, 0.002));
    assert!(!narrow.misses() && narrow.virtual_nodes() >= 1);
    // Its rays visit fewer nodes from the cut than from the root, and hit the same triangle.
    let ray = Ray::new(eye, Vec3::new(0.001, 0.001, 1.0));
    let (mut from_root, mut from_cut) = (TraversalStats::default(), TraversalStats::default());
    let a = bvh.closest_hit(&ray, f32::INFINITY, None, &mut from_root);
    let b = bvh.closest_hit_in(&narrow, &ray, f32::INFINITY, None, &mut from_cut);
    assert_eq!(a.map(|h| h.0), b.map(|h| h.0));
    assert!(a.is_some());
    assert!(
        from_cut.nodes_visited < from_root.nodes_visited,
        "{from_cut:?} vs {from_root:?}"
    );
}

#[test]
fn a_shadow_beam_over_a_small_patch_skips_levels_and_meets_the_same_blockers() {
    let centres: Vec<Vec3> = (0..4096)
        .map(|i| Vec3::new((i % 16) as f32, ((i / 16) % 16) as f32, (i / 256) as f32) * 0.5)
        .collect();
    let (positions, triangles) = soup(&centres, &[[Vec3::ZERO, Vec3::X * 0.2, Vec3::Y * 0.2]]);
    let bvh = WideTriangleBvh::new(&positions, &triangles);
    let light = Vec3::new(3.6, 3.6, -10.0);
    let patch = lucent_accel::Aabb::new(Vec3::new(1.0, 1.0, 9.0), Vec3::new(1.3, 1.3, 9.1));
    let cut = bvh.cut(&Frustum::from_point_over(light, &patch).unwrap());
    assert!(!cut.misses() && cut.virtual_nodes() >= 1);
    let (mut from_root, mut from_cut) = (TraversalStats::default(), TraversalStats::default());
    for k in 0..16 {
        let origin = patch.min + (patch.max - patch.min) * (k as f32 / 15.0);
        let offset = light - origin;
        let ray = Ray::new(origin, offset.normalize());
        let t = offset.length();
        let a = bvh.any_hit(&ray, t, &mut from_root, |_| true);
        let b = bvh.any_hit_in(&cut, &ray, t, &mut from_cut, |_| true);
        assert_eq!(a, b);
    }
    assert!(
        from_cut.nodes_visited < from_root.nodes_visited,
        "{from_cut:?} vs {from_root:?}"
    );
}

#[test]
fn packets_of_axis_parallel_and_missing_rays_find_what_single_rays_find() {
    let centres: Vec<Vec3> = (0..4096)
        .map(|i| Vec3::new((i % 16) as f32, ((i / 16) % 16) as f32, (i / 256) as f32) * 0.5)
        .collect();
    let (positions, triangles) = soup(&centres, &[[Vec3::ZERO, Vec3::X * 0.2, Vec3::Y * 0.2]]);
    let bvh = WideTriangleBvh::new(&positions, &triangles);
    // From a point level with a column of triangles' corners: the central rays have two zero
    // direction components, and their neighbours graze the corners; the outer ones miss.
    let eye = Vec3::new(3.5, 3.5, -10.0);
    let c = |x: f32, y: f32| Vec3::new(x, y, 1.0);
    let w = 0.3;
    let frustum = Frustum::new(eye, [c(-w, -w), c(w, -w), c(w, w), c(-w, w)]).unwrap();
    let cut = bvh.cut(&frustum);
    let dirs: Vec<Vec3> = [
        0.0, 1e-7, -1e-7, 0.01, 0.02, 0.29, -0.29, 0.3, -0.3, 0.1, -0.1,
    ]
    .iter()
    .flat_map(|&x| [0.0, 1e-7, 0.29, -0.3].map(move |y| c(x, y)))
    .collect();
    let rays: Vec<Ray> = dirs.iter().map(|d| Ray::new(eye, d.normalize())).collect();
    let mut stats = TraversalStats::default();
    let (mut hit, mut missed) = (0, 0);
    for chunk in rays.chunks(8) {
        let limits = vec![f32::INFINITY; chunk.len()];
        let hits = bvh.closest_hits_in(&cut, chunk, &limits, &mut stats);
        for (i, ray) in chunk.iter().enumerate() {
            let alone = bvh.closest_hit(ray, f32::INFINITY, None, &mut stats);
            let key = |h: Option<lucent_accel::wide_bvh::PackedHit>| {
                h.map(|(i, h, _)| (i, h.t.to_bits(), h.bary.map(f32::to_bits)))
            };
            assert_eq!(key(alone), key(hits[i]), "{ray:?}");
            if alone.is_some() {
                hit += 1;
            } else {
                missed += 1;
            }
        }
    }
    assert!(hit > 0 && missed > 0, "{hit} hit, {missed} missed");
}
