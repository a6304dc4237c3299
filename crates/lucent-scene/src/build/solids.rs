//! `[[object]]` tables of the exact solids: box, cylinder, cone, disc, ellipsoid and torus, each given by
//! its own keys (POV-Ray's: corners, end points and radii, major and minor radius), then an
//! optional placement, and built as a [`Solid`]: the canonical shape and one affine transform.

use super::objects::placement;
use super::{Context, RADIUS_RANGE, check, required};
use crate::desc::{Finite, ObjectDesc, ObjectKind, Point};
use crate::error::LoadError;
use glam::{Affine3A, DAffine3, DVec3, Mat3, Vec3};
use lucent::shape::solid::algebraic;
use lucent::shape::{Solid, SolidShape};
use std::ops::Range;
use toml::Spanned;

/// Whether `kind` is one of the exact solids.
pub(super) fn is_solid(kind: ObjectKind) -> bool {
    matches!(
        kind,
        ObjectKind::Box
            | ObjectKind::Cylinder
            | ObjectKind::Cone
            | ObjectKind::Disc
            | ObjectKind::Torus
            | ObjectKind::Ellipsoid
            | ObjectKind::Superellipsoid
            | ObjectKind::Algebraic
    )
}

/// The keys of a solid's own shape (a placement may follow).
pub(super) fn keys(kind: ObjectKind) -> impl Iterator<Item = &'static str> {
    let keys: &[&str] = match kind {
        ObjectKind::Box => &["min", "max"],
        ObjectKind::Cylinder => &["base", "cap", "radius", "open"],
        ObjectKind::Cone => &["base", "cap", "base_radius", "cap_radius", "open"],
        ObjectKind::Disc => &["center", "normal", "radius", "hole"],
        ObjectKind::Torus => &["major", "minor"],
        ObjectKind::Ellipsoid => &["center", "radii"],
        ObjectKind::Superellipsoid => &["exponents"],
        ObjectKind::Algebraic => &["terms", "bounds"],
        _ => &[],
    };
    keys.iter().copied()
}

/// Adds the solid of table `d` (at `table`) with `material`; `emissive`: its material emits a
/// colour, which a solid cannot yet do as an area light.
pub(super) fn add_solid(
    ctx: &mut Context,
    d: &ObjectDesc,
    table: Range<usize>,
    material: u32,
    emissive: bool,
) -> Result<(), LoadError> {
    let kind = d.kind.name();
    let source = ctx.source;
    if let Some(m) = &d.motion {
        return Err(source.error(
            m.span(),
            format!("a {kind} cannot move yet (spheres, meshes and the unit shapes can)"),
        ));
    }
    check(
        source,
        d.material.span(),
        !emissive,
        &format!(
            "a {kind} cannot be an area light yet, and material `{}` emits light (use a mesh or a sphere, or give the emission as a texture to make it glow without lighting the scene)",
            d.material.get_ref()
        ),
    )?;
    let solid = solid_of(ctx, d, table.clone(), DAffine3::IDENTITY)?;
    check(
        source,
        table,
        solid.is_bounded(),
        "an algebraic surface alone needs `bounds` (or cut it with an intersection or a difference)",
    )?;
    ctx.builder.solid(solid, material);
    Ok(())
}

/// The solid of table `d` (at `table`), placed by its own keys, its placement, then `parent`
/// (a combination's placement; maps in the scene's coordinates, relative to its origin).
pub(super) fn solid_of(
    ctx: &Context,
    d: &ObjectDesc,
    table: Range<usize>,
    parent: DAffine3,
) -> Result<Solid, LoadError> {
    let own = own_shape(ctx, d, table.clone())?;
    let frame = DAffine3 {
        matrix3: Mat3::from(own.linear).as_dmat3(),
        translation: own.origin - ctx.origin,
    };
    let m = parent * placed(ctx, d, table.clone())? * frame;
    let to_world = Affine3A::from_mat3_translation(m.matrix3.as_mat3(), m.translation.as_vec3());
    let kind = d.kind.name();
    Solid::new(own.shape, to_world).ok_or_else(|| {
        ctx.source.error(
            table,
            format!("the {kind} is flattened or overflows in single precision where it is placed"),
        )
    })
}

/// Table `d`'s placement keys as a map in the scene's coordinates (relative to its origin):
/// `w ↦ L·w + T` in the world is `x ↦ L·x + (T − o) + L·o` for `x = w − o`.
pub(super) fn placed(
    ctx: &Context,
    d: &ObjectDesc,
    table: Range<usize>,
) -> Result<DAffine3, LoadError> {
    let p = placement(ctx, d, table)?;
    let linear = Mat3::from(p.matrix3).as_dmat3();
    Ok(DAffine3 {
        matrix3: linear,
        translation: Vec3::from(p.translation).as_dvec3() + linear * ctx.origin,
    })
}

/// A canonical shape and the frame that makes it the table's: its linear part and origin (in
/// the world, before the scene's origin is taken off).
struct OwnShape {
    shape: SolidShape,
    linear: glam::Mat3A,
    origin: DVec3,
}

fn own_shape(ctx: &Context, d: &ObjectDesc, table: Range<usize>) -> Result<OwnShape, LoadError> {
    let kind = d.kind.name();
    let source = ctx.source;
    let point =
        |key: &str, v: &Option<Spanned<Point>>| -> Result<(DVec3, Range<usize>), LoadError> {
            let p = required(source, table.clone(), kind, key, v)?;
            Ok((p.get_ref().0, p.span()))
        };
    let length = |key: &str, v: &Option<Spanned<Finite>>, zero: bool| -> Result<f32, LoadError> {
        let r = required(source, table.clone(), kind, key, v)?;
        let x = r.get_ref().0;
        let ok = (zero && x == 0.0) || RADIUS_RANGE.contains(&x);
        let (lo, hi) = (RADIUS_RANGE.start(), RADIUS_RANGE.end());
        let least = if zero { "0 or " } else { "" };
        check(
            source,
            r.span(),
            ok,
            &format!("a {kind}'s `{key}` must be {least}between {lo:e} and {hi:e}, got {x}"),
        )?;
        Ok(x)
    };
    Ok(match d.kind {
        ObjectKind::Box => {
            let (lo, _) = point("min", &d.min)?;
            let (hi, at) = point("max", &d.max)?;
            check(
                source,
                at,
                lo.cmplt(hi).all(),
                &format!("a box's `max` must be above its `min` on every axis: min {lo}, max {hi}"),
            )?;
            OwnShape {
                shape: SolidShape::Box,
                linear: glam::Mat3A::from_diagonal(((hi - lo) * 0.5).as_vec3()),
                origin: (lo + hi) * 0.5,
            }
        }
        ObjectKind::Cylinder | ObjectKind::Cone => {
            let (base, _) = point("base", &d.base)?;
            let (cap, at) = point("cap", &d.cap)?;
            let axis = cap - base;
            check(
                source,
                at,
                axis.length() > 0.0,
                &format!("a {kind}'s `cap` must differ from its `base`"),
            )?;
            let (radii, open) = if d.kind == ObjectKind::Cylinder {
                let r = length("radius", &d.radius, false)?;
                ([r, r], d.open.unwrap_or(false))
            } else {
                let r0 = length("base_radius", &d.base_radius, true)?;
                let r1 = length("cap_radius", &d.cap_radius, true)?;
                let at = d.cap_radius.as_ref().map_or(table.clone(), Spanned::span);
                check(
                    source,
                    at,
                    r0 > 0.0 || r1 > 0.0,
                    "a cone's radii cannot both be 0",
                )?;
                ([r0, r1], d.open.unwrap_or(false))
            };
            let widest = radii[0].max(radii[1]);
            let shape = if d.kind == ObjectKind::Cylinder {
                SolidShape::Cylinder { open }
            } else {
                let ratio = |r: f32| f64::from(r) / f64::from(widest);
                SolidShape::Cone {
                    radii: [ratio(radii[0]), ratio(radii[1])],
                    open,
                }
            };
            OwnShape {
                shape,
                linear: frame_along(axis.as_vec3(), widest),
                origin: base,
            }
        }
        ObjectKind::Disc => {
            let (center, _) = point("center", &d.center)?;
            let n = required(source, table.clone(), kind, "normal", &d.normal)?;
            let normal = super::rescaled(n.get_ref().0);
            check(
                source,
                n.span(),
                normal != Vec3::ZERO,
                "a disc's normal cannot be zero",
            )?;
            let r = length("radius", &d.radius, false)?;
            let hole = match &d.hole {
                None => 0.0,
                Some(h) => {
                    let x = h.get_ref().0;
                    let why = format!(
                        "a disc's `hole` must be at least 0 and below its radius {r}, got {x}"
                    );
                    check(source, h.span(), (0.0..r).contains(&x), &why)?;
                    x
                }
            };
            let mut linear = frame_along(normal, r);
            linear.z_axis = linear.z_axis.normalize() * r;
            OwnShape {
                shape: SolidShape::Disc {
                    hole: f64::from(hole) / f64::from(r),
                },
                linear,
                origin: center,
            }
        }
        ObjectKind::Sphere => {
            // A sphere in a combination: the ellipsoid of equal radii.
            let (center, _) = point("center", &d.center)?;
            let r = length("radius", &d.radius, false)?;
            OwnShape {
                shape: SolidShape::Ellipsoid,
                linear: glam::Mat3A::from_diagonal(Vec3::splat(r)),
                origin: center,
            }
        }
        ObjectKind::Superellipsoid => {
            let x = required(source, table.clone(), kind, "exponents", &d.exponents)?;
            let [e, n] = x.get_ref().map(|v| v.0);
            check(
                source,
                x.span(),
                [e, n].iter().all(|v| (0.01..=10.0).contains(v)),
                &format!(
                    "a superellipsoid's `exponents` must each be from 0.01 to 10, got [{e}, {n}]"
                ),
            )?;
            OwnShape {
                shape: SolidShape::Superellipsoid {
                    exponents: [f64::from(e), f64::from(n)],
                },
                linear: glam::Mat3A::IDENTITY,
                origin: DVec3::ZERO,
            }
        }
        ObjectKind::Algebraic => algebraic(source, table.clone(), d)?,
        ObjectKind::Plane => {
            // In a combination: the half-space behind the plane, `n·(x − p) < 0`.
            let (at, _) = point("point", &d.point)?;
            let n = required(source, table.clone(), kind, "normal", &d.normal)?;
            let normal = n.get_ref().0.as_dvec3().normalize_or_zero();
            check(
                source,
                n.span(),
                normal != DVec3::ZERO,
                "a plane's normal cannot be zero",
            )?;
            OwnShape {
                shape: SolidShape::Algebraic {
                    coefficients: algebraic::half_space(normal, 0.0),
                    bounds: None,
                },
                linear: glam::Mat3A::IDENTITY,
                origin: at,
            }
        }
        ObjectKind::Ellipsoid => {
            let (center, _) = point("center", &d.center)?;
            let r = required(source, table.clone(), kind, "radii", &d.radii)?;
            let radii = r.get_ref().0;
            let (lo, hi) = (RADIUS_RANGE.start(), RADIUS_RANGE.end());
            check(
                source,
                r.span(),
                radii.to_array().iter().all(|x| RADIUS_RANGE.contains(x)),
                &format!(
                    "an ellipsoid's `radii` must each be between {lo:e} and {hi:e}, got {radii}"
                ),
            )?;
            OwnShape {
                shape: SolidShape::Ellipsoid,
                linear: glam::Mat3A::from_diagonal(radii),
                origin: center,
            }
        }
        _ => {
            let major = length("major", &d.major, false)?;
            let minor = length("minor", &d.minor, false)?;
            // The canonical torus lies about z; POV-Ray's, and this one's, about y.
            let about_y = glam::Mat3A::from_rotation_x(-std::f32::consts::FRAC_PI_2);
            OwnShape {
                shape: SolidShape::Torus {
                    minor: f64::from(minor) / f64::from(major),
                },
                linear: about_y * glam::Mat3A::from_diagonal(Vec3::splat(major)),
                origin: DVec3::ZERO,
            }
        }
    })
}

/// An algebraic surface's own shape from its `terms` and `bounds`.
fn algebraic(
    source: &super::Source,
    table: Range<usize>,
    d: &ObjectDesc,
) -> Result<OwnShape, LoadError> {
    let t = required(source, table, "algebraic", "terms", &d.terms)?;
    let mut terms = Vec::with_capacity(t.get_ref().len());
    for &[k, i, j, l] in t.get_ref() {
        let power = |x: f64| (x >= 0.0 && x.fract() == 0.0 && x <= 4.0).then_some(x as u8);
        let powers = [power(i), power(j), power(l)];
        let why = format!(
            "an algebraic term is `[coefficient, i, j, k]` with whole powers from 0 to 4 adding up to at most 4 and a finite coefficient, got [{k}, {i}, {j}, {l}]"
        );
        let fine = k.is_finite() && powers.iter().all(Option::is_some);
        let powers = powers.map(|p| p.unwrap_or(0));
        check(
            source,
            t.span(),
            fine && powers.iter().sum::<u8>() <= 4,
            &why,
        )?;
        terms.push((k, powers));
    }
    let coefficients = algebraic::from_terms(&terms).unwrap_or([0.0; algebraic::TERMS]);
    check(
        source,
        t.span(),
        algebraic::degree(&coefficients) >= 1,
        "an algebraic surface needs a term of degree 1 or more",
    )?;
    let bounds = match &d.bounds {
        None => None,
        Some(b) => {
            let [lo, hi] = b.get_ref().map(|p| p.0);
            let why = format!(
                "`bounds` must be [min, max] with max above min on every axis, got {lo} and {hi}"
            );
            check(source, b.span(), lo.cmplt(hi).all(), &why)?;
            Some([lo, hi])
        }
    };
    Ok(OwnShape {
        shape: SolidShape::Algebraic {
            coefficients,
            bounds,
        },
        linear: glam::Mat3A::IDENTITY,
        origin: DVec3::ZERO,
    })
}

/// Columns: two directions across `axis` scaled by `radius`, then `axis` itself; a
/// right-handed frame.
fn frame_along(axis: Vec3, radius: f32) -> glam::Mat3A {
    let (u, v) = axis.normalize().any_orthonormal_pair();
    let v = if u.cross(v).dot(axis) < 0.0 { -v } else { v };
    glam::Mat3A::from_cols((u * radius).into(), (v * radius).into(), axis.into())
}
