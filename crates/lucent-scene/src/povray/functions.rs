//! POV-Ray's built-in functions of numbers, vectors and strings.

use super::expr::{Scalar, number, vector_of};
use super::lexer::Loc;
use super::parser::Parser;
use super::value::Vect;
use crate::error::LoadError;
use glam::{DMat3, DVec3};

/// `w(args)`: the argument count is checked by the caller.
pub fn call(p: &mut Parser, w: &str, args: &[Scalar], loc: &Loc) -> Result<Scalar, LoadError> {
    let f = |i: usize| number(&args[i], loc);
    let v = |i: usize| vector_of(&args[i], loc).map(|v| v.v3());
    let s = |i: usize| match &args[i] {
        Scalar::S(s) => Ok(s.clone()),
        _ => Err(loc.error(format!("`{w}` needs a string"))),
    };
    let vec = |d: DVec3| Ok(Scalar::V(Vect::xyz(d.x, d.y, d.z)));
    let num = |x: f64| -> Result<Scalar, LoadError> {
        if x.is_finite() {
            Ok(Scalar::F(x))
        } else {
            Err(loc.error(format!("`{w}` of these arguments is not a finite number")))
        }
    };
    match w {
        "abs" => num(f(0)?.abs()),
        "acos" => num(f(0)?.acos()),
        "asin" => num(f(0)?.asin()),
        "atan" => num(f(0)?.atan()),
        "acosh" => num(f(0)?.acosh()),
        "asinh" => num(f(0)?.asinh()),
        "atanh" => num(f(0)?.atanh()),
        "ceil" => num(f(0)?.ceil()),
        "cos" => num(f(0)?.cos()),
        "cosh" => num(f(0)?.cosh()),
        "degrees" => num(f(0)?.to_degrees()),
        "radians" => num(f(0)?.to_radians()),
        "exp" => num(f(0)?.exp()),
        "floor" => num(f(0)?.floor()),
        "int" => num(f(0)?.trunc()),
        "ln" => num(f(0)?.ln()),
        "log" => num(f(0)?.log10()),
        "sin" => num(f(0)?.sin()),
        "sinh" => num(f(0)?.sinh()),
        "sqrt" => num(f(0)?.sqrt()),
        "sqr" => num(f(0)?.powi(2)),
        "tan" => num(f(0)?.tan()),
        "tanh" => num(f(0)?.tanh()),
        "atan2" => num(f(0)?.atan2(f(1)?)),
        "mod" => num(f(0)? % f(1)?),
        "div" => num((f(0)? / f(1)?).trunc()),
        "pow" => num(f(0)?.powf(f(1)?)),
        "bitwise_and" => num(((f(0)? as i64) & (f(1)? as i64)) as f64),
        "bitwise_or" => num(((f(0)? as i64) | (f(1)? as i64)) as f64),
        "bitwise_xor" => num(((f(0)? as i64) ^ (f(1)? as i64)) as f64),
        "max" | "min" => {
            let mut m = f(0)?;
            for i in 1..args.len() {
                m = if w == "max" {
                    m.max(f(i)?)
                } else {
                    m.min(f(i)?)
                };
            }
            num(m)
        }
        "select" => {
            let c = f(0)?;
            let pick = if args.len() == 3 {
                if c < 0.0 { 1 } else { 2 }
            } else if c < 0.0 {
                1
            } else if c == 0.0 {
                2
            } else {
                3
            };
            Ok(args[pick].clone())
        }
        "vlength" => num(v(0)?.length()),
        "vnormalize" => {
            let a = v(0)?;
            if a == DVec3::ZERO {
                return Err(loc.error("`vnormalize` of the zero vector"));
            }
            vec(a.normalize())
        }
        "vdot" => num(v(0)?.dot(v(1)?)),
        "vcross" => vec(v(0)?.cross(v(1)?)),
        "vrotate" => vec(rotation(v(1)?).transform_vector3(v(0)?)),
        "vaxis_rotate" => {
            let axis = v(1)?;
            if axis == DVec3::ZERO {
                return Err(loc.error("`vaxis_rotate` about the zero vector"));
            }
            let m = axis_rotation(axis.normalize(), f(2)?.to_radians());
            vec(m * v(0)?)
        }
        "vturbulence" => Err(loc.error("`vturbulence` is not read by lucent")),
        "strlen" => num(s(0)?.chars().count() as f64),
        "strupr" => Ok(Scalar::S(s(0)?.to_uppercase().into())),
        "strlwr" => Ok(Scalar::S(s(0)?.to_lowercase().into())),
        "chr" => Ok(Scalar::S(
            char::from_u32(f(0)? as u32)
                .unwrap_or('?')
                .to_string()
                .into(),
        )),
        "asc" => num(s(0)?.chars().next().map_or(0.0, |c| f64::from(c as u32))),
        "val" => num(s(0)?.trim().parse::<f64>().unwrap_or(0.0)),
        "concat" => {
            let mut out = String::new();
            for i in 0..args.len() {
                out.push_str(&s(i)?);
            }
            Ok(Scalar::S(out.into()))
        }
        "substr" => {
            let text = s(0)?;
            let (start, len) = (f(1)? as usize, f(2)? as usize);
            let out: String = text
                .chars()
                .skip(start.saturating_sub(1))
                .take(len)
                .collect();
            Ok(Scalar::S(out.into()))
        }
        "str" => Ok(Scalar::S(format_number(f(0)?, f(1)?, f(2)?).into())),
        "vstr" => {
            let n = (f(0)?.max(0.0) as usize).min(5);
            let v = vector_of(&args[1], loc)?;
            let (w, p) = (f(3)?, f(4)?);
            let parts: Vec<String> = (0..n).map(|i| format_number(v.c[i], w, p)).collect();
            Ok(Scalar::S(parts.join(&s(2)?).into()))
        }
        "seed" => {
            p.streams.push(f(0)? as i64 as u32);
            num((p.streams.len() - 1) as f64)
        }
        "rand" => {
            let i = f(0)?;
            let stream = p
                .streams
                .get_mut(i as usize)
                .filter(|_| i >= 0.0)
                .ok_or_else(|| loc.error("`rand` of a number `seed` did not give"))?;
            num(next_random(stream))
        }
        _ => Err(loc.error(format!("`{w}` is not a function lucent knows"))),
    }
}

/// The next number in `[0, 1]` of a random stream (POV-Ray's generator).
pub fn next_random(state: &mut u32) -> f64 {
    *state = state.wrapping_mul(1_812_433_253).wrapping_add(12_345);
    f64::from((*state >> 16) & 0xFFFF) / f64::from(0xFFFFu32)
}

/// `str(value, width, precision)`: POV-Ray's formatting (a negative precision: as needed).
fn format_number(v: f64, width: f64, precision: f64) -> String {
    let w = width.max(0.0) as usize;
    let mut s = if precision < 0.0 {
        format!("{v}")
    } else {
        format!("{v:.*}", precision as usize)
    };
    if width < 0.0 {
        // A negative width pads with zeros.
        let w = (-width) as usize;
        while s.len() < w {
            s.insert(if s.starts_with('-') { 1 } else { 0 }, '0');
        }
    }
    while s.len() < w {
        s.insert(0, ' ');
    }
    s
}

/// POV-Ray's `rotate <a, b, c>`: about x by a, then y by b, then z by c, in degrees. The
/// matrices are the usual ones; in POV-Ray's left-handed space they turn clockwise seen from
/// the axis's positive end.
pub fn rotation(angles: DVec3) -> glam::DAffine3 {
    let r = angles * std::f64::consts::PI / 180.0;
    let rx = DMat3::from_cols(
        DVec3::X,
        DVec3::new(0.0, r.x.cos(), r.x.sin()),
        DVec3::new(0.0, -r.x.sin(), r.x.cos()),
    );
    let ry = DMat3::from_cols(
        DVec3::new(r.y.cos(), 0.0, -r.y.sin()),
        DVec3::Y,
        DVec3::new(r.y.sin(), 0.0, r.y.cos()),
    );
    let rz = DMat3::from_cols(
        DVec3::new(r.z.cos(), r.z.sin(), 0.0),
        DVec3::new(-r.z.sin(), r.z.cos(), 0.0),
        DVec3::Z,
    );
    glam::DAffine3::from_mat3(rz * ry * rx)
}

/// A turn of `angle` radians about the unit `axis` (POV-Ray's `vaxis_rotate` and
/// `Axis_Rotate_Trans`).
pub fn axis_rotation(axis: DVec3, angle: f64) -> DMat3 {
    // The same matrix as the right-hand rule's; in POV-Ray's left-handed space it turns the
    // other way, as `rotate` does.
    DMat3::from_axis_angle(axis, angle)
}
