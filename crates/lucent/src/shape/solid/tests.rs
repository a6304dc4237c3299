//! Solids placed in the world: hits at known distances, crossings that agree with the inside
//! test, tori against a brute-force search, and rays leaving a surface that do not meet it
//! again where they start.

use super::*;
use crate::spawn::offset_origin;
use glam::Quat;
use proptest::prelude::*;

fn solid(shape: SolidShape, to_world: Affine3A) -> Solid {
    Solid::new(shape, to_world).expect("a regular transform")
}

fn shapes() -> Vec<SolidShape> {
    vec![
        SolidShape::Box,
        SolidShape::Cylinder { open: false },
        SolidShape::Cone {
            radii: [1.0, 0.3],
            open: false,
        },
        SolidShape::Cone {
            radii: [0.0, 0.8],
            open: false,
        },
        SolidShape::Torus { minor: 0.3 },
        SolidShape::Torus { minor: 1.2 },
        SolidShape::Ellipsoid,
        SolidShape::Superellipsoid {
            exponents: [0.4, 1.6],
        },
    ]
}

/// A placement from a rotation, a scale (uneven) and a translation.
fn placement(axis: Vec3, angle: f32, scale: Vec3, offset: Vec3) -> Affine3A {
    Affine3A::from_scale_rotation_translation(
        scale,
        Quat::from_axis_angle(axis.normalize(), angle),
        offset,
    )
}

#[test]
fn a_cylinder_between_two_points_is_hit_at_the_known_distance() {
    // Radius 0.5 from (0, 0, 0) to (0, 2, 0): z turned to y, scaled, placed.
    let to_world = Affine3A::from_rotation_x(-std::f32::consts::FRAC_PI_2)
        * Affine3A::from_scale(Vec3::new(0.5, 0.5, 2.0));
    let c = solid(SolidShape::Cylinder { open: false }, to_world);
    let ray = Ray::new(Vec3::new(-3.0, 1.0, 0.3), Vec3::X);
    let (t, part) = c.nearest(&ray, f32::INFINITY).unwrap();
    // x² = 0.25 − 0.09: x = −0.4.
    assert!((t - 2.6).abs() < 1e-6, "{t}");
    assert_eq!(part, 0);
    let s = c.surface(&ray, t, part);
    assert!(
        (s.normal - Vec3::new(-0.8, 0.0, 0.6)).length() < 1e-6,
        "{}",
        s.normal
    );
    // Down onto the top cap.
    let down = Ray::new(Vec3::new(0.1, 5.0, 0.1), Vec3::NEG_Y);
    let (t, part) = c.nearest(&down, f32::INFINITY).unwrap();
    assert!((t - 3.0).abs() < 1e-6 && part == 2, "{t} {part}");
    assert!((c.surface(&down, t, part).normal - Vec3::Y).length() < 1e-6);
    assert!(c.contains(Vec3::new(0.0, 1.0, 0.0)) && !c.contains(Vec3::new(0.0, 2.1, 0.0)));
}

#[test]
fn a_scaled_torus_is_hit_where_its_tube_lies() {
    // Major radius 2, minor 0.5, about y (POV-Ray's torus), centred at (1, 0, 0).
    let to_world = Affine3A::from_translation(Vec3::X)
        * Affine3A::from_rotation_x(-std::f32::consts::FRAC_PI_2)
        * Affine3A::from_scale(Vec3::splat(2.0));
    let t = solid(SolidShape::Torus { minor: 0.25 }, to_world);
    let ray = Ray::new(Vec3::new(-10.0, 0.0, 0.0), Vec3::X);
    let all: Vec<f64> = t
        .crossings(&ray, f32::INFINITY)
        .iter()
        .map(|c| c.0)
        .collect();
    let want = [8.5, 9.5, 12.5, 13.5];
    assert_eq!(all.len(), 4, "{all:?}");
    for (g, w) in all.iter().zip(want) {
        assert!((g - w).abs() < 1e-9, "{all:?}");
    }
    let s = t.surface(&ray, all[0], 0);
    assert!((s.normal - Vec3::NEG_X).length() < 1e-6, "{}", s.normal);
    // Straight down through the top of the tube at x = 3.
    let down = Ray::new(Vec3::new(3.0, 5.0, 0.0), Vec3::NEG_Y);
    let (d, _) = t.nearest(&down, f32::INFINITY).unwrap();
    assert!((d - 4.5).abs() < 1e-9, "{d}");
    // Only what lies before t_max.
    assert_eq!(t.crossings(&ray, 10.0).len(), 2);
}

#[test]
fn a_disc_is_hit_in_its_ring_and_has_no_inside() {
    let d = solid(
        SolidShape::Disc { hole: 0.5 },
        Affine3A::from_translation(Vec3::new(0.0, 0.0, -4.0)),
    );
    let hit = Ray::new(Vec3::new(0.7, 0.0, 0.0), Vec3::NEG_Z);
    assert_eq!(d.nearest(&hit, f32::INFINITY).map(|c| c.0), Some(4.0));
    let hole = Ray::new(Vec3::new(0.2, 0.0, 0.0), Vec3::NEG_Z);
    assert_eq!(d.nearest(&hole, f32::INFINITY), None);
    assert!(!d.contains(Vec3::new(0.7, 0.0, -4.0)));
}

#[test]
fn a_singular_placement_is_refused() {
    let flat = Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0));
    assert!(Solid::new(SolidShape::Box, flat).is_none());
}

/// The torus's function along the line, in f64, from the canonical equation.
fn torus_f(o: DVec3, d: DVec3, r: f64, t: f64) -> f64 {
    let p = o + d * t;
    let g = p.length_squared() + 1.0 - r * r;
    g * g - 4.0 * (p.x * p.x + p.y * p.y)
}

/// Brute force: the sign changes of the torus's function at 20000 steps along `[0, 20]`,
/// each refined by bisection.
fn torus_reference(o: DVec3, d: DVec3, r: f64) -> Vec<f64> {
    let steps = 20_000;
    let mut out = vec![];
    let mut prev = (0.0, torus_f(o, d, r, 0.0));
    for i in 1..=steps {
        let t = 20.0 * i as f64 / steps as f64;
        let f = torus_f(o, d, r, t);
        if prev.1 * f < 0.0 {
            let (mut a, mut b) = (prev.0, t);
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if (torus_f(o, d, r, m) < 0.0) == (prev.1 < 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            out.push(0.5 * (a + b));
        }
        prev = (t, f);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random rays at random tori (uneven tubes, rays from any side): the same crossings as
    /// the brute-force search.
    #[test]
    fn torus_crossings_match_a_brute_force_search(
        r in 0.05f64..0.9,
        from in proptest::array::uniform3(-4.0f64..4.0),
        to in proptest::array::uniform3(-1.5f64..1.5),
    ) {
        let o = DVec3::from(from) + DVec3::new(0.0, 0.0, 6.0);
        let d = (DVec3::from(to) - o).normalize();
        let mut got = Crossings::new();
        torus::crossings(o, d, r, [0.0, 20.0], &mut got);
        let want = torus_reference(o, d, r);
        prop_assert_eq!(got.len(), want.len(), "{:?} vs {:?}", got, want);
        for (g, w) in got.iter().zip(&want) {
            prop_assert!((g.0 - w).abs() < 1e-9, "{:?} vs {:?}", got, want);
        }
    }

    /// Rays that pass the tube's surface within `gap` of touching it (`gap` down to 1e-6 of
    /// the major radius): crossed twice just inside, missed just outside.
    #[test]
    fn near_tangent_rays_cross_a_torus_as_their_side_of_the_tangent_says(
        r in 0.1f64..0.8,
        phi in 0.0f64..std::f64::consts::TAU,
        theta in 0.0f64..std::f64::consts::TAU,
        turn in 0.0f64..std::f64::consts::PI,
        gap_exp in -6.0f64..-2.0,
        inside in any::<bool>(),
    ) {
        // A point on the tube, its outward normal, and a tangent direction there.
        let centre = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let n = DVec3::new(theta.cos() * phi.cos(), theta.cos() * phi.sin(), theta.sin());
        let p = centre + n * r;
        let (a, b) = n.any_orthonormal_pair();
        let dir = a * turn.cos() + b * turn.sin();
        // The tangent line touches the tube from outside only where the surface curves away
        // from it in every direction: on the outer half of the tube (cos θ > 0).
        prop_assume!(theta.cos() > 0.2);
        let gap = 10f64.powf(gap_exp);
        let o = p + n * if inside { -gap } else { gap } - dir * 5.0;
        let mut got = Crossings::new();
        torus::crossings(o, dir, r, [0.0, 10.0], &mut got);
        let near = got.iter().filter(|c| (c.0 - 5.0).abs() < 0.5).count();
        prop_assert_eq!(near, if inside { 2 } else { 0 }, "{:?}", got);
    }

    /// Any shape under any placement: between each two crossings the ray's midpoint is inside
    /// exactly when it is after an entry, and before the first and after the last it is
    /// outside.
    #[test]
    fn crossings_alternate_and_agree_with_the_inside_test(
        which in 0usize..8,
        axis in proptest::array::uniform3(-1.0f32..1.0),
        angle in 0.0f32..6.3,
        scale in proptest::array::uniform3(0.3f32..3.0),
        offset in proptest::array::uniform3(-2.0f32..2.0),
        from in proptest::array::uniform3(-8.0f32..8.0),
        to in proptest::array::uniform3(-1.0f32..1.0),
    ) {
        prop_assume!(Vec3::from(axis).length() > 0.1);
        let to_world = placement(axis.into(), angle, scale.into(), offset.into());
        let s = solid(shapes()[which], to_world);
        let o = Vec3::from(from) + Vec3::new(0.0, 0.0, 12.0);
        prop_assume!(!s.contains(o));
        let target = to_world.transform_point3(Vec3::from(to));
        let ray = Ray::new(o, (target - o).normalize());
        let c = s.crossings(&ray, f32::INFINITY);
        prop_assert!(c.len() % 2 == 0, "{:?}", c);
        let at = |t: f64| (ray.origin.as_dvec3() + ray.dir.as_dvec3() * t).as_vec3();
        for (i, w) in c.windows(2).enumerate() {
            let gap = w[1].0 - w[0].0;
            // A midpoint closer to the surface than f32 resolves says nothing.
            if gap < 1e-3 {
                continue;
            }
            prop_assert_eq!(s.contains(at(0.5 * (w[0].0 + w[1].0))), i % 2 == 0, "{:?}", c);
        }
        if let Some(last) = c.last() {
            prop_assert!(!s.contains(at(last.0 + 1.0)));
        }
    }

    /// A ray spawned from a hit, outwards or inwards, starts on the side it leaves on and
    /// meets the surface again only as far on as the shape allows: no crossing at its start.
    #[test]
    fn rays_leaving_a_surface_start_on_their_side(
        which in 0usize..8,
        axis in proptest::array::uniform3(-1.0f32..1.0),
        angle in 0.0f32..6.3,
        scale in proptest::array::uniform3(0.3f32..3.0),
        offset in proptest::array::uniform3(-300.0f32..300.0),
        from in proptest::array::uniform3(-8.0f32..8.0),
        to in proptest::array::uniform3(-0.9f32..0.9),
        out in proptest::array::uniform3(-1.0f32..1.0),
    ) {
        prop_assume!(Vec3::from(axis).length() > 0.1 && Vec3::from(out).length() > 0.1);
        let to_world = placement(axis.into(), angle, scale.into(), offset.into());
        let s = solid(shapes()[which], to_world);
        let o = Vec3::from(from) * 3.0 + Vec3::from(to_world.translation) + Vec3::new(0.0, 0.0, 30.0);
        let target = to_world.transform_point3(Vec3::from(to));
        let ray = Ray::new(o, (target - o).normalize());
        let Some((t, part)) = s.nearest(&ray, f32::INFINITY) else {
            return Ok(());
        };
        let hit = s.surface(&ray, t, part);
        let dir = Vec3::from(out).normalize();
        let outward = dir.dot(hit.normal) > 0.0;
        prop_assume!(dir.dot(hit.normal).abs() > 1e-3);
        let n = if outward { hit.normal } else { -hit.normal };
        let start = offset_origin(hit.point, n, hit.error);
        prop_assert_eq!(s.contains(start), !outward, "start {} hit {:?}", start, hit);
        let again = s.crossings(&Ray::new(start, dir), f32::INFINITY);
        let scale_of = to_world.matrix3.abs().to_cols_array().iter().fold(0.0f32, |a, &b| a.max(b));
        if let Some(first) = again.first() {
            prop_assert!(first.0 > 1e-4 * f64::from(scale_of), "{:?}", again);
        }
    }
}
