//! The sweep's scene generator: a seeded splitmix64 stream that writes lucent TOML scenes with
//! every section and key of `docs/scene-format.md`, each numeric value drawn from ordinary
//! values and from extremes the format accepts (0, f32 subnormals, 1e-30, 1e20, 3e38,
//! `f32::MAX`, negatives where allowed, far positions).
//!
//! A scene is a pure function of its seed: the `[render]` table is drawn from a second stream
//! keyed by the integrator, so the three integrators render the same scene. The values and
//! textures are in `values.rs`, the materials in `materials.rs`.

use crate::materials::{MaterialInfo, materials};
use crate::values::{EXTREME, Gen, SUBNORMAL, SplitMix64, num, vec3};
use std::fmt::Write;

/// The scene of `seed` for `integrator` (`"whitted"`, `"path"` or `"sppm"`): the image,
/// camera, world, materials, lights and objects depend on `seed` only.
pub fn scene(seed: u64, integrator: &str) -> String {
    let mut g = Gen {
        rng: SplitMix64::new(seed),
        wild: 0.0,
    };
    g.wild = g.rng.pick(&[0.02, 0.1, 0.25, 0.5]);
    let mut head = String::new();
    let (w, h) = (g.rng.pick(&[8, 8, 8, 1, 3]), g.rng.pick(&[8, 8, 8, 1, 5]));
    let spp = 1 + g.rng.below(4);
    let _ = writeln!(
        head,
        "[image]\nwidth = {w}\nheight = {h}\nsamples = {spp}\n"
    );
    let aperture = camera(&mut g, &mut head);
    world(&mut g, &mut head);
    let mut tail = String::new();
    let materials = materials(&mut g, &mut tail);
    lights(&mut g, &mut tail);
    objects(&mut g, &mut tail, &materials);

    let tag = integrator.bytes().fold(0u64, |h, b| h * 31 + u64::from(b));
    let mut r = Gen {
        rng: SplitMix64::new(seed ^ tag.wrapping_mul(0x2545_f491_4f6c_dd1d)),
        wild: g.wild,
    };
    let render = render(&mut r, integrator, aperture);
    format!("{head}{render}\n{tail}")
}

/// `[camera]`; true when it has a lens.
fn camera(g: &mut Gen, out: &mut String) -> bool {
    // A camera whose eye and look_at are more than about 1.8e19 apart (or less than about
    // 1e-19) is refused: the square of their distance overflows (underflows) in f32. Most
    // cameras look at the scene from near by, so that most scenes render.
    let ordinary = g.rng.chance(0.8);
    let (eye, look_at) = if ordinary {
        let eye = [g.near() * 0.3, 1.0 + g.near() * 0.3, 6.0];
        let look = [g.near() * 0.2, g.near() * 0.2, 0.0];
        (vec3(eye), vec3(look))
    } else {
        (g.vector(), g.vector())
    };
    let _ = writeln!(out, "[camera]\neye = {eye}\nlook_at = {look_at}");
    if g.rng.chance(0.3) {
        let _ = writeln!(out, "up = {}", g.direction());
    }
    if g.rng.chance(0.6) {
        let fov = g.from(
            &[20.0, 38.0, 45.0, 60.0, 90.0],
            &[
                SUBNORMAL, 1e-30, 1e-7, 1e-3, 170.0, 179.0, 179.99, 179.99998,
            ],
        );
        let _ = writeln!(out, "fov = {}", num(fov));
    }
    let lens = g.rng.chance(0.3);
    if lens {
        let aperture = g.from(
            &[0.0, 0.05, 0.2],
            &[0.0, SUBNORMAL, 1e-30, 1e-6, 1.0, 1e10, 1e30, 3e38, f32::MAX],
        );
        let _ = writeln!(out, "aperture = {}", num(aperture));
        if g.rng.chance(0.6) {
            let focus = g.from(
                &[1.0, 5.0, 6.0],
                &[SUBNORMAL, 1e-30, 1e-6, 1e10, 1e30, 3e38, f32::MAX],
            );
            let _ = writeln!(out, "focus_distance = {}", num(focus));
        }
    }
    if g.rng.chance(0.1) {
        let _ = writeln!(out, "motion = {}", motion(g, true));
    }
    out.push('\n');
    lens
}

fn world(g: &mut Gen, out: &mut String) {
    if g.rng.chance(0.8) {
        out.push_str("[world]\n");
        if g.rng.chance(0.7) {
            let _ = writeln!(out, "background = {}", g.colour());
        }
        if g.rng.chance(0.7) {
            let _ = writeln!(out, "ambient = {}", g.colour());
        }
        out.push('\n');
    }
}

/// `[render]` for `integrator`, with the keys that apply to it.
fn render(g: &mut Gen, integrator: &str, lens: bool) -> String {
    let mut out = format!("[render]\nintegrator = \"{integrator}\"\n");
    let w = &mut out;
    // Whitted's rays multiply with depth (at most 65536 per camera ray); the stochastic
    // integrators trace one path per sample, so they may go as deep as the format allows.
    let depth = if integrator == "whitted" {
        g.rng.pick(&[0, 1, 2, 3, 5, 8])
    } else {
        g.rng.pick(&[0, 1, 2, 3, 5, 1000])
    };
    if g.rng.chance(0.8) {
        let _ = writeln!(w, "max_depth = {depth}");
    }
    if g.rng.chance(0.4) {
        let mw = g.rng.pick(&[0.0, SUBNORMAL, 1e-30, 1.0 / 256.0, 0.5, 1.0]);
        let _ = writeln!(w, "min_weight = {}", num(mw));
    }
    if g.rng.chance(0.4) {
        let random = g.rng.next_u64() >> 1;
        let seed = g.rng.pick(&[0, 1, i64::MAX as u64, random]);
        let _ = writeln!(w, "seed = {seed}");
    }
    if g.rng.chance(0.6) {
        let a = g.rng.pick(&["brute", "bounds", "octree", "bvh", "wide"]);
        let _ = writeln!(w, "accelerator = \"{a}\"");
    }
    if g.rng.chance(0.3) {
        let t = g.rng.pick(&["watertight", "projection"]);
        let _ = writeln!(w, "triangle_test = \"{t}\"");
    }
    if g.rng.chance(0.4) {
        let f = g.rng.pick(&["box", "tent", "gaussian", "mitchell"]);
        let _ = writeln!(w, "filter = \"{f}\"");
        if g.rng.chance(0.5) {
            // 0.01 to 16 pixels; 1e-6 is refused (in f32, a narrower filter is zero).
            let r = g.rng.pick(&[1e-6, 0.01, 0.02, 0.5, 1.0, 2.0, 16.0]);
            let _ = writeln!(w, "filter_radius = {}", num(r));
        }
        if g.rng.chance(0.5) {
            let s = g.rng.pick(&["splat", "importance"]);
            let _ = writeln!(w, "filter_sampling = \"{s}\"");
        }
    }
    let mut uniform = true;
    match integrator {
        "whitted" => {
            if g.rng.chance(0.3) {
                let _ = writeln!(w, "shadows = {}", g.rng.chance(0.5));
            }
            // A lens needs uniform sampling; adaptive sampling is tried without one.
            if !lens && g.rng.chance(0.3) {
                uniform = false;
                let aa = g.rng.pick(&["adaptive", "quadtree"]);
                let _ = writeln!(w, "aa = \"{aa}\"");
                if g.rng.chance(0.5) {
                    let t = g.rng.pick(&[0.0, SUBNORMAL, 0.1, 1e30, f32::MAX]);
                    let _ = writeln!(w, "aa_threshold = {}", num(t));
                }
                if g.rng.chance(0.5) {
                    let _ = writeln!(w, "aa_depth = {}", g.rng.below(4));
                }
                if aa == "quadtree" && g.rng.chance(0.5) {
                    let _ = writeln!(w, "aa_block = {}", 1 + g.rng.below(4));
                }
            }
        }
        "path" => {
            if g.rng.chance(0.5) {
                let rr = g.rng.pick(&[0u64, 1, 5, 1000, u64::from(u32::MAX)]);
                let _ = writeln!(w, "rr_depth = {rr}");
            }
        }
        _ => {
            if g.rng.chance(0.5) {
                let _ = writeln!(w, "photons = {}", g.rng.pick(&[1, 2, 64, 1000]));
            }
            if g.rng.chance(0.5) {
                let r = g
                    .rng
                    .pick(&[SUBNORMAL, 1e-30, 1e-6, 0.1, 1.0, 1e20, 1e30, 3e38, f32::MAX]);
                let _ = writeln!(w, "photon_radius = {}", num(r));
            }
        }
    }
    if uniform && g.rng.chance(0.05) {
        let t = g.rng.pick(&[1e-30, 1e-3, 10.0]);
        let _ = writeln!(w, "time_limit = {}", num(t));
    }
    out
}
fn lights(g: &mut Gen, out: &mut String) {
    let mut environment = false;
    for _ in 0..g.rng.below(4) {
        let mut kind = g
            .rng
            .pick(&["point", "point", "spot", "directional", "environment"]);
        if kind == "environment" && environment {
            kind = "point";
        }
        environment |= kind == "environment";
        let _ = writeln!(out, "[[light]]\ntype = \"{kind}\"");
        if g.rng.chance(0.7) {
            let _ = writeln!(out, "intensity = {}", g.colour());
        }
        if matches!(kind, "point" | "spot") {
            let p = if g.rng.chance(0.6) {
                vec3([g.coord(), 3.0 + g.coord(), 2.0 + g.coord()])
            } else {
                g.vector()
            };
            let _ = writeln!(out, "position = {p}");
            if g.rng.chance(0.5) {
                let f = g.rng.pick(&["none", "quadratic"]);
                let _ = writeln!(out, "falloff = \"{f}\"");
            }
        }
        if matches!(kind, "spot" | "directional") {
            let _ = writeln!(out, "direction = {}", g.direction());
        }
        if kind == "spot" {
            let cutoff = g.from(
                &[10.0, 30.0, 60.0, 90.0],
                &[SUBNORMAL, 1e-30, 1e-3, 89.99999, 90.0],
            );
            let _ = writeln!(out, "cutoff = {}", num(cutoff));
            if g.rng.chance(0.5) {
                let start = g.rng.pick(&[0.0, 0.5, 0.9999, 1.0]) * cutoff;
                let _ = writeln!(out, "cutoff_start = {}", num(start));
            }
        }
        if kind == "environment" && g.rng.chance(0.5) {
            out.push_str("file = \"sky.png\"\n");
        }
        out.push('\n');
    }
}

const OBJECTS: [&str; 7] = [
    "sphere",
    "plane",
    "triangle",
    "rectangle",
    "cube",
    "disk",
    "mesh",
];

fn objects(g: &mut Gen, out: &mut String, materials: &[MaterialInfo]) {
    for _ in 0..1 + g.rng.below(5) {
        let kind = g.rng.pick(&OBJECTS);
        let mut m = g.rng.pick(materials);
        // An emitting plane is refused; most scenes should render, so a plane takes another
        // material where there is one (a few emitting planes stay, to see them refused).
        if kind == "plane" && m.emits && g.rng.chance(0.9) {
            m = materials.iter().find(|m| !m.emits).unwrap_or(&m).clone();
        }
        let _ = writeln!(
            out,
            "[[object]]\ntype = \"{kind}\"\nmaterial = \"{}\"",
            m.name
        );
        match kind {
            "sphere" => {
                let c = if g.rng.chance(0.6) {
                    vec3([g.coord() * 0.5, g.coord() * 0.5, g.coord() * 0.5])
                } else {
                    g.vector()
                };
                let r = g.from(&[0.3, 0.5, 1.0, 2.0], &[1e-8, 1e-6, 1e7, 1e15]);
                let _ = writeln!(out, "center = {c}\nradius = {}", num(r));
                if g.rng.chance(0.15) {
                    let s = g.from(&[1.0, 2.0], &[1e-30, 1e-15, 1e15, 3e38]);
                    let z = num(0.0);
                    let s = num(s);
                    let _ = writeln!(
                        out,
                        "uv_axes = [[{s}, {z}, {z}], [{z}, {z}, {s}], [{z}, {s}, {z}]]"
                    );
                }
            }
            "plane" => {
                let p = if g.rng.chance(0.6) {
                    vec3([0.0, g.coord() * 0.3 - 1.0, 0.0])
                } else {
                    g.vector()
                };
                let _ = writeln!(out, "point = {p}\nnormal = {}", g.direction());
            }
            "triangle" => {
                let vs = if g.rng.chance(0.6) {
                    let c = [g.coord() * 0.3, g.coord() * 0.3, g.coord() * 0.3];
                    let s = g.from(&[1.0, 2.0], &[1e-7, 1e-15, 1e7, 1e15, 1e20]);
                    [
                        [c[0] - s, c[1] - s, c[2]],
                        [c[0] + s, c[1] - s, c[2]],
                        [c[0], c[1] + s, c[2]],
                    ]
                } else {
                    [
                        [g.coord(), g.coord(), g.coord()],
                        [g.coord(), g.coord(), g.coord()],
                        [g.coord(), g.coord(), g.coord()],
                    ]
                };
                let _ = writeln!(
                    out,
                    "vertices = [{}, {}, {}]",
                    vec3(vs[0]),
                    vec3(vs[1]),
                    vec3(vs[2])
                );
            }
            _ => {
                if kind == "mesh" {
                    out.push_str("file = \"tri.obj\"\n");
                    if g.rng.chance(0.3) {
                        let _ = writeln!(out, "smooth = {}", g.rng.chance(0.5));
                    }
                } else if g.rng.chance(0.2) {
                    let _ = writeln!(out, "flip_v = {}", g.rng.chance(0.5));
                }
                if g.rng.chance(0.2) {
                    let _ = writeln!(out, "flip_normals = {}", g.rng.chance(0.5));
                }
                placement(g, out);
            }
        }
        if kind != "plane" && !m.emits && g.rng.chance(0.15) {
            let _ = writeln!(out, "motion = {}", motion(g, kind != "sphere"));
        }
        out.push('\n');
    }
}

/// A scale factor, `ordinary` or extreme: mostly within what a placement can invert in f32
/// (about 1e-12 to 1e12 on every axis), sometimes anything but 0 (often refused).
fn scale(g: &mut Gen, ordinary: f32) -> f32 {
    if !g.extreme() {
        return ordinary;
    }
    let s = if g.rng.chance(0.7) {
        g.rng.pick(&[1e-12, 1e-7, 1e-3, 1e3, 1e7, 1e12])
    } else {
        g.rng.pick(&EXTREME)
    };
    let s = if s == 0.0 { 1.0 } else { s };
    g.sign() * s
}

/// A placement: one `transform`, or any of `scale`, `rotate`, `translate`.
fn placement(g: &mut Gen, out: &mut String) {
    if g.rng.chance(0.2) {
        let d = [scale(g, 1.0), scale(g, 0.7), scale(g, 1.3)];
        let (a, b) = (g.any(0.0), g.any(0.2));
        let t = [g.coord(), g.coord(), g.coord()];
        let m = [
            d[0], a, 0.0, t[0], //
            0.0, d[1], b, t[1], //
            0.0, 0.0, d[2], t[2], //
            0.0, 0.0, 0.0, 1.0,
        ];
        let m: Vec<String> = m.iter().map(|&v| num(v)).collect();
        let _ = writeln!(out, "transform = [{}]", m.join(", "));
        return;
    }
    if g.rng.chance(0.6) {
        let s = if g.rng.chance(0.5) {
            num(scale(g, 0.8))
        } else {
            vec3([scale(g, 0.8), scale(g, 1.2), scale(g, -0.5)])
        };
        let _ = writeln!(out, "scale = {s}");
    }
    if g.rng.chance(0.5) {
        let r = [g.any(20.0), g.any(-35.0), g.any(90.0)];
        let _ = writeln!(out, "rotate = {}", vec3(r));
    }
    if g.rng.chance(0.6) {
        let t = [g.coord() * 0.5, g.coord() * 0.5, g.coord() * 0.5];
        let _ = writeln!(out, "translate = {}", vec3(t));
    }
}

/// A `motion` table (inline); `any_scale`: key scales may differ per axis (not on spheres).
fn motion(g: &mut Gen, any_scale: bool) -> String {
    let mut parts = Vec::new();
    if g.rng.chance(0.6) {
        let mut keys = Vec::new();
        // Times strictly increase: steps of 1 after -1e30, or of 1e-30 after 1, are lost in
        // f32 and the keys refused (a one-line error too), so extreme times come with extreme
        // steps but for a few.
        let mut t = g.rng.pick(&[-1e30, -1.0, 0.0, 1e-30, -1.0, 0.0]);
        let far = t == -1e30 && g.rng.chance(0.9);
        for _ in 0..1 + g.rng.below(3) {
            let mut k = format!("{{ time = {}", num(t));
            if g.rng.chance(0.6) {
                let _ = write!(k, ", translate = {}", g.vector());
            }
            if g.rng.chance(0.4) {
                let r = [g.any(0.0), g.any(90.0), g.any(0.0)];
                let _ = write!(k, ", rotate = {}", vec3(r));
            }
            if g.rng.chance(0.4) {
                let s = |g: &mut Gen| {
                    let s = g.from(&[0.5, 1.0, 2.0], &[1e-30, SUBNORMAL, 1e20, 3e38]);
                    num(s)
                };
                if any_scale && g.rng.chance(0.5) {
                    let _ = write!(k, ", scale = [{}, {}, {}]", s(g), s(g), s(g));
                } else {
                    let _ = write!(k, ", scale = {}", s(g));
                }
            }
            keys.push(k + " }");
            t += if far {
                1e30
            } else if g.rng.chance(0.1) {
                g.rng.pick(&[1e-30, 1e-7, 1e30])
            } else {
                g.rng.pick(&[0.5, 1.0, 2.0])
            };
        }
        parts.push(format!("keys = [{}]", keys.join(", ")));
        if g.rng.chance(0.4) {
            let r = g.rng.pick(&["hold", "loop", "bounce"]);
            parts.push(format!("repeat = \"{r}\""));
        }
    }
    if g.rng.chance(0.4) {
        let period = g.from(&[1.0, 2.5], &[SUBNORMAL, 1e-30, 1e30, f32::MAX]);
        let phase = g.any(0.0);
        parts.push(format!(
            "oscillate = {{ offset = {}, period = {}, phase = {} }}",
            g.vector(),
            num(period),
            num(phase)
        ));
    }
    if g.rng.chance(0.4) {
        let period = g.from(&[4.0, 8.0], &[SUBNORMAL, 1e-30, 1e30, f32::MAX]);
        let phase = g.any(0.0);
        parts.push(format!(
            "orbit = {{ center = {}, axis = {}, period = {}, phase = {} }}",
            g.vector(),
            g.direction(),
            num(period),
            num(phase)
        ));
    }
    format!("{{ {} }}", parts.join(", "))
}
