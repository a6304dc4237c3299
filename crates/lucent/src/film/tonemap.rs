//! From linear radiance to display values.

/// The sRGB transfer function (IEC 61966-2-1) of a linear value clamped to `[0, 1]`, as 8 bits.
pub fn srgb8(linear: f32) -> u8 {
    (linear_to_srgb(linear) * 255.0 + 0.5) as u8
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

/// The inverse of [`srgb8`]'s transfer function, for reading 8-bit sRGB back as linear.
pub fn srgb8_to_linear(v: u8) -> f32 {
    srgb_to_linear(f32::from(v) / 255.0)
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
    fn round_trips() {
        for v in 0..=255u8 {
            assert_eq!(srgb8(srgb8_to_linear(v)), v);
        }
    }
}
