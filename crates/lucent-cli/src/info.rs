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
        "objects:     {} ({} spheres, {} planes, {} mesh instances of {} meshes, {} exact solids, {} combinations)",
        c.objects, c.spheres, c.planes, c.instances, c.meshes, c.solids, c.csgs
    );
    println!(
        "triangles:   {} ({} stored)",
        c.triangles, c.unique_triangles
    );
    let e = &scene.emitters;
    let mut extra = Vec::new();
    match e.area.lights.len() {
        0 => {}
        1 => extra.push("1 area light".to_string()),
        n => extra.push(format!("{n} area lights")),
    }
    if e.environment.is_some() {
        extra.push("an environment".to_string());
    }
    let path = matches!(
        loaded.settings.integrator,
        lucent::integrator::Integrator::Path(_) | lucent::integrator::Integrator::Sppm(_)
    );
    if extra.is_empty() || !path {
        println!("lights:      {}", c.lights);
    } else {
        // What the path tracer samples besides the point-like lights (the classic
        // integrators see the environment only where rays miss).
        println!("lights:      {} (and {})", c.lights, extra.join(" and "));
    }
    let photometric: Vec<_> = scene
        .lights
        .iter()
        .filter_map(|l| match l {
            lucent::light::Light::Photometric(p) => Some(p),
            _ => None,
        })
        .collect();
    if !photometric.is_empty() {
        // The profiles' own flux (their tables are in candela), before `intensity` scales it.
        let lumens: f32 = photometric.iter().map(|p| p.profile.total()).sum();
        let kinds: Vec<_> = photometric
            .iter()
            .map(|p| p.profile.goniometry().name())
            .collect();
        println!(
            "photometric: {} ({}), {lumens:.0} lm from their tables",
            photometric.len(),
            kinds.join(", ")
        );
    }
    let images: Vec<_> = scene
        .lights
        .iter()
        .filter_map(|l| match l {
            lucent::light::Light::Image(i) => Some(i),
            _ => None,
        })
        .collect();
    if !images.is_empty() {
        use lucent::light::Mapping;
        let kinds: Vec<String> = images
            .iter()
            .map(|l| {
                let (w, h) = l.image.size();
                let kind = match (l.image.mapping(), l.image.cone()) {
                    (_, Some(_)) => "textured spot",
                    (Mapping::Projection { .. }, None) => "projection",
                    (Mapping::EqualArea, None) => "goniometric, equal-area",
                    (Mapping::LatLong, None) => "goniometric, lat-long",
                };
                format!("{kind} {w}×{h}")
            })
            .collect();
        let flux: f32 = images.iter().map(|l| l.power().luminance()).sum();
        println!(
            "image light: {} ({}), flux {flux:.3} (∫ I dω, as luminance)",
            images.len(),
            kinds.join("; ")
        );
    }
    println!("materials:   {}", c.materials);
    if scene.is_animated() {
        let n = scene.moving_objects();
        let objects = match n {
            1 => "1 object moves".to_string(),
            n => format!("{n} objects move"),
        };
        let camera = if scene.camera_moves() {
            "the camera moves"
        } else {
            "the camera stands still"
        };
        match scene.shutter() {
            Some(s) => println!(
                "motion:      {objects}, {camera} (blurred over the shutter, t = {} to {} s; `--time` picks one instant)",
                // As written (the file's times are single precision).
                s.open() as f32,
                s.close() as f32
            ),
            None => {
                let t = job.overrides.time.unwrap_or(0.0);
                println!(
                    "motion:      {objects}, {camera} (shown at t = {t} s; `--time` picks another instant)"
                );
            }
        }
    } else if let Some(s) = scene.shutter() {
        println!(
            "shutter:     open from t = {} to {} s (nothing moves: no blur)",
            s.open() as f32,
            s.close() as f32
        );
    }
    let b = scene.bounds();
    let infinite = if c.planes > 0 {
        format!(" (plus {} infinite planes)", c.planes)
    } else {
        String::new()
    };
    if b.is_empty() {
        println!("bounds:      empty{infinite}");
    } else {
        // In the file's world (the scene is built relative to a point near its camera).
        let v = |p: glam::Vec3| {
            let p = scene.world_point(p);
            format!("[{:.4}, {:.4}, {:.4}]", p.x, p.y, p.z)
        };
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
    let filter = if s.filter == lucent::film::filter::Filter::default() {
        String::new()
    } else {
        let how = match s.filter_sampling {
            lucent::film::splat::FilterSampling::Splat => "splatted",
            lucent::film::splat::FilterSampling::Importance => "importance-sampled",
        };
        format!(
            ", {} filter of radius {} ({how})",
            s.filter.name(),
            s.filter.radius()
        )
    };
    let limit = s.time_limit.map_or(String::new(), |t| {
        format!(", at most {:.1} s", t.as_secs_f64())
    });
    println!(
        "image:       {w}×{h}, {sampling}{limit}, integrator {}{filter}",
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
