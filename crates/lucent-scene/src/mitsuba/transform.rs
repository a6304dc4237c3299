//! `<transform>`: `translate`, `rotate`, `scale`, `matrix` and `lookat` composed in document
//! order, each applied after the ones before it (`M = op · M`), as Mitsuba 3 does; and what
//! lucent needs to know about the result.
//!
//! ```xml
//! <transform name="to_world">
//!     <scale value="0.5"/>                  <!-- first -->
//!     <rotate y="1" angle="90"/>            <!-- then -->
//!     <translate x="1" y="2" z="3"/>        <!-- last: M = T · R · S -->
//! </transform>
//! ```
//!
//! Matrices act on column vectors, `p' = M·p`; angles are in degrees, counter-clockwise about
//! the axis seen from its tip (right-handed). The arithmetic is in double precision and rounded
//! to single once, at the end.

use super::numbers::{number, numbers};
use super::xml::{Element, Loc};
use crate::desc::Matrix;
use crate::error::LoadError;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// The transform of a `<transform>` element.
pub fn parse(el: &Element) -> Result<DMat4, LoadError> {
    el.allow_attrs(&["name"])?;
    let mut m = DMat4::IDENTITY;
    for op in &el.children {
        let t = match op.tag.as_str() {
            "translate" => {
                op.allow_attrs(&["value", "x", "y", "z"])?;
                DMat4::from_translation(xyz(op, 0.0)?)
            }
            "scale" => {
                op.allow_attrs(&["value", "x", "y", "z"])?;
                DMat4::from_scale(xyz(op, 1.0)?)
            }
            "rotate" => rotation(op)?,
            "matrix" => matrix(op)?,
            "lookat" => look_at(op)?,
            other => {
                return Err(op.loc.error(format!(
                    "a <transform> holds translate, rotate, scale, matrix and lookat, not <{other}>"
                )));
            }
        };
        m = t * m;
    }
    if !m.is_finite() {
        return Err(el
            .loc
            .error("the transform overflows: its numbers are too large"));
    }
    Ok(m)
}

/// The three numbers of `x`, `y`, `z` (each `default` when missing) or of `value` (one number
/// for all three, or three), as Mitsuba's `expand_value_to_xyz`.
pub fn xyz(el: &Element, default: f64) -> Result<DVec3, LoadError> {
    let named = ["x", "y", "z"].map(|k| el.attr(k));
    let value = el.attr("value").or_else(|| el.attr("axis"));
    if let Some(v) = value {
        if named.iter().any(Option::is_some) {
            return Err(el.loc.error(format!(
                "give either `{}` or `x`, `y`, `z` in <{}>, not both",
                v.name, el.tag
            )));
        }
        return match numbers(&v.value, &v.loc)?[..] {
            [s] => Ok(DVec3::splat(s)),
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err(v.loc.error(format!(
                "`{}` takes one or three numbers, not `{}`",
                v.name, v.value
            ))),
        };
    }
    let mut out = [default; 3];
    for (slot, attr) in out.iter_mut().zip(named) {
        if let Some(a) = attr {
            *slot = number(&a.value, &a.loc)?;
        }
    }
    Ok(DVec3::from_array(out))
}

/// `<rotate x y z angle>` (or `value`/`axis` for the axis): right-handed, in degrees.
fn rotation(op: &Element) -> Result<DMat4, LoadError> {
    op.allow_attrs(&["angle", "value", "axis", "x", "y", "z"])?;
    let angle = op.require("angle")?;
    let degrees = number(&angle.value, &angle.loc)?;
    let axis = xyz(op, 0.0)?;
    let unit = axis
        .try_normalize()
        .ok_or_else(|| op.loc.error("the rotation axis is zero"))?;
    Ok(DMat4::from_axis_angle(unit, degrees.to_radians()))
}

/// `<matrix value="…">`: 16 numbers row by row, or 9 for the linear part alone.
fn matrix(op: &Element) -> Result<DMat4, LoadError> {
    op.allow_attrs(&["value"])?;
    let v = op.require("value")?;
    let n = numbers(&v.value, &v.loc)?;
    match n.len() {
        16 => Ok(DMat4::from_cols_slice(&n).transpose()),
        9 => Ok(DMat4::from_mat3(DMat3::from_cols_slice(&n).transpose())),
        k => Err(v.loc.error(format!(
            "a <matrix> takes 16 numbers (or 9), row by row; found {k}"
        ))),
    }
}

/// `<lookat origin target up>`: the camera-to-world transform of Mitsuba's `look_at`, whose
/// columns are `left = up × dir`, `up' = dir × left`, `dir` and `origin` (so camera-space +x
/// points left). A missing `up` is chosen perpendicular to the view, as Mitsuba does.
fn look_at(op: &Element) -> Result<DMat4, LoadError> {
    op.allow_attrs(&["origin", "target", "up"])?;
    let three = |name: &str| -> Result<DVec3, LoadError> {
        let a = op.require(name)?;
        match numbers(&a.value, &a.loc)?[..] {
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err(a
                .loc
                .error(format!("`{name}` takes three numbers, not `{}`", a.value))),
        }
    };
    let origin = three("origin")?;
    let target = three("target")?;
    let dir = (target - origin).try_normalize().ok_or_else(|| {
        op.loc
            .error("the lookat's origin and target are the same point")
    })?;
    let up = match op.attr("up") {
        Some(_) => three("up")?,
        None => coordinate_system(dir).0,
    };
    let left = up.cross(dir).try_normalize().ok_or_else(|| {
        op.loc
            .error("the lookat's up is zero or parallel to the view direction")
    })?;
    let new_up = dir.cross(left);
    Ok(DMat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        origin.extend(1.0),
    ))
}

/// Two unit vectors completing `n` (unit) to an orthonormal basis: Duff et al. 2017, "Building
/// an Orthonormal Basis, Revisited", the construction Mitsuba's `coordinate_system` uses.
fn coordinate_system(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The linear part's columns: the images of the axes.
fn axes(m: &DMat4) -> [DVec3; 3] {
    [
        m.x_axis.truncate(),
        m.y_axis.truncate(),
        m.z_axis.truncate(),
    ]
}

/// `Some(s)` when `m`'s linear part is `s` times a rotation or reflection (`s > 0`): the axes
/// stay perpendicular and equally long, to a relative 1e-6.
pub fn uniform_scale(m: &DMat4) -> Option<f64> {
    let [a, b, c] = axes(m);
    let s = a.length();
    let tol = 1e-6 * s * s;
    let equal =
        (b.length_squared() - s * s).abs() <= tol && (c.length_squared() - s * s).abs() <= tol;
    let perpendicular = a.dot(b).abs() <= tol && b.dot(c).abs() <= tol && a.dot(c).abs() <= tol;
    (s > 0.0 && equal && perpendicular).then_some(s)
}

/// The determinant of the linear part.
pub fn handedness(m: &DMat4) -> f64 {
    DMat3::from_mat4(*m).determinant()
}

/// Whether `m` is the identity, to rounding.
pub fn is_identity(m: &DMat4) -> bool {
    m.abs_diff_eq(DMat4::IDENTITY, 1e-12)
}

/// `m` as a placement for lucent: affine (last row `0 0 0 1`), invertible, finite in single
/// precision; otherwise an error at `loc`.
pub fn placement(m: &DMat4, loc: &Loc) -> Result<Matrix, LoadError> {
    if m.row(3) != DVec4::W {
        return Err(loc.error(
            "the transform is projective (its last row is not 0 0 0 1); lucent places shapes with affine transforms",
        ));
    }
    let single = m.as_mat4();
    let det = single.determinant();
    if !single.is_finite() || !det.is_finite() {
        return Err(loc.error("the transform's numbers are beyond single precision"));
    }
    if det == 0.0 {
        return Err(loc.error("the transform is singular: it flattens the shape"));
    }
    if lucent::shape::Transform::new(glam::Affine3A::from_mat4(single)).is_none() {
        return Err(loc.error(format!(
            "the transform's scales are too small, too large or too unequal for single precision (its determinant is {det:e})"
        )));
    }
    Ok(Matrix(*m))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mitsuba::xml::parse_str;

    fn transform(ops: &str) -> Result<DMat4, LoadError> {
        let text = format!(
            "<scene version=\"3.0.0\">\n<transform name=\"to_world\">\n{ops}\n</transform>\n</scene>"
        );
        let root = parse_str("transform.xml", &text)?;
        parse(&root.children[0])
    }

    fn close(a: DMat4, b: DMat4) -> bool {
        a.abs_diff_eq(b, 1e-12)
    }

    #[test]
    fn operations_compose_in_document_order() {
        // scale 2, then 90° about +z, then move by (1, 2, 3): M = T · R · S.
        let m = transform(
            r#"<scale value="2"/><rotate z="1" angle="90"/><translate x="1" y="2" z="3"/>"#,
        )
        .unwrap();
        #[rustfmt::skip]
        let expected = DMat4::from_cols_array(&[
            0.0, 2.0, 0.0, 0.0,
            -2.0, 0.0, 0.0, 0.0,
            0.0, 0.0, 2.0, 0.0,
            1.0, 2.0, 3.0, 1.0,
        ]);
        assert!(close(m, expected), "{m}");
        // (1, 0, 0) → scaled (2, 0, 0) → rotated (0, 2, 0) → moved (1, 4, 3).
        assert!(
            m.transform_point3(DVec3::X)
                .abs_diff_eq(DVec3::new(1.0, 4.0, 3.0), 1e-12)
        );
        // The other order: translate first, then rotate: R · T.
        let m = transform(r#"<translate x="1"/><rotate z="1" angle="90"/>"#).unwrap();
        assert!(m.transform_point3(DVec3::ZERO).abs_diff_eq(DVec3::Y, 1e-12));
    }

    #[test]
    fn matrix_is_row_by_row() {
        let m = transform(r#"<matrix value="1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1"/>"#).unwrap();
        assert_eq!(m.transform_point3(DVec3::ZERO), DVec3::new(5.0, 6.0, 7.0));
        let m = transform(r#"<matrix value="0 -1 0 1 0 0 0 0 1"/>"#).unwrap();
        assert_eq!(m.transform_vector3(DVec3::X), DVec3::Y);
        let e = transform(r#"<matrix value="1 2 3"/>"#).unwrap_err();
        assert_eq!(e.position, Some((3, 16)));
        assert!(e.message.contains("found 3"));
    }

    #[test]
    fn look_at_matches_mitsuba() {
        let m = transform(r#"<lookat origin="1, 2, 3" target="1, 2, 2" up="0, 1, 0"/>"#).unwrap();
        // dir = -z, left = up × dir = y × -z = -x, up' = dir × left = y.
        #[rustfmt::skip]
        let expected = DMat4::from_cols_array(&[
            -1.0, 0.0, 0.0, 0.0,
            0.0, 1.0, 0.0, 0.0,
            0.0, 0.0, -1.0, 0.0,
            1.0, 2.0, 3.0, 1.0,
        ]);
        assert!(close(m, expected), "{m}");
        let e = transform(r#"<lookat origin="0 0 0" target="0 1 0" up="0 1 0"/>"#).unwrap_err();
        assert!(e.message.contains("parallel"));
        // Without up: some perpendicular up, still a rotation.
        let m = transform(r#"<lookat origin="0 0 0" target="0 0 -1"/>"#).unwrap();
        assert!((handedness(&m) - 1.0).abs() < 1e-12);
        assert!(m.transform_vector3(DVec3::Z).abs_diff_eq(-DVec3::Z, 1e-12));
    }

    #[test]
    fn rotation_is_right_handed_in_degrees() {
        let m = transform(r#"<rotate value="0 1 0" angle="90"/>"#).unwrap();
        assert!(m.transform_vector3(DVec3::Z).abs_diff_eq(DVec3::X, 1e-12));
        let m = transform(r#"<rotate x="1" angle="90"/>"#).unwrap();
        assert!(m.transform_vector3(DVec3::Y).abs_diff_eq(DVec3::Z, 1e-12));
        let e = transform(r#"<rotate angle="90"/>"#).unwrap_err();
        assert_eq!(
            (e.position, e.message.as_str()),
            (Some((3, 1)), "the rotation axis is zero")
        );
    }

    #[test]
    fn scale_takes_one_value_or_axes() {
        let m = transform(r#"<scale value="2"/>"#).unwrap();
        assert_eq!(m, DMat4::from_scale(DVec3::splat(2.0)));
        let m = transform(r#"<scale y="3"/>"#).unwrap();
        assert_eq!(m, DMat4::from_scale(DVec3::new(1.0, 3.0, 1.0)));
        let e = transform(r#"<scale value="nan"/>"#).unwrap_err();
        assert_eq!(e.position, Some((3, 15)));
        let e = transform(r#"<spin/>"#).unwrap_err();
        assert!(e.message.contains("not <spin>"));
    }

    #[test]
    fn similarity_and_placement_checks() {
        let m = DMat4::from_scale_rotation_translation(
            DVec3::splat(2.0),
            glam::DQuat::from_rotation_y(0.3),
            DVec3::ONE,
        );
        assert!((uniform_scale(&m).unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(
            uniform_scale(&DMat4::from_scale(DVec3::new(1.0, 2.0, 1.0))),
            None
        );
        let shear = DMat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]);
        assert_eq!(uniform_scale(&shear), None);
        assert!(handedness(&DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0))) < 0.0);
        let loc = Loc {
            file: std::rc::Rc::from(std::path::Path::new("x.xml")),
            line: 4,
            column: 2,
        };
        let flat = placement(&DMat4::from_scale(DVec3::new(1.0, 0.0, 1.0)), &loc).unwrap_err();
        assert_eq!(
            flat.to_string(),
            "x.xml:4:2: the transform is singular: it flattens the shape"
        );
        let mut projective = DMat4::IDENTITY;
        projective.x_axis.w = 1.0;
        assert!(
            placement(&projective, &loc)
                .unwrap_err()
                .message
                .contains("projective")
        );
    }
}
