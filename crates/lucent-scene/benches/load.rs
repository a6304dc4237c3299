//! Loading speed of the mesh formats, in bytes of file per second: the binary PLY stored as
//! triangle strips (igea) and the largest OBJ (ogre) from `../shared/data`, parsed from memory
//! and read from disk. Run: `cargo bench -p lucent-scene --bench load`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lucent_scene::mesh_file::read_mesh;
use lucent_scene::{data_dir, obj, ply};
use std::hint::black_box;

fn load(c: &mut Criterion) {
    let meshes = data_dir().join("meshes");
    if !meshes.is_dir() {
        eprintln!("skipping: {} is not here", meshes.display());
        return;
    }
    let mut group = c.benchmark_group("load");
    group.sample_size(20);
    for name in ["igea.ply", "ogre.obj"] {
        let path = meshes.join(name);
        let bytes = std::fs::read(&path).unwrap();
        group.throughput(Throughput::Bytes(bytes.len() as u64));
        group.bench_function(format!("parse/{name}"), |b| {
            b.iter(|| {
                let triangles = if name.ends_with(".ply") {
                    ply::parse_ply(black_box(&bytes), &path)
                        .unwrap()
                        .triangles
                        .len()
                } else {
                    let file = obj::parse_obj(black_box(&bytes), &path).unwrap();
                    file.mesh(None).unwrap().triangles.len()
                };
                black_box(triangles)
            })
        });
        group.bench_function(format!("read/{name}"), |b| {
            b.iter(|| black_box(read_mesh(&path).unwrap().triangles.len()))
        });
    }
    group.finish();
}

criterion_group!(benches, load);
criterion_main!(benches);
