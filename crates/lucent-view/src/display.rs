//! From the presented image to the window's pixels: the library's tone mapping (clamp and
//! sRGB, as its PNG output), scaled to the window by nearest neighbour.

use lucent::Rgb;
use lucent::film::tonemap::srgb8;

/// The render resolution for a window of `width × height` pixels at `scale` window pixels per
/// rendered pixel (rounded up, so that the picture covers the window; at least 1×1).
pub fn render_size(width: u32, height: u32, scale: u32) -> (u32, u32) {
    let scale = scale.max(1);
    (width.div_ceil(scale).max(1), height.div_ceil(scale).max(1))
}

/// A pixel as softbuffer takes it: `0x00RRGGBB`.
fn pack(c: Rgb) -> u32 {
    (u32::from(srgb8(c.r)) << 16) | (u32::from(srgb8(c.g)) << 8) | u32::from(srgb8(c.b))
}

/// Fills `out` (`width × height` window pixels, row-major) from `image` (`iw × ih`, linear),
/// each window pixel taking the rendered pixel it falls in.
pub fn blit(image: &[Rgb], (iw, ih): (u32, u32), out: &mut [u32], (width, height): (u32, u32)) {
    debug_assert_eq!(image.len(), (iw * ih) as usize);
    debug_assert_eq!(out.len(), (width * height) as usize);
    // Which rendered column each window column shows, and one tone-mapped row at a time:
    // a rendered pixel is tone mapped once however many window pixels it covers.
    let columns: Vec<usize> = (0..width)
        .map(|x| (u64::from(x) * u64::from(iw) / u64::from(width)) as usize)
        .collect();
    let mut row = vec![0u32; iw as usize];
    let mut last = usize::MAX;
    for (y, line) in out.chunks_exact_mut(width as usize).enumerate() {
        let src = (y as u64 * u64::from(ih) / u64::from(height)) as usize;
        if src != last {
            let start = src * iw as usize;
            for (p, c) in row.iter_mut().zip(&image[start..start + iw as usize]) {
                *p = pack(*c);
            }
            last = src;
        }
        for (o, &x) in line.iter_mut().zip(&columns) {
            *o = row[x];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_render_covers_the_window() {
        assert_eq!(render_size(800, 600, 2), (400, 300));
        assert_eq!(render_size(801, 1, 2), (401, 1));
        assert_eq!(render_size(0, 0, 3), (1, 1));
    }

    #[test]
    fn nearest_neighbour_upscale_with_srgb() {
        let image = [
            Rgb::BLACK,
            Rgb::WHITE,
            Rgb::new(1.0, 0.0, 0.0),
            Rgb::gray(0.2159),
        ];
        let mut out = vec![0; 16];
        blit(&image, (2, 2), &mut out, (4, 4));
        assert_eq!(&out[0..4], &[0, 0, 0xffffff, 0xffffff]);
        assert_eq!(&out[4..8], &[0, 0, 0xffffff, 0xffffff]);
        assert_eq!(&out[8..12], &[0xff0000, 0xff0000, 0x808080, 0x808080]);
    }
}
