//! `lucent convert`: any scene lucent reads, written as lucent's TOML — the same image when
//! rendered. Mesh and image files are not copied: the TOML names them from its own folder.

use crate::cli::ConvertArgs;
use crate::output::write_atomically;
use anyhow::{Context, bail};
use lucent_scene::{LoadOptions, SceneFile};
use std::io::Write;
use std::process::ExitCode;

/// Reads, builds (to check it and to frame a camera), rebases file names, writes.
pub fn run(args: &ConvertArgs) -> anyhow::Result<ExitCode> {
    if lucent_scene::mesh_file::extension(&args.output).as_deref() != Some("toml") {
        bail!(
            "{}: the converted scene is written as TOML: name it .toml",
            args.output.display()
        );
    }
    crate::output::check_writable(&args.output)?;
    let options = LoadOptions {
        sandbox: args.sandbox,
        limits: crate::cli::limits_of(&args.limits),
        image_size: None,
    };
    let mut file = SceneFile::read_with(&args.input, &options)?;
    let framing_warning = crate::job::frame(&mut file, &args.framing);
    let mut loaded = file.build()?;
    loaded.warnings.extend(framing_warning);
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let to_dir = match args.output.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    file.rebase(&to_dir)
        .context("cannot name the scene's files from the output's folder")?;
    let text = file.to_toml(&loaded)?;
    // What TOML cannot say (a POV-Ray scene's negative colours) is refused here, not written
    // as a file lucent would then refuse to read.
    let base = args
        .output
        .parent()
        .map_or_else(std::path::PathBuf::new, std::path::Path::to_path_buf);
    if let Err(e) = SceneFile::parse(args.output.clone(), base, text.clone()) {
        bail!(
            "{}: the scene has no TOML form lucent can read back: {}",
            args.input.display(),
            e.message
        );
    }
    write_atomically(&args.output, |out| {
        writeln!(
            out,
            "# Converted by lucent {} from {}",
            env!("CARGO_PKG_VERSION"),
            args.input.display()
        )?;
        out.write_all(text.as_bytes())?;
        Ok(())
    })?;
    println!(
        "{}: {} objects, {} materials, {} lights",
        args.output.display(),
        file.desc.objects.len(),
        file.desc.materials.len(),
        file.desc.lights.len()
    );
    Ok(ExitCode::SUCCESS)
}
