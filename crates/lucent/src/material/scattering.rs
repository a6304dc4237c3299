//! A material resolved at a hit: the BSDFs of its surface's leaves with their textures
//! evaluated, each with its weight (from blends) and its shading frame (from normal maps and
//! the side the ray arrived on), evaluated and sampled as one BSDF in world space.
//!
//! Sampling picks a part with probability equal to its weight (reusing `u_lobe`, rescaled, for
//! the part's own lobe choice); a non-delta direction is then weighted by the whole mixture's
//! value over its whole density (one-sample MIS), a Dirac one by the part's own weight.

use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};

use super::gltf::GltfMaps;
use super::shading::{Geometry, facing};
use super::{Material, Surface};
use crate::Rgb;
use crate::bsdf::{Bsdf, Frame, Transport};
use crate::texture::{ImageTexture, TexCoords};

/// The most parts a resolved surface keeps (a glTF material's three layers, blends nested two
/// deep); further parts are dropped with their weight. Kept small: a hit's parts are moved
/// with its vertex.
const MAX_PARTS: usize = 4;

/// Which side of the surface a ray arrived on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The side the geometric normal points to.
    Front,
    /// The other.
    Back,
}

/// One leaf of a resolved surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Part<'a> {
    /// Its factor in the sum. The weights sum to at most 1, but for a glTF material's
    /// diffuse transmission, which shares its base's weight (the two split one diffuse lobe).
    pub weight: f32,
    /// The shading frame its BSDF works in.
    pub frame: Frame,
    /// The geometric normal, flipped as the frame is.
    pub ng: Vec3,
    /// Its BSDF, textures evaluated.
    pub bsdf: Bsdf<'a>,
    /// For a normal- or bump-mapped part, the shadowing of its bumps (see
    /// [`Terminator`]).
    pub terminator: Option<Terminator>,
}

/// The shadowing a normal or bump map's unseen bumps cast on light arriving at grazing angles
/// (Estevez et al., "A Microfacet-Based Shadowing Function to Solve the Bump Terminator
/// Problem", Ray Tracing Gems 2019, as Mitsuba's `normalmap` and `bumpmap` apply it): the
/// bumps are taken for microfacets of roughness `α² = min(tan²θ/8, 1)`, θ the perturbed
/// normal's tilt from the surface's own shading normal, and a light direction at `θi` from that
/// normal is weighted by their Smith masking `2/(1 + √(1 + α² tan²θi))`. Without it the
/// shading ends in a hard line where the perturbed normal turns from the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Terminator {
    /// The shading normal the map perturbs.
    pub base: Vec3,
    /// `α²` of the bumps.
    pub alpha2: f32,
}

impl Terminator {
    /// The terminator of a normal perturbed from `base` to `n` (unit vectors).
    pub fn new(base: Vec3, n: Vec3) -> Self {
        let c = n.dot(base).clamp(-1.0, 1.0);
        let tan2 = (1.0 - c * c).max(0.0) / (c * c).max(1e-12);
        Self {
            base,
            alpha2: (0.125 * tan2).min(1.0),
        }
    }

    /// The weight of light along unit direction `w`.
    #[inline]
    pub fn weight(&self, w: Vec3) -> f32 {
        let c = w.dot(self.base);
        let c2 = (c * c).max(1e-12);
        let tan2 = (1.0 - c2).max(0.0) / c2;
        2.0 / (1.0 + (1.0 + self.alpha2 * tan2).sqrt())
    }
}

impl Part<'_> {
    /// The terminator weight of light along `w` (1 without a map).
    #[inline]
    fn shadowing(&self, w: Vec3) -> f32 {
        self.terminator.map_or(1.0, |t| t.weight(w))
    }

    /// `w` in the frame, or `None` where the shading and the geometric normal put it on
    /// different sides (the no-leak rule of `material/shading.rs`).
    #[inline]
    fn local(&self, w: Vec3) -> Option<Vec3> {
        let l = self.frame.to_local(w);
        ((w.dot(self.ng) > 0.0) == (l.z > 0.0)).then_some(l)
    }
}

/// A direction drawn by [`Scattering::sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScatteringSample {
    /// The sampled direction, a unit vector in world space, away from the surface.
    pub wi: Vec3,
    /// `f·|cos θi| / pdf`: the factor the path's throughput is multiplied by.
    pub weight: Rgb,
    /// The solid-angle density (or, when `delta`, the probability of the Dirac lobe).
    pub pdf: f32,
    /// True for a Dirac lobe.
    pub delta: bool,
    /// Whether it stayed on the side it came from (else it passed through the surface).
    pub reflected: bool,
}

/// The material at one hit, as one BSDF over world directions.
#[derive(Clone, Debug, PartialEq)]
pub struct Scattering<'a> {
    parts: ArrayVec<Part<'a>, MAX_PARTS>,
    /// The sum of the weights.
    total: f32,
}

/// What resolving needs besides the surface.
struct Resolve<'s, 'a, 'o> {
    material: &'a Material,
    at: &'s TexCoords,
    images: &'s [ImageTexture],
    /// The geometric normal.
    ng: Vec3,
    /// The unit direction back towards where the ray came from.
    wo: Vec3,
    side: Side,
    out: &'o mut ArrayVec<Part<'a>, MAX_PARTS>,
}

impl<'a> Scattering<'a> {
    /// `material` at a hit with shading geometry `geometry`, geometric normal `ng` and texture
    /// coordinates `at`, seen along unit direction `dir` (the arriving ray's).
    pub fn new(
        material: &'a Material,
        geometry: Geometry,
        ng: Vec3,
        at: &TexCoords,
        images: &[ImageTexture],
        dir: Vec3,
    ) -> Self {
        let mut s = Self::empty();
        s.resolve(material, geometry, ng, at, images, dir);
        s
    }

    /// Nothing scatters: a surface to [`Scattering::resolve`] into where it will stay (a
    /// vertex's parts are a few hundred bytes, not moved once made).
    #[inline]
    pub fn empty() -> Self {
        Self {
            parts: ArrayVec::new(),
            total: 0.0,
        }
    }

    /// Replaces the parts by those of [`Scattering::new`] with the same arguments.
    pub fn resolve(
        &mut self,
        material: &'a Material,
        geometry: Geometry,
        ng: Vec3,
        at: &TexCoords,
        images: &[ImageTexture],
        dir: Vec3,
    ) {
        let side = if ng.dot(dir) > 0.0 {
            Side::Back
        } else {
            Side::Front
        };
        self.parts.clear();
        let mut r = Resolve {
            material,
            at,
            images,
            ng,
            wo: -dir,
            side,
            out: &mut self.parts,
        };
        r.surface(&material.surface, 1.0, geometry, false, None);
        self.total = self.parts.iter().map(|p| p.weight).sum();
    }

    /// The parts.
    pub fn parts(&self) -> &[Part<'a>] {
        &self.parts
    }

    /// `f(wo, wi)·|cos θi|` summed over the parts' non-delta lobes, for unit world directions
    /// pointing away from the surface.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: Transport) -> Rgb {
        let mut f = Rgb::BLACK;
        for p in &self.parts {
            if let Some(i) = p.local(wi) {
                f += p.bsdf.eval(p.frame.to_local(wo), i, mode) * (p.weight * p.shadowing(wi));
            }
        }
        f
    }

    /// [`Scattering::eval`] and [`Scattering::pdf`] together, in one pass over the parts.
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3, mode: Transport) -> (Rgb, f32) {
        if self.total <= 0.0 {
            return (Rgb::BLACK, 0.0);
        }
        let mut f = Rgb::BLACK;
        let mut pdf = 0.0;
        for p in &self.parts {
            if let Some(i) = p.local(wi) {
                let o = p.frame.to_local(wo);
                f += p.bsdf.eval(o, i, mode) * (p.weight * p.shadowing(wi));
                pdf += p.bsdf.pdf(o, i) * p.weight;
            }
        }
        (f, pdf / self.total)
    }

    /// The solid-angle density with which [`Scattering::sample`] draws `wi`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if self.total <= 0.0 {
            return 0.0;
        }
        let mut pdf = 0.0;
        for p in &self.parts {
            if let Some(i) = p.local(wi) {
                pdf += p.bsdf.pdf(p.frame.to_local(wo), i) * p.weight;
            }
        }
        pdf / self.total
    }

    /// A direction drawn from the mixture with two uniform inputs; `None` when nothing is
    /// scattered or the direction would leak through the surface.
    pub fn sample(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: Transport,
    ) -> Option<ScatteringSample> {
        // The part, and u_lobe rescaled to [0, 1) within its share.
        let mut acc = 0.0;
        let mut pick = None;
        let target = u_lobe * self.total;
        for (i, p) in self.parts.iter().enumerate() {
            if target < acc + p.weight || i + 1 == self.parts.len() {
                let u = ((target - acc) / p.weight).clamp(0.0, 1.0 - f32::EPSILON);
                pick = Some((i, u));
                break;
            }
            acc += p.weight;
        }
        let (i, u_part) = pick?;
        let p = &self.parts[i];
        let local_wo = p.frame.to_local(wo);
        let s = p.bsdf.sample(local_wo, u_part, u, mode)?;
        let (wi, reflected) = unleaked(&p.frame, p.ng, (wo, local_wo), s.wi)?;
        if s.delta || self.parts.len() == 1 {
            // The part was picked with probability w_i/W and carries w_i·f_i: its own weight
            // times W.
            return Some(ScatteringSample {
                wi,
                weight: s.weight * (self.total * p.shadowing(wi)),
                pdf: s.pdf * (p.weight / self.total),
                delta: s.delta,
                reflected,
            });
        }
        let (value, pdf) = self.eval_pdf(wo, wi, mode);
        (pdf > 0.0 && !value.is_black()).then(|| ScatteringSample {
            wi,
            weight: value * (1.0 / pdf),
            pdf,
            delta: false,
            reflected,
        })
    }

    /// True when every lobe of every part is a Dirac delta (light sampling is useless there).
    pub fn is_delta(&self) -> bool {
        self.parts.iter().all(|p| p.bsdf.is_delta())
    }

    /// The probability that [`Scattering::sample`] from `wo` picks a Dirac lobe.
    pub fn delta_share(&self, wo: Vec3) -> f32 {
        if self.total <= 0.0 {
            return 0.0;
        }
        let share: f32 = self
            .parts
            .iter()
            .map(|p| p.weight * p.bsdf.delta_share(p.frame.to_local(wo)))
            .sum();
        share / self.total
    }

    /// Whether any part transmits.
    pub fn transmits(&self) -> bool {
        self.parts.iter().any(|p| p.bsdf.transmits())
    }
}

/// The world direction of `local_wi`, sampled in `frame` (geometric normal `ng`) for the viewer
/// at `wo` (`local_wo` in the frame), normalised, and whether it stayed on the viewer's side;
/// `None` where it leaks: the side the sample chose disagrees with the geometric normal's.
#[inline(always)]
pub(crate) fn unleaked(
    frame: &Frame,
    ng: Vec3,
    (wo, local_wo): (Vec3, Vec3),
    local_wi: Vec3,
) -> Option<(Vec3, bool)> {
    let wi = frame.to_world(local_wi).normalize();
    let reflected = (local_wi.z > 0.0) == (local_wo.z > 0.0);
    let same_side = (wi.dot(ng) > 0.0) == (wo.dot(ng) > 0.0);
    (same_side == reflected).then_some((wi, reflected))
}

impl<'a> Resolve<'_, 'a, '_> {
    /// Adds the parts of `surface` with `weight`, shading geometry `g`, the frame already
    /// turned to the back when `flipped`, the bumps of a map above shadowing it when
    /// `terminator`.
    fn surface(
        &mut self,
        surface: &'a Surface,
        weight: f32,
        g: Geometry,
        flipped: bool,
        terminator: Option<Terminator>,
    ) {
        if weight.is_nan() || weight <= 0.0 {
            return;
        }
        match surface {
            Surface::Blend {
                weight: w,
                first,
                second,
            } => {
                let t = w.eval_float(self.at, self.images).clamp(0.0, 1.0);
                self.surface(first, weight * (1.0 - t), g, flipped, terminator);
                self.surface(second, weight * t, g, flipped, terminator);
            }
            Surface::TwoSided { front, back } => {
                if self.side == Side::Back && !flipped {
                    let g = Geometry { n: -g.n, ..g };
                    self.surface(back, weight, g, true, terminator);
                } else {
                    self.surface(front, weight, g, flipped, terminator);
                }
            }
            Surface::NormalMap {
                normals,
                strength,
                inner,
            } => {
                // Normals are looked up at a point, as pbrt-v4 does: averaging a MIP level's
                // normals flattens the bumps, and the shading is not linear in the normal.
                let point = TexCoords {
                    duv: [Vec2::ZERO; 2],
                    ..*self.at
                };
                let texel = normals.eval(&point, self.images);
                let (mapped, t) = self.perturbed(g, g.normal_mapped(texel, *strength));
                self.surface(inner, weight, mapped, flipped, Some(t));
            }
            Surface::BumpMap {
                height,
                scale,
                inner,
            } => {
                let grad = self.height_gradient(height) * *scale;
                let ng = if flipped { -self.ng } else { self.ng };
                let (bumped, t) = self.perturbed(g, g.bumped(grad, ng));
                self.surface(inner, weight, bumped, flipped, Some(t));
            }
            Surface::Gltf(maps) => self.gltf(maps, weight, g, flipped, terminator),
            leaf => {
                let Some(bsdf) = self.leaf(leaf) else { return };
                self.push(bsdf, weight, g, flipped, terminator, 0.0);
            }
        }
    }

    /// Adds a part: `bsdf` in the frame of `g` (turned to the back for a two-sided reflector
    /// hit from behind, the viewer kept above its horizon, its tangent turned by `rotation`
    /// radians towards the bitangent).
    fn push(
        &mut self,
        bsdf: Bsdf<'a>,
        weight: f32,
        g: Geometry,
        flipped: bool,
        terminator: Option<Terminator>,
        rotation: f32,
    ) {
        if weight.is_nan() || weight <= 0.0 || self.out.is_full() {
            return;
        }
        // A two-sided reflector scatters on whichever side the ray arrives.
        let flip =
            !flipped && self.side == Side::Back && self.material.two_sided && !bsdf.transmits();
        let (n, ng) = if flip || flipped {
            (if flip { -g.n } else { g.n }, -self.ng)
        } else {
            (g.n, self.ng)
        };
        let n = facing(n, ng, self.wo);
        let mut frame = Frame::from_normal_tangent(n, g.dpdu);
        if rotation != 0.0 {
            let (sin, cos) = rotation.sin_cos();
            let s = frame.s * cos + frame.t * sin;
            frame = Frame::from_normal_tangent(n, s);
        }
        let terminator = terminator.map(|t| Terminator {
            base: if flip { -t.base } else { t.base },
            ..t
        });
        self.out.push(Part {
            weight,
            frame,
            ng,
            bsdf,
            terminator,
        });
    }

    /// glTF's material: the base, the sheen on it and the clearcoat on both, as parts (see
    /// `material/gltf.rs`).
    fn gltf(
        &mut self,
        maps: &'a GltfMaps,
        weight: f32,
        g: Geometry,
        flipped: bool,
        terminator: Option<Terminator>,
    ) {
        let color = if self.material.vertex_colors {
            self.at.color
        } else {
            Rgb::WHITE
        };
        let layers = maps.at(self.at, self.images, color);
        let mut below = weight;
        if let Some((cc, facets)) = layers.clearcoat {
            let coat = match &maps.clearcoat_normals {
                Some((normals, strength)) => {
                    let point = TexCoords {
                        duv: [Vec2::ZERO; 2],
                        ..*self.at
                    };
                    g.normal_mapped(normals.eval(&point, self.images), *strength)
                }
                None => g,
            };
            let c = coat.n.dot(self.wo).abs().min(1.0);
            let f = 0.04 + 0.96 * (1.0 - c).powi(5);
            let w = cc * f;
            let mirror = Bsdf::RoughConductor {
                eta: Rgb::BLACK,
                k: Rgb::WHITE,
                specular: Rgb::WHITE,
                microfacet: facets,
            };
            self.push(mirror, weight * w, coat, flipped, terminator, 0.0);
            below *= 1.0 - w;
        }
        if let Some(sheen) = layers.sheen {
            let scale = match &maps.sheen_albedo {
                Some(table) => {
                    let e = table.albedo(g.n.dot(self.wo).abs(), sheen.roughness);
                    1.0 - sheen.color.max_channel() * e
                }
                None => 1.0,
            };
            self.push(Bsdf::Sheen(sheen), below, g, flipped, terminator, 0.0);
            below *= scale.max(0.0);
        }
        self.push(
            Bsdf::Gltf(layers.base),
            below,
            g,
            flipped,
            terminator,
            layers.rotation,
        );
        // After the base: where blends fill the parts, the base is kept.
        if let Some((share, translucent)) = layers.translucent {
            self.push(
                Bsdf::GltfTranslucent(translucent),
                below * share,
                g,
                flipped,
                terminator,
                0.0,
            );
        }
    }

    /// A map's perturbed geometry `p` of `g` made safe as Mitsuba's `normalmap` and `bumpmap`
    /// make it (after Schüssler et al. 2017): where the viewer would be on the other side of the
    /// perturbed normal than of the shading normal, the tilt is mirrored (the normal turned by
    /// half a turn about the shading normal); with the terminator shadowing of its bumps.
    fn perturbed(&self, g: Geometry, p: Geometry) -> (Geometry, Terminator) {
        let base = g.n;
        let mut n = p.n;
        if base.dot(self.wo) * n.dot(self.wo) <= 0.0 {
            n = (base * (2.0 * n.dot(base)) - n).normalize_or(base);
        }
        (Geometry { n, ..p }, Terminator::new(base, n))
    }

    /// `(∂h/∂u, ∂h/∂v)` of a height texture at the hit, by central differences over a step of
    /// half the lookup's footprint (at least `5·10⁻⁴` in texture coordinates).
    fn height_gradient(&self, height: &crate::texture::Texture) -> Vec2 {
        let d = self.at.duv;
        let du = (0.5 * (d[0].x.abs() + d[1].x.abs())).max(5e-4);
        let dv = (0.5 * (d[0].y.abs() + d[1].y.abs())).max(5e-4);
        let h = |offset: Vec2| {
            let at = TexCoords {
                uv: self.at.uv + offset,
                ..*self.at
            };
            height.eval_float(&at, self.images)
        };
        Vec2::new(
            (h(Vec2::new(du, 0.0)) - h(Vec2::new(-du, 0.0))) / (2.0 * du),
            (h(Vec2::new(0.0, dv)) - h(Vec2::new(0.0, -dv))) / (2.0 * dv),
        )
    }

    /// The BSDF of a leaf with its textures evaluated; `None` for a black one.
    fn leaf(&self, surface: &'a Surface) -> Option<Bsdf<'a>> {
        let (at, images) = (self.at, self.images);
        let m = self.material;
        let color = if m.vertex_colors {
            at.color
        } else {
            Rgb::WHITE
        };
        let c = |t: &crate::texture::Texture| t.eval(at, images);
        Some(match surface {
            Surface::Classic => m.classic_bsdf(m.kd.eval(at, images) * color),
            Surface::Diffuse { reflectance } => Bsdf::Lambert {
                albedo: c(reflectance) * color,
            },
            Surface::Conductor {
                eta,
                k,
                specular,
                roughness,
            } => match roughness {
                Some(r) => Bsdf::RoughConductor {
                    eta: c(eta),
                    k: c(k),
                    specular: c(specular),
                    microfacet: r.at(at, images),
                },
                None => Bsdf::Conductor {
                    eta: c(eta),
                    k: c(k),
                    specular: c(specular),
                },
            },
            Surface::Dielectric {
                eta,
                specular,
                transmittance,
                roughness,
            } => match roughness {
                Some(r) => Bsdf::RoughDielectric {
                    eta: *eta,
                    specular: c(specular),
                    transmittance: c(transmittance),
                    microfacet: r.at(at, images),
                },
                None => Bsdf::Dielectric {
                    eta: *eta,
                    specular: c(specular),
                    transmittance: c(transmittance),
                },
            },
            Surface::ThinDielectric {
                eta,
                specular,
                transmittance,
            } => Bsdf::ThinDielectric {
                eta: *eta,
                specular: c(specular),
                transmittance: c(transmittance),
            },
            Surface::Plastic {
                diffuse,
                eta,
                specular,
                nonlinear,
                coat,
            } => match coat {
                Some(coat) => Bsdf::RoughPlastic {
                    diffuse: c(diffuse) * color,
                    specular: c(specular),
                    nonlinear: *nonlinear,
                    coat,
                },
                None => Bsdf::Plastic {
                    diffuse: c(diffuse) * color,
                    eta: *eta,
                    specular: c(specular),
                    nonlinear: *nonlinear,
                },
            },
            Surface::Principled(p) => {
                let mut lobes = p.at(at, images);
                lobes.base_color *= color;
                Bsdf::Principled(lobes)
            }
            Surface::PrincipledThin(p) => {
                let mut lobes = p.at(at, images);
                lobes.base_color *= color;
                Bsdf::PrincipledThin(lobes)
            }
            Surface::Gltf(_)
            | Surface::Blend { .. }
            | Surface::TwoSided { .. }
            | Surface::NormalMap { .. }
            | Surface::BumpMap { .. } => return None,
        })
    }
}
