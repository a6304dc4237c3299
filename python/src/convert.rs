//! Between lucent's types and Python's: names, errors and the dicts of a render's meta data
//! and a scene's info.

use crate::SceneError;
use lucent::render::{RenderSettings, Rendered};
use lucent_scene::desc::IntegratorName;
use lucent_scene::overrides::Overrides;
use lucent_scene::{LoadError, Loaded, SceneFile};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Deserialize;
use serde::de::IntoDeserializer;

/// A setting's value from its name in scene files (`"path"`, `"debug:normals"`, `"gaussian"`).
fn parse_name<T: for<'de> Deserialize<'de>>(value: &str, setting: &str) -> PyResult<T> {
    let de: serde::de::value::StrDeserializer<'_, serde::de::value::Error> =
        value.into_deserializer();
    T::deserialize(de).map_err(|e| PyValueError::new_err(format!("{setting}: {e}")))
}

/// Overrides with the settings given by name parsed (`integrator="path"`, `filter`, `aa`), the
/// rest unset.
pub fn named_overrides(
    integrator: Option<&str>,
    filter: Option<&str>,
    aa: Option<&str>,
) -> PyResult<Overrides> {
    Ok(Overrides {
        integrator: integrator
            .map(|i| parse_name(i, "integrator"))
            .transpose()?,
        filter: filter.map(|f| parse_name(f, "filter")).transpose()?,
        aa: aa.map(|a| parse_name(a, "aa")).transpose()?,
        ..Overrides::default()
    })
}

/// A count given to a keyword (`spp=16`): a negative or huge one is a `ValueError` naming the
/// keyword (the ranges themselves are checked with the command's, in `Overrides::apply`).
pub fn count(setting: &str, value: Option<i64>) -> PyResult<Option<u32>> {
    value
        .map(|v| {
            u32::try_from(v).map_err(|_| {
                PyValueError::new_err(format!(
                    "{setting} must be zero or more and below 2³², not {v}"
                ))
            })
        })
        .transpose()
}

/// An integrator's name as scene files write it.
pub fn name(i: IntegratorName) -> String {
    match toml::Value::try_from(i) {
        Ok(toml::Value::String(s)) => s,
        _ => format!("{i:?}"),
    }
}

/// A [`LoadError`] as a `SceneError` with its file, line and column. A scene given as a string
/// or a dict has no file to look in: the message quotes the line of `text` at fault.
pub fn scene_error(py: Python<'_>, e: &LoadError, text: &str) -> PyErr {
    let in_memory = e.file.to_str().is_some_and(|f| f.starts_with('<'));
    let quoted = match e.position {
        Some((line, _)) if in_memory => text
            .lines()
            .nth(line.saturating_sub(1))
            .map(|l| format!("\n    {line} | {l}")),
        _ => None,
    };
    let err = SceneError::new_err(format!("{e}{}", quoted.unwrap_or_default()));
    let value = err.value(py);
    let (line, column) = e.position.unzip();
    let located = value
        .setattr("file", e.file.display().to_string())
        .and_then(|()| value.setattr("line", line))
        .and_then(|()| value.setattr("column", column))
        .and_then(|()| value.setattr("message", &e.message));
    match located {
        Ok(()) => err,
        Err(other) => other,
    }
}

/// What a render did: its size, samples, integrator, time, rays, and whether it finished.
pub fn meta<'py>(
    py: Python<'py>,
    file: &SceneFile,
    loaded: &Loaded,
    settings: &RenderSettings,
    r: &Rendered,
    interrupted: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let camera = &loaded.scene.camera;
    d.set_item("width", camera.width())?;
    d.set_item("height", camera.height())?;
    d.set_item("spp", settings.spp)?;
    d.set_item("samples_range", r.samples_range)?;
    d.set_item("integrator", name(file.desc.render.integrator))?;
    d.set_item("seed", settings.seed)?;
    d.set_item("threads", r.stats.threads)?;
    d.set_item("seconds", r.stats.elapsed.as_secs_f64())?;
    d.set_item("samples", r.stats.samples)?;
    let rays = PyDict::new(py);
    let s = &r.stats.rays;
    rays.set_item("camera", s.camera)?;
    rays.set_item("shadow", s.shadow)?;
    rays.set_item("reflected", s.reflected)?;
    rays.set_item("refracted", s.refracted)?;
    rays.set_item("photons", s.photons)?;
    rays.set_item("scattered", s.scattered)?;
    rays.set_item("total", s.total())?;
    d.set_item("rays", rays)?;
    d.set_item("mrays_per_second", r.stats.mrays_per_second())?;
    d.set_item("nonfinite_samples", s.nonfinite)?;
    d.set_item("complete", r.complete)?;
    d.set_item("timed_out", r.timed_out)?;
    d.set_item("interrupted", interrupted)?;
    d.set_item("warnings", loaded.warnings.clone())?;
    Ok(d)
}

/// What a scene holds and the settings its file gives.
pub fn info<'py>(
    py: Python<'py>,
    file: &SceneFile,
    loaded: &Loaded,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let scene = &loaded.scene;
    let c = scene.counts();
    d.set_item("path", file.path.display().to_string())?;
    d.set_item("objects", c.objects)?;
    d.set_item("spheres", c.spheres)?;
    d.set_item("planes", c.planes)?;
    d.set_item("meshes", c.meshes)?;
    d.set_item("mesh_instances", c.instances)?;
    d.set_item("triangles", c.triangles)?;
    d.set_item("lights", c.lights)?;
    d.set_item("area_lights", scene.emitters.area.lights.len())?;
    d.set_item("environment", scene.emitters.environment.is_some())?;
    d.set_item("materials", c.materials)?;
    let b = scene.bounds();
    d.set_item("bounds", (b.min.to_array(), b.max.to_array()))?;
    d.set_item("width", scene.camera.width())?;
    d.set_item("height", scene.camera.height())?;
    d.set_item("spp", loaded.settings.spp)?;
    d.set_item("integrator", name(file.desc.render.integrator))?;
    d.set_item("seed", loaded.settings.seed)?;
    d.set_item("warnings", loaded.warnings.clone())?;
    Ok(d)
}
