//! POV-Ray's algebraic shapes (`quadric`, `cubic`, `quartic`, `poly`) and the boxes that cut
//! them (`bounded_by`, `clipped_by`): an algebraic surface is often infinite, and POV-Ray's
//! scenes bound it with a sphere or a box.

use super::lexer::Loc;
use super::parser::Parser;
use super::scene::{Object, Shape};
use crate::error::LoadError;
use glam::{DAffine3, DVec3};
use lucent::shape::solid::algebraic;

/// Most coefficients a `<…>` of POV-Ray's polynomials holds (degree 15, POV-Ray's most).
const MOST: usize = 816;

impl Parser {
    /// The arguments of `quadric`, `cubic`, `quartic` or `poly` (its `{` read).
    pub fn algebraic(&mut self, w: &str, loc: &Loc) -> Result<Shape, LoadError> {
        let coefficients = match w {
            "quadric" => {
                // A·x² + B·y² + C·z² + D·xy + E·xz + F·yz + G·x + H·y + I·z + J.
                let mut v = Vec::with_capacity(10);
                for i in 0..3 {
                    if i > 0 {
                        self.eat_symbol(",")?;
                    }
                    v.extend(self.vec3()?.to_array());
                }
                self.eat_symbol(",")?;
                v.push(self.float()?);
                let powers = [
                    [2, 0, 0],
                    [0, 2, 0],
                    [0, 0, 2],
                    [1, 1, 0],
                    [1, 0, 1],
                    [0, 1, 1],
                    [1, 0, 0],
                    [0, 1, 0],
                    [0, 0, 1],
                    [0, 0, 0],
                ];
                let terms: Vec<_> = v.into_iter().zip(powers).collect();
                algebraic::from_terms(&terms)
            }
            _ => {
                let degree = match w {
                    "cubic" => 3.0,
                    "quartic" => 4.0,
                    _ => {
                        let n = self.float()?;
                        self.eat_symbol(",")?;
                        n
                    }
                };
                let values = self.coefficients(loc)?;
                if !(2.0..=4.0).contains(&degree) || degree.fract() != 0.0 {
                    // Warned where it is used, as other shapes lucent does not read.
                    return Ok(Shape::Unread(format!("{w}` of degree `{degree}").into()));
                }
                let want = algebraic::term_count(degree as u8);
                if values.len() != want {
                    return Err(loc.error(format!(
                        "a `{w}` of degree {degree} has {want} coefficients, not {}",
                        values.len()
                    )));
                }
                algebraic::from_pov(degree as u8, &values)
            }
        };
        let c = coefficients.ok_or_else(|| loc.error(format!("the `{w}` cannot be read")))?;
        if algebraic::degree(&c) == 0 {
            return Err(loc.error(format!("the `{w}` has no term with x, y or z")));
        }
        Ok(Shape::Algebraic(Box::new(c)))
    }

    /// `<c₀, c₁, …>`: a polynomial's coefficients (the commas may be left out, as in
    /// vectors).
    fn coefficients(&mut self, loc: &Loc) -> Result<Vec<f64>, LoadError> {
        self.expect_symbol("<")?;
        let mut values = Vec::new();
        while !self.eat_symbol(">")? {
            values.push(self.float()?);
            if values.len() > MOST {
                return Err(loc.error(format!("more than {MOST} coefficients (degree 15's)")));
            }
            self.eat_symbol(",")?;
        }
        Ok(values)
    }

    /// `bounded_by { … }` or `clipped_by { … }` (its word read): the box about the objects it
    /// holds, in `o`'s own space, kept for an algebraic shape or a plane to be cut to.
    pub fn bounds_block(&mut self, o: &mut Object, w: &str, loc: &Loc) -> Result<(), LoadError> {
        self.expect_symbol("{")?;
        // Several objects clip (or bound) by where they all are: the meet of their boxes.
        let mut world = [DVec3::NEG_INFINITY, DVec3::INFINITY];
        let mut exact = true;
        let mut count = 0;
        while let Some(t) = self.peek()?.cloned() {
            if t.is_symbol("}") {
                break;
            }
            if t.is_word("clipped_by") || t.is_word("bounded_by") {
                // `bounded_by { clipped_by }`: the clip is the bound.
                self.next_token()?;
                continue;
            }
            let b = self.object()?;
            count += 1;
            exact &= matches!(b.shape, Shape::Box(..));
            let [lo, hi] = box_of(&b);
            world = [world[0].max(lo), world[1].min(hi)];
        }
        exact &= count == 1;
        self.expect_symbol("}")?;
        // Algebraic shapes have no box of their own, and a plane cut to one is a rectangle.
        let cut = matches!(o.shape, Shape::Algebraic(_) | Shape::Plane(..));
        if !cut {
            if w == "clipped_by" {
                self.warn(loc, "`clipped_by` is not read by lucent");
            }
            return Ok(());
        }
        if count == 0 {
            // `bounded_by { clipped_by }`: the clip already read.
            return Ok(());
        }
        if !world.iter().any(|c| c.is_finite_mask().any()) {
            self.warn(
                loc,
                format!("this `{w}` gives no box lucent can read: the shape is left unbounded"),
            );
            return Ok(());
        }
        if w == "clipped_by" && !exact {
            self.warn(
                loc,
                "`clipped_by` with other than one box is read as the box about it",
            );
        }
        let own = transformed_box(world, &o.transform.inverse());
        o.bounds = Some(match o.bounds {
            // Both a bound and a clip: where both are.
            Some([lo, hi]) => [lo.max(own[0]), hi.min(own[1])],
            None => own,
        });
        Ok(())
    }
}

/// The box about `o` in the space it is written in: infinite on the axes it does not bound
/// (a plane's half-space, an infinite quadric), all of space for a shape without an obvious
/// box.
fn box_of(o: &Object) -> [DVec3; 2] {
    let everywhere = [DVec3::NEG_INFINITY, DVec3::INFINITY];
    let own = match &o.shape {
        Shape::Sphere(c, r) => [*c - DVec3::splat(*r), *c + DVec3::splat(*r)],
        Shape::Box(a, b) => [a.min(*b), a.max(*b)],
        Shape::Cylinder(a, b, r, _) => [a.min(*b) - DVec3::splat(*r), a.max(*b) + DVec3::splat(*r)],
        Shape::Cone(a, ra, b, rb, _) => {
            let r = DVec3::splat(ra.max(*rb));
            [a.min(*b) - r, a.max(*b) + r]
        }
        Shape::Torus(major, minor) => {
            let h = DVec3::new(major + minor, *minor, major + minor);
            [-h, h]
        }
        Shape::Superellipsoid(..) => [DVec3::NEG_ONE, DVec3::ONE],
        Shape::Algebraic(c) => o.bounds.unwrap_or_else(|| quadric_box(c)),
        Shape::Plane(n, d) => {
            // An axis-aligned plane bounds its axis on one side.
            let mut b = everywhere;
            let axis = n.abs().max_position();
            if n.abs().max_element() == n.length() {
                let at = d * n.length() / n[axis];
                if n[axis] > 0.0 {
                    b[1][axis] = at;
                } else {
                    b[0][axis] = at;
                }
            }
            b
        }
        _ => everywhere,
    };
    transformed_box(own, &o.transform)
}

/// The box of a quadric `Σ aᵢ·xᵢ² + J ≤ 0` with no cross or linear terms (an ellipsoid, a
/// cylinder along an axis), along the axes whose square has a positive coefficient while
/// none is negative; infinite elsewhere.
fn quadric_box(c: &algebraic::Coefficients) -> [DVec3; 2] {
    let mut b = [DVec3::NEG_INFINITY, DVec3::INFINITY];
    let mut squares = [0.0; 3];
    let mut constant = 0.0;
    for (k, p) in c.iter().zip(algebraic::POWERS) {
        match p {
            _ if *k == 0.0 => {}
            [2, 0, 0] => squares[0] = *k,
            [0, 2, 0] => squares[1] = *k,
            [0, 0, 2] => squares[2] = *k,
            [0, 0, 0] => constant = *k,
            _ => return b,
        }
    }
    if squares.iter().any(|&a| a < 0.0) || constant >= 0.0 {
        return b;
    }
    for (axis, a) in squares.into_iter().enumerate() {
        if a > 0.0 {
            let r = (-constant / a).sqrt();
            b[0][axis] = -r;
            b[1][axis] = r;
        }
    }
    b
}

/// The box about `b` moved by `m`.
fn transformed_box([lo, hi]: [DVec3; 2], m: &DAffine3) -> [DVec3; 2] {
    let mut out = [DVec3::INFINITY, DVec3::NEG_INFINITY];
    for i in 0..8 {
        let corner = DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let [p_lo, p_hi] = moved_corner(corner, m);
        out = [out[0].min(p_lo), out[1].max(p_hi)];
    }
    out
}

/// Where `m` takes `corner`, as the least and most each coordinate can be: a coordinate fed
/// by an infinite one is infinite that way (`0·∞` counted as 0), and both ways when two
/// infinities of opposite signs meet.
fn moved_corner(corner: DVec3, m: &DAffine3) -> [DVec3; 2] {
    // Rotations by a quarter turn leave rounding in place of zeros: those count as zeros.
    let tiny = 1e-12
        * m.matrix3
            .abs()
            .to_cols_array()
            .into_iter()
            .fold(0.0, f64::max);
    let row = |r: usize| {
        let (mut sum, mut up, mut down) = (m.translation[r], false, false);
        for col in 0..3 {
            let (k, c) = (m.matrix3.col(col)[r], corner[col]);
            if c.is_finite() {
                sum += k * c;
            } else if k.abs() > tiny {
                if (k > 0.0) == (c > 0.0) {
                    up = true;
                } else {
                    down = true;
                }
            }
        }
        match (up, down) {
            (false, false) => (sum, sum),
            (true, false) => (f64::INFINITY, f64::INFINITY),
            (false, true) => (f64::NEG_INFINITY, f64::NEG_INFINITY),
            (true, true) => (f64::NEG_INFINITY, f64::INFINITY),
        }
    };
    let [x, y, z] = [row(0), row(1), row(2)];
    [DVec3::new(x.0, y.0, z.0), DVec3::new(x.1, y.1, z.1)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_half_space_box_keeps_its_finite_side_when_moved() {
        // z ≤ 1 everywhere else, turned a quarter about x (z becomes −y) and moved up by 2.
        let m = DAffine3::from_translation(DVec3::Y * 2.0)
            * DAffine3::from_rotation_x(0.5 * std::f64::consts::PI);
        let b = [
            DVec3::NEG_INFINITY,
            DVec3::new(f64::INFINITY, f64::INFINITY, 1.0),
        ];
        let [lo, hi] = transformed_box(b, &m);
        assert!(
            (lo.y - 1.0).abs() < 1e-12 && hi.y == f64::INFINITY,
            "{lo} {hi}"
        );
        assert!(lo.x == f64::NEG_INFINITY && lo.z == f64::NEG_INFINITY && hi.z == f64::INFINITY);
    }

    #[test]
    fn a_box_moved_is_the_box_about_its_corners() {
        let m = DAffine3::from_translation(DVec3::X)
            * DAffine3::from_rotation_z(0.5 * std::f64::consts::PI);
        let [lo, hi] = transformed_box([DVec3::ZERO, DVec3::new(2.0, 1.0, 1.0)], &m);
        assert!((lo - DVec3::new(0.0, 0.0, 0.0)).length() < 1e-12, "{lo}");
        assert!((hi - DVec3::new(1.0, 2.0, 1.0)).length() < 1e-12, "{hi}");
    }
}
