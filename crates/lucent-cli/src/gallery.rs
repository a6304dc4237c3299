//! `lucent gallery OUT_DIR`: the lecture's concepts, rendered — each image made by one
//! `lucent render` command, which the gallery runs as it is (a process each) and writes down
//! beside the image in `OUT_DIR/gallery.md`. The scenes it needs besides the built-in one are
//! written to `OUT_DIR/scenes/`.

use crate::cli::GalleryArgs;
use anyhow::{Context, bail};
use std::fmt::Write as _;
use std::process::{Command, ExitCode};

/// A glass ball close to a checkered wall: the wall seen through it, upside down.
const REFRACTION: &str = r#"# A glass ball in front of a checkered wall: refraction turns the wall upside down.
[image]
width = 800
height = 600
[camera]
eye = [0, 1, 5]
look_at = [0, 1, 0]
fov = 40
[world]
background = [0.15, 0.35, 0.85]
ambient = 0.2
[[material]]
name = "checks"
ka = 0.4
kd = { checker = { even = [0.9, 0.9, 0.9], odd = [0.1, 0.1, 0.6], size = 0.5 } }
[[material]]
name = "glass"
ks = 0.5
shininess = 200
kr = 0.05
kt = 0.92
ior = 1.5
[[light]]
type = "point"
position = [3, 6, 8]
intensity = 0.9
[[object]]
type = "plane"
point = [0, 0, -3]
normal = [0, 0, 1]
material = "checks"
[[object]]
type = "plane"
point = [0, 0, 0]
normal = [0, 1, 0]
material = "checks"
[[object]]
type = "sphere"
center = [0, 1, 1]
radius = 1
material = "glass"
"#;

/// Looking up from under a glass surface: Snell's window, total internal reflection around it.
const TIR: &str = r#"# From under a glass surface, looking up: the sky through Snell's window (rays within 41.8
# degrees of the normal leave the glass), and around it the floor reflected by total internal
# reflection.
[image]
width = 800
height = 600
[camera]
eye = [0, -1, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov = 120
[world]
background = [0.15, 0.35, 0.85]
ambient = 0.3
[[material]]
name = "glass"
kt = 0.95
kr = 0.02
ior = 1.5
[[material]]
name = "floor"
ka = 0.5
kd = { checker = { even = [0.85, 0.1, 0.05], odd = [0.95, 0.8, 0.1], size = 1.0 } }
[[light]]
type = "directional"
direction = [0.3, -1, 0.2]
intensity = 0.7
[[object]]
type = "plane"
point = [0, 0, 0]
normal = [0, 1, 0]
material = "glass"
[[object]]
type = "plane"
point = [0, -3, 0]
normal = [0, 1, 0]
material = "floor"
"#;

/// A field of balls over a floor: work for the accelerators.
fn sphere_field() -> String {
    let mut s = String::from(
        "# 400 balls on a grid over a floor: work for the accelerators' cost maps.\n\
         [image]\nwidth = 800\nheight = 600\n[camera]\neye = [0, 6, 14]\nlook_at = [0, 0, 0]\nfov = 45\n\
         [world]\nbackground = [0.15, 0.35, 0.85]\nambient = 0.2\n\
         [[material]]\nname = \"white\"\nka = 0.3\nkd = 0.7\n\
         [[material]]\nname = \"floor\"\nka = 0.3\nkd = 0.5\n\
         [[light]]\ntype = \"point\"\nposition = [5, 10, 8]\n\
         [[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"floor\"\n",
    );
    for i in 0..20 {
        for j in 0..20 {
            let (x, z) = (i as f32 - 9.5, j as f32 - 12.0);
            let r = 0.2 + 0.15 * (((i * 7 + j * 13) % 5) as f32 / 4.0);
            let _ = write!(
                s,
                "[[object]]\ntype = \"sphere\"\ncenter = [{x}, {r}, {z}]\nradius = {r}\nmaterial = \"white\"\n"
            );
        }
    }
    s
}

/// One image: its file, what it shows, the scene (`None`: the built-in one) and the flags.
struct Shot {
    name: &'static str,
    caption: &'static str,
    /// The scene file under `scenes/`, or the built-in scene.
    scene: Option<&'static str>,
    flags: &'static [&'static str],
}

const SHOTS: &[Shot] = &[
    Shot {
        name: "raycast",
        caption: "Ray casting (Appel 1968): one ray per pixel, the nearest surface, its flat diffuse colour. No light, no shadow, no reflection: the mirror and the glass, which have almost no diffuse colour, show black.",
        scene: None,
        flags: &["--integrator", "raycast"],
    },
    Shot {
        name: "whitted",
        caption: "Whitted ray tracing (1980): local shading, shadow rays to each light, reflected and refracted rays.",
        scene: None,
        flags: &[],
    },
    Shot {
        name: "no-shadows",
        caption: "The same without shadow rays: every light reaches every point that faces it.",
        scene: None,
        flags: &["--no-shadows"],
    },
    Shot {
        name: "depth-0",
        caption: "Recursion depth 0: no reflected or refracted rays; the mirror and the glass show only their own shading.",
        scene: None,
        flags: &["--max-depth", "0"],
    },
    Shot {
        name: "depth-1",
        caption: "Depth 1: one bounce. The mirror reflects the scene, but the glass, whose rays must pass two surfaces, is still dark inside.",
        scene: None,
        flags: &["--max-depth", "1"],
    },
    Shot {
        name: "depth-2",
        caption: "Depth 2: rays now pass through the glass ball.",
        scene: None,
        flags: &["--max-depth", "2"],
    },
    Shot {
        name: "depth-5",
        caption: "Depth 5: reflections of refractions; little changes beyond.",
        scene: None,
        flags: &["--max-depth", "5"],
    },
    Shot {
        name: "refraction",
        caption: "Refraction by Snell's law: the checkered wall seen through a glass ball (ior 1.5), upside down.",
        scene: Some("refraction.toml"),
        flags: &[],
    },
    Shot {
        name: "tir",
        caption: "Total internal reflection: from under a glass surface, the sky through Snell's window (within 41.8° of the normal) and the floor mirrored around it.",
        scene: Some("tir.toml"),
        flags: &[],
    },
    Shot {
        name: "cost-brute",
        caption: "Cost map, brute force: every ray tests every one of the 400 balls — one flat colour.",
        scene: Some("sphere-field.toml"),
        flags: &["--integrator", "debug:cost", "--accel", "brute"],
    },
    Shot {
        name: "cost-bounds",
        caption: "Cost map, bounding volumes: a box test per object, the ball only when its box is hit — as many tests, each cheaper.",
        scene: Some("sphere-field.toml"),
        flags: &["--integrator", "debug:cost", "--accel", "bounds"],
    },
    Shot {
        name: "cost-octree",
        caption: "Cost map, octree: rays visit cells front to back and stop at the first hit.",
        scene: Some("sphere-field.toml"),
        flags: &["--integrator", "debug:cost", "--accel", "octree"],
    },
    Shot {
        name: "cost-bvh",
        caption: "Cost map, SAH BVH: work concentrates on silhouettes and rays that graze many balls.",
        scene: Some("sphere-field.toml"),
        flags: &["--integrator", "debug:cost", "--accel", "bvh"],
    },
    Shot {
        name: "cost-wide",
        caption: "Cost map, 8-wide BVH (the default): eight boxes per SIMD test, fewer nodes per ray.",
        scene: Some("sphere-field.toml"),
        flags: &["--integrator", "debug:cost", "--accel", "wide"],
    },
    Shot {
        name: "uniform-1",
        caption: "One ray through each pixel's centre: jagged edges, and the checks alias into moiré near the horizon.",
        scene: None,
        flags: &[],
    },
    Shot {
        name: "uniform-16",
        caption: "16 jittered rays per pixel: smooth, at 16 times the cost everywhere.",
        scene: None,
        flags: &["--spp", "16"],
    },
    Shot {
        name: "adaptive",
        caption: "Adaptive supersampling (Whitted 1980): rays at pixel corners, split where they differ — as smooth, for under a quarter of the rays.",
        scene: None,
        flags: &["--aa", "adaptive", "--density-map", "adaptive-density.png"],
    },
    Shot {
        name: "adaptive-density",
        caption: "Where adaptive sampling put its rays (black: 4 corners; white: split to the depth limit): edges, shadows, reflections and the checks.",
        scene: None,
        flags: &[],
    },
    Shot {
        name: "normals",
        caption: "A debug view: the surface normals as colours.",
        scene: None,
        flags: &["--integrator", "debug:normals"],
    },
    Shot {
        name: "cbox-whitted",
        caption: "The critique of Whitted ray tracing: the Cornell box under Whitted. Its area light becomes a point light — hard shadows — and light does not bounce from wall to wall: the ceiling stays black and no colour bleeds.",
        scene: Some("cornell-box.xml"),
        flags: &["--integrator", "whitted"],
    },
    Shot {
        name: "cbox-path",
        caption: "The answer, path tracing with next-event estimation and MIS: the area light sampled as the rectangle it is gives soft shadows, diffuse interreflection lights the ceiling, and the red and green walls bleed onto the boxes.",
        scene: Some("cornell-box.xml"),
        flags: &["--integrator", "path", "--spp", "64"],
    },
];

/// Writes the scenes, renders every shot, and writes `gallery.md`.
pub fn run(args: &GalleryArgs) -> anyhow::Result<ExitCode> {
    let out = &args.output;
    let scenes = out.join("scenes");
    std::fs::create_dir_all(&scenes)
        .with_context(|| format!("cannot create {}", scenes.display()))?;
    for (name, text) in [
        ("refraction", REFRACTION.to_string()),
        ("tir", TIR.to_string()),
        ("sphere-field", sphere_field()),
    ] {
        let path = scenes.join(format!("{name}.toml"));
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    // Mitsuba's Cornell box, as the examples ship it.
    {
        let path = scenes.join("cornell-box.xml");
        let text = include_str!("../../../examples/cornell-box.xml");
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let exe = std::env::current_exe().context("cannot find the lucent program")?;
    let size = [
        "--width".to_string(),
        args.width.to_string(),
        "--height".to_string(),
        args.height.to_string(),
    ];
    let mut index = String::from(
        "# The lecture, rendered\n\nMade by `lucent gallery`; each image with the command that made it.\n",
    );
    for shot in SHOTS {
        let file = format!("{}.png", shot.name);
        let mut argv: Vec<String> = vec!["render".into()];
        if let Some(scene) = shot.scene {
            argv.push(format!("scenes/{scene}"));
        }
        argv.extend(shot.flags.iter().map(|f| f.to_string()));
        // The density map is written by the render before it; nothing to run for it.
        let written_by_another = SHOTS.iter().any(|s| s.flags.contains(&file.as_str()));
        if !written_by_another {
            argv.extend(["-o".to_string(), file.clone()]);
            argv.extend(size.iter().cloned());
            eprintln!("lucent {}", argv.join(" "));
            let status = Command::new(&exe)
                .args(&argv)
                .current_dir(out)
                .stdout(std::process::Stdio::null())
                .status()
                .context("cannot run lucent")?;
            if !status.success() {
                bail!("`lucent {}` failed", argv.join(" "));
            }
        }
        let command = if written_by_another {
            "(written by the command above)".to_string()
        } else {
            format!("`lucent {}`", argv.join(" "))
        };
        let _ = write!(
            index,
            "\n## {}\n\n![{}]({file})\n\n{}\n\n{command}\n",
            shot.name, shot.caption, shot.caption
        );
    }
    let path = out.join("gallery.md");
    std::fs::write(&path, index).with_context(|| format!("cannot write {}", path.display()))?;
    println!("{}: {} images and gallery.md", out.display(), SHOTS.len());
    Ok(ExitCode::SUCCESS)
}
