//! Khronos' glTF sample models (in `../shared/data/gltf/`, skipped where absent) rendered from
//! the command line: a `.glb` renders as its `.gltf` does, and the test-pattern models show
//! what their patterns say must be there.
//!
//! Each pattern test converts the model to TOML, puts an orthographic camera square on to the
//! pattern (so that a point of the model falls on a known pixel), renders it with the path
//! tracer, and reads the pixels.

mod common;

use common::{Image, assert_success, lucent, read_pfm, render_to};
use std::path::{Path, PathBuf};

/// The folder of sample model `name`, or `None` (with a note) where the shared data is absent.
fn model(name: &str) -> Option<PathBuf> {
    let dir = lucent_scene::data_dir().join("gltf").join(name);
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: {} is not here", dir.display());
        None
    }
}

fn render(scene: &Path, out: &Path, args: &[&str]) {
    assert_success(&render_to(scene, args, out));
}

#[test]
fn a_glb_renders_as_its_gltf_and_files_do_bit_for_bit() {
    let Some(dir) = model("CesiumMilkTruck") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let args = [
        "--integrator",
        "path",
        "--spp",
        "4",
        "--width",
        "96",
        "--height",
        "72",
    ];
    let images: Vec<Image> = [
        "glTF/CesiumMilkTruck.gltf",
        "glTF-Binary/CesiumMilkTruck.glb",
    ]
    .iter()
    .enumerate()
    .map(|(i, file)| {
        let pfm = out.path().join(format!("{i}.pfm"));
        render(&dir.join(file), &pfm, &args);
        read_pfm(&pfm)
    })
    .collect();
    assert!(images[0] == images[1], "the .glb renders differently");
    // The truck's texture is there: its cab is not one flat colour.
    let spread = images[1]
        .pixels
        .iter()
        .filter(|p| p[0] > 0.05 && (p[0] - p[2]).abs() > 0.05)
        .count();
    assert!(spread > 50, "{spread} coloured texels");

    // Converted to TOML, the .glb's embedded images are named by the file and their index.
    let toml = out.path().join("converted/truck.toml");
    std::fs::create_dir_all(toml.parent().unwrap()).unwrap();
    let glb = dir.join("glTF-Binary/CesiumMilkTruck.glb");
    assert_success(
        &lucent()
            .arg("convert")
            .arg(&glb)
            .arg(&toml)
            .output()
            .unwrap(),
    );
    let text = std::fs::read_to_string(&toml).unwrap();
    assert!(text.contains("gltf_image = 0"), "{text}");
    let again = out.path().join("again.pfm");
    render(&toml, &again, &args);
    assert!(
        read_pfm(&again) == images[1],
        "the converted .glb renders differently"
    );
}

/// The model converted to TOML in `out`, seen by an orthographic camera at `eye` looking at
/// `look_at` over a view `height` high, lit from the camera too, rendered `size` pixels
/// square by the path tracer.
fn pattern(
    out: &Path,
    file: &Path,
    (eye, look_at, up): ([f32; 3], [f32; 3], [f32; 3]),
    height: f32,
    size: u32,
) -> Image {
    let toml = out.join("scene.toml");
    assert_success(
        &lucent()
            .arg("convert")
            .arg(file)
            .arg(&toml)
            .output()
            .unwrap(),
    );
    let text = std::fs::read_to_string(&toml).unwrap();
    let start = text.find("[camera]").expect("a camera");
    let end = text[start + 1..]
        .find("\n[")
        .map_or(text.len(), |e| start + 1 + e);
    let camera = format!(
        "[camera]\neye = {eye:?}\nlook_at = {look_at:?}\nup = {up:?}\northographic = {height}\n"
    );
    // A light from the camera, so that the pattern is lit whichever way it faces.
    let d = [0, 1, 2].map(|i| look_at[i] - eye[i]);
    let light = format!("\n[[light]]\ntype = \"directional\"\ndirection = {d:?}\n");
    let text = format!("{}{camera}{}{light}", &text[..start], &text[end..]);
    std::fs::write(&toml, text).unwrap();
    let pfm = out.join("pattern.pfm");
    let size = size.to_string();
    let args = [
        "--integrator",
        "path",
        "--spp",
        "16",
        "--width",
        &size,
        "--height",
        &size,
    ];
    render(&toml, &pfm, &args);
    read_pfm(&pfm)
}

/// The mean colour of the pixels whose centres fall in the view-space rectangle `[x0, x1] ×
/// [y0, y1]` (from the image's centre, +x right, +y up, in scene units) of an image `height`
/// units high.
fn mean(img: &Image, height: f32, (x0, x1): (f32, f32), (y0, y1): (f32, f32)) -> [f32; 3] {
    let scale = img.height as f32 / height;
    let to_px = |x: f32| x * scale + img.width as f32 / 2.0;
    let to_py = |y: f32| img.height as f32 / 2.0 - y * scale;
    let mut sum = [0.0f64; 3];
    let mut n = 0;
    for py in 0..img.height {
        for px in 0..img.width {
            let (cx, cy) = (px as f32 + 0.5, py as f32 + 0.5);
            if cx >= to_px(x0) && cx < to_px(x1) && cy >= to_py(y1) && cy < to_py(y0) {
                let p = img.at(px, py);
                (0..3).for_each(|c| sum[c] += f64::from(p[c]));
                n += 1;
            }
        }
    }
    assert!(n > 0, "an empty patch");
    sum.map(|s| (s / n as f64) as f32)
}

fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

#[test]
fn texture_coordinates_put_each_corner_s_checker_in_its_corner() {
    let Some(dir) = model("TextureCoordinateTest") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    // The model faces −z (its README): seen from there, +x is to the left.
    let view = ([0.0, 0.0, -5.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/TextureCoordinateTest.gltf"),
        view,
        2.6,
        260,
    );
    // Each square spans 0.2 to 1.2 from the centre along both axes; its template corner has a
    // checkered border along the square's two outer edges. Its other outer corners are plain.
    for (sx, sy) in [(-1.0f32, 1.0f32), (1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
        let patch = |ax: f32, ay: f32| {
            let span = |a: f32, s: f32| {
                // The template's border lies a little inside the square's edge.
                let (lo, hi) = (a - 0.14, a - 0.04);
                if s > 0.0 { (lo, hi) } else { (-hi, -lo) }
            };
            luminance(mean(&img, 2.6, span(ax, sx), span(ay, sy)))
        };
        // The outer corner, and the corners a flipped u or v would put the checker in.
        let (corner, along_x, along_y) = (patch(1.2, 1.2), patch(1.2, 0.36), patch(0.36, 1.2));
        assert!(
            corner < 0.8 * along_x && corner < 0.8 * along_y,
            "square ({sx}, {sy}): corner {corner}, beside it {along_x} and {along_y}"
        );
    }
}

#[test]
fn texture_transforms_offset_each_panel_to_its_tick() {
    let Some(dir) = model("TextureTransformTest") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let view = ([0.0, 0.55, 5.0], [0.0, 0.55, 0.0], [0.0, 1.0, 0.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/TextureTransformTest.gltf"),
        view,
        3.4,
        170,
    );
    // The top row: offsets in u, v and both move UV.png's quadrants so that the green, blue
    // and cyan ticks fill the panels; the yellow "not supported" quadrant is what shows when
    // the offset is not read.
    let panel = |x: f32| mean(&img, 3.4, (x - 0.3, x + 0.3), (-0.3, 0.3));
    let [r, g, b] = panel(-1.1);
    assert!(g > 2.0 * r && g > 2.0 * b, "Offset U: {r} {g} {b}");
    let [r, g, b] = panel(0.0);
    assert!(b > 2.0 * r && b > 2.0 * g, "Offset V: {r} {g} {b}");
    let [r, g, b] = panel(1.1);
    assert!(g > 2.0 * r && b > 2.0 * r, "Offset UV: {r} {g} {b}");
}

#[test]
fn a_single_sided_face_seen_from_behind_is_culled() {
    let Some(dir) = model("TextureSettingsTest") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    // The "single-sided" cell of the "Test" column: a face showing a red cross whose front
    // looks away, over a green tick. glTF culls the face; drawn, it hides the tick.
    let view = ([0.45, 2.54, 5.0], [0.45, 2.54, 0.0], [0.0, 1.0, 0.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/TextureSettingsTest.gltf"),
        view,
        1.0,
        100,
    );
    let green = img
        .pixels
        .iter()
        .filter(|p| p[1] > 0.05 && p[1] > 2.0 * p[0] && p[1] > 2.0 * p[2])
        .count();
    let red = img
        .pixels
        .iter()
        .filter(|p| p[0] > 0.05 && p[0] > 3.0 * p[1] && p[0] > 3.0 * p[2])
        .count();
    assert!(green > 100 && red < green, "green {green}, red {red}");
}

#[test]
fn normal_maps_light_their_bumps_from_the_side_the_geometry_is_lit() {
    let Some(dir) = model("NormalTangentTest") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let view = ([0.0, -0.125, 5.0], [0.0, -0.125, 0.0], [0.0, 1.0, 0.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/NormalTangentTest.gltf"),
        view,
        2.4,
        480,
    );
    // Each pair of tiles: a dome of geometry (centred at x, from the mesh) and, 0.32 to its
    // right, the same dome as a normal map, in each tangent orientation the rows try. The
    // default light comes from the upper left (with one from the camera): the upper left of
    // every dome is the brighter, the map's as the geometry's. (The gold column is left out:
    // a metal under two lights shows highlights, not shading.)
    let at =
        |x: f32, y: f32| luminance(mean(&img, 2.4, (x - 0.02, x + 0.02), (y - 0.02, y + 0.02)));
    for x in [-0.95f32, -0.15] {
        for row in [-0.8f32, -0.4, 0.0, 0.4, 0.8] {
            for (what, cx) in [("geometry", x), ("normal map", x + 0.32)] {
                let cy = row + 0.125;
                let (upper_left, lower_right) =
                    (at(cx - 0.05, cy + 0.05), at(cx + 0.05, cy - 0.05));
                assert!(
                    upper_left > 1.2 * lower_right,
                    "{what} at ({cx}, {cy}): upper left {upper_left}, lower right {lower_right}"
                );
            }
        }
    }
}

#[test]
fn vertex_colours_colour_the_box() {
    let Some(dir) = model("BoxVertexColors") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let view = ([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/BoxVertexColors.gltf"),
        view,
        1.2,
        120,
    );
    // The front face's corners take their vertices' colours: not one grey, nor one colour.
    let corner = |sx: f32, sy: f32| {
        let x = 0.4 * sx;
        let y = 0.4 * sy;
        mean(&img, 1.2, (x - 0.05, x + 0.05), (y - 0.05, y + 0.05))
    };
    let corners = [
        corner(-1.0, 1.0),
        corner(1.0, 1.0),
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
    ];
    let saturated = corners
        .iter()
        .filter(|c| {
            let (hi, lo) = (c[0].max(c[1]).max(c[2]), c[0].min(c[1]).min(c[2]));
            hi > 2.0 * lo.max(1e-4)
        })
        .count();
    let chroma = |c: [f32; 3]| {
        let s = c[0] + c[1] + c[2];
        c.map(|v| v / s.max(1e-6))
    };
    let spread = corners
        .iter()
        .flat_map(|a| corners.iter().map(move |b| (chroma(*a), chroma(*b))))
        .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0f32, f32::max))
        .fold(0.0f32, f32::max);
    assert!(saturated >= 2 && spread > 0.2, "{corners:?}");
}

#[test]
fn a_double_sided_plane_shows_its_texture_from_below() {
    let Some(dir) = model("TwoSidedPlane") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    // The plane lies in y = 0 facing +y; from below, its back shows the same wood, lit by
    // the light from the camera (single-sided, it would be culled: the grey background).
    let view = ([0.0, -5.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
    let img = pattern(
        out.path(),
        &dir.join("glTF/TwoSidedPlane.gltf"),
        view,
        2.4,
        96,
    );
    // (The light along the view puts the wood's glossy highlight in every pixel, which pales
    // its colour; the grey background would give r = g = b = 0.05.)
    let [r, g, b] = mean(&img, 2.4, (-0.6, 0.6), (-0.6, 0.6));
    assert!(r > 0.1 && r > 1.15 * b && r > g, "{r} {g} {b}");
}
