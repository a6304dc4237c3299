//! Density grids: the heterogeneous medium's density at every point (smoke, clouds), stored
//! as a regular grid of voxels over a box and interpolated trilinearly.
//!
//! Voxel `(i, j, k)` of an `nx × ny × nz` grid holds the density at the centre of its cell,
//! `((i + ½)/nx, (j + ½)/ny, (k + ½)/nz)` in the box's unit cube; between centres the density
//! is interpolated, and within half a voxel of the box's faces it is the nearest centre's
//! (Mitsuba's `gridvolume` with its default trilinear filter and clamped edges). Outside the
//! box the density is 0.
//!
//! Tracking needs an upper bound of the density along a ray (the *majorant*): a coarse grid
//! of cells, each holding the largest value interpolation can reach inside it, so that a ray
//! through thin or empty parts of the grid takes long steps there ([`DensityGrid::walk`]).

use glam::{Affine3A, Vec3};
use thiserror::Error;

/// Voxels per majorant cell along each axis (fewer where the grid is smaller).
const VOXELS_PER_CELL: usize = 8;

/// Midpoint-rule points per majorant cell in [`DensityGrid::quadrature`].
const QUADRATURE_STEPS: usize = 2 * VOXELS_PER_CELL;

/// The most voxels a grid may hold (4 GiB of `f32`): a bound on memory that a header cannot
/// talk past.
pub const MAX_VOXELS: usize = 1 << 30;

/// Why a grid cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GridError {
    /// A resolution is 0, or the voxels are too many.
    #[error("a grid of {0:?} voxels is empty or larger than {MAX_VOXELS} voxels")]
    Size([usize; 3]),
    /// The values do not fill the resolution.
    #[error("a grid of {res:?} voxels needs {needed} values, got {got}")]
    Count {
        /// The resolution.
        res: [usize; 3],
        /// Its product.
        needed: usize,
        /// How many were given.
        got: usize,
    },
    /// An albedo is outside [0, 1] or NaN.
    #[error("voxel ({x}, {y}, {z}) holds albedo {value}: albedos lie in [0, 1]")]
    Albedo {
        /// Its position.
        x: usize,
        /// Its position.
        y: usize,
        /// Its position.
        z: usize,
        /// What it holds (the first bad channel).
        value: f32,
    },
    /// A density is negative, NaN or infinite.
    #[error("voxel ({x}, {y}, {z}) holds {value}: densities must be finite and at least 0")]
    Value {
        /// Its position.
        x: usize,
        /// Its position.
        y: usize,
        /// Its position.
        z: usize,
        /// What it holds.
        value: f32,
    },
    /// The box has no volume (a transform that flattens it, or non-finite numbers).
    #[error("the grid's box has no volume or is not finite")]
    Box,
}

/// A grid of densities over a box in the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    res: [usize; 3],
    /// `x` fastest, then `y`, then `z`.
    values: Vec<f32>,
    /// The scene's space to the box's unit cube.
    to_unit: Affine3A,
    majorants: Majorants,
}

/// The coarse grid of upper bounds.
#[derive(Clone, Debug, PartialEq)]
struct Majorants {
    res: [usize; 3],
    max: Vec<f32>,
}

impl DensityGrid {
    /// A grid of `res` voxels holding `values` (`x` fastest), spanning the box that
    /// `to_world` makes of the unit cube.
    pub fn new(res: [usize; 3], values: Vec<f32>, to_world: Affine3A) -> Result<Self, GridError> {
        check_layout(res, values.len(), to_world)?;
        if let Some(i) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            let [x, y, z] = voxel(res, i);
            return Err(GridError::Value {
                x,
                y,
                z,
                value: values[i],
            });
        }
        let majorants = Majorants::of(res, &values);
        Ok(Self {
            res,
            values,
            to_unit: to_world.inverse(),
            majorants,
        })
    }

    /// The voxels along each axis.
    pub fn resolution(&self) -> [usize; 3] {
        self.res
    }

    /// The density at `p` (in the scene's space).
    pub fn density(&self, p: Vec3) -> f32 {
        self.density_unit(self.to_unit.transform_point3(p))
    }

    /// The density at `u` in the box's unit cube.
    fn density_unit(&self, u: Vec3) -> f32 {
        if !(u.cmpge(Vec3::ZERO).all() && u.cmple(Vec3::ONE).all()) {
            return 0.0;
        }
        trilinear(self.res, &self.values, u)
    }

    /// The midpoint rule along `origin + t·dir` over `[0, end]`: `visit(point, h, density)`
    /// for each of [`QUADRATURE_STEPS`] points per majorant cell the ray crosses (two per
    /// voxel across a cell), in order, `h` the length each stands for; cells whose bound is 0
    /// are skipped. A deterministic estimate, for integrators that want no noise.
    pub fn quadrature(
        &self,
        origin: Vec3,
        dir: Vec3,
        end: f32,
        mut visit: impl FnMut(Vec3, f32, f32),
    ) {
        for cell in self.walk(origin, dir, 0.0, end) {
            if cell.majorant <= 0.0 {
                continue;
            }
            let h = (cell.t1 - cell.t0) / QUADRATURE_STEPS as f32;
            for k in 0..QUADRATURE_STEPS {
                let p = origin + dir * (cell.t0 + (k as f32 + 0.5) * h);
                visit(p, h, self.density(p));
            }
        }
    }

    /// The stretches of the ray `origin + t·dir` within `[t0, t1]` that cross the grid's
    /// majorant cells, in order, each with its bound on the density.
    pub fn walk(&self, origin: Vec3, dir: Vec3, t0: f32, t1: f32) -> MajorantWalk<'_> {
        let m = &self.majorants;
        let scale = Vec3::new(m.res[0] as f32, m.res[1] as f32, m.res[2] as f32);
        let o = self.to_unit.transform_point3(origin) * scale;
        let d = self.to_unit.transform_vector3(dir) * scale;
        let (mut enter, mut exit) = (t0, t1);
        for a in 0..3 {
            let inv = 1.0 / d[a];
            let (near, far) = ((0.0 - o[a]) * inv, (scale[a] - o[a]) * inv);
            let (near, far) = if near <= far {
                (near, far)
            } else {
                (far, near)
            };
            // NaN (a ray in a face's plane) leaves the bounds as they were.
            enter = enter.max(near);
            exit = exit.min(far);
        }
        let mut walk = MajorantWalk {
            grid: self,
            t: enter,
            exit,
            cell: [0; 3],
            next: [f32::INFINITY; 3],
            delta: [f32::INFINITY; 3],
            step: [0; 3],
        };
        // NaN bounds (a degenerate ray) count as empty.
        if enter.partial_cmp(&exit) != Some(std::cmp::Ordering::Less) {
            walk.exit = walk.t;
            return walk;
        }
        let p = o + d * enter;
        for a in 0..3 {
            let n = m.res[a] as i64;
            let c = (p[a].floor() as i64).clamp(0, n - 1);
            walk.cell[a] = c;
            if d[a] > 0.0 {
                walk.step[a] = 1;
                walk.delta[a] = 1.0 / d[a];
                walk.next[a] = enter + ((c + 1) as f32 - p[a]) / d[a];
            } else if d[a] < 0.0 {
                walk.step[a] = -1;
                walk.delta[a] = -1.0 / d[a];
                walk.next[a] = enter + (c as f32 - p[a]) / d[a];
            }
        }
        walk
    }
}

/// Checks that `count` values fill a grid of `res` voxels, and that `to_world` makes a box of
/// the unit cube.
pub(super) fn check_layout(
    res: [usize; 3],
    count: usize,
    to_world: Affine3A,
) -> Result<(), GridError> {
    let needed = res
        .iter()
        .try_fold(1usize, |n, &r| n.checked_mul(r))
        .filter(|&n| n > 0 && n <= MAX_VOXELS)
        .ok_or(GridError::Size(res))?;
    if count != needed {
        return Err(GridError::Count {
            res,
            needed,
            got: count,
        });
    }
    let det = to_world.matrix3.determinant();
    if !(det.is_finite() && det != 0.0 && to_world.translation.is_finite()) {
        return Err(GridError::Box);
    }
    Ok(())
}

/// The position of value `i` in a grid of `res` voxels (`x` fastest).
pub(super) fn voxel(res: [usize; 3], i: usize) -> [usize; 3] {
    [i % res[0], i / res[0] % res[1], i / (res[0] * res[1])]
}

/// The trilinear interpolation at `u` (in the unit cube, clamped to it) of `values` over a
/// grid of `res` voxels, each at its cell's centre; the nearest centre's value within half a
/// voxel of the faces.
pub(super) fn trilinear<T>(res: [usize; 3], values: &[T], u: Vec3) -> T
where
    T: Copy
        + std::ops::Add<Output = T>
        + std::ops::Sub<Output = T>
        + std::ops::Mul<f32, Output = T>,
{
    let mut i0 = [0usize; 3];
    let mut f = [0f32; 3];
    for a in 0..3 {
        let n = res[a];
        let x = (u[a].clamp(0.0, 1.0) * n as f32 - 0.5).clamp(0.0, (n - 1) as f32);
        i0[a] = (x as usize).min(n.saturating_sub(2));
        f[a] = x - i0[a] as f32;
    }
    let step = |a: usize| usize::from(res[a] > 1);
    let (sx, sy, sz) = (step(0), step(1) * res[0], step(2) * res[0] * res[1]);
    let base = i0[0] + res[0] * (i0[1] + res[1] * i0[2]);
    let v = |o: usize| values[base + o];
    let lerp = |a: T, b: T, t: f32| a + (b - a) * t;
    let x00 = lerp(v(0), v(sx), f[0]);
    let x10 = lerp(v(sy), v(sx + sy), f[0]);
    let x01 = lerp(v(sz), v(sx + sz), f[0]);
    let x11 = lerp(v(sy + sz), v(sx + sy + sz), f[0]);
    lerp(lerp(x00, x10, f[1]), lerp(x01, x11, f[1]), f[2])
}

impl Majorants {
    /// The bounds of a grid of `res` voxels holding `values`: a cell's bound is the largest
    /// voxel among those interpolation reads anywhere inside it.
    fn of(res: [usize; 3], values: &[f32]) -> Self {
        let cells = res.map(|n| n.div_ceil(VOXELS_PER_CELL).max(1));
        // The voxels a cell's interpolation can read, along one axis.
        let span = |a: usize, c: usize| {
            let (n, m) = (res[a] as f32, cells[a] as f32);
            let lo = (c as f32 / m * n - 0.5).floor().max(0.0) as usize;
            let hi = (((c + 1) as f32 / m * n - 0.5).ceil().max(0.0) as usize).min(res[a] - 1);
            lo.min(res[a] - 1)..=hi
        };
        let mut max = Vec::with_capacity(cells.iter().product());
        for cz in 0..cells[2] {
            for cy in 0..cells[1] {
                for cx in 0..cells[0] {
                    let mut m = 0f32;
                    for z in span(2, cz) {
                        for y in span(1, cy) {
                            let row = res[0] * (y + res[1] * z);
                            for x in span(0, cx) {
                                m = m.max(values[row + x]);
                            }
                        }
                    }
                    max.push(m);
                }
            }
        }
        Self { res: cells, max }
    }

    fn at(&self, c: [i64; 3]) -> f32 {
        let [x, y, z] = c.map(|v| v as usize);
        self.max[x + self.res[0] * (y + self.res[1] * z)]
    }
}

/// The majorant cells along a ray: a 3D DDA (Amanatides & Woo) over the coarse grid.
#[derive(Clone, Debug)]
pub struct MajorantWalk<'a> {
    grid: &'a DensityGrid,
    t: f32,
    exit: f32,
    cell: [i64; 3],
    /// Where the ray crosses into the next cell along each axis.
    next: [f32; 3],
    /// The ray parameter one cell spans along each axis.
    delta: [f32; 3],
    step: [i64; 3],
}

/// A stretch of a ray in one majorant cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// Where it starts along the ray.
    pub t0: f32,
    /// Where it ends.
    pub t1: f32,
    /// The most density there.
    pub majorant: f32,
}

impl Iterator for MajorantWalk<'_> {
    type Item = Stretch;

    fn next(&mut self) -> Option<Stretch> {
        if self.t.partial_cmp(&self.exit) != Some(std::cmp::Ordering::Less) {
            return None;
        }
        let a = (0..3)
            .min_by(|&a, &b| self.next[a].total_cmp(&self.next[b]))
            .unwrap_or(0);
        let t1 = self.next[a].min(self.exit);
        let stretch = Stretch {
            t0: self.t,
            t1,
            majorant: self.grid.majorants.at(self.cell),
        };
        self.t = t1;
        self.cell[a] += self.step[a];
        self.next[a] += self.delta[a];
        let n = self.grid.majorants.res[a] as i64;
        if !(0..n).contains(&self.cell[a]) {
            self.exit = self.t;
        }
        Some(stretch)
    }
}
