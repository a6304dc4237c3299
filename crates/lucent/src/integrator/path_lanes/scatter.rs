//! The scatter of a lane group's paths at the surfaces lanes know: frames, light samples' BSDF
//! values and densities and BSDF samples in lanes; lights picked, shadow rays, bounces and
//! Russian roulette per path.

use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};
use wide::f32x8;

use super::LaneHit;
use super::lobes::{
    glass_sample, lambert_bounce, lambert_value_and_pdf, light_local, mirror_bounce,
    plastic_bounce, plastic_light_lane, plastic_sample_lane,
};
use super::rough::{
    rough_bounce, rough_glass_bounce, rough_glass_light_lane, rough_glass_sample_lane,
    rough_light_lane, rough_sample_lane,
};
use super::surfaces::LaneBsdf;
use crate::Rgb;
use crate::bsdf::ggx::Ggx;
use crate::bsdf::rough_conductor::reflection;
use crate::bsdf::{Frame, FrameOf, fresnel};
use crate::bsdf::{plastic, rough_dielectric};
use crate::integrator::RayStats;
use crate::integrator::path::{Arrival, Path, PathTracer};
use crate::integrator::vertex::{leave, light_through};
use crate::lanes::{LANES, Real, V3};
use crate::material::{Geometry, ScatteringSample, facing_lanes};
use crate::sampling::sobol::Sampler;
use crate::scene::Scene;

impl PathTracer {
    /// The scatter of every path in `batch`: the shading frames, the light samples' BSDF values
    /// and densities and the BSDF samples in lanes; the lights picked, the shadow rays, the
    /// bounces and Russian roulette per path. Returns the lanes whose paths ended; marks in
    /// `untraceable` those that met a ray they could not trace.
    #[inline(always)]
    pub(super) fn scatter_lanes(
        &self,
        scene: &Scene,
        batch: &[LaneHit],
        paths: &mut [Path],
        untraceable: &mut u32,
        stats: &mut RayStats,
    ) -> u32 {
        let k = batch.len();
        // Lanes past the batch repeat its first path; their results are not read.
        let of = |j: usize| &batch[if j < k { j } else { 0 }];
        let vec = |f: &dyn Fn(&LaneHit) -> Vec3| V3::gather(&std::array::from_fn(|j| f(of(j))));
        let mask = |f: &dyn Fn(&LaneHit) -> bool| {
            let bits: [u32; LANES] = std::array::from_fn(|j| if f(of(j)) { !0 } else { 0 });
            wide::bytemuck::cast::<[u32; LANES], f32x8>(bits)
        };

        // The part Resolve makes of a leaf (material/scattering.rs): seen from the back, a
        // two-sided reflector turns its normals round (glass, which transmits, does not); the
        // shading normal then faces the viewer ([`crate::material::facing`]); the frame follows
        // ∂p/∂u.
        let dir = vec(&|h| paths[h.lane].ray.dir);
        let wo = -dir;
        let ng = vec(&|h| h.hit.normal);
        let geometry: [Geometry; LANES] = std::array::from_fn(|j| Geometry::of_hit(&of(j).hit));
        let ns = V3::gather(&std::array::from_fn(|j| geometry[j].n));
        let dpdu = V3::gather(&std::array::from_fn(|j| geometry[j].dpdu));
        let flip = ng.dot(dir).gt(f32x8::ZERO) & mask(&|h| h.two_sided && !h.bsdf.transmits());
        let (ns, ng) = (V3::select(flip, -ns, ns), V3::select(flip, -ng, ng));
        let ns = facing_lanes(ns, ng, wo);
        let frame = FrameOf::from_normal_tangent(ns, dpdu);
        let wo_local = frame.to_local(wo);

        // Light sampling, where the surface is not a mirror (whose Dirac lobe no light sample
        // can meet): the lights sampled per path, their BSDF values in lanes.
        let lanes_of = |kind: fn(&LaneBsdf) -> bool| -> ArrayVec<usize, LANES> {
            (0..k).filter(|&j| kind(&batch[j].bsdf)).collect()
        };
        let samplers_of = |lanes: &[usize], pick: fn(&Arrival) -> Sampler| -> ArrayVec<_, LANES> {
            lanes.iter().map(|&j| pick(&batch[j].at)).collect()
        };
        // Lambert, the rough surfaces and plastic with a base: those with lobes that are not
        // Dirac deltas.
        let diffuse = lanes_of(|b| {
            matches!(
                b,
                LaneBsdf::Lambert(_)
                    | LaneBsdf::RoughMirror { .. }
                    | LaneBsdf::RoughGlass { .. }
                    | LaneBsdf::Plastic { delta: false, .. }
            )
        });
        let mut samplers = samplers_of(&diffuse, |at| at.u_light);
        let u_pick = Sampler::next_1d_lanes(&mut samplers);
        let u_light = Sampler::next_2d_lanes(&mut samplers);
        let points: ArrayVec<Vec3, LANES> = diffuse.iter().map(|&j| batch[j].hit.point).collect();
        let lights = at_lanes(
            &diffuse,
            scene
                .emitters
                .sample_lanes(&scene.lights, &points, &u_pick, &u_light),
            None,
        );
        let wi = V3::gather(&std::array::from_fn(|j| {
            lights[j].map_or(Vec3::Z, |s| s.wi)
        }));
        // The light in each frame, and where it does not leak; the same for every material.
        let (lit, local_wi) = light_local(&frame, ng, wi);
        let ((front, cos_over_pi), pdf_lanes) = lambert_value_and_pdf(wo_local, (lit, local_wi));
        // The rough and plastic surfaces' parameters in lanes — GGX facets (roughness 1
        // elsewhere), a dielectric coat's or glass's index (1.5 elsewhere), a plastic's specular
        // sampling weight (½ elsewhere) — gathered only for the kinds the group holds.
        let any = |kind: fn(&LaneBsdf) -> bool| batch.iter().any(|h| kind(&h.bsdf));
        let rough = any(|b| matches!(b, LaneBsdf::RoughMirror { .. }));
        let rough_glass = any(|b| matches!(b, LaneBsdf::RoughGlass { .. }));
        let plastic = any(|b| matches!(b, LaneBsdf::Plastic { .. }));
        let lanes_with = |param: fn(&LaneBsdf) -> Option<f32>, default: f32| {
            f32x8::new(std::array::from_fn(|j| {
                param(&of(j).bsdf).unwrap_or(default)
            }))
        };
        let ggx = (rough || rough_glass).then(|| Ggx {
            alpha_u: lanes_with(|b| b.alpha().map(|a| a.0), 1.0),
            alpha_v: lanes_with(|b| b.alpha().map(|a| a.1), 1.0),
        });
        let eta = (rough_glass || plastic).then(|| lanes_with(LaneBsdf::eta, 1.5));
        let rough_ggx = ggx.filter(|_| rough);
        let glass_facets = ggx.zip(eta).filter(|_| rough_glass);
        let plastic_coat = eta
            .filter(|_| plastic)
            .map(|eta| (eta, lanes_with(LaneBsdf::sampling_weight, 0.5)));
        let rough_light = rough_ggx.map(|ggx| reflection(ggx, wo_local, local_wi));
        let rough_glass_light = glass_facets.map(|(ggx, eta)| {
            rough_dielectric::value_and_pdf(ggx, eta, (wo_local, local_wi), false)
        });
        let plastic_light =
            plastic_coat.map(|(eta, w)| plastic::value_and_pdf(eta, w, (wo_local, local_wi)));

        // BSDF sampling's numbers: the lobe's dimension is spent (Lambert has one lobe), the
        // direction's drawn (a mirror draws none).
        let mut samplers = samplers_of(&diffuse, |at| {
            let mut u = at.u_bsdf;
            u.defer(1);
            u
        });
        let u_bsdf = at_lanes(
            &diffuse,
            Sampler::next_2d_lanes(&mut samplers),
            Vec2::splat(0.5),
        );
        let ux = f32x8::new(u_bsdf.map(|u| u.x));
        let uy = f32x8::new(u_bsdf.map(|u| u.y));
        let (cosine_ok, cosine_wi, cosine_pdf) = lambert_bounce(&frame, ng, wo, wo_local, (ux, uy));
        let (mirror_ok, mirror_wi) = mirror_bounce(&frame, ng, wo, wo_local);
        let rough_sample =
            rough_ggx.map(|ggx| rough_bounce(&frame, ng, (wo, wo_local), ggx, (ux, uy)));
        // Glass picks reflection or refraction, plastic its coat or its base, with the lobe's
        // number (smooth glass's direction's numbers are not used; the others' are those drawn
        // above), rescaled to its one part as Scattering::sample rescales it (itself, clamped
        // below 1).
        let picking = lanes_of(|b| b.transmits() || matches!(b, LaneBsdf::Plastic { .. }));
        let mut samplers = samplers_of(&picking, |at| at.u_bsdf);
        let u_lobe = at_lanes(&picking, Sampler::next_1d_lanes(&mut samplers), 0.0)
            .map(|u| u.clamp(0.0, 1.0 - f32::EPSILON));
        let u = (f32x8::new(u_lobe), (ux, uy));
        let plastic_sample =
            plastic_coat.map(|coat| plastic_bounce(&frame, ng, (wo, wo_local), coat, u));
        let rough_glass_sample =
            glass_facets.map(|glass| rough_glass_bounce(&frame, ng, (wo, wo_local), glass, u));

        let (lit, front, cosine_ok, mirror_ok) = (
            lit.to_bitmask(),
            front.to_bitmask(),
            cosine_ok.to_bitmask(),
            mirror_ok.to_bitmask(),
        );
        let mut ended = 0;
        for (j, h) in batch.iter().enumerate() {
            let before = stats.untraceable;
            let path = &mut paths[h.lane];
            let on = |bits: u32| bits & (1 << j) != 0;
            let consistent = on(lit);
            // The BSDF's value and density for the light sample where the surface has one, and
            // the BSDF sample.
            let (value, sample) = match h.bsdf {
                LaneBsdf::Lambert(albedo) => {
                    // Bsdf::eval's guard. (Scattering::eval_pdf adds this one part, of weight
                    // 1, to black: the same bits.)
                    let f = albedo * cos_over_pi.as_array()[j];
                    let f = if on(front) && f.is_finite() {
                        f
                    } else {
                        Rgb::BLACK
                    };
                    let value = (f, pdf_lanes.as_array()[j]);
                    // Lambert::sample and Bsdf::sample: no sample of a black albedo, nor of
                    // one that is not finite. Scattering::sample's sample of one part of weight
                    // 1: its weight and density times 1, the same bits.
                    let useful = albedo.is_finite() && !albedo.is_black();
                    let sample = (useful && on(cosine_ok)).then(|| ScatteringSample {
                        wi: cosine_wi.lane(j),
                        weight: albedo,
                        pdf: cosine_pdf.as_array()[j],
                        delta: false,
                        reflected: true,
                    });
                    (Some(value), sample)
                }
                LaneBsdf::Glass {
                    eta,
                    specular,
                    transmittance,
                } => {
                    let frame = Frame {
                        s: frame.s.lane(j),
                        t: frame.t.lane(j),
                        n: frame.n.lane(j),
                    };
                    let sample = glass_sample(
                        &frame,
                        (wo.lane(j), wo_local.lane(j), ng.lane(j)),
                        u_lobe[j],
                        (eta, specular, transmittance),
                    );
                    (None, sample)
                }
                LaneBsdf::RoughMirror {
                    eta, k, specular, ..
                } => {
                    let colours = (eta, k, specular);
                    let value = rough_light
                        .as_ref()
                        .map(|r| rough_light_lane(r, consistent, j, colours));
                    let sample = rough_sample.as_ref().and_then(|(ok, wi, (cos, g1, pdf))| {
                        let terms = (cos.as_array()[j], g1.as_array()[j], pdf.as_array()[j]);
                        on(ok.to_bitmask())
                            .then(|| rough_sample_lane(wi.lane(j), terms, colours))
                            .flatten()
                    });
                    (value, sample)
                }
                LaneBsdf::RoughGlass {
                    specular,
                    transmittance,
                    ..
                } => {
                    let tints = (specular, transmittance);
                    let value = rough_glass_light
                        .as_ref()
                        .map(|r| rough_glass_light_lane(r, consistent, j, tints));
                    let sample = rough_glass_sample.as_ref().and_then(|(ok, wi, s)| {
                        let wo_z = wo_local.z.as_array()[j];
                        on(ok.to_bitmask())
                            .then(|| rough_glass_sample_lane((wi.lane(j), s, j), wo_z, tints))
                            .flatten()
                    });
                    (value, sample)
                }
                LaneBsdf::Plastic { base, specular, .. } => {
                    let value = plastic_light
                        .as_ref()
                        .map(|l| plastic_light_lane(l, consistent, j, base));
                    let sample = plastic_sample.as_ref().and_then(|(ok, wi, s)| {
                        on(ok.to_bitmask())
                            .then(|| plastic_sample_lane((wi.lane(j), s, j), (base, specular)))
                            .flatten()
                    });
                    (value, sample)
                }
                LaneBsdf::Mirror { eta, k, specular } => {
                    // Conductor::sample: the tint times the Fresnel reflectance at the
                    // viewer's cosine; Bsdf::sample keeps a finite weight that is not black.
                    let weight = specular * fresnel::conductor(wo_local.z.as_array()[j], eta, k);
                    let useful = weight.is_finite() && !weight.is_black();
                    let sample = (useful && on(mirror_ok)).then(|| ScatteringSample {
                        wi: mirror_wi.lane(j),
                        weight,
                        pdf: 1.0,
                        delta: true,
                        reflected: true,
                    });
                    (None, sample)
                }
            };
            // The light sample (drawn where the surface is not a Dirac delta) through its
            // shadow ray, weighted by the BSDF's value and density.
            if let (Some(s), Some(f_pdf)) = (&lights[j], value) {
                path.l += path.beta * light_through(scene, &h.hit, s, f_pdf, true, stats);
            }
            let b = sample.and_then(|s| leave(&h.hit, s, stats));
            if !self.go_on(path, b, &h.hit, h.at.u_rr) {
                ended |= 1 << h.lane;
            }
            if stats.untraceable != before {
                *untraceable |= 1 << h.lane;
            }
        }
        ended
    }
}

/// The `values` of the group's lanes `lanes` in order, as an array over all lanes, `default`
/// in the others.
#[inline(always)]
fn at_lanes<T: Copy>(
    lanes: &[usize],
    values: impl IntoIterator<Item = T>,
    default: T,
) -> [T; LANES] {
    let mut out = [default; LANES];
    for (&j, v) in lanes.iter().zip(values) {
        out[j] = v;
    }
    out
}
