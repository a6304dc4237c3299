//! Linear RGB radiance and reflectance triples.

use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Sub};

/// A linear RGB triple: a radiance, an intensity or a per-channel coefficient.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
}

impl Rgb {
    /// Black, or a zero coefficient.
    pub const BLACK: Rgb = Rgb::gray(0.0);
    /// White, or a unit coefficient.
    pub const WHITE: Rgb = Rgb::gray(1.0);

    /// The triple `(r, g, b)`.
    pub const fn new(r: f32, g: f32, b: f32) -> Self {
        Self { r, g, b }
    }

    /// The same value in all three channels.
    pub const fn gray(v: f32) -> Self {
        Self { r: v, g: v, b: v }
    }

    /// The largest channel.
    pub fn max_channel(self) -> f32 {
        self.r.max(self.g).max(self.b)
    }

    /// True when every channel is zero.
    pub fn is_black(self) -> bool {
        self.r == 0.0 && self.g == 0.0 && self.b == 0.0
    }

    /// True when every channel is finite.
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }

    /// The channels as an array.
    pub fn to_array(self) -> [f32; 3] {
        [self.r, self.g, self.b]
    }

    /// The mean of the three channels.
    pub fn mean(self) -> f32 {
        (self.r + self.g + self.b) / 3.0
    }

    /// The luminance of linear sRGB primaries (Rec. 709 weights, as Mitsuba's `luminance`).
    pub fn luminance(self) -> f32 {
        0.212_671 * self.r + 0.715_160 * self.g + 0.072_169 * self.b
    }

    /// `self·(1 − t) + other·t`.
    pub fn lerp(self, other: Rgb, t: f32) -> Rgb {
        self * (1.0 - t) + other * t
    }

    /// Each channel clamped to `[lo, hi]`.
    pub fn clamp(self, lo: f32, hi: f32) -> Rgb {
        Rgb::new(
            self.r.clamp(lo, hi),
            self.g.clamp(lo, hi),
            self.b.clamp(lo, hi),
        )
    }

    /// `f` applied to each channel.
    pub fn map(self, f: impl Fn(f32) -> f32) -> Rgb {
        Rgb::new(f(self.r), f(self.g), f(self.b))
    }

    /// `self^e` per channel.
    pub fn powi(self, e: i32) -> Self {
        Self::new(self.r.powi(e), self.g.powi(e), self.b.powi(e))
    }
}

impl From<[f32; 3]> for Rgb {
    fn from([r, g, b]: [f32; 3]) -> Self {
        Self { r, g, b }
    }
}

impl Add for Rgb {
    type Output = Rgb;
    fn add(self, o: Rgb) -> Rgb {
        Rgb::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Rgb) {
        *self = *self + o;
    }
}

impl Mul for Rgb {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl MulAssign for Rgb {
    fn mul_assign(&mut self, o: Rgb) {
        *self = *self * o;
    }
}

impl Mul<f32> for Rgb {
    type Output = Rgb;
    fn mul(self, s: f32) -> Rgb {
        Rgb::new(self.r * s, self.g * s, self.b * s)
    }
}

impl Mul<Rgb> for f32 {
    type Output = Rgb;
    fn mul(self, c: Rgb) -> Rgb {
        c * self
    }
}

impl Sub for Rgb {
    type Output = Rgb;
    fn sub(self, o: Rgb) -> Rgb {
        Rgb::new(self.r - o.r, self.g - o.g, self.b - o.b)
    }
}

impl Div<f32> for Rgb {
    type Output = Rgb;
    fn div(self, s: f32) -> Rgb {
        Rgb::new(self.r / s, self.g / s, self.b / s)
    }
}
