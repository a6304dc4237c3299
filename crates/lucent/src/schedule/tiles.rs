//! Square tiles over the image, in reading order.

/// A rectangle of pixels `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Tile {
    /// How many pixels it covers.
    pub fn pixel_count(&self) -> u64 {
        u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0)
    }
}

/// Tiles of `size × size` pixels (smaller at the right and bottom edges) covering a
/// `width × height` image exactly once, row by row from the top left.
pub fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let size = size.max(1);
    let mut out = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            out.push(Tile {
                x0,
                y0,
                x1: (x0 + size).min(width),
                y1: (y0 + size).min(height),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_every_pixel_once() {
        let (w, h) = (37, 19);
        let mut count = vec![0u8; (w * h) as usize];
        for t in tiles(w, h, 8) {
            for y in t.y0..t.y1 {
                for x in t.x0..t.x1 {
                    count[(y * w + x) as usize] += 1;
                }
            }
        }
        assert!(count.iter().all(|&c| c == 1));
        assert_eq!(tiles(w, h, 8).len(), 5 * 3);
    }
}
