//! Numbers in the text of Mitsuba's attributes: lists split as its tokenizer splits them, and
//! each number finite and within single precision. Properties, transforms and spectra read
//! their numbers here.

use super::xml::Loc;
use crate::error::LoadError;

/// The parts of a list: separated by commas and white space, as Mitsuba's tokenizer does.
pub fn split(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
}

/// `text` as a finite number that also fits an `f32`, or an error at `loc`.
pub fn number(text: &str, loc: &Loc) -> Result<f64, LoadError> {
    let t = text.trim();
    let v: f64 = t
        .parse()
        .map_err(|_| loc.error(format!("cannot read `{t}` as a number")))?;
    if !v.is_finite() {
        return Err(loc.error(format!("expected a finite number, found `{t}`")));
    }
    if !(v as f32).is_finite() {
        return Err(loc.error(format!(
            "`{t}` is beyond single precision (at most about 3.4e38)"
        )));
    }
    Ok(v)
}

/// The numbers of a list (see [`split`]).
pub fn numbers(text: &str, loc: &Loc) -> Result<Vec<f64>, LoadError> {
    split(text).map(|t| number(t, loc)).collect()
}
