//! From linear radiance to display values.

/// The sRGB transfer function (IEC 61966-2-1) of a linear value clamped to `[0, 1]`, as 8 bits.
///
/// The same code as rounding [`linear_to_srgb`] to 8 bits, without `powf` (the sRGB curve
/// took a tenth of writing a PNG): the code of the value's bucket of 2¹⁶ floats, one above
/// it if the value reaches the next code's threshold. A bucket spans at most one threshold:
/// its width, at most `v/128`, is under the linear width of a code, `≈ 0.0089·v^0.58`, for
/// every `v ≤ 1`.
pub fn srgb8(linear: f32) -> u8 {
    let v = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    // +0.0 for −0.0, whose bits would index past the table.
    let v = v + 0.0;
    let (buckets, thresholds) = tables();
    let code = buckets[(v.to_bits() >> BUCKET_BITS) as usize];
    match thresholds.get(code as usize) {
        Some(&t) if v >= t => code + 1,
        _ => code,
    }
}

/// Floats per bucket of [`srgb8`]'s table, as a power of two.
const BUCKET_BITS: u32 = 16;

/// The curve rounded to 8 bits, as defined.
fn srgb8_by_curve(linear: f32) -> u8 {
    (linear_to_srgb(linear) * 255.0 + 0.5) as u8
}

/// The code of the least float of each bucket of 2^[`BUCKET_BITS`] floats in `[0, 1]`, and
/// `t[k − 1]`: the least value in `[0, 1]` that [`srgb8_by_curve`] encodes to `k` or more
/// (the rounded curve is monotone: a test walks it).
fn tables() -> &'static (Vec<u8>, [f32; 255]) {
    static TABLES: std::sync::OnceLock<(Vec<u8>, [f32; 255])> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let buckets = (0..=1f32.to_bits() >> BUCKET_BITS)
            .map(|b| srgb8_by_curve(f32::from_bits(b << BUCKET_BITS)))
            .collect();
        let thresholds = std::array::from_fn(|i| {
            let code = i as u8 + 1;
            // Bisection over the bit patterns of [0, 1], which order as the values do.
            let (mut lo, mut hi) = (0u32, 1f32.to_bits());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if srgb8_by_curve(f32::from_bits(mid)) >= code {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            f32::from_bits(lo)
        });
        (buckets, thresholds)
    })
}

/// The sRGB transfer function of a linear value clamped to `[0, 1]` (NaN as 0), in `[0, 1]`.
pub fn linear_to_srgb(linear: f32) -> f32 {
    let v = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`srgb8`]'s transfer function, for reading 8-bit sRGB back as linear: the
/// curve's value for each of the 256 codes, computed once (a `powf` per texel took half of
/// loading a scene with one 2048² texture).
pub fn srgb8_to_linear(v: u8) -> f32 {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|code| srgb_to_linear(code as f32 / 255.0)))
        [usize::from(v)]
}

/// The inverse of [`linear_to_srgb`]: an sRGB-encoded value in [0, 1] (clamped; NaN as 0) as
/// linear.
pub fn srgb_to_linear(encoded: f32) -> f32 {
    let e = if encoded.is_nan() {
        0.0
    } else {
        encoded.clamp(0.0, 1.0)
    };
    if e <= 0.040_45 {
        e / 12.92
    } else {
        ((e + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values() {
        assert_eq!(srgb8(0.0), 0);
        assert_eq!(srgb8(1.0), 255);
        assert_eq!(srgb8(2.0), 255);
        assert_eq!(srgb8(-1.0), 0);
        assert_eq!(srgb8(f32::NAN), 0);
        // Linear 0.2159 (the sRGB mid-grey 128/255 decoded) encodes to 128.
        assert_eq!(srgb8(0.2159), 128);
    }

    #[test]
    fn the_thresholds_encode_as_the_curve_does() {
        // Every value near a threshold, and a stride through all of [0, 1]'s floats.
        for &t in &tables().1 {
            let b = t.to_bits();
            for bits in b.saturating_sub(4)..=(b + 4).min(1f32.to_bits()) {
                let v = f32::from_bits(bits);
                assert_eq!(srgb8(v), srgb8_by_curve(v), "{v:e}");
            }
        }
        let mut last = 0;
        for bits in (0..=1f32.to_bits()).step_by(4093) {
            let v = f32::from_bits(bits);
            let code = srgb8_by_curve(v);
            assert!(code >= last, "the rounded curve falls at {v:e}");
            last = code;
            assert_eq!(srgb8(v), code, "{v:e}");
        }
    }

    #[test]
    fn round_trips() {
        for v in 0..=255u8 {
            assert_eq!(srgb8(srgb8_to_linear(v)), v);
            // The table is the curve, bit for bit.
            let curve = srgb_to_linear(f32::from(v) / 255.0);
            assert_eq!(srgb8_to_linear(v).to_bits(), curve.to_bits());
        }
    }
}
