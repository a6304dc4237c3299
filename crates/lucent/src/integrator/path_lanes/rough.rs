//! The rough surfaces lanes know — conductors and glass with GGX facets — in a lane group: the
//! light sample's value and density and the BSDF sample written once over [`Real`]
//! (`rough_conductor::reflection` and `mirrored`, `rough_dielectric::value_and_pdf` and
//! `sampled`) and run here on eight paths; their colours (Fresnel reflectance of a conductor,
//! tints) and `Bsdf`'s guards per lane.

use glam::Vec3;
use wide::f32x8;

use super::lobes::{guarded, kept, leaving};
use crate::Rgb;
use crate::bsdf::FrameOf;
use crate::bsdf::fresnel;
use crate::bsdf::ggx::Ggx;
use crate::bsdf::rough_conductor::{Reflection, mirrored};
use crate::bsdf::rough_dielectric::{Sampled, Scatter, sampled};
use crate::lanes::{Real, V3};
use crate::material::ScatteringSample;

/// Whether lane `j` of `mask` is set.
#[inline(always)]
fn on(mask: f32x8, j: usize) -> bool {
    mask.to_bitmask() & (1 << j) != 0
}

/// A rough conductor's value and density for a light in one lane, from the lanes' colourless
/// terms `r` (lane `j`, `rough_conductor::reflection`) where the light does not leak
/// (`consistent`): `RoughConductor::eval` and `pdf`, then `Bsdf`'s guards.
#[inline(always)]
pub(super) fn rough_light_lane(
    r: &Reflection<f32x8>,
    consistent: bool,
    j: usize,
    (eta, k, specular): (Rgb, Rgb, Rgb),
) -> (Rgb, f32) {
    if !consistent {
        return (Rgb::BLACK, 0.0);
    }
    let front = on(r.front, j);
    let (value, pdf) = (r.value.as_array()[j], r.pdf.as_array()[j]);
    let f = if front && value > 0.0 {
        specular * fresnel::conductor(r.cos.as_array()[j], eta, k) * value
    } else {
        Rgb::BLACK
    };
    guarded(f, if front { pdf } else { 0.0 })
}

/// A rough conductor's BSDF sample in lanes from `(ux, uy)`: where it is usable (the mask:
/// the viewer and the mirrored direction above the surface, not leaking through it), the
/// world direction, the Fresnel cosine, `G1(wi, m)` and the density. The lane's weight is
/// `specular·F(cos)·G1`, its last test [`rough_sample_lane`]'s.
#[inline(always)]
pub(super) fn rough_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    (wo, wo_local): (V3<f32x8>, V3<f32x8>),
    ggx: Ggx<f32x8>,
    u: (f32x8, f32x8),
) -> (f32x8, V3<f32x8>, (f32x8, f32x8, f32x8)) {
    let s = mirrored(ggx, wo_local, u);
    let (leaves, wi) = leaving(frame, ng, (wo, wo_local), s.wi);
    (
        wo_local.z.gt(f32x8::ZERO) & s.above & leaves,
        wi,
        (s.cos, s.g1, s.pdf),
    )
}

/// A rough conductor's sample in lane `j` of [`rough_bounce`]'s: the weight
/// `specular·F(wo·m)·G1(wi, m)`, kept where `Bsdf::sample` keeps it (a positive finite density,
/// a finite weight that is not black). Scattering::sample's one part of weight 1: the same
/// bits.
#[inline(always)]
pub(super) fn rough_sample_lane(
    wi: Vec3,
    (cos, g1, pdf): (f32, f32, f32),
    (eta, k, specular): (Rgb, Rgb, Rgb),
) -> Option<ScatteringSample> {
    kept(
        wi,
        specular * fresnel::conductor(cos, eta, k) * g1,
        pdf,
        true,
    )
}

/// Rough glass's value and density for a light in lane `j` of the lanes' terms `s`
/// (`rough_dielectric::value_and_pdf`), where the light does not leak (`consistent`):
/// `RoughDielectric::eval` and `pdf` (the tint of the lobe `wi` is in), then `Bsdf`'s guards.
#[inline(always)]
pub(super) fn rough_glass_light_lane(
    s: &Scatter<f32x8>,
    consistent: bool,
    j: usize,
    (specular, transmittance): (Rgb, Rgb),
) -> (Rgb, f32) {
    if !consistent || !on(s.linked, j) {
        return (Rgb::BLACK, 0.0);
    }
    let tint = if on(s.reflect, j) {
        specular
    } else {
        transmittance
    };
    guarded(tint * s.value.as_array()[j], s.pdf.as_array()[j])
}

/// Rough glass's BSDF sample in lanes with the lobe's number `u_lobe` (already rescaled to the
/// part) and the facet's `u`: where it is usable (the mask: a facet seen, the direction on the
/// side its lobe needs, finite, not leaking), the world direction, and the colourless sample.
#[inline(always)]
pub(super) fn rough_glass_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    (wo, wo_local): (V3<f32x8>, V3<f32x8>),
    (ggx, eta): (Ggx<f32x8>, f32x8),
    (u_lobe, u): (f32x8, (f32x8, f32x8)),
) -> (f32x8, V3<f32x8>, Sampled<f32x8>) {
    let s = sampled(ggx, eta, wo_local, (u_lobe, u), false);
    let (leaves, wi) = leaving(frame, ng, (wo, wo_local), s.wi);
    (s.ok & leaves, wi, s)
}

/// Rough glass's sample in lane `j` of [`rough_glass_bounce`]'s, the viewer at `wo_z` in the
/// frame: its tint times the colourless weight, kept where `Bsdf::sample` keeps it.
/// Scattering::sample's one part of weight 1: the same bits.
#[inline(always)]
pub(super) fn rough_glass_sample_lane(
    (wi, s, j): (Vec3, &Sampled<f32x8>, usize),
    wo_z: f32,
    (specular, transmittance): (Rgb, Rgb),
) -> Option<ScatteringSample> {
    let tint = if on(s.reflect, j) {
        specular
    } else {
        transmittance
    };
    let weight = tint * s.weight.as_array()[j];
    let reflected = (s.wi.z.as_array()[j] > 0.0) == (wo_z > 0.0);
    kept(wi, weight, s.pdf.as_array()[j], reflected)
}
