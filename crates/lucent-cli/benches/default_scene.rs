//! The built-in default scene (Whitted's picture) at 800×600, 1 spp, on 1 and 2 threads.
//!
//! Throughput is reported in rays (camera, shadow, reflected and refracted) per second.
//! Run: `cargo bench -p lucent-cli --bench default_scene`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lucent::render::{Hooks, render};
use lucent_scene::SceneFile;
use std::sync::atomic::AtomicBool;

fn default_scene(c: &mut Criterion) {
    let loaded = SceneFile::default_scene()
        .build()
        .expect("the default scene builds");
    let cancel = AtomicBool::new(false);
    let hooks = Hooks {
        cancel: &cancel,
        progress: &|_, _| {},
        checkpoint: None,
    };
    let mut group = c.benchmark_group("default_scene_800x600_1spp");
    group.sample_size(20);
    for threads in [1, 2] {
        let settings = lucent::render::RenderSettings {
            threads,
            ..loaded.settings
        };
        let rays = render(&loaded.scene, &settings, None, &hooks)
            .unwrap()
            .stats
            .rays
            .total();
        group.throughput(Throughput::Elements(rays));
        group.bench_function(format!("{threads}_threads"), |b| {
            b.iter(|| render(&loaded.scene, &settings, None, &hooks).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, default_scene);
criterion_main!(benches);
