//! `[[medium]]` tables to the scene's media, and the names objects and the camera use.

use super::Context;
use crate::desc::{Color, MediumDesc, Point, SceneDesc};
use crate::error::LoadError;
use glam::{Affine3A, Quat};
use lucent::Rgb;
use lucent::medium::{AlbedoGrid, DensityGrid, Medium, MediumInterface, phase::MAX_G};
use std::collections::HashMap;
use std::sync::Arc;
use toml::Spanned;

/// The media of a scene file, by name.
pub struct Media<'a> {
    ids: HashMap<&'a str, u32>,
}

impl<'a> Media<'a> {
    /// Adds every `[[medium]]` of `desc` to the scene.
    pub fn add(desc: &'a SceneDesc, ctx: &mut Context) -> Result<Self, LoadError> {
        let mut ids = HashMap::new();
        for m in &desc.media {
            let d = m.get_ref();
            let name = d.name.get_ref().as_str();
            if ids.contains_key(name) {
                return Err(ctx.source.error(
                    d.name.span(),
                    format!("a medium named `{name}` already exists"),
                ));
            }
            let medium = medium(ctx, m)?;
            ids.insert(name, ctx.builder.media().add(medium));
        }
        Ok(Self { ids })
    }

    /// The medium called `name`, or an error at it listing the known ones.
    pub fn named(&self, ctx: &Context, name: &Spanned<String>) -> Result<u32, LoadError> {
        if let Some(&id) = self.ids.get(name.get_ref().as_str()) {
            return Ok(id);
        }
        let mut known: Vec<_> = self.ids.keys().copied().collect();
        known.sort_unstable();
        let hint = if known.is_empty() {
            "no [[medium]] is defined".to_string()
        } else {
            format!("known: {}", known.join(", "))
        };
        Err(ctx.source.error(
            name.span(),
            format!("unknown medium `{}` ({hint})", name.get_ref()),
        ))
    }

    /// The interface of an object with `interior` and `exterior` media named, if any.
    pub fn interface(
        &self,
        ctx: &Context,
        interior: &Option<Spanned<String>>,
        exterior: &Option<Spanned<String>>,
    ) -> Result<MediumInterface, LoadError> {
        let id = |n: &Option<Spanned<String>>| n.as_ref().map(|n| self.named(ctx, n)).transpose();
        Ok(MediumInterface {
            inside: id(interior)?,
            outside: id(exterior)?,
        })
    }
}

/// The medium `m` describes, its keys checked.
fn medium(ctx: &mut Context, m: &Spanned<MediumDesc>) -> Result<Medium, LoadError> {
    let d = m.get_ref();
    let err = |span: std::ops::Range<usize>, why: &str| ctx.source.error(span, why.to_string());
    let value = |c: &Option<Spanned<Color>>| c.as_ref().map(|c| c.get_ref().0);
    let scale = match &d.scale {
        Some(s) if s.get_ref().0 < 0.0 => {
            return Err(err(s.span(), "`scale` must be at least 0"));
        }
        Some(s) => s.get_ref().0,
        None => 1.0,
    };
    let g = match &d.g {
        Some(g) if g.get_ref().0.abs() > MAX_G => {
            return Err(err(
                g.span(),
                "`g` must lie strictly between −1 and 1 (at ±1 the phase function is a delta; 0.999 at most)",
            ));
        }
        Some(g) => g.get_ref().0,
        None => 0.0,
    };
    let by_albedo = d.sigma_t.is_some() || d.albedo.is_some();
    let by_parts = d.sigma_a.is_some() || d.sigma_s.is_some();
    if by_albedo && by_parts {
        return Err(err(
            m.span(),
            "give `sigma_a` and `sigma_s`, or `sigma_t` and `albedo`, not keys of both",
        ));
    }
    if let Some(a) = &d.albedo
        && a.get_ref().0.max_channel() > 1.0
    {
        return Err(err(a.span(), "`albedo` must be at most 1 in every channel"));
    }
    let medium = if by_albedo {
        let Some(sigma_t) = value(&d.sigma_t) else {
            return Err(err(m.span(), "`albedo` needs `sigma_t`, the extinction"));
        };
        let albedo = value(&d.albedo).unwrap_or(Rgb::gray(0.8));
        Medium::from_albedo(sigma_t * scale, albedo, g)
    } else {
        let zero = Rgb::BLACK;
        Medium::new(
            value(&d.sigma_a).unwrap_or(zero) * scale,
            value(&d.sigma_s).unwrap_or(zero) * scale,
            g,
        )
    };
    if !medium.sigma_t().is_finite() {
        return Err(err(m.span(), "the coefficients times `scale` overflow"));
    }
    let Some(file) = &d.density else {
        return match (&d.bounds, &d.albedo_grid) {
            (Some(_), _) => Err(err(m.span(), "`bounds` places a `density` grid: give one")),
            (_, Some(a)) => Err(err(a.span(), "an `albedo_grid` needs a `density` grid")),
            (None, None) => Ok(medium),
        };
    };
    let (vol, path) = grid_file(ctx, file, 1)?;
    let to_world = placement(ctx, &d.bounds, &vol, file)?;
    let density = DensityGrid::new(vol.res, vol.values, to_world)
        .map_err(|e| LoadError::file(&path, format!("volume grid: {e}")))?;
    let mut medium = medium.with_density(Arc::new(density));
    if let Some(file) = &d.albedo_grid {
        let (vol, path) = grid_file(ctx, file, 3)?;
        let values = match vol.channels {
            1 => vol.values.iter().map(|&v| Rgb::gray(v)).collect(),
            _ => (vol.values.chunks_exact(3))
                .map(|c| Rgb::new(c[0], c[1], c[2]))
                .collect(),
        };
        let albedo = AlbedoGrid::new(vol.res, values, to_world)
            .map_err(|e| LoadError::file(&path, format!("albedo grid: {e}")))?;
        medium = medium.with_albedo(Arc::new(albedo));
    }
    Ok(medium)
}

/// The `.vol` grid the key `file` names (of at most `channels` channels), and its path.
fn grid_file(
    ctx: &mut Context,
    file: &Spanned<String>,
    channels: usize,
) -> Result<(crate::vol::VolGrid, std::path::PathBuf), LoadError> {
    let (path, bytes) = ctx.read_named(file, "grid file")?;
    let vol = crate::vol::parse_vol(&path, &bytes)?;
    if vol.channels > channels {
        let message = format!(
            "grid file `{}` has {} channels; a density grid has 1",
            path.display(),
            vol.channels
        );
        return Err(ctx.source.error(file.span(), message));
    }
    Ok((vol, path))
}

/// Where the grids go: the box `bounds` gives, or else the one the density file `vol` (which
/// the key `file` names) gives.
fn placement(
    ctx: &Context,
    bounds: &Option<Spanned<[Point; 2]>>,
    vol: &crate::vol::VolGrid,
    file: &Spanned<String>,
) -> Result<Affine3A, LoadError> {
    let (min, max, span) = match bounds {
        Some(b) => {
            let [lo, hi] = b.get_ref();
            (ctx.local(lo.0), ctx.local(hi.0), b.span())
        }
        None => (
            ctx.local(vol.bounds.0.as_dvec3()),
            ctx.local(vol.bounds.1.as_dvec3()),
            file.span(),
        ),
    };
    if !(min.cmplt(max).all() && min.is_finite() && max.is_finite()) {
        let whose = if bounds.is_some() {
            "`bounds`"
        } else {
            "the grid file's box"
        };
        return Err(ctx.source.error(
            span,
            format!("{whose} must have min < max on every axis, got {min} and {max}"),
        ));
    }
    let scale = max - min;
    Ok(Affine3A::from_scale_rotation_translation(
        scale,
        Quat::IDENTITY,
        min,
    ))
}
