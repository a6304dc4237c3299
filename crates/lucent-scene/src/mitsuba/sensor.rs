//! `<sensor>` → `[camera]` and `[image]`; `<integrator>` → `[render]`.
//!
//! `perspective` is a pinhole; `thinlens` adds its lens (`aperture_radius`, and
//! `focus_distance`, by default the far clip distance, as in Mitsuba); `orthographic` views the
//! square `[-1, 1]` wide and `[-1, 1]/aspect` high of its camera space, placed by `to_world`
//! (whose scale sizes it), along +z.
//!
//! Mitsuba's camera looks along its +z with +y up, and its camera space is left-handed in
//! the image: +x points to the image's *left* (`lookat` builds `left = up × dir`). lucent's
//! camera puts `dir × up` to the image's right. For a `to_world` whose linear part keeps
//! handedness (a rotation, possibly scaled) the two agree, so eye = M·0, look_at = eye + M·+z
//! and up = M·+y reproduce Mitsuba's picture; a mirroring `to_world` (negative determinant)
//! makes lucent's image the mirror of Mitsuba's, which is reported.
//!
//! Mitsuba's `fov` is measured along `fov_axis` (`x` by default; `y`, `smaller`, `larger`,
//! `diagonal`); lucent's is vertical. Following Mitsuba's `parse_fov`, it is first turned into
//! the horizontal angle `fx`, then `fov_y = 2·atan(tan(fx/2) / aspect)` with
//! `aspect = width / height`.
//!
//! `shutter_open` and `shutter_close` (the times it opens and closes, both 0 by default)
//! become `[camera] shutter`.

use super::Convert;
use super::transform;
use super::xml::{Element, Loc};
use crate::build::{MAX_DEPTH, MAX_IMAGE_SIDE, MAX_PIXELS, MAX_SAMPLES};
use crate::desc::settings::FilterName;
use crate::desc::{CameraDesc, Finite, IntegratorName, Point, SceneDesc, Vector};
use crate::error::LoadError;
use glam::{DMat4, DVec3};
use toml::Spanned;

/// The sensor types lucent reads.
pub const SENSORS: &[&str] = &["perspective", "thinlens", "orthographic"];
/// The film types lucent reads.
pub const FILMS: &[&str] = &["hdrfilm"];
/// The sampler types lucent reads (their `sample_count` only).
pub const SAMPLERS: &[&str] = &[
    "independent",
    "stratified",
    "multijitter",
    "orthogonal",
    "ldsampler",
];
/// Mitsuba's reconstruction filters (not read: lucent has its own).
pub const FILTERS: &[&str] = &[
    "box",
    "tent",
    "gaussian",
    "mitchell",
    "catmullrom",
    "lanczos",
];
/// The integrator types lucent reads.
pub const INTEGRATORS: &[&str] = &["path", "direct", "volpath", "volpathmis"];

/// Mitsuba's defaults: film 768 × 576, 4 samples per pixel.
pub const DEFAULT_FILM: (u32, u32) = (768, 576);
/// Mitsuba's default `sample_count`.
pub const DEFAULT_SAMPLES: u32 = 4;

/// Which angle a `fov` measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    /// Horizontal (Mitsuba's default).
    X,
    /// Vertical.
    Y,
    /// The smaller of the image's sides.
    Smaller,
    /// The larger of the image's sides.
    Larger,
    /// The diagonal.
    Diagonal,
}

impl FovAxis {
    fn parse(s: &str, loc: &Loc) -> Result<Self, LoadError> {
        Ok(match s.to_lowercase().as_str() {
            "x" => FovAxis::X,
            "y" => FovAxis::Y,
            "smaller" => FovAxis::Smaller,
            "larger" => FovAxis::Larger,
            "diagonal" => FovAxis::Diagonal,
            _ => {
                return Err(loc.error(format!(
                    "fov_axis is x, y, smaller, larger or diagonal, not `{s}`"
                )));
            }
        })
    }
}

/// The vertical field of view, in degrees, of a Mitsuba `fov` (degrees) along `axis` on an
/// image of `aspect` = width / height.
pub fn vertical_fov(fov: f64, axis: FovAxis, aspect: f64) -> f64 {
    let half = (fov.to_radians() / 2.0).tan();
    // Mitsuba's parse_fov: "smaller" is y when the image is wider than tall, else x.
    let axis = match axis {
        FovAxis::Smaller if aspect > 1.0 => FovAxis::Y,
        FovAxis::Smaller => FovAxis::X,
        FovAxis::Larger if aspect > 1.0 => FovAxis::X,
        FovAxis::Larger => FovAxis::Y,
        a => a,
    };
    // tan of half the horizontal angle.
    let half_x = match axis {
        FovAxis::X => half,
        FovAxis::Y => half * aspect,
        FovAxis::Diagonal => half / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        FovAxis::Smaller | FovAxis::Larger => unreachable!("resolved above"),
    };
    2.0 * (half_x / aspect).atan().to_degrees()
}

/// The integer `v` (or `default`), which must be in `1..=max`.
fn positive_u32(
    v: Option<(i64, &Loc)>,
    default: u32,
    max: u32,
    what: &str,
) -> Result<u32, LoadError> {
    match v {
        None => Ok(default),
        Some((i, loc)) => u32::try_from(i)
            .ok()
            .filter(|n| (1..=max).contains(n))
            .ok_or_else(|| {
                loc.error(format!(
                    "the {what} must be an integer from 1 to {max} (lucent's limit), got {i}"
                ))
            }),
    }
}

/// Reads the `<sensor>` `el` into `desc`'s camera and image.
pub fn read<'a>(
    cx: &mut Convert<'a>,
    el: &'a Element,
    desc: &mut SceneDesc,
) -> Result<(), LoadError> {
    let p = cx.plugin(el)?;
    if !SENSORS.contains(&p.kind) {
        return Err(super::unknown_type(el, p.kind));
    }
    let (mut width, mut height) = DEFAULT_FILM;
    let films = p.take("film");
    if let Some(extra) = films.get(1) {
        return Err(extra.at.error("a sensor has one film; this is a second"));
    }
    if let Some(film) = films.first() {
        let f = cx.plugin(film.el)?;
        if !FILMS.contains(&f.kind) {
            return Err(super::unknown_type(film.el, f.kind));
        }
        let w = f.integer("width")?;
        let h = f.integer("height")?;
        width = positive_u32(w, width, MAX_IMAGE_SIDE, "film width")?;
        height = positive_u32(h, height, MAX_IMAGE_SIDE, "film height")?;
        if u64::from(width) * u64::from(height) > MAX_PIXELS {
            let at = w.or(h).map_or(&film.el.loc, |(_, loc)| loc);
            return Err(at.error(format!(
                "the film has {width} × {height} pixels; lucent renders at most {MAX_PIXELS}"
            )));
        }
        for filter in f.take("rfilter") {
            let r = cx.plugin(filter.el)?;
            if !FILTERS.contains(&r.kind) {
                return Err(super::unknown_type(filter.el, r.kind));
            }
            desc.render.filter = Some(Spanned::new(0..0, rfilter(&r, &filter.el.loc)?));
            r.finish(&mut cx.warnings, &[]);
        }
        f.finish(
            &mut cx.warnings,
            &[
                "pixel_format",
                "component_format",
                "file_format",
                "sample_border",
            ],
        );
    }
    let media = p.take("medium");
    if let Some(extra) = media.get(1) {
        return Err(extra
            .at
            .error("a sensor sits in one medium; this is a second"));
    }
    let camera_medium = match media.first() {
        Some(m) => Some(Spanned::new(0..0, super::medium::named(cx, m.el)?)),
        None => None,
    };
    let mut samples = DEFAULT_SAMPLES;
    let samplers = p.take("sampler");
    if let Some(extra) = samplers.get(1) {
        return Err(extra.at.error("a sensor has one sampler; this is a second"));
    }
    if let Some(sampler) = samplers.first() {
        let s = cx.plugin(sampler.el)?;
        if !SAMPLERS.contains(&s.kind) {
            return Err(super::unknown_type(sampler.el, s.kind));
        }
        samples = positive_u32(
            s.integer("sample_count")?,
            samples,
            MAX_SAMPLES,
            "sample_count",
        )?;
        s.finish(&mut cx.warnings, &["seed", "jitter"]);
    }

    let aspect = f64::from(width) / f64::from(height);
    let m = p.transform("to_world")?;
    let (m, at) = m.map_or((DMat4::IDENTITY, &el.loc), |(m, loc)| (m, loc));
    let projection = if p.kind == "orthographic" {
        let (x, y) = (m.x_axis.truncate().length(), m.y_axis.truncate().length());
        if (x - y).abs() > 1e-6 * x.max(y) {
            p.warn(
                at,
                format!("the orthographic sensor's to_world scales x ({x}) and y ({y}) apart: lucent's view keeps the image's aspect, sized by y"),
            );
        }
        Projection::Orthographic((2.0 * y / aspect) as f32)
    } else {
        Projection::Perspective(fov_of(&p, el, aspect)?)
    };
    let lens = if p.kind == "thinlens" {
        let radius = p.float("aperture_radius")?.ok_or_else(|| {
            el.loc
                .error("a thinlens sensor needs its `aperture_radius` (as Mitsuba does)")
        })?;
        let far = p.float_or("far_clip", 1e4)?;
        let focus = p.float_or("focus_distance", far)?;
        if !(radius >= 0.0 && focus > 0.0 && radius.is_finite() && focus.is_finite()) {
            return Err(el.loc.error(format!(
                "the thin lens needs an aperture_radius ≥ 0 and a positive focus_distance, got {radius} and {focus}"
            )));
        }
        Some((Finite(radius as f32), Finite(focus as f32)))
    } else {
        None
    };
    let eye = m.transform_point3(DVec3::ZERO);
    let look_at = eye + m.transform_vector3(DVec3::Z);
    let up = m.transform_vector3(DVec3::Y);
    // What lucent's camera needs (as the build checks it, but here where the XML can be named).
    let forward = (look_at - eye).as_vec3();
    if forward.try_normalize().is_none() || forward.cross(up.as_vec3()).try_normalize().is_none() {
        return Err(at.error(
            "the sensor's to_world flattens its view: +z and +y must map to two directions that are not parallel",
        ));
    }
    if transform::handedness(&m) < 0.0 {
        p.warn(
            at,
            "the sensor's to_world mirrors (negative determinant): lucent's image is the mirror image of Mitsuba's",
        );
    }
    if transform::uniform_scale(&m).is_none() && p.kind != "orthographic" {
        p.warn(
            at,
            "the sensor's to_world scales unevenly or shears: lucent keeps only its position and orientation",
        );
    }
    let v = |v: DVec3| -> Result<Vector, LoadError> {
        let s = v.as_vec3();
        if s.is_finite() {
            Ok(Vector(s))
        } else {
            Err(at.error("the camera is beyond single precision"))
        }
    };
    let point = |p: DVec3| v(p).map(|_| Point(p));
    let open = p.float_or("shutter_open", 0.0)?;
    let close = p.float_or("shutter_close", 0.0)?;
    if close < open {
        return Err(at.error(format!(
            "the shutter closes (shutter_close = {close}) before it opens (shutter_open = {open})"
        )));
    }
    let time = |t: f64| Finite(t as f32);
    let shutter = (close > open).then(|| Spanned::new(0..0, [time(open), time(close)]));
    desc.camera = Spanned::new(
        0..0,
        CameraDesc {
            eye: point(eye)?,
            look_at: point(look_at)?,
            up: v(up)?,
            fov: Finite(match projection {
                Projection::Perspective(fov) => fov as f32,
                Projection::Orthographic(_) => 45.0,
            }),
            aperture: lens.map(|(r, _)| r),
            focus_distance: lens.map(|(_, f)| f),
            orthographic: match projection {
                Projection::Orthographic(h) => Some(Finite(h)),
                Projection::Perspective(_) => None,
            },
            motion: None,
            shutter,
            medium: camera_medium,
        },
    );
    desc.image.width = Spanned::new(0..0, width);
    desc.image.height = Spanned::new(0..0, height);
    desc.image.samples = Spanned::new(0..0, samples);
    p.finish(
        &mut cx.warnings,
        &["near_clip", "far_clip", "focus_distance"],
    );
    Ok(())
}

/// How a sensor projects.
#[derive(Clone, Copy)]
enum Projection {
    /// Through a point: the vertical field of view in degrees.
    Perspective(f64),
    /// Parallel: the view's height in scene units.
    Orthographic(f32),
}

/// A perspective sensor's vertical field of view in degrees, from its `fov` (along
/// `fov_axis`) or `focal_length`, for an image of `aspect`.
fn fov_of(p: &super::props::Plugin, el: &Element, aspect: f64) -> Result<f64, LoadError> {
    let (fov, axis) = match (p.float("fov")?, p.string("focal_length")?) {
        (Some(_), Some((_, loc))) => {
            return Err(loc.error("give either `fov` or `focal_length`, not both"));
        }
        (Some(fov), None) => {
            let axis = match p.string("fov_axis")? {
                Some((s, loc)) => FovAxis::parse(s, loc)?,
                None => FovAxis::X,
            };
            (fov, axis)
        }
        (None, focal) => (
            focal_fov(focal.unwrap_or(("50mm", &el.loc)))?,
            FovAxis::Diagonal,
        ),
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(el.loc.error(format!(
            "the field of view must be between 0 and 180 degrees, got {fov}"
        )));
    }
    Ok(vertical_fov(fov, axis, aspect))
}

/// The diagonal field of view of a 35 mm film behind a lens of `focal_length` (`"50mm"`).
fn focal_fov((text, loc): (&str, &Loc)) -> Result<f64, LoadError> {
    let number = text.trim().trim_end_matches("mm");
    let f: f64 = number
        .trim()
        .parse()
        .ok()
        .filter(|f: &f64| f.is_finite() && *f > 0.0)
        .ok_or_else(|| loc.error(format!("cannot read the focal length `{text}` (e.g. 50mm)")))?;
    // The diagonal of 36 × 24 mm film.
    Ok(2.0
        * ((36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / (2.0 * f))
            .atan()
            .to_degrees())
}

/// lucent's filter for the `<rfilter>` `r` (at `loc`): the same kind with Mitsuba's default
/// parameters; other parameters, and the kinds lucent lacks, are approximated with a warning.
fn rfilter(r: &super::props::Plugin, loc: &Loc) -> Result<FilterName, LoadError> {
    let (name, defaults): (FilterName, &[(&str, f64)]) = match r.kind {
        "box" => (FilterName::Box, &[("radius", 0.5)]),
        "tent" => (FilterName::Tent, &[("radius", 1.0)]),
        "gaussian" => (FilterName::Gaussian, &[("stddev", 0.5)]),
        "mitchell" => (FilterName::Mitchell, &[("B", 1.0 / 3.0), ("C", 1.0 / 3.0)]),
        other => {
            r.warn(
                loc,
                format!("the `{other}` filter is rendered with lucent's Mitchell filter"),
            );
            return Ok(FilterName::Mitchell);
        }
    };
    for &(key, default) in defaults {
        if let Some(v) = r.float(key)?
            && (v - default).abs() > 1e-6
        {
            r.warn(
                loc,
                format!(
                    "the {} filter's `{key}` {v} is rendered as Mitsuba's default {default}",
                    r.kind
                ),
            );
        }
    }
    Ok(name)
}

/// Reads the `<integrator>` `el` into `desc`'s render settings: its `max_depth` (−1, Mitsuba's
/// unbounded default, keeps lucent's).
///
/// Mitsuba counts the vertices of a path after the camera: `max_depth` 1 shows only what emits,
/// 2 adds direct lighting, each further one a bounce. Whitted's depth counts the bounces after
/// the directly lit first hit, so it is Mitsuba's less 2.
pub fn integrator<'a>(
    cx: &mut Convert<'a>,
    el: &'a Element,
    desc: &mut SceneDesc,
) -> Result<(), LoadError> {
    let p = cx.plugin(el)?;
    if !INTEGRATORS.contains(&p.kind) {
        return Err(super::unknown_type(el, p.kind));
    }
    if let Some((depth, loc)) = p.integer("max_depth")? {
        match depth {
            -1 => {}
            0 | 1 => {
                desc.render.max_depth = Spanned::new(0..0, 0);
                let mitsuba = if depth == 0 {
                    "a black image"
                } else {
                    "only what emits, unlit"
                };
                p.warn(
                    loc,
                    format!(
                        "max_depth {depth}: Mitsuba renders {mitsuba}; lucent's path integrator at its least depth (0) lights what the camera sees directly"
                    ),
                );
            }
            d if d >= 2 && d - 2 <= i64::from(MAX_DEPTH) => {
                let bounces = u32::try_from(d - 2).expect("at most MAX_DEPTH");
                desc.render.max_depth = Spanned::new(0..0, bounces);
            }
            d if d >= 2 => {
                return Err(loc.error(format!(
                    "max_depth {d} is more than lucent traces ({}, {MAX_DEPTH} bounces)",
                    i64::from(MAX_DEPTH) + 2
                )));
            }
            d => {
                return Err(loc.error(format!(
                    "max_depth is -1 (unbounded) or at least 0, not {d}"
                )));
            }
        }
    }
    desc.render.integrator = IntegratorName::Path;
    if p.kind == "direct" {
        // Direct lighting only: what a path of at most two segments gathers.
        desc.render.max_depth = Spanned::new(0..0, 0);
    }
    if let Some((rr, loc)) = p.integer("rr_depth")? {
        let Ok(rr) = u32::try_from(rr) else {
            return Err(loc.error(format!("rr_depth must be at least 0, not {rr}")));
        };
        desc.render.rr_depth = Some(Spanned::new(0..0, rr));
    }
    p.finish(&mut cx.warnings, &[]);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn fov_axes_convert_to_vertical() {
        let a = 4.0 / 3.0;
        let t = |deg: f64| (deg.to_radians() / 2.0).tan();
        let deg = |tan_half: f64| 2.0 * tan_half.atan().to_degrees();
        // x: tan(fy/2) = tan(fx/2) / aspect.
        assert!(close(vertical_fov(60.0, FovAxis::X, a), deg(t(60.0) / a)));
        // y: unchanged.
        assert!(close(vertical_fov(40.0, FovAxis::Y, a), 40.0));
        // smaller on a wide image is y; on a tall image x.
        assert!(close(vertical_fov(40.0, FovAxis::Smaller, a), 40.0));
        assert!(close(
            vertical_fov(40.0, FovAxis::Smaller, 0.5),
            deg(t(40.0) / 0.5)
        ));
        // larger on a wide image is x; on a tall image y.
        assert!(close(
            vertical_fov(40.0, FovAxis::Larger, a),
            deg(t(40.0) / a)
        ));
        assert!(close(vertical_fov(40.0, FovAxis::Larger, 0.5), 40.0));
        // diagonal: tan(fd/2)² = tan(fx/2)² + tan(fy/2)²; on 4:3 the half-diagonal is 5/3 of
        // the half-height.
        assert!(close(
            vertical_fov(50.0, FovAxis::Diagonal, a),
            deg(t(50.0) * 3.0 / 5.0)
        ));
        // A square image: every axis but the diagonal is the same angle.
        for axis in [FovAxis::X, FovAxis::Y, FovAxis::Smaller, FovAxis::Larger] {
            assert!(close(vertical_fov(39.3077, axis, 1.0), 39.3077));
        }
    }

    #[test]
    fn focal_length_is_a_diagonal_angle() {
        let loc = Loc {
            file: std::rc::Rc::from(std::path::Path::new("f.xml")),
            line: 1,
            column: 1,
        };
        // 50 mm on 35 mm film: 46.79° diagonally.
        let f = focal_fov(("50mm", &loc)).unwrap();
        assert!((f - 46.7930).abs() < 1e-3, "{f}");
        assert!(focal_fov(("wide", &loc)).is_err());
    }
}
