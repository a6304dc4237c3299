//! Solid patterns as POV-Ray defines them: a number at each point of space (a gradient, rings,
//! noise), shaped by a wave and looked up in a colour map; or a block pattern (checker,
//! hexagon) choosing among a few colours. Noise is lucent's own gradient noise, not POV-Ray's
//! table, so noise-based patterns (bozo, granite, agate, marble's turbulence) have POV-Ray's
//! character and scale but not its exact grain.

use crate::Rgb;
use glam::{Affine3A, Vec3};

/// What a pattern computes at a point of its space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PatternKind {
    /// `frac(p · axis)` (the axis normalised).
    Gradient(Vec3),
    /// `x`, with a triangle wave by default.
    Marble,
    /// The distance from the z axis, with a triangle wave by default.
    Wood,
    /// The distance from the origin.
    Onion,
    /// `((sin x + sin y + sin z) / 3)²`.
    Leopard,
    /// The angle about the y axis, from 0 to 1.
    Radial,
    /// `1 − min(1, |p|)`.
    Spherical,
    /// `1 − min(1, √(x² + z²))`.
    Cylindrical,
    /// `1 − min(1, |y|)`.
    Planar,
    /// `1 − min(1, max(|x|, |y|, |z|))`.
    Boxed,
    /// Noise (POV-Ray's bozo, spotted, bumps).
    Noise,
    /// Six octaves of noise folded about its middle (granite).
    Granite,
    /// Noise-bent sine bands along z (agate).
    Agate,
    /// Concentric ripples from the origin.
    Ripples,
    /// Noise summed over octaves, unsigned (wrinkles).
    Wrinkles,
    /// Unit cubes alternating between two colours.
    Checker,
    /// Hexagonal columns along y in three colours.
    Hexagon,
}

/// How a pattern's value is shaped before the map lookup.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Wave {
    /// The value's fractional part.
    #[default]
    Ramp,
    /// Up from 0 to 1 and back over one unit.
    Triangle,
    /// `(1 + sin 2πv) / 2`.
    Sine,
    /// `|sin πv|`.
    Scallop,
    /// Smoothstep of the ramp.
    Cubic,
    /// The ramp to a power.
    Poly(f32),
}

/// Turbulence: the point displaced by vector noise summed over octaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turbulence {
    /// How far, per axis.
    pub amount: Vec3,
    /// Octaves summed (1 to 10).
    pub octaves: u32,
    /// Each octave's weight relative to the one before.
    pub omega: f32,
    /// Each octave's frequency relative to the one before.
    pub lambda: f32,
}

/// A pattern placed in the world and mapped to colours.
#[derive(Clone, Debug, PartialEq)]
pub struct Pattern {
    /// What it computes.
    pub kind: PatternKind,
    /// From world positions into the pattern's space.
    pub to_pattern: Affine3A,
    /// The shaping wave.
    pub wave: Wave,
    /// The value's frequency and phase (before the wave).
    pub frequency: f32,
    /// See `frequency`.
    pub phase: f32,
    /// Turbulence, if any.
    pub turbulence: Option<Turbulence>,
    /// Colour map entries `(value, colour)`, in increasing value; a block pattern's colours
    /// in order.
    pub map: Vec<(f32, Rgb)>,
}

impl Pattern {
    /// The colour at world position `world`.
    pub fn eval(&self, world: Vec3) -> Rgb {
        let p = self.place(world);
        match self.kind {
            PatternKind::Checker => {
                let c = (p + 1e-5).floor();
                let i = (c.x + c.y + c.z).rem_euclid(2.0) as usize;
                return self.entry(i);
            }
            PatternKind::Hexagon => return self.entry(hexagon(p)),
            _ => {}
        }
        lookup(&self.map, self.shaped(p))
    }

    /// `world` in the pattern's space, turbulence included.
    fn place(&self, world: Vec3) -> Vec3 {
        self.turbulent(self.to_pattern.transform_point3(world))
    }

    /// `p` (in the pattern's space) displaced by the turbulence, if any.
    fn turbulent(&self, p: Vec3) -> Vec3 {
        match &self.turbulence {
            Some(t) => p + turbulence(p, t) * t.amount,
            None => p,
        }
    }

    /// The value at `p` (the pattern's space, turbulence applied) shaped by its frequency,
    /// phase and wave: what the colour map is looked up with, in `[0, 1]`.
    fn shaped(&self, p: Vec3) -> f32 {
        let v = self.value(p) * self.frequency + self.phase;
        match self.wave {
            Wave::Ramp => ramp(v),
            Wave::Triangle => {
                let f = ramp(v);
                if f < 0.5 { 2.0 * f } else { 2.0 - 2.0 * f }
            }
            Wave::Sine => 0.5 * (1.0 + (v * std::f32::consts::TAU).sin()),
            Wave::Scallop => (v * std::f32::consts::PI).sin().abs(),
            Wave::Cubic => {
                let f = ramp(v);
                f * f * (3.0 - 2.0 * f)
            }
            Wave::Poly(e) => ramp(v).powf(e),
        }
    }

    /// The gradient of the shaped value at `world` in the pattern's own units, by central
    /// differences `delta` apart in the pattern's space (POV-Ray's `accuracy`, 0.02 by
    /// default), turned into the world by the transpose of the placement (as a normal turns)
    /// with its length kept: a scaled pattern bends a normal as much as the unscaled one, as
    /// POV-Ray's normals do.
    pub fn slope(&self, world: Vec3, delta: f32) -> Vec3 {
        let p = self.to_pattern.transform_point3(world);
        let at = |q: Vec3| self.shaped(self.turbulent(q));
        let g = Vec3::new(
            at(p + Vec3::X * delta) - at(p - Vec3::X * delta),
            at(p + Vec3::Y * delta) - at(p - Vec3::Y * delta),
            at(p + Vec3::Z * delta) - at(p - Vec3::Z * delta),
        ) / (2.0 * delta);
        // h(w) = h'(A·w + b): ∇h = Aᵀ·∇h', whose direction is kept.
        let turned = glam::Mat3::from(self.to_pattern.matrix3).transpose() * g;
        turned.normalize_or_zero() * g.length()
    }

    fn entry(&self, i: usize) -> Rgb {
        self.map
            .get(i)
            .or(self.map.last())
            .map_or(Rgb::BLACK, |e| e.1)
    }

    /// The pattern's raw value at `p` (its own space).
    fn value(&self, p: Vec3) -> f32 {
        match self.kind {
            PatternKind::Gradient(axis) => p.dot(axis.normalize_or_zero()),
            PatternKind::Marble => p.x,
            PatternKind::Wood => (p.x * p.x + p.y * p.y).sqrt(),
            PatternKind::Onion => p.length(),
            PatternKind::Leopard => {
                let s = (p.x.sin() + p.y.sin() + p.z.sin()) / 3.0;
                s * s
            }
            PatternKind::Radial => (p.x.atan2(-p.z) / std::f32::consts::TAU + 0.5).fract(),
            PatternKind::Spherical => 1.0 - p.length().min(1.0),
            PatternKind::Cylindrical => 1.0 - (p.x * p.x + p.z * p.z).sqrt().min(1.0),
            PatternKind::Planar => 1.0 - p.y.abs().min(1.0),
            PatternKind::Boxed => 1.0 - p.abs().max_element().min(1.0),
            PatternKind::Noise => noise(p).clamp(0.0, 0.9999),
            PatternKind::Granite => {
                let mut sum = 0.0;
                let mut freq = 1.0;
                for _ in 0..6 {
                    let n = (1.0 - 2.0 * noise(p * 4.0 * freq)).abs().min(0.5);
                    sum += n / freq;
                    freq *= 2.0;
                }
                sum.clamp(0.0, 0.9999)
            }
            PatternKind::Agate => {
                let t = Turbulence {
                    amount: Vec3::ONE,
                    octaves: 7,
                    omega: 0.5,
                    lambda: 2.0,
                };
                let bent = p.z + turbulence(p, &t).x;
                (0.5 * (1.0 + (bent * std::f32::consts::TAU).sin())).powf(0.77)
            }
            PatternKind::Ripples => 0.5 * (1.0 + (p.length() * std::f32::consts::TAU).sin()),
            PatternKind::Wrinkles => {
                let mut sum = 0.0;
                let mut freq = 1.0;
                for _ in 0..10 {
                    sum += (2.0 * noise(p * freq) - 1.0).abs() / freq;
                    freq *= 2.0;
                }
                sum.clamp(0.0, 0.9999)
            }
            PatternKind::Checker | PatternKind::Hexagon => 0.0,
        }
    }
}

fn ramp(v: f32) -> f32 {
    v - v.floor()
}

/// The colour of a map at `v`: linear between neighbouring entries, the end colours beyond.
pub fn lookup(map: &[(f32, Rgb)], v: f32) -> Rgb {
    let Some(first) = map.first() else {
        return Rgb::gray(v);
    };
    if v <= first.0 {
        return first.1;
    }
    for pair in map.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if v < b.0 {
            let span = b.0 - a.0;
            let t = if span > 0.0 { (v - a.0) / span } else { 1.0 };
            return a.1.lerp(b.1, t);
        }
    }
    map.last().map_or(Rgb::BLACK, |e| e.1)
}

/// Which of the three colours of POV-Ray's hexagon tiling (in the x–z plane, sides of length
/// 1, colour 0 centred on the origin) holds `p`.
fn hexagon(p: Vec3) -> usize {
    // Axial coordinates of the hexagon holding (x, z) (pointy sides along x), by rounding
    // cube coordinates.
    let (x, z) = (p.x, p.z);
    let q = (2.0 / 3.0) * x;
    let r = (-1.0 / 3.0) * x + (3f32.sqrt() / 3.0) * z;
    let s = -q - r;
    let (mut rq, mut rr, rs) = (q.round(), r.round(), s.round());
    let (dq, dr, ds) = ((rq - q).abs(), (rr - r).abs(), (rs - s).abs());
    if dq > dr && dq > ds {
        rq = -rr - rs;
    } else if dr > ds {
        rr = -rq - rs;
    }
    ((rq - rr) as i64).rem_euclid(3) as usize
}

/// Gradient noise in [0, 1] (0.5 on average), smooth, of period 256 along each axis.
pub fn noise(p: Vec3) -> f32 {
    let cell = p.floor();
    let f = p - cell;
    let fade = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    let (ix, iy, iz) = (cell.x as i32, cell.y as i32, cell.z as i32);
    let grad = |i: i32, j: i32, k: i32, d: Vec3| -> f32 {
        let h = hash(ix + i, iy + j, iz + k);
        // 12 edge directions of the cube.
        let g = match h % 12 {
            0 => Vec3::new(1.0, 1.0, 0.0),
            1 => Vec3::new(-1.0, 1.0, 0.0),
            2 => Vec3::new(1.0, -1.0, 0.0),
            3 => Vec3::new(-1.0, -1.0, 0.0),
            4 => Vec3::new(1.0, 0.0, 1.0),
            5 => Vec3::new(-1.0, 0.0, 1.0),
            6 => Vec3::new(1.0, 0.0, -1.0),
            7 => Vec3::new(-1.0, 0.0, -1.0),
            8 => Vec3::new(0.0, 1.0, 1.0),
            9 => Vec3::new(0.0, -1.0, 1.0),
            10 => Vec3::new(0.0, 1.0, -1.0),
            _ => Vec3::new(0.0, -1.0, -1.0),
        };
        g.dot(d)
    };
    let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
    let mut corners = [0.0f32; 8];
    for (n, c) in corners.iter_mut().enumerate() {
        let (i, j, k) = ((n & 1) as i32, ((n >> 1) & 1) as i32, ((n >> 2) & 1) as i32);
        *c = grad(i, j, k, f - Vec3::new(i as f32, j as f32, k as f32));
    }
    let x0 = lerp(corners[0], corners[1], fade.x);
    let x1 = lerp(corners[2], corners[3], fade.x);
    let x2 = lerp(corners[4], corners[5], fade.x);
    let x3 = lerp(corners[6], corners[7], fade.x);
    let y0 = lerp(x0, x1, fade.y);
    let y1 = lerp(x2, x3, fade.y);
    (0.5 + 0.5 * lerp(y0, y1, fade.z)).clamp(0.0, 1.0)
}

/// A lattice point's hash (period 256 per axis).
fn hash(x: i32, y: i32, z: i32) -> u32 {
    let mut h = (x & 255) as u32;
    h = h.wrapping_mul(0x27d4_eb2d) ^ (y & 255) as u32;
    h = h.wrapping_mul(0x1656_67b1) ^ (z & 255) as u32;
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h
}

/// Vector noise summed over octaves (POV-Ray's `DTurbulence`), each component in about
/// [−1, 1].
fn turbulence(p: Vec3, t: &Turbulence) -> Vec3 {
    let mut sum = Vec3::ZERO;
    let (mut weight, mut freq) = (1.0f32, 1.0f32);
    for _ in 0..t.octaves.clamp(1, 10) {
        let q = p * freq;
        let v = Vec3::new(
            noise(q) * 2.0 - 1.0,
            noise(q + Vec3::new(31.4, 17.3, 5.9)) * 2.0 - 1.0,
            noise(q + Vec3::new(-9.7, 47.1, 23.5)) * 2.0 - 1.0,
        );
        sum += v * weight;
        weight *= t.omega;
        freq *= t.lambda;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pattern(kind: PatternKind, map: Vec<(f32, Rgb)>) -> Pattern {
        Pattern {
            kind,
            to_pattern: Affine3A::IDENTITY,
            wave: Wave::Ramp,
            frequency: 1.0,
            phase: 0.0,
            turbulence: None,
            map,
        }
    }

    #[test]
    fn a_gradient_ramps_through_its_map() {
        let p = pattern(
            PatternKind::Gradient(Vec3::X * 2.0),
            vec![(0.0, Rgb::BLACK), (1.0, Rgb::WHITE)],
        );
        assert!((p.eval(Vec3::new(0.25, 5.0, 5.0)).r - 0.25).abs() < 1e-6);
        // No mirror for negative values: −0.9375 is 0.0625 into its unit.
        assert!((p.eval(Vec3::new(-0.9375, 0.0, 0.0)).r - 0.0625).abs() < 1e-5);
    }

    #[test]
    fn checker_and_hexagon_choose_their_colours() {
        let colours = vec![(0.0, Rgb::BLACK), (1.0, Rgb::WHITE), (2.0, Rgb::gray(0.5))];
        let c = pattern(PatternKind::Checker, colours.clone());
        assert_eq!(c.eval(Vec3::new(0.5, 0.5, 0.5)), Rgb::BLACK);
        assert_eq!(c.eval(Vec3::new(-0.5, 0.5, 0.0)), Rgb::WHITE);
        // A plane exactly on a grid line shows the cell above it.
        assert_eq!(c.eval(Vec3::new(0.5, -1e-7, 0.5)), Rgb::BLACK);
        let h = pattern(PatternKind::Hexagon, colours);
        assert_eq!(h.eval(Vec3::ZERO), Rgb::BLACK);
        let across = [
            Vec3::new(1.5, 0.0, 0.866),
            Vec3::new(0.0, 0.0, 1.732),
            Vec3::new(1.5, 0.0, -0.866),
        ];
        let seen: Vec<Rgb> = across.iter().map(|p| h.eval(*p)).collect();
        assert!(
            seen.iter().all(|c| *c != Rgb::BLACK),
            "neighbours differ from the centre: {seen:?}"
        );
    }

    #[test]
    fn noise_is_smooth_and_within_its_range() {
        let mut lo: f32 = 1.0;
        let mut hi: f32 = 0.0;
        for i in 0..2000 {
            let p = Vec3::new(i as f32 * 0.37, i as f32 * 0.11, i as f32 * 0.05);
            let n = noise(p);
            lo = lo.min(n);
            hi = hi.max(n);
            let step = (noise(p + Vec3::splat(1e-3)) - n).abs();
            assert!(step < 0.01, "a jump of {step} at {p}");
        }
        assert!(lo >= 0.0 && hi <= 1.0 && hi - lo > 0.5, "range {lo}..{hi}");
    }
}
