//! `[[material]]` tables of every kind, with their keys and the common ones.

use crate::values::{ALPHA, COLOUR_EXTREME, Gen, IOR, SUBNORMAL, num, vec3};
use std::fmt::Write;

/// What the objects need to know of a material.
#[derive(Clone)]
pub struct MaterialInfo {
    pub name: String,
    /// Not `whitted`: may be named by `back` and `materials`.
    pub physical: bool,
    /// A solid, non-black emission: an area light (no planes, no motion).
    pub emits: bool,
}

/// The material kinds of `docs/scene-format.md`.
const KINDS: [&str; 13] = [
    "whitted",
    "diffuse",
    "conductor",
    "roughconductor",
    "dielectric",
    "roughdielectric",
    "thindielectric",
    "plastic",
    "roughplastic",
    "blend",
    "principled",
    "principledthin",
    "pbr",
];

pub fn materials(g: &mut Gen, out: &mut String) -> Vec<MaterialInfo> {
    let mut made: Vec<MaterialInfo> = Vec::new();
    for i in 0..1 + g.rng.below(4) {
        let name = format!("m{i}");
        let physical: Vec<String> = made
            .iter()
            .filter(|m| m.physical)
            .map(|m| m.name.clone())
            .collect();
        let mut kind = g.rng.pick(&KINDS);
        if kind == "blend" && physical.is_empty() {
            kind = "diffuse";
        }
        let _ = writeln!(out, "[[material]]\nname = \"{name}\"");
        if kind != "whitted" || g.rng.chance(0.5) {
            let _ = writeln!(out, "type = \"{kind}\"");
        }
        match kind {
            "whitted" => {
                for k in ["ka", "ks", "kr", "kt"] {
                    let c = g.colour();
                    key(g, out, k, c);
                }
                let kd = g.texture(true, 0);
                key(g, out, "kd", kd);
                let s = g.from(&[0.0, 10.0, 50.0, 200.0], &[SUBNORMAL, 1e6, 1e30, f32::MAX]);
                key(g, out, "shininess", num(s));
                let ior = g.rng.pick(&IOR);
                key(g, out, "ior", num(ior));
            }
            "diffuse" => {
                let r = g.texture(true, 0);
                key(g, out, "reflectance", r);
            }
            "conductor" | "roughconductor" => {
                let s = g.texture(true, 0);
                key(g, out, "specular", s);
                match g.rng.below(3) {
                    0 => {
                        let m = g.rng.pick(&["Au", "ag", "Cu", "Al", "W", "Cr"]);
                        let _ = writeln!(out, "metal = \"{m}\"");
                    }
                    1 => {
                        let _ = writeln!(out, "eta = {}", conductor_index(g));
                        if g.rng.chance(0.6) {
                            let _ = writeln!(out, "k = {}", conductor_index(g));
                        }
                    }
                    _ => {}
                }
                if kind == "roughconductor" {
                    roughness(g, out, true, false);
                }
            }
            "dielectric" | "roughdielectric" | "thindielectric" => {
                for k in ["ior", "ext_ior"] {
                    let v = g.rng.pick(&IOR);
                    key(g, out, k, num(v));
                }
                for k in ["specular", "transmittance"] {
                    let t = g.texture(true, 0);
                    key(g, out, k, t);
                }
                if kind == "roughdielectric" {
                    roughness(g, out, true, false);
                }
            }
            "plastic" | "roughplastic" => {
                let r = g.texture(true, 0);
                key(g, out, "reflectance", r);
                for k in ["ior", "ext_ior"] {
                    let v = g.rng.pick(&IOR);
                    key(g, out, k, num(v));
                }
                let s = g.texture(true, 0);
                key(g, out, "specular", s);
                let nl = g.rng.chance(0.5).to_string();
                key(g, out, "nonlinear", nl);
                if kind == "roughplastic" {
                    roughness(g, out, false, false);
                } else if g.rng.chance(0.3) {
                    // A `plastic` takes `distribution` only with a `roughness`.
                    roughness(g, out, false, true);
                }
            }
            "blend" => {
                let (a, b) = (g.rng.pick(&physical[..]), g.rng.pick(&physical[..]));
                let _ = writeln!(out, "materials = [\"{a}\", \"{b}\"]");
                // The weight is clamped to [0, 1]: any non-negative value is valid.
                let w = if g.rng.chance(0.3) {
                    num(g.from(&[0.0, 0.5, 1.0], &COLOUR_EXTREME))
                } else {
                    g.unit_texture()
                };
                key(g, out, "weight", w);
            }
            "principled" | "principledthin" => {
                let c = g.texture(true, 0);
                key(g, out, "base_color", c);
                let mut params = vec![
                    "roughness",
                    "anisotropic",
                    "spec_trans",
                    "spec_tint",
                    "sheen",
                    "sheen_tint",
                    "flatness",
                ];
                if kind == "principled" {
                    params.extend(["metallic", "clearcoat", "clearcoat_gloss"]);
                }
                for k in params {
                    let t = g.unit_texture();
                    key(g, out, k, t);
                }
                if kind == "principledthin" {
                    let d = g.rng.pick(&[0.0, SUBNORMAL, 1.0, 1.9999999, 2.0]);
                    key(g, out, "diff_trans", num(d));
                }
                if kind == "principled" && g.rng.chance(0.3) {
                    let s = g.rng.pick(&[SUBNORMAL, 1e-30, 0.5, 1.0]);
                    let _ = writeln!(out, "specular = {}", num(s));
                } else {
                    let ior = g.rng.pick(&IOR);
                    key(g, out, "ior", num(ior));
                }
            }
            _ => {
                // pbr
                for k in ["base_color", "specular_color", "sheen_color"] {
                    let t = g.texture(true, 0);
                    key(g, out, k, t);
                }
                for k in [
                    "metallic",
                    "roughness",
                    "transmission",
                    "clearcoat",
                    "clearcoat_roughness",
                    "sheen_roughness",
                    "anisotropy",
                ] {
                    let t = g.unit_texture();
                    key(g, out, k, t);
                }
                // Clamped to [0, 1]: any non-negative value.
                let s = g.from(&[0.0, 0.5, 1.0], &COLOUR_EXTREME);
                key(g, out, "specular", num(s));
                let ior = g.rng.pick(&IOR);
                key(g, out, "ior", num(ior));
                let vol = g.rng.chance(0.5).to_string();
                key(g, out, "volume", vol);
                let rot = g.any(30.0);
                key(g, out, "anisotropy_rotation", num(rot));
                if g.rng.chance(0.2) {
                    let _ = writeln!(out, "clearcoat_normal_map = {}", normal_map(g));
                    if g.rng.chance(0.5) {
                        let _ = writeln!(out, "clearcoat_normal_scale = {}", num(g.any(1.0)));
                    }
                }
                if g.rng.chance(0.3) {
                    let w = g.unit_texture();
                    let _ = writeln!(out, "iridescence = {w}");
                    let ior = g.rng.pick(&IOR);
                    key(g, out, "iridescence_ior", num(ior));
                    // Nanometres, 0 to 65535; a texture's values are clamped.
                    let d = if g.rng.chance(0.7) {
                        num(g.from(&[100.0, 400.0, 1000.0], &[0.0, SUBNORMAL, 1.0, 65535.0]))
                    } else {
                        g.texture(false, 0)
                    };
                    key(g, out, "iridescence_thickness", d);
                }
            }
        }
        let emits = g.rng.chance(0.25);
        let mut solid_emission = false;
        if emits {
            if g.rng.chance(0.75) {
                let e = g.colour();
                solid_emission = e != "0" && e != "[0, 0, 0]";
                let _ = writeln!(out, "emission = {e}");
            } else {
                let _ = writeln!(out, "emission = {}", g.texture(true, 0));
            }
        }
        if g.rng.chance(0.15) {
            let o = if g.rng.chance(0.5) {
                num(g.from(&[0.0, 0.5, 1.0], &COLOUR_EXTREME))
            } else {
                g.unit_texture()
            };
            let _ = writeln!(out, "opacity = {o}");
        }
        if g.rng.chance(0.15) {
            let _ = writeln!(out, "normal_map = {}", normal_map(g));
            if g.rng.chance(0.5) {
                let _ = writeln!(out, "normal_scale = {}", num(g.any(1.0)));
            }
        }
        if g.rng.chance(0.15) {
            let _ = writeln!(out, "bump_map = {}", g.unit_texture());
            if g.rng.chance(0.5) {
                let _ = writeln!(out, "bump_scale = {}", num(g.any(0.1)));
            }
        }
        let back = !physical.is_empty() && g.rng.chance(0.15);
        if back {
            let _ = writeln!(out, "back = \"{}\"", g.rng.pick(&physical[..]));
        }
        if g.rng.chance(0.15) {
            let _ = writeln!(out, "two_sided = {}", back || g.rng.chance(0.5));
        }
        if g.rng.chance(0.1) {
            let _ = writeln!(out, "vertex_colors = {}", g.rng.chance(0.5));
        }
        out.push('\n');
        made.push(MaterialInfo {
            name,
            physical: kind != "whitted",
            emits: solid_emission,
        });
    }
    made
}

/// A conductor's `eta` or `k`: a number or colour in [0, 1000], or now and then a texture
/// (whose values are not bounded).
fn conductor_index(g: &mut Gen) -> String {
    const INDEX: [f32; 10] = [
        0.0, SUBNORMAL, 1e-30, 0.05, 0.2, 1.0, 1.5, 3.0, 10.0, 1000.0,
    ];
    match g.rng.below(5) {
        0 => g.texture(true, 0),
        1 => vec3([g.rng.pick(&INDEX), g.rng.pick(&INDEX), g.rng.pick(&INDEX)]),
        _ => num(g.rng.pick(&INDEX)),
    }
}

/// Writes `k = v` to `out`, or (with probability 0.4) leaves the key out.
fn key(g: &mut Gen, out: &mut String, k: &str, v: String) {
    if g.rng.chance(0.6) {
        let _ = writeln!(out, "{k} = {v}");
    }
}

/// A normal map: an image, or any other texture (read as `2·value − 1`).
fn normal_map(g: &mut Gen) -> String {
    if g.rng.chance(0.6) {
        g.image("tex.png")
    } else {
        g.texture(true, 0)
    }
}

/// The roughness keys of a rough kind (`anisotropic`: may give `roughness_u`/`roughness_v`
/// and textures; a plastic's roughness is one number); `required`: always some roughness.
fn roughness(g: &mut Gen, out: &mut String, anisotropic: bool, required: bool) {
    let number = |g: &mut Gen| num(g.rng.pick(&ALPHA));
    let value = |g: &mut Gen| {
        if anisotropic && g.rng.chance(0.3) {
            // Texture values are clamped to [1e-4, 100]: any non-negative value.
            g.texture(false, 0)
        } else {
            number(g)
        }
    };
    match g.rng.below(3) {
        0 if !required => {}
        1 if anisotropic => {
            let (u, v) = (value(g), value(g));
            let _ = writeln!(out, "roughness_u = {u}\nroughness_v = {v}");
        }
        _ => {
            let _ = writeln!(out, "roughness = {}", value(g));
        }
    }
    if g.rng.chance(0.4) {
        let d = g.rng.pick(&["ggx", "beckmann", "GGX"]);
        let _ = writeln!(out, "distribution = \"{d}\"");
    }
}
