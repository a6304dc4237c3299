//! A smooth conductor: a mirror whose reflectance is the exact Fresnel reflectance of a complex
//! index `η + i·k` per channel (Mitsuba 3 `conductor`).

use glam::Vec3;

use super::{BsdfSample, fresnel, mirror};
use crate::Rgb;

/// The smooth conductor's parameters.
pub(super) struct Conductor {
    pub eta: Rgb,
    pub k: Rgb,
    pub specular: Rgb,
}

impl Conductor {
    /// The mirror direction, weighted `specular·F(cos θo)`: the Dirac lobe
    /// `f = specular·F·δ(wi − R(wo))/|cos θi|` divided by its (certain) choice.
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi: mirror(wo),
            weight: self.specular * fresnel::conductor(wo.z, self.eta, self.k),
            pdf: 1.0,
            delta: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_metal_mirrors_with_its_fresnel_reflectance() {
        let b = Conductor {
            eta: Rgb::new(0.2, 0.9, 1.1),
            k: Rgb::new(3.9, 2.4, 2.2),
            specular: Rgb::new(1.0, 0.5, 1.0),
        };
        let wo = Vec3::new(0.6, -0.48, 0.64);
        let s = b.sample(wo).unwrap();
        assert!((s.wi - Vec3::new(-0.6, 0.48, 0.64)).length() < 1e-6);
        let f = fresnel::conductor(0.64, b.eta, b.k);
        assert_eq!(s.weight, Rgb::new(f.r, 0.5 * f.g, f.b));
        assert!(s.delta && s.pdf == 1.0);
        assert!(b.sample(-wo).is_none(), "one-sided");
    }
}
