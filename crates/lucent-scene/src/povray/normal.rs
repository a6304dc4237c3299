//! `normal { … }` blocks: a pattern whose slope bends the surface's normal (POV-Ray's
//! `bumps`, `dents`, `ripples`, `waves`, `wrinkles`, and every pigment pattern lucent reads),
//! its depth, and its placement.

use super::lexer::{Loc, Tok};
use super::parser::Parser;
use super::texture::{Pattern, Pigment};
use super::value::{Value, Vect};
use crate::error::LoadError;
use glam::DVec3;
use std::rc::Rc;

/// POV-Ray's depth of a normal pattern written without one.
const DEFAULT_AMOUNT: f64 = 0.5;

/// A normal perturbation.
#[derive(Clone, Debug)]
pub struct Normal {
    /// Its pattern, shaping and transform, as a pigment's (the colour map unused).
    pub pattern: Pigment,
    /// Its depth: the number after the pattern's name, or `bump_size`.
    pub amount: f64,
    /// What was read and is not applied, for warnings: (what, where).
    pub unread: Vec<(String, Loc)>,
}

/// The patterns a normal may follow, besides `gradient` (which takes an axis).
const PATTERNS: [&str; 24] = [
    "bumps",
    "dents",
    "ripples",
    "waves",
    "wrinkles",
    "bozo",
    "spotted",
    "marble",
    "wood",
    "granite",
    "agate",
    "leopard",
    "onion",
    "radial",
    "spherical",
    "cylindrical",
    "planar",
    "boxed",
    "crackle",
    "quilted",
    "cells",
    "spiral1",
    "spiral2",
    "mandel",
];

impl Parser {
    /// `{ … }` of a normal (the word `normal` read).
    pub fn normal_block(&mut self) -> Result<Normal, LoadError> {
        self.expect_symbol("{")?;
        let loc = self.loc();
        let mut n = Normal {
            pattern: Pigment::solid(Vect::splat(0.0, 5), loc.clone()),
            amount: DEFAULT_AMOUNT,
            unread: Vec::new(),
        };
        if let Some(Value::Normal(q)) =
            self.take_named("a normal", |v| matches!(v, Value::Normal(_)))?
        {
            n = (*q).clone();
        }
        loop {
            let Some((w, t)) = self.block_word("a normal's contents")? else {
                return Ok(n);
            };
            let p = &mut n.pattern;
            match &*w {
                "gradient" => {
                    let axis = self.vec3()?;
                    p.pattern = Pattern::Mapped(w.clone(), axis, Rc::new(Vec::new()));
                    self.eat_symbol(",")?;
                    if self.starts_value()? {
                        n.amount = self.float()?;
                    }
                }
                w if PATTERNS.contains(&w) => {
                    p.pattern = Pattern::Mapped(w.into(), DVec3::ZERO, Rc::new(Vec::new()));
                    if matches!(w, "spiral1" | "spiral2" | "mandel") {
                        // Arms or iterations, then the depth.
                        self.float()?;
                        self.eat_symbol(",")?;
                    }
                    if self.starts_value()? {
                        n.amount = self.float()?;
                    }
                }
                "bump_size" => n.amount = self.float()?,
                "accuracy" | "control0" | "control1" => {
                    self.float()?;
                }
                "no_bump_scale" | "uv_mapping" => {}
                "slope_map" | "normal_map" | "bump_map" | "image_pattern" | "pigment_pattern"
                | "warp" => {
                    n.unread.push((format!("a normal's `{w}`"), t.loc.clone()));
                    self.skip_braces()?;
                    // A pattern's depth may follow it: `pigment_pattern { … }, 0.5`.
                    if self.eat_symbol(",")? {
                        n.amount = self.float()?;
                    }
                }
                "checker" | "hexagon" | "brick" | "average" | "function" | "facets" => {
                    // Patterns of normals, or ones lucent lacks: the surface stays smooth.
                    n.unread
                        .push((format!("the normal pattern `{w}`"), t.loc.clone()));
                    p.pattern = Pattern::Solid(Vect::splat(0.0, 5));
                    self.skip_to_close()?;
                    self.expect_symbol("}")?;
                    return Ok(n);
                }
                w if self.shaping_word(w, &mut p.shaping)? => {}
                _ => {
                    self.push_back(t.clone());
                    match self.transform_item()? {
                        Some(m) => p.transform = m * p.transform,
                        None => return Err(t.loc.error(format!("`{w}` is not part of a normal"))),
                    }
                }
            }
        }
    }

    /// Skips to the `}` that closes the block being read (nested blocks whole), leaving it
    /// to be read.
    fn skip_to_close(&mut self) -> Result<(), LoadError> {
        while let Some(t) = self.peek()?.cloned() {
            match &t.tok {
                Tok::Symbol("}") => return Ok(()),
                Tok::Symbol("{") => self.skip_braces()?,
                _ => {
                    self.next_token()?;
                }
            }
        }
        Ok(())
    }
}
