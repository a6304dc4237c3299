//! Renders that never lose work and spread over machines: interrupt and resume, shards in
//! separate processes, merge refusals, damaged checkpoints, SIGKILL while writing, and the
//! recipes of docs/farm.md run as written.

mod common;

use common::{assert_success, lucent, workspace};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The built-in Whitted scene at `width × height`, as a scene file.
fn small_scene(width: u32, height: u32) -> String {
    let text = std::fs::read_to_string(workspace().join("examples/whitted.toml")).unwrap();
    assert!(text.contains("width = 800") && text.contains("height = 600"));
    text.replace("width = 800", &format!("width = {width}"))
        .replace("height = 600", &format!("height = {height}"))
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Runs `lucent` with `args` in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    lucent().current_dir(dir).args(args).output().unwrap()
}

/// Asserts that lucent refused with a message (exit status 1, no panic) containing `needle`.
fn assert_refused(output: &Output, needle: &str) {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(!err.contains("internal error"), "{err}");
    assert!(err.contains(needle), "expected `{needle}` in: {err}");
}

/// Polls until `path` exists (true) or `child` exits or the deadline passes (false).
fn wait_for_file(path: &Path, child: &mut Child, deadline: Duration) -> bool {
    let start = Instant::now();
    while start.elapsed() < deadline {
        if path.exists() {
            return true;
        }
        if child.try_wait().unwrap().is_some() {
            return path.exists();
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    false
}

#[cfg(unix)]
fn signal(child: &Child, name: &str) {
    let status = Command::new("kill")
        .args([&format!("-{name}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

/// The `lucent.samples` attribute of an EXR image.
fn exr_samples(path: &Path) -> String {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    match image
        .layer_data
        .attributes
        .other
        .get(&Text::new_or_panic("lucent.samples"))
    {
        Some(AttributeValue::Text(t)) => t.to_string(),
        other => panic!("no lucent.samples attribute: {other:?}"),
    }
}

/// The linear pixels of an EXR image, as bits.
fn exr_bits(path: &Path) -> Vec<[u32; 3]> {
    let image = image::open(path).unwrap().to_rgb32f();
    image.pixels().map(|p| p.0.map(f32::to_bits)).collect()
}

/// SIGTERM mid-way leaves a valid partial image and a checkpoint; damaged or stale checkpoints
/// are refused; resuming on another thread count gives the uninterrupted image bit for bit.
#[cfg(unix)]
#[test]
fn an_interrupted_render_resumes_to_the_same_bits() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), small_scene(480, 360)).unwrap();
    let settings = ["--spp", "32", "--seed", "3"];

    let reference = run_in(
        d,
        &[
            &["render", "scene.toml", "-o", "ref.exr", "--threads", "2"][..],
            &settings,
        ]
        .concat(),
    );
    assert_success(&reference);
    assert_eq!(exr_samples(&d.join("ref.exr")), "32");

    // One thread, checkpoints every 0.1 s; stop it as soon as the first one is written.
    let mut child = lucent()
        .current_dir(d)
        .args(["render", "scene.toml", "-o", "out.exr", "--threads", "1"])
        .args(settings)
        .args(["--checkpoint-every", "0.1"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let checkpoint = d.join("out.exr.checkpoint");
    assert!(
        wait_for_file(&checkpoint, &mut child, Duration::from_secs(60)),
        "no periodic checkpoint"
    );
    signal(&child, "TERM");
    let stopped = Instant::now();
    let output = child.wait_with_output().unwrap();
    assert!(
        stopped.elapsed() < Duration::from_secs(2),
        "stops within a second or so"
    );
    assert_eq!(output.status.code(), Some(130), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("lucent render --resume"),
        "{}",
        stderr(&output)
    );
    let partial = exr_samples(&d.join("out.exr"));
    let (least, most) = partial
        .split_once("..")
        .expect("a partial image says MIN..MAX");
    assert!(least.parse::<u32>().unwrap() < most.parse::<u32>().unwrap());
    assert_ne!(exr_bits(&d.join("out.exr")), exr_bits(&d.join("ref.exr")));

    // Damaged copies of the checkpoint, another file, and a changed scene are all refused.
    let bytes = std::fs::read(&checkpoint).unwrap();
    let bad = d.join("bad.checkpoint");
    let resume_bad = || run_in(d, &["render", "--resume", "bad.checkpoint"]);
    std::fs::write(&bad, &bytes[..bytes.len() / 2]).unwrap();
    assert_refused(&resume_bad(), "bad.checkpoint");
    for at in [bytes.len() / 2, bytes.len() * 3 / 4, bytes.len() - 9] {
        let mut flipped = bytes.clone();
        flipped[at] ^= 0x20;
        std::fs::write(&bad, &flipped).unwrap();
        let output = resume_bad();
        assert_refused(&output, "bad.checkpoint");
        let err = stderr(&output);
        assert!(
            err.contains("corrupted") || err.contains("cannot read"),
            "{err}"
        );
    }
    std::fs::copy(d.join("ref.exr"), &bad).unwrap();
    assert_refused(&resume_bad(), "not a lucent partial film or checkpoint");
    std::fs::write(&bad, "not an image").unwrap();
    assert_refused(&resume_bad(), "cannot read the film file");
    let scene = std::fs::read_to_string(d.join("scene.toml")).unwrap();
    std::fs::write(d.join("scene.toml"), format!("{scene}\n# edited\n")).unwrap();
    assert_refused(
        &run_in(d, &["render", "--resume", "out.exr.checkpoint"]),
        "changed since this checkpoint was written",
    );
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    assert!(
        bytes == std::fs::read(&checkpoint).unwrap(),
        "refusals leave the checkpoint alone"
    );

    // Resume on two threads: the uninterrupted image, bit for bit; the checkpoint is gone.
    let resumed = run_in(
        d,
        &["render", "--resume", "out.exr.checkpoint", "--threads", "2"],
    );
    assert_success(&resumed);
    // It continued rather than started over: fewer camera rays than the whole render's.
    let line = String::from_utf8_lossy(&resumed.stdout).into_owned();
    let camera: u64 = line
        .split("(camera ")
        .nth(1)
        .and_then(|rest| rest.split(',').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no camera count in: {line}"));
    assert!(camera > 0 && camera < 480 * 360 * 32, "{line}");
    assert!(
        exr_bits(&d.join("out.exr")) == exr_bits(&d.join("ref.exr")),
        "resumed image differs"
    );
    assert_eq!(exr_samples(&d.join("out.exr")), "32");
    assert!(!checkpoint.exists());
}

/// Three shards rendered by three processes at once merge into the single-process image, bit
/// for bit; `auto/N` takes the index from Kubernetes' or Slurm's variable.
#[test]
fn shards_in_separate_processes_merge_to_the_same_bits() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let size = ["--width", "100", "--height", "70", "--spp", "3"];
    assert_success(&run_in(
        d,
        &[&["render", "-o", "whole.pfm"][..], &size].concat(),
    ));
    assert_success(&run_in(
        d,
        &[&["render", "-o", "whole.png"][..], &size].concat(),
    ));
    assert_success(&run_in(
        d,
        &[&["render", "-o", "whole.exr"][..], &size].concat(),
    ));

    let shard = |spec: &str, out: &str, var: Option<(&str, &str)>| {
        let mut cmd = lucent();
        cmd.current_dir(d)
            .args(["render", "--shard", spec, "-o", out, "--threads", "1"])
            .args(size)
            .env_remove("SLURM_ARRAY_TASK_ID")
            .env_remove("JOB_COMPLETION_INDEX");
        if let Some((k, v)) = var {
            cmd.env(k, v);
        }
        cmd.stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let children = [
        shard("0/3", "p0.exr", None),
        shard("auto/3", "p1.exr", Some(("JOB_COMPLETION_INDEX", "1"))),
        shard("auto/3", "p2.exr", Some(("SLURM_ARRAY_TASK_ID", "2"))),
    ];
    for child in children {
        assert_success(&child.wait_with_output().unwrap());
    }
    assert_success(&run_in(
        d,
        &["merge", "p2.exr", "p0.exr", "p1.exr", "-o", "merged.pfm"],
    ));
    assert_success(&run_in(
        d,
        &["merge", "p0.exr", "p1.exr", "p2.exr", "-o", "merged.png"],
    ));
    let read = |name: &str| std::fs::read(d.join(name)).unwrap();
    assert!(
        read("merged.pfm") == read("whole.pfm"),
        "merged floats differ"
    );
    assert!(
        read("merged.png") == read("whole.png"),
        "merged PNG differs"
    );
    assert_success(&run_in(
        d,
        &["merge", "p1.exr", "p0.exr", "p2.exr", "-o", "merged.exr"],
    ));
    assert!(
        read("merged.exr") == read("whole.exr"),
        "the same image gives the same EXR bytes"
    );

    // Refusals: missing, duplicated, foreign (another seed; another shard count), bad index.
    assert_refused(
        &run_in(d, &["merge", "p0.exr", "p2.exr", "-o", "x.pfm"]),
        "shard 1/3 missing",
    );
    assert_refused(
        &run_in(
            d,
            &[
                "merge", "p0.exr", "p1.exr", "p2.exr", "p1.exr", "-o", "x.pfm",
            ],
        ),
        "shard 1/3 is given twice",
    );
    assert_success(&run_in(
        d,
        &[
            &["render", "--shard", "1/3", "-o", "seed.exr", "--seed", "9"][..],
            &size,
        ]
        .concat(),
    ));
    assert_refused(
        &run_in(d, &["merge", "p0.exr", "seed.exr", "p2.exr", "-o", "x.pfm"]),
        "seed.exr is from another render",
    );
    assert_success(&run_in(
        d,
        &[&["render", "--shard", "1/2", "-o", "half.exr"][..], &size].concat(),
    ));
    assert_refused(
        &run_in(d, &["merge", "p0.exr", "half.exr", "p2.exr", "-o", "x.pfm"]),
        "half.exr is from another render",
    );
    assert_refused(
        &run_in(d, &["merge", "whole.pfm", "-o", "x.pfm"]),
        "whole.pfm",
    );
    // The merged image may not replace a shard (under its own name or another path to it).
    let shard = read("p0.exr");
    for output in ["p0.exr", "./sub/../p0.exr"] {
        std::fs::create_dir_all(d.join("sub")).unwrap();
        assert_refused(
            &run_in(d, &["merge", "p0.exr", "p1.exr", "p2.exr", "-o", output]),
            "p0.exr is one of the partial films being merged",
        );
        assert!(read("p0.exr") == shard, "the shard is kept");
    }
    assert!(!d.join("x.pfm").exists());
    let env_free = lucent()
        .current_dir(d)
        .args(["render", "--shard", "auto/3", "-o", "y.exr"])
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("JOB_COMPLETION_INDEX")
        .output()
        .unwrap();
    assert_refused(
        &env_free,
        "neither $SLURM_ARRAY_TASK_ID nor $JOB_COMPLETION_INDEX is set",
    );
    assert_refused(
        &run_in(d, &["render", "--shard", "3/3", "-o", "y.exr"]),
        "0 ≤ I < N",
    );
    assert_refused(
        &run_in(d, &["render", "--shard", "0/3", "-o", "y.png"]),
        "use -o PART.exr",
    );
}

/// SIGKILL while a checkpoint or the image is being written never leaves a truncated file under
/// the final name: the kill lands as soon as the temporary file appears.
#[cfg(unix)]
#[test]
fn sigkill_while_writing_never_leaves_a_truncated_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let spawn = |args: &[&str]| {
        lucent()
            .current_dir(d)
            .args(["render", "--width", "1600", "--height", "1200"])
            .args(["--integrator", "raycast"])
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap()
    };
    // Kills `child` the moment a file named `name` (or its temporary `name.tmp-PID`) appears,
    // then checks that whatever is under `name` is whole.
    let kill_when_written = |mut child: Child, name: &str, whole: &dyn Fn(&Path)| {
        let fin = d.join(name);
        let tmp = d.join(format!("{name}.tmp-{}", child.id()));
        let start = Instant::now();
        while !(tmp.exists() || fin.exists()) {
            assert!(
                child.try_wait().unwrap().is_none(),
                "{name}: exited before writing"
            );
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "{name}: never written"
            );
            std::thread::sleep(Duration::from_millis(1));
        }
        signal(&child, "KILL");
        child.wait().unwrap();
        eprintln!("{name}: killed while writing: {}", tmp.exists());
        if fin.exists() {
            whole(&fin);
        }
    };

    // A periodic checkpoint: `merge` reads a whole one (checksum and all) and only then
    // refuses its missing samples.
    let checkpoint_is_whole = |path: &Path| {
        let out = run_in(d, &["merge", path.to_str().unwrap(), "-o", "m.pfm"]);
        assert_refused(&out, "is unfinished");
    };
    let child = spawn(&["--spp", "64", "-o", "a.exr", "--checkpoint-every", "0.05"]);
    kill_when_written(child, "a.exr.checkpoint", &checkpoint_is_whole);
    assert!(!d.join("a.exr").exists());

    // The final image, in both formats.
    for name in ["b.exr", "b.png"] {
        let child = spawn(&["--spp", "1", "-o", name]);
        kill_when_written(child, name, &|path| {
            image::open(path).unwrap();
        });
    }
}

/// The block of `docs/farm.md` after the marker line containing `marker`.
fn doc_block(marker: &str) -> String {
    let doc = std::fs::read_to_string(workspace().join("docs/farm.md")).unwrap();
    let at = doc
        .find(marker)
        .unwrap_or_else(|| panic!("no `{marker}` in docs/farm.md"));
    let rest = &doc[at..];
    let open = rest.find("```").unwrap();
    let body = &rest[open..];
    let start = body.find('\n').unwrap() + 1;
    let end = body[start..].find("```").unwrap();
    body[start..start + end].to_string()
}

/// The folder holding the `lucent` binary first on PATH, as the recipes expect.
fn path_with_lucent() -> String {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_lucent"));
    let folder = bin.parent().unwrap().display().to_string();
    format!("{folder}:{}", std::env::var("PATH").unwrap_or_default())
}

/// True when `tool` runs; false (and a note) when it is missing and the run does not require
/// it. `.ci/run` sets LUCENT_REQUIRE_TOOLS=1 after installing them.
fn have(tool: &str) -> bool {
    let ok = Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var("LUCENT_REQUIRE_TOOLS").is_err(),
            "`{tool}` is required (LUCENT_REQUIRE_TOOLS is set) but not installed"
        );
        eprintln!("skipped: `{tool}` is not installed (apt-get install {tool})");
    }
    ok
}

/// The single-process render of `scene.toml` in `d`, as PNG bytes.
fn single_process_png(d: &Path) -> Vec<u8> {
    assert_success(&run_in(d, &["render", "scene.toml", "-o", "single.png"]));
    std::fs::read(d.join("single.png")).unwrap()
}

#[test]
fn the_gnu_parallel_recipe_runs_as_written() {
    if !have("parallel") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), small_scene(96, 64)).unwrap();
    let output = Command::new("bash")
        .args([
            "-euo",
            "pipefail",
            "-c",
            &doc_block("tested: crates/lucent-cli/tests/farm.rs runs this block"),
        ])
        .current_dir(d)
        .env("PATH", path_with_lucent())
        .output()
        .unwrap();
    assert_success(&output);
    assert!(std::fs::read(d.join("image.png")).unwrap() == single_process_png(d));
}

/// The Slurm script, run as Slurm would run it for each array index (its `#SBATCH` lines are
/// comments to bash): one task is stopped by SIGTERM at its "time limit" and run again, which
/// resumes it; a finished task run again does nothing; the parts merge into the one-process
/// image.
#[cfg(unix)]
#[test]
fn the_slurm_script_runs_once_per_array_index_and_resumes_a_stopped_task() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Heavy enough that one shard on one thread takes a few seconds.
    let scene = small_scene(320, 240).replace("samples = 1", "samples = 96");
    assert!(
        scene.contains("samples = 96"),
        "the example sets `samples = 1`"
    );
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    let script = doc_block("runs this script once per array index");
    assert!(script.starts_with("#!/bin/bash\n#SBATCH"));
    assert!(script.contains("\nN=16\n"));
    let script = script.replace("\nN=16\n", "\nN=4\n");
    let task = |index: u32| {
        let mut cmd = Command::new("bash");
        cmd.arg("-c")
            .arg(&script)
            .current_dir(d)
            .env("PATH", path_with_lucent())
            .env("SLURM_ARRAY_TASK_ID", index.to_string())
            .env("SLURM_CPUS_PER_TASK", "1")
            .env_remove("JOB_COMPLETION_INDEX");
        cmd
    };

    // Task 0 runs out of time: SIGTERM (the script `exec`s lucent, so it gets the signal).
    let mut child = task(0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(400));
    assert!(
        child.try_wait().unwrap().is_none(),
        "task 0 finished too soon to be stopped"
    );
    signal(&child, "TERM");
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130), "{}", stderr(&output));
    assert!(d.join("parts/part-0.exr.checkpoint").is_file());
    assert!(
        !d.join("parts/part-0.exr").exists(),
        "an unfinished shard leaves no part"
    );

    // Run again: it resumes; then it is finished, and a third run does nothing.
    assert_success(&task(0).output().unwrap());
    assert!(
        d.join("parts/part-0.exr").is_file() && !d.join("parts/part-0.exr.checkpoint").exists()
    );
    let before = std::fs::read(d.join("parts/part-0.exr")).unwrap();
    assert_success(&task(0).output().unwrap());
    assert!(std::fs::read(d.join("parts/part-0.exr")).unwrap() == before);
    for index in 1..4 {
        let mut cmd = task(index);
        cmd.env("SLURM_CPUS_PER_TASK", "0");
        assert_success(&cmd.output().unwrap());
    }
    let parts = [
        "parts/part-0.exr",
        "parts/part-1.exr",
        "parts/part-2.exr",
        "parts/part-3.exr",
    ];
    assert_success(&run_in(
        d,
        &[&["merge"][..], &parts, &["-o", "image.png"]].concat(),
    ));
    assert!(std::fs::read(d.join("image.png")).unwrap() == single_process_png(d));
}

#[test]
fn the_kubernetes_job_runs_once_per_completion_index() {
    let manifest = doc_block("runs the container's script once per index");
    let field = |key: &str| -> String {
        let line = manifest
            .lines()
            .find(|l| l.trim_start().starts_with(key))
            .unwrap_or_else(|| panic!("no `{key}` in the manifest"));
        line.trim_start()[key.len()..].trim().to_string()
    };
    assert_eq!(field("completionMode:"), "Indexed");
    let completions: usize = field("completions:").parse().unwrap();
    // The container's script: the lines indented under `- |`.
    let lines: Vec<&str> = manifest.lines().collect();
    let start = lines.iter().position(|l| l.trim() == "- |").unwrap() + 1;
    let indent = lines[start].len() - lines[start].trim_start().len();
    let script: String = lines[start..]
        .iter()
        .take_while(|l| l.len() - l.trim_start().len() >= indent && !l.trim().is_empty())
        .map(|l| format!("{}\n", &l[indent..]))
        .collect();
    assert!(
        script.contains(&format!("--shard auto/{completions}")),
        "{script}"
    );

    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let work = d.display().to_string();
    std::fs::write(d.join("scene.toml"), small_scene(96, 64)).unwrap();
    let script = script.replace("/work", &work);
    for index in 0..completions {
        let output = Command::new("sh")
            .arg("-c")
            .arg(&script)
            .current_dir(d)
            .env("PATH", path_with_lucent())
            .env("JOB_COMPLETION_INDEX", index.to_string())
            .env_remove("SLURM_ARRAY_TASK_ID")
            .output()
            .unwrap();
        assert_success(&output);
    }
    let parts: Vec<String> = (0..completions)
        .map(|i| format!("parts/part-{i}.exr"))
        .collect();
    let mut args: Vec<&str> = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["-o", "image.png"]);
    assert_success(&run_in(d, &args));
    assert!(std::fs::read(d.join("image.png")).unwrap() == single_process_png(d));
}

/// What can be known before rendering is checked before rendering: nothing is lost at the end.
#[test]
fn bad_plans_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let small = ["--width", "40", "--height", "30"];
    let run = |args: &[&str]| run_in(d, &[&["render"][..], &small, args].concat());
    assert_refused(
        &run(&["-o", "a.exr", "--checkpoint", "a.exr"]),
        "the same file",
    );
    assert_refused(&run(&["-o", "no/such/folder/a.png"]), "does not exist");
    std::fs::write(d.join("b.png.checkpoint"), "anything").unwrap();
    assert_refused(
        &run(&["-o", "b.png"]),
        "lucent render --resume b.png.checkpoint",
    );
    assert_eq!(
        std::fs::read_to_string(d.join("b.png.checkpoint")).unwrap(),
        "anything"
    );
    // 40×30 pixels are 3×2 tiles of 16: at most 6 shards.
    assert_refused(&run(&["--shard", "0/7", "-o", "c.exr"]), "only 6 tiles");
    assert_success(&run(&["--shard", "5/6", "-o", "c.exr"]));
    // A finished shard given to --resume is named for what it is, from its header alone.
    assert_refused(
        &run_in(d, &["render", "--resume", "c.exr"]),
        "this is shard 5/6's finished partial film, not a checkpoint",
    );

    // A film whose header claims an enormous image is refused before its pixels are read.
    let mut bytes = std::fs::read(d.join("c.exr")).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = bytes.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
    for (i, v) in [0i32, 0, 65535, 65535].iter().enumerate() {
        bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
    std::fs::write(d.join("huge.exr"), &bytes).unwrap();
    assert_refused(
        &run_in(d, &["merge", "huge.exr", "-o", "x.png"]),
        "huge.exr",
    );
    assert_refused(&run_in(d, &["render", "--resume", "huge.exr"]), "huge.exr");

    // One of a size lucent renders, 1024 × 1024 (20 MiB of pixel data), is held to the `film`
    // budget from its header too, with `--limit` on `merge` and on `--resume`.
    for (i, v) in [0i32, 0, 1023, 1023].iter().enumerate() {
        bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
    std::fs::write(d.join("big.exr"), &bytes).unwrap();
    let over = "a 1024×1024 film holds 20 MiB of pixel data, over the budget of 16 MiB (`--limit film=N` raises it)";
    assert_refused(
        &run_in(
            d,
            &["merge", "big.exr", "-o", "x.png", "--limit", "film=16"],
        ),
        over,
    );
    assert_refused(
        &run_in(d, &["render", "--resume", "big.exr", "--limit", "film=16"]),
        over,
    );
    // Within the budget its header passes, and the missing pixels are what is refused.
    let past = run_in(d, &["merge", "big.exr", "-o", "x.png"]);
    assert_eq!(past.status.code(), Some(1));
    assert!(!stderr(&past).contains("budget"), "{}", stderr(&past));
}
