//! Photometric (IES) lights: the intensity a light sends along every direction of its file's
//! table is the file's value there (a sphere of sensors around it), for the three photometric
//! types, a tilted luminaire and a turned one; broken files are refused with the line at fault.

use glam::Vec3;
use lucent::light::Light;
use lucent_scene::SceneFile;
use lucent_scene::ies::parse_ies;
use std::path::{Path, PathBuf};

/// A scratch folder of this test process.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lucent-ies-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An IES file of photometric `kind` (1 = C, 2 = B, 3 = A) with `tilt` after `TILT=`, candela
/// multiplier 2 and ballast factor 0.5 (so the values are as written), `vertical` × `horizontal`
/// angles and `values` (for each horizontal angle, one per vertical angle).
fn ies_text(kind: u32, tilt: &str, vertical: &[f32], horizontal: &[f32], values: &[f32]) -> String {
    let list = |v: &[f32]| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    format!(
        "IESNA:LM-63-2002\n[TEST] made by lucent's tests\n[MANUFAC] nobody\nTILT={tilt}\n\
         1 1000 2 {} {} {kind} 2 0.1 0.2 0\n0.5 1 100\n{}\n{}\n{}\n",
        vertical.len(),
        horizontal.len(),
        list(vertical),
        list(horizontal),
        list(values)
    )
}

/// The scene with one photometric light at `position`, its table `light` (TOML keys after
/// `type`), the IES file `ies` beside it.
fn light_of(name: &str, ies: &str, light: &str) -> Light {
    let dir = scratch(name);
    std::fs::write(dir.join("lamp.ies"), ies).unwrap();
    let text = format!(
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
         [[light]]\ntype = \"photometric\"\nfile = \"lamp.ies\"\n{light}\n"
    );
    let loaded = SceneFile::parse(dir.join("scene.toml"), dir.clone(), text)
        .and_then(|f| f.build())
        .unwrap_or_else(|e| panic!("{e}"));
    loaded.scene.lights[0].clone()
}

/// The candela the light sends along world direction `d` (sensed 3 units away, quadratic
/// falloff undone, lucent's 1/683 undone).
fn candela(light: &Light, at: Vec3, d: Vec3) -> f32 {
    let r = 3.0;
    light
        .illuminate(at + d.normalize() * r)
        .map_or(0.0, |s| s.intensity.r * r * r * 683.0)
}

/// Checks every entry of the table: `dir(v, h)` is the documented direction of the angles in
/// the luminaire's frame, `to_world` takes it to the scene.
fn check_table(
    light: &Light,
    at: Vec3,
    vertical: &[f32],
    horizontal: &[f32],
    values: &[f32],
    dir: impl Fn(f32, f32) -> Vec3,
    to_world: impl Fn(Vec3) -> Vec3,
) {
    for (hi, &h) in horizontal.iter().enumerate() {
        for (vi, &v) in vertical.iter().enumerate() {
            let want = values[hi * vertical.len() + vi];
            let got = candela(light, at, to_world(dir(v, h)));
            assert!(
                (got - want).abs() <= 0.01 * want.max(1.0),
                "at ({v}°, {h}°): {got} cd, the file says {want}"
            );
        }
    }
}

/// 0 at the poles (γ = 0° and 180°, where every C is one direction, so a real table has one
/// value there), 1 at the horizontal.
fn pole_free(gamma: f32) -> f32 {
    gamma * (180.0 - gamma) / 8100.0
}

/// The direction of a table's (vertical, horizontal) angles in the luminaire's frame.
type Angles = fn(f32, f32) -> Vec3;

fn rad(deg: f32) -> f32 {
    deg.to_radians()
}

/// Type C: `γ` from the nadir (−z), `C` from +x towards +y.
fn type_c_dir(gamma: f32, c: f32) -> Vec3 {
    let (g, c) = (rad(gamma), rad(c));
    Vec3::new(g.sin() * c.cos(), g.sin() * c.sin(), -g.cos())
}

/// The luminaire frame of a light hanging straight down with its length along +x: +z is up
/// (+y of the world), +y across (−z of the world).
fn hanging(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.z, -v.y)
}

#[test]
fn a_type_c_table_is_sent_along_every_one_of_its_directions() {
    let vertical = [0.0, 22.5, 45.0, 67.5, 90.0, 135.0, 180.0];
    let horizontal = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0, 360.0];
    let values: Vec<f32> = horizontal
        .iter()
        .flat_map(|h| {
            vertical
                .iter()
                .map(move |v| 100.0 + 3.0 * v + h * pole_free(*v))
        })
        .collect();
    let ies = ies_text(1, "NONE", &vertical, &horizontal, &values);
    let at = Vec3::new(1.0, 4.0, -2.0);
    let light = light_of("c", &ies, "position = [1, 4, -2]");
    check_table(
        &light,
        at,
        &vertical,
        &horizontal[..8],
        &values,
        type_c_dir,
        hanging,
    );
}

#[test]
fn type_b_and_type_a_tables_are_sent_along_their_directions() {
    // Away from the poles (type B's at H = ±90°, type A's at V = ±90°), every pair distinct.
    let vertical = [-60.0, -30.0, 0.0, 20.0, 45.0, 60.0];
    let horizontal = [-60.0, -20.0, 0.0, 30.0, 60.0];
    let values: Vec<f32> = horizontal
        .iter()
        .flat_map(|h| vertical.iter().map(move |v| 200.0 + 2.0 * v + h))
        .collect();
    // Type B: d = (cos H sin V, sin H, −cos H cos V).
    let type_b = |v: f32, h: f32| {
        let (v, h) = (rad(v), rad(h));
        Vec3::new(h.cos() * v.sin(), h.sin(), -h.cos() * v.cos())
    };
    // Type A: d = (cos V cos H, −cos V sin H, sin V).
    let type_a = |v: f32, h: f32| {
        let (v, h) = (rad(v), rad(h));
        Vec3::new(v.cos() * h.cos(), -v.cos() * h.sin(), v.sin())
    };
    let types: [(u32, &str, Angles); 2] = [(2, "b", type_b), (3, "a", type_a)];
    for (kind, name, dir) in types {
        let ies = ies_text(kind, "NONE", &vertical, &horizontal, &values);
        let light = light_of(name, &ies, "position = [0, 2, 0]");
        check_table(
            &light,
            Vec3::Y * 2.0,
            &vertical,
            &horizontal,
            &values,
            dir,
            hanging,
        );
    }
    // A type B table measured on one side (H from 0°) is mirrored to the other.
    let one_side = [0.0, 30.0, 60.0];
    let values: Vec<f32> = one_side
        .iter()
        .flat_map(|h| vertical.iter().map(move |v| 200.0 + 2.0 * v + h))
        .collect();
    let light = light_of(
        "b-half",
        &ies_text(2, "NONE", &vertical, &one_side, &values),
        "position = [0, 2, 0]",
    );
    let mirrored: Vec<f32> = one_side.iter().map(|h| -h).collect();
    check_table(
        &light,
        Vec3::Y * 2.0,
        &vertical,
        &mirrored,
        &values,
        type_b,
        hanging,
    );
}

#[test]
fn a_turned_luminaire_turns_its_table() {
    // Pointing along +x (a wall washer), its length up (+y): C = 0° is world +y.
    let vertical = [0.0, 30.0, 60.0, 90.0];
    let horizontal = [0.0, 90.0, 180.0, 270.0, 360.0];
    let values: Vec<f32> = horizontal
        .iter()
        .flat_map(|h| {
            vertical
                .iter()
                .map(move |v| 50.0 + v + 2.0 * h * pole_free(*v))
        })
        .collect();
    let ies = ies_text(1, "NONE", &vertical, &horizontal, &values);
    let light = light_of(
        "turned",
        &ies,
        "position = [0, 0, 0]\ndirection = [1, 0, 0]\nfront = [0, 1, 0]",
    );
    // Luminaire frame: x = world y, z (up) = world −x, y = z × x = world −z.
    let to_world = |v: Vec3| Vec3::new(-v.z, v.x, -v.y);
    check_table(
        &light,
        Vec3::ZERO,
        &vertical,
        &horizontal[..4],
        &values,
        type_c_dir,
        to_world,
    );
}

#[test]
fn symmetric_type_c_tables_light_the_whole_turn() {
    // Quadrant symmetry: 0°–90° measured.
    let vertical = [0.0, 90.0, 180.0];
    let horizontal = [0.0, 90.0];
    let values = [10.0, 20.0, 30.0, 40.0, 50.0, 60.0];
    let ies = ies_text(1, "NONE", &vertical, &horizontal, &values);
    let light = light_of("quadrant", &ies, "position = [0, 0, 0]");
    for c in [0.0, 180.0] {
        let got = candela(&light, Vec3::ZERO, hanging(type_c_dir(90.0, c)));
        assert!((got - 20.0).abs() < 0.2, "C = {c}: {got}");
    }
    for c in [90.0, 270.0] {
        let got = candela(&light, Vec3::ZERO, hanging(type_c_dir(90.0, c)));
        assert!((got - 50.0).abs() < 0.5, "C = {c}: {got}");
    }
}

#[test]
fn a_tilt_table_scales_a_leaning_luminaire() {
    let vertical = [0.0, 90.0, 180.0];
    let horizontal = [0.0];
    let values = [100.0, 100.0, 100.0];
    // Geometry 1, three tilt angles: full output hanging straight, 80% at 30°, 40% at 90°.
    let ies = ies_text(
        1,
        "INCLUDE\n1\n3\n0 30 90\n1.0 0.8 0.4",
        &vertical,
        &horizontal,
        &values,
    );
    let straight = light_of("tilt-0", &ies, "position = [0, 0, 0]");
    assert!((candela(&straight, Vec3::ZERO, Vec3::NEG_Y) - 100.0).abs() < 0.5);
    let (s, c) = rad(30.0).sin_cos();
    let leaning = light_of(
        "tilt-30",
        &ies,
        &format!("position = [0, 0, 0]\ndirection = [{s}, {}, 0]", -c),
    );
    let got = candela(&leaning, Vec3::ZERO, Vec3::new(s, -c, 0.0));
    assert!((got - 80.0).abs() < 0.8, "{got}");
}

#[test]
fn lumens_and_keywords_are_read_and_values_are_scaled() {
    let text = ies_text(1, "NONE", &[0.0, 90.0], &[0.0], &[7.0, 3.0]);
    let ies = parse_ies(Path::new("lamp.ies"), &text).unwrap();
    assert_eq!(ies.edition, "LM-63-2002");
    assert_eq!(ies.lumens_per_lamp, 1000.0);
    assert_eq!(
        ies.keywords[0],
        ("TEST".to_string(), "made by lucent's tests".to_string())
    );
    // Multiplier 2 × ballast factor 0.5.
    assert_eq!(ies.profile.intensity(Vec3::NEG_Z), 7.0);
    assert!(ies.tilt.is_none());
}

#[test]
fn broken_files_are_refused_at_their_line() {
    let good = ies_text(1, "NONE", &[0.0, 90.0], &[0.0], &[7.0, 3.0]);
    let err = |text: &str| {
        parse_ies(Path::new("lamp.ies"), text)
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    // A short table: the file ends before its last value.
    let short = good.trim_end().trim_end_matches('3').to_string();
    let e = err(&short);
    assert!(
        e.contains("lamp.ies:") && e.contains("ends before its candela value #2"),
        "{e}"
    );
    // NaN where a value belongs, at its line.
    let e = err(&good.replace("7 3", "7 nan"));
    assert!(
        e.contains("lamp.ies:9") && e.contains("candela value #2"),
        "{e}"
    );
    // Absurd sizes are refused before anything is allocated.
    let e = err(&good.replace("1 1000 2 2 1 1", "1 1000 2 9000 9000 1"));
    assert!(e.contains("lamp.ies:5") && e.contains("at most"), "{e}");
    let e = err(&good.replace("1 1000 2 2 1 1", "1 1000 2 2 1 4"));
    assert!(e.contains("photometric type 4"), "{e}");
    let e = err("IESNA:LM-63-2002\n[TEST] no tilt line\n1 2 3\n");
    assert!(e.contains("no `TILT=` line"), "{e}");
    let e = err(&good.replace("TILT=NONE", "TILT=lamp.tlt"));
    assert!(
        e.contains("lamp.ies:4") && e.contains("TILT=INCLUDE"),
        "{e}"
    );
    // Angles that go backwards.
    let e = err(&good.replace("\n0 90\n", "\n90 0\n"));
    assert!(e.contains("must increase"), "{e}");
}

#[test]
fn a_missing_file_and_a_bad_front_are_errors_at_the_scene_line() {
    let dir = scratch("errors");
    std::fs::write(
        dir.join("lamp.ies"),
        ies_text(1, "NONE", &[0.0, 90.0], &[0.0], &[1.0, 1.0]),
    )
    .unwrap();
    let build = |light: &str| {
        let text = format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[light]]\ntype = \"photometric\"\n{light}\n"
        );
        SceneFile::parse(dir.join("scene.toml"), dir.clone(), text)
            .and_then(|f| f.build())
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let e = build("file = \"none.ies\"\nposition = [0, 0, 0]");
    assert!(e.contains("scene.toml:6") && e.contains("none.ies"), "{e}");
    let e = build("file = \"lamp.ies\"\nposition = [0, 0, 0]\nfront = [0, -2, 0]");
    assert!(e.contains("scene.toml:8") && e.contains("front"), "{e}");
    let e = build("file = \"lamp.ies\"");
    assert!(e.contains("position"), "{e}");
}
