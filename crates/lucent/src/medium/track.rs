//! Tracking through a heterogeneous medium, whose coefficients are its own (per unit density)
//! times a [`DensityGrid`]'s density.
//!
//! Both estimators fill the medium with fictitious "null" particles up to a majorant, cell by
//! cell of the grid's majorant walk, so that collisions with the sum are exponentially
//! distributed and can be drawn exactly (Woodcock's delta tracking):
//! - *Delta tracking* ([`sample_distance`]) draws tentative collisions at the hero channel's
//!   majorant rate and takes each for real with probability `density / majorant`; a real one is
//!   where the path scatters, a null one goes on. Every stretch and choice contributes to the
//!   throughput and to the channels' densities relative to the hero's as in the homogeneous
//!   case, so the path's spectral MIS ([`super::Interaction`]) covers null collisions as well
//!   (pbrt-v4's `r_u`).
//! - *Ratio tracking* ([`transmittance`]) draws tentative collisions at one rate for all
//!   channels and multiplies the estimate by each collision's null share `1 − σt/majorant`:
//!   unbiased transmittance without ending at the first real collision (Novák et al. 2014),
//!   ended by Russian roulette once it is small.

use super::grid::DensityGrid;
use super::{Interaction, Medium};
use crate::Rgb;
use crate::sampling::Rng;
use glam::Vec3;

/// Below this, ratio tracking's estimate plays Russian roulette.
const ROULETTE_BELOW: f32 = 0.1;

/// Delta tracking along `origin + t·dir` (unit `dir`) for a segment of length `end`: where the
/// path scatters, or that it passes. The first collision is drawn from `u`, the rest from `rng`.
pub(super) fn sample_distance(
    m: &Medium,
    grid: &DensityGrid,
    (origin, dir): (Vec3, Vec3),
    end: f32,
    hero: usize,
    u: f32,
    rng: &mut Rng,
) -> Interaction {
    if !m.scatters() {
        return Interaction::Pass {
            weight: transmittance(m, grid, (origin, dir), end, rng),
            ratio: Rgb::WHITE,
        };
    }
    let st = m.sigma_t();
    let s_hero = st.to_array()[hero];
    // The product of every stretch's and null collision's factor so far; weight and ratio are
    // both proportional to it, so it is kept at mean 1 (the path's MIS divides it out).
    let mut acc = Rgb::WHITE;
    let mut u = u;
    for cell in grid.walk(origin, dir, 0.0, end) {
        if cell.majorant <= 0.0 {
            continue;
        }
        let rate = cell.majorant * s_hero;
        let mut t = cell.t0;
        loop {
            let step = if rate > 0.0 {
                -(1.0 - u).ln() / rate
            } else {
                f32::INFINITY
            };
            u = rng.f32();
            // The majorant transmittance up to the collision or the cell's end, over the
            // hero's probability of getting there.
            let reach = step.min(cell.t1 - t);
            let tr = st.map(|s| (-cell.majorant * s * reach).exp());
            let tr_hero = tr.to_array()[hero];
            if tr_hero <= 0.0 || tr_hero.is_nan() {
                return dead(t);
            }
            if t + step >= cell.t1 {
                acc = normalised(acc * tr / tr_hero);
                break;
            }
            t += step;
            let at = origin + dir * t;
            let density = grid.density(at);
            // A collision of either kind has, per channel, the density of the hero's times
            // `tr·σt / (tr_hero·σt_hero)`; a real one contributes `tr·σs`, a null one `tr·σn`,
            // and σn is σt's multiple `1 − density / majorant` in every channel.
            let ratio = acc * tr * st / (tr_hero * s_hero);
            if rng.f32() * cell.majorant < density {
                let weight = acc * tr * m.sigma_s_at(at) / (tr_hero * s_hero);
                return Interaction::Scatter { t, weight, ratio };
            }
            acc = normalised(ratio);
            if acc.is_black() {
                return dead(t);
            }
        }
    }
    Interaction::Pass {
        weight: acc,
        ratio: acc,
    }
}

/// Ratio tracking: an unbiased estimate of the transmittance along `origin + t·dir` (unit
/// `dir`) over `[0, end]`.
pub(super) fn transmittance(
    m: &Medium,
    grid: &DensityGrid,
    (origin, dir): (Vec3, Vec3),
    end: f32,
    rng: &mut Rng,
) -> Rgb {
    let st = m.sigma_t();
    let s_max = st.max_channel();
    if s_max <= 0.0 {
        return Rgb::WHITE;
    }
    let shares = st / s_max;
    let mut tr = Rgb::WHITE;
    for cell in grid.walk(origin, dir, 0.0, end) {
        if cell.majorant <= 0.0 {
            continue;
        }
        let rate = cell.majorant * s_max;
        let mut t = cell.t0;
        loop {
            t += -(1.0 - rng.f32()).ln() / rate;
            if t >= cell.t1 {
                break;
            }
            let fill = grid.density(origin + dir * t) / cell.majorant;
            tr *= (Rgb::WHITE - shares * fill).map(|x| x.max(0.0));
            let most = tr.max_channel();
            if most < ROULETTE_BELOW {
                let keep = most / ROULETTE_BELOW;
                if rng.f32() >= keep {
                    return Rgb::BLACK;
                }
                tr = tr / keep;
            }
        }
    }
    tr
}

/// `acc` scaled to mean 1 (black when it has no finite mean).
fn normalised(acc: Rgb) -> Rgb {
    let mean = acc.mean();
    if mean > 0.0 && mean.is_finite() {
        acc / mean
    } else {
        Rgb::BLACK
    }
}

/// A path that carries nothing on: it scatters at `t` with no weight.
fn dead(t: f32) -> Interaction {
    Interaction::Scatter {
        t,
        weight: Rgb::BLACK,
        ratio: Rgb::WHITE,
    }
}
