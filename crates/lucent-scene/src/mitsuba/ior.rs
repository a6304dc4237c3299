//! Mitsuba's named indices of refraction, for `int_ior` and `ext_ior`.
//!
//! The table of Mitsuba 3's `include/mitsuba/render/ior.h` (values from Hecht, *Optics*, 4th
//! edition: measured between 0 and 20 °C at about 589 nm). Names are matched without regard
//! to case, as Mitsuba does.

use super::props::{NumberOrName, Plugin};
use crate::error::LoadError;

/// `(name, index of refraction)`.
pub const IORS: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The index of refraction called `name`, if Mitsuba knows it.
pub fn named(name: &str) -> Option<f64> {
    let lower = name.trim().to_lowercase();
    IORS.iter().find(|(n, _)| *n == lower).map(|&(_, v)| v)
}

/// The index of refraction `name` of plugin `p`: a number or a name from [`IORS`]; `default`
/// (a name) when absent. It must be positive.
pub fn read(p: &Plugin, name: &str, default: &str) -> Result<f64, LoadError> {
    let (value, loc) = match p.number_or_name(name)? {
        None => return Ok(named(default).expect("the defaults are in the table")),
        Some(NumberOrName::Number(v, loc)) => (v, loc),
        Some(NumberOrName::Name(n, loc)) => {
            let v = named(n).ok_or_else(|| {
                let known: Vec<&str> = IORS.iter().map(|(n, _)| *n).collect();
                loc.error(format!(
                    "unknown index of refraction `{n}` (Mitsuba names: {})",
                    known.join(", ")
                ))
            })?;
            (v, loc)
        }
    };
    if value <= 0.0 {
        return Err(loc.error(format!("`{name}` must be positive, got {value}")));
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_match_without_case() {
        assert_eq!(named("BK7"), Some(1.5046));
        assert_eq!(named("water"), Some(1.333));
        assert_eq!(named("Acrylic Glass"), Some(1.49));
        assert_eq!(named("air"), Some(1.000277));
        assert_eq!(named("vacuum"), Some(1.0));
        assert_eq!(named("diamond"), Some(2.419));
        assert_eq!(named("polypropylene"), Some(1.49));
        assert_eq!(named("unobtainium"), None);
    }
}
