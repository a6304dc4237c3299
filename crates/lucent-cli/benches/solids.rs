//! The exact solids' cost per ray: a 4 × 4 grid of one kind of object, closest hits of the
//! same 65,536 rays (from a camera above, aimed into the grid) for each kind, one thread. The
//! triangle cube and the sphere are the comparisons: the exact box is the cube's own shape; a
//! box with a cylinder subtracted is the cost of a combination.
//! Run: `cargo bench -p lucent-cli --bench solids`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lucent::accel::{Ray, TraversalStats};
use lucent::scene::Scene;
use lucent_scene::SceneFile;
use std::hint::black_box;
use std::path::PathBuf;

/// The object table of each kind, centred at the origin with a size of about 1.
const KINDS: [(&str, &str); 9] = [
    (
        "sphere",
        "type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.5",
    ),
    ("cube_triangles", "type = \"cube\"\nscale = 0.4"),
    (
        "box",
        "type = \"box\"\nmin = [-0.4, -0.4, -0.4]\nmax = [0.4, 0.4, 0.4]",
    ),
    (
        "cylinder",
        "type = \"cylinder\"\nbase = [0, -0.5, 0]\ncap = [0, 0.5, 0]\nradius = 0.4",
    ),
    (
        "cone",
        "type = \"cone\"\nbase = [0, -0.5, 0]\ncap = [0, 0.5, 0]\nbase_radius = 0.5\ncap_radius = 0.1",
    ),
    (
        "disc",
        "type = \"disc\"\ncenter = [0, 0, 0]\nnormal = [0, 1, 1]\nradius = 0.5\nhole = 0.2",
    ),
    (
        "torus",
        "type = \"torus\"\nmajor = 0.35\nminor = 0.12\nrotate = [40, 0, 0]",
    ),
    (
        "superellipsoid",
        "type = \"superellipsoid\"\nexponents = [0.3, 0.6]\nscale = 0.45",
    ),
    (
        "box_minus_cylinder",
        "type = \"difference\"\nchildren = [{ type = \"box\", min = [-0.4, -0.4, -0.4], max = [0.4, 0.4, 0.4] }, \
         { type = \"cylinder\", base = [0, -1, 0], cap = [0, 1, 0], radius = 0.2 }]",
    ),
];

fn scene(object: &str) -> Scene {
    let mut text = String::from(
        "[camera]\neye = [0, 6, 8]\nlook_at = [0, 0, 0]\n[[material]]\nname = \"m\"\nkd = 0.5\n",
    );
    for i in 0..16 {
        let (x, z) = ((i % 4) as f32 * 1.5 - 2.25, (i / 4) as f32 * 1.5 - 2.25);
        // A sphere by its centre, every other kind by a placement after its own keys.
        let placed = match object.strip_prefix("type = \"sphere\"\ncenter = [0, 0, 0]") {
            Some(rest) => format!("type = \"sphere\"\ncenter = [{x}, 0, {z}]{rest}"),
            None => format!("{object}\ntranslate = [{x}, 0, {z}]"),
        };
        text += &format!("[[object]]\n{placed}\nmaterial = \"m\"\n");
    }
    let file = SceneFile::parse(PathBuf::from("solids.toml"), PathBuf::new(), text);
    file.and_then(|f| f.build())
        .expect("the scene builds")
        .scene
}

/// Rays from above the grid to points spread over it.
fn rays() -> Vec<Ray> {
    let eye = glam::Vec3::new(0.0, 6.0, 8.0);
    (0..65_536)
        .map(|i| {
            let (u, v) = ((i % 256) as f32 / 255.0, (i / 256) as f32 / 255.0);
            let target = glam::Vec3::new(u * 6.0 - 3.0, 0.0, v * 6.0 - 3.0);
            Ray::new(eye, (target - eye).normalize())
        })
        .collect()
}

fn solids(c: &mut Criterion) {
    let rays = rays();
    let mut group = c.benchmark_group("solids_closest_hit_65536_rays_1_thread");
    group.throughput(Throughput::Elements(rays.len() as u64));
    group.sample_size(20);
    for (name, object) in KINDS {
        let scene = scene(object);
        let hits = rays
            .iter()
            .filter(|r| scene.intersect(r, &mut TraversalStats::default()).is_some())
            .count();
        assert!(hits > 1000, "{name}: {hits} hits");
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut stats = TraversalStats::default();
                for r in &rays {
                    black_box(scene.intersect(r, &mut stats));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, solids);
criterion_main!(benches);
