//! Paths in lanes: the path tracer run on up to eight paths at once, bounce by bounce, with the
//! shading of the surfaces that lanes know ([`LaneMaterials`]: Lambertian surfaces, any albedo
//! texture, smooth conductors and smooth glass) done for all of them together in
//! [`wide::f32x8`] lanes, and everything else per path by the scalar path tracer's own steps
//! (`PathTracer::arrive`, the scalar scatter, [`light_through`], [`leave`],
//! `PathTracer::go_on`).
//!
//! The lane code is the scalar code: the shading frame, Lambert's value, density and sample, the
//! facing test, a triangle light's sample and the Sobol scrambles are written once (over
//! [`Real`], or as loops over lanes) and run by the scalar path tracer too. A path traced in a
//! lane therefore gets exactly the bits it gets alone — the test
//! `lanes_give_the_scalar_paths_bits` holds the two to that — and an image is the same with
//! lanes or without, on any number of threads.

use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};
use wide::f32x8;

use super::path::{Arrival, Path, PathTracer};
use super::vertex::{leave, light_through};
use super::{RayStats, UNTRACEABLE};
use crate::Rgb;
use crate::bsdf::lambert::{lambert_eval, lambert_pdf, lambert_sample};
use crate::bsdf::{Bsdf, FrameOf, Transport, fresnel};
use crate::lanes::{LANES, Mask as _, Real, V3};
use crate::material::{Geometry, ScatteringSample, Surface, facing_lanes};
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
use crate::texture::Texture;
use lucent_accel::Ray;

/// Which of a scene's materials the lanes shade, and how.
#[derive(Clone, Debug, Default)]
pub struct LaneMaterials<'a> {
    /// Per material: how lanes shade it, if they do.
    lanes: Vec<Option<LaneMaterial<'a>>>,
}

/// A material as lanes shade it.
#[derive(Clone, Copy, Debug)]
struct LaneMaterial<'a> {
    surface: LaneSurface<'a>,
    /// Whether the hit's vertex colour multiplies a Lambertian albedo.
    vertex_colors: bool,
    two_sided: bool,
}

/// The surfaces lanes know, with their textures.
#[derive(Clone, Copy, Debug)]
enum LaneSurface<'a> {
    /// Lambertian (Mitsuba's `diffuse`).
    Lambert { reflectance: &'a Texture },
    /// A smooth conductor (Mitsuba's `conductor`).
    Mirror {
        eta: &'a Texture,
        k: &'a Texture,
        specular: &'a Texture,
    },
    /// Smooth glass (Mitsuba's `dielectric`).
    Glass {
        eta: f32,
        specular: &'a Texture,
        transmittance: &'a Texture,
    },
}

/// What a lane's surface is at its hit, textures evaluated.
#[derive(Clone, Copy, Debug)]
enum LaneBsdf {
    /// Lambert's albedo.
    Lambert(Rgb),
    /// A smooth conductor's index and tint.
    Mirror { eta: Rgb, k: Rgb, specular: Rgb },
    /// Smooth glass's index and tints.
    Glass {
        eta: f32,
        specular: Rgb,
        transmittance: Rgb,
    },
}

impl<'a> LaneMaterials<'a> {
    /// The materials of `scene` that lanes shade: Lambertian surfaces (Mitsuba's `diffuse`),
    /// smooth conductors (`conductor`) and smooth glass (`dielectric`), their parameters
    /// colours or textures. Any other
    /// material is shaded per path.
    pub fn of(scene: &'a Scene) -> Self {
        let lanes = scene
            .materials
            .iter()
            .map(|m| {
                let surface = match &m.surface {
                    Surface::Diffuse { reflectance } => LaneSurface::Lambert { reflectance },
                    Surface::Conductor {
                        eta,
                        k,
                        specular,
                        roughness: None,
                    } => LaneSurface::Mirror { eta, k, specular },
                    Surface::Dielectric {
                        eta,
                        specular,
                        transmittance,
                        roughness: None,
                    } => LaneSurface::Glass {
                        eta: *eta,
                        specular,
                        transmittance,
                    },
                    _ => return None,
                };
                Some(LaneMaterial {
                    surface,
                    vertex_colors: m.vertex_colors,
                    two_sided: m.two_sided,
                })
            })
            .collect();
        Self { lanes }
    }

    /// Whether lanes shade any material of the scene.
    pub fn any(&self) -> bool {
        self.lanes.iter().any(Option::is_some)
    }
}

/// A path of a lane group that arrived at a surface lanes know this bounce.
struct LaneHit {
    /// Its lane.
    lane: usize,
    hit: SurfaceHit,
    at: Arrival,
    bsdf: LaneBsdf,
    two_sided: bool,
}

impl PathTracer {
    /// [`PathTracer::radiance_in`] for up to [`LANES`] camera rays at once (`samplers[i]` is
    /// ray `i`'s): the same radiance for each, bit for bit.
    ///
    /// On a processor with AVX2 the lanes' code is compiled for it (eight lanes a register,
    /// the Sobol scrambles' multiplications in vectors); the arithmetic is the same IEEE
    /// arithmetic (no fused multiply–adds), so the bits are the same either way.
    pub fn radiance_lanes(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: `radiance_lanes_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.radiance_lanes_avx2(scene, lanes, beam, rays, samplers, stats) };
        }
        self.radiance_lanes_with(scene, lanes, beam, rays, samplers, stats)
    }

    /// [`PathTracer::radiance_lanes`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn radiance_lanes_avx2(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        self.radiance_lanes_with(scene, lanes, beam, rays, samplers, stats)
    }

    /// The body of [`PathTracer::radiance_lanes`], inlined into each instruction set's version.
    #[inline(always)]
    fn radiance_lanes_with(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        let n = rays.len();
        assert!(
            n <= LANES && samplers.len() == n,
            "{n} rays, {} samplers",
            samplers.len()
        );
        let mut paths: ArrayVec<Path, LANES> = rays.iter().map(Path::new).collect();
        let mut alive: u32 = (1 << n) - 1;
        // Lanes whose path met a ray it could not trace: their estimate is dropped.
        let mut untraceable = 0u32;
        while alive != 0 {
            let mut batch = ArrayVec::<LaneHit, LANES>::new();
            let bounce_alive = alive;
            for lane in (0..n).filter(|&i| bounce_alive & (1 << i) != 0) {
                let before = stats.untraceable;
                let sampler = &mut samplers[lane];
                let go_on = self.arrive(
                    scene,
                    beam,
                    &mut paths[lane],
                    sampler,
                    stats,
                    |path, hit, at, stats| match lanes
                        .lanes
                        .get(hit.material as usize)
                        .copied()
                        .flatten()
                    {
                        Some(m) => {
                            batch.push(LaneHit {
                                lane,
                                bsdf: bsdf_at(scene, m, &hit, at.footprint),
                                two_sided: m.two_sided,
                                hit,
                                at,
                            });
                            true
                        }
                        None => self.scatter(scene, path, hit, at, stats),
                    },
                );
                if !go_on {
                    alive &= !(1 << lane);
                }
                if stats.untraceable != before {
                    untraceable |= 1 << lane;
                }
            }
            if !batch.is_empty() {
                alive &= !self.scatter_lanes(scene, &batch, &mut paths, &mut untraceable, stats);
            }
        }
        paths
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if untraceable & (1 << i) != 0 {
                    UNTRACEABLE
                } else {
                    p.l
                }
            })
            .collect()
    }

    /// The scatter of every path in `batch`: the shading frames, the light samples' BSDF values
    /// and densities and the BSDF samples in lanes; the lights picked, the shadow rays, the
    /// bounces and Russian roulette per path. Returns the lanes whose paths ended; marks in
    /// `untraceable` those that met a ray they could not trace.
    #[inline(always)]
    fn scatter_lanes(
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
        // two-sided reflector turns its normals round (glass, which transmits, does not); the shading normal then faces
        // the viewer ([`crate::material::facing`]), the frame follows ∂p/∂u.
        let dir = vec(&|h| paths[h.lane].ray.dir);
        let wo = -dir;
        let ng = vec(&|h| h.hit.normal);
        let geometry: [Geometry; LANES] = std::array::from_fn(|j| Geometry::of_hit(&of(j).hit));
        let ns = V3::gather(&std::array::from_fn(|j| geometry[j].n));
        let dpdu = V3::gather(&std::array::from_fn(|j| geometry[j].dpdu));
        let flip = ng.dot(dir).gt(f32x8::ZERO)
            & mask(&|h| h.two_sided && !matches!(h.bsdf, LaneBsdf::Glass { .. }));
        let (ns, ng) = (V3::select(flip, -ns, ns), V3::select(flip, -ng, ng));
        let ns = facing_lanes(ns, ng, wo);
        let frame = FrameOf::from_normal_tangent(ns, dpdu);
        let wo_local = frame.to_local(wo);

        // Light sampling, where the surface is not a mirror (whose Dirac lobe no light sample
        // can meet): the lights sampled per path, their BSDF values in lanes.
        let diffuse: ArrayVec<usize, LANES> = (0..k)
            .filter(|&j| matches!(batch[j].bsdf, LaneBsdf::Lambert(_)))
            .collect();
        let mut samplers: ArrayVec<Sampler, LANES> =
            diffuse.iter().map(|&j| batch[j].at.u_light).collect();
        let u_pick = Sampler::next_1d_lanes(&mut samplers);
        let u_light = Sampler::next_2d_lanes(&mut samplers);
        let points: ArrayVec<Vec3, LANES> = diffuse.iter().map(|&j| batch[j].hit.point).collect();
        let mut lights = [None; LANES];
        let sampled = scene
            .emitters
            .sample_lanes(&scene.lights, &points, &u_pick, &u_light);
        for (&j, s) in diffuse.iter().zip(sampled) {
            lights[j] = s;
        }
        let wi = V3::gather(&std::array::from_fn(|j| {
            lights[j].map_or(Vec3::Z, |s| s.wi)
        }));
        let ((front, cos_over_pi), pdf_lanes) = lambert_value_and_pdf(&frame, ng, wo_local, wi);

        // BSDF sampling's numbers: the lobe's dimension is spent (Lambert has one lobe), the
        // direction's drawn (a mirror draws none).
        let mut samplers: ArrayVec<Sampler, LANES> = diffuse
            .iter()
            .map(|&j| {
                let mut u = batch[j].at.u_bsdf;
                u.defer(1);
                u
            })
            .collect();
        let mut u_bsdf = [(0.5, 0.5); LANES];
        for (&j, u) in diffuse.iter().zip(Sampler::next_2d_lanes(&mut samplers)) {
            u_bsdf[j] = (u.x, u.y);
        }
        let ux = f32x8::new(std::array::from_fn(|j| u_bsdf[j].0));
        let uy = f32x8::new(std::array::from_fn(|j| u_bsdf[j].1));
        let (cosine_ok, cosine_wi, cosine_pdf) = lambert_bounce(&frame, ng, wo, wo_local, (ux, uy));
        let (mirror_ok, mirror_wi) = mirror_bounce(&frame, ng, wo, wo_local);
        // Glass picks reflection or refraction with the lobe's number (its direction's
        // numbers are not used).
        let glass: ArrayVec<usize, LANES> = (0..k)
            .filter(|&j| matches!(batch[j].bsdf, LaneBsdf::Glass { .. }))
            .collect();
        let mut samplers: ArrayVec<Sampler, LANES> =
            glass.iter().map(|&j| batch[j].at.u_bsdf).collect();
        let mut u_lobe = [0.0; LANES];
        for (&j, u) in glass.iter().zip(Sampler::next_1d_lanes(&mut samplers)) {
            u_lobe[j] = u;
        }

        let (front, cosine_ok, mirror_ok) = (
            front.to_bitmask(),
            cosine_ok.to_bitmask(),
            mirror_ok.to_bitmask(),
        );
        let mut ended = 0;
        for (j, h) in batch.iter().enumerate() {
            let before = stats.untraceable;
            let path = &mut paths[h.lane];
            let on = |bits: u32| bits & (1 << j) != 0;
            let sample = match h.bsdf {
                LaneBsdf::Lambert(albedo) => {
                    if let Some(s) = &lights[j] {
                        // Bsdf::eval's guard. (Scattering::eval_pdf adds this one part, of
                        // weight 1, to black: the same bits.)
                        let f = albedo * cos_over_pi.as_array()[j];
                        let f = if on(front) && f.is_finite() {
                            f
                        } else {
                            Rgb::BLACK
                        };
                        let pdf = pdf_lanes.as_array()[j];
                        let light = light_through(scene, &h.hit, s, (f, pdf), true, stats);
                        path.l += path.beta * light;
                    }
                    // Lambert::sample and Bsdf::sample: no sample of a black albedo, nor of
                    // one that is not finite. Scattering::sample's sample of one part of weight
                    // 1: its weight and density times 1, the same bits.
                    let useful = albedo.is_finite() && !albedo.is_black();
                    (useful && on(cosine_ok)).then(|| ScatteringSample {
                        wi: cosine_wi.lane(j),
                        weight: albedo,
                        pdf: cosine_pdf.as_array()[j],
                        delta: false,
                        reflected: true,
                    })
                }
                LaneBsdf::Glass {
                    eta,
                    specular,
                    transmittance,
                } => {
                    let frame = FrameOf {
                        s: V3::from(frame.s.lane(j)),
                        t: V3::from(frame.t.lane(j)),
                        n: V3::from(frame.n.lane(j)),
                    };
                    let wo_local = wo_local.lane(j);
                    let (wo, ng) = (wo.lane(j), ng.lane(j));
                    glass_sample(
                        frame,
                        (wo, wo_local, ng),
                        u_lobe[j],
                        (eta, specular, transmittance),
                    )
                }
                LaneBsdf::Mirror { eta, k, specular } => {
                    // Conductor::sample: the tint times the Fresnel reflectance at the
                    // viewer's cosine; Bsdf::sample keeps a finite weight that is not black.
                    let weight = specular * fresnel::conductor(wo_local.z.as_array()[j], eta, k);
                    let useful = weight.is_finite() && !weight.is_black();
                    (useful && on(mirror_ok)).then(|| ScatteringSample {
                        wi: mirror_wi.lane(j),
                        weight,
                        pdf: 1.0,
                        delta: true,
                        reflected: true,
                    })
                }
            };
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

/// What material `m` is at `hit`, its textures evaluated as `Resolve` evaluates them (at the
/// hit's coordinates, over `footprint`); a Lambertian albedo times the vertex colour (the
/// hit's, white on shapes without) where the material says.
#[inline(always)]
fn bsdf_at(scene: &Scene, m: LaneMaterial, hit: &SurfaceHit, footprint: f32) -> LaneBsdf {
    let eval = |t: &Texture| match t {
        Texture::Solid(c) => *c,
        t => {
            let material = &scene.materials[hit.material as usize];
            t.eval(&scene.tex_coords(material, hit, footprint), &scene.images)
        }
    };
    match m.surface {
        LaneSurface::Lambert { reflectance } => {
            let color = if m.vertex_colors {
                hit.color
            } else {
                Rgb::WHITE
            };
            LaneBsdf::Lambert(eval(reflectance) * color)
        }
        LaneSurface::Mirror { eta, k, specular } => LaneBsdf::Mirror {
            eta: eval(eta),
            k: eval(k),
            specular: eval(specular),
        },
        LaneSurface::Glass {
            eta,
            specular,
            transmittance,
        } => LaneBsdf::Glass {
            eta,
            specular: eval(specular),
            transmittance: eval(transmittance),
        },
    }
}

/// Smooth glass's sample in one lane, as `Scattering::sample` draws it from its one part of
/// weight 1: the lobe's number rescaled to the part (itself, clamped below 1), the scalar
/// BSDF's sample in the frame, the direction in the world, and the leak test; the weight and
/// density times 1, the same bits.
#[inline(always)]
fn glass_sample(
    frame: FrameOf<f32>,
    (wo, wo_local, ng): (Vec3, Vec3, Vec3),
    u_lobe: f32,
    (eta, specular, transmittance): (f32, Rgb, Rgb),
) -> Option<ScatteringSample> {
    let u_part = u_lobe.clamp(0.0, 1.0 - f32::EPSILON);
    let bsdf = Bsdf::Dielectric {
        eta,
        specular,
        transmittance,
    };
    let s = bsdf.sample(wo_local, u_part, Vec2::ZERO, Transport::Radiance)?;
    let wi: Vec3 = frame.to_world(s.wi.into()).normalize().into();
    let reflected = (s.wi.z > 0.0) == (wo_local.z > 0.0);
    let same_side = (wi.dot(ng) > 0.0) == (wo.dot(ng) > 0.0);
    (same_side == reflected).then_some(ScatteringSample {
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
fn mirror_bounce(
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

/// For a light along world direction `wi`: where it reaches the front of a Lambertian part
/// without leaking through the surface (the mask), `cos θi/π` — [`Scattering`]'s value without
/// the albedo — and the part's density of sampling `wi` (0 where it leaks).
///
/// [`Scattering`]: crate::material::Scattering
#[inline(always)]
fn lambert_value_and_pdf(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    wo_local: V3<f32x8>,
    wi: V3<f32x8>,
) -> ((f32x8, f32x8), f32x8) {
    let zero = f32x8::ZERO;
    let local = frame.to_local(wi);
    // Part::local: the shading and the geometric normal put wi on the same side.
    let consistent = wi.dot(ng).gt(zero).same(local.z.gt(zero));
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
fn lambert_bounce(
    frame: &FrameOf<f32x8>,
    ng: V3<f32x8>,
    wo: V3<f32x8>,
    wo_local: V3<f32x8>,
    (ux, uy): (f32x8, f32x8),
) -> (f32x8, V3<f32x8>, f32x8) {
    let zero = f32x8::ZERO;
    let (ok, local, pdf) = lambert_sample(wo_local, ux, uy);
    // Bsdf::sample's test of a useful sample (the albedo is finite and not black).
    let finite = local.x.finite() & local.y.finite() & local.z.finite();
    let useful = ok & pdf.gt(zero) & pdf.finite() & finite;
    let wi = frame.to_world(local).normalize();
    // Scattering::sample's leak test: the side the sample chose agrees with the geometric one.
    let reflected = local.z.gt(zero).same(wo_local.z.gt(zero));
    let same_side = wi.dot(ng).gt(zero).same(wo.dot(ng).gt(zero));
    (useful & same_side.same(reflected), wi, pdf)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::light::Light;
    use crate::light::point::{Falloff, PointLight};
    use crate::material::Material;
    use crate::scene::SceneBuilder;
    use crate::shape::{Mesh, Sphere};

    /// An open box of Lambertian walls (one two-sided, one seen from behind through the open
    /// side), a Lambertian ball, a metal one and a glass one, a rectangular light, a point light and a grey
    /// sky: paths that go through lanes, per path, and between the two.
    fn mixed_scene() -> Scene {
        let camera = Camera::new(Vec3::new(0.2, 0.1, 3.5), Vec3::ZERO, Vec3::Y, 50.0, 16, 16);
        let mut b = SceneBuilder::new(camera.unwrap());
        b.background(Rgb::gray(0.3));
        let white = b.material(Material::lambertian(Rgb::new(0.8, 0.7, 0.6)));
        let checker = b.material(Material {
            surface: Surface::Diffuse {
                reflectance: Texture::Checker(crate::texture::checker::Checker {
                    even: Rgb::new(0.9, 0.8, 0.1),
                    odd: Rgb::BLACK,
                    size: 0.3,
                }),
            },
            ..Material::default()
        });
        let red = b.material(Material {
            two_sided: true,
            ..Material::lambertian(Rgb::new(0.6, 0.05, 0.05))
        });
        let metal = b.material(
            Material::physically_based(
                Surface::Conductor {
                    eta: Texture::from(0.2),
                    k: Texture::from(3.0),
                    specular: Texture::from(1.0),
                    roughness: None,
                },
                &[],
            )
            .0,
        );
        let glass = b.material(
            Material::physically_based(
                Surface::Dielectric {
                    eta: 1.5,
                    specular: Texture::from(1.0),
                    transmittance: Texture::from(Rgb::new(0.9, 1.0, 0.95)),
                    roughness: None,
                },
                &[],
            )
            .0,
        );
        let lamp = b.material(Material {
            ke: Rgb::new(9.0, 8.0, 6.0),
            ..Material::lambertian(Rgb::gray(0.5))
        });
        let quad = |c: [Vec3; 4]| Mesh::new(c.to_vec(), vec![[0, 1, 2], [0, 2, 3]]);
        let v = Vec3::new;
        let (l, h, a, c) = (-1.0, 1.0, -0.3, 0.3);
        let walls = [
            ([v(l, l, l), v(h, l, l), v(h, l, h), v(l, l, h)], checker),
            ([v(l, l, l), v(l, h, l), v(h, h, l), v(h, l, l)], white),
            ([v(l, l, l), v(l, l, h), v(l, h, h), v(l, h, l)], red),
            ([v(h, l, l), v(h, h, l), v(h, h, h), v(h, l, h)], red),
            (
                [v(a, 0.99, a), v(c, 0.99, a), v(c, 0.99, c), v(a, 0.99, c)],
                lamp,
            ),
        ];
        for (corners, material) in walls {
            b.mesh(quad(corners), material);
        }
        b.sphere(
            Sphere {
                center: Vec3::new(-0.4, -0.6, 0.1),
                radius: 0.4,
            },
            white,
        );
        b.sphere(
            Sphere {
                center: Vec3::new(0.45, -0.65, -0.2),
                radius: 0.35,
            },
            metal,
        );
        b.sphere(
            Sphere {
                center: Vec3::new(0.1, -0.1, 0.5),
                radius: 0.25,
            },
            glass,
        );
        b.light(Light::Point(PointLight {
            position: Vec3::new(0.5, 0.5, 0.8),
            intensity: Rgb::gray(0.5),
            falloff: Falloff::Quadratic,
        }));
        b.build().unwrap()
    }

    #[test]
    fn lanes_give_the_scalar_paths_bits() {
        let scene = mixed_scene();
        let lanes = LaneMaterials::of(&scene);
        assert!(lanes.any());
        let tracer = PathTracer {
            max_depth: 6,
            rr_depth: 2,
        };
        let (w, h) = (scene.camera.width(), scene.camera.height());
        let mut scalar_stats = RayStats::default();
        let mut lane_stats = RayStats::default();
        // Groups of every size from 1 to 8 (so that partial groups are covered).
        let mut pixel = 0u64;
        let mut shown = 0;
        for size in (1..=LANES).cycle().take(400) {
            let mut rays = ArrayVec::<Ray, LANES>::new();
            let mut samplers = ArrayVec::<Sampler, LANES>::new();
            for _ in 0..size {
                let (x, y) = (
                    (pixel % u64::from(w)) as u32,
                    ((pixel / u64::from(w)) % u64::from(h)) as u32,
                );
                let s = (pixel / u64::from(w * h)) as u32;
                let mut sampler = Sampler::new(3, pixel, s);
                let u = sampler.next_2d();
                sampler.defer(2);
                rays.push(scene.camera.ray(x as f32 + u.x, y as f32 + u.y));
                samplers.push(sampler);
                pixel += 1;
            }
            let expected: Vec<Rgb> = rays
                .iter()
                .zip(samplers.clone())
                .map(|(r, mut s)| tracer.radiance(&scene, r, &mut s, &mut scalar_stats))
                .collect();
            // As the processor runs it (with AVX2 where it has it), and in the baseline
            // instruction set.
            let mut baseline = samplers.clone();
            let got =
                tracer.radiance_lanes(&scene, &lanes, None, &rays, &mut samplers, &mut lane_stats);
            let got_baseline = tracer.radiance_lanes_with(
                &scene,
                &lanes,
                None,
                &rays,
                &mut baseline,
                &mut RayStats::default(),
            );
            for ((e, g), b) in expected.iter().zip(&got).zip(&got_baseline) {
                let bits = |c: &Rgb| c.to_array().map(f32::to_bits);
                assert_eq!(bits(e), bits(g), "expected {e:?}, got {g:?}");
                assert_eq!(bits(e), bits(b), "expected {e:?}, got {b:?} (baseline)");
                shown += usize::from(!e.is_black());
            }
        }
        assert_eq!(scalar_stats, lane_stats, "the same rays");
        assert!(shown > 400, "only {shown} paths found light");
        assert!(
            scalar_stats.shadow > 1000 && scalar_stats.reflected > 1000,
            "{scalar_stats:?}"
        );
    }
}
