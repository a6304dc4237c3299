//! A short mutation fuzz of every scene parser, run with the tests: real files — small valid
//! samples written here, and the heads of the shared meshes where the data folder exists — are
//! mutated (bits flipped, runs inserted, deleted and spliced, files cut short, numbers replaced
//! by huge values, NaN or −1, 32-bit words overwritten, lines repeated) and read. Every read
//! must return (`Ok` or `Err`: no panic), within [`watch::DEADLINE`] (no hang), holding at most
//! [`CAP`] bytes at once (no runaway allocation).
//!
//! The long-running counterpart is `fuzz/` (cargo-fuzz); this one keeps the parsers honest on
//! every `cargo test`. It is deterministic: a fixed seed unless `PROPTEST_RNG_SEED` is set, and
//! `PROPTEST_CASES` (default 1024: about a second in all) cases per format.
//!
//! How each failure shows:
//! - a panic, or more than [`CAP`] bytes live: the test fails after proptest has shrunk the
//!   mutations, naming them (they replay the case) and the file the input was written to;
//! - a hang: the input is written out and the process exits at once (a stuck thread cannot be
//!   stopped, and shrinking would start more of them);
//! - a single request, or a live total, over [`watch::HARD_CAP`]: the allocator refuses it, and the
//!   process aborts with "memory allocation of N bytes failed". Each format's last input is in
//!   `target/tmp/fuzz_mutations/FORMAT/` to replay it.

#[path = "fuzz_mutations/mutate.rs"]
mod mutate;
#[path = "fuzz_mutations/samples.rs"]
mod samples;
// The counting allocator is the one unsafe item: `GlobalAlloc` is an unsafe trait; it forwards
// to `System` unchanged.
#[allow(unsafe_code)]
#[path = "fuzz_mutations/watch.rs"]
mod watch;

use lucent::shape::Mesh;
use lucent_scene::gltf_file::read_gltf_part;
use lucent_scene::hash::Fingerprint;
use lucent_scene::mtl::parse_mtl;
use lucent_scene::obj::parse_obj;
use lucent_scene::ply::parse_ply;
use lucent_scene::{LoadOptions, SceneFile};
use mutate::{Mutation, apply, mutation};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestError, TestRunner};
use samples::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use watch::{CAP, run_watched};

/// Bytes kept of each shared mesh: its header and a few thousand lines.
const HEAD: usize = 64 << 10;
/// Loads are sandboxed: a mutated file can name only the files of its own folder.
const SANDBOX: LoadOptions = LoadOptions {
    sandbox: true,
    limits: lucent_scene::Limits::DEFAULT,
    image_size: None,
};

// ---------------------------------------------------------------------------------------------
// The run.

/// A format's samples, and how one input of it is read: `read(bytes, folder)`, where `folder`
/// holds [`write_neighbours`]'s files; true when it was read (and built) without an error.
struct Format {
    name: &'static str,
    samples: Vec<Vec<u8>>,
    read: fn(&[u8], &Path) -> bool,
}

/// The folder of one format's run: its neighbour files and its last input.
fn folder(format: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fuzz_mutations")
        .join(format);
    std::fs::create_dir_all(&dir).unwrap();
    write_neighbours(&dir);
    dir
}

/// Mutates `format`'s samples and reads each result, `PROPTEST_CASES` (default 1024) times.
fn fuzz(format: Format) {
    assert!(!format.samples.is_empty());
    let dir = folder(format.name);
    let mut config = Config {
        failure_persistence: None,
        max_shrink_iters: 256,
        ..Config::default()
    };
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = 1024;
    }
    if config.rng_seed == RngSeed::Random {
        config.rng_seed = RngSeed::Fixed(0x6c75_6365_6e74); // "lucent"
    }
    let seed = config.rng_seed;
    let mut runner = TestRunner::new(config);
    let samples = format.samples;
    let strategy = (any::<Index>(), proptest::collection::vec(mutation(), 0..=6));
    let mutated = |(which, mutations): &(Index, Vec<Mutation>)| {
        let mut b = samples[which.index(samples.len())].clone();
        for m in mutations {
            apply(m, &mut b, &samples);
        }
        b
    };
    let last = dir.join("last-input");
    // How many inputs were read, and how many of them without an error: a fuzz whose inputs
    // all fail at the first line would test little.
    let (cases, read_fine) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
    let result = runner.run(&strategy, |case| {
        let bytes = mutated(&case);
        std::fs::write(&last, &bytes).unwrap();
        let (read, dir, fine) = (format.read, dir.clone(), read_fine.clone());
        cases.fetch_add(1, Ordering::Relaxed);
        run_watched(format.name, &last, move || {
            if read(&bytes, &dir) {
                fine.fetch_add(1, Ordering::Relaxed);
            }
        })
        .map_err(TestCaseError::fail)
    });
    match result {
        Ok(()) => println!(
            "{}: {} mutated inputs, {} read without an error",
            format.name,
            cases.load(Ordering::Relaxed),
            read_fine.load(Ordering::Relaxed)
        ),
        Err(TestError::Fail(why, case)) => {
            let failing = dir.join("failing-input");
            std::fs::write(&failing, mutated(&case)).unwrap();
            panic!(
                "{}: {why}\n  the input (sample {}, then {:?}; seed {seed:?}) is in {}",
                format.name,
                case.0.index(samples.len()),
                case.1,
                failing.display()
            );
        }
        Err(e) => panic!("{}: {e}", format.name),
    }
}

/// The first [`HEAD`] bytes of the shared mesh `name`, or `None` (with a note) without the
/// data folder.
fn shared_head(name: &str) -> Option<Vec<u8>> {
    let path = lucent_scene::data_dir().join("meshes").join(name);
    match std::fs::read(&path) {
        Ok(mut b) => {
            b.truncate(HEAD);
            Some(b)
        }
        Err(e) => {
            println!(
                "note: {} cannot be read ({e}); fuzzing without it",
                path.display()
            );
            None
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One test per format.

/// Writes `bytes` to the file `name` of `dir`.
fn input(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Imports the scene file at `path` and builds it: true when both go without an error.
fn load(path: &Path) -> bool {
    SceneFile::read_with(path, &SANDBOX).is_ok_and(|file| file.build().is_ok())
}

#[test]
fn mutated_toml_scenes() {
    fuzz(Format {
        name: "toml",
        samples: vec![SCENE_SPHERES.into(), SCENE_MESHES.into()],
        read: |bytes, dir| {
            let Ok(text) = String::from_utf8(bytes.to_vec()) else {
                return false;
            };
            let Ok(mut file) = SceneFile::parse(dir.join("scene.toml"), dir.into(), text) else {
                return false;
            };
            file.options = SANDBOX;
            file.build()
                .is_ok_and(|loaded| file.to_toml(&loaded).is_ok())
        },
    });
}

#[test]
fn mutated_obj_files() {
    let mut samples: Vec<Vec<u8>> = vec![OBJ_QUAD.into(), TRI_OBJ.into()];
    samples.extend(
        ["teapot.obj", "suzanne.obj"]
            .into_iter()
            .filter_map(shared_head),
    );
    fuzz(Format {
        name: "obj",
        samples,
        read: |bytes, dir| {
            let Ok(obj) = parse_obj(bytes, Path::new("fuzz.obj")) else {
                return false;
            };
            let all = obj.mesh(None).expect("all faces are a part");
            all.validate().expect("a parsed file gives a valid mesh");
            for name in obj.used_materials() {
                let part = obj.mesh(Some(name)).expect("a used material is a part");
                part.validate().expect("a parsed file gives valid parts");
            }
            load(&input(dir, "fuzz.obj", bytes))
        },
    });
}

#[test]
fn mutated_mtl_files() {
    fuzz(Format {
        name: "mtl",
        samples: vec![MTL_THREE.into(), TRI_MTL.into()],
        read: |bytes, _| {
            let Ok(materials) = parse_mtl(bytes, Path::new("fuzz.mtl")) else {
                return false;
            };
            let mut warnings = Vec::new();
            for m in &materials {
                let _ = m.to_desc(&m.name, m.texture().map(str::to_string), &mut warnings);
            }
            true
        },
    });
}

#[test]
fn mutated_ies_files() {
    let street = include_bytes!("../../../examples/lamps/street.ies");
    let tilted = b"IESNA:LM-63-2002\n[TEST] t\nTILT=INCLUDE\n1\n3\n0 30 90\n1 0.8 0.4\n\
        1 -1 1 3 2 2 2 0 0 0\n1 1 10\n-60 0 60\n0 90\n1 2 3 4 5 6\n";
    fuzz(Format {
        name: "ies",
        samples: vec![street.to_vec(), tilted.to_vec()],
        read: |bytes, _| {
            let text = String::from_utf8_lossy(bytes);
            match lucent_scene::ies::parse_ies(Path::new("fuzz.ies"), &text) {
                Ok(ies) => {
                    // Every direction gives a finite, non-negative intensity.
                    for d in [
                        glam::Vec3::NEG_Z,
                        glam::Vec3::X,
                        glam::Vec3::new(0.3, -0.5, 0.8),
                    ] {
                        let i = ies.profile.intensity(d.normalize());
                        assert!(i.is_finite() && i >= 0.0, "{i}");
                    }
                    assert!(ies.profile.total().is_finite());
                    true
                }
                Err(_) => false,
            }
        },
    });
}

#[test]
fn mutated_ply_files() {
    let mut samples: Vec<Vec<u8>> = vec![
        PLY_QUAD.into(),
        PLY_STRIPS.into(),
        TRI_PLY.into(),
        ply_binary(false),
        ply_binary(true),
    ];
    if let Some(head) = shared_head("igea.ply") {
        samples.extend(ply_head_that_reads(&head));
        samples.push(head);
    }
    fuzz(Format {
        name: "ply",
        samples,
        read: |bytes, dir| {
            let Ok(m) = parse_ply(bytes, Path::new("fuzz.ply")) else {
                return false;
            };
            let n = m.positions.len();
            assert!(m.normals.as_ref().is_none_or(|v| v.len() == n));
            assert!(m.colors.as_ref().is_none_or(|v| v.len() == n));
            Mesh::new(m.positions, m.triangles)
                .validate()
                .expect("a parsed file gives a valid mesh");
            load(&input(dir, "fuzz.ply", bytes))
        },
    });
}

#[test]
fn mutated_gltf_files() {
    let [text, glb] = gltf_samples();
    fuzz(Format {
        name: "gltf",
        samples: vec![text, glb, tri_gltf("tri.bin").into()],
        read: |bytes, dir| {
            let name = if bytes.starts_with(b"glTF") {
                "fuzz.glb"
            } else {
                "fuzz.gltf"
            };
            let path = input(dir, name, bytes);
            let whole = read_gltf_part(&path, None, &SANDBOX, &mut Fingerprint::default());
            if let Ok(mesh) = whole {
                mesh.validate().expect("a read file gives a valid mesh");
            }
            load(&path)
        },
    });
}

#[test]
fn mutated_mitsuba_files() {
    fuzz(Format {
        name: "mitsuba",
        samples: vec![MITSUBA_SCENE.into(), MITSUBA_INCLUDE.into()],
        read: |bytes, dir| {
            // The include sample's sibling; mutations may make a file include itself instead.
            input(dir, "other.xml", MITSUBA_SCENE.as_bytes());
            load(&input(dir, "fuzz.xml", bytes))
        },
    });
}

#[test]
fn mutated_povray_files() {
    fuzz(Format {
        name: "povray",
        samples: vec![POV_LANGUAGE.into(), POV_SHAPES.into()],
        read: |bytes, dir| load(&input(dir, "fuzz.pov", bytes)),
    });
}

/// The harness itself: mutations stay in bounds, the allocator sees a read's memory, and the
/// samples read as written (a fuzz of samples that fail at once would test little).
#[test]
fn the_harness_works() {
    let samples = vec![b"v 1 2 3\nf 1 1 1\n".to_vec(), Vec::new()];
    let mut runner = TestRunner::deterministic();
    for _ in 0..2000 {
        let m = mutation().new_tree(&mut runner).unwrap().current();
        for s in &samples {
            let mut b = s.clone();
            apply(&m, &mut b, &samples);
        }
    }
    assert_eq!(mutate::numbers(b"v 1.5 -2e3 x\n"), vec![(2, 5), (6, 10)]);
    let big = run_watched("harness", Path::new("-"), || {
        // Zeroed: the pages are never touched, so this costs no real memory.
        std::hint::black_box(vec![0u8; CAP + 1]);
    });
    assert!(big.unwrap_err().contains("the cap is 512 MiB"));
    let panics = run_watched("harness", Path::new("-"), || panic!("boom"));
    assert!(panics.unwrap_err().contains("boom"));

    let dir = folder("harness");
    let tri = obj_ok(TRI_OBJ.as_bytes()) + obj_ok(OBJ_QUAD.as_bytes());
    assert_eq!(tri, 1 + 5);
    for s in [MTL_THREE, TRI_MTL] {
        assert!(parse_mtl(s.as_bytes(), Path::new("m.mtl")).is_ok());
    }
    let mut plies = vec![PLY_QUAD.into(), PLY_STRIPS.into(), TRI_PLY.into()];
    plies.extend([ply_binary(false), ply_binary(true)]);
    if let Some(head) = shared_head("igea.ply") {
        let fixed = ply_head_that_reads(&head).expect("igea.ply is binary, of scalar vertices");
        assert!(
            parse_ply(&fixed, Path::new("h.ply"))
                .unwrap()
                .positions
                .len()
                > 1000
        );
        plies.push(fixed);
    }
    for p in &plies {
        parse_ply(p, Path::new("s.ply")).unwrap();
    }
    let loads = |name: &str, bytes: &[u8]| {
        let file = SceneFile::read_with(&input(&dir, name, bytes), &SANDBOX).unwrap();
        file.build().unwrap_or_else(|e| panic!("{name}: {e}"));
    };
    loads("spheres.toml", SCENE_SPHERES.as_bytes());
    loads("meshes.toml", SCENE_MESHES.as_bytes());
    let [text, glb] = gltf_samples();
    loads("scene.gltf", &text);
    loads("scene.glb", &glb);
    input(&dir, "other.xml", MITSUBA_SCENE.as_bytes());
    loads("scene.xml", MITSUBA_SCENE.as_bytes());
    loads("include.xml", MITSUBA_INCLUDE.as_bytes());
    loads("language.pov", POV_LANGUAGE.as_bytes());
    loads("shapes.pov", POV_SHAPES.as_bytes());
}

/// Triangles of an OBJ sample, which must parse.
fn obj_ok(b: &[u8]) -> usize {
    parse_obj(b, Path::new("s.obj")).unwrap().triangle_count()
}
