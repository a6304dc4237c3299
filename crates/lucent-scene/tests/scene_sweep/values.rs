//! The sweep's values: a seeded splitmix64 stream, the pools of ordinary and extreme numbers
//! each key draws from, and textures written as TOML.
//!
//! Colours and emissions go up to 1e30, not to `f32::MAX`: a film sums finite samples, and a
//! few of 3e38 overflow that sum to +inf. That overflow is another issue's (the film's); this
//! sweep holds the loader and the integrators to finite pixels for finite sums.

use std::fmt::Write;

/// Sebastiano Vigna's splitmix64: small, seedable, and good enough to draw test cases.
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The stream of `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        // splitmix64's step, finished by the renderer's own mixer (the same function).
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        lucent::sampling::mix64(self.0)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// Uniform in `0..n` (the modulo bias is far below what matters here).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// One of `xs`.
    pub fn pick<T: Clone>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())].clone()
    }
}

/// The smallest positive subnormal `f32`.
pub const SUBNORMAL: f32 = 1e-45;
/// Positive magnitudes far from 1, for keys that take any finite number.
pub const EXTREME: [f32; 14] = [
    SUBNORMAL,
    1e-40,
    f32::MIN_POSITIVE,
    1e-30,
    1e-20,
    1e-7,
    1e7,
    1e15,
    1e20,
    1e30,
    1e37,
    3e38,
    f32::MAX,
    0.0,
];
/// Colour components: ordinary, and extremes up to 1e30 (see the module docs).
pub const COLOUR: [f32; 8] = [0.0, 0.05, 0.2, 0.5, 0.8, 1.0, 0.5, 0.9];
pub const COLOUR_EXTREME: [f32; 9] = [SUBNORMAL, 1e-38, 1e-30, 1e-7, 2.0, 10.0, 1e6, 1e15, 1e30];
/// Numbers of `[0, 1]`.
pub const UNIT: [f32; 7] = [0.0, SUBNORMAL, 1e-30, 1e-7, 0.5, 0.9999999, 1.0];
/// Numbers of `(0, 1]`: microfacet roughness.
pub const ALPHA: [f32; 8] = [SUBNORMAL, 1e-30, 1e-10, 1e-4, 0.01, 0.1, 0.5, 1.0];
/// Indices of refraction, `[0.001, 1000]`.
pub const IOR: [f32; 10] = [
    1e-3, 0.0010001, 0.5, 0.999, 1.0, 1.0001, 1.33, 1.5, 2.4, 1e3,
];

/// A number as TOML: short as written where that is short, else in scientific notation (which
/// reads back to the same `f32`).
pub fn num(v: f32) -> String {
    let plain = format!("{v}");
    if plain.len() <= 9 {
        plain
    } else {
        format!("{v:e}")
    }
}

/// Writes the generator's choices, with how wild this scene is.
pub struct Gen {
    pub rng: SplitMix64,
    /// The chance that a value is an extreme rather than an ordinary one: some scenes are
    /// mostly ordinary (so rays hit things and shade them), some wild.
    pub wild: f64,
}

impl Gen {
    pub fn extreme(&mut self) -> bool {
        self.rng.chance(self.wild)
    }

    pub fn sign(&mut self) -> f32 {
        if self.rng.chance(0.5) { 1.0 } else { -1.0 }
    }

    /// Any finite number: a coordinate, an angle, a scale factor.
    pub fn any(&mut self, ordinary: f32) -> f32 {
        if self.extreme() {
            self.sign() * self.rng.pick(&EXTREME)
        } else {
            ordinary
        }
    }

    /// A coordinate near the origin, in `[-3, 3]`.
    pub fn near(&mut self) -> f32 {
        ((self.rng.unit() * 6.0 - 3.0) * 100.0).round() as f32 / 100.0
    }

    /// A coordinate near the origin, or far away, or tiny.
    pub fn coord(&mut self) -> f32 {
        let near = self.near();
        self.any(near)
    }

    pub fn vector(&mut self) -> String {
        let v = [self.coord(), self.coord(), self.coord()];
        vec3(v)
    }

    /// A direction: ordinary, or with extreme components.
    pub fn direction(&mut self) -> String {
        let mut v = [
            (self.rng.unit() * 2.0 - 1.0) as f32,
            (self.rng.unit() * 2.0 - 1.0) as f32,
            (self.rng.unit() * 2.0 - 1.0) as f32,
        ];
        for c in &mut v {
            *c = (*c * 100.0).round() / 100.0;
            if self.extreme() {
                *c = self.sign() * self.rng.pick(&EXTREME);
            }
        }
        if v == [0.0; 3] {
            v[1] = -1.0;
        }
        vec3(v)
    }

    pub fn colour_component(&mut self) -> f32 {
        if self.extreme() {
            self.rng.pick(&COLOUR_EXTREME)
        } else {
            self.rng.pick(&COLOUR)
        }
    }

    pub fn colour(&mut self) -> String {
        if self.rng.chance(0.4) {
            num(self.colour_component())
        } else {
            vec3([
                self.colour_component(),
                self.colour_component(),
                self.colour_component(),
            ])
        }
    }

    /// One of `pool`, or with the scene's wildness one of `extremes`.
    pub fn from(&mut self, pool: &[f32], extremes: &[f32]) -> f32 {
        if self.extreme() {
            self.rng.pick(extremes)
        } else {
            self.rng.pick(pool)
        }
    }

    /// A texture (or a plain value) for a parameter that reads colours (`colour`) or numbers
    /// in `[0, 1]`; `depth` bounds the nesting of products, mixes and steps.
    pub fn texture(&mut self, colour: bool, depth: u32) -> String {
        let plain = |g: &mut Gen| {
            if colour {
                g.colour()
            } else {
                num(g.rng.pick(&UNIT))
            }
        };
        if !self.rng.chance(0.35) {
            return plain(self);
        }
        let kinds = if depth < 2 { 7 } else { 4 };
        match self.rng.below(kinds) {
            0 => {
                let size = self.from(&[0.25, 0.5, 1.0], &EXTREME[..12]);
                let size = if size == 0.0 { 1.0 } else { size };
                format!(
                    "{{ checker = {{ even = {}, odd = {}, size = {} }} }}",
                    self.colour(),
                    self.colour(),
                    num(size)
                )
            }
            1 => {
                let placement = self.placement();
                format!(
                    "{{ checkerboard = {{ even = {}, odd = {} }}{placement} }}",
                    self.colour(),
                    self.colour()
                )
            }
            2 => self.image("tex.png"),
            3 => "{ vertex_color = true }".to_string(),
            4 => format!(
                "{{ product = [{}, {}] }}",
                self.texture(colour, depth + 1),
                self.texture(colour, depth + 1)
            ),
            5 => format!(
                "{{ mix = [{}, {}], amount = {} }}",
                self.texture(colour, depth + 1),
                self.texture(colour, depth + 1),
                self.texture(false, depth + 1)
            ),
            _ => {
                let cutoff = self.any(0.5);
                format!(
                    "{{ step = {}, cutoff = {} }}",
                    self.texture(colour, depth + 1),
                    num(cutoff)
                )
            }
        }
    }

    /// A number of `[0, 1]` or a texture (values outside are clamped where shaded).
    pub fn unit_texture(&mut self) -> String {
        self.texture(false, 0)
    }

    /// An image lookup of `file` with a random choice of its settings.
    pub fn image(&mut self, file: &str) -> String {
        let mut s = format!("{{ image = \"{file}\"");
        if self.rng.chance(0.3) {
            let _ = write!(s, ", encoding = \"{}\"", self.rng.pick(&["srgb", "linear"]));
        }
        if self.rng.chance(0.3) {
            let _ = write!(
                s,
                ", channel = \"{}\"",
                self.rng.pick(&["rgb", "r", "g", "b", "a"])
            );
        }
        if self.rng.chance(0.3) {
            let wraps = ["repeat", "mirror", "clamp"];
            let (u, v) = (self.rng.pick(&wraps), self.rng.pick(&wraps));
            let _ = write!(s, ", wrap = [\"{u}\", \"{v}\"]");
        }
        if self.rng.chance(0.5) {
            let filters = ["nearest", "bilinear", "trilinear", "anisotropic"];
            let _ = write!(s, ", filter = \"{}\"", self.rng.pick(&filters));
        }
        s += &self.placement();
        s + " }"
    }

    /// `, scale = …, offset = …, rotation = …` of a texture, each part or none.
    pub fn placement(&mut self) -> String {
        let mut s = String::new();
        if self.rng.chance(0.4) {
            let (u, v) = (self.any(4.0), self.any(2.0));
            let _ = write!(s, ", scale = [{}, {}]", num(u), num(v));
        }
        if self.rng.chance(0.3) {
            let (u, v) = (self.any(0.25), self.any(0.5));
            let _ = write!(s, ", offset = [{}, {}]", num(u), num(v));
        }
        if self.rng.chance(0.3) {
            let r = self.any(30.0);
            let _ = write!(s, ", rotation = {}", num(r));
        }
        s
    }
}

pub fn vec3(v: [f32; 3]) -> String {
    format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]))
}
