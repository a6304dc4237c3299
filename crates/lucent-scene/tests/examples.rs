//! The built-in scene and every example scene load and build.

use lucent_scene::{DEFAULT_SCENE, SceneFile};
use std::path::Path;

fn examples_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"))
}

#[test]
fn the_default_scene_is_whitteds_picture() {
    let loaded = SceneFile::default_scene().build().unwrap();
    let c = loaded.scene.counts();
    assert_eq!((c.spheres, c.planes), (2, 1));
    assert!(c.lights >= 1);
    let m = &loaded.scene.materials;
    assert!(
        m.iter().any(|m| m.kt.max_channel() > 0.5 && m.ior > 1.0),
        "a glass material"
    );
    assert!(
        m.iter()
            .any(|m| m.kr.max_channel() > 0.5 && m.kt.is_black()),
        "a mirror material"
    );
    assert!(
        matches!(m[0].kd, lucent::texture::Texture::Checker(_)),
        "a checkerboard floor"
    );
}

#[test]
fn the_default_scene_is_the_whitted_example() {
    let file = std::fs::read_to_string(examples_dir().join("whitted.toml")).unwrap();
    assert_eq!(file, DEFAULT_SCENE);
}

#[test]
fn every_example_builds() {
    let mut count = 0;
    for entry in std::fs::read_dir(examples_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            // Examples that need the shared meshes are skipped where they are absent.
            let text = std::fs::read_to_string(&path).unwrap();
            if text.contains("shared/data") && !examples_dir().join("../../shared/data").is_dir() {
                eprintln!("skipping {}: ../shared/data is not here", path.display());
                continue;
            }
            SceneFile::read(&path)
                .and_then(|f| f.build())
                .unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    assert!(count >= 1);
}
