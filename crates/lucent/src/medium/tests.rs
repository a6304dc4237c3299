use super::*;
use glam::Vec3;

fn chromatic() -> Medium {
    Medium::new(Rgb::new(0.2, 0.5, 1.5), Rgb::new(0.8, 0.3, 0.1), 0.3)
}

#[test]
fn transmittance_is_beer_lambert() {
    let m = chromatic();
    for d in [0.0, 0.25, 1.0, 3.0] {
        let tr = m.transmittance(d).to_array();
        for (c, st) in m.sigma_t().to_array().into_iter().enumerate() {
            assert_eq!(tr[c], (-st * d).exp(), "d {d} channel {c}");
        }
    }
    assert_eq!(m.transmittance(f32::INFINITY), Rgb::BLACK);
    let clear = Medium::new(Rgb::BLACK, Rgb::BLACK, 0.0);
    assert_eq!(clear.transmittance(f32::INFINITY), Rgb::WHITE);
}

#[test]
fn albedo_and_extinction_give_the_coefficients() {
    let m = Medium::from_albedo(Rgb::new(2.0, 1.0, 4.0), Rgb::new(0.5, 1.0, 0.25), 0.0);
    assert_eq!(m.sigma_s, Rgb::new(1.0, 1.0, 1.0));
    assert_eq!(m.sigma_a, Rgb::new(1.0, 0.0, 3.0));
}

/// The mean over the three hero channels and a stratified grid of `u` of what a distance
/// sample contributes to a segment of length `end` under the balance heuristic over channels
/// (`weight / mean(ratio)`): the share passed, and the light scattered in the segment (each
/// scattering point seeing radiance 1).
fn expected(m: &Medium, end: f32) -> (Rgb, Rgb) {
    let n = 200_000;
    // Summed in f64: 600,000 terms in f32 would drift by more than the tolerance.
    let (mut pass, mut scatter) = ([0f64; 3], [0f64; 3]);
    let add = |sum: &mut [f64; 3], v: Rgb| {
        for (s, c) in sum.iter_mut().zip(v.to_array()) {
            *s += f64::from(c);
        }
    };
    for hero in 0..3 {
        for j in 0..n {
            let u = (j as f32 + 0.5) / n as f32;
            match m.sample_distance(end, hero, u) {
                Interaction::Pass { weight, ratio } => add(&mut pass, weight / ratio.mean()),
                Interaction::Scatter { t, weight, ratio } => {
                    assert!((0.0..end).contains(&t));
                    add(&mut scatter, weight / ratio.mean());
                }
            }
        }
    }
    let mean = |s: [f64; 3]| Rgb::from(s.map(|c| (c / f64::from(3 * n)) as f32));
    (mean(pass), mean(scatter))
}

#[test]
fn distance_samples_are_unbiased_in_every_channel() {
    // Passing: E = Tr(end). Scattering: E = ∫₀^end σs·Tr(t) dt = σs/σt·(1 − Tr(end)).
    let m = chromatic();
    for end in [0.3, 1.0, 4.0] {
        let (pass, scatter) = expected(&m, end);
        let tr = m.transmittance(end).to_array();
        let (st, ss) = (m.sigma_t().to_array(), m.sigma_s.to_array());
        for c in 0..3 {
            let want_scatter = ss[c] / st[c] * (1.0 - tr[c]);
            assert!(
                (pass.to_array()[c] - tr[c]).abs() < 2e-3,
                "end {end} channel {c}: passed {} against {}",
                pass.to_array()[c],
                tr[c]
            );
            assert!(
                (scatter.to_array()[c] - want_scatter).abs() < 2e-3,
                "end {end} channel {c}: scattered {} against {want_scatter}",
                scatter.to_array()[c]
            );
        }
    }
}

#[test]
fn a_gray_medium_weighs_scattering_by_its_albedo_and_passing_by_one() {
    let m = Medium::from_albedo(Rgb::gray(2.0), Rgb::gray(0.7), 0.0);
    match m.sample_distance(10.0, 1, 0.5) {
        Interaction::Scatter { weight, ratio, .. } => {
            assert!((weight - Rgb::gray(0.7)).max_channel().abs() < 1e-6);
            assert!((ratio - Rgb::WHITE).max_channel().abs() < 1e-6);
        }
        other => panic!("{other:?}"),
    }
    match m.sample_distance(0.01, 1, 0.5) {
        Interaction::Pass { weight, .. } => {
            assert!((weight - Rgb::WHITE).max_channel().abs() < 1e-6)
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_medium_that_only_absorbs_passes_with_its_transmittance() {
    let m = Medium::new(Rgb::new(0.5, 1.0, 2.0), Rgb::BLACK, 0.0);
    for u in [0.01, 0.5, 0.99] {
        assert_eq!(
            m.sample_distance(1.5, 2, u),
            Interaction::Pass {
                weight: m.transmittance(1.5),
                ratio: Rgb::WHITE
            }
        );
    }
}

#[test]
fn rays_enter_the_medium_on_the_side_they_go_to() {
    let interface = MediumInterface {
        inside: Some(0),
        outside: None,
    };
    let n = Vec3::Z;
    assert_eq!(interface.towards(n, -Vec3::Z, None), Some(0));
    assert_eq!(interface.towards(n, Vec3::Z, Some(0)), None);
    // An object without media keeps the medium the ray was in.
    let none = MediumInterface::default();
    assert_eq!(none.towards(n, -Vec3::Z, Some(3)), Some(3));
}
