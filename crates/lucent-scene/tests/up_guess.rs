//! The up axis guessed for the shared meshes (`../shared/data/meshes`), all +y up as published
//! (rendered and looked at), and for copies of them turned to every other up axis: the guess
//! must keep the originals at +y, follow the turned copies whose geometry has a clue (a flat
//! base, a ground at the origin), and never guess an axis that is not up.

use glam::Vec3;
use lucent_scene::SceneFile;
use lucent_scene::framing::{Axis, Framing, UpGuess, View, guess_up};
use lucent_scene::mesh_file::read_mesh;
use std::path::PathBuf;

fn meshes() -> Option<PathBuf> {
    let dir = lucent_scene::data_dir().join("meshes");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: {} is not here", dir.display());
        None
    }
}

/// Each mesh, with the clues its geometry holds (ground, flat base), all along +y.
const CLUES: [(&str, bool, bool); 7] = [
    ("stanford-bunny.obj", false, true),
    ("ogre.obj", true, false),
    ("igea.ply", false, false),
    ("teapot.obj", true, true),
    ("spot.obj", false, false),
    ("cow.obj", false, false),
    ("suzanne.obj", false, false),
];

#[test]
fn the_shared_meshes_are_guessed_y_up_for_what_they_show() {
    let Some(dir) = meshes() else { return };
    for (name, ground, base) in CLUES {
        let file = SceneFile::read(&dir.join(name)).unwrap();
        let expected = UpGuess {
            up: Axis::Y,
            ground: ground.then_some(Axis::Y),
            base: base.then_some(Axis::Y),
        };
        assert_eq!(file.up_guess(), Some(expected), "{name}");
        assert_eq!(file.framing(), Framing::default(), "{name}");
    }
}

#[test]
fn turned_copies_are_followed_where_a_clue_shows_and_left_at_y_elsewhere() {
    let Some(dir) = meshes() else { return };
    for (name, ground, base) in CLUES {
        let mesh = read_mesh(&dir.join(name)).unwrap();
        for up in Axis::ALL {
            // The model as a file with `up` up would hold it: +y goes to `up`, and the front
            // (+z) to the frame's back, so the framing camera sees the same picture.
            let f = Framing {
                up,
                view: View::Front,
            }
            .model_frame();
            let turned: Vec<Vec3> = mesh
                .positions
                .iter()
                .map(|p| p.x * f.right + p.y * f.up + p.z * f.back)
                .collect();
            let g = guess_up(&turned, &mesh.triangles);
            // Clues are looked for along positive axes only: an upside-down copy has none.
            let positive = matches!(up, Axis::X | Axis::Y | Axis::Z);
            let expected = UpGuess {
                up: if positive && (ground || base) {
                    up
                } else {
                    Axis::Y
                },
                ground: (positive && ground).then_some(up),
                base: (positive && base).then_some(up),
            };
            assert_eq!(g, expected, "{name} turned to {up} up");
        }
    }
}

#[test]
fn other_formats_are_not_guessed() {
    // A glTF file is +y up by its specification; a TOML scene has its camera.
    let model = lucent_scene::data_dir().join("gltf/Duck/glTF/Duck.gltf");
    if !model.is_file() {
        eprintln!("skipping: {} is not here", model.display());
        return;
    }
    let file = SceneFile::read(&model).unwrap();
    assert_eq!(file.up_guess(), None, "{}", model.display());
    assert_eq!(file.framing(), Framing::default());
    assert_eq!(SceneFile::default_scene().up_guess(), None);
}
