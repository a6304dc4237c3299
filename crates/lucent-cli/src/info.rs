//! `lucent info`: what a scene holds.

use crate::cli::InfoArgs;
use crate::render::read_scene;
use std::process::ExitCode;

/// Prints counts, bounds and settings of the scene.
pub fn run(args: &InfoArgs) -> anyhow::Result<ExitCode> {
    let file = read_scene(args.scene.as_deref())?;
    let loaded = file.build()?;
    let scene = &loaded.scene;
    let c = scene.counts();
    println!("scene:       {}", file.path.display());
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
    println!(
        "image:       {}×{}, {} spp, integrator {}",
        scene.camera.width(),
        scene.camera.height(),
        s.spp,
        s.integrator.name()
    );
    let a = scene.accel_report();
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
    Ok(ExitCode::SUCCESS)
}
