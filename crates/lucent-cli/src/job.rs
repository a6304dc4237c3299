//! A render job: the scene, the command line's overrides, and the fingerprint that tells
//! whether two renders (shards, a checkpoint and its resumption) draw the same image.

use crate::cli::{
    AaArg, FilterArg, FilterSamplingArg, FramingArgs, IntegratorArg, Overrides, TriangleTestArg,
};
use anyhow::{anyhow, bail};
use lucent_scene::desc::IntegratorName;
use lucent_scene::desc::settings::{
    FilterName, FilterSamplingName, SamplingName, TriangleTestName,
};
use lucent_scene::framing::{Axis, Framing};
use lucent_scene::hash::Fingerprint;
use lucent_scene::{LoadOptions, Loaded, SceneFile};
use std::path::{Path, PathBuf};

/// A scene loaded with the command line's settings applied.
pub struct Job {
    /// The scene file as given (`None`: the built-in default scene).
    pub scene_path: Option<PathBuf>,
    /// The settings given on the command line.
    pub overrides: Overrides,
    /// The built scene and its render settings.
    pub loaded: Loaded,
    /// Wall time of reading and building the scene (accelerators included).
    pub load_time: std::time::Duration,
    /// The camera as the file gives it (or the one framing a scene without one): the viewer
    /// rebuilds it at the window's size.
    #[cfg_attr(not(feature = "viewer"), allow(dead_code))]
    pub camera: lucent_scene::desc::CameraDesc,
    /// How the camera frames a scene without one (`None`: the scene's own camera).
    pub framing: Option<Framing>,
}

impl Job {
    /// Reads and builds the scene at `scene` (or the built-in one) with `overrides` applied.
    pub fn load(scene: Option<&Path>, overrides: &Overrides) -> anyhow::Result<Self> {
        let start = std::time::Instant::now();
        let options = LoadOptions {
            sandbox: overrides.sandbox,
            limits: crate::cli::limits_of(&overrides.limits),
            // A POV-Ray scene's `image_width` and `image_height`.
            image_size: overrides.width.zip(overrides.height),
        };
        let file = match scene {
            Some(p) => SceneFile::read_with(p, &options)?,
            None => SceneFile::default_scene(),
        };
        Self::from_file(file, scene, overrides, start)
    }

    /// The built-in moving scene (of `lucent study frameless`) with `overrides` applied.
    pub fn load_moving(overrides: &Overrides) -> anyhow::Result<Self> {
        let start = std::time::Instant::now();
        Self::from_file(SceneFile::moving_scene(), None, overrides, start)
    }

    fn from_file(
        mut file: SceneFile,
        scene: Option<&Path>,
        overrides: &Overrides,
        start: std::time::Instant,
    ) -> anyhow::Result<Self> {
        apply(&mut file, overrides)?;
        let framing_warning = frame(&mut file, &overrides.framing);
        let mut loaded = file.build()?;
        if let Some(t) = overrides.time {
            if loaded.scene.is_animated() {
                loaded.scene = loaded.scene.at_time(t);
            } else {
                loaded
                    .warnings
                    .push("--time has no effect: nothing in the scene moves".to_string());
            }
        }
        loaded.warnings.extend(framing_warning);
        for w in &loaded.warnings {
            eprintln!("warning: {w}");
        }
        let camera = if file.camera_given {
            file.desc.camera.get_ref().clone()
        } else {
            file.framing_camera(&loaded)
        };
        Ok(Self {
            scene_path: scene.map(Path::to_path_buf),
            overrides: overrides.clone(),
            loaded,
            load_time: start.elapsed(),
            camera,
            framing: (!file.camera_given).then(|| file.framing()),
        })
    }

    /// Hex fingerprint of the scene's inputs (scene text, mesh files) and of every setting that
    /// shapes the image: resolution, samples, seed, tile size (the unit of shards), integrator
    /// and triangle test — and lucent's version, since another build may draw other bits.
    /// Threads and the accelerator change nothing in the image, so they are left out. A
    /// framed scene adds its framing (its camera is in no file).
    pub fn fingerprint(&self) -> String {
        let s = &self.loaded.settings;
        let c = &self.loaded.scene.camera;
        let settings = format!(
            "lucent {} {}x{} spp={} seed={} tile={} {:?} {:?} {} {:?} {:?} t={}",
            env!("CARGO_PKG_VERSION"),
            c.width(),
            c.height(),
            s.spp,
            s.seed,
            s.tile_size,
            s.integrator,
            s.sampling,
            self.loaded.scene.triangle_test().name(),
            (s.filter, s.filter_sampling),
            c.lens(),
            self.overrides.time.unwrap_or(0.0).to_bits(),
        );
        let mut f = Fingerprint::default();
        f.add(&self.loaded.inputs.to_le_bytes());
        f.add(settings.as_bytes());
        if let Some(framing) = self.framing {
            f.add(format!("framing {} {}", framing.up, framing.view).as_bytes());
        }
        format!("{:016x}", f.value())
    }
}

/// Film bytes per pixel while rendering: radiance sums (12), weight (4), sample count (4).
const FILM_BYTES_PER_PIXEL: u64 = 20;
/// Bytes per pixel while a file is written, at most: a checkpoint holds a copy of the film (20),
/// its raw channels (20), the EXR encoder's copy of them (20) and its compressed blocks (up to
/// 20); an image needs less (a linear copy, 12, and its encoding, up to 12).
const FILE_BYTES_PER_PIXEL: u64 = 80;

/// The memory a render needs, in bytes.
#[derive(Clone, Copy, Debug)]
pub struct Memory {
    /// Geometry and accelerators (already allocated once the job is loaded).
    pub scene: u64,
    /// The film.
    pub film: u64,
    /// Writing an image or a checkpoint.
    pub files: u64,
}

impl Memory {
    /// All of it.
    pub fn total(&self) -> u64 {
        self.scene + self.film + self.files
    }
}

impl Job {
    /// The memory the render will need.
    pub fn memory(&self) -> Memory {
        let scene = &self.loaded.scene;
        let pixels = u64::from(scene.camera.width()) * u64::from(scene.camera.height());
        Memory {
            scene: (scene.accel_report().bytes + scene.geometry_bytes()) as u64,
            film: pixels * FILM_BYTES_PER_PIXEL,
            files: pixels * FILE_BYTES_PER_PIXEL,
        }
    }
}

/// The memory the system can still give, from /proc/meminfo (None elsewhere).
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Frames a scene without a camera as `--up` and `--view` ask, first printing (as a note) the
/// up axis guessed for a mesh file when `--up` does not give it. Returns the warning for a
/// scene with its own camera, which keeps it: a script that gives the flags for every file
/// still renders those that place their camera themselves.
pub fn frame(file: &mut SceneFile, args: &FramingArgs) -> Option<String> {
    if file.camera_given {
        return (args.up.is_some() || args.view.is_some()).then(|| {
            "--up and --view have no effect: the scene has its own camera (they frame scenes without one)"
                .to_string()
        });
    }
    if args.up.is_none()
        && let Some(guess) = file.up_guess()
    {
        let hint = if guess.up == Axis::Y {
            "--up to choose another"
        } else {
            "--up y to override"
        };
        eprintln!("note: {}: {guess}; {hint}", file.path.display());
    }
    file.set_framing(Framing {
        up: args.up.unwrap_or(file.framing().up),
        view: args.view.unwrap_or_default(),
    });
    None
}

/// The command line's overrides as the library's ([`lucent_scene::overrides`]).
fn scene_overrides(o: &Overrides) -> lucent_scene::overrides::Overrides {
    lucent_scene::overrides::Overrides {
        width: o.width,
        height: o.height,
        spp: o.spp,
        integrator: o.integrator.map(|i| match i {
            IntegratorArg::Raycast => IntegratorName::Raycast,
            IntegratorArg::Whitted => IntegratorName::Whitted,
            IntegratorArg::Path => IntegratorName::Path,
            IntegratorArg::Sppm => IntegratorName::Sppm,
            IntegratorArg::DebugNormals => IntegratorName::DebugNormals,
            IntegratorArg::DebugDepth => IntegratorName::DebugDepth,
            IntegratorArg::DebugAlbedo => IntegratorName::DebugAlbedo,
            IntegratorArg::DebugId => IntegratorName::DebugId,
            IntegratorArg::DebugBarycentrics => IntegratorName::DebugBarycentrics,
            IntegratorArg::DebugCost => IntegratorName::DebugCost,
        }),
        max_depth: o.max_depth,
        seed: o.seed,
        accel: o.accel,
        triangle_test: o.triangle_test.map(|t| match t {
            TriangleTestArg::Watertight => TriangleTestName::Watertight,
            TriangleTestArg::Projection => TriangleTestName::Projection,
        }),
        no_shadows: o.no_shadows,
        aa: o.aa.map(|a| match a {
            AaArg::Uniform => SamplingName::Uniform,
            AaArg::Adaptive => SamplingName::Adaptive,
            AaArg::Quadtree => SamplingName::Quadtree,
        }),
        aa_threshold: o.aa_threshold,
        aa_depth: o.aa_depth,
        aa_block: o.aa_block,
        filter: o.filter.map(|f| match f {
            FilterArg::Box => FilterName::Box,
            FilterArg::Tent => FilterName::Tent,
            FilterArg::Gaussian => FilterName::Gaussian,
            FilterArg::Mitchell => FilterName::Mitchell,
        }),
        filter_sampling: o.filter_sampling.map(|f| match f {
            FilterSamplingArg::Splat => FilterSamplingName::Splat,
            FilterSamplingArg::Importance => FilterSamplingName::Importance,
        }),
        time_limit: o.time_limit,
    }
}

fn apply(file: &mut SceneFile, o: &Overrides) -> anyhow::Result<()> {
    scene_overrides(o)
        .apply(file, lucent_scene::overrides::Spelling::Flags)
        .map_err(|e| anyhow!(e))
}

impl Overrides {
    /// The overrides as `key=value` pairs separated by `;` (for checkpoints).
    pub fn to_pairs(&self) -> String {
        let mut pairs = Vec::new();
        let mut put = |k: &str, v: Option<String>| {
            if let Some(v) = v {
                pairs.push(format!("{k}={v}"));
            }
        };
        put("width", self.width.map(|v| v.to_string()));
        put("height", self.height.map(|v| v.to_string()));
        put("spp", self.spp.map(|v| v.to_string()));
        put("integrator", self.integrator.map(IntegratorArg::name));
        put("max_depth", self.max_depth.map(|v| v.to_string()));
        put("seed", self.seed.map(|v| v.to_string()));
        put("accel", self.accel.map(|v| v.name().to_string()));
        put(
            "triangle_test",
            self.triangle_test.map(|v| format!("{v:?}").to_lowercase()),
        );
        put("sandbox", self.sandbox.then(|| "true".to_string()));
        put(
            "limits",
            (!self.limits.is_empty()).then(|| self.limits.join(",")),
        );
        put("no_shadows", self.no_shadows.then(|| "true".to_string()));
        put("aa", self.aa.map(|v| format!("{v:?}").to_lowercase()));
        // Bit patterns: the threshold comes back exactly.
        put(
            "aa_threshold",
            self.aa_threshold.map(|v| v.to_bits().to_string()),
        );
        put("aa_depth", self.aa_depth.map(|v| v.to_string()));
        put("aa_block", self.aa_block.map(|v| v.to_string()));
        put(
            "filter",
            self.filter.map(|v| format!("{v:?}").to_lowercase()),
        );
        put(
            "time_limit",
            self.time_limit.map(|v| v.to_bits().to_string()),
        );
        put("time", self.time.map(|v| v.to_bits().to_string()));
        put(
            "filter_sampling",
            self.filter_sampling
                .map(|v| format!("{v:?}").to_lowercase()),
        );
        put("up", self.framing.up.map(|v| v.name().to_string()));
        put("view", self.framing.view.map(|v| v.name().to_string()));
        pairs.join(";")
    }

    /// Reads what [`Overrides::to_pairs`] wrote.
    pub fn from_pairs(s: &str) -> anyhow::Result<Self> {
        let mut o = Overrides::default();
        for pair in s.split(';').filter(|p| !p.is_empty()) {
            let (k, v) = pair
                .split_once('=')
                .ok_or_else(|| anyhow!("a garbled setting `{pair}`"))?;
            let bad = || anyhow!("a garbled setting `{pair}`");
            match k {
                "width" => o.width = Some(v.parse().map_err(|_| bad())?),
                "height" => o.height = Some(v.parse().map_err(|_| bad())?),
                "spp" => o.spp = Some(v.parse().map_err(|_| bad())?),
                "integrator" => {
                    o.integrator = Some(
                        <IntegratorArg as clap::ValueEnum>::from_str(v, false)
                            .map_err(|_| bad())?,
                    )
                }
                "max_depth" => o.max_depth = Some(v.parse().map_err(|_| bad())?),
                "seed" => o.seed = Some(v.parse().map_err(|_| bad())?),
                "accel" => o.accel = Some(v.parse().map_err(|_| bad())?),
                "triangle_test" => {
                    o.triangle_test = Some(match v {
                        "watertight" => TriangleTestArg::Watertight,
                        "projection" => TriangleTestArg::Projection,
                        _ => return Err(bad()),
                    })
                }
                "sandbox" => o.sandbox = v == "true",
                "limits" => {
                    for spec in v.split(',') {
                        lucent_scene::Limits::default()
                            .set(spec)
                            .map_err(|_| bad())?;
                        o.limits.push(spec.to_string());
                    }
                }
                "no_shadows" => o.no_shadows = v == "true",
                "aa" => {
                    o.aa = Some(match v {
                        "uniform" => AaArg::Uniform,
                        "adaptive" => AaArg::Adaptive,
                        "quadtree" => AaArg::Quadtree,
                        _ => return Err(bad()),
                    })
                }
                "aa_threshold" => {
                    o.aa_threshold = Some(f32::from_bits(v.parse().map_err(|_| bad())?))
                }
                "aa_depth" => o.aa_depth = Some(v.parse().map_err(|_| bad())?),
                "aa_block" => o.aa_block = Some(v.parse().map_err(|_| bad())?),
                "filter" => {
                    o.filter = Some(
                        <FilterArg as clap::ValueEnum>::from_str(v, false).map_err(|_| bad())?,
                    )
                }
                "filter_sampling" => {
                    o.filter_sampling = Some(
                        <FilterSamplingArg as clap::ValueEnum>::from_str(v, false)
                            .map_err(|_| bad())?,
                    )
                }
                "time_limit" => o.time_limit = Some(f64::from_bits(v.parse().map_err(|_| bad())?)),
                "time" => o.time = Some(f64::from_bits(v.parse().map_err(|_| bad())?)),
                "up" => o.framing.up = Some(v.parse().map_err(|_| bad())?),
                "view" => o.framing.view = Some(v.parse().map_err(|_| bad())?),
                _ => bail!("an unknown setting `{k}`"),
            }
        }
        Ok(o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_round_trip() {
        let o = Overrides {
            width: Some(10),
            height: None,
            spp: Some(4),
            integrator: Some(IntegratorArg::DebugCost),
            max_depth: Some(2),
            seed: Some(u64::MAX),
            accel: Some(lucent::accel::AccelKind::Octree),
            triangle_test: Some(TriangleTestArg::Projection),
            sandbox: true,
            limits: vec!["xml=64".to_string(), "objects=500000".to_string()],
            no_shadows: true,
            aa: Some(AaArg::Quadtree),
            aa_threshold: Some(0.1),
            aa_depth: Some(4),
            aa_block: Some(2),
            filter: Some(FilterArg::Mitchell),
            filter_sampling: Some(FilterSamplingArg::Importance),
            time_limit: Some(2.5),
            time: Some(-1.25),
            framing: FramingArgs {
                up: Some(Axis::NegZ),
                view: Some(lucent_scene::framing::View::Iso),
            },
        };
        assert_eq!(Overrides::from_pairs(&o.to_pairs()).unwrap(), o);
        for up in Axis::ALL {
            let o = Overrides {
                framing: FramingArgs {
                    up: Some(up),
                    view: None,
                },
                ..Overrides::default()
            };
            assert_eq!(Overrides::from_pairs(&o.to_pairs()).unwrap(), o);
        }
        assert_eq!(Overrides::from_pairs("").unwrap(), Overrides::default());
        assert!(Overrides::from_pairs("width=x").is_err());
    }
}
