//! `lucent explain`: the ray tree of one pixel, as the lecture describes it — every camera,
//! shadow, reflected and refracted ray, what it hit, its weight and what it adds to the pixel —
//! printed, and drawn as an SVG tree (see `docs/debug.md`).

use crate::cli::ExplainArgs;
use crate::job::Job;
use crate::output::write_atomically;
use anyhow::Context;
use lucent::Rgb;
use lucent::integrator::explain::{ExplainError, ExplainedSample, explain_pixel};
use lucent::integrator::record::{Cut, RayKind, RayNode};
use std::fmt::Write as _;
use std::io::Write as _;
use std::process::ExitCode;

/// Traces the pixel's samples with recording on; prints and draws their trees.
pub fn run(args: &ExplainArgs) -> anyhow::Result<ExitCode> {
    let job = Job::load(args.scene.as_deref(), &args.overrides)?;
    let scene = &job.loaded.scene;
    let s = &job.loaded.settings;
    if let Some(svg) = &args.svg {
        crate::output::check_writable(svg)?;
    }
    let explained = explain_pixel(scene, s, args.pixel, args.sample).map_err(|e| {
        let (prefix, hint) = match e {
            ExplainError::NotWhitted(_) => ("lucent ", " (add --integrator whitted)"),
            ExplainError::NotUniform => ("lucent ", " (add --aa uniform)"),
            ExplainError::TooManySamples(_) => ("", ": pick one with --sample K"),
            _ => ("", ""),
        };
        anyhow::anyhow!("{prefix}{e}{hint}")
    })?;
    let (x, y) = args.pixel;
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let mut out = String::new();
    let name = job.scene_path.as_ref().map_or_else(
        || "the built-in scene".to_string(),
        |p| p.display().to_string(),
    );
    writeln!(
        out,
        "pixel {x},{y} of {name} ({w}×{h}), {} sample(s)",
        s.spp
    )?;
    let mut trees = Vec::new();
    let (mut value, mut sum) = (Rgb::BLACK, Rgb::BLACK);
    let mut finite = 0u32;
    for ExplainedSample {
        sample,
        through,
        radiance,
        root,
    } in explained
    {
        writeln!(
            out,
            "\nsample {sample}, through ({:.3}, {:.3}):",
            through.0, through.1
        )?;
        print_node(&mut out, &root, 1, scene)?;
        writeln!(out, "  radiance {}", rgb(radiance))?;
        if radiance.is_finite() {
            value += radiance;
            sum += root
                .walk()
                .iter()
                .map(|n| n.contribution())
                .fold(Rgb::BLACK, |a, b| a + b);
            finite += 1;
        } else {
            writeln!(out, "  (NaN or infinite: the film leaves this sample out)")?;
        }
        trees.push(root);
    }
    let n = finite.max(1) as f32;
    writeln!(out, "\nsum of contributions: {}", exact(sum * (1.0 / n)))?;
    // One sample chosen: its own value, not the pixel's.
    let label = if args.sample.is_some() {
        "sample value:         "
    } else {
        "pixel value:          "
    };
    writeln!(out, "{label}{}", exact(value * (1.0 / n)))?;
    print!("{out}");
    if let Some(path) = &args.svg {
        let svg = draw(&trees);
        write_atomically(path, |f| Ok(f.write_all(svg.as_bytes())?))
            .with_context(|| format!("cannot write {}", path.display()))?;
        println!("drew the tree to {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}

fn rgb(c: Rgb) -> String {
    format!("({:.4}, {:.4}, {:.4})", c.r, c.g, c.b)
}

fn exact(c: Rgb) -> String {
    format!("{:.9} {:.9} {:.9}", c.r, c.g, c.b)
}

fn v3(v: glam::Vec3) -> String {
    format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z)
}

/// The scene's point `p` where the file has it (the scene is built relative to a point near
/// its camera).
fn at(p: glam::Vec3, scene: &lucent::scene::Scene) -> String {
    let p = scene.world_point(p);
    format!("({:.3}, {:.3}, {:.3})", p.x, p.y, p.z)
}

fn print_node(
    out: &mut String,
    node: &RayNode,
    indent: usize,
    scene: &lucent::scene::Scene,
) -> std::fmt::Result {
    let pad = "  ".repeat(indent);
    writeln!(
        out,
        "{pad}{} ray from {} along {}, weight {}",
        node.kind.name(),
        at(node.origin, scene),
        v3(node.dir),
        rgb(node.weight)
    )?;
    match &node.hit {
        None => writeln!(out, "{pad}  hits nothing: background {}", rgb(node.local))?,
        Some(hit) => {
            writeln!(
                out,
                "{pad}  hits object #{} (material #{}) at t = {:.4}, {} its surface at {}",
                hit.object,
                hit.material,
                hit.t,
                if hit.entering { "entering" } else { "leaving" },
                at(hit.point, scene)
            )?;
            for l in &node.lights {
                if l.shadow.is_black() {
                    writeln!(out, "{pad}  shadow ray to light {}: blocked", l.index)?;
                } else {
                    writeln!(
                        out,
                        "{pad}  shadow ray to light {}: S = {}, adds {}",
                        l.index,
                        rgb(l.shadow),
                        rgb(l.term)
                    )?;
                }
            }
            writeln!(out, "{pad}  local colour {}", rgb(node.local))?;
        }
    }
    writeln!(
        out,
        "{pad}  contributes {} to the pixel",
        rgb(node.contribution())
    )?;
    for cut in &node.cuts {
        let text = match cut {
            Cut::TotalInternalReflection => {
                "total internal reflection: no refracted ray, kt joins kr".to_string()
            }
            Cut::Depth => "max_depth reached: no reflected or refracted ray".to_string(),
            Cut::Weight(k, w) => format!(
                "{} ray not traced: its weight {} is under min_weight",
                k.name(),
                rgb(*w)
            ),
            Cut::Budget(k) => format!(
                "{} ray not traced: the pixel's budget of secondary rays is spent",
                k.name()
            ),
        };
        writeln!(out, "{pad}  {text}")?;
    }
    for c in &node.children {
        print_node(out, c, indent + 1, scene)?;
    }
    Ok(())
}

/// Node boxes on a grid: one column per leaf, one row per depth.
const CELL_W: f32 = 190.0;
const CELL_H: f32 = 110.0;

/// The trees as one SVG: each ray a box (kind, what it hit, its contribution), joined to its
/// children by lines coloured by kind; cuts and total internal reflection as notes.
fn draw(trees: &[RayNode]) -> String {
    let mut boxes = String::new();
    let mut next_column = 0.0f32;
    let mut depth_max = 0;
    for tree in trees {
        place(tree, 0, &mut next_column, &mut depth_max, &mut boxes);
        next_column += 0.5;
    }
    let width = next_column * CELL_W + 20.0;
    let height = (depth_max + 1) as f32 * CELL_H + 40.0;
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{boxes}</svg>\n"
    )
}

/// Draws `node` and its subtree; returns the x of its box's centre.
fn place(
    node: &RayNode,
    depth: usize,
    column: &mut f32,
    depth_max: &mut usize,
    out: &mut String,
) -> f32 {
    *depth_max = (*depth_max).max(depth);
    let y = 20.0 + depth as f32 * CELL_H;
    let centres: Vec<(f32, RayKind)> = node
        .children
        .iter()
        .map(|c| (place(c, depth + 1, column, depth_max, out), c.kind))
        .collect();
    let x = if centres.is_empty() {
        let x = 10.0 + (*column + 0.5) * CELL_W;
        *column += 1.0;
        x
    } else {
        centres.iter().map(|c| c.0).sum::<f32>() / centres.len() as f32
    };
    for (cx, kind) in centres {
        let colour = match kind {
            RayKind::Reflected => "#1f5fbf",
            RayKind::Refracted => "#1f9f4f",
            RayKind::Camera => "#000",
        };
        let _ = writeln!(
            out,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{cx:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"2\"/>",
            y + 70.0,
            y + CELL_H
        );
    }
    let what = match &node.hit {
        None => "misses: background".to_string(),
        Some(h) => format!("object #{} at t {:.3}", h.object, h.t),
    };
    let lights = node
        .lights
        .iter()
        .map(|l| if l.shadow.is_black() { "■" } else { "☀" })
        .collect::<String>();
    let mut notes: Vec<String> = node
        .cuts
        .iter()
        .map(|c| match c {
            Cut::TotalInternalReflection => "TIR".to_string(),
            Cut::Depth => "depth limit".to_string(),
            Cut::Weight(k, _) => format!("{} cut: weight", k.name()),
            Cut::Budget(k) => format!("{} cut: budget", k.name()),
        })
        .collect();
    if notes.is_empty() {
        notes.push(String::new());
    }
    let tir = node.cuts.contains(&Cut::TotalInternalReflection);
    let c = node.contribution();
    let _ = writeln!(
        out,
        "<g><rect x=\"{:.1}\" y=\"{y:.1}\" width=\"{:.1}\" height=\"70\" rx=\"6\" fill=\"#f6f6f6\" stroke=\"{}\"/>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" font-weight=\"bold\">{} ray</text>\n\
         <text x=\"{:.1}\" y=\"{:.1}\">{what}</text>\n\
         <text x=\"{:.1}\" y=\"{:.1}\">lights {lights} adds ({:.3}, {:.3}, {:.3})</text>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" fill=\"#b00\">{}</text></g>",
        x - CELL_W / 2.0 + 6.0,
        CELL_W - 12.0,
        if tir { "#b00" } else { "#888" },
        x - CELL_W / 2.0 + 12.0,
        y + 15.0,
        node.kind.name(),
        x - CELL_W / 2.0 + 12.0,
        y + 31.0,
        x - CELL_W / 2.0 + 12.0,
        y + 47.0,
        c.r,
        c.g,
        c.b,
        x - CELL_W / 2.0 + 12.0,
        y + 63.0,
        notes.join(", ")
    );
    x
}
