//! The command line: subcommands and their flags.

use clap::{Args, Parser, Subcommand, ValueEnum};
use lucent::accel::AccelKind;
use lucent::schedule::frameless::DisplayMode;
use lucent_scene::framing::{Axis, View};
use std::path::PathBuf;

/// lucent: a ray tracer for learning, teaching and using ray tracing.
#[derive(Debug, Parser)]
#[command(name = "lucent", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to an image (the built-in Whitted scene when none is given).
    Render(RenderArgs),
    /// Print what a scene holds: objects, triangles, lights, materials, bounds and memory.
    Info(InfoArgs),
    /// Print the ray tree of one pixel (Whitted): every ray, what it hit, its contribution.
    Explain(ExplainArgs),
    /// Render the lecture's concepts, one image each, with the commands that made them.
    Gallery(GalleryArgs),
    /// Combine the partial films of a sharded render into one image.
    Merge(MergeArgs),
    /// Write any scene lucent reads (OBJ, PLY, glTF, Mitsuba XML) as lucent's TOML.
    Convert(ConvertArgs),
    /// Measure every accelerator on the same rays: build time, memory, million rays per second.
    Bench(BenchArgs),
    /// Measure a claim of the literature in a simulation (see `lucent study frameless --help`).
    #[command(subcommand)]
    Study(StudyCommand),
    /// Open a window that shows the scene as it is traced (frameless, double-buffered or
    /// adaptive), with a camera to move; needs the `viewer` feature (on by default).
    View(ViewArgs),
}

/// `lucent study`'s studies.
#[derive(Debug, Subcommand)]
pub enum StudyCommand {
    /// Double buffering, frameless and adaptive frameless rendering at one sample rate: error
    /// against the ideal image over time, latency and stale pixels; and the sample rate at which
    /// each frameless mode matches double buffering's error.
    Frameless(FramelessStudyArgs),
}

/// `lucent study frameless`.
#[derive(Debug, Args)]
pub struct FramelessStudyArgs {
    /// Scene file with motion (`motion` keys); default: the built-in moving scene.
    pub scene: Option<PathBuf>,
    /// Settings that override the scene file's (the integrator must be deterministic).
    #[command(flatten)]
    pub overrides: Overrides,
    /// Samples every mode traces per second of simulated time.
    #[arg(long, default_value_t = 400_000.0, value_parser = positive_number)]
    pub samples_per_second: f64,
    /// Display refreshes per second.
    #[arg(long, default_value_t = 60.0, value_parser = positive_number)]
    pub refresh: f64,
    /// Seconds of scene time measured.
    #[arg(long, default_value_t = 6.0, value_parser = positive_seconds)]
    pub duration: f64,
    /// Seconds simulated before measuring, from an exact first picture. Default: long enough
    /// for the slowest run to sample every pixel twice (at least 2 s).
    #[arg(long, value_parser = non_negative_seconds)]
    pub warmup: Option<f64>,
    /// Lower rates tried for the frameless modes: the full rate divided by each of these.
    #[arg(long, value_delimiter = ',', default_value = "2,4,8,16,32", value_parser = positive_number)]
    pub rate_divisors: Vec<f64>,
    /// Seed of the sample orders and of the instants of change.
    #[arg(long, default_value_t = 1)]
    pub study_seed: u64,
    /// Threads tracing the samples; 0 uses every core (the figures do not depend on it).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u16).range(0..=1024))]
    pub threads: u16,
    /// Where to write every refresh of every run (mode, samples_per_second, time_s, rmse,
    /// stale_fraction).
    #[arg(long, default_value = "frameless-study.csv")]
    pub csv: PathBuf,
    /// Where to write the plot (SVG): error over time per mode, and error against sample rate.
    #[arg(long, default_value = "frameless-study.svg")]
    pub plot: PathBuf,
    /// Also write what each mode shows at this instant (and the ideal image) as PNGs in
    /// --frames-dir.
    #[arg(long, value_name = "SECONDS", requires = "frames_dir")]
    pub frames_at: Option<f64>,
    /// Folder of the --frames-at pictures (created if missing).
    #[arg(long, value_name = "DIR")]
    pub frames_dir: Option<PathBuf>,
}

/// Integrators selectable on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorArg {
    /// Ray casting: the flat diffuse colour of the visible surface.
    Raycast,
    /// Whitted ray tracing: shadows, reflection, refraction.
    Whitted,
    /// Path tracing: global illumination, area and environment lights, soft shadows.
    Path,
    /// Stochastic progressive photon mapping: caustics, even from point lights.
    Sppm,
    /// Debug view: shading normals as colours.
    #[value(name = "debug:normals")]
    DebugNormals,
    /// Debug view: distance along the camera ray.
    #[value(name = "debug:depth")]
    DebugDepth,
    /// Debug view: diffuse colour.
    #[value(name = "debug:albedo")]
    DebugAlbedo,
    /// Debug view: a colour per object.
    #[value(name = "debug:id")]
    DebugId,
    /// Debug view: triangle barycentric weights.
    #[value(name = "debug:barycentrics")]
    DebugBarycentrics,
    /// Debug view: accelerator work per camera ray (heat map).
    #[value(name = "debug:cost")]
    DebugCost,
}

impl IntegratorArg {
    /// The name on the command line.
    pub fn name(self) -> String {
        use clap::ValueEnum;
        self.to_possible_value()
            .map(|v| v.get_name().to_string())
            .unwrap_or_default()
    }
}

/// How pixels are sampled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AaArg {
    /// `--spp` stratified, jittered samples per pixel.
    Uniform,
    /// Whitted's adaptive supersampling: rays at pixel corners, split where they differ.
    Adaptive,
    /// A quadtree over the screen: one corner per block of pixels, blocks split where their
    /// corners differ, down to pixels and below as `adaptive` does.
    Quadtree,
}

/// Ray–triangle tests selectable on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TriangleTestArg {
    /// Woop, Benthin & Wald 2013 (default).
    Watertight,
    /// The lecture notes' plane-and-barycentrics method.
    Projection,
}

/// Settings of the command line that override the scene file's.
#[derive(Clone, Debug, Default, PartialEq, Args)]
pub struct Overrides {
    /// Image width in pixels (overrides the scene file).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub width: Option<u32>,
    /// Image height in pixels (overrides the scene file).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub height: Option<u32>,
    /// Samples per pixel (overrides the scene file).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_048_576))]
    pub spp: Option<u32>,
    /// Integrator (overrides the scene file).
    #[arg(long, value_enum)]
    pub integrator: Option<IntegratorArg>,
    /// Deepest reflection/refraction bounce (overrides the scene file).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=1000))]
    pub max_depth: Option<u32>,
    /// Seed of the random sample positions (overrides the scene file).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Acceleration structure (overrides the scene file).
    #[arg(long)]
    pub accel: Option<AccelKind>,
    /// Ray–triangle test (overrides the scene file).
    #[arg(long, value_enum)]
    pub triangle_test: Option<TriangleTestArg>,
    /// Refuse files named by the scene outside its folder (absolute paths, `..`): for scenes
    /// from untrusted sources.
    #[arg(long)]
    pub sandbox: bool,
    /// Raise (or lower) one of the scene's budgets, checked before the work they bound:
    /// `xml` (MiB of Mitsuba XML, includes counted each time; default 16), `objects` (default
    /// 100000), `geometry` (vertices plus triangles stored; default 134217728) or `film` (MiB of
    /// a partial film or checkpoint; default 1024). Repeat for several.
    #[arg(long = "limit", value_name = "NAME=VALUE", value_parser = limit_spec)]
    pub limits: Vec<String>,
    /// Whitted without shadow rays: every light reaches every point that faces it.
    #[arg(long)]
    pub no_shadows: bool,
    /// Anti-aliasing: `uniform` (--spp samples per pixel), `adaptive` (Whitted's corners) or
    /// `quadtree` (corners of blocks of pixels first).
    #[arg(long, value_enum)]
    pub aa: Option<AaArg>,
    /// Adaptive: split a pixel (or sub-pixel) whose corners' display values differ by at least
    /// this much in a channel, 0 to 1 (0 splits everything). Default 0.1.
    #[arg(long, value_parser = threshold)]
    pub aa_threshold: Option<f32>,
    /// Adaptive: how many times a pixel may be halved, 0 to 8. Default 3.
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=8))]
    pub aa_depth: Option<u32>,
    /// Quadtree: the starting blocks are 2^K pixels a side, K from 1 to 4. Default 3 (8×8).
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=4))]
    pub aa_block: Option<u32>,
    /// Reconstruction filter (overrides the scene file): `box` (one pixel, the default),
    /// `tent`, `gaussian` (σ 0.5, radius 2) or `mitchell`.
    #[arg(long, value_enum)]
    pub filter: Option<FilterArg>,
    /// How a filter other than the box weighs samples: `splat` (into every pixel it reaches,
    /// the default: less noise) or `importance` (into their own pixel; shards need it).
    #[arg(long, value_enum)]
    pub filter_sampling: Option<FilterSamplingArg>,
    /// Stop after this many seconds (uniform sampling); without --spp the samples are then
    /// unbounded, with it whichever comes first ends the render.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub time_limit: Option<f64>,
    /// The instant of a moving scene to render, in seconds (default 0). The image is that
    /// instant alone: there is no shutter, so nothing is motion-blurred.
    #[arg(long, value_name = "SECONDS", value_parser = instant)]
    pub time: Option<f64>,
    /// How a scene without a camera is framed.
    #[command(flatten)]
    pub framing: FramingArgs,
}

/// How a scene without a camera of its own (a bare mesh file) is framed: `--up` and `--view`.
/// A scene with a camera keeps it, with a warning that they are ignored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Args)]
pub struct FramingArgs {
    /// The model's up axis, for the camera that frames a scene without one (`+x`, `+y` and
    /// `+z` are taken too). Default: guessed for OBJ and PLY files (a note says what and why),
    /// +y for glTF and Mitsuba files.
    #[arg(long, value_name = "AXIS", allow_hyphen_values = true, ignore_case = true,
          value_parser = axis_parser())]
    pub up: Option<Axis>,
    /// Where that camera looks from: `front` (the default; a little above), `side` (from the
    /// model's right), `top` (down the up axis, the model's front at the image's bottom) or
    /// `iso` (from the front right, 35° above).
    #[arg(long, ignore_case = true, value_parser = view_parser())]
    pub view: Option<View>,
}

/// An up axis by name (`x` … `-z`, `+x` too).
fn axis_parser() -> impl clap::builder::TypedValueParser<Value = Axis> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    let values = Axis::ALL.map(|a| {
        let value = PossibleValue::new(a.name());
        match a.signed_name() {
            signed if signed.starts_with('+') => value.alias(signed),
            _ => value,
        }
    });
    PossibleValuesParser::new(values).map(|s| s.parse().expect("a listed axis"))
}

/// A view by name.
fn view_parser() -> impl clap::builder::TypedValueParser<Value = View> {
    use clap::builder::{PossibleValuesParser, TypedValueParser};
    PossibleValuesParser::new(View::ALL.map(View::name)).map(|s| s.parse().expect("a listed view"))
}

/// A finite number of seconds, negative allowed (motions run both ways in time).
fn instant(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("expected a number of seconds, got `{s}`")),
    }
}

/// A switch on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OnOff {
    /// Enabled.
    On,
    /// Disabled.
    Off,
}

/// How filters weigh samples, on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FilterSamplingArg {
    /// Into every pixel the filter reaches.
    Splat,
    /// Into their own pixel, placed in proportion to the filter.
    Importance,
}

/// Reconstruction filters selectable on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FilterArg {
    /// One pixel, every sample weighted alike.
    Box,
    /// A tent of radius 1.
    Tent,
    /// A Gaussian of σ 0.5, radius 2 (Mitsuba's default).
    Gaussian,
    /// Mitchell–Netravali, B = C = 1/3, radius 2.
    Mitchell,
}

/// A `--limit` value, checked: `NAME=VALUE` with a budget's name and a positive number.
fn limit_spec(s: &str) -> Result<String, String> {
    lucent_scene::Limits::default().set(s)?;
    Ok(s.trim().to_string())
}

/// The budgets `specs` (checked `--limit` values) set, over the defaults.
pub fn limits_of(specs: &[String]) -> lucent_scene::Limits {
    let mut limits = lucent_scene::Limits::default();
    for s in specs {
        limits.set(s).expect("checked when parsed");
    }
    limits
}

fn threshold(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v >= 0.0 => Ok(v),
        _ => Err(format!("`{s}` is not a number ≥ 0")),
    }
}

/// `lucent render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file: lucent's TOML, or OBJ, PLY, glTF (.gltf, .glb) or Mitsuba 3 XML; the
    /// built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// Settings that override the scene file's.
    #[command(flatten)]
    pub overrides: Overrides,
    /// Output image: .png (sRGB, 8 bit), .pfm or .exr (linear float); a shard's output is a
    /// partial film (.exr) for `lucent merge`. Default: render.png.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Render threads; 0 uses every core.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u16).range(0..=1024))]
    pub threads: u16,
    /// Trace each tile's camera rays as one beam (pinhole cameras; under Whitted in packets of
    /// eight, with shadow beams towards point lights): `on` (the default, faster) or `off`
    /// (every ray from the root of the accelerators). The image is the same.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub beam: OnOff,
    /// Trace the path tracer's samples eight at a time, shading the materials that lanes know
    /// in SIMD lanes: `on` (the default, faster) or `off` (one path at a time). The image is
    /// the same.
    #[arg(long, value_enum, default_value_t = OnOff::On)]
    pub lanes: OnOff,
    /// Render only shard I of N (tiles I, I+N, I+2N, …), as `I/N`; `auto/N` takes I from
    /// $SLURM_ARRAY_TASK_ID or $JOB_COMPLETION_INDEX.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Where to write the checkpoint on Ctrl-C or SIGTERM (and every --checkpoint-every
    /// seconds): an OpenEXR film. Default: the output's name with `.checkpoint` added.
    #[arg(long)]
    pub checkpoint: Option<PathBuf>,
    /// Also write the checkpoint every this many seconds, for crash safety.
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub checkpoint_every: Option<f64>,
    /// Continue a stopped render from its checkpoint, to the samples it asked for; the scene
    /// and settings come from the checkpoint.
    #[arg(long, value_name = "CHECKPOINT")]
    pub resume: Option<PathBuf>,
    /// With `--aa adaptive`: also write where the samples went, as a grey PNG (black: the 4
    /// corners of an unsplit pixel; white: split to the depth limit).
    #[arg(long, value_name = "PNG")]
    pub density_map: Option<PathBuf>,
}

/// `lucent view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Scene file (as `render` takes); the built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// How the screen is made from the samples: `frameless` (each sample shown at once),
    /// `double-buffer` (whole frames) or `adaptive`.
    #[arg(long, default_value = "frameless", value_parser = mode_parser())]
    pub mode: DisplayMode,
    /// Render threads; 0 uses every core.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u16).range(0..=1024))]
    pub threads: u16,
    /// Window pixels per rendered pixel, a side: 2 traces a quarter of the window's pixels.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub scale: u32,
    /// The window's starting size, as WIDTHxHEIGHT; default: the scene's image size.
    #[arg(long, value_parser = size)]
    pub size: Option<(u32, u32)>,
    /// Redraws per second.
    #[arg(long, default_value_t = 60.0, value_parser = refresh)]
    pub refresh: f64,
    /// Close by itself after this many seconds, printing the samples per second (for
    /// measurements and tests).
    #[arg(long, value_name = "SECONDS", value_parser = positive_seconds)]
    pub exit_after: Option<f64>,
    /// Integrator (overrides the scene file).
    #[arg(long, value_enum)]
    pub integrator: Option<IntegratorArg>,
    /// Deepest reflection/refraction bounce (overrides the scene file).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=1000))]
    pub max_depth: Option<u32>,
    /// Seed of the sample order and the samples (overrides the scene file).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Acceleration structure (overrides the scene file).
    #[arg(long)]
    pub accel: Option<AccelKind>,
    /// Refuse files named by the scene outside its folder.
    #[arg(long)]
    pub sandbox: bool,
    /// Raise (or lower) one of the scene's budgets, checked before the work they bound:
    /// `xml` (MiB of Mitsuba XML, includes counted each time; default 16), `objects` (default
    /// 100000), `geometry` (vertices plus triangles stored; default 134217728) or `film` (MiB of
    /// a partial film or checkpoint; default 1024). Repeat for several.
    #[arg(long = "limit", value_name = "NAME=VALUE", value_parser = limit_spec)]
    pub limits: Vec<String>,
    /// How a scene without a camera is framed.
    #[command(flatten)]
    pub framing: FramingArgs,
}

impl ViewArgs {
    /// The scene settings this command overrides, as `render` takes them.
    #[cfg_attr(not(feature = "viewer"), allow(dead_code))] // no scene is loaded without a viewer
    pub fn overrides(&self) -> Overrides {
        Overrides {
            integrator: self.integrator,
            max_depth: self.max_depth,
            seed: self.seed,
            accel: self.accel,
            sandbox: self.sandbox,
            limits: self.limits.clone(),
            framing: self.framing,
            ..Overrides::default()
        }
    }
}

/// A display mode by its library name (`double-buffer`, `frameless`, `adaptive`).
fn mode_parser() -> impl clap::builder::TypedValueParser<Value = DisplayMode> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(DisplayMode::ALL.map(DisplayMode::name))
        .map(|s| s.parse().expect("a listed mode"))
}

/// Redraws per second, 1 to 1000.
fn refresh(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (1.0..=1000.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "expected redraws per second from 1 to 1000, got `{s}`"
        )),
    }
}

/// `lucent merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Partial films written by `lucent render --shard I/N -o PART.exr`, one per shard.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The merged image: .png, .pfm or .exr.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Raise (or lower) the `film` budget: MiB of pixel data a partial film may hold
    /// (default 1024), checked from its header before its pixels are read.
    #[arg(long = "limit", value_name = "film=MIB", value_parser = limit_spec)]
    pub limits: Vec<String>,
}

/// `lucent convert`.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The scene to convert: .toml, .obj, .ply, .gltf, .glb or Mitsuba .xml.
    pub input: PathBuf,
    /// The TOML scene to write; mesh and image files stay where they are, named from its folder.
    pub output: PathBuf,
    /// Refuse files named by the scene outside its folder.
    #[arg(long)]
    pub sandbox: bool,
    /// Raise (or lower) one of the scene's budgets, checked before the work they bound:
    /// `xml` (MiB of Mitsuba XML, includes counted each time; default 16), `objects` (default
    /// 100000), `geometry` (vertices plus triangles stored; default 134217728) or `film` (MiB of
    /// a partial film or checkpoint; default 1024). Repeat for several.
    #[arg(long = "limit", value_name = "NAME=VALUE", value_parser = limit_spec)]
    pub limits: Vec<String>,
    /// How a scene without a camera is framed (the framing camera is written out).
    #[command(flatten)]
    pub framing: FramingArgs,
}

/// `lucent gallery`.
#[derive(Debug, Args)]
pub struct GalleryArgs {
    /// The folder to write the images, their scenes and gallery.md into.
    pub output: PathBuf,
    /// Image width in pixels.
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 600, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub height: u32,
}

/// `lucent explain`.
#[derive(Debug, Args)]
pub struct ExplainArgs {
    /// Scene file; the built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// The pixel, as X,Y (column and row from the top left, from 0).
    #[arg(long, value_name = "X,Y", value_parser = pixel)]
    pub pixel: (u32, u32),
    /// Also draw the tree as an SVG diagram here.
    #[arg(long, value_name = "FILE.svg")]
    pub svg: Option<PathBuf>,
    /// Only this sample of the pixel (from 0); all of them (at most 64) when omitted.
    #[arg(long, value_name = "K")]
    pub sample: Option<u32>,
    /// Settings that override the scene file's.
    #[command(flatten)]
    pub overrides: Overrides,
}

/// `X,Y` pixel coordinates.
fn pixel(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected X,Y such as 400,300, got `{s}`");
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    Ok((
        x.trim().parse().map_err(|_| bad())?,
        y.trim().parse().map_err(|_| bad())?,
    ))
}

/// `lucent info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Scene file (TOML, OBJ, PLY, glTF or Mitsuba XML); the built-in default scene when
    /// omitted.
    pub scene: Option<PathBuf>,
    /// Settings that override the scene file's.
    #[command(flatten)]
    pub overrides: Overrides,
}

/// `lucent bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Scene files (TOML) or OBJ meshes; default: examples/*.toml and the shared meshes.
    pub scenes: Vec<PathBuf>,
    /// Accelerators to measure, comma-separated; default: all.
    #[arg(long, value_delimiter = ',')]
    pub accel: Vec<AccelKind>,
    /// Thread counts to measure, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Vec<u16>,
    /// Incoherent and occlusion rays per set (camera rays: 1024×1024).
    #[arg(long, default_value_t = 1 << 20)]
    pub rays: usize,
    /// Seed of the random rays.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Also write the results as CSV here.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Also write the results as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Instead of the accelerators: adaptive against uniform supersampling at equal image
    /// error, on the first scene given (default: the built-in one), on the most threads given.
    #[arg(long)]
    pub sampling: bool,
    /// Image size of `--sampling`, as WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600", value_parser = size)]
    pub size: (u32, u32),
}

/// `WIDTHxHEIGHT`, each 1 to 65536.
fn size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected WIDTHxHEIGHT such as 800x600, got `{s}`");
    let (w, h) = s.split_once('x').ok_or_else(bad)?;
    let side = |v: &str| v.parse::<u32>().ok().filter(|v| (1..=65536).contains(v));
    Ok((side(w).ok_or_else(bad)?, side(h).ok_or_else(bad)?))
}

/// A positive, finite number.
fn positive_number(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err(format!("expected a positive number, got `{s}`")),
    }
}

/// A number of seconds from 0 to a year.
fn non_negative_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v >= 0.0 && v <= f64::from(lucent_scene::build::MAX_TIME_LIMIT) => Ok(v),
        _ => Err(format!(
            "expected a number of seconds from 0 to a year, got `{s}`"
        )),
    }
}

/// A positive, finite number of seconds (at most a year).
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v <= f64::from(lucent_scene::build::MAX_TIME_LIMIT) => Ok(v),
        _ => Err(format!(
            "expected a positive number of seconds (at most a year), got `{s}`"
        )),
    }
}
