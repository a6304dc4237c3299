//! Where in a pixel each of its samples goes: the centre for one sample, stratified jitter for more.

use super::{hash, permute, to_unit_float};

/// The offset within pixel `pixel` of sample `sample` out of `spp`, in `[0, 1)²`.
///
/// With one sample per pixel it is the centre `(0.5, 0.5)`. With more, the pixel is cut into a
/// grid of `cols × rows ≥ spp` cells (`cols = ⌈√spp⌉`, `rows = ⌈spp / cols⌉`); the samples take
/// distinct cells, chosen by a per-pixel random permutation, each jittered uniformly within its
/// cell. For square `spp` every cell is used exactly once: classic stratified (jittered) sampling.
pub fn pixel_offset(seed: u64, pixel: u64, sample: u32, spp: u32) -> (f32, f32) {
    if spp <= 1 {
        return (0.5, 0.5);
    }
    let cols = (spp as f64).sqrt().ceil() as u32;
    let rows = spp.div_ceil(cols);
    let cells = cols * rows;
    let cell = permute(sample, cells, hash(seed, pixel, u32::MAX, 0));
    let (cx, cy) = (cell % cols, cell / cols);
    let jx = to_unit_float(hash(seed, pixel, sample, 0));
    let jy = to_unit_float(hash(seed, pixel, sample, 1));
    (
        (cx as f32 + jx) / cols as f32,
        (cy as f32 + jy) / rows as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_sample_goes_through_the_centre() {
        assert_eq!(pixel_offset(3, 17, 0, 1), (0.5, 0.5));
    }

    #[test]
    fn square_counts_put_one_sample_in_every_stratum() {
        let spp = 16;
        let mut seen = [false; 16];
        for s in 0..spp {
            let (x, y) = pixel_offset(5, 42, s, spp);
            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
            let cell = (y * 4.0) as usize * 4 + (x * 4.0) as usize;
            assert!(!seen[cell], "two samples in stratum {cell}");
            seen[cell] = true;
        }
    }

    #[test]
    fn other_counts_use_distinct_cells() {
        let spp = 5; // a 3 × 2 grid
        let mut cells: Vec<_> = (0..spp)
            .map(|s| {
                let (x, y) = pixel_offset(1, 2, s, spp);
                ((y * 2.0) as u32, (x * 3.0) as u32)
            })
            .collect();
        cells.sort();
        cells.dedup();
        assert_eq!(cells.len(), 5);
    }
}
