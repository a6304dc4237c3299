//! `lucent gallery` at a small size: every image made, the commands written beside them, and
//! the images differing where their captions say they do.

mod common;

use common::{assert_success, lucent};

#[test]
fn the_gallery_renders_every_concept() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("gallery");
    let output = lucent()
        .args(["gallery", "--width", "48", "--height", "36"])
        .arg(&out)
        .output()
        .unwrap();
    assert_success(&output);
    let index = std::fs::read_to_string(out.join("gallery.md")).unwrap();
    let image = |name: &str| {
        assert!(index.contains(&format!("({name}.png)")), "{name} is listed");
        let img = image::open(out.join(format!("{name}.png")))
            .unwrap()
            .to_rgb8();
        assert_eq!(img.dimensions(), (48, 36), "{name}");
        img
    };
    let names = [
        "raycast",
        "whitted",
        "no-shadows",
        "depth-0",
        "depth-1",
        "depth-2",
        "depth-5",
        "refraction",
        "tir",
        "cost-brute",
        "cost-bounds",
        "cost-octree",
        "cost-bvh",
        "cost-wide",
        "uniform-1",
        "uniform-16",
        "adaptive",
        "adaptive-density",
        "normals",
        "cbox-whitted",
        "cbox-path",
    ];
    for name in names {
        image(name);
    }
    // Each command is written down as it ran.
    assert!(index.contains("`lucent render --max-depth 0 -o depth-0.png --width 48 --height 36`"));
    assert!(out.join("scenes/sphere-field.toml").is_file());
    // Shadows, recursion and sampling change the picture; brute force's cost is one colour.
    assert_ne!(image("whitted"), image("no-shadows"));
    assert_ne!(image("depth-0"), image("depth-5"));
    assert_ne!(image("uniform-1"), image("adaptive"));
    let brute = image("cost-brute");
    let first = *brute.get_pixel(0, 0);
    assert!(brute.pixels().all(|p| *p == first));
    let bvh = image("cost-bvh");
    assert!(bvh.pixels().any(|p| *p != *bvh.get_pixel(0, 0)));
    // The critique answered: under Whitted the Cornell box's ceiling beside the light is
    // barely lit (its point light grazes it); the path tracer lights it by interreflection.
    let ceiling = |img: &image::RgbImage| {
        let p = img.get_pixel(12, 2);
        u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2])
    };
    let (whitted, path) = (
        ceiling(&image("cbox-whitted")),
        ceiling(&image("cbox-path")),
    );
    assert!(
        path > 2 * whitted,
        "ceiling: whitted {whitted}, path {path}"
    );
}
