//! Photometric lights: a point light whose intensity varies with direction as a measured table
//! says (an IES file's candela table, LM-63), the "anisotropic light sources" of the notes'
//! critique.
//!
//! A [`Profile`] holds the table as measured — intensities at a grid of two angles whose meaning
//! the photometric type ([`Goniometry`]) gives — and answers the intensity along any direction of
//! the luminaire's own frame: the direction's two angles, folded by the symmetry the table's
//! range implies, interpolated bilinearly between the four surrounding measurements, zero beyond
//! the measured range. The luminaire's frame: `−z` is the nadir (straight down, where type C's
//! vertical angle is 0), `+x` the luminaire's length (type C's `C = 0` half-plane), `+y` its
//! width (`C = 90°`).
//!
//! For photon emission and light picking a profile also tabulates itself over the sphere (cells
//! of equal angle, weighted by their solid angle): its total `∫ I dω` and a distribution to draw
//! directions from in proportion to the intensity.

use super::LightSample;
use super::point::PointLight;
use crate::sampling::distribution::Distribution2D;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;
use std::fmt;
use std::sync::Arc;

/// What a table's two angles measure (LM-63's photometric types), in the luminaire's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Goniometry {
    /// Type C (architectural luminaires): the polar axis is vertical. The vertical angle `γ`
    /// runs from the nadir (0°) through the horizontal (90°) to the zenith (180°); the
    /// horizontal angle `C` turns about the vertical axis from `+x` (0°) towards `+y` (90°).
    C,
    /// Type B (floodlights): the planes of constant `V` share the horizontal axis `y`; `V`
    /// turns from the nadir (0°) towards `+x` (90°), and `H` is the lateral angle within the
    /// plane, towards `+y`: `d = (cos H sin V, sin H, −cos H cos V)`.
    B,
    /// Type A (automotive lamps): the planes of constant `H` share the vertical axis `z`; `H`
    /// turns from `+x` (the photometric horizontal) towards `−y`, and `V` rises within the
    /// plane towards `+z` (−90° is the nadir): `d = (cos V cos H, −cos V sin H, sin V)`.
    A,
}

impl Goniometry {
    /// The (vertical, horizontal) angles in degrees of unit direction `d` of the luminaire's
    /// frame.
    pub fn angles(self, d: Vec3) -> (f32, f32) {
        match self {
            Goniometry::C => {
                let gamma = (-d.z).clamp(-1.0, 1.0).acos().to_degrees();
                let c = d.y.atan2(d.x).to_degrees().rem_euclid(360.0);
                (gamma, c)
            }
            Goniometry::B => {
                let h = d.y.clamp(-1.0, 1.0).asin().to_degrees();
                let v = d.x.atan2(-d.z).to_degrees();
                (v, h)
            }
            Goniometry::A => {
                let v = d.z.clamp(-1.0, 1.0).asin().to_degrees();
                let h = (-d.y).atan2(d.x).to_degrees();
                (v, h)
            }
        }
    }

    /// The name LM-63 gives it.
    pub fn name(self) -> &'static str {
        match self {
            Goniometry::C => "type C",
            Goniometry::B => "type B",
            Goniometry::A => "type A",
        }
    }
}

/// Why a table is not a profile: a sentence naming the value at fault.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileError(pub String);

impl fmt::Display for ProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ProfileError {}

/// The most angles of one kind a profile takes (LM-63 files have tens to a few hundred).
pub const MAX_ANGLES: usize = 10_000;

/// How a type C table's horizontal angles extend to the whole turn.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Symmetry {
    /// One horizontal angle: the same in every direction about the vertical axis.
    Rotational,
    /// 0° to 90°: mirrored in both vertical planes.
    Quadrant,
    /// 0° to 180°: mirrored in the `C = 0°–180°` plane.
    Bilateral,
    /// 90° to 270°: mirrored in the `C = 90°–270°` plane.
    BilateralAcross,
    /// 0° to 360° (the last equal to the first), or any other range: as measured, zero where
    /// not measured.
    None,
    /// Types A and B: 0° to 90° horizontally, mirrored across `H = 0`.
    Mirrored,
}

/// A measured intensity table (candela, or any unit: a light scales it), see the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    goniometry: Goniometry,
    vertical: Vec<f32>,
    horizontal: Vec<f32>,
    /// `values[h * vertical.len() + v]`.
    values: Vec<f32>,
    symmetry: Symmetry,
    /// Types A and B measured only from `V = 0°` up: mirrored below.
    vertical_mirrored: bool,
    /// `∫ I dω` over the sphere.
    total: f32,
    /// Directions drawn in proportion to intensity: over `(φ/2π, (1 − cos θ)/2)` cells, with
    /// `θ` from the nadir and `φ` from `+x` towards `+y`.
    distribution: Option<Distribution2D>,
}

/// Cells of the tabulation over the sphere: across (`φ`) and down (`θ`).
const TABLE_WIDTH: usize = 256;
const TABLE_HEIGHT: usize = 128;

impl Profile {
    /// The table of intensities `values` (for each horizontal angle, one per vertical angle)
    /// at `vertical` × `horizontal` angles in degrees, both increasing, of type `goniometry`;
    /// checked.
    pub fn new(
        goniometry: Goniometry,
        vertical: Vec<f32>,
        horizontal: Vec<f32>,
        values: Vec<f32>,
    ) -> Result<Self, ProfileError> {
        let fail = |m: String| Err(ProfileError(m));
        for (what, angles) in [("vertical", &vertical), ("horizontal", &horizontal)] {
            if angles.is_empty() || angles.len() > MAX_ANGLES {
                return fail(format!(
                    "{} {what} angles (1 to {MAX_ANGLES} are read)",
                    angles.len()
                ));
            }
            if let Some(i) = angles.iter().position(|a| !a.is_finite()) {
                return fail(format!("{what} angle #{} is not a finite number", i + 1));
            }
            if let Some(i) = angles.windows(2).position(|w| w[1] <= w[0]) {
                return fail(format!(
                    "the {what} angles must increase, and #{} ({}°) does not",
                    i + 2,
                    angles[i + 1]
                ));
            }
        }
        let expected = vertical.len() * horizontal.len();
        if values.len() != expected {
            return fail(format!(
                "{} candela values for {} vertical × {} horizontal angles ({expected})",
                values.len(),
                vertical.len(),
                horizontal.len()
            ));
        }
        if let Some(i) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return fail(format!(
                "candela value #{} ({}) is not a finite, non-negative number",
                i + 1,
                values[i]
            ));
        }
        let (v0, v1) = (vertical[0], vertical[vertical.len() - 1]);
        let (h0, h1) = (horizontal[0], horizontal[horizontal.len() - 1]);
        let range = |what: &str, first: f32, last: f32, allowed: &str| {
            ProfileError(format!("{what} angles from {first}° to {last}°: {allowed}"))
        };
        let (symmetry, vertical_mirrored) = match goniometry {
            Goniometry::C => {
                if v0 < 0.0 || v1 > 180.0 {
                    return Err(range("vertical", v0, v1, "type C's run from 0° to 180°"));
                }
                let symmetry = match (h0, h1) {
                    _ if horizontal.len() == 1 => Symmetry::Rotational,
                    (0.0, 90.0) => Symmetry::Quadrant,
                    (0.0, 180.0) => Symmetry::Bilateral,
                    (90.0, 270.0) => Symmetry::BilateralAcross,
                    _ if h0 >= 0.0 && h1 <= 360.0 => Symmetry::None,
                    _ => {
                        return Err(range(
                            "horizontal",
                            h0,
                            h1,
                            "type C's run from 0° to 360° (or 0°–90°, 0°–180°, 90°–270° for a symmetric luminaire)",
                        ));
                    }
                };
                (symmetry, false)
            }
            Goniometry::A | Goniometry::B => {
                if v0 < -90.0 || v1 > 90.0 {
                    return Err(range(
                        "vertical",
                        v0,
                        v1,
                        "types A and B run from −90° to 90° (or 0° to 90°, mirrored)",
                    ));
                }
                if h0 < -180.0 || h1 > 180.0 {
                    return Err(range(
                        "horizontal",
                        h0,
                        h1,
                        "types A and B run from −180° to 180° (or 0° up, mirrored)",
                    ));
                }
                let symmetry = if h0 == 0.0 && horizontal.len() > 1 {
                    Symmetry::Mirrored
                } else {
                    Symmetry::None
                };
                (symmetry, v0 == 0.0 && vertical.len() > 1)
            }
        };
        let mut profile = Self {
            goniometry,
            vertical,
            horizontal,
            values,
            symmetry,
            vertical_mirrored,
            total: 0.0,
            distribution: None,
        };
        profile.tabulate();
        Ok(profile)
    }

    /// Which way its angles run.
    pub fn goniometry(&self) -> Goniometry {
        self.goniometry
    }

    /// The largest intensity of the table.
    pub fn max(&self) -> f32 {
        self.values.iter().copied().fold(0.0, f32::max)
    }

    /// `∫ I dω` over the sphere (the luminaire's flux, in lumens for a table in candela), from
    /// the tabulation.
    pub fn total(&self) -> f32 {
        self.total
    }

    /// The intensity along unit direction `d` of the luminaire's frame.
    pub fn intensity(&self, d: Vec3) -> f32 {
        let (v, h) = self.goniometry.angles(d);
        self.at_angles(v, h)
    }

    /// The intensity at vertical angle `v` and horizontal angle `h` (degrees), the table's
    /// symmetry applied; zero beyond what it covers.
    pub fn at_angles(&self, v: f32, h: f32) -> f32 {
        let v = if self.vertical_mirrored { v.abs() } else { v };
        let h = match self.symmetry {
            Symmetry::Rotational => self.horizontal[0],
            Symmetry::Quadrant => {
                let h = h.rem_euclid(360.0);
                let h = if h > 180.0 { 360.0 - h } else { h };
                if h > 90.0 { 180.0 - h } else { h }
            }
            Symmetry::Bilateral => {
                let h = h.rem_euclid(360.0);
                if h > 180.0 { 360.0 - h } else { h }
            }
            Symmetry::BilateralAcross => {
                let h = h.rem_euclid(360.0);
                if h < 90.0 {
                    180.0 - h
                } else if h > 270.0 {
                    540.0 - h
                } else {
                    h
                }
            }
            Symmetry::Mirrored => h.abs(),
            Symmetry::None => match self.goniometry {
                // A full turn measured from C = 0° may end at 360° or one step short of it:
                // between the last angle and 360° the table wraps to its first.
                Goniometry::C => h.rem_euclid(360.0),
                _ => h,
            },
        };
        let nv = self.vertical.len();
        let Some((vi, vt)) = locate(&self.vertical, v) else {
            return 0.0;
        };
        let (hi, ht, wrap) = match locate(&self.horizontal, h) {
            Some((hi, ht)) => (hi, ht, None),
            None if self.symmetry == Symmetry::None
                && self.goniometry == Goniometry::C
                && self.horizontal[0] == 0.0 =>
            {
                // Between the last measured C and the full turn.
                let last = self.horizontal[self.horizontal.len() - 1];
                let t = (h - last) / (360.0 - last);
                (self.horizontal.len() - 1, t, Some(0))
            }
            None => return 0.0,
        };
        let value = |h: usize, v: usize| self.values[h * nv + v];
        let next_h = wrap.unwrap_or((hi + 1).min(self.horizontal.len() - 1));
        let next_v = (vi + 1).min(nv - 1);
        let lo = value(hi, vi) * (1.0 - vt) + value(hi, next_v) * vt;
        let hi_row = value(next_h, vi) * (1.0 - vt) + value(next_h, next_v) * vt;
        lo * (1.0 - ht) + hi_row * ht
    }

    /// The unit direction of the luminaire's frame at `θ` from the nadir and `φ` about the
    /// vertical axis from `+x` towards `+y`.
    fn direction(theta: f32, phi: f32) -> Vec3 {
        let (s, c) = theta.sin_cos();
        Vec3::new(s * phi.cos(), s * phi.sin(), -c)
    }

    /// The intensity tabulated over the sphere: `total` and `distribution`.
    fn tabulate(&mut self) {
        let (w, h) = (TABLE_WIDTH, TABLE_HEIGHT);
        let mut weights = vec![0.0; w * h];
        let mut total = 0.0f64;
        let dphi = 2.0 * PI / w as f32;
        for row in 0..h {
            // Rows of equal `cos θ` steps: equal solid angle per cell.
            let cos_hi = 1.0 - 2.0 * row as f32 / h as f32;
            let cos_lo = 1.0 - 2.0 * (row + 1) as f32 / h as f32;
            let solid_angle = dphi * (cos_hi - cos_lo);
            for col in 0..w {
                // The cell's largest intensity over its centre and corners: a cell that the
                // table lights anywhere is drawn from.
                let mut most = 0.0f32;
                let mut mean = 0.0f32;
                for (du, dv) in [(0.5, 0.5), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                    let cos = cos_hi + (cos_lo - cos_hi) * dv;
                    let phi = (col as f32 + du) * dphi;
                    let i = self.intensity(Self::direction(cos.clamp(-1.0, 1.0).acos(), phi));
                    most = most.max(i);
                    if (du, dv) == (0.5, 0.5) {
                        mean = i;
                    }
                }
                weights[row * w + col] = most * solid_angle;
                total += f64::from(mean * solid_angle);
            }
        }
        self.total = total as f32;
        self.distribution = Distribution2D::new(&weights, w, h);
    }

    /// A direction of the luminaire's frame drawn in proportion to the tabulated intensity by
    /// `u`, and its density per unit solid angle; `None` for a dark profile.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let (p, pdf) = self.distribution.as_ref()?.sample(u);
        let cos = 1.0 - 2.0 * p.y;
        let phi = 2.0 * PI * p.x;
        // The unit square maps to the sphere with Jacobian 4π (φ over 2π, cos θ over 2).
        let d = Self::direction(cos.clamp(-1.0, 1.0).acos(), phi);
        Some((d, pdf / (4.0 * PI)))
    }
}

/// The cell of increasing `angles` holding `x` and the fraction across it; a single angle is
/// its own cell; `None` outside.
fn locate(angles: &[f32], x: f32) -> Option<(usize, f32)> {
    let (first, last) = (angles[0], angles[angles.len() - 1]);
    if angles.len() == 1 {
        return Some((0, 0.0));
    }
    // A direction's angles carry rounding: a measurement at the table's edge is still its own.
    const SLACK: f32 = 1e-3;
    if !(x >= first - SLACK && x <= last + SLACK) {
        return None;
    }
    let x = x.clamp(first, last);
    let i = angles
        .partition_point(|&a| a <= x)
        .clamp(1, angles.len() - 1)
        - 1;
    let t = (x - angles[i]) / (angles[i + 1] - angles[i]);
    Some((i, t.clamp(0.0, 1.0)))
}

/// A point light whose intensity along each direction is its colour times a profile's value
/// there.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotometricLight {
    /// Position, colour (the profile's unit in lucent's: 1/683 for candela) and falloff.
    pub point: PointLight,
    /// Takes world directions to the luminaire's frame (a rotation).
    pub to_luminaire: Mat3,
    /// The measured intensities.
    pub profile: Arc<Profile>,
}

impl PhotometricLight {
    /// The light reaching `p`, if any goes its way.
    pub fn illuminate(&self, p: Vec3) -> Option<LightSample> {
        let mut s = self.point.illuminate(p)?;
        let i = self.profile.intensity(self.to_luminaire * -s.to_light);
        if i <= 0.0 {
            return None;
        }
        s.intensity = s.intensity * i;
        Some(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit direction of the luminaire's frame at type C angles (degrees).
    fn type_c(gamma: f32, c: f32) -> Vec3 {
        Profile::direction(gamma.to_radians(), c.to_radians())
    }

    #[test]
    fn an_isotropic_table_sends_four_pi() {
        let p = Profile::new(Goniometry::C, vec![0.0, 180.0], vec![0.0], vec![1.0, 1.0]).unwrap();
        for d in [
            Vec3::X,
            Vec3::NEG_Z,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
        ] {
            assert!((p.intensity(d) - 1.0).abs() < 1e-6);
        }
        assert!(
            (p.total() - 4.0 * PI).abs() < 4.0 * PI * 1e-3,
            "{}",
            p.total()
        );
    }

    #[test]
    fn a_downward_table_is_dark_above_and_interpolates_between_angles() {
        // 100 cd at the nadir falling linearly to 0 at the horizontal; nothing measured above.
        let p = Profile::new(Goniometry::C, vec![0.0, 90.0], vec![0.0], vec![100.0, 0.0]).unwrap();
        assert_eq!(p.intensity(Vec3::NEG_Z), 100.0);
        assert!((p.intensity(type_c(45.0, 30.0)) - 50.0).abs() < 1e-3);
        assert_eq!(p.intensity(Vec3::Z), 0.0);
        assert_eq!(p.intensity(type_c(120.0, 0.0)), 0.0);
        // ∫ over the lower hemisphere of 100·(1 − γ/90°): 2π·100·∫ (1 − 2γ/π) sin γ dγ.
        let exact = 2.0 * PI * 100.0 * (1.0 - 2.0 / PI);
        assert!(
            (p.total() - exact).abs() < exact * 5e-3,
            "{} {exact}",
            p.total()
        );
    }

    #[test]
    fn symmetric_tables_are_mirrored_to_the_whole_turn() {
        // Quadrant symmetry: C = 0° gives 10, C = 90° gives 20.
        let q = Profile::new(
            Goniometry::C,
            vec![0.0, 180.0],
            vec![0.0, 90.0],
            vec![10.0, 10.0, 20.0, 20.0],
        )
        .unwrap();
        for (c, want) in [
            (0.0, 10.0),
            (90.0, 20.0),
            (180.0, 10.0),
            (270.0, 20.0),
            (45.0, 15.0),
            (315.0, 15.0),
        ] {
            let got = q.intensity(type_c(60.0, c));
            assert!((got - want).abs() < 1e-3, "C = {c}: {got}");
        }
        // Bilateral: 0°–180° mirrored to 180°–360°.
        let b = Profile::new(
            Goniometry::C,
            vec![0.0, 180.0],
            vec![0.0, 90.0, 180.0],
            vec![1.0, 1.0, 2.0, 2.0, 3.0, 3.0],
        )
        .unwrap();
        assert!((b.intensity(type_c(60.0, 270.0)) - 2.0).abs() < 1e-3);
        assert!((b.intensity(type_c(60.0, 225.0)) - 2.5).abs() < 1e-3);
        // A full turn without its 360° column wraps to its first.
        let full = Profile::new(
            Goniometry::C,
            vec![0.0, 180.0],
            vec![0.0, 120.0, 240.0],
            vec![0.0, 0.0, 3.0, 3.0, 6.0, 6.0],
        )
        .unwrap();
        assert!((full.intensity(type_c(60.0, 300.0)) - 3.0).abs() < 1e-3);
    }

    #[test]
    fn photons_are_drawn_in_proportion_and_carry_the_total() {
        // A lopsided table: bright towards +x, dim elsewhere.
        let p = Profile::new(
            Goniometry::C,
            vec![0.0, 90.0, 180.0],
            vec![0.0, 90.0, 180.0, 270.0],
            vec![
                5.0, 40.0, 5.0, 5.0, 10.0, 5.0, 5.0, 1.0, 5.0, 5.0, 10.0, 5.0,
            ],
        )
        .unwrap();
        let n = 20_000;
        let mut sum = 0.0f64;
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 40) as f32 / (1u64 << 24) as f32
        };
        for _ in 0..n {
            let (d, pdf) = p.sample(Vec2::new(next(), next())).unwrap();
            assert!(pdf > 0.0);
            sum += f64::from(p.intensity(d) / pdf);
        }
        let mean = (sum / n as f64) as f32;
        assert!(
            (mean - p.total()).abs() < 0.02 * p.total(),
            "{mean} vs {}",
            p.total()
        );
    }

    #[test]
    fn bad_tables_are_refused_with_a_cause() {
        let e = |v: Vec<f32>, h: Vec<f32>, c: Vec<f32>| {
            Profile::new(Goniometry::C, v, h, c)
                .unwrap_err()
                .to_string()
        };
        assert!(
            e(vec![0.0, 90.0], vec![0.0], vec![1.0]).contains("1 candela values for 2 vertical")
        );
        assert!(e(vec![90.0, 0.0], vec![0.0], vec![1.0, 1.0]).contains("must increase"));
        assert!(e(vec![0.0, 90.0], vec![0.0], vec![1.0, f32::NAN]).contains("#2"));
        assert!(e(vec![0.0, 200.0], vec![0.0], vec![1.0, 1.0]).contains("0° to 180°"));
        assert!(e(vec![], vec![0.0], vec![]).contains("0 vertical angles"));
    }
}
