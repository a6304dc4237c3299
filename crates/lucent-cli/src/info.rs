//! `lucent info`: what a scene holds, and what rendering it will need.

use crate::cli::InfoArgs;
use crate::job::Job;
use std::process::ExitCode;

/// Prints counts, bounds, settings, the accelerator and the memory the render will need.
pub fn run(args: &InfoArgs) -> anyhow::Result<ExitCode> {
    let job = Job::load(args.scene.as_deref(), &args.overrides)?;
    let loaded = &job.loaded;
    let scene = &loaded.scene;
    let c = scene.counts();
    let name = job.scene_path.as_ref().map_or_else(
        || "<built-in default scene>".to_string(),
        |p| p.display().to_string(),
    );
    println!("scene:       {name}");
    println!(
        "objects:     {} ({} spheres, {} planes, {} mesh instances of {} meshes)",
        c.objects, c.spheres, c.planes, c.instances, c.meshes
    );
    println!(
        "triangles:   {} ({} stored)",
        c.triangles, c.unique_triangles
    );
    println!("lights:      {}", c.lights);
    println!("materials:   {}", c.materials);
    let b = scene.bounds();
    let infinite = if c.planes > 0 {
        format!(" (plus {} infinite planes)", c.planes)
    } else {
        String::new()
    };
    if b.is_empty() {
        println!("bounds:      empty{infinite}");
    } else {
        let v = |p: glam::Vec3| format!("[{:.4}, {:.4}, {:.4}]", p.x, p.y, p.z);
        println!("bounds:      {} to {}{infinite}", v(b.min), v(b.max));
    }
    let s = &loaded.settings;
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let sampling = match s.sampling {
        lucent::render::Sampling::Uniform => format!("{} spp", s.spp),
        lucent::render::Sampling::Adaptive(a) if a.block > 0 => format!(
            "quadtree of {0}×{0} blocks (threshold {1}, depth {2})",
            1 << a.block,
            a.threshold,
            a.depth
        ),
        lucent::render::Sampling::Adaptive(a) => {
            format!("adaptive (threshold {}, depth {})", a.threshold, a.depth)
        }
    };
    println!(
        "image:       {w}×{h}, {sampling}, integrator {}",
        s.integrator.name()
    );
    let a = scene.accel_report();
    println!(
        "loaded in:   {:.1} ms (files read and scene built, accelerators included)",
        job.load_time.as_secs_f64() * 1e3
    );
    println!(
        "accelerator: {}, built in {:.1} ms: {} nodes, depth {}, {:.2} MB ({:.1} bytes per primitive)",
        a.kind,
        a.build_time.as_secs_f64() * 1e3,
        a.nodes,
        a.depth,
        a.bytes as f64 / 1e6,
        a.bytes as f64 / a.primitives.max(1) as f64
    );
    println!("triangle test: {}", scene.triangle_test().name());
    let m = job.memory();
    let mb = |b: u64| b as f64 / 1e6;
    println!(
        "memory:      about {:.1} MB: scene {:.1} MB (geometry and accelerators), film {:.1} MB, writing files {:.1} MB",
        mb(m.total()),
        mb(m.scene),
        mb(m.film),
        mb(m.files)
    );
    Ok(ExitCode::SUCCESS)
}
