//! `lucent._lucent`: the extension module under the `lucent` Python package (`lucent/`).
//!
//! A scene is read once ([`load`], [`load_string`]) and kept unbuilt, so each render can
//! override its settings the way `lucent render`'s flags do (`lucent_scene::overrides`, the
//! same code): the same settings give the same image bits as the command line. Renders run
//! on their own thread with the GIL released; the calling thread wakes every 50 ms to report
//! progress and to let Python's signal handlers run, so Ctrl-C stops the render and returns
//! what it has.

mod convert;
mod dict_scene;
mod explain;
mod image;
mod polled;
mod study;

use convert::{count, meta, name, named_overrides, scene_error};
use lucent::integrator::explain::{ExplainError, explain_pixel};
use lucent::render::{Hooks, render};
use lucent::study::frameless::{StudySettings, run_study};
use lucent::study::scene_tracer::SceneTracer;
use lucent_scene::overrides::{Overrides, Spelling};
use lucent_scene::{Loaded, SceneFile};
use numpy::{PyArray3, PyReadonlyArray3};
use polled::run_polled;
use pyo3::exceptions::{PyException, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::Ordering;

pyo3::create_exception!(
    _lucent,
    SceneError,
    PyException,
    "A scene that cannot be read or built; `file`, `line` and `column` say where (`line` and \
     `column` are None for a problem with the file as a whole)."
);

/// A scene file read and parsed, not yet built: each render builds it with its settings.
#[pyclass(frozen, module = "lucent._lucent")]
struct Scene {
    file: SceneFile,
}

#[pymethods]
impl Scene {
    /// The file the scene came from.
    #[getter]
    fn path(&self) -> String {
        self.file.path.display().to_string()
    }

    /// The folder relative file names in the scene start from.
    #[getter]
    fn base_dir(&self) -> String {
        self.file.base_dir.display().to_string()
    }

    /// The scene file's text (empty for files imported from another format).
    #[getter]
    fn text(&self) -> &str {
        &self.file.text
    }

    /// Renders the scene: `(pixels, meta)`, pixels an H×W×3 float32 array of linear radiance
    /// (rows from the top), meta a dict of what the render did. Arguments left None keep the
    /// scene file's settings. `progress(done, total)` is called about every 50 ms.
    #[pyo3(signature = (*, spp=None, integrator=None, width=None, height=None, threads=0,
        seed=None, time_limit=None, max_depth=None, filter=None, shadows=true, aa=None,
        aa_threshold=None, aa_depth=None, aa_block=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        spp: Option<i64>,
        integrator: Option<&str>,
        width: Option<i64>,
        height: Option<i64>,
        threads: usize,
        seed: Option<u64>,
        time_limit: Option<f64>,
        max_depth: Option<i64>,
        filter: Option<&str>,
        shadows: bool,
        aa: Option<&str>,
        aa_threshold: Option<f32>,
        aa_depth: Option<i64>,
        aa_block: Option<i64>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyArray3<f32>>, Bound<'py, PyDict>)> {
        let overrides = Overrides {
            width: count("width", width)?,
            height: count("height", height)?,
            spp: count("spp", spp)?,
            max_depth: count("max_depth", max_depth)?,
            seed,
            time_limit,
            no_shadows: !shadows,
            aa_threshold,
            aa_depth: count("aa_depth", aa_depth)?,
            aa_block: count("aa_block", aa_block)?,
            ..named_overrides(integrator, filter, aa)?
        };
        let file = self.with(&overrides)?;
        let loaded = build(py, &file)?;
        let mut settings = loaded.settings;
        settings.threads = threads;
        let (rendered, interrupted) = run_polled(py, progress.as_ref(), |c| {
            let hooks = Hooks {
                cancel: c.cancel,
                progress: c.report,
                checkpoint: None,
            };
            render(&loaded.scene, &settings, None, &hooks)
        })?;
        let rendered = rendered.map_err(|e| PyException::new_err(e.to_string()))?;
        let meta = meta(py, &file, &loaded, &settings, &rendered, interrupted)?;
        let pixels = image::to_array(py, &rendered.film)?;
        Ok((pixels, meta))
    }

    /// The ray trees of pixel (x, y)'s samples as the Whitted integrator traces them (the
    /// render's own camera rays): a list of dicts, one per sample, each with its `tree` of
    /// nested dicts. `sample` picks one sample; the other arguments override the scene's
    /// settings as `render`'s do.
    #[pyo3(signature = (x, y, *, sample=None, spp=None, integrator=None, width=None,
        height=None, seed=None, max_depth=None, shadows=true, aa=None))]
    #[allow(clippy::too_many_arguments)]
    fn explain<'py>(
        &self,
        py: Python<'py>,
        x: i64,
        y: i64,
        sample: Option<i64>,
        spp: Option<i64>,
        integrator: Option<&str>,
        width: Option<i64>,
        height: Option<i64>,
        seed: Option<u64>,
        max_depth: Option<i64>,
        shadows: bool,
        aa: Option<&str>,
    ) -> PyResult<Bound<'py, PyList>> {
        let overrides = Overrides {
            width: count("width", width)?,
            height: count("height", height)?,
            spp: count("spp", spp)?,
            max_depth: count("max_depth", max_depth)?,
            seed,
            no_shadows: !shadows,
            ..named_overrides(integrator, None, aa)?
        };
        let (x, y, sample) = (
            count("x", Some(x))?.unwrap_or_default(),
            count("y", Some(y))?.unwrap_or_default(),
            count("sample", sample)?,
        );
        let file = self.with(&overrides)?;
        let loaded = build(py, &file)?;
        let samples = py
            .detach(|| explain_pixel(&loaded.scene, &loaded.settings, (x, y), sample))
            .map_err(|e| {
                let hint = match e {
                    ExplainError::NotWhitted(_) => " (pass integrator=\"whitted\")",
                    ExplainError::NotUniform => " (pass aa=\"uniform\")",
                    ExplainError::TooManySamples(_) => ": pick one with sample=K",
                    _ => "",
                };
                PyValueError::new_err(format!("{e}{hint}"))
            })?;
        let list = PyList::empty(py);
        for s in &samples {
            list.append(explain::sample(py, &loaded.scene, s)?)?;
        }
        Ok(list)
    }

    /// The frameless study (`lucent study frameless`) on this scene, which should move: a
    /// dict with `rows` (one per run), `refreshes` (every refresh, as the CLI's CSV) and
    /// `matching` (the rates at which frameless modes match double buffering's error).
    #[pyo3(signature = (*, samples_per_second=400_000.0, refresh=60.0, duration=6.0,
        warmup=None, rate_divisors=vec![2.0, 4.0, 8.0, 16.0, 32.0], seed=1, threads=0,
        integrator=None, width=None, height=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn frameless_study<'py>(
        &self,
        py: Python<'py>,
        samples_per_second: f64,
        refresh: f64,
        duration: f64,
        warmup: Option<f64>,
        rate_divisors: Vec<f64>,
        seed: u64,
        threads: usize,
        integrator: Option<&str>,
        width: Option<i64>,
        height: Option<i64>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        for (name, v) in [
            ("samples_per_second", samples_per_second),
            ("refresh", refresh),
            ("duration", duration),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "{name} must be a positive number, not {v}"
                )));
            }
        }
        if let Some(w) = warmup
            && !(w.is_finite() && w >= 0.0)
        {
            return Err(PyValueError::new_err(format!(
                "warmup must be zero or more seconds, not {w}"
            )));
        }
        if let Some(d) = rate_divisors.iter().find(|d| !(d.is_finite() && **d > 0.0)) {
            return Err(PyValueError::new_err(format!(
                "rate_divisors must be positive numbers, not {d}"
            )));
        }
        let overrides = Overrides {
            width: count("width", width)?,
            height: count("height", height)?,
            ..named_overrides(integrator, None, None)?
        };
        let file = self.with(&overrides)?;
        let loaded = build(py, &file)?;
        let chosen = loaded.settings.integrator;
        if chosen.is_stochastic() {
            return Err(PyValueError::new_err(format!(
                "the study compares every sample with an ideal image, so it needs a deterministic integrator: {} draws random numbers (pass integrator=\"whitted\" or \"raycast\")",
                chosen.name()
            )));
        }
        let scene = Arc::new(loaded.scene);
        if !scene.is_animated() {
            PyErr::warn(
                py,
                &py.get_type::<pyo3::exceptions::PyUserWarning>(),
                c"the scene does not move: every mode converges to the same picture (give objects or the camera a `motion`)",
                1,
            )?;
        }
        let settings = StudySettings {
            samples_per_second,
            refresh_hz: refresh,
            duration,
            warmup,
            rate_divisors,
            seed,
            ..StudySettings::default()
        };
        let step = 1.0 / (settings.refresh_hz * f64::from(settings.substeps));
        let tracer = SceneTracer::new(scene, chosen, loaded.settings.seed, step);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| PyException::new_err(format!("starting the threads: {e}")))?;
        let (report, interrupted) = run_polled(py, progress.as_ref(), |c| {
            pool.install(|| {
                run_study(&tracer, &settings, |done, total| {
                    (c.report)(done as u64, total as u64);
                    !c.cancel.load(Ordering::Relaxed)
                })
            })
        })?;
        study::report(py, &report, tracer.rays(), interrupted)
    }

    /// What the scene holds (counts, bounds) and the settings its file gives.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let loaded = build(py, &self.file)?;
        convert::info(py, &self.file, &loaded)
    }

    fn __repr__(&self) -> String {
        format!("lucent.Scene({:?})", self.file.path.display().to_string())
    }
}

/// The scene of `file`, built with the GIL released; its errors as `SceneError`s.
fn build(py: Python<'_>, file: &SceneFile) -> PyResult<Loaded> {
    py.detach(|| file.build())
        .map_err(|e| scene_error(py, &e, &file.text))
}

impl Scene {
    /// The scene file with `overrides` applied, as `render`'s keywords name them.
    fn with(&self, overrides: &Overrides) -> PyResult<SceneFile> {
        let mut file = self.file.clone();
        overrides
            .apply(&mut file, Spelling::Keywords)
            .map_err(PyValueError::new_err)?;
        Ok(file)
    }
}

/// Reads a scene file: lucent's TOML, Mitsuba XML, glTF/GLB, OBJ or PLY.
#[pyfunction]
fn load(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
    let file = py
        .detach(|| SceneFile::read(&path))
        .map_err(|e| scene_error(py, &e, ""))?;
    Ok(Scene { file })
}

/// A scene from text: `format` "toml" (lucent's format) or "mitsuba" (Mitsuba 3 XML);
/// relative file names in it start from `base_dir` (default: the current folder).
#[pyfunction]
#[pyo3(signature = (text, format="toml", base_dir=None))]
fn load_string(
    py: Python<'_>,
    text: String,
    format: &str,
    base_dir: Option<PathBuf>,
) -> PyResult<Scene> {
    let (label, base_dir) = (PathBuf::from("<string>"), base_dir.unwrap_or_default());
    let parsed = match format {
        "toml" => SceneFile::parse(label, base_dir, text.clone()),
        "mitsuba" | "xml" => py.detach(|| SceneFile::parse_mitsuba(label, base_dir, text.clone())),
        _ => {
            return Err(PyValueError::new_err(format!(
                "load_string reads format=\"toml\" or \"mitsuba\", not {format:?}: load glTF, OBJ and PLY from their files with lucent.load"
            )));
        }
    };
    let file = parsed.map_err(|e| scene_error(py, &e, &text))?;
    Ok(Scene { file })
}

/// A scene built from Python: a dict shaped like the TOML file (`{"camera": {...},
/// "sphere": [{...}, ...]}`), read as that TOML would be; relative file names in it start
/// from `base_dir` (default: the current folder).
#[pyfunction]
#[pyo3(signature = (scene, base_dir=None))]
fn load_dict(scene: &Bound<'_, PyDict>, base_dir: Option<PathBuf>) -> PyResult<Scene> {
    let py = scene.py();
    let text = dict_scene::toml_text(scene)?;
    let file = SceneFile::parse(
        PathBuf::from("<dict>"),
        base_dir.unwrap_or_default(),
        text.clone(),
    )
    .map_err(|e| scene_error(py, &e, &text))?;
    Ok(Scene { file })
}

/// The built-in default scene (Whitted's picture), as `lucent render` renders without a file.
#[pyfunction]
fn default_scene() -> Scene {
    Scene {
        file: SceneFile::default_scene(),
    }
}

/// The built-in moving scene `lucent study frameless` studies without a file.
#[pyfunction]
fn moving_scene() -> Scene {
    Scene {
        file: SceneFile::moving_scene(),
    }
}

/// Writes an H×W×3 float32 array of linear radiance as an image file, by its extension
/// (.png, .exr, .pfm), as `lucent render` writes its images.
#[pyfunction]
fn write(py: Python<'_>, pixels: PyReadonlyArray3<'_, f32>, path: PathBuf) -> PyResult<()> {
    let film = image::to_film(&pixels)?;
    let format = lucent_cli::output::ImageFormat::from_path(&path)
        .map_err(|e| PyValueError::new_err(format!("{e:#}")))?;
    py.detach(|| lucent_cli::output::write_image(&film, &path, format))
        .map_err(|e| PyOSError::new_err(format!("{e:#}")))
}

/// The PNG file's bytes of an H×W×3 float32 array of linear radiance (sRGB, 8 bits).
#[pyfunction]
fn png_bytes(py: Python<'_>, pixels: PyReadonlyArray3<'_, f32>) -> PyResult<Vec<u8>> {
    let film = image::to_film(&pixels)?;
    py.detach(|| image::png(&film))
        .map_err(|e| PyException::new_err(format!("{e:#}")))
}

/// An H×W×3 float32 array of linear radiance as its PNG file holds it: 8-bit sRGB, H×W×3.
#[pyfunction]
fn srgb8<'py>(
    py: Python<'py>,
    pixels: PyReadonlyArray3<'_, f32>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let film = image::to_film(&pixels)?;
    let (w, h) = (film.width() as usize, film.height() as usize);
    let bytes = py.detach(|| film.to_srgb8());
    let array = numpy::ndarray::Array3::from_shape_vec((h, w, 3), bytes)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(PyArray3::from_owned_array(py, array))
}

/// The integrator names `render(integrator=...)` takes.
#[pyfunction]
fn integrators() -> Vec<String> {
    use lucent_scene::desc::IntegratorName as I;
    [
        I::Raycast,
        I::Whitted,
        I::Path,
        I::Sppm,
        I::DebugNormals,
        I::DebugDepth,
        I::DebugAlbedo,
        I::DebugId,
        I::DebugBarycentrics,
        I::DebugCost,
    ]
    .into_iter()
    .map(name)
    .collect()
}

#[pymodule]
fn _lucent(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(load_string, m)?)?;
    m.add_function(wrap_pyfunction!(load_dict, m)?)?;
    m.add_function(wrap_pyfunction!(default_scene, m)?)?;
    m.add_function(wrap_pyfunction!(moving_scene, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(png_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(srgb8, m)?)?;
    m.add_function(wrap_pyfunction!(integrators, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
