//! The Cornell box as Mitsuba publishes it: read, built and rendered with each wall in its place.

use super::support::*;
use glam::Vec3;
use lucent::Rgb;
use lucent::integrator::RayStats;
use lucent_scene::SceneFile;
use lucent_scene::desc::{IntegratorName, ObjectKind};

#[test]
fn the_cornell_box_reads_as_mitsuba_describes_it() {
    let dir = Dir::new("cbox-read");
    let path = dir.write("cbox.xml", CBOX);
    let (file, loaded) = load(&path);
    let d = &file.desc;

    // The sensor: at (0, 0, 3.9) looking down −z, y up; on a square film every fov_axis is the
    // same angle, so the vertical field of view is Mitsuba's 39.3077°.
    assert!(file.camera_given);
    let cam = d.camera.get_ref();
    assert!(
        near(cam.eye.0.as_vec3(), Vec3::new(0.0, 0.0, 3.9)),
        "{:?}",
        cam.eye
    );
    assert!(near(
        (cam.look_at.0 - cam.eye.0).normalize().as_vec3(),
        -Vec3::Z
    ));
    assert!(near(cam.up.0.normalize(), Vec3::Y));
    assert!((cam.fov.0 - 39.3077).abs() < 1e-4, "{}", cam.fov.0);
    assert_eq!(
        (*d.image.width.get_ref(), *d.image.height.get_ref()),
        (256, 256)
    );
    assert_eq!(*d.image.samples.get_ref(), 64);
    // max_depth 8 counts path vertices; Whitted's depth counts bounces after the lit first hit.
    assert_eq!(*d.render.max_depth.get_ref(), 6);

    // The built camera agrees: its centre ray goes down −z, its top edge 19.65° above it.
    let camera = &loaded.scene.camera;
    assert!(near(camera.eye(), Vec3::new(0.0, 0.0, 3.9)));
    let centre = camera.ray(128.0, 128.0).dir;
    assert!(near(centre, -Vec3::Z), "{centre}");
    let top = camera.ray(128.0, 0.0).dir;
    assert!((angle(centre, top) - 39.3077 / 2.0).abs() < 1e-3);
    assert!(top.y > 0.0, "row 0 is the top of the image");

    // Six rectangles (five walls and the light) and two boxes; three BSDFs and the emitting
    // copy of the white one.
    let o: Vec<ObjectKind> = d.objects.iter().map(|o| o.get_ref().kind).collect();
    assert_eq!(o.iter().filter(|k| **k == ObjectKind::Rectangle).count(), 6);
    assert_eq!(o.iter().filter(|k| **k == ObjectKind::Cube).count(), 2);
    assert_eq!(o.len(), 8);
    assert!(d.lights.is_empty(), "the box is lit by its area light only");
    let mut names: Vec<&str> = d
        .materials
        .iter()
        .map(|m| m.get_ref().name.get_ref().as_str())
        .collect();
    names.sort_unstable();
    assert_eq!(names.len(), 4, "{names:?}");
    assert_eq!(&names[..3], ["green", "red", "white"]);
    assert!(
        names[3].starts_with("white emitting at cbox.xml:"),
        "{names:?}"
    );
    let c = loaded.scene.counts();
    assert_eq!((c.instances, c.meshes, c.spheres, c.planes), (8, 2, 0, 0));
    assert_eq!(c.triangles, 6 * 2 + 2 * 12);
    assert_eq!(c.lights, 0, "the box is lit by its area light only");
    assert_eq!(c.materials, 4);
    // Under the path tracer the area light is sampled as the rectangle it is.
    assert_eq!(loaded.scene.emitters.area.lights.len(), 1);
    assert!((loaded.scene.emitters.area.lights[0].area - 4.0 * 0.23 * 0.19).abs() < 1e-5);
    assert!(
        matches!(loaded.settings.integrator, lucent::integrator::Integrator::Path(p) if p.max_depth == 6)
    );
    // Nothing is approximated: the box renders as Mitsuba describes it.
    assert!(loaded.warnings.is_empty(), "{:#?}", loaded.warnings);
}

/// Rows and columns of a 64 × 64 render where one surface alone is seen, worked out from the
/// camera (the image plane at distance 1 spans ±tan(19.65°) = ±0.357): a point (x, y, z) is at
/// column 32·(1 + 2.8·x / (3.9 − z)) and row 32·(1 − 2.8·y / (3.9 − z)).
struct Region {
    name: &'static str,
    xs: std::ops::RangeInclusive<u32>,
    ys: std::ops::RangeInclusive<u32>,
    /// Its reflectance.
    albedo: Rgb,
    /// The surface's facing, as Mitsuba's transform turns the rectangle's +z.
    normal: Vec3,
    /// Which coordinate is fixed on it, and at what value.
    plane: (usize, f32),
}

fn cbox_regions() -> Vec<Region> {
    vec![
        // The red wall, x = −1, seen at columns 1–13.
        Region {
            name: "left wall",
            xs: 2..=10,
            ys: 28..=36,
            albedo: RED,
            normal: Vec3::X,
            plane: (0, -1.0),
        },
        Region {
            name: "right wall",
            xs: 53..=61,
            ys: 28..=36,
            albedo: GREEN,
            normal: -Vec3::X,
            plane: (0, 1.0),
        },
        // The ceiling, y = 1, from row 1 (z = 0.96) down to the back wall at row 14; the light
        // hangs under it at rows 8–9.
        Region {
            name: "ceiling",
            xs: 20..=44,
            ys: 1..=6,
            albedo: WHITE,
            normal: -Vec3::Y,
            plane: (1, 1.0),
        },
        Region {
            name: "light",
            xs: 28..=35,
            ys: 8..=9,
            albedo: WHITE,
            normal: -Vec3::Y,
            plane: (1, 0.99),
        },
        // The floor in front of the tall box and left of the short one.
        Region {
            name: "floor",
            xs: 12..=26,
            ys: 57..=62,
            albedo: WHITE,
            normal: Vec3::Y,
            plane: (1, -1.0),
        },
        // The back wall, z = −1, above the tall box (its top is at row 27).
        Region {
            name: "back wall",
            xs: 22..=42,
            ys: 16..=24,
            albedo: WHITE,
            normal: Vec3::Z,
            plane: (2, -1.0),
        },
    ]
}

#[test]
fn the_cornell_box_renders_each_wall_in_its_place() {
    let dir = Dir::new("cbox-render");
    let path = dir.write("cbox.xml", CBOX);
    let file = SceneFile::read_with(&path, &open()).unwrap();

    // Ray casting shows each surface's own colour: every pixel of a region is its wall's.
    let flat = render_small(&file, 64, IntegratorName::Raycast);
    for r in cbox_regions() {
        for (x, y, c) in flat.region(r.xs.clone(), r.ys.clone()) {
            assert!(
                same_color(c, r.albedo, 1e-5),
                "{} at ({x}, {y}): {c:?}, expected {:?}",
                r.name,
                r.albedo
            );
        }
    }
    // Beyond the box's open front (column 0 at mid-height) there is nothing.
    assert_eq!(flat.at(0, 32), Rgb::BLACK);

    // The camera's rays meet the surface each region names, facing the way Mitsuba's
    // transforms turn it.
    let mut small = file.clone();
    small.desc.image.width = lucent_scene::Spanned::new(0..0, 64);
    small.desc.image.height = lucent_scene::Spanned::new(0..0, 64);
    let scene = small.build().unwrap().scene;
    let mut stats = RayStats::default();
    for r in cbox_regions() {
        for (x, y, _) in flat.region(r.xs.clone(), r.ys.clone()) {
            let ray = scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
            let hit = scene.intersect(&ray, &mut stats.traversal).unwrap();
            assert!(
                hit.normal.abs_diff_eq(r.normal, 1e-4),
                "{} at ({x}, {y}) faces {}",
                r.name,
                hit.normal
            );
            assert!(
                (hit.point[r.plane.0] - r.plane.1).abs() < 1e-3,
                "{} at ({x}, {y}) is at {}",
                r.name,
                hit.point
            );
        }
    }

    // Whitted's shading: the light (seen from below, its front) is by far the brightest; the
    // walls take their colour from it.
    let lit = render_small(&file, 64, IntegratorName::Whitted);
    let mean = |name: &str| {
        let r = cbox_regions().into_iter().find(|r| r.name == name).unwrap();
        let pixels = lit.region(r.xs, r.ys);
        let n = pixels.len() as f32;
        pixels
            .iter()
            .fold(Rgb::BLACK, |sum, (_, _, c)| sum + *c * (1.0 / n))
    };
    let light = mean("light");
    assert!(light.r > 10.0, "the light: {light:?}");
    for name in ["left wall", "right wall", "ceiling", "floor", "back wall"] {
        let m = mean(name);
        assert!(
            m.max_channel() < light.max_channel() / 5.0,
            "{name} {m:?} vs light {light:?}"
        );
        assert!(m.max_channel() > 0.0, "{name} is lit");
    }
    let left = mean("left wall");
    assert!(left.r > 3.0 * left.g && left.r > 3.0 * left.b, "{left:?}");
    let right = mean("right wall");
    assert!(
        right.g > 2.0 * right.r && right.g > 2.0 * right.b,
        "{right:?}"
    );
    let floor = mean("floor");
    assert!(
        floor.r > floor.g && floor.g > floor.b && floor.b > 0.2 * floor.r,
        "{floor:?}"
    );
}
