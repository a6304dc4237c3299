//! The path tracer with its samples traced eight at a time in SIMD lanes against one at a time,
//! in the same run: Mitsuba's Cornell box (`examples/cornell-box.xml`) at 128×128, 8 samples a
//! pixel, on 1 and 2 threads. The two images are the same bit for bit; only the time differs.
//!
//! Throughput is reported in rays per second.
//! Run: `cargo bench -p lucent-cli --bench path_lanes`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadOptions, SceneFile, Spanned};
use std::path::Path;

fn path_lanes(c: &mut Criterion) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cornell-box.xml");
    let mut file = SceneFile::read_with(&file, &LoadOptions::default()).expect("it reads");
    file.desc.image.width = Spanned::new(0..0, 128);
    file.desc.image.height = Spanned::new(0..0, 128);
    let loaded = file.build().expect("the Cornell box builds");
    let hooks = Hooks::none();
    let mut group = c.benchmark_group("cornell_box_path_128x128_8spp");
    group.sample_size(10);
    for threads in [1, 2] {
        for lanes in [false, true] {
            let settings = RenderSettings {
                threads,
                lanes,
                spp: 8,
                ..loaded.settings
            };
            let scene = &loaded.scene;
            let rays = render(scene, &settings, None, &hooks)
                .unwrap()
                .stats
                .rays
                .total();
            group.throughput(Throughput::Elements(rays));
            let name = format!(
                "{threads}_threads_lanes_{}",
                if lanes { "on" } else { "off" }
            );
            group.bench_function(name, |b| {
                b.iter(|| render(scene, &settings, None, &hooks).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, path_lanes);
criterion_main!(benches);
