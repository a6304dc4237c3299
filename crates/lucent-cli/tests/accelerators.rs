//! Every accelerator renders exactly the same image of every example scene (and of a scene of
//! instanced meshes with transforms), with either triangle test.

mod common;

use common::{assert_success, lucent, read_pfm, workspace};

const ACCELS: [&str; 5] = ["brute", "bounds", "octree", "bvh", "wide"];

fn render(
    scene: &std::path::Path,
    accel: &str,
    extra: &[&str],
    out: &std::path::Path,
) -> common::Image {
    let output = lucent()
        .arg("render")
        .arg(scene)
        .args(["--width", "64", "--height", "48", "--accel", accel, "-o"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    assert_success(&output);
    read_pfm(out)
}

#[test]
fn every_accelerator_renders_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut scenes: Vec<std::path::PathBuf> = ["whitted.toml", "box-room.toml"]
        .iter()
        .map(|s| workspace().join("examples").join(s))
        .collect();
    // A scene of a mesh placed three times, scaled, rotated and mirrored.
    let obj = dir.path().join("tetra.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let instanced = dir.path().join("instanced.toml");
    std::fs::write(
        &instanced,
        r#"
        [camera]
        eye = [0.5, 1.5, 4]
        look_at = [0.3, 0.3, 0]
        [world]
        ambient = 0.2
        [[material]]
        name = "m"
        kd = [0.8, 0.5, 0.2]
        ks = 0.4
        shininess = 20
        kr = 0.2
        [[material]]
        name = "glass"
        kt = 0.8
        ior = 1.4
        [[light]]
        type = "point"
        position = [2, 4, 3]
        [[object]]
        type = "mesh"
        file = "tetra.obj"
        material = "m"
        [[object]]
        type = "mesh"
        file = "tetra.obj"
        translate = [1.2, 0, 0]
        rotate = [20, 40, 0]
        scale = [1, -0.7, 1.3]
        material = "glass"
        [[object]]
        type = "mesh"
        file = "tetra.obj"
        translate = [-1, 0.2, -0.5]
        scale = 1.5
        material = "m"
        [[object]]
        type = "plane"
        point = [0, -0.5, 0]
        normal = [0, 1, 0]
        material = "m"
        "#,
    )
    .unwrap();
    scenes.push(instanced);
    let bunny = workspace().join("examples/bunny.toml");
    if lucent_scene::data_dir()
        .join("meshes/stanford-bunny.obj")
        .is_file()
    {
        scenes.push(bunny);
    }
    for scene in &scenes {
        for test in ["watertight", "projection"] {
            let want = render(
                scene,
                "bvh",
                &["--triangle-test", test],
                &dir.path().join("want.pfm"),
            );
            for accel in ACCELS {
                // Brute force on the bunny would take minutes: it is held to the BVH on the rest.
                if accel == "brute" && scene.ends_with("bunny.toml") {
                    continue;
                }
                let got = render(
                    scene,
                    accel,
                    &["--triangle-test", test],
                    &dir.path().join("got.pfm"),
                );
                assert!(
                    got == want,
                    "{accel} ({test}) differs from bvh on {}",
                    scene.display()
                );
            }
        }
    }
}
