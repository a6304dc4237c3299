//! The thin-surface Disney BSDF as Mitsuba 3 computes it (`principledthin`; Burley 2015): a
//! sheet with no inside (leaves, paper, cloth), the same from both sides.
//!
//! With `V` turned to the front and `L` with it, the lobes, weighted by `spec_trans` and
//! `diff_trans` (read as half its 0–2 value), are:
//! - **specular reflection**, `spec_trans·F·D·G/(4 cos θV)`, anisotropic GGX of the Disney
//!   roughness, `F` the dielectric Fresnel of `eta` blended towards a tinted Schlick by
//!   `spec_tint` (there only where `spec_trans > 0`, as in Mitsuba);
//! - **specular transmission** straight through the sheet, the reflection mirrored to the back
//!   with the roughness scaled by `0.65·eta − 0.35` (Burley 2015, figure 15):
//!   `spec_trans·base·(1 − F)·D·G/(4 cos θV)`;
//! - **diffuse** with retro-reflection, fake subsurface and sheen, as the principled BSDF's,
//!   weighted by `(1 − spec_trans)(1 − diff_trans)`;
//! - **diffuse transmission**, Lambertian through the sheet, `(1 − spec_trans)·diff_trans·
//!   base/π`.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::principled::{
    compatible, disney_diffuse, r0_of_eta, schlick, schlick_weight, specular_facets, tint_of,
};
use super::{BsdfSample, fresnel};
use crate::Rgb;
use crate::optics::reflect;

/// The thin principled BSDF's parameters at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledThin {
    /// The base colour.
    pub base_color: Rgb,
    /// Perceptual roughness.
    pub roughness: f32,
    /// Anisotropy of the specular lobes.
    pub anisotropic: f32,
    /// The share of specular transmission (and of the specular lobes).
    pub spec_trans: f32,
    /// Diffuse transmission, 0 to 2 (Mitsuba's range; its half is the share).
    pub diff_trans: f32,
    /// Tint of the specular reflection towards the base colour.
    pub spec_tint: f32,
    /// Strength of the sheen.
    pub sheen: f32,
    /// Tint of the sheen.
    pub sheen_tint: f32,
    /// Blend of the diffuse lobe towards the fake subsurface.
    pub flatness: f32,
    /// The sheet's index of refraction.
    pub eta: f32,
}

impl Default for PrincipledThin {
    /// Mitsuba's defaults: grey 0.5, roughness 0.5, η 1.5, the rest 0.
    fn default() -> Self {
        Self {
            base_color: Rgb::gray(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            spec_trans: 0.0,
            diff_trans: 0.0,
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            eta: 1.5,
        }
    }
}

impl PrincipledThin {
    /// `diff_trans` as a share.
    fn diff_share(&self) -> f32 {
        0.5 * self.diff_trans
    }

    /// The lobes' probabilities: specular reflection, transmission, diffuse reflection and
    /// transmission.
    fn probabilities(&self) -> [f32; 4] {
        let (s, d) = (self.spec_trans, self.diff_share());
        let p = [0.5 * s, 0.5 * s, (1.0 - s) * (1.0 - d), (1.0 - s) * d];
        let sum: f32 = p.iter().sum();
        if sum > 0.0 && sum.is_finite() {
            p.map(|x| x / sum)
        } else {
            [0.0; 4]
        }
    }

    /// `v` and `l` turned so that `v` is in front.
    fn front(v: Vec3, l: Vec3) -> (Vec3, Vec3) {
        if v.z < 0.0 { (-v, -l) } else { (v, l) }
    }

    /// The half vector of `v` and `l` mirrored to `v`'s side.
    fn half(v: Vec3, l: Vec3) -> Option<Vec3> {
        (v + Vec3::new(l.x, l.y, l.z.abs())).try_normalize()
    }

    /// `f(V, L)·|cos θL|` (see the module docs).
    pub fn eval(&self, v: Vec3, l: Vec3) -> Rgb {
        if v.z == 0.0 {
            return Rgb::BLACK;
        }
        let (v, l) = Self::front(v, l);
        let (cos_i, cos_o) = (v.z, l.z);
        let reflect = cos_o > 0.0;
        let refract = cos_o < 0.0;
        let Some(wh) = Self::half(v, l) else {
            return Rgb::BLACK;
        };
        let base = self.base_color;
        let (s, dt) = (self.spec_trans, self.diff_share());
        let eta = fresnel::sane_eta(self.eta);
        let mut value = Rgb::BLACK;
        if s > 0.0 {
            let f = fresnel::dielectric(v.dot(wh), eta).r;
            if reflect && compatible(wh, v, l, v.z, true) {
                let spec = specular_facets(self.roughness, self.anisotropic);
                let tinted = schlick(tint_of(base) * r0_of_eta(eta), v.dot(wh), eta);
                let f_thin = Rgb::gray(f).lerp(tinted, self.spec_tint);
                value += f_thin * (s * spec.d(wh) * spec.g(v, l, wh) / (4.0 * cos_i));
            }
            if refract && compatible(wh, v, l, v.z, false) {
                let spec = specular_facets((0.65 * eta - 0.35) * self.roughness, self.anisotropic);
                value += base * (s * (1.0 - f) * spec.d(wh) * spec.g(v, l, wh) / (4.0 * cos_i));
            }
        }
        if reflect && s < 1.0 && dt < 1.0 {
            let weights = (schlick_weight(cos_o.abs()), schlick_weight(cos_i));
            let cos_d = wh.dot(l);
            let lobe = disney_diffuse(
                self.roughness,
                self.flatness,
                weights,
                cos_d,
                cos_o.abs() + cos_i.abs(),
            );
            value += base * ((1.0 - s) * cos_o * FRAC_1_PI * (1.0 - dt) * lobe);
            if self.sheen > 0.0 {
                let fd = schlick_weight(cos_d.abs());
                let c_sheen = Rgb::WHITE.lerp(tint_of(base), self.sheen_tint);
                value += c_sheen * (self.sheen * (1.0 - s) * fd * (1.0 - dt) * cos_o.abs());
            }
        }
        if refract && s < 1.0 && dt > 0.0 {
            value += base * ((1.0 - s) * dt * FRAC_1_PI * cos_o.abs());
        }
        value
    }

    /// The density with which [`PrincipledThin::sample`] draws `l`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if v.z == 0.0 {
            return 0.0;
        }
        let (v, l) = Self::front(v, l);
        let reflect = l.z > 0.0;
        let refract = l.z < 0.0;
        let [p_sr, p_st, p_dr, p_dt] = self.probabilities();
        let mut pdf = 0.0;
        if self.spec_trans > 0.0
            && let Some(wh) = Self::half(v, l)
        {
            let lr = Vec3::new(l.x, l.y, l.z.abs());
            let jacobian = (1.0 / (4.0 * lr.dot(wh))).abs();
            let eta = fresnel::sane_eta(self.eta);
            if reflect && compatible(wh, v, l, v.z, true) {
                let spec = specular_facets(self.roughness, self.anisotropic);
                pdf += p_sr * spec.visible_pdf(v, wh) * jacobian;
            }
            if refract && compatible(wh, v, l, v.z, false) {
                let spec = specular_facets((0.65 * eta - 0.35) * self.roughness, self.anisotropic);
                pdf += p_st * spec.visible_pdf(v, wh) * jacobian;
            }
        }
        if reflect {
            pdf += p_dr * cosine_pdf(l);
        }
        if refract {
            pdf += p_dt * cosine_pdf(-l);
        }
        if pdf.is_finite() { pdf } else { 0.0 }
    }

    /// A direction by the lobes' probabilities, weighted by the whole value over the whole
    /// density.
    pub fn sample(&self, v0: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if v0.z == 0.0 {
            return None;
        }
        let flip = v0.z < 0.0;
        let v = if flip { -v0 } else { v0 };
        let [p_sr, p_st, p_dr, _] = self.probabilities();
        let eta = fresnel::sane_eta(self.eta);
        let l = if u_lobe < p_sr {
            let spec = specular_facets(self.roughness, self.anisotropic);
            let m = spec.sample_visible(v, u);
            let l = reflect(-v, m);
            if !(l.z > 0.0 && compatible(m, v, l, v.z, true)) {
                return None;
            }
            l
        } else if u_lobe < p_sr + p_st {
            let spec = specular_facets((0.65 * eta - 0.35) * self.roughness, self.anisotropic);
            let m = spec.sample_visible(v, u);
            let mut l = reflect(-v, m);
            l.z = -l.z;
            if !(l.z < 0.0 && compatible(m, v, l, v.z, false)) {
                return None;
            }
            l
        } else if u_lobe < p_sr + p_st + p_dr {
            sample_cosine(u)?
        } else {
            -sample_cosine(u)?
        };
        let l = if flip { -l } else { l };
        BsdfSample::of_mixture(l, self.eval(v0, l), self.pdf(v0, l))
    }
}
