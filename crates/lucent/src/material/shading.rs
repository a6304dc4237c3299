//! The shading geometry at a hit, and how normal maps, bump maps and the shading-normal policy
//! change it.
//!
//! **The shading-normal policy.** A shading normal (interpolated, normal-mapped or bumped)
//! differs from the geometric one, so a direction can be above one surface and below the
//! other. Two rules keep that from showing:
//! - *no black fringes*: where the viewer `wo` is below the shading normal's horizon but above
//!   the geometric surface, the shading normal is turned towards the viewer, in the plane of
//!   the two, just far enough that `wo` is a little above its horizon ([`facing`]) — the BSDF
//!   always sees the viewer on the side it really is on;
//! - *no light leaks*: a light or a sampled direction counts only where the shading and the
//!   geometric normal put it on the same side (`Part`'s consistency check), so no light
//!   arrives through a surface.

use glam::{Vec2, Vec3};
use wide::f32x8;

use crate::Rgb;
use crate::lanes::{LANES, Real, V3};

/// `cos θ` of the viewer above the shading horizon that [`facing`] keeps.
const MIN_COS: f32 = 1e-2;

/// The differential geometry shading sees at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// The unit shading normal.
    pub n: Vec3,
    /// `∂p/∂u`: the tangent the shading frame follows (a mesh's own tangent where it has
    /// one, at the length of `∂p/∂u`).
    pub dpdu: Vec3,
    /// `∂p/∂v`.
    pub dpdv: Vec3,
    /// Which way a normal map's `+y` points: `1` along `n × dpdu` (Mitsuba's frame, and glTF's
    /// for unmirrored uvs), `−1` against it (a glTF tangent's `w` of −1: mirrored uvs).
    pub handedness: f32,
}

impl Geometry {
    /// The shading geometry of a hit: its shading normal and uv tangents, and the mesh's own
    /// tangent frame in place of `dpdu` where it has one.
    pub fn of_hit(hit: &crate::shape::SurfaceHit) -> Geometry {
        let (dpdu, handedness) = match hit.tangent {
            Some(t) => {
                let len = hit.dpdu.length();
                let len = if len > 0.0 { len } else { 1.0 };
                match t.truncate().try_normalize() {
                    Some(d) => (d * len, t.w.signum()),
                    None => (hit.dpdu, 1.0),
                }
            }
            None => (hit.dpdu, 1.0),
        };
        Geometry {
            n: hit.shading_normal,
            dpdu,
            dpdv: hit.dpdv,
            handedness,
        }
    }
}

impl Geometry {
    /// The geometry with its normal read from a tangent-space normal map texel `texel`
    /// (`2·texel − 1`, its x and y scaled by `strength`), in the frame (tangent `dpdu`,
    /// `handedness·(n × s)`, `n`): Mitsuba's `normalmap`, and glTF's `normalTexture`.
    pub fn normal_mapped(&self, texel: Rgb, strength: f32) -> Geometry {
        let frame = crate::bsdf::Frame::from_normal_tangent(self.n, self.dpdu);
        let local = Vec3::new(
            (2.0 * texel.r - 1.0) * strength,
            (2.0 * texel.g - 1.0) * strength * self.handedness,
            2.0 * texel.b - 1.0,
        );
        match frame.to_world(local).try_normalize() {
            Some(n) => Geometry { n, ..*self },
            None => *self,
        }
    }

    /// The geometry bumped by a height whose gradient over texture coordinates is `grad`
    /// (`∂h/∂u`, `∂h/∂v`, scale included), as Mitsuba's `bumpmap` does: the displaced surface
    /// `p + h·n` has tangents `∂p/∂u + (∂h/∂u)·n` (the tangents first made perpendicular to
    /// `n`), and its normal is their cross product, turned to the side of `ng`.
    pub fn bumped(&self, grad: Vec2, ng: Vec3) -> Geometry {
        let n = self.n;
        let dpdu = self.dpdu + n * (grad.x - n.dot(self.dpdu));
        let dpdv = self.dpdv + n * (grad.y - n.dot(self.dpdv));
        match dpdu.cross(dpdv).try_normalize() {
            Some(b) => Geometry {
                n: if b.dot(ng) < 0.0 { -b } else { b },
                ..*self
            },
            None => *self,
        }
    }
}

/// The shading normal `ns` turned, if need be, so that the viewer direction `wo` is on the same
/// side of it as of the geometric normal `ng`, at least `MIN_COS` above its horizon (the
/// policy in the module docs). `ns` itself where it already is, or where `wo` grazes `ng`.
#[inline]
pub fn facing(ns: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
    let (keep, side) = keeps_facing(ns.into(), ng.into(), wo.into());
    if keep {
        ns
    } else {
        tilted(ns, ng, wo, side.signum())
    }
}

/// [`facing`] for eight lanes: the same test in every lane, the turn (`tilted`) lane by lane
/// where it is needed, so that each lane has the scalar's bits.
#[inline(always)]
pub fn facing_lanes(ns: V3<f32x8>, ng: V3<f32x8>, wo: V3<f32x8>) -> V3<f32x8> {
    let (keep, side) = keeps_facing(ns, ng, wo);
    if keep.all() {
        return ns;
    }
    let keep = keep.to_bitmask();
    let out: [Vec3; LANES] = std::array::from_fn(|i| {
        if keep & (1 << i) != 0 {
            ns.lane(i)
        } else {
            let side = side.as_array()[i].signum();
            tilted(ns.lane(i), ng.lane(i), wo.lane(i), side)
        }
    });
    V3::gather(&out)
}

/// Whether [`facing`] keeps `ns` (where `wo` grazes `ng`, or is already `MIN_COS` above the
/// shading horizon on `ng`'s side), and `wo·ng`.
#[inline(always)]
fn keeps_facing<R: Real>(ns: V3<R>, ng: V3<R>, wo: V3<R>) -> (R::Mask, R) {
    let side = wo.dot(ng);
    let grazing = side.eq(R::splat(0.0)) | !side.finite();
    let above = (wo.dot(ns) * side.sign_one()).ge(R::splat(MIN_COS));
    (grazing | above, side)
}

/// [`facing`] where `ns` must turn (kept out of line: most shading normals already face `wo`).
#[inline(never)]
fn tilted(ns: Vec3, ng: Vec3, wo: Vec3, side: f32) -> Vec3 {
    // ns's part perpendicular to wo, then tilted towards wo by MIN_COS.
    let perp = ns - wo * wo.dot(ns);
    let perp = match perp.try_normalize() {
        Some(p) if p.dot(ng) * side > 0.0 => p,
        _ => return ng * side,
    };
    let n = perp * (1.0 - MIN_COS * MIN_COS).sqrt() + wo * (side * MIN_COS);
    n.normalize_or(ns)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_viewer_below_the_shading_horizon_is_brought_just_above_it() {
        let ng = Vec3::Z;
        let ns = Vec3::new(0.6, 0.0, 0.8);
        // Seen from far to the −x side: above the surface, below ns's horizon.
        let wo = Vec3::new(-0.95, 0.0, 0.312).normalize();
        assert!(wo.dot(ns) < 0.0 && wo.dot(ng) > 0.0);
        let bent = facing(ns, ng, wo);
        assert!((bent.length() - 1.0).abs() < 1e-5);
        assert!((wo.dot(bent) - MIN_COS).abs() < 1e-4, "{}", wo.dot(bent));
        // In the plane of ns and wo, and still on ng's side.
        assert!(bent.y.abs() < 1e-6 && bent.dot(ng) > 0.0);
        // A viewer already above is left alone; so is one from inside glass seeing the inside.
        let above = Vec3::new(0.3, 0.0, 0.95).normalize();
        assert_eq!(facing(ns, ng, above), ns);
        let inside = Vec3::new(0.3, 0.0, -0.95).normalize();
        assert_eq!(facing(ns, ng, inside), ns);
    }

    #[test]
    fn flat_normal_maps_and_bumps_leave_the_normal() {
        let g = Geometry {
            n: Vec3::Z,
            dpdu: Vec3::X * 2.0,
            dpdv: Vec3::Y * 2.0,
            handedness: 1.0,
        };
        let flat = g.normal_mapped(Rgb::new(0.5, 0.5, 1.0), 1.0);
        assert!((flat.n - Vec3::Z).length() < 1e-6);
        // A texel leaning towards +x tilts the normal towards the tangent.
        let tilted = g.normal_mapped(Rgb::new(0.8, 0.5, 0.9), 1.0);
        assert!(tilted.n.x > 0.3 && tilted.n.y.abs() < 1e-6);
        // +y of the map leans along n × t, or against it for a mirrored frame (glTF's w = −1).
        let up = Rgb::new(0.5, 0.8, 0.9);
        assert!(g.normal_mapped(up, 1.0).n.y > 0.3);
        let mirrored = Geometry {
            handedness: -1.0,
            ..g
        };
        assert!(mirrored.normal_mapped(up, 1.0).n.y < -0.3);
        assert!((g.bumped(Vec2::ZERO, Vec3::Z).n - Vec3::Z).length() < 1e-6);
        // Height rising with u: p + h n leans back, its normal towards −x.
        let b = g.bumped(Vec2::new(1.0, 0.0), Vec3::Z);
        assert!(
            (b.n - Vec3::new(-1.0, 0.0, 2.0).normalize()).length() < 1e-5,
            "{}",
            b.n
        );
    }
}
