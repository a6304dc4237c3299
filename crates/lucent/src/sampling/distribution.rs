//! Piecewise-constant distributions: choosing a cell in proportion to its weight, in one
//! dimension (a light by its power, a filter by its profile) or two (an environment map by its
//! luminance × sin θ).
//!
//! Sampling inverts the cumulative distribution, so it is monotone in `u`: stratified input
//! stays stratified. A cell of zero weight is never chosen, and the densities returned with a
//! sample are those that [`Distribution1D::pdf`] and [`Distribution2D::pdf`] give for the same
//! point.

use glam::Vec2;

/// The largest float below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// A distribution over `n` cells with non-negative weights: discrete over the cell indices, or
/// continuous over `[0, 1)` cut into `n` equal cells with a density constant in each.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution1D {
    /// The weights as given.
    weights: Vec<f32>,
    /// `cdf[i]` is the share of the total weight in cells `0..i`: `cdf[0] = 0`, `cdf[n] = 1`,
    /// and `cdf[i] = cdf[i + 1]` exactly when cell `i` weighs nothing.
    cdf: Vec<f32>,
    /// The sum of the weights.
    total: f32,
}

impl Distribution1D {
    /// The distribution of `weights`, or `None` if there are none, any is negative or not
    /// finite, or all are zero (or their sum overflows).
    pub fn new(weights: &[f32]) -> Option<Self> {
        if weights.is_empty() || weights.iter().any(|w| !w.is_finite() || *w < 0.0) {
            return None;
        }
        // Prefix sums in double precision: a million small cells add up without drift, and
        // the last nonzero cell ends at exactly 1 after the division.
        let mut prefix = Vec::with_capacity(weights.len() + 1);
        let mut sum = 0.0f64;
        prefix.push(0.0);
        for &w in weights {
            sum += f64::from(w);
            prefix.push(sum);
        }
        let total = sum as f32;
        if sum <= 0.0 || !total.is_finite() {
            return None;
        }
        let cdf = prefix.iter().map(|&p| (p / sum) as f32).collect();
        Some(Self {
            weights: weights.to_vec(),
            cdf,
            total,
        })
    }

    /// The number of cells.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Always `false`: a distribution has at least one cell.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// The sum of the weights.
    pub fn total(&self) -> f32 {
        self.total
    }

    /// The cell `i` with `cdf[i] ≤ u < cdf[i + 1]` for `u` in `[0, 1)` (values outside are
    /// clamped): never a cell of zero weight.
    #[inline]
    fn find(&self, u: f32) -> usize {
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        // How many of cdf[1..n] are ≤ u. cdf[0] = 0 ≤ u and cdf[n] = 1 > u, so the cell is in
        // range, and a cell with cdf[i] = cdf[i + 1] cannot satisfy both inequalities.
        let n = self.weights.len();
        self.cdf[1..n].partition_point(|&c| c <= u)
    }

    /// Where `u` falls within cell `i`, rescaled to `[0, 1)`.
    #[inline]
    fn remap(&self, u: f32, i: usize) -> f32 {
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        let (lo, hi) = (self.cdf[i], self.cdf[i + 1]);
        ((u - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON)
    }

    /// A cell chosen with probability proportional to its weight by `u` in `[0, 1)`: its
    /// index, its probability ([`pmf`](Self::pmf)), and `u` rescaled to `[0, 1)` within the
    /// cell, uniform and independent of the choice, for reuse.
    pub fn sample_discrete(&self, u: f32) -> (usize, f32, f32) {
        if self.weights.len() == 1 {
            // One cell (a scene's only light): nothing to search, and `u` is already its own.
            return (0, 1.0, u.clamp(0.0, ONE_MINUS_EPSILON));
        }
        let i = self.find(u);
        (i, self.pmf(i), self.remap(u, i))
    }

    /// The probability of choosing cell `i`: its weight over the total (0 past the end).
    pub fn pmf(&self, i: usize) -> f32 {
        self.weights.get(i).map_or(0.0, |w| w / self.total)
    }

    /// A point `x` of `[0, 1)` with the piecewise-constant density of the weights, by `u` in
    /// `[0, 1)`: the point, its density ([`pdf`](Self::pdf)), and its cell.
    pub fn sample_continuous(&self, u: f32) -> (f32, f32, usize) {
        let i = self.find(u);
        let n = self.weights.len();
        let mut x = ((i as f32 + self.remap(u, i)) / n as f32).min(ONE_MINUS_EPSILON);
        // Rounding may carry x across an edge of cell i; step back into it, so that
        // `pdf(x)` finds the cell that was sampled.
        while self.cell_of(x) > i {
            x = x.next_down();
        }
        while self.cell_of(x) < i {
            x = x.next_up();
        }
        (x, self.cell_density(i), i)
    }

    /// The cell holding `x` in `[0, 1)`.
    #[inline]
    fn cell_of(&self, x: f32) -> usize {
        let n = self.weights.len();
        ((x * n as f32) as usize).min(n - 1)
    }

    /// The density over `[0, 1)` inside cell `i`: `n · weight / total`.
    #[inline]
    fn cell_density(&self, i: usize) -> f32 {
        self.weights[i] * self.weights.len() as f32 / self.total
    }

    /// The density of [`sample_continuous`](Self::sample_continuous) at `x`: `n · weight /
    /// total` of the cell holding `x`, and 0 outside `[0, 1)` (or for NaN).
    pub fn pdf(&self, x: f32) -> f32 {
        if (0.0..1.0).contains(&x) {
            self.cell_density(self.cell_of(x))
        } else {
            0.0
        }
    }
}

/// A piecewise-constant distribution over the unit square cut into `width × height` cells,
/// from row-major weights (row 0 at `y ∈ [0, 1/height)`), e.g. an environment map's
/// luminance × sin θ.
///
/// A row is chosen by its total weight (the marginal), then a cell within the row (the
/// conditional).
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2D {
    width: usize,
    height: usize,
    /// Over the rows, by their sums.
    marginal: Distribution1D,
    /// Over the cells of each row; `None` for a row of zero weight, which the marginal never
    /// chooses.
    conditional: Vec<Option<Distribution1D>>,
}

impl Distribution2D {
    /// The distribution of `width × height` row-major `weights`, or `None` if the size is zero
    /// or does not match, or the weights are not a valid [`Distribution1D`] (a negative or
    /// non-finite weight, all zero).
    pub fn new(weights: &[f32], width: usize, height: usize) -> Option<Self> {
        if width == 0 || height == 0 || width.checked_mul(height)? != weights.len() {
            return None;
        }
        let conditional: Vec<_> = weights
            .chunks_exact(width)
            .map(Distribution1D::new)
            .collect();
        let row_weights: Vec<f32> = weights
            .chunks_exact(width)
            .zip(&conditional)
            .map(|(row, d)| match d {
                Some(d) => d.total(),
                // A row that is not a distribution: zero (weight 0) or invalid (fail below).
                None if row.iter().all(|&w| w == 0.0) => 0.0,
                None => f32::NAN,
            })
            .collect();
        let marginal = Distribution1D::new(&row_weights)?;
        Some(Self {
            width,
            height,
            marginal,
            conditional,
        })
    }

    /// Cells across.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Cells down.
    pub fn height(&self) -> usize {
        self.height
    }

    /// A point of `[0, 1)²` with density proportional to the weight of its cell, by `u` in
    /// `[0, 1)²` (`u.y` chooses the row, `u.x` the place within it; both monotone), and its
    /// density over the unit square ([`pdf`](Self::pdf)).
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (y, row_pdf, row) = self.marginal.sample_continuous(u.y);
        let Some(cond) = &self.conditional[row] else {
            unreachable!("the marginal never chooses a row of zero weight");
        };
        let (x, x_pdf, _) = cond.sample_continuous(u.x);
        (Vec2::new(x, y), row_pdf * x_pdf)
    }

    /// The density of [`sample`](Self::sample) at `p` over the unit square: the marginal
    /// density of its row times the conditional density of its column (`width · height ·
    /// weight / total`); 0 outside `[0, 1)²`.
    pub fn pdf(&self, p: Vec2) -> f32 {
        let row_pdf = self.marginal.pdf(p.y);
        if row_pdf == 0.0 {
            return 0.0;
        }
        match &self.conditional[self.marginal.cell_of(p.y)] {
            Some(cond) => row_pdf * cond.pdf(p.x),
            None => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::uniform;
    use crate::sampling::warp::chi2;

    const WEIGHTS: [f32; 9] = [0.0, 3.0, 0.5, 0.0, 0.0, 7.0, 1e-3, 2.0, 0.0];

    fn below_one() -> f32 {
        ONE_MINUS_EPSILON
    }

    #[test]
    fn invalid_weights_are_refused() {
        assert!(Distribution1D::new(&[]).is_none());
        assert!(Distribution1D::new(&[0.0, 0.0]).is_none());
        assert!(Distribution1D::new(&[1.0, -1.0]).is_none());
        assert!(Distribution1D::new(&[1.0, f32::NAN]).is_none());
        assert!(Distribution1D::new(&[1.0, f32::INFINITY]).is_none());
        assert!(Distribution1D::new(&[f32::MAX, f32::MAX]).is_none());
        assert!(Distribution2D::new(&[1.0; 6], 2, 2).is_none());
        assert!(Distribution2D::new(&[], 0, 0).is_none());
        assert!(Distribution2D::new(&[0.0; 4], 2, 2).is_none());
        assert!(Distribution2D::new(&[1.0, 1.0, -1.0, 0.0], 2, 2).is_none());
        assert!(Distribution2D::new(&[0.0, 0.0, f32::NAN, 1.0], 2, 2).is_none());
    }

    #[test]
    fn discrete_frequencies_match_the_pmf() {
        let d = Distribution1D::new(&WEIGHTS).unwrap();
        assert_eq!(d.len(), 9);
        assert!(!d.is_empty());
        assert!((d.total() - 12.501).abs() < 1e-5);
        let pmf_sum: f32 = (0..d.len()).map(|i| d.pmf(i)).sum();
        assert!((pmf_sum - 1.0).abs() < 1e-6);
        assert_eq!(d.pmf(9), 0.0);
        let n = 200_000;
        let mut counts = vec![0.0; WEIGHTS.len()];
        let mut remapped = vec![0.0; 20];
        for s in 0..n {
            let (i, pmf, v) = d.sample_discrete(uniform(1, 0, s, 0));
            assert!(WEIGHTS[i] > 0.0, "cell {i} of zero weight");
            assert_eq!(pmf, d.pmf(i));
            assert!((0.0..1.0).contains(&v));
            counts[i] += 1.0;
            if i == 5 {
                remapped[(v * 20.0) as usize] += 1.0;
            }
        }
        let expected: Vec<f64> = (0..d.len())
            .map(|i| f64::from(d.pmf(i)) * f64::from(n))
            .collect();
        chi2::assert_fits("discrete", &counts, &expected);
        let in_5: f64 = remapped.iter().sum();
        chi2::assert_fits("remapped u", &remapped, &[in_5 / 20.0; 20]);
    }

    #[test]
    fn zero_cells_are_never_chosen_even_at_their_edges() {
        let d = Distribution1D::new(&WEIGHTS).unwrap();
        // Every cdf value, the floats either side of it, and the ends of [0, 1].
        let mut us = vec![0.0, below_one(), 1.0, -0.5, 2.0];
        for &c in &d.cdf {
            us.extend([
                c,
                f32::from_bits(c.to_bits().saturating_sub(1)),
                c.next_up(),
            ]);
        }
        for u in us {
            let (i, _, v) = d.sample_discrete(u);
            assert!(WEIGHTS[i] > 0.0, "u = {u}: cell {i}");
            assert!((0.0..1.0).contains(&v), "u = {u}: remapped {v}");
            let (x, pdf, j) = d.sample_continuous(u);
            assert!(
                WEIGHTS[j] > 0.0 && (0.0..1.0).contains(&x),
                "u = {u}: x = {x}"
            );
            assert_eq!(pdf, d.pdf(x), "u = {u}");
        }
        assert_eq!(d.sample_discrete(0.0).0, 1);
        assert_eq!(d.sample_discrete(below_one()).0, 7);
    }

    #[test]
    fn continuous_samples_follow_the_pdf() {
        let d = Distribution1D::new(&WEIGHTS).unwrap();
        // Four histogram bins per cell, each expected to hold a quarter of the cell's mass.
        let n = 200_000;
        let bins = 4 * WEIGHTS.len();
        let mut counts = vec![0.0; bins];
        let mut last = (0.0, 0.0);
        for s in 0..n {
            let u = s as f32 / n as f32;
            let (x, pdf, i) = d.sample_continuous(uniform(2, 0, s, 0));
            assert!((0.0..1.0).contains(&x));
            assert_eq!(i, d.cell_of(x));
            assert_eq!(pdf, d.pdf(x));
            assert!(pdf > 0.0);
            counts[(x * bins as f32) as usize] += 1.0;
            // Monotone in u (checked on an increasing sweep).
            let (y, _, _) = d.sample_continuous(u);
            assert!(y >= last.1, "u {} → {}, u {u} → {y}", last.0, last.1);
            last = (u, y);
        }
        let expected: Vec<f64> = (0..bins)
            .map(|b| f64::from(d.pmf(b / 4)) / 4.0 * f64::from(n))
            .collect();
        chi2::assert_fits("continuous", &counts, &expected);
        // The density integrates to 1 (midpoint rule; exact for a piecewise constant).
        let m = 9 * 1000;
        let integral: f64 = (0..m)
            .map(|k| f64::from(d.pdf((k as f32 + 0.5) / m as f32)) / f64::from(m))
            .sum();
        assert!((integral - 1.0).abs() < 1e-5, "{integral}");
        assert_eq!(d.pdf(-0.1), 0.0);
        assert_eq!(d.pdf(1.0), 0.0);
        assert_eq!(d.pdf(f32::NAN), 0.0);
    }

    #[test]
    fn one_cell_is_the_identity() {
        let d = Distribution1D::new(&[2.5]).unwrap();
        for u in [0.0, 0.3, 0.7, below_one()] {
            assert_eq!(d.sample_discrete(u), (0, 1.0, u));
            assert_eq!(d.sample_continuous(u), (u, 1.0, 0));
        }
        assert_eq!(d.pdf(0.4), 1.0);
    }

    #[test]
    fn large_distributions_end_below_one() {
        // Many cells with a tiny one at the end: u just below 1 stays in range.
        let mut w = vec![1.0; 100_000];
        w.push(1e-6);
        let d = Distribution1D::new(&w).unwrap();
        let (x, pdf, i) = d.sample_continuous(below_one());
        assert!(x < 1.0 && pdf > 0.0 && i < w.len());
        let (i, _, v) = d.sample_discrete(below_one());
        assert!(i < w.len() && v < 1.0);
    }

    /// A 6 × 4 map with a zero row, zero cells and a bright spot.
    fn map() -> (Vec<f32>, usize, usize) {
        #[rustfmt::skip]
        let w = vec![
            1.0, 2.0, 0.0, 1.0, 0.5, 0.0,
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            3.0, 0.0, 40.0, 1.0, 0.0, 2.0,
            0.1, 0.1, 0.1, 0.0, 0.1, 9.0,
        ];
        (w, 6, 4)
    }

    #[test]
    fn two_dimensional_frequencies_match_the_weights() {
        let (w, width, height) = map();
        let d = Distribution2D::new(&w, width, height).unwrap();
        assert_eq!((d.width(), d.height()), (6, 4));
        let total: f32 = w.iter().sum();
        let n = 200_000;
        let mut counts = vec![0.0; w.len()];
        for s in 0..n {
            let u = Vec2::new(uniform(3, 0, s, 0), uniform(3, 0, s, 1));
            let (p, pdf) = d.sample(u);
            assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
            let cell = (p.y * height as f32) as usize * width + (p.x * width as f32) as usize;
            assert!(w[cell] > 0.0, "cell {cell} of zero weight");
            let want = w[cell] * (width * height) as f32 / total;
            assert!((pdf - want).abs() <= 1e-5 * want, "{pdf} vs {want}");
            assert_eq!(pdf, d.pdf(p));
            counts[cell] += 1.0;
        }
        let expected: Vec<f64> = w
            .iter()
            .map(|&x| f64::from(x / total) * f64::from(n))
            .collect();
        chi2::assert_fits("2D", &counts, &expected);
        // The density integrates to 1 over the square.
        let m = 240;
        let mut integral = 0.0;
        for j in 0..m {
            for i in 0..m {
                let p = Vec2::new((i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32);
                integral += f64::from(d.pdf(p)) / (m * m) as f64;
            }
        }
        assert!((integral - 1.0).abs() < 1e-5, "{integral}");
        assert_eq!(d.pdf(Vec2::new(0.5, 1.0)), 0.0);
        assert_eq!(d.pdf(Vec2::new(-0.1, 0.5)), 0.0);
        // The corners of u.
        for u in [
            Vec2::ZERO,
            Vec2::splat(below_one()),
            Vec2::new(0.0, below_one()),
        ] {
            let (p, pdf) = d.sample(u);
            assert!(
                p.x < 1.0 && p.y < 1.0 && pdf > 0.0 && pdf == d.pdf(p),
                "{u}"
            );
        }
    }

    #[test]
    fn two_dimensional_sampling_is_monotone_in_each_coordinate() {
        let (w, width, height) = map();
        let d = Distribution2D::new(&w, width, height).unwrap();
        let steps = 300;
        for a in 0..steps {
            let (mut last_x, mut last_y) = (0.0f32, 0.0f32);
            for b in 0..steps {
                let (s, t) = (a as f32 / steps as f32, b as f32 / steps as f32);
                // Along u.x within a row, and along u.y.
                let px = d.sample(Vec2::new(t, s)).0;
                let py = d.sample(Vec2::new(s, t)).0;
                assert!(px.x >= last_x && py.y >= last_y);
                (last_x, last_y) = (px.x, py.y);
            }
        }
    }
}
