//! `motion` tables into [`Motion`]s, with errors at the key or part at fault.

use crate::desc::{MotionDesc, RepeatName};
use crate::error::{LoadError, Source};
use glam::{DVec3, Vec3};
use lucent::motion::{Key, Motion, MotionError, MotionPart, Orbit, Oscillate, Repeat};
use toml::Spanned;

/// The motion `m` describes, checked, in a scene whose coordinates' zero is at `origin` in the
/// file's world: its orbit's centre is moved as every point is, and its keys still scale and
/// rotate about the world's origin.
pub fn motion(
    source: &Source,
    m: &Spanned<MotionDesc>,
    origin: DVec3,
) -> Result<Motion, LoadError> {
    let d = m.get_ref();
    let keys = d
        .keys
        .iter()
        .map(|k| {
            let k = k.get_ref();
            Key::new(f64::from(k.time.get_ref().0))
                .with_translate(k.translate.map_or(Vec3::ZERO, |v| v.0))
                .with_rotate_degrees(k.rotate.map_or(Vec3::ZERO, |v| v.0))
                .with_scale(k.scale.as_ref().map_or(Vec3::ONE, |s| s.get_ref().0))
        })
        .collect();
    let repeat = match d.repeat.as_ref().map(|r| *r.get_ref()) {
        None | Some(RepeatName::Hold) => Repeat::Hold,
        Some(RepeatName::Loop) => Repeat::Loop,
        Some(RepeatName::Bounce) => Repeat::Bounce,
    };
    if let Some(r) = &d.repeat
        && d.keys.is_empty()
    {
        return Err(source.error(r.span(), "`repeat` needs `keys` to repeat"));
    }
    let degrees = |p: Option<crate::desc::Finite>| p.map_or(0.0, |p| f64::from(p.0).to_radians());
    let oscillate = d.oscillate.as_ref().map(|o| {
        let o = o.get_ref();
        Oscillate {
            offset: o.offset.0,
            period: f64::from(o.period.get_ref().0),
            phase: degrees(o.phase),
        }
    });
    let orbit = d.orbit.as_ref().map(|o| {
        let o = o.get_ref();
        Orbit {
            center: (o.center.map_or(DVec3::ZERO, |c| c.0) - origin).as_vec3(),
            axis: o
                .axis
                .as_ref()
                .map_or(Vec3::Y, |a| super::rescaled(a.get_ref().0)),
            period: f64::from(o.period.get_ref().0),
            phase: degrees(o.phase),
        }
    });
    Motion::new(keys, repeat, oscillate, orbit)
        .map(|m| m.with_keys_about(-origin))
        .map_err(|e| {
            let span = span_of(d, &e).unwrap_or_else(|| m.span());
            source.error(span, format!("motion: {e}"))
        })
}

/// Where in the table error `e` points.
fn span_of(d: &MotionDesc, e: &MotionError) -> Option<std::ops::Range<usize>> {
    match (e, e.part()) {
        (MotionError::KeyOrder { .. }, MotionPart::Key(i)) => {
            Some(d.keys.get(i)?.get_ref().time.span())
        }
        (MotionError::Scale { .. }, MotionPart::Key(i)) => {
            let key = d.keys.get(i)?;
            Some(
                key.get_ref()
                    .scale
                    .as_ref()
                    .map_or(key.span(), |s| s.span()),
            )
        }
        (_, MotionPart::Key(i)) => Some(d.keys.get(i)?.span()),
        (MotionError::ZeroAxis, _) => d.orbit.as_ref()?.get_ref().axis.as_ref().map(|a| a.span()),
        (MotionError::Period { .. }, MotionPart::Orbit) => {
            Some(d.orbit.as_ref()?.get_ref().period.span())
        }
        (MotionError::Period { .. }, MotionPart::Oscillate) => {
            Some(d.oscillate.as_ref()?.get_ref().period.span())
        }
        (_, MotionPart::Orbit) => Some(d.orbit.as_ref()?.span()),
        (_, MotionPart::Oscillate) => Some(d.oscillate.as_ref()?.span()),
    }
}
