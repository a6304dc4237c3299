//! What the Mitsuba tests share: a folder per test, the Cornell box as Mitsuba publishes it,
//! positions in a text, error checks, and a small render.

use glam::{Mat4, Vec3};
use lucent::Rgb;
use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::desc::{IntegratorName, LightDesc, LightKind, MaterialDesc, ObjectDesc};
use lucent_scene::hash::Fingerprint;
use lucent_scene::mitsuba::import_mitsuba;
use lucent_scene::{Imported, LoadError, LoadOptions, Loaded, SceneFile, Spanned};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// A folder of its own for one test, removed when the test ends.
pub struct Dir(pub PathBuf);

impl Dir {
    pub fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("lucent-mitsuba-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Writes `text` to `name` (making its folders) and returns the path.
    pub fn write(&self, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
        let path = self.path(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Mitsuba 3's `mi.cornell_box()` (python/mitsuba/python/util.py) written as a scene file: the
/// same plugins, parameters and transforms, each `T.translate(t).rotate(a, θ).scale(s)` written
/// in document order (scale, then rotate, then translate).
pub const CBOX: &str = r#"<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="8"/>
    </integrator>
    <sensor type="perspective">
        <string name="fov_axis" value="smaller"/>
        <float name="near_clip" value="0.001"/>
        <float name="far_clip" value="100.0"/>
        <float name="focus_distance" value="1000"/>
        <float name="fov" value="39.3077"/>
        <transform name="to_world">
            <lookat origin="0, 0, 3.9" target="0, 0, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="64"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="256"/>
            <integer name="height" value="256"/>
            <rfilter type="gaussian"/>
            <string name="pixel_format" value="rgb"/>
            <string name="component_format" value="float32"/>
        </film>
    </sensor>

    <bsdf type="diffuse" id="white">
        <rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/>
    </bsdf>
    <bsdf type="diffuse" id="green">
        <rgb name="reflectance" value="0.105421, 0.37798, 0.076425"/>
    </bsdf>
    <bsdf type="diffuse" id="red">
        <rgb name="reflectance" value="0.570068, 0.0430135, 0.0443706"/>
    </bsdf>

    <shape type="rectangle" id="light">
        <transform name="to_world">
            <scale x="0.23" y="0.19" z="0.19"/>
            <rotate x="1" angle="90"/>
            <translate x="0" y="0.99" z="0.01"/>
        </transform>
        <ref id="white"/>
        <emitter type="area">
            <rgb name="radiance" value="18.387, 13.9873, 6.75357"/>
        </emitter>
    </shape>
    <shape type="rectangle" id="floor">
        <transform name="to_world">
            <rotate x="1" angle="-90"/>
            <translate y="-1"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="rectangle" id="ceiling">
        <transform name="to_world">
            <rotate x="1" angle="90"/>
            <translate y="1"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="rectangle" id="back">
        <transform name="to_world">
            <translate z="-1"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="rectangle" id="green-wall">
        <transform name="to_world">
            <rotate y="1" angle="-90"/>
            <translate x="1"/>
        </transform>
        <ref id="green"/>
    </shape>
    <shape type="rectangle" id="red-wall">
        <transform name="to_world">
            <rotate y="1" angle="90"/>
            <translate x="-1"/>
        </transform>
        <ref id="red"/>
    </shape>
    <shape type="cube" id="small-box">
        <transform name="to_world">
            <scale value="0.3"/>
            <rotate y="1" angle="-17"/>
            <translate x="0.335" y="-0.7" z="0.38"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="cube" id="large-box">
        <transform name="to_world">
            <scale x="0.3" y="0.61" z="0.3"/>
            <rotate y="1" angle="18.25"/>
            <translate x="-0.33" y="-0.4" z="-0.28"/>
        </transform>
        <ref id="white"/>
    </shape>
</scene>
"#;

/// The reflectances of the box's three BSDFs.
pub const WHITE: Rgb = Rgb::new(0.885809, 0.698859, 0.666422);
pub const GREEN: Rgb = Rgb::new(0.105421, 0.37798, 0.076425);
pub const RED: Rgb = Rgb::new(0.570068, 0.0430135, 0.0443706);

/// A unit square in two triangles, with one normal.
pub const QUAD_OBJ: &str =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
/// One triangle, in ASCII PLY.
pub const TRIANGLE_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

/// The scene `<scene version="3.0.0">…</scene>` around `body`.
pub fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")
}

pub fn open() -> LoadOptions {
    LoadOptions::default()
}

pub fn sandboxed() -> LoadOptions {
    LoadOptions {
        sandbox: true,
        ..LoadOptions::default()
    }
}

/// The import of the file at `path`.
pub fn import_with(path: &Path, options: &LoadOptions) -> Result<Imported, LoadError> {
    import_mitsuba(path, options, &mut Fingerprint::default())
}

pub fn import(path: &Path) -> Imported {
    import_with(path, &open()).unwrap_or_else(|e| panic!("{e}"))
}

/// The file read through the usual route (with its extension) and built.
pub fn load(path: &Path) -> (SceneFile, Loaded) {
    let file = SceneFile::read_with(path, &open()).unwrap_or_else(|e| panic!("{e}"));
    let loaded = file.build().unwrap_or_else(|e| panic!("{e}"));
    (file, loaded)
}

/// 1-based line and column (in characters) of the only occurrence of `needle` in `text`.
pub fn position(text: &str, needle: &str) -> (usize, usize) {
    assert_eq!(text.matches(needle).count(), 1, "`{needle}` is not unique");
    let offset = text.find(needle).unwrap();
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

/// 1-based line and column of the character just after the only occurrence of `needle` (the
/// start of an attribute's value, for a needle ending in `="`).
pub fn after(text: &str, needle: &str) -> (usize, usize) {
    let (line, column) = position(text, needle);
    let last_line = needle.rsplit('\n').next().unwrap();
    if needle.contains('\n') {
        (
            line + needle.matches('\n').count(),
            last_line.chars().count() + 1,
        )
    } else {
        (line, column + needle.chars().count())
    }
}

/// Asserts that `e` is about `file` at `at` and says `words`, and that its one line reads
/// `file:line:column: …`.
pub fn assert_error(e: &LoadError, file: &Path, at: (usize, usize), words: &str) {
    assert_eq!(e.file, file, "{e}");
    assert_eq!(e.position, Some(at), "{e}");
    assert!(e.message.contains(words), "`{words}` not in: {e}");
    let shown = e.to_string();
    let prefix = format!("{}:{}:{}: ", file.display(), at.0, at.1);
    assert!(shown.starts_with(&prefix), "{shown}");
    assert!(!shown.contains('\n'), "one line: {shown}");
}

/// The error of importing `path` (which must fail).
pub fn import_error(path: &Path, options: &LoadOptions) -> LoadError {
    match import_with(path, options) {
        Ok(_) => panic!("{} should not import", path.display()),
        Err(e) => e,
    }
}

/// A rendered image, row by row from the top.
pub struct Image {
    pub width: u32,
    pub pixels: Vec<Rgb>,
}

impl Image {
    pub fn at(&self, x: u32, y: u32) -> Rgb {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Every pixel of columns `xs` and rows `ys`.
    pub fn region(
        &self,
        xs: std::ops::RangeInclusive<u32>,
        ys: std::ops::RangeInclusive<u32>,
    ) -> Vec<(u32, u32, Rgb)> {
        ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
            .map(|(x, y)| (x, y, self.at(x, y)))
            .collect()
    }
}

/// `file` rendered at `size` × `size` pixels, one sample each (through the pixel's centre),
/// with `integrator`, on one thread.
pub fn render_small(file: &SceneFile, size: u32, integrator: IntegratorName) -> Image {
    let mut file = file.clone();
    file.desc.image.width = Spanned::new(0..0, size);
    file.desc.image.height = Spanned::new(0..0, size);
    file.desc.image.samples = Spanned::new(0..0, 1);
    file.desc.render.integrator = integrator;
    // One ray through each pixel's centre, nothing of its neighbours: the box filter.
    file.desc.render.filter = None;
    let loaded = file.build().unwrap_or_else(|e| panic!("{e}"));
    let settings = RenderSettings {
        threads: 1,
        ..loaded.settings
    };
    let cancel = AtomicBool::new(false);
    let hooks = Hooks {
        cancel: &cancel,
        progress: &|_, _| {},
        checkpoint: None,
    };
    let done = render(&loaded.scene, &settings, None, &hooks).unwrap();
    assert!(done.complete);
    let film = &done.film;
    let pixels = (0..size)
        .flat_map(|y| (0..size).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y))
        .collect();
    Image {
        width: size,
        pixels,
    }
}

/// Whether `a` and `b` agree to `tolerance` in every channel.
pub fn same_color(a: Rgb, b: Rgb, tolerance: f32) -> bool {
    (a.r - b.r).abs() <= tolerance
        && (a.g - b.g).abs() <= tolerance
        && (a.b - b.b).abs() <= tolerance
}

/// The imported objects, in document order.
pub fn objects(imported: &lucent_scene::Imported) -> Vec<&ObjectDesc> {
    imported.desc.objects.iter().map(|o| o.get_ref()).collect()
}

/// The imported material called `name`.
pub fn material<'a>(imported: &'a lucent_scene::Imported, name: &str) -> &'a MaterialDesc {
    imported
        .desc
        .materials
        .iter()
        .map(|m| m.get_ref())
        .find(|m| m.name.get_ref() == name)
        .unwrap_or_else(|| panic!("no material `{name}`"))
}

/// The object's placement.
pub fn transform(o: &ObjectDesc) -> Mat4 {
    o.transform
        .as_ref()
        .expect("a transform")
        .get_ref()
        .0
        .as_mat4()
}

/// Whether two points or vectors agree to 1e-5.
pub fn near(a: Vec3, b: Vec3) -> bool {
    a.abs_diff_eq(b, 1e-5)
}

/// The angle between two directions, in degrees.
pub fn angle(a: Vec3, b: Vec3) -> f32 {
    a.normalize()
        .dot(b.normalize())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// The imported light of kind `kind` (the first, if several).
pub fn light(imported: &lucent_scene::Imported, kind: LightKind) -> &LightDesc {
    imported
        .desc
        .lights
        .iter()
        .map(|l| l.get_ref())
        .find(|l| l.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?} light"))
}
