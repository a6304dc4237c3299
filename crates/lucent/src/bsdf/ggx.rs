//! The GGX (Trowbridge–Reitz) microfacet distribution written once over [`Real`]: the density,
//! Smith's masking and the sampling of visible normals that [`Microfacet`] uses for GGX, and
//! that the lane path tracer runs on eight paths at once with the same bits. The formulas and
//! their references are [`Microfacet`]'s; the branches are lane masks.
//!
//! [`Microfacet`]: super::Microfacet

use std::f32::consts::PI;

use glam::Vec3;

use crate::lanes::{Real, V3, sin_cos_turn};

/// GGX of roughness `alpha_u` along the tangent and `alpha_v` along the bitangent (already
/// clamped, as [`super::Microfacet::new`] clamps them), per lane.
#[derive(Clone, Copy, Debug)]
pub struct Ggx<R> {
    pub alpha_u: R,
    pub alpha_v: R,
}

/// A distribution of facet normals as the BSDF code written once sees it: the density, the
/// masking and the sampling of visible normals, in the local frame (`z` the macro-normal).
pub trait Facets<R: Real>: Copy {
    /// `D(m)`, zero below the horizon.
    fn d(self, m: V3<R>) -> R;
    /// `G1(v, m) / |cos θv|`, finite at grazing `v`.
    fn g1_over_cos(self, v: V3<R>, m: V3<R>) -> R;
    /// Smith's masking `G1(v, m)`.
    #[inline(always)]
    fn g1(self, v: V3<R>, m: V3<R>) -> R {
        self.g1_over_cos(v, m) * v.z.abs()
    }
    /// A normal drawn from those visible from `v` (`v.z ≥ 0`) with the numbers `u`.
    fn sample_visible(self, v: V3<R>, u: (R, R)) -> V3<R>;
    /// The density of [`Facets::sample_visible`] at `m`: `G1(v, m)·max(0, v·m)·D(m) / cos θv`.
    #[inline(always)]
    fn visible_pdf(self, v: V3<R>, m: V3<R>) -> R {
        let cos_vm = v.dot(m);
        let zero = R::splat(0.0);
        R::select(
            cos_vm.le(zero),
            zero,
            self.g1_over_cos(v, m) * cos_vm * self.d(m),
        )
    }
}

impl<R: Real> Facets<R> for Ggx<R> {
    /// `D = 1 / (π α_u α_v (s² + m_z²)²)` with `s² = (m_x/α_u)² + (m_y/α_v)²`; zero for
    /// `m_z ≤ 0` and where it is not finite.
    #[inline(always)]
    fn d(self, m: V3<R>) -> R {
        let (x, y) = (m.x / self.alpha_u, m.y / self.alpha_v);
        let s2 = x * x + y * y;
        let norm = R::splat(PI) * self.alpha_u * self.alpha_v;
        let t = s2 + m.z * m.z;
        let d = R::splat(1.0) / (norm * t * t);
        let zero = R::splat(0.0);
        R::select(m.z.gt(zero) & d.finite(), d, zero)
    }

    /// `2 / (|v_z| + √(v_z² + (α_u v_x)² + (α_v v_y)²))`; zero where `v` sees the back of the
    /// facet.
    #[inline(always)]
    fn g1_over_cos(self, v: V3<R>, m: V3<R>) -> R {
        let (x, y) = (self.alpha_u * v.x, self.alpha_v * v.y);
        let p = x * x + y * y;
        let z = v.z.abs();
        let g = R::splat(2.0) / (z + (z * z + p).sqrt());
        let zero = R::splat(0.0);
        R::select((v.dot(m) * v.z).le(zero), zero, g)
    }

    /// Stretch `v` to the configuration where `α = 1`, sample there (Heitz 2018), unstretch.
    #[inline(always)]
    fn sample_visible(self, v: V3<R>, u: (R, R)) -> V3<R> {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let zero = R::splat(0.0);
        let vh = V3::new(au * v.x, av * v.y, v.z.max(zero)).normalize_or(Vec3::Z);
        let nh = visible_11(vh, u);
        V3::new(au * nh.x, av * nh.y, nh.z.max(zero)).normalize_or(Vec3::Z)
    }
}

/// A visible normal of GGX of roughness 1 seen from unit `vh` (`vh.z ≥ 0`), by Heitz 2018: for
/// α = 1 the facets are a hemisphere, so sample the hemisphere's projected disc seen from
/// `vh` — a disc whose far half is squashed by `(1 + cos θ)/2` — and lift the point onto it.
#[inline(always)]
fn visible_11<R: Real>(vh: V3<R>, (u1, u2): (R, R)) -> V3<R> {
    let zero = R::splat(0.0);
    let one = R::splat(1.0);
    // A basis around vh: t1 horizontal (undefined at normal incidence, where any will do).
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = V3::select(
        len2.gt(zero),
        V3::new(-vh.y, vh.x, zero) / len2.sqrt(),
        V3::splat(Vec3::X),
    );
    let t2 = vh.cross(t1);
    let r = u1.sqrt();
    let (sin_phi, cos_phi) = sin_cos_turn(u2);
    let p1 = r * cos_phi;
    let s = R::splat(0.5) * (one + vh.z);
    let p2 = (one - s) * (one - p1 * p1).max(zero).sqrt() + s * r * sin_phi;
    t1 * p1 + t2 * p2 + vh * (one - p1 * p1 - p2 * p2).max(zero).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use wide::f32x8;

    fn lanes(f: impl Fn(usize) -> f32) -> f32x8 {
        f32x8::new(std::array::from_fn(f))
    }

    fn v3(f: impl Fn(usize) -> Vec3) -> V3<f32x8> {
        V3::gather(&std::array::from_fn(f))
    }

    #[test]
    fn lanes_compute_the_scalar_bits() {
        // Roughnesses from smooth to rough and anisotropic; directions from head-on to
        // grazing and below; the degenerate normal (0, 0, 1).
        let au = |i: usize| [1e-4, 0.05, 0.2, 0.5, 1.0, 0.3, 2.0, 0.7][i];
        let av = |i: usize| [1e-4, 0.05, 0.6, 0.5, 1.0, 0.1, 2.0, 0.7][i];
        let dir = |i: usize| {
            let a = i as f32 * 0.23;
            Vec3::new(
                a.sin() * (1.0 + i as f32).cos(),
                a.sin() * 0.4,
                a.cos() - 0.3 * (i / 7) as f32,
            )
            .normalize()
        };
        let m = |i: usize| if i == 0 { Vec3::Z } else { dir(7 - i) };
        let u = |i: usize| ((i as f32 * 0.37) % 1.0, (i as f32 * 0.61 + 0.05) % 1.0);
        let wide = Ggx {
            alpha_u: lanes(au),
            alpha_v: lanes(av),
        };
        let d = wide.d(v3(m));
        let g = wide.g1(v3(dir), v3(m));
        let s = wide.sample_visible(
            v3(|i| dir(i) * Vec3::new(1.0, 1.0, dir(i).z.signum())),
            (lanes(|i| u(i).0), lanes(|i| u(i).1)),
        );
        for i in 0..8 {
            let one = Ggx {
                alpha_u: au(i),
                alpha_v: av(i),
            };
            let v = dir(i) * Vec3::new(1.0, 1.0, dir(i).z.signum());
            assert_eq!(
                d.as_array()[i].to_bits(),
                one.d(m(i).into()).to_bits(),
                "D, lane {i}"
            );
            let g1 = one.g1(dir(i).into(), m(i).into());
            assert_eq!(g.as_array()[i].to_bits(), g1.to_bits(), "G1, lane {i}");
            let n = Vec3::from(one.sample_visible(v.into(), u(i)));
            assert_eq!(
                s.lane(i).to_array().map(f32::to_bits),
                n.to_array().map(f32::to_bits)
            );
        }
    }
}
