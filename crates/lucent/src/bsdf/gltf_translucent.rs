//! The diffuse transmission of glTF's `KHR_materials_diffuse_transmission`: a Lambertian lobe
//! through the surface, the same from both sides (a thin translucent sheet: leaves, paper,
//! lampshades), under the dielectric's specular layer.
//!
//! The extension splits the dielectric's diffuse lobe: `mix(diffuse_brdf(base),
//! diffuse_btdf(color), diffuse_transmission)`, under `fresnel_mix` like the rest. The
//! reflected share stays in [`GltfPbr`] (its `diffuse_transmission`); this part is the other,
//! carried as a [`GltfPbr`] whose `base_color` is the transmission colour, with its Fresnel
//! parameters (`ior`, `specular`, `specular_color`, the film). Its weight in the material,
//! `(1 − metallic)(1 − transmission)·diffuse_transmission`, is the part's.
//!
//! With `V` turned to the front and `L` with it (`L` then below), and `H` the half vector of
//! `V` and `L` mirrored to the front (as the reflection the light would have had):
//! `f·|cos θL| = (1 − max(s·F_d(V·H)))·color·|cos θL|/π`, sampled by the cosine below.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::{BsdfSample, GltfPbr};
use crate::Rgb;

/// The translucent part's parameters (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct GltfTranslucent(pub GltfPbr);

/// `(v, l)` turned so that `v` is on the front.
fn to_front(v: Vec3, l: Vec3) -> (Vec3, Vec3) {
    if v.z < 0.0 {
        (Vec3::new(v.x, v.y, -v.z), Vec3::new(l.x, l.y, -l.z))
    } else {
        (v, l)
    }
}

impl GltfTranslucent {
    /// `f(V, L)·|cos θL|`: non-zero only with `V` and `L` on opposite sides.
    pub fn eval(&self, v: Vec3, l: Vec3) -> Rgb {
        let (v, l) = to_front(v, l);
        if v.z <= 0.0 || l.z >= 0.0 {
            return Rgb::BLACK;
        }
        let mirrored = Vec3::new(l.x, l.y, -l.z);
        let Some(h) = (v + mirrored).try_normalize() else {
            return Rgb::BLACK;
        };
        let f = self.0.fresnel_dielectric(v.dot(h)).max_channel();
        self.0.base_color * ((1.0 - f).max(0.0) * FRAC_1_PI * -l.z)
    }

    /// The cosine's density on the side opposite `v`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        let (v, l) = to_front(v, l);
        if v.z <= 0.0 || l.z >= 0.0 {
            return 0.0;
        }
        cosine_pdf(-l)
    }

    /// A cosine-weighted direction through the surface.
    pub fn sample(&self, v: Vec3, u: Vec2) -> Option<BsdfSample> {
        if v.z == 0.0 || self.0.base_color.is_black() {
            return None;
        }
        let mut l = sample_cosine(u)?;
        if v.z > 0.0 {
            l.z = -l.z;
        }
        BsdfSample::of_mixture(l, self.eval(v, l), self.pdf(v, l))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sheet(color: Rgb, specular: f32) -> GltfTranslucent {
        GltfTranslucent(GltfPbr {
            specular,
            ..GltfPbr::plain(color, 0.0, 0.25)
        })
    }

    #[test]
    fn head_on_it_passes_what_the_specular_layer_leaves() {
        // V = N, L = −N: H = N, F_d = f0 = 0.04.
        let b = sheet(Rgb::new(0.2, 0.6, 1.0), 1.0);
        let f = b.eval(Vec3::Z, -Vec3::Z);
        let want = 0.96 * FRAC_1_PI;
        assert!((f.b - want).abs() < 1e-6, "{f:?}");
        assert!((f.r - 0.2 * want).abs() < 1e-6, "{f:?}");
        // Without a specular layer, the whole colour over π.
        let bare = sheet(Rgb::WHITE, 0.0).eval(Vec3::Z, -Vec3::Z);
        assert!((bare.g - FRAC_1_PI).abs() < 1e-6);
    }

    #[test]
    fn it_transmits_only_and_alike_from_both_sides() {
        let b = sheet(Rgb::gray(0.7), 1.0);
        let v = Vec3::new(0.3, -0.2, 0.9).normalize();
        let l = Vec3::new(-0.5, 0.1, -0.7).normalize();
        assert!(b.eval(v, -l).is_black(), "no reflection");
        assert_eq!(b.pdf(v, -l), 0.0);
        let front = b.eval(v, l);
        let back = b.eval(-l, -v);
        assert!(!front.is_black());
        // Reciprocal: f(V, L)/|cos L| = f(L, V)/|cos V| (mirrored through the sheet).
        let f1 = front.g / l.z.abs();
        let f2 = back.g / v.z.abs();
        assert!((f1 - f2).abs() < 1e-5 * f1, "{f1} vs {f2}");
        let s = b.sample(-v, Vec2::new(0.3, 0.6)).unwrap();
        assert!(s.wi.z > 0.0, "from the back it passes to the front");
    }

    #[test]
    fn it_is_the_diffuse_light_the_base_gives_up_mirrored_through_the_surface() {
        // The base with all its diffuse lobe given away loses, towards each L, what this part
        // sends towards L mirrored: the two split one lobe (same colour here).
        use crate::bsdf::Transport;
        let color = Rgb::new(0.8, 0.4, 0.1);
        let keep = GltfPbr {
            iridescence: 0.5,
            film_thickness: 280,
            ..sheet(color, 1.0).0
        };
        let give = GltfPbr {
            diffuse_transmission: 255,
            ..keep
        };
        let part = GltfTranslucent(keep);
        let v = Vec3::new(0.4, 0.1, 0.8).normalize();
        for l in [
            Vec3::new(-0.3, 0.5, 0.6),
            Vec3::new(0.7, -0.2, 0.2),
            Vec3::new(0.0, 0.0, 1.0),
        ] {
            let l = l.normalize();
            let lost = keep.eval(v, l, Transport::Radiance) - give.eval(v, l, Transport::Radiance);
            let passed = part.eval(v, Vec3::new(l.x, l.y, -l.z));
            for (a, b) in lost.to_array().into_iter().zip(passed.to_array()) {
                assert!(
                    (a - b).abs() < 1e-5 * a.abs().max(1e-3),
                    "{lost:?} vs {passed:?}"
                );
            }
        }
    }
}
