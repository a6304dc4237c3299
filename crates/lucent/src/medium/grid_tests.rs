use super::grid::{DensityGrid, GridError};
use super::{AlbedoGrid, Interaction, Medium};
use crate::Rgb;
use crate::sampling::Rng;
use glam::{Affine3A, Quat, Vec3};
use std::sync::Arc;

/// A box `length` long in x over the unit square, of `n` voxels along x whose centres hold
/// `a + b·x`: trilinear interpolation reproduces that between the first and last centres,
/// and holds the end values within half a voxel of the faces.
fn ramp(n: usize, length: f32, (a, b): (f32, f32)) -> DensityGrid {
    let values = (0..n)
        .map(|i| a + b * (i as f32 + 0.5) / n as f32 * length)
        .collect();
    let to_world = Affine3A::from_scale(Vec3::new(length, 1.0, 1.0));
    DensityGrid::new([n, 1, 1], values, to_world).unwrap()
}

/// `∫₀^x` of the ramp's density along a ray down its axis, in f64.
fn optical_depth(n: usize, length: f64, (a, b): (f64, f64), x: f64) -> f64 {
    let half = length / n as f64 / 2.0;
    let steps = 20_000;
    let h = x.min(length) / steps as f64;
    let d = |x: f64| a + b * x.clamp(half, length - half);
    (0..steps)
        .map(|i| (d(i as f64 * h) + d((i + 1) as f64 * h)) / 2.0 * h)
        .sum()
}

#[test]
fn lookups_interpolate_between_voxel_centres_and_hold_the_edges() {
    let g = DensityGrid::new([4, 1, 1], vec![0.0, 1.0, 2.0, 3.0], Affine3A::IDENTITY).unwrap();
    let at = |x: f32| g.density(Vec3::new(x, 0.5, 0.5));
    for (x, want) in [
        (0.125, 0.0),
        (0.25, 0.5),
        (0.375, 1.0),
        (0.5, 1.5),
        (0.875, 3.0),
        (0.0, 0.0),
        (1.0, 3.0),
        (0.95, 3.0),
        (1.01, 0.0),
        (-0.01, 0.0),
    ] {
        assert!((at(x) - want).abs() < 1e-5, "at {x}: {} not {want}", at(x));
    }
    // A 2×2×2 grid is the trilinear blend of its corners.
    let corners: Vec<f32> = (0..8).map(|i| i as f32).collect();
    let g = DensityGrid::new([2, 2, 2], corners, Affine3A::IDENTITY).unwrap();
    let p = Vec3::new(0.25 + 0.5 * 0.3, 0.25 + 0.5 * 0.6, 0.25 + 0.5 * 0.9);
    assert!((g.density(p) - (0.3 + 2.0 * 0.6 + 4.0 * 0.9)).abs() < 1e-5);
}

#[test]
fn walks_cover_the_ray_inside_the_box_and_bound_its_density() {
    let mut rng = Rng::new(11);
    let res = [37, 12, 20];
    let values = (0..res.iter().product())
        .map(|_| {
            let v = rng.f32();
            if v < 0.6 { 0.0 } else { v * 5.0 }
        })
        .collect();
    let to_world = Affine3A::from_scale_rotation_translation(
        Vec3::new(3.0, 1.0, 2.0),
        Quat::from_rotation_y(0.4),
        Vec3::new(-1.0, 0.5, 0.2),
    );
    let g = DensityGrid::new(res, values, to_world).unwrap();
    for _ in 0..2000 {
        let origin = Vec3::new(
            rng.f32() * 8.0 - 4.0,
            rng.f32() * 3.0 - 1.0,
            rng.f32() * 6.0 - 3.0,
        );
        let dir = (Vec3::new(rng.f32(), rng.f32(), rng.f32()) - 0.5).normalize();
        let cells: Vec<_> = g.walk(origin, dir, 0.0, 10.0).collect();
        // Contiguous stretches; every point inside the box lies in one.
        for w in cells.windows(2) {
            assert_eq!(w[0].t1, w[1].t0);
        }
        for k in 0..200 {
            let t = k as f32 * 0.05;
            let d = g.density(origin + dir * t);
            let cell = cells.iter().find(|c| c.t0 <= t && t <= c.t1);
            match cell {
                Some(c) => assert!(d <= c.majorant * (1.0 + 1e-5) + 1e-5, "{d} > {c:?}"),
                None => assert!(d == 0.0, "density {d} at t {t} outside every stretch"),
            }
        }
    }
}

#[test]
fn ratio_tracking_is_beer_lambert_through_a_grid() {
    let (n, length, ramp_ab) = (24, 3.0, (0.2, 0.8));
    let g = ramp(n, length, ramp_ab);
    let m = Medium::new(Rgb::new(0.1, 0.6, 1.4), Rgb::new(0.3, 0.2, 0.0), 0.0)
        .with_density(Arc::new(g));
    let mut rng = Rng::new(5);
    // From outside the box, through it and past it; and ending inside it.
    for (start, end) in [(-1.0, 6.0), (-0.5, 2.0)] {
        let samples = 100_000;
        let mut sum = [0f64; 3];
        for _ in 0..samples {
            let origin = Vec3::new(start, 0.5, 0.5);
            let tr = m.transmittance_along((origin, Vec3::X), end, &mut rng);
            for (s, c) in sum.iter_mut().zip(tr.to_array()) {
                *s += f64::from(c);
            }
        }
        let x = f64::from(start + end);
        let depth = optical_depth(n, f64::from(length), (0.2, 0.8), x);
        for (c, st) in m.sigma_t().to_array().into_iter().enumerate() {
            let want = (-f64::from(st) * depth).exp();
            let got = sum[c] / samples as f64;
            assert!(
                (got - want).abs() < 6e-3,
                "channel {c} to {x}: {got} against {want}"
            );
        }
    }
}

#[test]
fn delta_tracking_is_unbiased_in_every_channel_through_a_grid() {
    // Passing: E = Tr(end). Scattering with radiance 1 everywhere: E = albedo·(1 − Tr(end)).
    let (n, length) = (16, 2.0);
    let g = Arc::new(ramp(n, length, (0.5, 1.5)));
    let albedo = Rgb::new(0.9, 0.5, 0.7);
    let m = Medium::from_albedo(Rgb::new(0.4, 1.0, 2.5), albedo, 0.0).with_density(g);
    let mut rng = Rng::new(9);
    let end = 1.6;
    let samples = 60_000;
    let (mut pass, mut scatter) = ([0f64; 3], [0f64; 3]);
    for hero in 0..3 {
        for j in 0..samples {
            let u = (j as f32 + 0.5) / samples as f32;
            let ray = (Vec3::new(0.0, 0.5, 0.5), Vec3::X);
            let (sum, w, ratio) = match m.sample_along(ray, end, hero, u, &mut rng) {
                Interaction::Pass { weight, ratio } => (&mut pass, weight, ratio),
                Interaction::Scatter { t, weight, ratio } => {
                    assert!((0.0..end).contains(&t));
                    (&mut scatter, weight, ratio)
                }
            };
            for (s, c) in sum.iter_mut().zip((w / ratio.mean()).to_array()) {
                *s += f64::from(c);
            }
        }
    }
    let depth = optical_depth(n, f64::from(length), (0.5, 1.5), f64::from(end));
    for c in 0..3 {
        let tr = (-f64::from(m.sigma_t().to_array()[c]) * depth).exp();
        let want_scatter = f64::from(albedo.to_array()[c]) * (1.0 - tr);
        let (p, s) = (
            pass[c] / (3 * samples) as f64,
            scatter[c] / (3 * samples) as f64,
        );
        assert!(
            (p - tr).abs() < 5e-3,
            "channel {c}: passed {p} against {tr}"
        );
        assert!(
            (s - want_scatter).abs() < 5e-3,
            "channel {c}: scattered {s} against {want_scatter}"
        );
    }
}

#[test]
fn a_constant_grid_tracks_as_the_homogeneous_medium() {
    let g = DensityGrid::new([3, 3, 3], vec![2.0; 27], Affine3A::IDENTITY).unwrap();
    let base = Medium::new(Rgb::new(0.3, 0.1, 0.6), Rgb::new(0.5, 0.5, 0.2), 0.0);
    let dense = Medium::new(base.sigma_a * 2.0, base.sigma_s * 2.0, 0.0);
    let m = base.with_density(Arc::new(g));
    let mut rng = Rng::new(3);
    let ray = (Vec3::new(0.5, 0.5, 0.0), Vec3::Z);
    let samples = 50_000;
    let mut sum = Rgb::BLACK;
    for _ in 0..samples {
        sum += m.transmittance_along(ray, 0.8, &mut rng);
    }
    let got = sum / samples as f32;
    let want = dense.transmittance(0.8);
    assert!(
        (got - want).max_channel().abs() < 5e-3,
        "{got:?} against {want:?}"
    );
}

#[test]
fn grids_that_lie_are_refused() {
    let id = Affine3A::IDENTITY;
    assert_eq!(
        DensityGrid::new([2, 2, 2], vec![0.0; 7], id),
        Err(GridError::Count {
            res: [2, 2, 2],
            needed: 8,
            got: 7
        })
    );
    assert_eq!(
        DensityGrid::new([0, 2, 2], vec![], id),
        Err(GridError::Size([0, 2, 2]))
    );
    assert_eq!(
        DensityGrid::new([1 << 20, 1 << 20, 1 << 20], vec![], id),
        Err(GridError::Size([1 << 20, 1 << 20, 1 << 20]))
    );
    let mut v = vec![1.0; 8];
    v[5] = -0.5;
    assert_eq!(
        DensityGrid::new([2, 2, 2], v.clone(), id),
        Err(GridError::Value {
            x: 1,
            y: 0,
            z: 1,
            value: -0.5
        })
    );
    v[5] = f32::NAN;
    assert!(matches!(
        DensityGrid::new([2, 2, 2], v, id),
        Err(GridError::Value {
            x: 1,
            y: 0,
            z: 1,
            ..
        })
    ));
    let flat = Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0));
    assert_eq!(
        DensityGrid::new([2, 2, 2], vec![1.0; 8], flat),
        Err(GridError::Box)
    );
}

/// A medium of density 2 over `[0, 2]` in x (the unit square across) whose albedo rises
/// along x as `0.2 + 0.3·x` at the voxel centres, per channel scaled by `tint`.
fn sooty(tint: Rgb) -> (Medium, impl Fn(f32) -> Rgb) {
    let n = 8;
    let to_world = Affine3A::from_scale(Vec3::new(2.0, 1.0, 1.0));
    let density = DensityGrid::new([2, 1, 1], vec![2.0; 2], to_world).unwrap();
    let centre = move |i: usize| (i as f32 + 0.5) / n as f32 * 2.0;
    let a = move |x: f32| tint * (0.2 + 0.3 * x.clamp(centre(0), centre(n - 1)));
    let values = (0..n).map(|i| a(centre(i))).collect();
    let albedo = AlbedoGrid::new([n, 1, 1], values, to_world).unwrap();
    let m = Medium::new(Rgb::new(0.5, 1.0, 2.0), Rgb::BLACK, 0.0)
        .with_density(Arc::new(density))
        .with_albedo(Arc::new(albedo));
    (m, a)
}

/// `∫₀^end σt·ρ·albedo(t)·Tr(t) dt` per channel for [`sooty`], in f64 by the midpoint rule.
fn sooty_scattered(m: &Medium, albedo: &impl Fn(f32) -> Rgb, end: f32) -> [f64; 3] {
    let steps = 20_000;
    let h = f64::from(end) / steps as f64;
    let st = m.sigma_t().to_array();
    std::array::from_fn(|c| {
        (0..steps)
            .map(|i| {
                let t = (i as f64 + 0.5) * h;
                let s = f64::from(st[c]) * 2.0;
                s * f64::from(albedo(t as f32).to_array()[c]) * (-s * t).exp() * h
            })
            .sum()
    })
}

#[test]
fn an_albedo_grid_weighs_each_scattering_by_its_own_albedo() {
    let tint = Rgb::new(1.0, 0.8, 0.5);
    let (m, albedo) = sooty(tint);
    let end = 1.7;
    let want = sooty_scattered(&m, &albedo, end);
    let mut rng = Rng::new(21);
    let samples = 60_000;
    let mut sum = [0f64; 3];
    for hero in 0..3 {
        for j in 0..samples {
            let u = (j as f32 + 0.5) / samples as f32;
            let ray = (Vec3::new(0.0, 0.5, 0.5), Vec3::X);
            if let Interaction::Scatter { weight, ratio, .. } =
                m.sample_along(ray, end, hero, u, &mut rng)
            {
                for (s, c) in sum.iter_mut().zip((weight / ratio.mean()).to_array()) {
                    *s += f64::from(c);
                }
            }
        }
    }
    for c in 0..3 {
        let got = sum[c] / (3 * samples) as f64;
        assert!(
            (got - want[c]).abs() < 5e-3,
            "channel {c}: {got} against {}",
            want[c]
        );
    }
    // Whitted's quadrature of the same integral, without noise.
    let (tr, scattered) = m.fog_along((Vec3::new(0.0, 0.5, 0.5), Vec3::X), end);
    let channels = scattered
        .to_array()
        .into_iter()
        .zip(tr.to_array())
        .zip(want);
    for (c, ((got, tr), want)) in channels.enumerate() {
        let got = f64::from(got);
        assert!(
            (got - want).abs() < 2e-3,
            "quadrature, channel {c}: {got} against {want}"
        );
        let want_tr = (-f64::from(m.sigma_t().to_array()[c]) * 2.0 * f64::from(end)).exp();
        assert!((f64::from(tr) - want_tr).abs() < 1e-4);
    }
}

#[test]
fn albedo_grids_out_of_range_are_refused() {
    let id = Affine3A::IDENTITY;
    let mut v = vec![Rgb::gray(0.5); 8];
    v[3] = Rgb::new(0.2, 1.5, 0.1);
    assert_eq!(
        AlbedoGrid::new([2, 2, 2], v.clone(), id),
        Err(GridError::Albedo {
            x: 1,
            y: 1,
            z: 0,
            value: 1.5
        })
    );
    v[3] = Rgb::new(f32::NAN, 0.5, 0.5);
    assert!(matches!(
        AlbedoGrid::new([2, 2, 2], v, id),
        Err(GridError::Albedo {
            x: 1,
            y: 1,
            z: 0,
            ..
        })
    ));
}
