//! The Disney principled BSDF as Mitsuba 3 computes it (`principled`; Burley 2012 and 2015,
//! "Physically Based Shading at Disney" and "Extending the Disney BRDF to a BSDF with
//! Integrated Subsurface Scattering"): one material of a dozen artist-friendly parameters.
//!
//! With `V` the viewer (`wo` here, Mitsuba's `wi`), `L` the light, `brdf = (1 − metallic)(1 −
//! spec_trans)` and `bsdf = (1 − metallic)·spec_trans`, the lobes are:
//! - **specular reflection**, anisotropic GGX (`α_x = max(0.001, r²/a)`, `α_y = max(0.001,
//!   r²·a)`, `a = √(1 − 0.9·anisotropic)`): `F·D·G/(4|cos θV|)` with `F` the dielectric Fresnel
//!   of `eta` blended with Schlick's for a metal of the base colour (`metallic`) and for a
//!   tinted dielectric (`spec_tint`); from inside only `bsdf·F_dielectric`;
//! - **specular transmission**, the rough dielectric's, tinted by `√base_color`, weighted by
//!   `bsdf`;
//! - **clearcoat**, `0.25·clearcoat·F_schlick(0.04)·D_GTR1·G·|cos θL|` with GTR1 of roughness
//!   `lerp(0.1, 0.001, clearcoat_gloss)` and Smith GGX masking of roughness 0.25 (Mitsuba's
//!   form, which leaves out the `1/(4 cos θV cos θL)` of Burley's);
//! - **diffuse** with retro-reflection (and, by `flatness`, a fake subsurface), `brdf·base/π`
//!   times Burley's factors, front side only;
//! - **sheen**, `sheen·(1 − metallic)·F_schlick(θd)·tint·|cos θL|` (Mitsuba's, without `1/π`).
//!
//! Sampling picks the diffuse, clearcoat, transmission or reflection lobe in proportion to
//! their weights (the Fresnel of the sampled facet splitting reflection from transmission, a
//! quarter of the clearcoat), and weights the direction by the whole value over the whole
//! density.

use std::f32::consts::{FRAC_1_PI, PI, TAU};

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::microfacet::{Distribution, Microfacet};
use super::{BsdfSample, Transport, fresnel};
use crate::Rgb;
use crate::optics::reflect;

/// The principled BSDF's parameters at a surface point (each in `[0, 1]` but `eta`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principled {
    /// The base colour.
    pub base_color: Rgb,
    /// Perceptual roughness (`α = roughness²`).
    pub roughness: f32,
    /// Anisotropy of the specular lobes.
    pub anisotropic: f32,
    /// Metalness.
    pub metallic: f32,
    /// The share of the dielectric part that is transmitted.
    pub spec_trans: f32,
    /// Tint of the dielectric reflection towards the base colour.
    pub spec_tint: f32,
    /// Strength of the sheen.
    pub sheen: f32,
    /// Tint of the sheen towards the base colour.
    pub sheen_tint: f32,
    /// Blend of the diffuse lobe towards the fake subsurface.
    pub flatness: f32,
    /// Strength of the clearcoat.
    pub clearcoat: f32,
    /// Glossiness of the clearcoat.
    pub clearcoat_gloss: f32,
    /// Index of refraction (inside over outside), from Mitsuba's `eta` or `specular`.
    pub eta: f32,
}

impl Default for Principled {
    /// Mitsuba's defaults: grey 0.5 base, roughness 0.5, specular 0.5 (η ≈ 1.5), the rest 0.
    fn default() -> Self {
        Self {
            base_color: Rgb::gray(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            metallic: 0.0,
            spec_trans: 0.0,
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            clearcoat: 0.0,
            clearcoat_gloss: 0.0,
            eta: eta_of_specular(0.5),
        }
    }
}

/// The index of refraction whose normal-incidence reflectance is `0.08·specular`, Burley's
/// mapping: `η = 2/(1 − √(0.08·specular)) − 1` (specular 0.5: η ≈ 1.5).
pub fn eta_of_specular(specular: f32) -> f32 {
    let s = specular.max(1e-3);
    2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
}

/// `(1 − cos)⁵`, Schlick's weight.
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's Fresnel of reflectance `r0` at `cos_i` on a boundary of index `eta`, taken at the
/// transmitted angle when light goes from the denser side (Mitsuba's `calc_schlick`).
pub(super) fn schlick(r0: Rgb, cos_i: f32, eta: f32) -> Rgb {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    let eta_ti = 1.0 / eta_it;
    let cos = if eta_it > 1.0 {
        cos_i.abs()
    } else {
        (1.0 - (1.0 - cos_i * cos_i) * eta_ti * eta_ti)
            .max(0.0)
            .sqrt()
    };
    let w = schlick_weight(cos);
    r0 * (1.0 - w) + Rgb::gray(w)
}

/// `((η − 1)/(η + 1))²`.
pub(super) fn r0_of_eta(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// The base colour over its luminance (white for black), the tint's hue.
pub(super) fn tint_of(base: Rgb) -> Rgb {
    let lum = base.luminance();
    if lum > 0.0 { base / lum } else { Rgb::WHITE }
}

/// The specular distribution of roughness `r` and anisotropy `a` (Disney's mapping).
pub(super) fn specular_facets(roughness: f32, anisotropic: f32) -> Microfacet {
    let r2 = roughness * roughness;
    let aspect = (1.0 - 0.9 * anisotropic).max(0.0).sqrt();
    Microfacet::new(
        Distribution::Ggx,
        (r2 / aspect.max(1e-6)).max(1e-3),
        (r2 * aspect).max(1e-3),
    )
}

/// Whether the facet `m` links `v` and `w` from the side `cos_v` says: both in front of it
/// (reflection), or `w` behind it (refraction) — Mitsuba's `mac_mic_compatibility`.
pub(super) fn compatible(m: Vec3, v: Vec3, w: Vec3, cos_v: f32, reflection: bool) -> bool {
    let s = if cos_v >= 0.0 { 1.0 } else { -1.0 };
    let mv = m * s;
    if reflection {
        v.dot(mv) > 0.0 && w.dot(mv) > 0.0
    } else {
        v.dot(mv) > 0.0 && w.dot(-mv) > 0.0
    }
}

/// Burley's GTR1 ("Berry") distribution of the clearcoat, of roughness `alpha`.
#[derive(Clone, Copy)]
struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    fn d(self, m: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let c2 = m.z * m.z;
        let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * c2));
        if d * m.z > 1e-20 { d } else { 0.0 }
    }

    fn pdf(self, m: Vec3) -> f32 {
        if m.z < 0.0 { 0.0 } else { m.z * self.d(m) }
    }

    fn sample(self, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = (TAU * u.x).sin_cos();
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin = (1.0 - cos2).max(0.0).sqrt();
        Vec3::new(cos_phi * sin, sin_phi * sin, cos2.max(0.0).sqrt())
    }
}

/// The Disney diffuse lobe's shape (without `base/π` and the cosine): Burley's retro-reflective
/// diffuse `f_diff + f_retro`, blended by `flatness` towards the Hanrahan–Krueger-like
/// subsurface approximation, as Mitsuba's principled BSDFs compute it. `fo`, `fi` are the
/// Schlick weights of the two directions, `cos_d` the cosine between the incoming direction and
/// the half vector, `cos_sum` the sum of the two cosines' magnitudes.
pub(super) fn disney_diffuse(
    roughness: f32,
    flatness: f32,
    (fo, fi): (f32, f32),
    cos_d: f32,
    cos_sum: f32,
) -> f32 {
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    if flatness > 0.0 {
        let fss90 = rr / 2.0;
        let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
        let f_ss = 1.25 * (fss * (1.0 / cos_sum - 0.5) + 0.5);
        (f_diff + f_retro) * (1.0 - flatness) + f_ss * flatness
    } else {
        f_diff + f_retro
    }
}

/// Smith's GGX masking of isotropic roughness `alpha` (the clearcoat's), zero on the back of
/// the facet.
fn smith_ggx1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    let c2 = v.z * v.z;
    if c2 >= 1.0 {
        return 1.0;
    }
    let tan2 = (1.0 - c2) / c2.max(1e-12);
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// The lobes' selection probabilities (diffuse, clearcoat, transmission, reflection) from the
/// viewer's side and the dielectric Fresnel `f`.
fn probabilities(p: &Principled, front: bool, f: f32) -> [f32; 4] {
    let brdf = (1.0 - p.metallic) * (1.0 - p.spec_trans);
    let bsdf = (1.0 - p.metallic) * p.spec_trans;
    let (diffuse, clearcoat, trans, refl) = if front {
        (
            brdf,
            0.25 * p.clearcoat,
            bsdf * (1.0 - f),
            1.0 - bsdf * (1.0 - f),
        )
    } else {
        (0.0, 0.0, if p.spec_trans > 0.0 { 1.0 - f } else { 0.0 }, f)
    };
    let sum = diffuse + clearcoat + trans + refl;
    if sum > 0.0 && sum.is_finite() {
        [diffuse / sum, clearcoat / sum, trans / sum, refl / sum]
    } else {
        [0.0; 4]
    }
}

impl Principled {
    fn weights(&self) -> (f32, f32) {
        (
            (1.0 - self.metallic) * (1.0 - self.spec_trans),
            (1.0 - self.metallic) * self.spec_trans,
        )
    }

    fn eta(&self) -> f32 {
        let eta = fresnel::sane_eta(self.eta);
        if eta == 1.0 { 1.001 } else { eta }
    }

    /// The half vector of `v` and `l` (reflection or refraction), turned up.
    fn half(&self, v: Vec3, l: Vec3, reflect: bool, eta_path: f32) -> Option<Vec3> {
        let h = if reflect { v + l } else { v + l * eta_path };
        let h = h.try_normalize()?;
        Some(if h.z < 0.0 { -h } else { h })
    }

    /// `f(V, L)·|cos θL|` (see the module docs).
    pub fn eval(&self, v: Vec3, l: Vec3, mode: Transport) -> Rgb {
        let cos_i = v.z;
        let cos_o = l.z;
        if cos_i == 0.0 {
            return Rgb::BLACK;
        }
        let eta = self.eta();
        let (brdf, bsdf) = self.weights();
        let base = self.base_color;
        let reflect = cos_i * cos_o > 0.0;
        let refract = cos_i * cos_o < 0.0;
        let front = cos_i > 0.0;
        let eta_path = if front { eta } else { 1.0 / eta };
        let Some(wh) = self.half(v, l, reflect, eta_path) else {
            return Rgb::BLACK;
        };
        let f = fresnel::dielectric(v.dot(wh), eta).r;
        let spec = specular_facets(self.roughness, self.anisotropic);
        let reflect_ok = compatible(wh, v, l, cos_i, true);
        let refract_ok = compatible(wh, v, l, cos_i, false);
        let mut value = Rgb::BLACK;
        let d = spec.d(wh);
        let g = spec.g(v, l, wh);
        if reflect && reflect_ok && f > 0.0 {
            let f_principled = if front {
                let cos = v.dot(wh);
                let eta_it = if cos >= 0.0 { eta } else { 1.0 / eta };
                let metal = schlick(base, cos, eta) * self.metallic;
                let tint = tint_of(base) * r0_of_eta(eta_it);
                let tinted = schlick(tint, cos, eta) * ((1.0 - self.metallic) * self.spec_tint);
                Rgb::gray((1.0 - self.metallic) * (1.0 - self.spec_tint) * f) + metal + tinted
            } else {
                Rgb::gray(bsdf * f)
            };
            value += f_principled * (d * g / (4.0 * cos_i.abs()));
        }
        if bsdf > 0.0 && refract && refract_ok && f < 1.0 {
            let scale = match mode {
                Transport::Radiance => 1.0 / (eta_path * eta_path),
                Transport::Importance => 1.0,
            };
            let (vh, lh) = (v.dot(wh), l.dot(wh));
            let denom = vh + eta_path * lh;
            let t = (scale * (1.0 - f) * d * g * eta_path * eta_path * vh * lh
                / (cos_i * denom * denom))
                .abs();
            if t.is_finite() {
                value += base.map(f32::sqrt) * (bsdf * t);
            }
        }
        if self.clearcoat > 0.0 && reflect && reflect_ok && front {
            let fcc = schlick(Rgb::gray(0.04), v.dot(wh), eta).r;
            let gtr = Gtr1 {
                alpha: 0.1 * (1.0 - self.clearcoat_gloss) + 0.001 * self.clearcoat_gloss,
            };
            let g = smith_ggx1(v, wh, 0.25) * smith_ggx1(l, wh, 0.25);
            value += Rgb::gray(0.25 * self.clearcoat * fcc * gtr.d(wh) * g * cos_o.abs());
        }
        if brdf > 0.0 && reflect && front {
            let weights = (schlick_weight(cos_o.abs()), schlick_weight(cos_i.abs()));
            let cos_d = wh.dot(l);
            let lobe = disney_diffuse(
                self.roughness,
                self.flatness,
                weights,
                cos_d,
                cos_o.abs() + cos_i.abs(),
            );
            value += base * (brdf * cos_o.abs() * FRAC_1_PI * lobe);
            if self.sheen > 0.0 && self.metallic < 1.0 {
                let fd = schlick_weight(cos_d.abs());
                let c_sheen = Rgb::WHITE.lerp(tint_of(base), self.sheen_tint);
                value += c_sheen * (self.sheen * (1.0 - self.metallic) * fd * cos_o.abs());
            }
        }
        value
    }

    /// The density with which [`Principled::sample`] draws `l`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        let cos_i = v.z;
        let cos_o = l.z;
        if cos_i == 0.0 {
            return 0.0;
        }
        let eta = self.eta();
        let front = cos_i > 0.0;
        // From behind, sampling goes on only through transmission.
        if !front && self.weights().1 <= 0.0 {
            return 0.0;
        }
        let eta_path = if front { eta } else { 1.0 / eta };
        let reflect = cos_i * cos_o > 0.0;
        let refract = cos_i * cos_o < 0.0;
        let Some(wh) = self.half(v, l, reflect, eta_path) else {
            return 0.0;
        };
        let f = fresnel::dielectric(v.dot(wh), eta).r;
        let [p_diffuse, p_clearcoat, p_trans, p_refl] = probabilities(self, front, f);
        let (vh, lh) = (v.dot(wh), l.dot(wh));
        let jacobian = if reflect {
            (1.0 / (4.0 * lh)).abs()
        } else {
            let denom = vh + eta_path * lh;
            (eta_path * eta_path * lh / (denom * denom)).abs()
        };
        let spec = specular_facets(self.roughness, self.anisotropic);
        let viewer = if front { v } else { -v };
        let visible = spec.visible_pdf(viewer, wh);
        let mut pdf = 0.0;
        if reflect && compatible(wh, v, l, cos_i, true) {
            pdf += p_refl * visible * jacobian;
            if p_clearcoat > 0.0 {
                let gtr = Gtr1 {
                    alpha: 0.1 * (1.0 - self.clearcoat_gloss) + 0.001 * self.clearcoat_gloss,
                };
                pdf += p_clearcoat * gtr.pdf(wh) * jacobian;
            }
        }
        if reflect && front {
            pdf += p_diffuse * cosine_pdf(l);
        }
        if refract && compatible(wh, v, l, cos_i, false) {
            pdf += p_trans * visible * jacobian;
        }
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// A direction by the lobes' probabilities, weighted by the whole value over the whole
    /// density.
    pub fn sample(&self, v: Vec3, u_lobe: f32, u: Vec2, mode: Transport) -> Option<BsdfSample> {
        let cos_i = v.z;
        if cos_i == 0.0 {
            return None;
        }
        let eta = self.eta();
        let front = cos_i > 0.0;
        let (_, bsdf) = self.weights();
        if !front && bsdf <= 0.0 {
            return None;
        }
        let spec = specular_facets(self.roughness, self.anisotropic);
        let viewer = if front { v } else { -v };
        let m = spec.sample_visible(viewer, u);
        let fm = fresnel::dielectric(v.dot(m), eta);
        let [p_diffuse, p_clearcoat, p_trans, _] = probabilities(self, front, fm.r);
        let l = if u_lobe < p_diffuse {
            sample_cosine(u)?
        } else if u_lobe < p_diffuse + p_clearcoat {
            let gtr = Gtr1 {
                alpha: 0.1 * (1.0 - self.clearcoat_gloss) + 0.001 * self.clearcoat_gloss,
            };
            let mc = gtr.sample(u);
            let l = reflect(-v, mc);
            if !(compatible(mc, v, l, cos_i, true) && cos_i * l.z > 0.0) {
                return None;
            }
            l
        } else if u_lobe < p_diffuse + p_clearcoat + p_trans {
            if fm.is_total() {
                return None;
            }
            let l = fresnel::refract(v, m, &fm);
            if !(compatible(m, v, l, cos_i, false) && cos_i * l.z < 0.0) {
                return None;
            }
            l
        } else {
            let l = reflect(-v, m);
            if !(compatible(m, v, l, cos_i, true) && cos_i * l.z > 0.0) {
                return None;
            }
            l
        };
        let l = l.normalize();
        BsdfSample::of_mixture(l, self.eval(v, l, mode), self.pdf(v, l))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specular_half_gives_the_index_of_glass() {
        assert!((eta_of_specular(0.5) - 1.5).abs() < 1e-5);
        assert!((r0_of_eta(eta_of_specular(0.5)) - 0.04).abs() < 1e-4);
    }

    #[test]
    fn a_white_principled_returns_what_mitsubas_does() {
        // Disney's diffuse does not subtract the specular and its retro-reflection brightens
        // grazing light: a white default principled returns more than it receives. Mitsuba
        // 3.9.1's own albedos of it (`bsdf.sample` averaged over 10⁵ draws, see
        // docs/materials.md) at 0°, 45°, 70° and 85°:
        let mitsuba = [
            (0.0f32, 1.0427),
            (45.0, 1.0496),
            (70.0, 1.1101),
            (85.0, 1.1839),
        ];
        let p = Principled {
            base_color: Rgb::WHITE,
            ..Principled::default()
        };
        for (deg, want) in mitsuba {
            let t = deg.to_radians();
            let v = Vec3::new(t.sin() * 0.7f32.cos(), t.sin() * 0.7f32.sin(), t.cos());
            let n = 200_000u64;
            let mut sum = 0.0f64;
            for i in 0..n {
                let u = Vec2::new(
                    (i as f32 + 0.5) / n as f32,
                    ((i * 7919) % n) as f32 / n as f32,
                );
                let u_lobe = ((i * 104_729) % n) as f32 / n as f32;
                if let Some(s) = p.sample(v, u_lobe, u, Transport::Radiance) {
                    sum += f64::from(s.weight.r);
                }
            }
            let e = sum / n as f64;
            assert!(
                (e - want).abs() < 0.005 * want,
                "{deg}°: {e} vs Mitsuba's {want}"
            );
        }
        // Black from behind without transmission, and never sampled there.
        let (v, l) = (Vec3::Z, Vec3::new(0.0, 0.6, 0.8));
        assert!(p.eval(-v, -l, Transport::Radiance).is_black());
        assert_eq!(p.pdf(-v, -l), 0.0);
    }
}
