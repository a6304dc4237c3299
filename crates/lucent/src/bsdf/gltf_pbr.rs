//! glTF 2.0's metallic-roughness BRDF, as the specification's appendix B defines it, with the
//! layers `KHR_materials_specular`, `_ior` and `_transmission` put into its dielectric part and
//! `KHR_materials_iridescence` into the Fresnel of both parts (the sheen and clearcoat layers
//! are parts of their own: `material/scattering.rs`).
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
//! A thin film (`KHR_materials_iridescence`, weight `w`, index `η_f`, thickness `d`) replaces
//! both Fresnel terms by their mix with the film's reflectance `F_film` ([`thin_film`]): the
//! metal's `F(base)` by `mix(F(base), F_film(base), w)`, and the dielectric's `s·F_d` by
//! `α = mix(s·F_d, F_film(s·f0_d), w)` with `f0_d = min(f0(ior)·specular_color, 1)`, in the
//! reflection and in the weight `1 − max(α)` of the diffuse and transmitted light below it
//! (the extension's `iridescent_dielectric_layer` with `KHR_materials_specular`).
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
use super::microfacet::{Distribution, Microfacet};
use super::{BsdfSample, Transport, fresnel, thin_film};
use crate::Rgb;
use crate::optics::reflect;

/// The glTF BRDF's parameters at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfPbr {
    /// The base colour.
    pub base_color: Rgb,
    /// Metalness in `[0, 1]`.
    pub metallic: f32,
    /// The GGX roughness along the frame's `x` (tangent) and `y` (bitangent): `roughness²`,
    /// stretched along one under `KHR_materials_anisotropy`. (glTF's microfacets are always
    /// GGX: the pair, rather than a [`Microfacet`], keeps [`super::Bsdf`] at 64 bytes.)
    pub alpha: Vec2,
    /// The index of refraction (`KHR_materials_ior`, default 1.5).
    pub ior: f32,
    /// `KHR_materials_specular`'s factor (default 1).
    pub specular: f32,
    /// `KHR_materials_specular`'s colour (default white).
    pub specular_color: Rgb,
    /// `KHR_materials_transmission`'s factor (default 0).
    pub transmission: f32,
    /// `KHR_materials_iridescence`: the thin film's weight in `[0, 1]` (0, the default: no
    /// film).
    pub iridescence: f32,
    /// The film's index of refraction (default 1.3).
    pub film_ior: f32,
    /// The film's thickness in whole nanometres (default 400). A nanometre moves the
    /// interference's phase by under 0.05 rad, invisible; 16 bits rather than an `f32` keep
    /// [`super::Bsdf`] at 64 bytes.
    pub film_thickness: u16,
    /// Whether transmitted light refracts (`KHR_materials_volume` with a thickness) or passes
    /// a thin wall unbent.
    pub volume: bool,
    /// `KHR_materials_diffuse_transmission`: the share of the diffuse lobe that passes through
    /// the surface, in 255ths (0, the default: none). The diffuse reflection keeps the rest;
    /// the transmitted share, of its own colour, is a part of its own
    /// (`bsdf/gltf_translucent.rs`). Eight bits, below what a texture resolves, keep
    /// [`super::Bsdf`] at 64 bytes.
    pub diffuse_transmission: u8,
}

/// Schlick's Fresnel of normal reflectance `f0` at `cos`.
pub(super) fn schlick(f0: Rgb, cos: f32) -> Rgb {
    let m = (1.0 - cos.abs()).clamp(0.0, 1.0);
    let w = m * m * m * m * m;
    f0 + (Rgb::WHITE - f0) * w
}

impl GltfPbr {
    /// Base colour `base_color`, metalness `metallic` and isotropic GGX roughness `alpha`, and
    /// glTF's defaults for the rest: index 1.5, full specular, no transmission, film or
    /// diffuse transmission.
    pub fn plain(base_color: Rgb, metallic: f32, alpha: f32) -> Self {
        Self {
            base_color,
            metallic,
            alpha: Vec2::splat(alpha),
            ior: 1.5,
            specular: 1.0,
            specular_color: Rgb::WHITE,
            transmission: 0.0,
            iridescence: 0.0,
            film_ior: 1.3,
            film_thickness: 400,
            volume: false,
            diffuse_transmission: 0,
        }
    }

    /// The microfacets.
    fn microfacet(&self) -> Microfacet {
        Microfacet::new(Distribution::Ggx, self.alpha.x, self.alpha.y)
    }

    /// The dielectric's normal reflectance, `min(((η − 1)/(η + 1))²·specular_color, 1)`.
    fn f0_dielectric(&self) -> Rgb {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        (self.specular_color * (r * r)).clamp(0.0, 1.0)
    }

    /// The thin film's reflectance over a base of normal reflectance `f0`, at `cos`.
    fn film(&self, f0: Rgb, cos: f32) -> Rgb {
        let d = f32::from(self.film_thickness);
        thin_film::reflectance(cos, self.film_ior, d, f0)
    }

    /// The dielectric's Fresnel weight at `cos`: `s·F_d`, mixed with the film's reflectance
    /// over `s·f0_d` (see the module docs). What the specular lobe is weighted by; the
    /// diffuse and transmitted light keep `1 − max` of it.
    pub(super) fn fresnel_dielectric(&self, cos: f32) -> Rgb {
        let f0 = self.f0_dielectric();
        let plain = schlick(f0, cos) * self.specular;
        if self.iridescence <= 0.0 {
            return plain;
        }
        plain.lerp(self.film(f0 * self.specular, cos), self.iridescence)
    }

    /// The metal's Fresnel at `cos`: `F(base)`, mixed with the film's reflectance over it.
    fn fresnel_metal(&self, cos: f32) -> Rgb {
        let plain = schlick(self.base_color, cos);
        if self.iridescence <= 0.0 {
            return plain;
        }
        plain.lerp(self.film(self.base_color, cos), self.iridescence)
    }

    /// The specular lobe `D·G/(4|N·V||N·L|)·|N·L|` for the facet `h` linking `v` and `l` (both
    /// taken to the front).
    fn specular(&self, v: Vec3, l: Vec3, h: Vec3) -> f32 {
        let g = self.microfacet();
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
        let g = self.microfacet();
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
        let t = self.transmission;
        if v.z < 0.0 {
            // Inside a volume: only the refraction back out (and total internal reflection,
            // which single scattering leaves out).
            if l.z < 0.0 {
                return Rgb::BLACK;
            }
            let (btdf, cos) = self.refracted(v, l, mode);
            let fd = self.fresnel_dielectric(cos).max_channel();
            return base * ((1.0 - m) * t * (1.0 - fd) * btdf);
        }
        if l.z > 0.0 {
            let Some(h) = (v + l).try_normalize() else {
                return Rgb::BLACK;
            };
            let cos = v.dot(h);
            let spec = self.specular(v, l, h);
            let mut f = Rgb::BLACK;
            if m < 1.0 {
                let fd = self.fresnel_dielectric(cos);
                let diffuse = base * ((1.0 - t) * self.diffuse_reflected() * FRAC_1_PI * l.z);
                f += (diffuse * (1.0 - fd.max_channel()) + fd * spec) * (1.0 - m);
            }
            if m > 0.0 {
                f += self.fresnel_metal(cos) * (m * spec);
            }
            return f;
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
        let fd = self.fresnel_dielectric(cos).max_channel();
        base * ((1.0 - m) * t * (1.0 - fd) * btdf)
    }

    /// The share of the diffuse lobe reflected: `1 − diffuse_transmission`.
    fn diffuse_reflected(&self) -> f32 {
        1.0 - f32::from(self.diffuse_transmission) / 255.0
    }

    /// The lobes' probabilities: diffuse, reflection, transmission (from outside), in
    /// proportion to their weights at the facet of the normal (the film's included).
    fn probabilities(&self, v: Vec3) -> [f32; 3] {
        let (m, t) = (self.metallic, self.transmission);
        let f = if m < 1.0 {
            self.fresnel_dielectric(v.z).max_channel()
        } else {
            0.0
        };
        let lum = self.base_color.luminance().max(0.05);
        let diffuse = (1.0 - m) * (1.0 - t) * self.diffuse_reflected() * (1.0 - f) * lum;
        let specular = (1.0 - m) * f + m;
        let trans = (1.0 - m) * t * (1.0 - f) * lum;
        let sum = diffuse + specular + trans;
        if sum > 0.0 && sum.is_finite() {
            [diffuse / sum, specular / sum, trans / sum]
        } else {
            [0.0; 3]
        }
    }

    /// The density with which [`GltfPbr::sample`] draws `l`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        let g = self.microfacet();
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
        let g = self.microfacet();
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
        let g = self.microfacet();
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

    fn pbr(base: Rgb, metallic: f32, roughness: f32) -> GltfPbr {
        GltfPbr::plain(base, metallic, roughness * roughness)
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

    /// Pairs of directions on the front, reflected and transmitted, away from the normal.
    fn directions() -> Vec<(Vec3, Vec3)> {
        let at = |theta: f32, phi: f32| {
            let (t, p) = (theta.to_radians(), phi.to_radians());
            Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
        };
        let mut v = Vec::new();
        for (a, b) in [
            (10.0, 20.0),
            (35.0, 60.0),
            (50.0, 5.0),
            (70.0, 80.0),
            (85.0, 40.0),
        ] {
            let (wo, wi) = (at(a, 30.0), at(b, 200.0));
            v.push((wo, wi));
            v.push((wo, Vec3::new(wi.x, wi.y, -wi.z)));
        }
        v
    }

    #[test]
    fn without_a_film_the_brdf_is_the_plain_one() {
        // Iridescence 0 ignores the film's parameters; a film of thickness 0 fades to nothing:
        // both give the BRDF without the extension, for metals, dielectrics and glass.
        for (metallic, transmission, volume) in
            [(0.0, 0.0, false), (1.0, 0.0, false), (0.4, 0.7, true)]
        {
            let plain = GltfPbr {
                transmission,
                volume,
                ..pbr(Rgb::new(0.8, 0.5, 0.2), metallic, 0.4)
            };
            let off = GltfPbr {
                film_ior: 2.0,
                film_thickness: 300,
                ..plain
            };
            let vanished = GltfPbr {
                iridescence: 1.0,
                film_ior: 2.0,
                film_thickness: 0,
                ..plain
            };
            for (wo, wi) in directions() {
                let want = plain.eval(wo, wi, Transport::Radiance);
                assert_eq!(off.eval(wo, wi, Transport::Radiance), want);
                assert_eq!(off.pdf(wo, wi), plain.pdf(wo, wi));
                let got = vanished.eval(wo, wi, Transport::Radiance);
                for (a, b) in got.to_array().into_iter().zip(want.to_array()) {
                    assert!(
                        (a - b).abs() <= 1e-5 * b.max(1.0),
                        "{wo} {wi}: {got:?} vs {want:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_film_tints_both_parts_by_its_weight() {
        // A white dielectric's reflection is grey without a film and coloured with one; the
        // metal's value is linear in the film's weight (the Fresnel terms are mixed).
        let (wo, wi) = (Vec3::new(0.3, 0.0, 0.954), Vec3::new(-0.3, 0.0, 0.954));
        let white = pbr(Rgb::WHITE, 0.0, 0.2);
        let filmed = GltfPbr {
            iridescence: 1.0,
            ..white
        };
        let grey = white.eval(wo, wi, Transport::Radiance);
        let tinted = filmed.eval(wo, wi, Transport::Radiance);
        assert!((grey.r - grey.b).abs() < 1e-6 * grey.r, "{grey:?}");
        assert!((tinted.r - tinted.b).abs() > 0.05 * tinted.r, "{tinted:?}");
        let metal = |w: f32| {
            GltfPbr {
                iridescence: w,
                ..pbr(Rgb::new(0.9, 0.6, 0.2), 1.0, 0.3)
            }
            .eval(wo, wi, Transport::Radiance)
        };
        let (none, half, full) = (metal(0.0), metal(0.5), metal(1.0));
        // Gold-like: the film hardly dims the strong red, but shifts the weak blue.
        assert!(
            (full.b / full.r - none.b / none.r).abs() > 0.05,
            "{none:?} {full:?}"
        );
        for ((n, h), f) in none
            .to_array()
            .into_iter()
            .zip(half.to_array())
            .zip(full.to_array())
        {
            assert!(
                (h - 0.5 * (n + f)).abs() <= 1e-5 * n.max(f),
                "{none:?} {half:?} {full:?}"
            );
        }
    }

    #[test]
    fn the_parameters_fit_the_bsdf_enum() {
        // Every hit's parts carry a `Bsdf` by value; glTF's variant, the film included, must not
        // make it larger than its other variants do (64 bytes).
        assert!(
            std::mem::size_of::<super::super::Bsdf>() <= 64,
            "Bsdf is {} bytes, GltfPbr {}",
            std::mem::size_of::<super::super::Bsdf>(),
            std::mem::size_of::<GltfPbr>()
        );
    }
}
