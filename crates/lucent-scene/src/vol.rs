//! Mitsuba's binary volume grid files (`.vol`): a heterogeneous medium's density.
//!
//! The layout (little-endian): the bytes `VOL`, the version byte 3, an `i32` encoding (1:
//! `f32` values; Mitsuba 3 writes no other), three `i32` resolutions `nx, ny, nz`, an `i32`
//! channel count, the bounding box as six `f32` (`min`, then `max`), then `nx·ny·nz·channels`
//! values, `x` fastest, then `y`, then `z`, channels interleaved. A density grid has one
//! channel, an albedo grid one or three. The header's sizes are checked against the file's length before anything is
//! allocated, so a file that lies about its size costs no memory.

use crate::error::LoadError;
use glam::Vec3;
use lucent::medium::grid::MAX_VOXELS;
use std::path::Path;

/// The header's length in bytes.
const HEADER: usize = 48;

/// A `.vol` file's grid, of one or three channels.
#[derive(Clone, Debug, PartialEq)]
pub struct VolGrid {
    /// Voxels along x, y, z.
    pub res: [usize; 3],
    /// Values per voxel: 1 or 3.
    pub channels: usize,
    /// The values, channels interleaved, `x` fastest.
    pub values: Vec<f32>,
    /// The box the file gives (Mitsuba 3 ignores it unless told otherwise).
    pub bounds: (Vec3, Vec3),
}

/// The grid in `bytes`, read from `path` (for errors).
pub fn parse_vol(path: &Path, bytes: &[u8]) -> Result<VolGrid, LoadError> {
    let err = |m: String| LoadError::file(path, format!("volume grid: {m}"));
    if bytes.len() < HEADER || &bytes[..3] != b"VOL" {
        return Err(err(
            "not a Mitsuba `.vol` grid (it does not start with `VOL` and a 48-byte header)".into(),
        ));
    }
    if bytes[3] != 3 {
        return Err(err(format!("version {} is not read (only 3)", bytes[3])));
    }
    let int = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let float = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let encoding = int(4);
    if encoding != 1 {
        return Err(err(format!(
            "encoding {encoding} is not read (only 1, 32-bit floats)"
        )));
    }
    let dims = [int(8), int(12), int(16)];
    let channels = match int(20) {
        1 => 1,
        3 => 3,
        n => return Err(err(format!("{n} channels: lucent reads grids of 1 or 3"))),
    };
    let res = dims.map(|d| usize::try_from(d).unwrap_or(0));
    let voxels = res
        .iter()
        .try_fold(1usize, |n, &r| n.checked_mul(r))
        .filter(|&n| n > 0 && n <= MAX_VOXELS)
        .ok_or_else(|| {
            err(format!(
                "the header's size {}×{}×{} is empty, negative or above {MAX_VOXELS} voxels",
                dims[0], dims[1], dims[2]
            ))
        })?;
    let count = voxels * channels;
    let data = &bytes[HEADER..];
    if data.len() != count * 4 {
        return Err(err(format!(
            "the header says {}×{}×{}×{channels} values ({} bytes) but {} bytes follow it",
            res[0],
            res[1],
            res[2],
            count * 4,
            data.len()
        )));
    }
    let min = Vec3::new(float(24), float(28), float(32));
    let max = Vec3::new(float(36), float(40), float(44));
    let values = data
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
        .collect();
    Ok(VolGrid {
        res,
        channels,
        values,
        bounds: (min, max),
    })
}

/// A `.vol` file's bytes for a grid (for tests).
pub fn write_vol(grid: &VolGrid) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + grid.values.len() * 4);
    out.extend_from_slice(b"VOL\x03");
    out.extend_from_slice(&1i32.to_le_bytes());
    for r in grid.res {
        out.extend_from_slice(&(r as i32).to_le_bytes());
    }
    out.extend_from_slice(&(grid.channels as i32).to_le_bytes());
    for v in grid
        .bounds
        .0
        .to_array()
        .into_iter()
        .chain(grid.bounds.1.to_array())
    {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in &grid.values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> VolGrid {
        VolGrid {
            res: [3, 2, 1],
            channels: 1,
            values: vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5],
            bounds: (Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 2.0, 0.5)),
        }
    }

    #[test]
    fn a_written_grid_reads_back() {
        let bytes = write_vol(&grid());
        assert_eq!(bytes.len(), 48 + 6 * 4);
        assert_eq!(parse_vol(Path::new("g.vol"), &bytes).unwrap(), grid());
    }

    #[test]
    fn files_that_lie_are_refused_before_allocating() {
        let p = Path::new("g.vol");
        let message = |b: &[u8]| parse_vol(p, b).unwrap_err().message;
        let good = write_vol(&grid());
        assert!(message(&good[..60]).contains("but 12 bytes follow"));
        let mut huge = good.clone();
        huge[8..12].copy_from_slice(&i32::MAX.to_le_bytes());
        huge[12..16].copy_from_slice(&i32::MAX.to_le_bytes());
        assert!(message(&huge).contains("above"), "{}", message(&huge));
        let mut negative = good.clone();
        negative[16..20].copy_from_slice(&(-4i32).to_le_bytes());
        assert!(message(&negative).contains("negative"));
        let mut rgb = good.clone();
        rgb[20..24].copy_from_slice(&2i32.to_le_bytes());
        assert!(message(&rgb).contains("2 channels"));
        rgb[20..24].copy_from_slice(&3i32.to_le_bytes());
        assert!(message(&rgb).contains("3 values (72 bytes) but 24"));
        let mut half = good.clone();
        half[4..8].copy_from_slice(&2i32.to_le_bytes());
        assert!(message(&half).contains("encoding 2"));
        assert!(message(b"PLY garbage").contains("not a Mitsuba"));
        let mut v2 = good;
        v2[3] = 2;
        assert!(message(&v2).contains("version 2"));
    }

    #[test]
    fn mutated_files_give_an_answer_never_a_panic() {
        let good = write_vol(&grid());
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..20_000 {
            let mut bytes = good.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() % bytes.len() as u64) as usize;
                bytes[i] = next() as u8;
            }
            let cut = (next() % (bytes.len() as u64 + 1)) as usize;
            if next() % 4 == 0 {
                bytes.truncate(cut);
            }
            if let Ok(g) = parse_vol(Path::new("m.vol"), &bytes) {
                assert_eq!(g.values.len(), g.channels * g.res.iter().product::<usize>());
            }
        }
    }
}
