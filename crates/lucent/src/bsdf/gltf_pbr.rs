//! glTF 2.0's metallic-roughness BRDF, as the specification's appendix B defines it, with the
//! layers `KHR_materials_specular`, `_ior` and `_transmission` put into its dielectric part
//! (the sheen and clearcoat layers are parts of their own: `material/scattering.rs`).
//!
//! With `α` the GGX roughness (`roughness²`, anisotropic under `KHR_materials_anisotropy`),
//! `D` its distribution, `G` Smith's separable masking, `H` the half vector of the viewer `V`
//! and the light `L`, and Schlick's `F(f0) = f0 + (1 − f0)(1 − |V·H|)⁵`:
//! - `specular = D·G/(4|N·V||N·L|)`;
//! - `metal = F(base)·specular`;
//! - `dielectric = (1 − s·max(F_d))·[(1 − t)·base/π + t·base·btdf] + s·F_d·specular`, with
//!   `F_d = F(min(f0(ior)·specular_color, 1))` and `s` the specular factor (the spec's
//!   `fresnel_mix`), `t` the transmission;
//! - `material = (1 − metallic)·dielectric + metallic·metal`.
//!
//! The transmission lobe (`btdf`) is the specular lobe seen through the surface: for a
//! thin-walled material (glTF's default without `KHR_materials_volume`) the light passes
//! unbent and the lobe is the reflection mirrored to the back; for a volume it refracts by
//! `ior`, Walter et al.'s BTDF without its Fresnel (which `fresnel_mix` supplies), with the
//! `1/η²` of radiance entering a denser medium.
//!
//! Sampling picks the diffuse lobe by the cosine, and the reflection and the transmission by
//! the visible normals, in proportion to estimates of their weights; every direction is
//! weighted by the whole value over the whole density.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::microfacet::Microfacet;
use super::{BsdfSample, Transport, fresnel};
use crate::Rgb;
use crate::optics::reflect;

/// The glTF BRDF's parameters at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfPbr {
    /// The base colour.
    pub base_color: Rgb,
    /// Metalness in `[0, 1]`.
    pub metallic: f32,
    /// The microfacets (`α = roughness²`, per direction under anisotropy).
    pub microfacet: Microfacet,
    /// The index of refraction (`KHR_materials_ior`, default 1.5).
    pub ior: f32,
    /// `KHR_materials_specular`'s factor (default 1).
    pub specular: f32,
    /// `KHR_materials_specular`'s colour (default white).
    pub specular_color: Rgb,
    /// `KHR_materials_transmission`'s factor (default 0).
    pub transmission: f32,
    /// Whether transmitted light refracts (`KHR_materials_volume` with a thickness) or passes
    /// a thin wall unbent.
    pub volume: bool,
}

/// Schlick's Fresnel of normal reflectance `f0` at `cos`.
fn schlick(f0: Rgb, cos: f32) -> Rgb {
    let m = (1.0 - cos.abs()).clamp(0.0, 1.0);
    let w = m * m * m * m * m;
    f0 + (Rgb::WHITE - f0) * w
}

impl GltfPbr {
    /// The dielectric's normal reflectance, `min(((η − 1)/(η + 1))²·specular_color, 1)`.
    fn f0_dielectric(&self) -> Rgb {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        (self.specular_color * (r * r)).clamp(0.0, 1.0)
    }

    /// The specular lobe `D·G/(4|N·V||N·L|)·|N·L|` for the facet `h` linking `v` and `l` (both
    /// taken to the front).
    fn specular(&self, v: Vec3, l: Vec3, h: Vec3) -> f32 {
        let g = self.microfacet;
        g.d(h) * g.g1_over_cos(v, h) * g.g1(l, h) * 0.25
    }

    /// The refracted direction's BTDF without Fresnel, `|V·H||L·H|·D·G/(|N·V||N·L|(V·H +
    /// η' L·H)²)·|N·L|` (Walter's, whose `η'²` radiance loses entering the denser side), with
    /// `η'` the index ratio across; and `|V·H|` for the Fresnel.
    fn refracted(&self, v: Vec3, l: Vec3, mode: Transport) -> (f32, f32) {
        let eta = fresnel::sane_eta(self.ior);
        let eta_it = if v.z > 0.0 { eta } else { 1.0 / eta };
        let h = v + l * eta_it;
        let Some(h) = h.try_normalize() else {
            return (0.0, 1.0);
        };
        let h = if h.z < 0.0 { -h } else { h };
        let (vh, lh) = (v.dot(h), l.dot(h));
        if vh * v.z <= 0.0 || lh * l.z <= 0.0 {
            return (0.0, 1.0);
        }
        let g = self.microfacet;
        let denom = vh + eta_it * lh;
        let scale = match mode {
            Transport::Radiance => 1.0,
            Transport::Importance => eta_it * eta_it,
        };
        let f =
            g.d(h) * g.g1_over_cos(v, h) * g.g1(l, h) * (vh * lh).abs() / (denom * denom) * scale;
        (if f.is_finite() { f } else { 0.0 }, vh.abs())
    }

    /// `f(V, L)·|cos θL|` (see the module docs).
    pub fn eval(&self, v: Vec3, l: Vec3, mode: Transport) -> Rgb {
        if v.z <= 0.0 && !(self.volume && self.transmission > 0.0) {
            return Rgb::BLACK;
        }
        if v.z == 0.0 || l.z == 0.0 {
            return Rgb::BLACK;
        }
        let base = self.base_color;
        let m = self.metallic;
        let s = self.specular;
        let t = self.transmission;
        if v.z < 0.0 {
            // Inside a volume: only the refraction back out (and total internal reflection,
            // which single scattering leaves out).
            if l.z < 0.0 {
                return Rgb::BLACK;
            }
            let (btdf, cos) = self.refracted(v, l, mode);
            let fd = schlick(self.f0_dielectric(), cos).max_channel();
            return base * ((1.0 - m) * t * (1.0 - s * fd) * btdf);
        }
        if l.z > 0.0 {
            let Some(h) = (v + l).try_normalize() else {
                return Rgb::BLACK;
            };
            let cos = v.dot(h);
            let fd = schlick(self.f0_dielectric(), cos);
            let fm = schlick(base, cos);
            let spec = self.specular(v, l, h);
            let diffuse = base * ((1.0 - t) * FRAC_1_PI * l.z);
            let dielectric = diffuse * (1.0 - s * fd.max_channel()) + fd * (s * spec);
            return dielectric * (1.0 - m) + fm * (m * spec);
        }
        // Transmission.
        if t <= 0.0 || m >= 1.0 {
            return Rgb::BLACK;
        }
        let (btdf, cos) = if self.volume {
            self.refracted(v, l, mode)
        } else {
            let mirrored = Vec3::new(l.x, l.y, -l.z);
            let Some(h) = (v + mirrored).try_normalize() else {
                return Rgb::BLACK;
            };
            (self.specular(v, mirrored, h), v.dot(h))
        };
        let fd = schlick(self.f0_dielectric(), cos).max_channel();
        base * ((1.0 - m) * t * (1.0 - s * fd) * btdf)
    }

    /// The lobes' probabilities: diffuse, reflection, transmission (from outside).
    fn probabilities(&self, v: Vec3) -> [f32; 3] {
        let (m, s, t) = (self.metallic, self.specular, self.transmission);
        let f = schlick(self.f0_dielectric(), v.z).max_channel();
        let lum = self.base_color.luminance().max(0.05);
        let diffuse = (1.0 - m) * (1.0 - t) * (1.0 - s * f) * lum;
        let specular = (1.0 - m) * s * f + m;
        let trans = (1.0 - m) * t * (1.0 - s * f) * lum;
        let sum = diffuse + specular + trans;
        if sum > 0.0 && sum.is_finite() {
            [diffuse / sum, specular / sum, trans / sum]
        } else {
            [0.0; 3]
        }
    }

    /// The density with which [`GltfPbr::sample`] draws `l`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        let g = self.microfacet;
        if v.z < 0.0 {
            // From inside a volume only the refraction out is sampled.
            if !(self.volume && self.transmission > 0.0) || l.z <= 0.0 {
                return 0.0;
            }
            return self.refraction_pdf(-v, l, true);
        }
        if v.z == 0.0 {
            return 0.0;
        }
        let [p_diffuse, p_spec, p_trans] = self.probabilities(v);
        if l.z > 0.0 {
            let h = (v + l).normalize_or_zero();
            let spec = g.visible_pdf(v, h) / (4.0 * v.dot(h).abs().max(1e-12));
            return p_diffuse * cosine_pdf(l) + p_spec * spec;
        }
        if l.z < 0.0 && p_trans > 0.0 {
            return p_trans * self.refraction_pdf(v, l, false);
        }
        0.0
    }

    /// The density of the transmission lobe's samples: the mirrored reflection's (thin) or the
    /// refraction's (volume), by the visible normals seen from `v` (turned to the front;
    /// `inside` when the path is inside the volume).
    fn refraction_pdf(&self, v: Vec3, l: Vec3, inside: bool) -> f32 {
        let g = self.microfacet;
        if !self.volume {
            let mirrored = Vec3::new(l.x, l.y, -l.z);
            let h = (v + mirrored).normalize_or_zero();
            return g.visible_pdf(v, h) / (4.0 * v.dot(h).abs().max(1e-12));
        }
        // From inside the ratio inverts; `l` is then outside (z > 0) and `v` was turned.
        let eta = fresnel::sane_eta(self.ior);
        let (vv, ll, eta_it) = if inside {
            (-v, l, 1.0 / eta)
        } else {
            (v, l, eta)
        };
        let h = (vv + ll * eta_it).normalize_or_zero();
        let h = if h.z < 0.0 { -h } else { h };
        let (vh, lh) = (vv.dot(h), ll.dot(h));
        // Only a facet that both directions see from their own sides refracts one into the
        // other.
        if vh * vv.z <= 0.0 || lh * ll.z <= 0.0 {
            return 0.0;
        }
        let denom = vh + eta_it * lh;
        let jacobian = (eta_it * eta_it * lh / (denom * denom)).abs();
        let viewer = if vv.z < 0.0 { -vv } else { vv };
        let p = g.visible_pdf(viewer, h) * jacobian;
        if p.is_finite() { p } else { 0.0 }
    }

    /// A direction drawn from the lobes, weighted by the whole value over the whole density.
    pub fn sample(&self, v: Vec3, u_lobe: f32, u: Vec2, mode: Transport) -> Option<BsdfSample> {
        let g = self.microfacet;
        if v.z < 0.0 {
            if !(self.volume && self.transmission > 0.0) {
                return None;
            }
            let m = g.sample_visible(-v, u);
            let f = fresnel::dielectric(v.dot(m), self.ior);
            if f.is_total() {
                return None;
            }
            let l = fresnel::refract(v, m, &f).normalize();
            if l.z <= 0.0 {
                return None;
            }
            return BsdfSample::of_mixture(l, self.eval(v, l, mode), self.pdf(v, l));
        }
        if v.z == 0.0 {
            return None;
        }
        let [p_diffuse, p_spec, _] = self.probabilities(v);
        let l = if u_lobe < p_diffuse {
            sample_cosine(u)?
        } else if u_lobe < p_diffuse + p_spec {
            let l = reflect(-v, g.sample_visible(v, u));
            if l.z <= 0.0 {
                return None;
            }
            l
        } else if self.volume {
            let m = g.sample_visible(v, u);
            let f = fresnel::dielectric(v.dot(m), self.ior);
            if f.is_total() {
                return None;
            }
            let l = fresnel::refract(v, m, &f).normalize();
            if l.z >= 0.0 {
                return None;
            }
            l
        } else {
            let mut l = reflect(-v, g.sample_visible(v, u));
            if l.z <= 0.0 {
                return None;
            }
            l.z = -l.z;
            l
        };
        BsdfSample::of_mixture(l, self.eval(v, l, mode), self.pdf(v, l))
    }

    /// Whether light arrives from inside: a volume's transmission. (A thin wall transmits
    /// too, but has no inside: seen from behind it is turned around like any two-sided
    /// reflector.)
    pub fn transmits(&self) -> bool {
        self.volume && self.transmission > 0.0 && self.metallic < 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::Distribution;

    fn pbr(base: Rgb, metallic: f32, roughness: f32) -> GltfPbr {
        GltfPbr {
            base_color: base,
            metallic,
            microfacet: Microfacet::isotropic(Distribution::Ggx, roughness * roughness),
            ior: 1.5,
            specular: 1.0,
            specular_color: Rgb::WHITE,
            transmission: 0.0,
            volume: false,
        }
    }

    #[test]
    fn the_appendix_b_brdf_head_on() {
        // V = L = N: H = N, Schlick at cos 1 is f0; D(N) = 1/(πα²), G = 1.
        let (v, l) = (Vec3::Z, Vec3::Z);
        let alpha = 0.25f32 * 0.25;
        let spec = 1.0 / (std::f32::consts::PI * alpha * alpha) / 4.0;
        let metal = pbr(Rgb::new(0.9, 0.6, 0.2), 1.0, 0.25).eval(v, l, Transport::Radiance);
        assert!((metal.r - 0.9 * spec).abs() < 1e-3 * metal.r, "{metal:?}");
        let plastic = pbr(Rgb::gray(0.5), 0.0, 0.25).eval(v, l, Transport::Radiance);
        let want = 0.5 * FRAC_1_PI * (1.0 - 0.04) + 0.04 * spec;
        assert!(
            (plastic.r - want).abs() < 1e-3 * want,
            "{} vs {want}",
            plastic.r
        );
        // One-sided without a volume.
        assert!(
            pbr(Rgb::WHITE, 0.0, 0.5)
                .eval(-v, -l, Transport::Radiance)
                .is_black()
        );
    }
}
