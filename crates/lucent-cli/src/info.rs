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
        "objects:     {} ({} spheres, {} planes, {} meshes)",
        c.objects, c.spheres, c.planes, c.meshes
    );
    println!("triangles:   {}", c.triangles);
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
    println!(
        "accelerator: {} ({} triangle test)",
        scene.accelerator(),
        scene.triangle_test().name()
    );
    Ok(ExitCode::SUCCESS)
}
