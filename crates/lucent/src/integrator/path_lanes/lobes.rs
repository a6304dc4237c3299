//! What each surface lanes know does in a lane group: the light sample's BSDF value and
//! density and the BSDF sample, in lanes where the material's code is written once over
//! [`Real`] (Lambert, a smooth conductor, plastic), per lane where it is not (smooth glass); the
//! shared steps (a light's direction in the frame, the leak test, `Bsdf`'s guards). The rough
//! surfaces are `rough.rs`.

use glam::{Vec2, Vec3};
use wide::f32x8;

use crate::Rgb;
use crate::bsdf::lambert::{lambert_eval, lambert_pdf, lambert_sample};
use crate::bsdf::plastic::{self, PlasticLight, PlasticSample};
use crate::bsdf::{Bsdf, Frame, FrameOf, Transport};
use crate::lanes::{Mask as _, Real, V3};
use crate::material::{ScatteringSample, unleaked};

/// Smooth glass's sample in one lane, as `Scattering::sample` draws it from its one part of
/// weight 1: with the lobe's number `u_part` already rescaled to the part (itself, clamped
/// below 1), the scalar BSDF's sample in the frame, then the direction in the world and the
/// leak test ([`unleaked`]); the weight and density times 1, the same bits.
#[inline(always)]
pub(super) fn glass_sample(
    frame: &Frame,
    (wo, wo_local, ng): (Vec3, Vec3, Vec3),
    u_part: f32,
    (eta, specular, transmittance): (f32, Rgb, Rgb),
) -> Option<ScatteringSample> {
    let bsdf = Bsdf::Dielectric {
        eta,
        specular,
        transmittance,
    };
    let s = bsdf.sample(wo_local, u_part, Vec2::ZERO, Transport::Radiance)?;
    let (wi, reflected) = unleaked(frame, ng, (wo, wo_local), s.wi)?;
    Some(ScatteringSample {
        wi,
        weight: s.weight,
        pdf: s.pdf,
        delta: s.delta,
        reflected,
    })
}

/// The mirror direction of a smooth conductor: where it is usable (the mask: the viewer above
/// the surface, and the reflection not leaking through it), the world direction (normalised, as
/// [`Scattering`] returns it).
///
/// [`Scattering`]: crate::material::Scattering
#[inline(always)]
pub(super) fn mirror_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    wo: V3<f32x8>,
    wo_local: V3<f32x8>,
) -> (f32x8, V3<f32x8>) {
    let zero = f32x8::ZERO;
    let local = V3::new(-wo_local.x, -wo_local.y, wo_local.z);
    let finite = local.x.finite() & local.y.finite() & local.z.finite();
    let wi = frame.to_world(local).normalize();
    // Scattering::sample's leak test: a reflection stays on the viewer's side.
    let same_side = wi.dot(ng).gt(zero).same(wo.dot(ng).gt(zero));
    (wo_local.z.gt(zero) & finite & same_side, wi)
}

/// For a light along `local` in the frame (`consistent` where it does not leak through the
/// surface, [`light_local`]): where it reaches the front of a Lambertian part (the mask),
/// `cos θi/π` — [`Scattering`]'s value without the albedo — and the part's density of sampling
/// it (0 where it leaks).
///
/// [`Scattering`]: crate::material::Scattering
#[inline(always)]
pub(super) fn lambert_value_and_pdf(
    wo_local: V3<f32x8>,
    (consistent, local): (f32x8, V3<f32x8>),
) -> ((f32x8, f32x8), f32x8) {
    let zero = f32x8::ZERO;
    let (front, cos_over_pi) = lambert_eval(wo_local, local);
    // Bsdf::pdf keeps only finite, positive densities (Scattering::eval_pdf's sum over one part
    // of weight 1, divided by the total weight 1, gives the same bits).
    let p = lambert_pdf(wo_local, local);
    let usable = consistent & p.finite() & p.gt(zero);
    let pdf = <f32x8 as Real>::select(usable, p, zero);
    ((front & consistent, cos_over_pi), pdf)
}

/// The BSDF sample of a Lambertian part from `(ux, uy)`: where it is usable (the mask: above
/// the surface, a positive finite density, not leaking through it), the world direction
/// (normalised, as [`Scattering`] returns it) and its density.
///
/// [`Scattering`]: crate::material::Scattering
#[inline(always)]
pub(super) fn lambert_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    wo: V3<f32x8>,
    wo_local: V3<f32x8>,
    (ux, uy): (f32x8, f32x8),
) -> (f32x8, V3<f32x8>, f32x8) {
    let (ok, local, pdf) = lambert_sample(wo_local, ux, uy);
    // Bsdf::sample's test of a useful sample (the albedo is finite and not black).
    let useful = ok & pdf.gt(f32x8::ZERO) & pdf.finite();
    let (leaves, wi) = leaving(frame, ng, (wo, wo_local), local);
    (useful & leaves, wi, pdf)
}

/// The world direction of a sampled `local` direction (normalised, as [`Scattering`] returns
/// it) in `frame` for the viewer at `wo`, and where the path may leave along it: `local` is
/// finite (`Bsdf::sample`'s test) and does not leak, the side the sample chose agreeing with
/// the geometric normal's ([`unleaked`] in lanes).
///
/// [`Scattering`]: crate::material::Scattering
#[inline(always)]
pub(super) fn leaving(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    (wo, wo_local): (V3<f32x8>, V3<f32x8>),
    local: V3<f32x8>,
) -> (f32x8, V3<f32x8>) {
    let zero = f32x8::ZERO;
    let finite = local.x.finite() & local.y.finite() & local.z.finite();
    let wi = frame.to_world(local).normalize();
    let reflected = local.z.gt(zero).same(wo_local.z.gt(zero));
    let same_side = wi.dot(ng).gt(zero).same(wo.dot(ng).gt(zero));
    (finite & same_side.same(reflected), wi)
}

/// `Bsdf::eval`'s and `Bsdf::pdf`'s guards on a light sample's value and density (a value
/// that is not finite is black; a density that is not finite and positive is 0).
/// Scattering::eval_pdf's sum over one part of weight 1 gives the same bits.
#[inline(always)]
pub(super) fn guarded(f: Rgb, pdf: f32) -> (Rgb, f32) {
    let f = if f.is_finite() { f } else { Rgb::BLACK };
    (
        f,
        if pdf.is_finite() && pdf > 0.0 {
            pdf
        } else {
            0.0
        },
    )
}

/// A sample as `Bsdf::sample` keeps it (a positive finite density, a finite weight that is not
/// black), not a Dirac lobe's. Scattering::sample's one part of weight 1: the same bits.
#[inline(always)]
pub(super) fn kept(wi: Vec3, weight: Rgb, pdf: f32, reflected: bool) -> Option<ScatteringSample> {
    let useful = pdf > 0.0 && pdf.is_finite() && weight.is_finite() && !weight.is_black();
    useful.then_some(ScatteringSample {
        wi,
        weight,
        pdf,
        delta: false,
        reflected,
    })
}

/// A light's world direction `wi` in the frame, and where it does not leak: the shading and the
/// geometric normal put it on the same side (`Part::local`).
#[inline(always)]
pub(super) fn light_local(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    wi: V3<f32x8>,
) -> (f32x8, V3<f32x8>) {
    let local = frame.to_local(wi);
    let consistent = wi.dot(ng).gt(f32x8::ZERO).same(local.z.gt(f32x8::ZERO));
    (consistent, local)
}

/// Plastic's value and density for a light in lane `j` of the lanes' terms `l`
/// ([`plastic::value_and_pdf`]), where the light does not leak (`consistent`): `Plastic::eval`
/// and `pdf` (`base` times the lane's factor), then `Bsdf`'s guards.
#[inline(always)]
pub(super) fn plastic_light_lane(
    l: &PlasticLight<f32x8>,
    consistent: bool,
    j: usize,
    base: Rgb,
) -> (Rgb, f32) {
    if !consistent || l.front.to_bitmask() & (1 << j) == 0 {
        return (Rgb::BLACK, 0.0);
    }
    guarded(base * l.factor.as_array()[j], l.pdf.as_array()[j])
}

/// Plastic's BSDF sample in lanes with the lobe's number `u_lobe` (rescaled to the part) and
/// the base's `u`: where it is usable (the mask), the world direction, the colourless sample.
#[inline(always)]
pub(super) fn plastic_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    (wo, wo_local): (V3<f32x8>, V3<f32x8>),
    (eta, w): (f32x8, f32x8),
    (u_lobe, u): (f32x8, (f32x8, f32x8)),
) -> (f32x8, V3<f32x8>, PlasticSample<f32x8>) {
    let s = plastic::sampled(eta, w, wo_local, (u_lobe, u));
    let (leaves, wi) = leaving(frame, ng, (wo, wo_local), s.wi);
    (s.ok & leaves, wi, s)
}

/// Plastic's sample in lane `j` of [`plastic_bounce`]'s: the coat's mirror (`specular` times
/// the factor, a Dirac lobe) or the base (`base` times it), kept where `Bsdf::sample` keeps
/// it.
#[inline(always)]
pub(super) fn plastic_sample_lane(
    (wi, s, j): (Vec3, &PlasticSample<f32x8>, usize),
    (base, specular): (Rgb, Rgb),
) -> Option<ScatteringSample> {
    let coat = s.coat.to_bitmask() & (1 << j) != 0;
    let weight = if coat { specular } else { base } * s.factor.as_array()[j];
    kept(wi, weight, s.pdf.as_array()[j], true).map(|k| ScatteringSample { delta: coat, ..k })
}
