//! Pixel reconstruction filters, applied by importance sampling (pbrt-v4's approach): each
//! camera sample is placed at an offset from the pixel centre drawn in proportion to `|f|`, and
//! added to that one pixel with the weight `f / pdf`. No sample is splatted onto neighbours, so
//! pixels stay independent (and replayable) and the film's running sums need no locks.
//!
//! The filter's integral is divided out of the weight, so for a filter that is never negative
//! and is sampled exactly (box, tent) every weight is 1; a tabulated filter (Gaussian) gives
//! weights near 1, and Mitchell's negative lobes give negative ones. In every case the expected
//! weight is 1, and the pixel's estimate, `Σ w·L / Σ w`, tends to `∫ f·L / ∫ f`.
//!
//! Filters are separable, `f(x, y) = f₁(x)·f₁(y)`, with offsets in pixels and `|x|, |y| ≤
//! radius`. [`Filter`] is the description (what a scene file names); [`FilterSampler`] holds the
//! tables a Gaussian or Mitchell filter samples from, built once per render.
//!
//! To add a filter: a variant, its arms in `Filter::profile` (the one-axis shape),
//! [`Filter::radius`], [`Filter::name`], [`Filter::default_of`] and [`Filter::validate`], and an
//! exact inversion in [`FilterSampler::sample`] or an arm in `FilterSampler::new` that
//! tabulates it.

use glam::Vec2;

use crate::sampling::distribution::Distribution1D;

/// A separable pixel reconstruction filter; offsets and radii in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    /// 1 within `radius` of the centre on both axes; radius 0.5 covers exactly one pixel.
    Box {
        /// Half the width of the square, in pixels.
        radius: f32,
    },
    /// `max(0, radius − |x|)` on each axis: linear interpolation between pixels at radius 1.
    Tent {
        /// Where the filter reaches zero, in pixels.
        radius: f32,
    },
    /// A Gaussian of standard deviation `sigma` less its value at `radius` (so that it reaches
    /// zero there without a step), on each axis.
    Gaussian {
        /// Where the filter is cut off, in pixels.
        radius: f32,
        /// Standard deviation, in pixels.
        sigma: f32,
    },
    /// Mitchell and Netravali's cubic (1988) with parameters `b` and `c`, stretched so that
    /// its support `[−2, 2]` covers `[−radius, radius]`. `b = c = 1/3` is their recommendation;
    /// `b = 0, c = 1/2` is Catmull–Rom. It has negative lobes, which sharpen.
    Mitchell {
        /// Half the width of the support, in pixels.
        radius: f32,
        /// Blur: 1 gives the cubic B-spline.
        b: f32,
        /// Ringing: larger values sharpen more.
        c: f32,
    },
}

impl Default for Filter {
    /// `Box { radius: 0.5 }`: each sample counts for the one pixel it falls in, with weight 1.
    fn default() -> Self {
        Filter::Box { radius: 0.5 }
    }
}

/// Mitchell and Netravali's cubic on `[−2, 2]`: a piecewise cubic with a partition of unity
/// (`∫ = 1` for every `b`, `c`).
fn mitchell_1d(x: f32, b: f32, c: f32) -> f32 {
    let x = x.abs();
    let (x2, x3) = (x * x, x * x * x);
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else if x < 2.0 {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    v * (1.0 / 6.0)
}

/// `exp(−x² / 2σ²)`.
fn gaussian_1d(x: f32, sigma: f32) -> f32 {
    (-x * x / (2.0 * sigma * sigma)).exp()
}

/// The widest filter radius, in pixels.
pub const MAX_RADIUS: f32 = 16.0;

impl Filter {
    /// The named filter with its usual parameters: `"box"` radius 0.5, `"tent"` radius 1,
    /// `"gaussian"` radius 1.5 and σ 0.5, `"mitchell"` radius 2 and `b = c = 1/3`; `None` for
    /// another name. The inverse of [`name`](Self::name).
    pub fn default_of(name: &str) -> Option<Filter> {
        Some(match name {
            "box" => Filter::Box { radius: 0.5 },
            "tent" => Filter::Tent { radius: 1.0 },
            "gaussian" => Filter::Gaussian {
                radius: 2.0,
                sigma: 0.5,
            },
            "mitchell" => Filter::Mitchell {
                radius: 2.0,
                b: 1.0 / 3.0,
                c: 1.0 / 3.0,
            },
            _ => return None,
        })
    }

    /// The lower-case name of the kind of filter (`"box"`, `"tent"`, `"gaussian"`,
    /// `"mitchell"`).
    pub fn name(&self) -> &'static str {
        match self {
            Filter::Box { .. } => "box",
            Filter::Tent { .. } => "tent",
            Filter::Gaussian { .. } => "gaussian",
            Filter::Mitchell { .. } => "mitchell",
        }
    }

    /// How far from the pixel centre the filter reaches on each axis, in pixels.
    pub fn radius(&self) -> f32 {
        match *self {
            Filter::Box { radius }
            | Filter::Tent { radius }
            | Filter::Gaussian { radius, .. }
            | Filter::Mitchell { radius, .. } => radius,
        }
    }

    /// `Err` naming the parameter when one is out of range: radii and σ must be positive and
    /// finite, `b` and `c` finite.
    pub fn validate(&self) -> Result<(), String> {
        let name = self.name();
        let r = self.radius();
        if !(r.is_finite() && r > 0.0 && r <= MAX_RADIUS) {
            return Err(format!(
                "{name} filter: radius must be positive and at most {MAX_RADIUS} pixels, not {r}"
            ));
        }
        if self.profile(0.0) <= 0.0 {
            return Err(format!("{name} filter: it is zero at its centre"));
        }
        match *self {
            Filter::Gaussian { sigma, .. } if !(sigma.is_finite() && sigma > 0.0) => Err(format!(
                "gaussian filter: sigma must be positive, not {sigma}"
            )),
            Filter::Mitchell { b, c, .. } if !(b.is_finite() && c.is_finite()) => Err(format!(
                "mitchell filter: b and c must be finite, not {b} and {c}"
            )),
            _ => Ok(()),
        }
    }

    /// The filter's profile on one axis, `f₁(x)`, unnormalised (1 at the centre of a box).
    fn profile(&self, x: f32) -> f32 {
        let r = self.radius();
        if x.abs() > r {
            return 0.0;
        }
        match *self {
            Filter::Box { .. } => 1.0,
            Filter::Tent { .. } => r - x.abs(),
            Filter::Gaussian { sigma, .. } => {
                (gaussian_1d(x, sigma) - gaussian_1d(r, sigma)).max(0.0)
            }
            Filter::Mitchell { b, c, .. } => mitchell_1d(2.0 * x / r, b, c),
        }
    }

    /// `out[i] = f₁(x0 − i)`: the profile at offsets one pixel apart, as a splat needs them
    /// (the Gaussian's tail worked out once, not per offset).
    pub fn profiles_from(&self, x0: f32, out: &mut [f32]) {
        match *self {
            Filter::Gaussian { sigma, radius } => {
                let tail = gaussian_1d(radius, sigma);
                for (i, o) in out.iter_mut().enumerate() {
                    let x = x0 - i as f32;
                    *o = if x.abs() > radius {
                        0.0
                    } else {
                        (gaussian_1d(x, sigma) - tail).max(0.0)
                    };
                }
            }
            _ => {
                for (i, o) in out.iter_mut().enumerate() {
                    *o = self.profile(x0 - i as f32);
                }
            }
        }
    }

    /// The filter's value at offset `(x, y)` from the pixel centre, in pixels: `f₁(x)·f₁(y)`,
    /// unnormalised (the film divides by the sum of weights), 0 beyond the radius.
    pub fn eval(&self, x: f32, y: f32) -> f32 {
        self.profile(x) * self.profile(y)
    }

    /// The tables to sample this filter with, built once: see [`FilterSampler::new`].
    ///
    /// # Panics
    /// If the filter is invalid ([`validate`](Self::validate)); scenes are checked when built.
    pub fn sampler(&self) -> FilterSampler {
        FilterSampler::new(*self).unwrap_or_else(|e| panic!("{e}"))
    }

    /// An offset from the pixel centre drawn in proportion to |f|, and the sample's film weight
    /// f/pdf normalised so that positive filters give weight 1 (Mitchell's negative lobes give
    /// negative weights).
    ///
    /// `u` in `[0, 1)²`; the offset is in pixels, within the radius on each axis; the expected
    /// weight is 1. Box and tent filters are inverted exactly (weight exactly 1). Gaussian and
    /// Mitchell filters are sampled from a table of `|f₁|`, which this builds on every call: a
    /// renderer takes many samples through one [`FilterSampler`] instead, with the same
    /// results.
    ///
    /// # Panics
    /// If the filter is invalid ([`validate`](Self::validate)).
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        self.sampler().sample(u)
    }
}

/// A filter ready to be sampled: for a Gaussian or Mitchell filter, the tabulated distribution
/// of its profile. Build one per render and share it (it is read-only).
#[derive(Clone, Debug, PartialEq)]
pub struct FilterSampler {
    filter: Filter,
    table: Option<Table>,
}

/// A piecewise-constant distribution over `[−radius, radius]` whose cells weigh `∫|f₁|` over
/// them, and the signed integral `∫ f₁` that normalises the weights.
#[derive(Clone, Debug, PartialEq)]
struct Table {
    distribution: Distribution1D,
    integral: f32,
}

/// Nodes and weights of 4-point Gauss–Legendre quadrature on `[−1, 1]`: exact for cubics, so
/// for each piece of a Mitchell filter.
const GAUSS_LEGENDRE_4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

impl Table {
    fn new(filter: &Filter) -> Self {
        let r = f64::from(filter.radius());
        // Cells narrow enough to follow the shape: a Mitchell filter's shape does not depend
        // on its radius; a Gaussian's cells are at most σ/32 wide. A multiple of 4, so that
        // Mitchell's knots at ±radius/2 fall on cell edges and each cell is one cubic.
        let n = match *filter {
            Filter::Gaussian { radius, sigma } => {
                ((64.0 * radius / sigma).ceil() as usize).clamp(128, 4096)
            }
            _ => 128,
        }
        .next_multiple_of(4);
        let h = 2.0 * r / n as f64;
        let (mut weights, mut integral) = (Vec::with_capacity(n), 0.0f64);
        for i in 0..n {
            let mid = -r + (i as f64 + 0.5) * h;
            let (mut abs, mut signed) = (0.0, 0.0);
            for (node, weight) in GAUSS_LEGENDRE_4 {
                let v = f64::from(filter.profile((mid + 0.5 * h * node) as f32));
                abs += weight * v.abs();
                signed += weight * v;
            }
            weights.push((0.5 * h * abs) as f32);
            integral += 0.5 * h * signed;
        }
        let distribution =
            Distribution1D::new(&weights).expect("a valid filter has a positive integral");
        Self {
            distribution,
            integral: integral as f32,
        }
    }

    /// An offset on one axis for `u`, and its weight `f₁ / (pdf · ∫f₁)`.
    fn sample(&self, filter: &Filter, u: f32) -> (f32, f32) {
        let r = filter.radius();
        let (t, pdf_t, _) = self.distribution.sample_continuous(u);
        let x = r * (2.0 * t - 1.0);
        // The density over x is pdf_t / 2r.
        let weight = filter.profile(x) * 2.0 * r / (pdf_t * self.integral);
        (x, weight)
    }
}

/// The inverse of the cumulative distribution of a tent of radius `r`: density `(r − |x|)/r²`.
fn sample_tent(u: f32, r: f32) -> f32 {
    if u < 0.5 {
        r * ((2.0 * u).sqrt() - 1.0)
    } else {
        r * (1.0 - (2.0 - 2.0 * u).sqrt())
    }
}

impl FilterSampler {
    /// The sampler of `filter`, or `Err` naming a parameter out of range
    /// ([`Filter::validate`]).
    ///
    /// A Gaussian or Mitchell filter is tabulated: 128 cells across its width (a Gaussian up to
    /// 4,096, enough for cells no wider than σ/32), each weighing the integral of `|f₁|` over
    /// it.
    pub fn new(filter: Filter) -> Result<Self, String> {
        filter.validate()?;
        let table = match filter {
            Filter::Box { .. } | Filter::Tent { .. } => None,
            Filter::Gaussian { .. } | Filter::Mitchell { .. } => Some(Table::new(&filter)),
        };
        Ok(Self { filter, table })
    }

    /// The filter this samples.
    pub fn filter(&self) -> Filter {
        self.filter
    }

    /// As [`Filter::sample`]: an offset from the pixel centre in pixels drawn in proportion to
    /// `|f|` by `u` in `[0, 1)²`, and its film weight `f / (pdf · ∫f)` (expected value 1).
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        match (self.filter, &self.table) {
            (Filter::Box { radius }, _) => (radius * (2.0 * u - Vec2::ONE), 1.0),
            (Filter::Tent { radius }, _) => (
                Vec2::new(sample_tent(u.x, radius), sample_tent(u.y, radius)),
                1.0,
            ),
            (filter, Some(table)) => {
                let (x, wx) = table.sample(&filter, u.x);
                let (y, wy) = table.sample(&filter, u.y);
                (Vec2::new(x, y), wx * wy)
            }
            (_, None) => unreachable!("Gaussian and Mitchell filters are tabulated"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::uniform;
    use crate::sampling::warp::chi2;

    fn filters() -> Vec<Filter> {
        vec![
            Filter::default(),
            Filter::Box { radius: 1.5 },
            Filter::default_of("tent").unwrap(),
            Filter::Tent { radius: 2.5 },
            Filter::default_of("gaussian").unwrap(),
            Filter::Gaussian {
                radius: 3.0,
                sigma: 0.4,
            },
            Filter::default_of("mitchell").unwrap(),
            // Catmull–Rom, with deeper negative lobes, on a narrower support.
            Filter::Mitchell {
                radius: 1.5,
                b: 0.0,
                c: 0.5,
            },
        ]
    }

    fn point(seed: u64, i: u32) -> Vec2 {
        Vec2::new(uniform(seed, 0, i, 0), uniform(seed, 0, i, 1))
    }

    #[test]
    fn filter_weighted_means_match_the_filter() {
        // E[w·g(offset)] / E[w] against ∫f·g / ∫f by the midpoint rule on a grid whose lines
        // fall on the filters' knots (centre, ±radius/2, ±radius).
        type G = fn(Vec2) -> f64;
        let tests: [(&str, G); 4] = [
            ("x²", |p| f64::from(p.x * p.x)),
            ("cos x · cos y", |p| f64::from(p.x.cos() * p.y.cos())),
            ("(x + 0.3)·y + y²", |p| {
                f64::from((p.x + 0.3) * p.y + p.y * p.y)
            }),
            ("a bump off centre", |p| {
                f64::from((-(p - Vec2::new(0.4, -0.2)).length_squared()).exp())
            }),
        ];
        let n = 200_000;
        for filter in filters() {
            let sampler = filter.sampler();
            let samples: Vec<(Vec2, f32)> = (0..n).map(|i| sampler.sample(point(1, i))).collect();
            let r = filter.radius();
            let m = 400;
            let h = 2.0 * r / m as f32;
            let grid: Vec<(Vec2, f64)> = (0..m * m)
                .map(|k| {
                    let (i, j) = (k % m, k / m);
                    let p = Vec2::new(-r + (i as f32 + 0.5) * h, -r + (j as f32 + 0.5) * h);
                    (p, f64::from(filter.eval(p.x, p.y)))
                })
                .collect();
            let f_sum: f64 = grid.iter().map(|g| g.1).sum();
            for (name, g) in tests {
                let want = grid.iter().map(|&(p, f)| f * g(p)).sum::<f64>() / f_sum;
                let w_sum: f64 = samples.iter().map(|s| f64::from(s.1)).sum();
                let got = samples
                    .iter()
                    .map(|&(p, w)| f64::from(w) * g(p))
                    .sum::<f64>()
                    / w_sum;
                // The standard error of a ratio estimator.
                let var: f64 = samples
                    .iter()
                    .map(|&(p, w)| (f64::from(w) * (g(p) - got)).powi(2))
                    .sum();
                let se = var.sqrt() / w_sum;
                assert!(
                    (got - want).abs() < 5.0 * se + 1e-4,
                    "{filter:?}, g = {name}: {got} vs {want} (σ {se})"
                );
                assert!(se < 0.01, "{filter:?}, g = {name}: σ {se}");
            }
        }
    }

    #[test]
    fn expected_weights_are_one() {
        let n = 200_000;
        for filter in filters() {
            let sampler = filter.sampler();
            let (mut sum, mut sq, mut negative) = (0.0f64, 0.0f64, 0u32);
            for i in 0..n {
                let w = f64::from(sampler.sample(point(2, i)).1);
                assert!(w.is_finite());
                sum += w;
                sq += w * w;
                negative += u32::from(w < 0.0);
            }
            let mean = sum / f64::from(n);
            let se = ((sq / f64::from(n) - mean * mean) / f64::from(n)).sqrt();
            assert!(
                (mean - 1.0).abs() < 5.0 * se + 1e-6,
                "{filter:?}: {mean} ± {se}"
            );
            match filter {
                Filter::Mitchell { .. } => assert!(negative > 0, "{filter:?}"),
                _ => assert_eq!(negative, 0, "{filter:?}"),
            }
        }
    }

    #[test]
    fn box_and_tent_weights_are_exactly_one_and_gaussian_near_it() {
        for i in 0..10_000 {
            let u = point(3, i);
            assert_eq!(Filter::default().sample(u).1, 1.0);
            assert_eq!(Filter::Tent { radius: 1.0 }.sample(u).1, 1.0);
        }
        // A Gaussian is tabulated: its weight on each axis is f₁ over the mean of f₁ in the
        // cell. Away from the cut-off (where f₁ → 0 in the last cell) that is within a few
        // percent of 1; the 2D weight is the product of the two axes'.
        let filter = Filter::default_of("gaussian").unwrap();
        let g = filter.sampler();
        let table = g.table.as_ref().unwrap();
        for i in 0..10_000 {
            let (x, w) = table.sample(&filter, uniform(4, 0, i, 0));
            assert!(w > 0.0 || x.abs() == 1.5, "{x}: {w}");
            if x.abs() < 1.0 {
                assert!((w - 1.0).abs() < 0.05, "{x}: {w}");
            }
        }
    }

    #[test]
    fn box_offsets_are_uniform_over_the_pixel() {
        let filter = Filter::default();
        let n = 100_000;
        let mut counts = vec![0.0; 100];
        for i in 0..n {
            let (p, _) = filter.sample(point(5, i));
            assert!(p.x >= -0.5 && p.x < 0.5 && p.y >= -0.5 && p.y < 0.5, "{p}");
            let q = (p + Vec2::splat(0.5)) * 10.0;
            counts[q.y as usize * 10 + q.x as usize] += 1.0;
        }
        chi2::assert_fits("box offsets", &counts, &[f64::from(n) / 100.0; 100]);
    }

    #[test]
    fn tent_offsets_follow_the_tent() {
        // The x offsets in 20 bins: a bin [a, b] of a unit tent holds ∫ₐᵇ (1 − |x|) dx.
        let filter = Filter::Tent { radius: 1.0 };
        let n = 100_000;
        let mut counts = vec![0.0; 20];
        for i in 0..n {
            let (p, _) = filter.sample(point(6, i));
            counts[(((p.x + 1.0) * 10.0) as usize).min(19)] += 1.0;
        }
        let cdf = |x: f64| {
            if x < 0.0 {
                (1.0 + x).powi(2) / 2.0
            } else {
                1.0 - (1.0 - x).powi(2) / 2.0
            }
        };
        let expected: Vec<f64> = (0..20)
            .map(|b| {
                let (a, c) = (-1.0 + b as f64 / 10.0, -1.0 + (b + 1) as f64 / 10.0);
                (cdf(c) - cdf(a)) * f64::from(n)
            })
            .collect();
        chi2::assert_fits("tent offsets", &counts, &expected);
    }

    #[test]
    fn offsets_stay_within_the_radius() {
        let below_one = 1.0 - f32::EPSILON / 2.0;
        let edges = [0.0, 1e-7, 0.25, 0.5, 0.75, 1.0 - 1e-6, below_one];
        for filter in filters() {
            let sampler = filter.sampler();
            let r = filter.radius();
            let us = edges
                .iter()
                .flat_map(|&x| edges.iter().map(move |&y| Vec2::new(x, y)))
                .chain((0..20_000).map(|i| point(7, i)));
            for (k, u) in us.enumerate() {
                let (p, w) = sampler.sample(u);
                assert!(p.x.abs() <= r && p.y.abs() <= r, "{filter:?}: {u} → {p}");
                assert!(w.is_finite(), "{filter:?}: {u} → weight {w}");
                // The one-off path (which tabulates on every call) gives the same samples.
                if k < 1000 {
                    assert_eq!((p, w), filter.sample(u));
                }
            }
        }
    }

    #[test]
    fn values_are_the_published_shapes() {
        let m = Filter::default_of("mitchell").unwrap();
        let (b, c) = (1.0f32 / 3.0, 1.0f32 / 3.0);
        // At the centre (6 − 2B)/6 per axis, B/6 at the knot, 0 at the edge.
        assert!((m.eval(0.0, 0.0) - ((6.0 - 2.0 * b) / 6.0).powi(2)).abs() < 1e-6);
        assert!((m.eval(1.0, 0.0) - b / 6.0 * (6.0 - 2.0 * b) / 6.0).abs() < 1e-6);
        assert!(m.eval(2.0, 0.0).abs() < 1e-6 && m.eval(2.1, 0.0) == 0.0);
        assert!(m.eval(1.5, 0.0) < 0.0, "the negative lobe");
        // A partition of unity: the integral of the Mitchell cubic is 1 for any B and C.
        for (b, c) in [(b, c), (0.0, 0.5), (1.0, 0.0), (0.2, 0.9)] {
            let k = 4000;
            let integral: f32 = (0..k)
                .map(|i| {
                    mitchell_1d(-2.0 + 4.0 * (i as f32 + 0.5) / k as f32, b, c) * 4.0 / k as f32
                })
                .sum();
            assert!(
                (integral - 1.0).abs() < 1e-4,
                "B = {b}, C = {c}: {integral}"
            );
        }
        let g = Filter::default_of("gaussian").unwrap();
        assert_eq!(g.eval(2.0, 0.0), 0.0);
        assert!(g.eval(0.0, 0.0) > g.eval(0.3, 0.2));
        assert!((g.eval(0.3, -0.2) - g.eval(-0.3, 0.2)).abs() < 1e-7);
        let b = Filter::default();
        assert_eq!((b.eval(0.5, -0.5), b.eval(0.51, 0.0)), (1.0, 0.0));
        assert_eq!(Filter::Tent { radius: 2.0 }.eval(1.0, -1.5), 0.5);
    }

    #[test]
    fn names_defaults_and_validation() {
        assert_eq!(Filter::default(), Filter::Box { radius: 0.5 });
        for name in ["box", "tent", "gaussian", "mitchell"] {
            let f = Filter::default_of(name).unwrap();
            assert_eq!(f.name(), name);
            assert!(f.validate().is_ok());
            assert_eq!(FilterSampler::new(f).unwrap().filter(), f);
        }
        assert_eq!(Filter::default_of("lanczos"), None);
        assert_eq!(Filter::default_of("mitchell").unwrap().radius(), 2.0);
        for bad in [
            Filter::Box { radius: 0.0 },
            Filter::Tent { radius: -1.0 },
            Filter::Gaussian {
                radius: f32::NAN,
                sigma: 0.5,
            },
            Filter::Gaussian {
                radius: 1.5,
                sigma: 0.0,
            },
            Filter::Mitchell {
                radius: 2.0,
                b: f32::INFINITY,
                c: 0.3,
            },
        ] {
            let e = bad.validate().unwrap_err();
            assert!(e.starts_with(bad.name()), "{e}");
            assert!(FilterSampler::new(bad).is_err());
        }
    }
}
