//! Expressions: numbers, vectors, colours and strings, with POV-Ray's operators, its built-in
//! functions and constants. A number where a vector is wanted becomes one with every
//! component that number (POV-Ray's promotion).

use super::lexer::{Loc, Tok, Token};
use super::parser::Parser;
use super::value::{Array, Value, Vect};
use crate::error::LoadError;
use std::cell::RefCell;
use std::rc::Rc;

/// A number, vector or string, as an expression gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum Scalar {
    /// A number.
    F(f64),
    /// A vector or colour.
    V(Vect),
    /// A string.
    S(Rc<str>),
}

impl Parser {
    /// A number.
    pub fn float(&mut self) -> Result<f64, LoadError> {
        let loc = self.next_loc()?;
        match self.expression()? {
            Scalar::F(v) => Ok(v),
            Scalar::V(v) => Ok(v.c[0]),
            Scalar::S(_) => Err(loc.error("expected a number, found a string")),
        }
    }

    /// A vector of at least `n` components (a number is promoted).
    pub fn vector(&mut self, n: usize) -> Result<Vect, LoadError> {
        let loc = self.next_loc()?;
        match self.expression()? {
            Scalar::F(v) => Ok(Vect::splat(v, n)),
            Scalar::V(v) => Ok(Vect { n: v.n.max(n), ..v }),
            Scalar::S(_) => Err(loc.error("expected a vector, found a string")),
        }
    }

    /// A 3-vector.
    pub fn vec3(&mut self) -> Result<glam::DVec3, LoadError> {
        Ok(self.vector(3)?.v3())
    }

    /// A string.
    pub fn string(&mut self) -> Result<Rc<str>, LoadError> {
        let loc = self.next_loc()?;
        match self.expression()? {
            Scalar::S(s) => Ok(s),
            _ => Err(loc.error("expected a string")),
        }
    }

    /// Where the next token is.
    pub fn next_loc(&mut self) -> Result<Loc, LoadError> {
        let last = self.loc();
        Ok(self.peek()?.map_or(last, |t| t.loc.clone()))
    }

    /// A whole expression (`a ? b : c` and everything under it). Comparisons (`<`, `=`, …)
    /// are read inside parentheses only, as `box { <a> <b> }` needs: there `<` starts a
    /// vector.
    pub fn expression(&mut self) -> Result<Scalar, LoadError> {
        self.ternary(false)
    }

    fn ternary(&mut self, compare: bool) -> Result<Scalar, LoadError> {
        let c = self.logical(compare)?;
        if self.eat_symbol("?")? {
            let loc = self.loc();
            let a = self.ternary(compare)?;
            self.expect_symbol(":")?;
            let b = self.ternary(compare)?;
            return Ok(if truth(&c, &loc)? { a } else { b });
        }
        Ok(c)
    }

    fn logical(&mut self, compare: bool) -> Result<Scalar, LoadError> {
        let mut a = self.comparison(compare)?;
        loop {
            let op = match self.peek_plain() {
                Some(t) if t.is_symbol("&") => "&",
                Some(t) if t.is_symbol("|") => "|",
                _ => return Ok(a),
            };
            self.next_token()?;
            let loc = self.loc();
            let b = self.comparison(compare)?;
            let (x, y) = (truth(&a, &loc)?, truth(&b, &loc)?);
            a = Scalar::F(f64::from(u8::from(if op == "&" { x && y } else { x || y })));
        }
    }

    fn comparison(&mut self, compare: bool) -> Result<Scalar, LoadError> {
        let a = self.additive()?;
        if !compare {
            return Ok(a);
        }
        let op = match self.peek_plain() {
            Some(Token {
                tok: Tok::Symbol(s @ ("<" | "<=" | "=" | "!=" | ">=" | ">")),
                ..
            }) => *s,
            _ => return Ok(a),
        };
        self.next_token()?;
        let loc = self.loc();
        let b = self.additive()?;
        let result = match (&a, &b) {
            (Scalar::S(x), Scalar::S(y)) => compare_by(op, x.cmp(y)),
            _ => {
                let (x, y) = (number(&a, &loc)?, number(&b, &loc)?);
                match op {
                    "<" => x < y,
                    "<=" => x <= y,
                    "=" => x == y,
                    "!=" => x != y,
                    ">=" => x >= y,
                    _ => x > y,
                }
            }
        };
        Ok(Scalar::F(f64::from(u8::from(result))))
    }

    /// Sums and differences (the extent of `rgb`'s operand).
    pub fn additive(&mut self) -> Result<Scalar, LoadError> {
        let mut a = self.term()?;
        loop {
            let op = match self.peek_plain() {
                Some(t) if t.is_symbol("+") => '+',
                Some(t) if t.is_symbol("-") => '-',
                _ => return Ok(a),
            };
            self.next_token()?;
            let loc = self.loc();
            let b = self.term()?;
            a = arithmetic(op, &a, &b, &loc)?;
        }
    }

    fn term(&mut self) -> Result<Scalar, LoadError> {
        let mut a = self.unary()?;
        loop {
            let op = match self.peek_plain() {
                Some(t) if t.is_symbol("*") => '*',
                Some(t) if t.is_symbol("/") => '/',
                _ => return Ok(a),
            };
            self.next_token()?;
            let loc = self.loc();
            let b = self.unary()?;
            a = arithmetic(op, &a, &b, &loc)?;
        }
    }

    fn unary(&mut self) -> Result<Scalar, LoadError> {
        if self.eat_symbol("-")? {
            let loc = self.loc();
            let a = self.unary()?;
            return arithmetic('*', &Scalar::F(-1.0), &a, &loc);
        }
        if self.eat_symbol("+")? {
            return self.unary();
        }
        if self.eat_symbol("!")? {
            let loc = self.loc();
            let a = self.unary()?;
            return Ok(Scalar::F(f64::from(u8::from(!truth(&a, &loc)?))));
        }
        let a = self.primary()?;
        self.postfix(a)
    }

    /// `.x`, `.red`, …: one component.
    fn postfix(&mut self, mut a: Scalar) -> Result<Scalar, LoadError> {
        while self.peek_plain().is_some_and(|t| t.is_symbol(".")) {
            self.next_token()?;
            let t = self.expect_any("a component's name")?;
            let i = match &t.tok {
                Tok::Word(w) => match &**w {
                    "x" | "u" | "red" => 0,
                    "y" | "v" | "green" => 1,
                    "z" | "blue" => 2,
                    "t" | "filter" => 3,
                    "transmit" => 4,
                    "gray" | "grey" => {
                        let v = vector_of(&a, &t.loc)?;
                        a = Scalar::F(0.297 * v.c[0] + 0.589 * v.c[1] + 0.114 * v.c[2]);
                        continue;
                    }
                    _ => return Err(t.loc.error(format!("`.{w}` is not a component"))),
                },
                _ => {
                    return Err(t
                        .loc
                        .error(format!("expected a component, found {}", t.tok)));
                }
            };
            a = Scalar::F(vector_of(&a, &t.loc)?.c[i]);
        }
        Ok(a)
    }

    fn primary(&mut self) -> Result<Scalar, LoadError> {
        let t = self.expect_any("a value")?;
        let loc = t.loc.clone();
        match &t.tok {
            Tok::Number(v) => Ok(Scalar::F(*v)),
            Tok::Str(s) => Ok(Scalar::S(s.clone())),
            Tok::Symbol("(") => {
                let v = self.ternary(true)?;
                self.expect_symbol(")")?;
                Ok(v)
            }
            Tok::Symbol("<") => {
                let mut c = [0.0; 5];
                let mut n = 0;
                loop {
                    if n == 5 {
                        return Err(loc.error("a vector has at most 5 components"));
                    }
                    c[n] = number(&self.ternary(false)?, &self.loc())?;
                    n += 1;
                    if self.eat_symbol(">")? {
                        break;
                    }
                    // Old scenes leave the commas out: `< -1 0 0 >`.
                    self.eat_symbol(",")?;
                }
                if n < 2 {
                    return Err(loc.error("a vector needs at least 2 components"));
                }
                Ok(Scalar::V(Vect { c, n }))
            }
            Tok::Word(w) => self.word(w.clone(), &loc),
            _ => Err(loc.error(format!("expected a value, found {}", t.tok))),
        }
    }

    /// A colour: `rgb <…>` and its kin, `red 1 green 0.5`, a colour's name, or an
    /// expression; 5 components.
    pub fn color_body(&mut self) -> Result<Vect, LoadError> {
        let mut c = Vect::splat(0.0, 5);
        let mut any = false;
        while let Some(t) = self.peek()?.cloned() {
            let word = match &t.tok {
                Tok::Word(w) => w.clone(),
                _ if !any => {
                    c = self.color_value()?;
                    any = true;
                    continue;
                }
                _ => break,
            };
            let component = match &*word {
                "red" => 0,
                "green" => 1,
                "blue" => 2,
                "filter" => 3,
                "transmit" => 4,
                "rgb" | "rgbf" | "rgbt" | "rgbft" | "srgb" | "srgbf" | "srgbt" | "srgbft"
                    if !any =>
                {
                    c = self.color_value()?;
                    any = true;
                    continue;
                }
                _ if !any && !is_keyword(&word) => {
                    c = self.color_value()?;
                    any = true;
                    continue;
                }
                _ => break,
            };
            self.next_token()?;
            c.c[component] = self.float()?;
            any = true;
        }
        if !any {
            return Err(self.loc().error("expected a colour"));
        }
        Ok(c)
    }

    /// A colour-valued expression (5 components; a 3-vector has no filter or transmit).
    fn color_value(&mut self) -> Result<Vect, LoadError> {
        let loc = self.next_loc()?;
        match self.additive()? {
            Scalar::F(v) => Ok(Vect::splat(v, 5)),
            Scalar::V(v) => Ok(Vect { n: 5, ..v }),
            Scalar::S(_) => Err(loc.error("expected a colour, found a string")),
        }
    }

    /// A word in an expression: a constant, a function, `rgb`…, or an identifier.
    fn word(&mut self, w: Rc<str>, loc: &Loc) -> Result<Scalar, LoadError> {
        let v3 = |x, y, z| Ok(Scalar::V(Vect::xyz(x, y, z)));
        match &*w {
            "pi" => return Ok(Scalar::F(std::f64::consts::PI)),
            "tau" => return Ok(Scalar::F(std::f64::consts::TAU)),
            "true" | "yes" | "on" => return Ok(Scalar::F(1.0)),
            "false" | "no" | "off" => return Ok(Scalar::F(0.0)),
            "x" => return v3(1.0, 0.0, 0.0),
            "y" => return v3(0.0, 1.0, 0.0),
            "z" => return v3(0.0, 0.0, 1.0),
            "t" => {
                return Ok(Scalar::V(Vect {
                    c: [0.0, 0.0, 0.0, 1.0, 0.0],
                    n: 4,
                }));
            }
            "u" => {
                return Ok(Scalar::V(Vect {
                    c: [1.0, 0.0, 0.0, 0.0, 0.0],
                    n: 2,
                }));
            }
            "v" => {
                return Ok(Scalar::V(Vect {
                    c: [0.0, 1.0, 0.0, 0.0, 0.0],
                    n: 2,
                }));
            }
            "clock" | "initial_clock" | "final_clock" | "clock_on" | "frame_number"
            | "initial_frame" | "final_frame" => return Ok(Scalar::F(0.0)),
            "clock_delta" => return Ok(Scalar::F(1.0)),
            "image_width" => return Ok(Scalar::F(f64::from(self.image_size.0))),
            "image_height" => return Ok(Scalar::F(f64::from(self.image_size.1))),
            "version" => return Ok(Scalar::F(self.version)),
            "max_intersections" | "max_trace_level" => return Ok(Scalar::F(0.0)),
            "color" | "colour" => return Ok(Scalar::V(self.color_body()?)),
            "rgb" | "rgbf" | "rgbt" | "rgbft" | "srgb" | "srgbf" | "srgbt" | "srgbft" => {
                return self.rgb(&w, loc);
            }
            _ => {}
        }
        if let Some(f) = self.function(&w, loc)? {
            return Ok(f);
        }
        match self.lookup(&w).cloned() {
            Some(Value::Float(v)) => Ok(Scalar::F(v)),
            Some(Value::Vector(v)) => Ok(Scalar::V(v)),
            Some(Value::Str(s)) => Ok(Scalar::S(s)),
            Some(Value::Array(a)) => match self.element(&w, &a, loc)? {
                Value::Float(v) => Ok(Scalar::F(v)),
                Value::Vector(v) => Ok(Scalar::V(v)),
                Value::Str(s) => Ok(Scalar::S(s)),
                other => Err(loc.error(format!(
                    "an element of `{w}` is {}, not a number or vector",
                    other.kind()
                ))),
            },
            Some(other) => Err(loc.error(format!(
                "`{w}` is {}, where a number, vector or string is wanted",
                other.kind()
            ))),
            None if is_keyword(&w) => {
                Err(loc.error(format!("`{w}` where a number, vector or string is wanted")))
            }
            None => Err(loc.error(format!("`{w}` is not declared"))),
        }
    }

    fn rgb(&mut self, w: &str, loc: &Loc) -> Result<Scalar, LoadError> {
        let v = match self.additive()? {
            Scalar::F(v) => Vect::splat(v, 5),
            Scalar::V(v) => v,
            Scalar::S(_) => return Err(loc.error(format!("`{w}` needs a vector, not a string"))),
        };
        let mut c = [v.c[0], v.c[1], v.c[2], 0.0, 0.0];
        let srgb = w.starts_with('s');
        if srgb {
            for x in &mut c[..3] {
                *x = srgb_to_linear(*x);
            }
        }
        match w.trim_start_matches('s') {
            "rgbf" => c[3] = v.c[3],
            "rgbt" => c[4] = v.c[3],
            "rgbft" => {
                c[3] = v.c[3];
                c[4] = v.c[4];
            }
            _ => {}
        }
        Ok(Scalar::V(Vect { c, n: 5 }))
    }

    /// A built-in function's value, `None` if `w` is not one.
    fn function(&mut self, w: &str, loc: &Loc) -> Result<Option<Scalar>, LoadError> {
        let arity: usize = match w {
            "abs" | "acos" | "asin" | "atan" | "ceil" | "cos" | "cosh" | "degrees" | "exp"
            | "floor" | "int" | "ln" | "log" | "radians" | "sin" | "sinh" | "sqrt" | "tan"
            | "tanh" | "acosh" | "asinh" | "atanh" | "vlength" | "vnormalize" | "strlen"
            | "chr" | "val" | "asc" | "strupr" | "strlwr" | "seed" | "rand" | "sqr" => 1,
            "atan2" | "mod" | "pow" | "vdot" | "vcross" | "vrotate" | "div" | "bitwise_and"
            | "bitwise_or" | "bitwise_xor" => 2,
            "vaxis_rotate" | "str" | "substr" | "select" | "vturbulence" => 3,
            "vstr" => 5,
            "max" | "min" | "concat" => 0,
            "defined" => {
                self.expect_symbol("(")?;
                let name = match self.expect_any("an identifier")?.tok {
                    Tok::Word(n) => n,
                    other => {
                        return Err(loc.error(format!("expected an identifier, found {other}")));
                    }
                };
                self.expect_symbol(")")?;
                return Ok(Some(Scalar::F(f64::from(u8::from(
                    self.lookup(&name).is_some(),
                )))));
            }
            "dimension_size" | "dimensions" => return self.array_size(w, loc).map(Some),
            "file_exists" => {
                self.expect_symbol("(")?;
                self.string()?;
                self.expect_symbol(")")?;
                return Ok(Some(Scalar::F(0.0)));
            }
            _ => return Ok(None),
        };
        self.expect_symbol("(")?;
        let mut args = Vec::new();
        if !self.eat_symbol(")")? {
            loop {
                args.push(self.expression()?);
                if self.eat_symbol(")")? {
                    break;
                }
                self.expect_symbol(",")?;
            }
        }
        // `select(a, b, c)` or `select(a, b, c, d)`.
        let ok = match w {
            "max" | "min" | "concat" => !args.is_empty(),
            "select" => args.len() == 3 || args.len() == 4,
            _ => args.len() == arity,
        };
        if !ok {
            return Err(loc.error(format!(
                "`{w}` takes {arity} arguments, given {}",
                args.len()
            )));
        }
        super::functions::call(self, w, &args, loc).map(Some)
    }

    fn array_size(&mut self, w: &str, loc: &Loc) -> Result<Scalar, LoadError> {
        self.expect_symbol("(")?;
        let name = match self.expect_any("an array")?.tok {
            Tok::Word(n) => n,
            other => return Err(loc.error(format!("expected an array, found {other}"))),
        };
        let dim = if w == "dimension_size" {
            self.expect_symbol(",")?;
            self.float()? as usize
        } else {
            0
        };
        self.expect_symbol(")")?;
        let Some(Value::Array(a)) = self.lookup(&name) else {
            return Err(loc.error(format!("`{name}` is not an array")));
        };
        let a = a.borrow();
        Ok(Scalar::F(if w == "dimensions" {
            a.dims.len() as f64
        } else {
            dim.checked_sub(1)
                .and_then(|d| a.dims.get(d))
                .map_or(0.0, |&s| s as f64)
        }))
    }

    /// `array[n]…` and its optional `{ items }`.
    pub fn array(&mut self, loc: &Loc) -> Result<Value, LoadError> {
        let mut dims = Vec::new();
        while self.eat_symbol("[")? {
            let n = self.float()?;
            if !(1.0..=1e7).contains(&n) {
                return Err(loc.error(format!("an array's size must be 1 to 10⁷, not {n}")));
            }
            dims.push(n as usize);
            self.expect_symbol("]")?;
        }
        if dims.is_empty() {
            return Err(loc.error("an array needs its size: `array[n]`"));
        }
        let total: usize = dims.iter().product();
        if total > 10_000_000 {
            return Err(loc.error("an array of more than 10⁷ elements"));
        }
        let mut items = vec![None; total];
        if self.eat_symbol("{")? {
            let mut flat = Vec::new();
            self.array_items(&mut flat)?;
            if flat.len() != total {
                return Err(loc.error(format!(
                    "the array holds {total} elements but {} are given",
                    flat.len()
                )));
            }
            for (slot, v) in items.iter_mut().zip(flat) {
                *slot = Some(v);
            }
        }
        Ok(Value::Array(Rc::new(RefCell::new(Array { dims, items }))))
    }

    /// Items up to the closing `}`, nested braces flattened.
    fn array_items(&mut self, out: &mut Vec<Value>) -> Result<(), LoadError> {
        loop {
            if self.eat_symbol("}")? {
                return Ok(());
            }
            if self.eat_symbol("{")? {
                self.array_items(out)?;
            } else {
                out.push(self.declared_value()?);
            }
            self.eat_symbol(",")?;
        }
    }
}

fn compare_by(op: &str, o: std::cmp::Ordering) -> bool {
    use std::cmp::Ordering::*;
    match op {
        "<" => o == Less,
        "<=" => o != Greater,
        "=" => o == Equal,
        "!=" => o != Equal,
        ">=" => o != Less,
        _ => o == Greater,
    }
}

/// sRGB-encoded to linear.
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn truth(a: &Scalar, loc: &Loc) -> Result<bool, LoadError> {
    Ok(number(a, loc)? != 0.0)
}

/// A number from a scalar (a vector's first component, as POV-Ray takes it).
pub fn number(a: &Scalar, loc: &Loc) -> Result<f64, LoadError> {
    match a {
        Scalar::F(v) => Ok(*v),
        Scalar::V(v) => Ok(v.c[0]),
        Scalar::S(_) => Err(loc.error("a string where a number is wanted")),
    }
}

/// A vector from a scalar (a number promoted to 3 components).
pub fn vector_of(a: &Scalar, loc: &Loc) -> Result<Vect, LoadError> {
    match a {
        Scalar::F(v) => Ok(Vect::splat(*v, 3)),
        Scalar::V(v) => Ok(*v),
        Scalar::S(_) => Err(loc.error("a string where a vector is wanted")),
    }
}

fn arithmetic(op: char, a: &Scalar, b: &Scalar, loc: &Loc) -> Result<Scalar, LoadError> {
    let f = |x: f64, y: f64| match op {
        '+' => x + y,
        '-' => x - y,
        '*' => x * y,
        _ => x / y,
    };
    match (a, b) {
        (Scalar::F(x), Scalar::F(y)) => Ok(Scalar::F(f(*x, *y))),
        (Scalar::S(x), Scalar::S(y)) if op == '+' => Ok(Scalar::S(format!("{x}{y}").into())),
        (Scalar::S(_), _) | (_, Scalar::S(_)) => {
            Err(loc.error(format!("`{op}` does not apply to strings")))
        }
        _ => {
            let n = match (a, b) {
                (Scalar::V(x), Scalar::V(y)) => x.n.max(y.n),
                (Scalar::V(x), _) | (_, Scalar::V(x)) => x.n,
                _ => 3,
            };
            let (x, y) = (vector_of(a, loc)?, vector_of(b, loc)?);
            let promote = |v: Vect, s: &Scalar| match s {
                Scalar::F(k) => Vect::splat(*k, 5),
                _ => v,
            };
            let (x, y) = (promote(x, a), promote(y, b));
            let mut c = [0.0; 5];
            for (i, out) in c.iter_mut().enumerate().take(n) {
                *out = f(x.c[i], y.c[i]);
            }
            Ok(Scalar::V(Vect { c, n }))
        }
    }
}

/// Words of the scene language that end a colour (`color red 1 finish {…}`).
pub fn is_keyword(w: &str) -> bool {
    matches!(
        w,
        "finish"
            | "normal"
            | "pigment"
            | "texture"
            | "interior"
            | "translate"
            | "rotate"
            | "scale"
            | "matrix"
            | "transform"
            | "no_shadow"
            | "hollow"
            | "inverse"
            | "spotlight"
            | "parallel"
            | "area_light"
            | "fade_distance"
            | "fade_power"
            | "shadowless"
            | "point_at"
            | "radius"
            | "falloff"
            | "tightness"
            | "looks_like"
            | "media_interaction"
            | "media_attenuation"
            | "adaptive"
            | "jitter"
            | "circular"
            | "orient"
            | "area_illumination"
            | "cylinder"
            | "projected_through"
            | "photons"
            | "quick_color"
            | "quick_colour"
            | "frequency"
            | "phase"
            | "ramp_wave"
            | "triangle_wave"
            | "sine_wave"
            | "scallop_wave"
            | "cubic_wave"
            | "poly_wave"
            | "turbulence"
            | "octaves"
            | "omega"
            | "lambda"
            | "warp"
            | "color_map"
            | "colour_map"
            | "pigment_map"
    )
}
