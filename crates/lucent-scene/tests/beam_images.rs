//! Beam tracing of camera rays changes no pixel: every example scene, rendered small with
//! beams on and off, gives the same film bit for bit (stochastic integrators too, since the
//! sampler is a pure function of pixel and sample).

mod common;

use common::examples;
use lucent::film::Film;
use lucent::film::filter::Filter;
use lucent::film::splat::FilterSampling;
use lucent::integrator::{Integrator, Whitted};
use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadOptions, SceneFile, Spanned};

fn film(scene: &lucent::scene::Scene, settings: &RenderSettings, beam: bool) -> Film {
    let hooks = Hooks::none();
    let settings = RenderSettings {
        beam,
        threads: 2,
        // Small tiles: more beams, more edges between them.
        tile_size: 8,
        ..*settings
    };
    render(scene, &settings, None, &hooks).unwrap().film
}

/// An example scene file at `width`×`height`.
fn small(path: &std::path::Path, width: u32, height: u32) -> SceneFile {
    let mut file = SceneFile::read_with(path, &LoadOptions::default()).unwrap();
    file.desc.image.width = Spanned::new(0..0, width);
    file.desc.image.height = Spanned::new(0..0, height);
    file
}

/// Renders with beams on and off and holds the two films to be the same.
fn assert_beams_change_nothing(
    scene: &lucent::scene::Scene,
    settings: &RenderSettings,
    what: &str,
) {
    let on = film(scene, settings, true);
    let off = film(scene, settings, false);
    assert_same(&on, &off, what);
}

fn assert_same(a: &Film, b: &Film, what: &str) {
    let (w, h) = (a.width(), a.height());
    for y in 0..h {
        for x in 0..w {
            let (p, q) = (a.pixel(x, y).to_array(), b.pixel(x, y).to_array());
            assert_eq!(
                p.map(f32::to_bits),
                q.map(f32::to_bits),
                "{what}: pixel ({x}, {y}) differs with beams: {p:?} vs {q:?}"
            );
            assert_eq!(a.samples(x, y), b.samples(x, y));
        }
    }
}

#[test]
fn every_example_renders_the_same_with_and_without_beams() {
    for path in examples() {
        let mut file = small(&path, 56, 40);
        let spp = (*file.desc.image.samples.get_ref()).min(2);
        file.desc.image.samples = Spanned::new(0..0, spp);
        let loaded = file.build().unwrap();
        assert_beams_change_nothing(&loaded.scene, &loaded.settings, &path.display().to_string());
    }
}

#[test]
fn every_example_renders_the_same_under_whitted_with_and_without_beams() {
    // Under Whitted a beam also brings packets of camera rays and shadow beams towards point
    // lights (transmissive blockers traced again from the roots): every example, whatever
    // its own integrator.
    // Over the wide BVH (packed meshes, cuts, packets) and the binary one (none of those).
    for (path, accel) in examples()
        .into_iter()
        .flat_map(|p| ["wide", "bvh"].map(|a| (p.clone(), a)))
    {
        let mut file = small(&path, 61, 40);
        file.desc.render.accelerator = Spanned::new(0..0, accel.to_string());
        let loaded = file.build().unwrap();
        let settings = RenderSettings {
            integrator: Integrator::Whitted(Whitted::default()),
            spp: 2,
            ..loaded.settings
        };
        let name = format!("{} ({accel})", path.display());
        assert_beams_change_nothing(&loaded.scene, &settings, &name);
    }
}

#[test]
fn wide_filters_and_jittered_samples_render_the_same_with_beams() {
    let mut file = SceneFile::default_scene();
    file.desc.image.width = Spanned::new(0..0, 80);
    file.desc.image.height = Spanned::new(0..0, 60);
    let loaded = file.build().unwrap();
    for filter_sampling in [FilterSampling::Importance, FilterSampling::Splat] {
        let settings = RenderSettings {
            spp: 3,
            filter: Filter::default_of("gaussian").unwrap(),
            filter_sampling,
            ..loaded.settings
        };
        assert_beams_change_nothing(&loaded.scene, &settings, &format!("{filter_sampling:?}"));
    }
}

#[test]
fn adaptive_and_quadtree_sampling_render_the_same_with_beams() {
    // Corner rays (pixel corners, sub-pixel corners, the corners of neighbouring pixels and of
    // quadtree blocks) through each tile's beam: every example under Whitted, at a depth and
    // threshold that split often, from pixels and from 4×4 blocks.
    use lucent::render::Sampling;
    use lucent::schedule::adaptive::Adaptive;
    for path in examples() {
        let loaded = small(&path, 45, 34).build().unwrap();
        for block in [0, 2] {
            let settings = RenderSettings {
                integrator: Integrator::Whitted(Whitted::default()),
                sampling: Sampling::Adaptive(Adaptive {
                    threshold: 0.02,
                    depth: 2,
                    block,
                }),
                ..loaded.settings
            };
            let name = format!("{} (adaptive, blocks of {})", path.display(), 1 << block);
            assert_beams_change_nothing(&loaded.scene, &settings, &name);
        }
    }
}
