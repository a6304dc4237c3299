//! Albedo grids: a heterogeneous medium's single-scattering albedo `σs/σt` at every point
//! (smoke that is darker where it is sooty), over a box like a density grid and interpolated
//! the same way ([`super::grid`]).

use super::grid::{GridError, check_layout, trilinear, voxel};
use crate::Rgb;
use glam::{Affine3A, Vec3};

/// A grid of albedos over a box in the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct AlbedoGrid {
    res: [usize; 3],
    /// `x` fastest, then `y`, then `z`.
    values: Vec<Rgb>,
    /// The scene's space to the box's unit cube.
    to_unit: Affine3A,
}

impl AlbedoGrid {
    /// A grid of `res` voxels holding `values` (`x` fastest, each channel in [0, 1]), spanning
    /// the box that `to_world` makes of the unit cube.
    pub fn new(res: [usize; 3], values: Vec<Rgb>, to_world: Affine3A) -> Result<Self, GridError> {
        check_layout(res, values.len(), to_world)?;
        let bad = |c: f32| !(0.0..=1.0).contains(&c);
        if let Some(i) = values
            .iter()
            .position(|v| v.to_array().into_iter().any(bad))
        {
            let [x, y, z] = voxel(res, i);
            let value = values[i]
                .to_array()
                .into_iter()
                .find(|&c| bad(c))
                .unwrap_or(f32::NAN);
            return Err(GridError::Albedo { x, y, z, value });
        }
        Ok(Self {
            res,
            values,
            to_unit: to_world.inverse(),
        })
    }

    /// The albedo at `p` (in the scene's space); outside the box, the nearest face's.
    pub fn albedo(&self, p: Vec3) -> Rgb {
        trilinear(self.res, &self.values, self.to_unit.transform_point3(p))
    }
}
