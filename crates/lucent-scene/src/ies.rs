//! IES photometric files (ANSI/IESNA LM-63: the 1986, 1991, 1995 and 2002 editions): a
//! luminaire's measured intensity in candela over a grid of angles, read into a
//! [`lucent::light::Profile`].
//!
//! The layout: an optional first line naming the edition (`IESNA:LM-63-2002`, `IESNA91`,
//! `IES:LM-63-2019`, …;
//! none in 1986), keyword lines (`[TEST] …`), a `TILT=` line (`NONE`, `INCLUDE` followed by the
//! tilt table, or a file name), then numbers separated by blanks, commas or line ends: the
//! number of lamps, lumens per lamp (−1: absolute photometry), the candela multiplier, the
//! numbers of vertical and horizontal angles, the photometric type (1 = C, 2 = B, 3 = A), the
//! units (1 = feet, 2 = metres), the luminous opening's width, length and height, the ballast
//! factor, the ballast-lamp photometric factor (until 1991; reserved since), the input watts, the
//! vertical angles, the horizontal angles, and for each horizontal angle the candela values at
//! every vertical angle. Errors name the file and the line of the value at fault.

use crate::error::LoadError;
use lucent::light::{Goniometry, Profile};
use std::path::Path;

/// The most candela values a file may hold (a 1° grid over the whole sphere has 65,341).
pub const MAX_VALUES: usize = 1 << 20;

/// How a lamp's output changes as the luminaire tilts (`TILT=INCLUDE`).
#[derive(Clone, Debug, PartialEq)]
pub struct Tilt {
    /// Lamp-to-luminaire geometry: 1 (vertical base-up or base-down), 2 (horizontal, tilting
    /// along the lamp), 3 (horizontal, tilting across it).
    pub geometry: u32,
    /// Tilt angles in degrees, increasing.
    pub angles: Vec<f32>,
    /// The factor at each angle.
    pub factors: Vec<f32>,
}

impl Tilt {
    /// The factor at `angle` degrees, interpolated; the end values beyond the table.
    pub fn factor(&self, angle: f32) -> f32 {
        let a = &self.angles;
        let i = a.partition_point(|&x| x <= angle);
        if i == 0 {
            return self.factors[0];
        }
        if i == a.len() {
            return self.factors[a.len() - 1];
        }
        let t = (angle - a[i - 1]) / (a[i] - a[i - 1]);
        self.factors[i - 1] + t * (self.factors[i] - self.factors[i - 1])
    }
}

/// An IES file as read.
#[derive(Clone, Debug)]
pub struct Ies {
    /// The edition its first line names (`"LM-63-1986"` when it names none).
    pub edition: String,
    /// The intensity table in candela: the values times the candela multiplier and the
    /// ballast and ballast-lamp factors.
    pub profile: Profile,
    /// The tilt table, if the file has one.
    pub tilt: Option<Tilt>,
    /// Lumens per lamp; −1 for absolute photometry.
    pub lumens_per_lamp: f32,
    /// The `[TEST]`, `[MANUFAC]`, `[LUMCAT]`, … keywords and their values.
    pub keywords: Vec<(String, String)>,
}

/// The numbers of a file after its `TILT=` line, each with its line number.
struct Numbers<'a> {
    path: &'a Path,
    tokens: Vec<(usize, &'a str)>,
    next: usize,
    last_line: usize,
}

impl<'a> Numbers<'a> {
    fn new(path: &'a Path, lines: &[(usize, &'a str)]) -> Self {
        let tokens: Vec<_> = lines
            .iter()
            .flat_map(|&(n, line)| {
                line.split(|c: char| c.is_whitespace() || c == ',')
                    .filter(|t| !t.is_empty())
                    .map(move |t| (n, t))
            })
            .collect();
        let last_line = lines.last().map_or(1, |l| l.0);
        Self {
            path,
            tokens,
            next: 0,
            last_line,
        }
    }

    /// The next number, described as `what` in errors.
    fn number(&mut self, what: &str) -> Result<f32, LoadError> {
        let Some(&(line, token)) = self.tokens.get(self.next) else {
            return Err(LoadError::line(
                self.path,
                self.last_line,
                format!("the file ends before its {what}"),
            ));
        };
        self.next += 1;
        match token.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(LoadError::line(
                self.path,
                line,
                format!("{what}: expected a finite number, found `{token}`"),
            )),
        }
    }

    /// The next number as a count in `1..=max`.
    fn count(&mut self, what: &str, max: usize) -> Result<usize, LoadError> {
        let line = self.line();
        let v = self.number(what)?;
        if v.fract() != 0.0 || v < 1.0 || v > max as f32 {
            return Err(LoadError::line(
                self.path,
                line,
                format!("{what}: expected a whole number from 1 to {max}, found {v}"),
            ));
        }
        Ok(v as usize)
    }

    /// `n` numbers.
    fn list(&mut self, n: usize, what: &str) -> Result<Vec<f32>, LoadError> {
        (0..n)
            .map(|i| self.number(&format!("{what} #{}", i + 1)))
            .collect()
    }

    /// The line of the next number (or the last line).
    fn line(&self) -> usize {
        self.tokens.get(self.next).map_or(self.last_line, |t| t.0)
    }
}

/// The IES file at `path`.
pub fn read_ies(path: &Path) -> Result<Ies, LoadError> {
    let bytes = crate::input::read(path).map_err(|e| LoadError::file(path, e.to_string()))?;
    parse_ies(path, &String::from_utf8_lossy(&bytes))
}

/// The IES file `text`, read from `path` (for errors).
pub fn parse_ies(path: &Path, text: &str) -> Result<Ies, LoadError> {
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .collect();
    let mut at = 0;
    let edition = match lines.first() {
        Some((_, l)) if l.to_ascii_uppercase().starts_with("IES") => {
            at = 1;
            l.trim_start_matches(|c: char| c.is_ascii_alphabetic())
                .trim_start_matches(':')
                .trim()
                .to_string()
        }
        _ => "LM-63-1986".to_string(),
    };
    let mut keywords = Vec::new();
    let tilt_line = loop {
        let Some(&(n, line)) = lines.get(at) else {
            return Err(LoadError::line(
                path,
                lines.len().max(1),
                "no `TILT=` line: not an IES photometric file",
            ));
        };
        at += 1;
        if line.to_ascii_uppercase().starts_with("TILT") {
            break (n, line);
        }
        if let Some(rest) = line.strip_prefix('[')
            && let Some((key, value)) = rest.split_once(']')
        {
            keywords.push((key.to_string(), value.trim().to_string()));
        }
    };
    let (tilt_n, tilt_text) = tilt_line;
    let Some((_, tilt_value)) = tilt_text.split_once('=') else {
        return Err(LoadError::line(
            path,
            tilt_n,
            "expected `TILT=NONE`, `TILT=INCLUDE` or `TILT=<file>`",
        ));
    };
    let mut numbers = Numbers::new(path, &lines[at..]);
    let tilt = match tilt_value.trim().to_ascii_uppercase().as_str() {
        "NONE" => None,
        "INCLUDE" => Some(read_tilt(&mut numbers)?),
        _ => {
            return Err(LoadError::line(
                path,
                tilt_n,
                format!(
                    "tilt data in another file (`{}`) is not read: include it in this one with `TILT=INCLUDE`",
                    tilt_value.trim()
                ),
            ));
        }
    };
    let _lamps = numbers.number("number of lamps")?;
    let lumens_per_lamp = numbers.number("lumens per lamp")?;
    let multiplier = numbers.number("candela multiplier")?;
    let nv_line = numbers.line();
    let nv = numbers.count(
        "number of vertical angles",
        lucent::light::photometric::MAX_ANGLES,
    )?;
    let nh = numbers.count(
        "number of horizontal angles",
        lucent::light::photometric::MAX_ANGLES,
    )?;
    if nv * nh > MAX_VALUES {
        return Err(LoadError::line(
            path,
            nv_line,
            format!("{nv} × {nh} candela values; at most {MAX_VALUES} are read"),
        ));
    }
    let type_line = numbers.line();
    let goniometry = match numbers.number("photometric type")? {
        1.0 => Goniometry::C,
        2.0 => Goniometry::B,
        3.0 => Goniometry::A,
        t => {
            return Err(LoadError::line(
                path,
                type_line,
                format!("photometric type {t}: expected 1 (type C), 2 (type B) or 3 (type A)"),
            ));
        }
    };
    let _units = numbers.number("units type")?;
    let _width = numbers.number("width")?;
    let _length = numbers.number("length")?;
    let _height = numbers.number("height")?;
    let ballast = numbers.number("ballast factor")?;
    let ballast_lamp = numbers.number("ballast-lamp photometric factor")?;
    let _watts = numbers.number("input watts")?;
    let vertical = numbers.list(nv, "vertical angle")?;
    let horizontal = numbers.list(nh, "horizontal angle")?;
    let values_line = numbers.line();
    // The ballast-lamp factor of 1986 and 1991 became a reserved field in 1995 (and a code of
    // how the file was made in 2019): only the old editions multiply by it.
    let old = edition == "LM-63-1986" || edition == "91";
    let scale = multiplier * ballast * if old { ballast_lamp } else { 1.0 };
    let values: Vec<f32> = numbers
        .list(nv * nh, "candela value")?
        .into_iter()
        .map(|v| v * scale)
        .collect();
    let profile = Profile::new(goniometry, vertical, horizontal, values)
        .map_err(|e| LoadError::line(path, values_line, e.to_string()))?;
    Ok(Ies {
        edition,
        profile,
        tilt,
        lumens_per_lamp,
        keywords,
    })
}

/// The block after `TILT=INCLUDE`.
fn read_tilt(numbers: &mut Numbers) -> Result<Tilt, LoadError> {
    let line = numbers.line();
    let geometry = numbers.number("lamp-to-luminaire geometry")?;
    if ![1.0, 2.0, 3.0].contains(&geometry) {
        return Err(LoadError::line(
            numbers.path,
            line,
            format!("lamp-to-luminaire geometry {geometry}: expected 1, 2 or 3"),
        ));
    }
    let n = numbers.count(
        "number of tilt angles",
        lucent::light::photometric::MAX_ANGLES,
    )?;
    let angles_line = numbers.line();
    let angles = numbers.list(n, "tilt angle")?;
    let factors = numbers.list(n, "tilt factor")?;
    if angles.windows(2).any(|w| w[1] <= w[0]) {
        return Err(LoadError::line(
            numbers.path,
            angles_line,
            "the tilt angles must increase",
        ));
    }
    if factors.iter().any(|f| *f < 0.0) {
        return Err(LoadError::line(
            numbers.path,
            angles_line,
            "the tilt factors must not be negative",
        ));
    }
    Ok(Tilt {
        geometry: geometry as u32,
        angles,
        factors,
    })
}
