//! Every class of bad scene file gets an error naming the file, line and column, and the cause.

use lucent_scene::{LoadError, SceneFile};
use std::path::PathBuf;

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
const MATERIAL: &str = "[[material]]\nname = \"m\"\nkd = 0.5\n";

fn load(text: &str) -> Result<(), LoadError> {
    let file = SceneFile::parse(PathBuf::from("bad.toml"), PathBuf::new(), text.to_string())?;
    file.build().map(|_| ())
}

/// The error for `text`, checked to be at `line:column` and to mention `cause`.
fn assert_error(text: &str, line: usize, column: usize, cause: &str) {
    let e = load(text).expect_err("the scene should be refused");
    let shown = e.to_string();
    assert!(
        shown.starts_with(&format!("bad.toml:{line}:{column}: ")),
        "wrong place: {shown}"
    );
    assert!(
        shown.contains(cause),
        "`{shown}` does not mention `{cause}`"
    );
    assert_eq!(shown.lines().count(), 1, "one line: {shown}");
}

#[test]
fn a_good_scene_loads() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    load(&text).unwrap();
}

#[test]
fn unknown_key() {
    let text = format!("{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncentre = [0, 0, 0]\n");
    assert_error(&text, 9, 1, "unknown field `centre`");
}

#[test]
fn unknown_table() {
    assert_error(
        &format!("{CAMERA}[lights]\n"),
        4,
        2,
        "unknown field `lights`",
    );
}

#[test]
fn key_of_another_kind_of_object() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nradius = 2\nmaterial = \"m\"\n"
    );
    assert_error(&text, 11, 10, "`radius` does not apply to a plane");
}

#[test]
fn wrong_type() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = \"origin\"\nradius = 1\nmaterial = \"m\"\n"
    );
    assert_error(
        &text,
        9,
        10,
        "invalid type: string \"origin\", expected a vector",
    );
}

#[test]
fn integer_where_a_vector_belongs() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = 0\nradius = 1\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 10, "invalid type: integer `0`, expected a vector");
}

#[test]
fn vector_too_long() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0, 1, 2]\nradius = 1\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 10, "invalid length 5");
}

#[test]
fn vector_of_the_wrong_length() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 10, "invalid length 2");
}

#[test]
fn unknown_object_type() {
    let text = format!("{CAMERA}{MATERIAL}[[object]]\ntype = \"pyramid\"\nmaterial = \"m\"\n");
    assert_error(&text, 8, 8, "unknown variant `pyramid`");
}

#[test]
fn unknown_material_name() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"gold\"\n"
    );
    assert_error(&text, 11, 12, "unknown material `gold` (known: m)");
}

#[test]
fn duplicate_material_name() {
    assert_error(
        &format!("{CAMERA}{MATERIAL}{MATERIAL}"),
        8,
        8,
        "a material named `m` already exists",
    );
}

#[test]
fn negative_radius() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\nmaterial = \"m\"\n"
    );
    assert_error(&text, 10, 10, "radius must be positive, got -1");
}

#[test]
fn sphere_radius_out_of_range() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1e20\nmaterial = \"m\"\n"
    );
    assert_error(
        &text,
        10,
        10,
        "radius must be between 1e-8 and 1e15, got 1e20",
    );
}

#[test]
fn zero_normal() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 0]\nmaterial = \"m\"\n"
    );
    assert_error(&text, 10, 10, "normal must not be zero");
}

#[test]
fn nan_and_infinity() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, nan, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 14, "expected a finite number, found NaN");
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = inf\nmaterial = \"m\"\n"
    );
    assert_error(
        &text,
        10,
        10,
        "expected a finite number (at most about 3.4e38), found inf",
    );
    // Beyond f32's range, shown briefly.
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1e300\nmaterial = \"m\"\n"
    );
    assert_error(&text, 10, 10, "found 1e300");
}

#[test]
fn negative_colour() {
    assert_error(
        &format!("{CAMERA}[world]\nambient = [0, -1, 0]\n"),
        5,
        11,
        "colours must not be negative",
    );
}

#[test]
fn missing_required_key() {
    let text = format!("{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\nmaterial = \"m\"\n");
    assert_error(&text, 7, 1, "a sphere needs `center`");
}

#[test]
fn degenerate_camera() {
    assert_error(
        "[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, 0]\n",
        1,
        1,
        "eye and look_at are the same point",
    );
}

#[test]
fn zero_width() {
    assert_error(
        &format!("{CAMERA}[image]\nwidth = 0\n"),
        5,
        9,
        "width must be between 1 and",
    );
}

#[test]
fn negative_integer() {
    assert_error(
        &format!("{CAMERA}[image]\nwidth = -3\n"),
        5,
        9,
        "invalid value: integer `-3`",
    );
}

#[test]
fn collinear_triangle() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"triangle\"\nvertices = [[0, 0, 0], [1, 1, 1], [2, 2, 2]]\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 12, "collinear");
}

#[test]
fn unknown_integrator_and_accelerator() {
    assert_error(
        &format!("{CAMERA}[render]\nintegrator = \"radiosity\"\n"),
        5,
        14,
        "unknown variant `radiosity`",
    );
    assert_error(
        &format!("{CAMERA}[render]\naccelerator = \"kd\"\n"),
        5,
        15,
        "unknown accelerator `kd`",
    );
}

#[test]
fn bad_checker() {
    let text = format!(
        "{CAMERA}[[material]]\nname = \"c\"\nkd = {{ checker = {{ even = 1, odd = 0, size = 0 }} }}\n"
    );
    assert_error(&text, 6, 6, "checker size must be positive");
    let text = format!("{CAMERA}[[material]]\nname = \"c\"\nkd = {{ marble = 1 }}\n");
    assert_error(&text, 6, 6, "unknown texture key `marble`");
}

#[test]
fn invalid_toml_syntax() {
    assert_error(&format!("{CAMERA}[world\n"), 4, 7, "");
}

#[test]
fn missing_mesh_file() {
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"mesh\"\nfile = \"nowhere.obj\"\nmaterial = \"m\"\n"
    );
    assert_error(&text, 9, 8, "mesh file `nowhere.obj` not found");
}

#[test]
fn bad_mesh_file_names_the_mesh_files_line() {
    let dir = std::env::temp_dir().join(format!("lucent-scene-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap();
    let text = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"mesh\"\nfile = \"bad.obj\"\nmaterial = \"m\"\n"
    );
    let file = SceneFile::parse(dir.join("s.toml"), dir.clone(), text).unwrap();
    let e = file.build().unwrap_err().to_string();
    assert!(
        e.ends_with("bad.obj:3:1: vertex index 3 is out of range (2 in the file)"),
        "{e}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn sampling_settings_belong_to_their_sampling() {
    assert_error(
        &format!("{CAMERA}[render]\naa_threshold = 0.2\n"),
        5,
        16,
        "`aa_threshold` needs `aa = \"adaptive\"` or `\"quadtree\"`",
    );
    assert_error(
        &format!("{CAMERA}[render]\naa = \"adaptive\"\naa_block = 2\n"),
        6,
        12,
        "`aa_block` needs `aa = \"quadtree\"`",
    );
    assert_error(
        &format!("{CAMERA}[render]\naa = \"quadtree\"\naa_depth = 9\n"),
        6,
        12,
        "aa_depth must be at most 8",
    );
    assert_error(
        &format!("{CAMERA}[render]\naa = \"quadtree\"\naa_block = 5\n"),
        6,
        12,
        "aa_block must be between 1 and 4",
    );
    assert_error(&format!("{CAMERA}[render]\naa = \"jitter\"\n"), 5, 6, "");
    assert_error(
        &format!("{CAMERA}[render]\nintegrator = \"raycast\"\nshadows = false\n"),
        6,
        11,
        "`shadows` applies to the whitted integrator only",
    );
    // A good one: adaptive settings in the file, one film sample per pixel.
    let text = format!(
        "{CAMERA}[image]\nsamples = 16\n[render]\naa = \"quadtree\"\naa_threshold = 0.05\naa_block = 2\n"
    );
    let file = SceneFile::parse(PathBuf::from("s.toml"), PathBuf::new(), text).unwrap();
    let settings = file.build().unwrap().settings;
    assert_eq!(settings.spp, 1);
    assert_eq!(
        settings.sampling,
        lucent::render::Sampling::Adaptive(lucent::schedule::adaptive::Adaptive {
            threshold: 0.05,
            depth: 3,
            block: 2,
        })
    );
}

/// CRC-32 (as PNG chunks use it), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

#[test]
fn a_huge_image_is_refused_from_its_header() {
    // A PNG whose header claims 30000 × 30000 texels (10 GB as float triples), with no data:
    // refused before anything is decoded.
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&30_000u32.to_be_bytes());
    ihdr.extend_from_slice(&30_000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    for chunk in [&b"IDAT"[..], b"IEND"] {
        png.extend_from_slice(&0u32.to_be_bytes());
        png.extend_from_slice(chunk);
        png.extend_from_slice(&crc32(chunk).to_be_bytes());
    }
    let dir = std::env::temp_dir().join(format!("lucent-scene-huge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("huge.png"), png).unwrap();
    let text = format!(
        "{CAMERA}[[material]]\nname = \"m\"\nkd = {{ image = \"huge.png\" }}\n[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
    );
    let file = SceneFile::parse(dir.join("s.toml"), dir.clone(), text).unwrap();
    let e = file.build().unwrap_err().to_string();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(e.contains("huge.png") && e.contains("30000×30000"), "{e}");
}

#[test]
fn photon_counts_are_bounded_per_iteration() {
    let text = format!("{CAMERA}[render]\nintegrator = \"sppm\"\nphotons = 4294967295\n");
    assert_error(&text, 6, 11, "at most 16777216 per iteration");
    let text = format!("{CAMERA}[render]\nintegrator = \"sppm\"\nphotons = 16777216\n");
    load(&text).unwrap();
}

#[test]
fn indices_of_refraction_are_bounded() {
    let text = format!("{CAMERA}[[material]]\nname = \"g\"\ntype = \"dielectric\"\nior = 3e38\n");
    assert_error(&text, 7, 7, "between 0.001 and 1000");
    let text = format!("{CAMERA}[[material]]\nname = \"g\"\nkt = 1\nior = 1e-30\n");
    assert_error(&text, 7, 7, "between 0.001 and 1000");
}

#[test]
fn a_thin_film_is_checked_and_belongs_to_pbr() {
    let pbr = format!("{CAMERA}[[material]]\nname = \"g\"\ntype = \"pbr\"\n");
    load(&format!(
        "{pbr}iridescence = 1\niridescence_ior = 1.8\niridescence_thickness = 650\n"
    ))
    .unwrap();
    assert_error(
        &format!("{pbr}iridescence = 1\niridescence_thickness = 70000\n"),
        8,
        25,
        "iridescence_thickness must lie in [0, 65535]",
    );
    assert_error(
        &format!("{pbr}iridescence = 1.5\n"),
        7,
        15,
        "iridescence must lie in [0, 1]",
    );
    assert_error(
        &format!("{pbr}iridescence_ior = 0\n"),
        7,
        19,
        "iridescence_ior must be positive",
    );
    assert_error(
        &format!("{CAMERA}[[material]]\nname = \"g\"\ntype = \"diffuse\"\niridescence = 1\n"),
        7,
        15,
        "`iridescence` does not apply to a diffuse material",
    );
}

// The scene sweep's findings (tests/scene_sweep.rs): values the format took that the renderer
// could not use are refused where they are written, and directions of any length work.

#[test]
fn placements_the_renderer_cannot_invert_are_refused_at_their_scale() {
    let rect = format!("{CAMERA}{MATERIAL}[[object]]\ntype = \"rectangle\"\nmaterial = \"m\"\n");
    // 1e-20 on every axis: a determinant of 1e-60, 0 in f32.
    let cause = "the placement is singular or overflows in single precision";
    assert_error(&format!("{rect}scale = 1e-20\n"), 10, 9, cause);
    // 1e-13: a determinant of 1e-39, whose reciprocal overflows.
    assert_error(&format!("{rect}scale = 1e-13\n"), 10, 9, cause);
    assert_error(&format!("{rect}scale = [1e20, 1e20, 1]\n"), 10, 9, cause);
    let m = "transform = [1e20, 0, 0, 0, 0, 1e20, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n";
    assert_error(&format!("{rect}{m}"), 10, 13, "determinant overflows");
    load(&format!("{rect}scale = [1e12, 1e-12, 1]\n")).unwrap();
    // A motion that does it at time 0 is refused at the motion.
    let keys = "motion = { keys = [{ time = 0, scale = 1e-20 }] }\n";
    assert_error(
        &format!("{rect}{keys}"),
        10,
        10,
        "moved to its place at time 0, the placement is singular",
    );
    let far =
        "translate = [3e38, 0, 0]\nmotion = { keys = [{ time = 0, translate = [3e38, 0, 0] }] }\n";
    assert_error(&format!("{rect}{far}"), 11, 10, "the translation overflows");
}

#[test]
fn objects_with_a_textured_emission_cannot_move() {
    let text = format!(
        "{CAMERA}[[material]]\nname = \"m\"\nemission = {{ checker = {{ even = 1, odd = 0, size = 1 }} }}\n\
         [[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n\
         motion = {{ orbit = {{ period = 4 }} }}\n"
    );
    assert_error(&text, 12, 10, "an object that emits light cannot move");
}

#[test]
fn filter_radii_are_bounded_below() {
    for (filter, radius) in [
        ("gaussian", "1e-30"),
        ("mitchell", "1e-45"),
        ("tent", "0.001"),
    ] {
        let text = format!("{CAMERA}[render]\nfilter = \"{filter}\"\nfilter_radius = {radius}\n");
        assert_error(
            &text,
            6,
            17,
            "filter_radius must be between 0.01 and 16 pixels",
        );
        let text = format!("{CAMERA}[render]\nfilter = \"{filter}\"\nfilter_radius = 0.01\n");
        load(&text).unwrap();
    }
}

#[test]
fn conductor_indices_are_bounded() {
    let metal = format!("{CAMERA}[[material]]\nname = \"m\"\ntype = \"conductor\"\n");
    let index = "a conductor's index of refraction";
    assert_error(&format!("{metal}eta = 1e15\n"), 4, 1, index);
    let k = "an extinction coefficient";
    assert_error(&format!("{metal}eta = 1\nk = [1, 2, 1e10]\n"), 4, 1, k);
    load(&format!("{metal}eta = 1000\nk = 1000\n")).unwrap();
}

#[test]
fn directions_may_have_any_length() {
    let sphere =
        "[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n";
    for v in ["1e-30", "1e-45", "1e30", "3e38"] {
        let lights = format!(
            "[[light]]\ntype = \"directional\"\ndirection = [0, -{v}, 0]\n\
             [[light]]\ntype = \"spot\"\nposition = [0, 5, 0]\ndirection = [{v}, -{v}, 0]\ncutoff = 30\n"
        );
        let plane = format!(
            "[[object]]\ntype = \"plane\"\npoint = [0, -1, 0]\nnormal = [0, {v}, 0]\nmaterial = \"m\"\n"
        );
        let moving = format!(
            "[[object]]\ntype = \"cube\"\nmaterial = \"m\"\nmotion = {{ orbit = {{ axis = [0, {v}, 0], period = 4 }} }}\n"
        );
        let camera = format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, {v}, 0]\n");
        let text = format!("{camera}{MATERIAL}{lights}{sphere}{plane}{moving}");
        load(&text).unwrap_or_else(|e| panic!("{v}: {e}"));
        // The plane faces the camera and is seen: its normal normalises, whatever its length.
        let wall = format!(
            "{CAMERA}{MATERIAL}[image]\nwidth = 1\nheight = 1\n[render]\nintegrator = \"raycast\"\n\
             [[object]]\ntype = \"plane\"\npoint = [0, 0, -1]\nnormal = [0, 0, {v}]\nmaterial = \"m\"\n"
        );
        let file = SceneFile::parse(PathBuf::from("wall.toml"), PathBuf::new(), wall).unwrap();
        let loaded = file.build().unwrap();
        let cancel = std::sync::atomic::AtomicBool::new(false);
        let hooks = lucent::render::Hooks {
            cancel: &cancel,
            progress: &|_, _| {},
            checkpoint: None,
        };
        let film = lucent::render::render(&loaded.scene, &loaded.settings, None, &hooks)
            .unwrap()
            .film;
        assert_eq!(film.pixel(0, 0).to_array(), [0.5; 3], "normal [0, 0, {v}]");
    }
}
