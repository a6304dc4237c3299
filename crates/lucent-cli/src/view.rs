//! `lucent view`: load the scene as `render` does, then hand it to the viewer's window.
//!
//! Built without the `viewer` feature, the command still parses and says so.

use crate::cli::ViewArgs;
use std::process::ExitCode;

/// Runs `lucent view`.
#[cfg(feature = "viewer")]
pub fn run(args: &ViewArgs) -> anyhow::Result<ExitCode> {
    use crate::job::Job;
    use lucent_view::{Options, Pose};

    let job = Job::load(args.scene.as_deref(), &args.overrides())?;
    let loaded = job.loaded;
    let camera = &loaded.scene.camera;
    // The viewer moves the camera in the built scene's coordinates.
    let origin = loaded.scene.origin();
    let pose = Pose {
        eye: (job.camera.eye.0 - origin).as_vec3(),
        look_at: (job.camera.look_at.0 - origin).as_vec3(),
        up: job.camera.up.0,
        fov_degrees: job.camera.fov.0,
        lens: camera.lens(),
    };
    let options = Options {
        mode: args.mode,
        threads: usize::from(args.threads),
        scale: args.scale,
        size: args.size.unwrap_or((camera.width(), camera.height())),
        refresh: args.refresh,
        exit_after: args.exit_after,
        seed: loaded.settings.seed,
        name: job.scene_path.as_deref().map_or_else(
            || "default scene".to_string(),
            |p| {
                p.file_name()
                    .unwrap_or(p.as_os_str())
                    .to_string_lossy()
                    .into_owned()
            },
        ),
    };
    eprintln!("{}", lucent_view::HELP);
    let summary = lucent_view::run(loaded.scene, pose, loaded.settings.integrator, &options)?;
    println!("lucent view: {summary}");
    Ok(ExitCode::SUCCESS)
}

/// Runs `lucent view` in a binary built without the viewer: says so.
#[cfg(not(feature = "viewer"))]
pub fn run(args: &ViewArgs) -> anyhow::Result<ExitCode> {
    let _ = args;
    anyhow::bail!(
        "this lucent was built without the viewer: build it with the `viewer` feature (on by default), e.g. `cargo build --release -p lucent-cli`"
    )
}
