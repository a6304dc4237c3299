//! The inner kernels: ray–box, ray–triangle, and traversal of every structure over the same
//! rays, at three scene sizes; the wide BVH's build. Run: `cargo bench -p lucent-accel --bench kernels`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use lucent_accel::triangle::watertight;
use lucent_accel::{Aabb, AccelKind, Accelerator, Ray, TraversalStats, WideTriangleBvh};
use std::hint::black_box;

/// A deterministic stream of numbers in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn vec(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next())
    }
}

/// `n` small random triangles in the unit cube.
fn triangles(n: usize) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut rng = Rng(1);
    let size = 0.5 / (n as f32).cbrt();
    let mut positions = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = rng.vec();
        for _ in 0..3 {
            positions.push(c + size * (rng.vec() - 0.5));
        }
    }
    let tris = (0..n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    (positions, tris)
}

/// Random rays from inside the unit cube in random directions.
fn rays(n: usize) -> Vec<Ray> {
    let mut rng = Rng(7);
    (0..n)
        .map(|_| Ray::new(rng.vec(), (rng.vec() - 0.5).normalize_or(Vec3::X)))
        .collect()
}

fn box_and_triangle(c: &mut Criterion) {
    let rays = rays(1024);
    let b = Aabb::new(Vec3::splat(0.3), Vec3::splat(0.6));
    let tri = [
        Vec3::new(0.2, 0.2, 0.5),
        Vec3::new(0.8, 0.3, 0.5),
        Vec3::new(0.4, 0.9, 0.5),
    ];
    let mut g = c.benchmark_group("primitive_tests");
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.bench_function("ray_box", |bench| {
        bench.iter(|| {
            rays.iter()
                .filter(|r| b.hit(black_box(r), f32::INFINITY).is_some())
                .count()
        })
    });
    g.bench_function("ray_triangle_watertight", |bench| {
        bench.iter(|| {
            rays.iter()
                .filter(|r| watertight(black_box(r), tri, f32::INFINITY).is_some())
                .count()
        })
    });
    g.finish();
}

fn traversal(c: &mut Criterion) {
    let rays = rays(4096);
    let mut g = c.benchmark_group("closest_hit_traversal");
    g.sample_size(10);
    for n in [1_000usize, 30_000, 300_000] {
        let (positions, tris) = triangles(n);
        let boxes: Vec<Aabb> = tris
            .iter()
            .map(|t| Aabb::from_points(t.map(|i| positions[i as usize])))
            .collect();
        g.throughput(Throughput::Elements(rays.len() as u64));
        for kind in [AccelKind::Octree, AccelKind::Bvh, AccelKind::Wide] {
            let accel = kind.build(&boxes);
            g.bench_with_input(BenchmarkId::new(kind.name(), n), &n, |bench, _| {
                bench.iter(|| {
                    let mut stats = TraversalStats::default();
                    let mut hits = 0;
                    for r in &rays {
                        hits += u32::from(accel.closest_hit(
                            r,
                            f32::INFINITY,
                            &mut stats,
                            |i, t_max| {
                                let v = tris[i as usize].map(|k| positions[k as usize]);
                                match watertight(r, v, *t_max) {
                                    Some(h) => {
                                        *t_max = h.t;
                                        true
                                    }
                                    None => false,
                                }
                            },
                        ));
                    }
                    hits
                })
            });
        }
        let packed = WideTriangleBvh::new(&positions, &tris);
        g.bench_with_input(
            BenchmarkId::new("wide_packed_triangles", n),
            &n,
            |bench, _| {
                bench.iter(|| {
                    let mut stats = TraversalStats::default();
                    rays.iter()
                        .filter(|r| {
                            packed
                                .closest_hit(r, f32::INFINITY, None, &mut stats)
                                .is_some()
                        })
                        .count()
                })
            },
        );
    }
    g.finish();
}

/// The build of the wide BVH over packed triangles (what a mesh costs at load), on one thread.
fn build(c: &mut Criterion) {
    let mut g = c.benchmark_group("wide_triangle_build");
    g.sample_size(10);
    for n in [30_000usize, 300_000] {
        let (positions, tris) = triangles(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |bench, _| {
            bench.iter(|| WideTriangleBvh::new(black_box(&positions), black_box(&tris)))
        });
    }
    g.finish();
}

criterion_group!(benches, box_and_triangle, traversal, build);
criterion_main!(benches);
