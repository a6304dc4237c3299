//! `<spectrum>` → a linear sRGB colour, as Mitsuba 3.9.1's RGB variants (`scalar_rgb`,
//! `llvm_ad_rgb`) make one when they load the scene.
//!
//! ```xml
//! <bsdf type="diffuse">
//!     <spectrum name="reflectance" value="400:0.04, 500:0.058, 600:0.287, 700:0.642"/>
//! </bsdf>
//! <emitter type="constant">
//!     <spectrum name="radiance" value="400:0, 500:8, 600:15.6, 700:18.4"/>
//! </emitter>
//! <emitter type="point">
//!     <spectrum name="intensity" type="blackbody"><float name="temperature" value="2700"/></spectrum>
//! </emitter>
//! ```
//!
//! What Mitsuba does (`Properties::get_texture_impl` and `spectrum_list_to_srgb`):
//!
//! - A list of `wavelength:value` pairs (nm; at least two, wavelengths strictly increasing, or
//!   the file is refused) is a piecewise linear spectrum, zero outside its first and last
//!   wavelengths. It is summed against the CIE 1931 colour matching functions (linear between
//!   their 5 nm samples, zero outside 360–830 nm) at 1000 wavelengths spaced evenly from 360 to
//!   830 nm, both included, each weighed 470/1000 nm; the XYZ so found, scaled by
//!   1/106.7502593994140625 (which gives a flat spectrum of 1 the luminance 1), becomes linear
//!   sRGB through the Rec. 709 matrix.
//! - It depends on what the colour is ([`Role`]). A reflectance's spectrum is weighed by
//!   illuminant D65 (scaled to luminance 1), sRGB's white, so that a flat reflectance is grey;
//!   the colour is then clamped to [0, 1]. An emitted spectrum is the light itself and is not
//!   weighed (a flat one, illuminant E, is pinkish in sRGB); it is clamped at 0 only. A
//!   conductor's η and k are weighed like a reflectance and clamped at 0 only. Mitsuba warns
//!   when it clamps; so does lucent.
//! - One value `v` is the grey `v`, except for an emitted colour, where it is the flat spectrum
//!   `v`: `v` times the sRGB of XYZ (1, 1, 1).
//! - Spectrum plugins (`<spectrum type="…">`) are textures and are used as they are, whatever
//!   the role: `d65` is its `color` (default 1) times its `scale` (default 1) — sRGB's white is
//!   D65 —, `uniform` is the grey `value`, `srgb` is its `color` (in [0, 1] unless `unbounded`).
//!   `blackbody`, `regular` and `irregular` load in the RGB variants but cannot be rendered
//!   there ("not implemented for non-spectral modes"). lucent reads them anyway, as Mitsuba's
//!   spectral variants render them, with a warning: `regular` and `irregular` as the same
//!   `wavelength:value` list, `blackbody` as Planck's radiance at `temperature` kelvin, in
//!   W m⁻² sr⁻¹ nm⁻¹ (large numbers: Mitsuba's scenes are otherwise unitless), integrated
//!   against the colour matching functions over 360–830 nm (D65-weighed and clamped like a list
//!   when used as a reflectance).
//!
//! Not read: spectra from files (`filename`). lucent's XML reader would have to resolve the
//! file and record it among the scene's inputs, as it does for meshes and images, and it does
//! not yet; the same values can be given as a list.

mod cie;

use super::numbers::{number, numbers, split};
use super::props::{Ids, Plugin};
use super::xml::{Element, Loc};
use crate::error::LoadError;
use lucent::Rgb;

/// What a colour is: Mitsuba converts a spectrum to RGB differently for each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A reflectance or other albedo: D65-weighed, clamped to [0, 1].
    Reflectance,
    /// Not emitted but allowed above 1 (a conductor's η and k): D65-weighed, clamped at 0.
    Unbounded,
    /// Emitted (an emitter's `radiance`, `intensity`, `irradiance`): not weighed, clamped at 0.
    Emitted,
}

/// The wavelengths of Mitsuba's CIE tables, in nm.
const CIE_MIN: f64 = 360.0;
const CIE_MAX: f64 = 830.0;
/// Samples of each table, 5 nm apart.
const CIE_SAMPLES: usize = 95;
/// Wavelengths of Mitsuba's sum over a list.
const STEPS: usize = 1000;
/// Gives a flat spectrum of 1 the luminance 1 (Mitsuba's `MI_CIE_Y_NORMALIZATION`).
const Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;
/// Gives D65 the luminance 1 (`MI_CIE_D65_NORMALIZATION`).
const D65_NORMALIZATION: f64 = 1.0 / 98.997_417_518_762_55;
/// XYZ → linear sRGB (Rec. 709 primaries, D65 white), in the single precision Mitsuba writes
/// it in.
#[rustfmt::skip]
const XYZ_TO_SRGB: [[f32; 3]; 3] = [
    [ 3.240479, -1.53715,  -0.498535],
    [-0.969256,  1.875991,  0.041556],
    [ 0.055648, -0.204043,  1.057311],
];

/// A spectrum's linear sRGB colour, and whether the clamp changed it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Converted {
    /// The colour, clamped as Mitsuba clamps it for the role.
    pub rgb: [f64; 3],
    /// The colour before the clamp, when the clamp changed it.
    pub unclamped: Option<[f64; 3]>,
}

impl Converted {
    fn exact(rgb: [f64; 3]) -> Self {
        Self {
            rgb,
            unclamped: None,
        }
    }
}

/// Where `wavelength` falls among the tables' samples: the sample below it (at most the last
/// but one) and the weight of the one above; `None` outside 360–830 nm, where Mitsuba's tables
/// are zero.
fn table_position(wavelength: f64) -> Option<(usize, f64)> {
    if !(CIE_MIN..=CIE_MAX).contains(&wavelength) {
        return None;
    }
    let t = (wavelength - CIE_MIN) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX - CIE_MIN));
    let i = (t as usize).min(CIE_SAMPLES - 2);
    Some((i, t - i as f64))
}

/// The CIE 1931 colour matching functions x̄, ȳ, z̄ at `wavelength` nm.
fn cie_xyz(wavelength: f64) -> [f64; 3] {
    let Some((i, f)) = table_position(wavelength) else {
        return [0.0; 3];
    };
    let (a, b) = (cie::XYZ[i], cie::XYZ[i + 1]);
    std::array::from_fn(|c| (1.0 - f) * f64::from(a[c]) + f * f64::from(b[c]))
}

/// Illuminant D65 at `wavelength` nm, scaled to luminance 1.
fn d65(wavelength: f64) -> f64 {
    let Some((i, f)) = table_position(wavelength) else {
        return 0.0;
    };
    let v = (1.0 - f) * f64::from(cie::D65[i]) + f * f64::from(cie::D65[i + 1]);
    v * D65_NORMALIZATION
}

/// What the spectrum is weighed by at `wavelength` nm in the sum, for `role`.
fn weight(role: Role, wavelength: f64) -> f64 {
    match role {
        Role::Reflectance | Role::Unbounded => d65(wavelength),
        Role::Emitted => 1.0,
    }
}

fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_SRGB.map(|row| (0..3).map(|c| f64::from(row[c]) * xyz[c]).sum())
}

/// The colour of `xyz` (already scaled), clamped for `role`.
fn finish(xyz: [f64; 3], role: Role) -> Converted {
    let rgb = xyz_to_srgb(xyz);
    let high = match role {
        Role::Reflectance => 1.0,
        Role::Unbounded | Role::Emitted => f64::INFINITY,
    };
    let clamped = rgb.map(|c| c.clamp(0.0, high));
    Converted {
        rgb: clamped,
        unclamped: (clamped != rgb).then_some(rgb),
    }
}

/// The constant spectrum `value`: grey, except emitted, where it is `value` times the sRGB of
/// XYZ (1, 1, 1) (not clamped: Mitsuba does not clamp a single value).
pub fn uniform(value: f64, role: Role) -> [f64; 3] {
    match role {
        Role::Reflectance | Role::Unbounded => [value; 3],
        Role::Emitted => xyz_to_srgb([1.0; 3]).map(|c| c * value),
    }
}

/// The piecewise linear spectrum through (`wavelengths[i]` nm, `values[i]`), zero outside
/// them, summed as Mitsuba sums it (see the module docs).
///
/// `wavelengths` must hold at least two wavelengths, strictly increasing, and `values` as many
/// values.
pub fn list(wavelengths: &[f64], values: &[f64], role: Role) -> Converted {
    let n = wavelengths.len();
    debug_assert!(n >= 2 && values.len() == n);
    debug_assert!(wavelengths.windows(2).all(|w| w[0] < w[1]));
    let (first, last) = (wavelengths[0], wavelengths[n - 1]);
    let mut xyz = [0.0; 3];
    for i in 0..STEPS {
        let w = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if w < first || w > last {
            continue;
        }
        // The segment holding w: the last one whose start is at most w, but not the last point.
        let k = (wavelengths.partition_point(|&x| x <= w) - 1).min(n - 2);
        let (w0, w1) = (wavelengths[k], wavelengths[k + 1]);
        let (v0, v1) = (values[k], values[k + 1]);
        let v = v0 + (v1 - v0) * (w - w0) / (w1 - w0);
        let cmf = cie_xyz(w);
        for c in 0..3 {
            xyz[c] += cmf[c] * v * weight(role, w);
        }
    }
    // Every step stands for 470/1000 nm (Mitsuba's weight; the steps are 470/999 nm apart).
    let scale = (CIE_MAX - CIE_MIN) / STEPS as f64 * Y_NORMALIZATION;
    finish(xyz.map(|x| x * scale), role)
}

/// The spectral radiance of a black body at `kelvin`, in W m⁻² sr⁻¹ nm⁻¹, at `nm`: Planck's
/// law, 2hc² / (λ⁵ (e^(hc/λkT) − 1)), with Mitsuba's constants (CODATA 2014).
pub fn planck(nm: f64, kelvin: f64) -> f64 {
    const C: f64 = 2.997_924_58e8; // speed of light, m/s
    const H: f64 = 6.626_070_04e-34; // Planck, J s
    const K: f64 = 1.380_648_52e-23; // Boltzmann, J/K
    let lambda = nm * 1e-9; // m
    // Per metre of wavelength, then per nanometre.
    2.0 * H * C * C / (lambda.powi(5) * (H * C / (lambda * K * kelvin)).exp_m1()) * 1e-9
}

/// A black body at `kelvin` as Mitsuba's spectral variants see it: ∫ x̄ȳz̄(λ) B(λ) dλ over
/// 360–830 nm, scaled as a list is (D65-weighed as a reflectance), to sRGB, clamped for
/// `role`.
///
/// The integral, not the list's 1000-step sum: a spectral render estimates the integral. It
/// is Simpson's rule on eight intervals of each 5 nm table interval, where the tables are
/// linear and B smooth (exact to about 1e-9 of the result).
pub fn blackbody(kelvin: f64, role: Role) -> Converted {
    const INTERVALS: usize = 8;
    let h = (CIE_MAX - CIE_MIN) / (CIE_SAMPLES - 1) as f64 / INTERVALS as f64;
    let mut xyz = [0.0; 3];
    for i in 0..CIE_SAMPLES - 1 {
        let start = CIE_MIN + (i * INTERVALS) as f64 * h;
        for j in 0..=INTERVALS {
            let w = start + j as f64 * h;
            let simpson = match j {
                0 => 1.0,
                _ if j == INTERVALS => 1.0,
                _ if j % 2 == 1 => 4.0,
                _ => 2.0,
            };
            let f = planck(w, kelvin) * weight(role, w) * simpson * h / 3.0;
            let cmf = cie_xyz(w);
            for c in 0..3 {
                xyz[c] += cmf[c] * f;
            }
        }
    }
    finish(xyz.map(|x| x * Y_NORMALIZATION), role)
}

/// The colour of the `<spectrum>` element `el` (the property `name`) as Mitsuba's RGB variants
/// load it for `role` (see the module docs), and the warnings to give.
pub fn read(el: &Element, name: &str, role: Role) -> Result<(Rgb, Vec<String>), LoadError> {
    let mut warnings = Vec::new();
    let converted = if el.attr("type").is_some() {
        plugin(el, role, &mut warnings)?
    } else {
        if let Some(f) = el.attr("filename") {
            return Err(f.loc.error(
                "spectra from files are not read by lucent; give the values as `wavelength:value` pairs",
            ));
        }
        el.allow_attrs(&["name", "value"])?;
        let v = el.require("value")?;
        let tokens: Vec<&str> = split(&v.value).collect();
        match tokens[..] {
            [] => return Err(v.loc.error("the spectrum has no values")),
            [one] if !one.contains(':') => Converted::exact(uniform(number(one, &v.loc)?, role)),
            _ => {
                let (wavelengths, values) = pairs(&tokens, &v.loc)?;
                let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
                if last < CIE_MIN || first > CIE_MAX {
                    warnings.push(v.loc.warning(format!(
                        "the spectrum `{name}` lies outside 360–830 nm ({first} to {last}), where Mitsuba's colour matching functions are zero: it is black (wavelengths are in nm)"
                    )));
                }
                list(&wavelengths, &values, role)
            }
        }
    };
    if let Some([r, g, b]) = converted.unclamped {
        let [cr, cg, cb] = converted.rgb;
        warnings.push(el.loc.warning(format!(
            "the spectrum `{name}` is out of the sRGB gamut, ({r:.6}, {g:.6}, {b:.6}): clamped to ({cr:.6}, {cg:.6}, {cb:.6}), as Mitsuba clamps it"
        )));
    }
    let [r, g, b] = converted.rgb.map(|c| c as f32);
    if !(r.is_finite() && g.is_finite() && b.is_finite()) {
        return Err(el.loc.error(format!(
            "the spectrum `{name}` makes a colour beyond single precision"
        )));
    }
    Ok((Rgb::new(r, g, b), warnings))
}

/// The `wavelength:value` pairs of `tokens`: at least two, wavelengths strictly increasing, as
/// Mitsuba requires.
fn pairs(tokens: &[&str], loc: &Loc) -> Result<(Vec<f64>, Vec<f64>), LoadError> {
    let mut wavelengths = Vec::with_capacity(tokens.len());
    let mut values = Vec::with_capacity(tokens.len());
    for t in tokens {
        let Some((w, v)) = t.split_once(':') else {
            return Err(loc.error(format!(
                "a spectrum is one value or `wavelength:value` pairs; `{t}` is neither"
            )));
        };
        wavelengths.push(number(w, loc)?);
        values.push(number(v, loc)?);
    }
    increasing(&wavelengths, loc)?;
    Ok((wavelengths, values))
}

/// An error unless `wavelengths` holds two or more, strictly increasing.
fn increasing(wavelengths: &[f64], loc: &Loc) -> Result<(), LoadError> {
    if wavelengths.len() < 2 {
        return Err(loc.error(
            "a spectrum list needs at least two `wavelength:value` pairs (one value alone is a constant spectrum)",
        ));
    }
    if let Some(w) = wavelengths.windows(2).find(|w| w[1] <= w[0]) {
        return Err(loc.error(format!(
            "the spectrum's wavelengths must increase: {} comes after {}",
            w[1], w[0]
        )));
    }
    Ok(())
}

/// The spectrum plugin `el` (`<spectrum type="…">`).
fn plugin(el: &Element, role: Role, warnings: &mut Vec<String>) -> Result<Converted, LoadError> {
    let p = Plugin::new(el, &Ids::new())?;
    let needs = |what: &str| el.loc.error(format!("the {} needs {what}", p.what()));
    let spectral_only = |kind: &str, reading: &str| {
        el.loc.warning(format!(
            "Mitsuba's RGB variants load a {kind} spectrum but cannot render it; lucent reads it as the spectral variants render it, {reading}"
        ))
    };
    let converted = match p.kind {
        "blackbody" => {
            let kelvin = p
                .float("temperature")?
                .ok_or_else(|| needs("a `temperature` (in kelvin)"))?;
            if kelvin <= 0.0 {
                return Err(el.loc.error(format!(
                    "a blackbody's temperature must be positive, not {kelvin} K"
                )));
            }
            warnings.push(spectral_only(
                "blackbody",
                "as Planck's radiance in W m⁻² sr⁻¹ nm⁻¹",
            ));
            blackbody(kelvin, role)
        }
        "regular" => {
            let min = p.float("wavelength_min")?;
            let max = p.float("wavelength_max")?;
            let (Some(min), Some(max)) = (min, max) else {
                return Err(needs("`wavelength_min` and `wavelength_max`"));
            };
            let (text, loc) = p.string("values")?.ok_or_else(|| needs("`values`"))?;
            let values = numbers(text, loc)?;
            let step = (max - min) / (values.len().max(2) - 1) as f64;
            let wavelengths: Vec<f64> = (0..values.len()).map(|i| min + step * i as f64).collect();
            increasing(&wavelengths, loc)?;
            warnings.push(spectral_only("regular", "as the same list"));
            list(&wavelengths, &values, role)
        }
        "irregular" => {
            let (w_text, w_loc) = p
                .string("wavelengths")?
                .ok_or_else(|| needs("`wavelengths`"))?;
            let (v_text, v_loc) = p.string("values")?.ok_or_else(|| needs("`values`"))?;
            let wavelengths = numbers(w_text, w_loc)?;
            let values = numbers(v_text, v_loc)?;
            if wavelengths.len() != values.len() {
                return Err(v_loc.error(format!(
                    "{} values for {} wavelengths",
                    values.len(),
                    wavelengths.len()
                )));
            }
            increasing(&wavelengths, w_loc)?;
            warnings.push(spectral_only("irregular", "as the same list"));
            list(&wavelengths, &values, role)
        }
        "d65" => {
            let color = p.color_or("color", 1.0)?;
            let scale = f64::from(p.float_or("scale", 1.0)? as f32);
            Converted::exact([color.r, color.g, color.b].map(|c| f64::from(c) * scale))
        }
        "uniform" => {
            let value = p.float("value")?.ok_or_else(|| needs("a `value`"))?;
            Converted::exact([value; 3])
        }
        "srgb" => {
            let color = p.color("color")?.ok_or_else(|| needs("a `color`"))?;
            let rgb = [color.r, color.g, color.b].map(f64::from);
            if p.boolean("unbounded")? != Some(true) && rgb.iter().any(|&c| c > 1.0) {
                return Err(el.loc.error(format!(
                    "an srgb spectrum's color must be in [0, 1], not ({}, {}, {}); Mitsuba refuses it unless `unbounded` is true",
                    rgb[0], rgb[1], rgb[2]
                )));
            }
            Converted::exact(rgb)
        }
        other => {
            return Err(el.loc.error(format!(
                "unknown spectrum type `{other}` (lucent reads: blackbody, d65, uniform, srgb, regular, irregular)"
            )));
        }
    };
    p.finish(warnings, &[]);
    Ok(converted)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mitsuba::xml::parse_str;

    /// Mitsuba's Cornell box (cbox.xml): the walls' measured reflectances and the light.
    const CBOX_RED: &str = "400:0.04, 404:0.046, 408:0.048, 412:0.053, 416:0.049, 420:0.05, 424:0.053, 428:0.055, 432:0.057, 436:0.056, 440:0.059, 444:0.057, 448:0.061, 452:0.061, 456:0.06, 460:0.062, 464:0.062, 468:0.062, 472:0.061, 476:0.062, 480:0.06, 484:0.059, 488:0.057, 492:0.058, 496:0.058, 500:0.058, 504:0.056, 508:0.055, 512:0.056, 516:0.059, 520:0.057, 524:0.055, 528:0.059, 532:0.059, 536:0.058, 540:0.059, 544:0.061, 548:0.061, 552:0.063, 556:0.063, 560:0.067, 564:0.068, 568:0.072, 572:0.08, 576:0.09, 580:0.099, 584:0.124, 588:0.154, 592:0.192, 596:0.255, 600:0.287, 604:0.349, 608:0.402, 612:0.443, 616:0.487, 620:0.513, 624:0.558, 628:0.584, 632:0.62, 636:0.606, 640:0.609, 644:0.651, 648:0.612, 652:0.61, 656:0.65, 660:0.638, 664:0.627, 668:0.62, 672:0.63, 676:0.628, 680:0.642, 684:0.639, 688:0.657, 692:0.639, 696:0.635, 700:0.642";
    const CBOX_GREEN: &str = "400:0.092, 404:0.096, 408:0.098, 412:0.097, 416:0.098, 420:0.095, 424:0.095, 428:0.097, 432:0.095, 436:0.094, 440:0.097, 444:0.098, 448:0.096, 452:0.101, 456:0.103, 460:0.104, 464:0.107, 468:0.109, 472:0.112, 476:0.115, 480:0.125, 484:0.14, 488:0.16, 492:0.187, 496:0.229, 500:0.285, 504:0.343, 508:0.39, 512:0.435, 516:0.464, 520:0.472, 524:0.476, 528:0.481, 532:0.462, 536:0.447, 540:0.441, 544:0.426, 548:0.406, 552:0.373, 556:0.347, 560:0.337, 564:0.314, 568:0.285, 572:0.277, 576:0.266, 580:0.25, 584:0.23, 588:0.207, 592:0.186, 596:0.171, 600:0.16, 604:0.148, 608:0.141, 612:0.136, 616:0.13, 620:0.126, 624:0.123, 628:0.121, 632:0.122, 636:0.119, 640:0.114, 644:0.115, 648:0.117, 652:0.117, 656:0.118, 660:0.12, 664:0.122, 668:0.128, 672:0.132, 676:0.139, 680:0.144, 684:0.146, 688:0.15, 692:0.152, 696:0.157, 700:0.159";
    const CBOX_WHITE: &str = "400:0.343, 404:0.445, 408:0.551, 412:0.624, 416:0.665, 420:0.687, 424:0.708, 428:0.723, 432:0.715, 436:0.71, 440:0.745, 444:0.758, 448:0.739, 452:0.767, 456:0.777, 460:0.765, 464:0.751, 468:0.745, 472:0.748, 476:0.729, 480:0.745, 484:0.757, 488:0.753, 492:0.75, 496:0.746, 500:0.747, 504:0.735, 508:0.732, 512:0.739, 516:0.734, 520:0.725, 524:0.721, 528:0.733, 532:0.725, 536:0.732, 540:0.743, 544:0.744, 548:0.748, 552:0.728, 556:0.716, 560:0.733, 564:0.726, 568:0.713, 572:0.74, 576:0.754, 580:0.764, 584:0.752, 588:0.736, 592:0.734, 596:0.741, 600:0.74, 604:0.732, 608:0.745, 612:0.755, 616:0.751, 620:0.744, 624:0.731, 628:0.733, 632:0.744, 636:0.731, 640:0.712, 644:0.708, 648:0.729, 652:0.73, 656:0.727, 660:0.707, 664:0.703, 668:0.729, 672:0.75, 676:0.76, 680:0.751, 684:0.739, 688:0.724, 692:0.73, 696:0.74, 700:0.737";
    const CBOX_LIGHT: &str = "400:0, 500:8, 600:15.6, 700:18.4";

    // Made by bench/peers/spectra.py (Mitsuba 3.9.1): the colours of each spectrum as a
    // reflectance and as an emitted radiance (see the script for the black bodies).
    #[rustfmt::skip]
    const MITSUBA: &[(&str, &str, [f32; 3], [f32; 3])] = &[
        ("cbox red", CBOX_RED, [0.49132004, 0.049228106, 0.0509219], [0.5697172, 0.043014023, 0.0443235]),
        ("cbox green", CBOX_GREEN, [0.06828254, 0.39776018, 0.08629087], [0.10519344, 0.37810352, 0.07627125]),
        ("cbox white", CBOX_WHITE, [0.735013, 0.7356246, 0.73626435], [0.8853053, 0.69900846, 0.666026]),
        ("cbox light", CBOX_LIGHT, [1.0, 1.0, 1.0], [20.710836, 10.854634, 2.771152]),
        ("flat", "400:0.5, 700:0.5", [0.497671, 0.4998782, 0.49745455], [0.5998468, 0.47476017, 0.45172167]),
        ("one value", "0.5", [0.5, 0.5, 0.5], [0.60239697, 0.4741455, 0.45445803]),
        ("narrow peak", "540:0, 545:1, 550:0", [0.0, 0.07324154, 0.0], [0.0, 0.06956739, 0.0]),
        ("beyond 360-830", "300:0.2, 500:0.8, 900:0.4", [0.64525676, 0.7718024, 0.65034187], [0.7882268, 0.7330853, 0.58647007]),
        ("from 500", "500:0.3, 600:0.9, 700:0.6", [0.99386084, 0.5447262, 0.0], [1.1395892, 0.5254789, 0.0]),
        ("out of gamut", "400:1, 500:1", [0.0, 0.01359328, 1.0], [0.0, 0.006461716, 1.0029879]),
        ("outside", "900:1, 1000:1", [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ("blackbody 2700 K", "blackbody:2700", [1.0, 1.0, 1.0], [314.50577, 130.62906, 31.199436]),
        ("blackbody 6500 K", "blackbody:6500", [1.0, 1.0, 1.0], [43962.555, 41448.625, 43626.242]),
    ];

    /// The `<spectrum>` element of `body` inside a scene, read as `role`: the colour and the
    /// warnings, or the error as `line:column message`.
    fn load(body: &str, role: Role) -> Result<(Rgb, Vec<String>), String> {
        let text = format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
        let root = parse_str("spectrum.xml", &text).unwrap();
        read(&root.children[0], "c", role).map_err(|e| {
            let (l, c) = e.position.unwrap();
            format!("{l}:{c} {}", e.message)
        })
    }

    fn spectrum(value: &str) -> String {
        match value.strip_prefix("blackbody:") {
            Some(t) => format!(
                r#"<spectrum name="c" type="blackbody"><float name="temperature" value="{t}"/></spectrum>"#
            ),
            None => format!(r#"<spectrum name="c" value="{value}"/>"#),
        }
    }

    #[test]
    fn colours_agree_with_mitsuba() {
        // The largest difference of the lists and of the black bodies.
        let mut worst = [(0.0f64, ""); 2];
        for &(name, value, reflectance, emitted) in MITSUBA {
            let kind = usize::from(value.starts_with("blackbody"));
            for (role, want) in [(Role::Reflectance, reflectance), (Role::Emitted, emitted)] {
                let (got, _) = load(&spectrum(value), role).unwrap();
                for (g, w) in [got.r, got.g, got.b].into_iter().zip(want) {
                    // Relative above 1: the lights and black bodies are large.
                    let error = f64::from((g - w).abs()) / f64::from(w.abs()).max(1.0);
                    assert!(
                        error < 1e-4,
                        "{name} as {role:?}: {got:?}, Mitsuba {want:?}"
                    );
                    if error > worst[kind].0 {
                        worst[kind] = (error, name);
                    }
                }
            }
        }
        let [(list, l), (black, b)] = worst;
        println!("largest difference: lists {list:.2e} ({l}), black bodies {black:.2e} ({b})");
    }

    #[test]
    fn a_flat_spectrum_is_white_as_a_reflectance() {
        // D65 is sRGB's white; the sum's 470/1000 nm weights miss a thousandth.
        let c = list(&[300.0, 900.0], &[1.0, 1.0], Role::Unbounded).rgb;
        assert!(c.iter().all(|&v| (v - 0.9988).abs() < 1e-3), "{c:?}");
        // The tables: x̄ + ȳ + z̄ peaks near 445 nm and D65 is 100 at 560 nm.
        assert_eq!(cie::D65[40], 100.0);
        assert!((cie_xyz(555.0)[1] - 1.0).abs() < 1e-6);
    }

    #[test]
    fn clamps_and_darkness_are_warnings() {
        let (c, warnings) = load(&spectrum("400:1, 500:1"), Role::Reflectance).unwrap();
        assert_eq!((c.r, c.b), (0.0, 1.0));
        assert_eq!(warnings.len(), 1);
        assert!(
            warnings[0].contains("spectrum.xml:2:1: the spectrum `c` is out of the sRGB gamut"),
            "{}",
            warnings[0]
        );
        let (c, warnings) = load(&spectrum("900:1, 1000:1"), Role::Emitted).unwrap();
        assert_eq!(c, Rgb::gray(0.0));
        assert!(warnings[0].contains("lies outside 360–830 nm (900 to 1000)"));
        let (_, warnings) = load(&spectrum(CBOX_RED), Role::Reflectance).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        // Negative values are read, as Mitsuba reads them; the colour is clamped.
        let (c, _) = load(&spectrum("400:-1, 700:-1"), Role::Emitted).unwrap();
        assert_eq!(c, Rgb::gray(0.0));
    }

    #[test]
    fn lists_mitsuba_refuses_are_errors() {
        let e = |value: &str| load(&spectrum(value), Role::Reflectance).unwrap_err();
        assert_eq!(
            e("500:1, 400:1"),
            "2:27 the spectrum's wavelengths must increase: 400 comes after 500"
        );
        assert!(e("400:1, 400:2").contains("must increase: 400 comes after 400"));
        assert!(e("500:1").starts_with("2:27 a spectrum list needs at least two"));
        assert!(e("400:1, 500:1, 600").contains("`600` is neither"));
        assert!(e("400:1, 500:nan").contains("expected a finite number, found `nan`"));
        assert!(e("").contains("the spectrum has no values"));
        let e = load(
            r#"<spectrum name="c" filename="red.spd"/>"#,
            Role::Reflectance,
        )
        .unwrap_err();
        assert!(e.starts_with("2:30 spectra from files are not read"), "{e}");
    }

    #[test]
    fn plugins() {
        let ok = |body: &str, role| load(body, role).unwrap();
        let (c, _) = ok(
            r#"<spectrum name="c" type="d65"><rgb name="color" value="0.2, 0.5, 0.8"/><float name="scale" value="2"/></spectrum>"#,
            Role::Emitted,
        );
        assert_eq!(c, Rgb::new(0.4, 1.0, 1.6));
        let (c, _) = ok(r#"<spectrum name="c" type="d65"/>"#, Role::Emitted);
        assert_eq!(c, Rgb::gray(1.0));
        let (c, _) = ok(
            r#"<spectrum name="c" type="uniform"><float name="value" value="0.3"/></spectrum>"#,
            Role::Emitted,
        );
        assert_eq!(c, Rgb::gray(0.3));
        let srgb = r#"<spectrum name="c" type="srgb"><rgb name="color" value="2, 0.5, 0.8"/>"#;
        let e = load(&format!("{srgb}</spectrum>"), Role::Emitted).unwrap_err();
        assert!(e.contains("must be in [0, 1]"), "{e}");
        let unbounded = format!(r#"{srgb}<boolean name="unbounded" value="true"/></spectrum>"#);
        assert_eq!(ok(&unbounded, Role::Emitted).0, Rgb::new(2.0, 0.5, 0.8));

        // `regular` and `irregular` are their lists, with a warning.
        let (list_colour, _) = ok(&spectrum("400:0.1, 550:0.5, 700:0.9"), Role::Reflectance);
        let (c, warnings) = ok(
            r#"<spectrum name="c" type="regular"><float name="wavelength_min" value="400"/><float name="wavelength_max" value="700"/><string name="values" value="0.1, 0.5, 0.9"/></spectrum>"#,
            Role::Reflectance,
        );
        assert_eq!(c, list_colour);
        assert!(warnings[0].contains("cannot render it"), "{warnings:?}");
        let (c, _) = ok(
            r#"<spectrum name="c" type="irregular"><string name="wavelengths" value="400, 550, 700"/><string name="values" value="0.1 0.5 0.9"/></spectrum>"#,
            Role::Reflectance,
        );
        assert_eq!(c, list_colour);

        let e = load(
            r#"<spectrum name="c" type="blackbody"><float name="temperature" value="0"/></spectrum>"#,
            Role::Emitted,
        )
        .unwrap_err();
        assert!(e.contains("temperature must be positive"), "{e}");
        let e = load(r#"<spectrum name="c" type="blackbody"/>"#, Role::Emitted).unwrap_err();
        assert!(
            e.contains("the blackbody spectrum needs a `temperature`"),
            "{e}"
        );
        let e = load(r#"<spectrum name="c" type="rawconstant"/>"#, Role::Emitted).unwrap_err();
        assert!(
            e.starts_with("2:1 unknown spectrum type `rawconstant`"),
            "{e}"
        );
        let (_, warnings) = ok(
            r#"<spectrum name="c" type="blackbody"><float name="temperature" value="5000"/><float name="lambda_min" value="400"/></spectrum>"#,
            Role::Emitted,
        );
        assert!(
            warnings
                .iter()
                .any(|w| w.contains("`lambda_min` of the blackbody spectrum is not read")),
            "{warnings:?}"
        );
    }

    #[test]
    fn a_conductors_eta_and_k_are_not_clamped_at_one() {
        // Mitsuba 3.9.1 scalar_rgb reads this k as (2.98603, 2.99927, 2.98473).
        let text = "<scene version=\"3.0.0\">\n<bsdf type=\"roughconductor\">\n<spectrum name=\"k\" value=\"400:3, 700:3\"/>\n<spectrum name=\"specular_reflectance\" value=\"400:3, 700:3\"/>\n</bsdf>\n</scene>";
        let root = parse_str("conductor.xml", text).unwrap();
        let p = Plugin::new(&root.children[0], &Ids::new()).unwrap();
        let k = p.color("k").unwrap().unwrap();
        assert!(
            (k.r - 2.98603).abs() < 1e-5 && (k.g - 2.99927).abs() < 1e-5,
            "{k:?}"
        );
        let s = p.color("specular_reflectance").unwrap().unwrap();
        assert_eq!(s, Rgb::gray(1.0));
    }
}
