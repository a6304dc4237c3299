//! `motion` tables: read into moving scenes, refused with errors at their place, written back
//! by `to_toml`; the built-in moving scene.

use glam::Vec3;
use lucent::accel::{Ray, TraversalStats};
use lucent_scene::{LoadError, Loaded, MOVING_SCENE, SceneFile};
use std::path::{Path, PathBuf};

const CAMERA: &str = "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\n";
const MATERIAL: &str = "[[material]]\nname = \"m\"\nkd = 0.5\n";

fn parse(text: &str) -> Result<SceneFile, LoadError> {
    SceneFile::parse(PathBuf::from("m.toml"), PathBuf::new(), text.to_string())
}

fn load(text: &str) -> Result<Loaded, LoadError> {
    parse(text)?.build()
}

/// The error for `text`, checked to be at `line:column` and to mention `cause`.
fn assert_error(text: &str, line: usize, column: usize, cause: &str) {
    let e = load(text)
        .expect_err("the scene should be refused")
        .to_string();
    assert!(
        e.starts_with(&format!("m.toml:{line}:{column}: ")),
        "wrong place: {e}"
    );
    assert!(e.contains(cause), "`{e}` does not mention `{cause}`");
}

fn sphere(motion: &str) -> String {
    format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\nmotion = {motion}\n"
    )
}

fn hit(loaded: &Loaded, t: f64, origin: Vec3) -> Option<f32> {
    let ray = Ray::new(origin, -Vec3::Z);
    let scene = loaded.scene.at_time(t);
    scene
        .intersect(&ray, &mut TraversalStats::default())
        .map(|h| h.t)
}

#[test]
fn keys_move_a_sphere() {
    let loaded = load(&sphere(
        "{ repeat = \"loop\", keys = [ { time = 0 }, { time = 2, translate = [4, 0, 0] } ] }",
    ))
    .unwrap();
    assert!(loaded.scene.is_animated());
    let at_x2 = Vec3::new(2.0, 0.0, 5.0);
    assert_eq!(hit(&loaded, 0.0, at_x2), None);
    assert_eq!(hit(&loaded, 1.0, at_x2), Some(4.0));
    assert_eq!(hit(&loaded, 3.0, at_x2), Some(4.0)); // looped
}

#[test]
fn an_orbiting_camera_and_an_oscillating_box() {
    let text = format!(
        "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nmotion = {{ orbit = {{ axis = [0, 1, 0], period = 40, phase = 90 }} }}\n{MATERIAL}\
         [[object]]\ntype = \"cube\"\nmaterial = \"m\"\nmotion = {{ oscillate = {{ offset = [0, 2, 0], period = 4 }} }}\n"
    );
    let loaded = load(&text).unwrap();
    let s = &loaded.scene;
    assert!(s.camera_moves() && s.moving_objects() == 1);
    // A phase of 90°: the eye starts a quarter turn on, at +x.
    assert!((s.camera.eye() - Vec3::new(10.0, 0.0, 0.0)).length() < 1e-4);
    let b = s.at_time(1.0).bounds();
    assert!(
        (b.min.y - 1.0).abs() < 1e-5 && (b.max.y - 3.0).abs() < 1e-5,
        "{b:?}"
    );
}

#[test]
fn bad_motions_are_refused_at_their_place() {
    let text = sphere("{ keys = [ { time = 1 }, { time = 1 } ] }");
    assert_error(&text, 12, 44, "key times must increase");
    let text = sphere("{ orbit = { period = 0 } }");
    assert_error(&text, 12, 31, "period must be a positive");
    let text = sphere("{ orbit = { axis = [0, 0, 0], period = 1 } }");
    assert_error(&text, 12, 29, "axis must not be zero");
    let text = sphere("{ oscillate = { offset = [1, 0, 0], period = -2 } }");
    assert_error(&text, 12, 55, "period");
    let text = sphere("{ keys = [ { time = 0, scale = -1 } ] }");
    assert_error(&text, 12, 41, "positive on every axis");
    let text = sphere("{ keys = [ { time = 0, scale = [1, 2, 1] } ] }");
    assert_error(&text, 12, 10, "scale alike on every axis");
    let text = sphere("{ repeat = \"loop\" }");
    assert_error(&text, 12, 21, "`repeat` needs `keys`");
    let text = sphere("{ spin = 1 }");
    assert_error(&text, 12, 12, "unknown field `spin`");
    let text = sphere("{ repeat = \"twice\", keys = [ { time = 0 } ] }");
    assert_error(&text, 12, 21, "unknown variant `twice`");
}

#[test]
fn planes_and_lights_cannot_move() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\nmotion = {{ orbit = {{ period = 1 }} }}\n"
    );
    assert_error(&text, 12, 10, "an infinite plane cannot move");
    let text = format!(
        "{CAMERA}[[material]]\nname = \"lamp\"\nemission = 1\n[[object]]\ntype = \"rectangle\"\nmaterial = \"lamp\"\nmotion = {{ orbit = {{ period = 1 }} }}\n"
    );
    assert_error(&text, 10, 10, "emits light cannot move");
}

#[test]
fn motion_survives_to_toml() {
    let file = SceneFile::moving_scene();
    let loaded = file.build().unwrap();
    let text = file.to_toml(&loaded).unwrap();
    let again = parse(&text).unwrap().build().unwrap();
    for t in [0.0, 0.7, 3.3, 12.0] {
        let (a, b) = (loaded.scene.at_time(t), again.scene.at_time(t));
        assert_eq!(a.camera, b.camera, "t = {t}");
        assert_eq!(a.bounds(), b.bounds(), "t = {t}");
    }
}

#[test]
fn the_built_in_moving_scene_is_the_example_and_moves() {
    let example = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/moving.toml"
    ));
    assert_eq!(std::fs::read_to_string(example).unwrap(), MOVING_SCENE);
    let loaded = SceneFile::moving_scene().build().unwrap();
    let s = &loaded.scene;
    assert!(s.camera_moves());
    assert!(s.moving_objects() >= 2);
    assert_eq!(s.camera.resolution(), (320, 240));
    // The camera turns slowly: between 20 and 40 s a turn, so a few degrees a second.
    let turned = s
        .at_time(1.0)
        .camera
        .forward()
        .angle_between(s.camera.forward());
    assert!(
        (9f32.to_radians()..18f32.to_radians()).contains(&turned),
        "{turned}"
    );
}
