//! Heterogeneous media in scene files: a `[[medium]]`'s `density` grid (a Mitsuba `.vol` file)
//! and its `bounds`; what it renders, and the errors for grids that lie or make no sense.

use glam::Vec3;
use lucent::render::{Hooks, render};
use lucent_scene::vol::{VolGrid, write_vol};
use lucent_scene::{LoadError, Loaded, SceneFile};
use std::path::{Path, PathBuf};

/// A 1-pixel camera looking down −z through the centre of a unit sphere, on a white background.
const VIEW: &str = "[image]\nwidth = 1\nheight = 1\nsamples = 4096\n\
[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 0.01\n\
[world]\nbackground = 1.0\n[render]\nintegrator = \"path\"\n\
[[material]]\nname = \"boundary\"\ntype = \"null\"\n\
[[object]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"boundary\"\ninterior = \"smoke\"\n";

struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("lucent-grids-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn load(dir: &Path, text: &str) -> Result<Loaded, LoadError> {
    SceneFile::parse(dir.join("grids.toml"), dir.to_path_buf(), text.to_string())?.build()
}

/// The one pixel of the scene in `text`.
fn pixel(dir: &Path, text: &str) -> [f32; 3] {
    let loaded = load(dir, text).unwrap();
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    film.pixel(0, 0).to_array()
}

/// A grid of `n` voxels along z over `bounds`, whose centres hold `a + b·z`.
fn ramp(n: usize, (lo, hi): (Vec3, Vec3), (a, b): (f32, f32)) -> VolGrid {
    let values = (0..n)
        .map(|k| a + b * (lo.z + (hi.z - lo.z) * (k as f32 + 0.5) / n as f32))
        .collect();
    VolGrid {
        res: [1, 1, n],
        channels: 1,
        values,
        bounds: (lo, hi),
    }
}

fn medium(keys: &str) -> String {
    format!("{VIEW}[[medium]]\nname = \"smoke\"\n{keys}\n")
}

#[test]
fn an_absorbing_grid_dims_by_its_optical_depth() {
    // Along the chord z ∈ [−1, 1] the density is 0.5 + 0.4·z (interpolation is exact between
    // voxel centres, which span it): optical depth 2·0.5 = 1, times σa.
    let dir = Dir::new("ramp");
    let (lo, hi) = (Vec3::splat(-1.5), Vec3::splat(1.5));
    std::fs::write(
        dir.0.join("ramp.vol"),
        write_vol(&ramp(6, (lo, hi), (0.5, 0.4))),
    )
    .unwrap();
    let sigma_a = [0.3f32, 0.9, 1.6];
    let from_file = medium("sigma_a = [0.3, 0.9, 1.6]\ndensity = \"ramp.vol\"");
    // The same grid placed by `bounds` (the file's box elsewhere).
    std::fs::write(
        dir.0.join("moved.vol"),
        write_vol(&VolGrid {
            bounds: (Vec3::ZERO, Vec3::ONE),
            ..ramp(6, (lo, hi), (0.5, 0.4))
        }),
    )
    .unwrap();
    let by_bounds = medium(
        "sigma_a = [0.3, 0.9, 1.6]\ndensity = \"moved.vol\"\nbounds = [[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]",
    );
    // Whitted's ray tracer integrates the grid by quadrature: no noise, a tighter bound.
    let whitted = from_file.replace("integrator = \"path\"", "integrator = \"whitted\"");
    let got = pixel(&dir.0, &whitted);
    for c in 0..3 {
        let want = (-sigma_a[c]).exp();
        assert!(
            (got[c] - want).abs() < 1e-3 * want,
            "Whitted, channel {c}: {} against {want}",
            got[c]
        );
    }
    for text in [from_file, by_bounds] {
        let got = pixel(&dir.0, &text);
        for c in 0..3 {
            let want = (-sigma_a[c]).exp();
            assert!(
                (got[c] - want).abs() < 0.02 * want,
                "channel {c}: {} against {want}",
                got[c]
            );
        }
    }
}

fn assert_error(dir: &Path, text: &str, place: &str, cause: &str) {
    let shown = load(dir, text)
        .expect_err("the scene should be refused")
        .to_string();
    assert!(shown.contains(place), "wrong place: `{shown}`, not {place}");
    assert!(
        shown.contains(cause),
        "`{shown}` does not mention `{cause}`"
    );
}

#[test]
fn grids_that_lie_or_make_no_sense_are_refused() {
    let dir = Dir::new("bad");
    let good = ramp(4, (Vec3::splat(-1.0), Vec3::ONE), (1.0, 0.0));
    let mut short = write_vol(&good);
    short.truncate(short.len() - 4);
    std::fs::write(dir.0.join("short.vol"), short).unwrap();
    let mut negative = good.clone();
    negative.values[2] = -1.0;
    std::fs::write(dir.0.join("negative.vol"), write_vol(&negative)).unwrap();
    let mut flat = good.clone();
    flat.bounds.1.x = -1.0;
    std::fs::write(dir.0.join("flat.vol"), write_vol(&flat)).unwrap();
    std::fs::write(dir.0.join("good.vol"), write_vol(&good)).unwrap();
    // VIEW is 21 lines; the medium's keys start on line 24.
    let d = &dir.0;
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"none.vol\""),
        "grids.toml:25:11",
        "No such file",
    );
    let short_file = d.join("short.vol").display().to_string();
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"short.vol\""),
        &short_file,
        "but 12 bytes follow",
    );
    let negative_file = d.join("negative.vol").display().to_string();
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"negative.vol\""),
        &negative_file,
        "voxel (0, 0, 2) holds -1",
    );
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"flat.vol\""),
        "grids.toml:25:11",
        "the grid file's box must have min < max",
    );
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"good.vol\"\nbounds = [[0, 0, 0], [1, 0, 1]]"),
        "grids.toml:26:10",
        "`bounds` must have min < max",
    );
    assert_error(
        d,
        &medium("sigma_t = 1\nalbedo_grid = \"good.vol\""),
        "grids.toml:25:15",
        "an `albedo_grid` needs a `density` grid",
    );
    let rgb = VolGrid {
        channels: 3,
        values: vec![0.5; 12],
        ..good.clone()
    };
    std::fs::write(dir.0.join("rgb.vol"), write_vol(&rgb)).unwrap();
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"rgb.vol\""),
        "grids.toml:25:11",
        "has 3 channels; a density grid has 1",
    );
    let mut bright = rgb.clone();
    bright.values[7] = 1.5;
    std::fs::write(dir.0.join("bright.vol"), write_vol(&bright)).unwrap();
    let bright_file = d.join("bright.vol").display().to_string();
    assert_error(
        d,
        &medium("sigma_t = 1\ndensity = \"good.vol\"\nalbedo_grid = \"bright.vol\""),
        &bright_file,
        "voxel (0, 0, 2) holds albedo 1.5",
    );
    assert_error(
        d,
        &medium("sigma_t = 1\nbounds = [[0, 0, 0], [1, 1, 1]]"),
        "grids.toml:22:1",
        "`bounds` places a `density` grid",
    );
}
