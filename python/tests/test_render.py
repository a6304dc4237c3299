"""Renders from Python against `lucent render`'s own files, bit for bit."""

import os
import pathlib
import time

import numpy as np
import pytest

import lucent
from conftest import EXAMPLES, ROOT, cli_render, read_pfm

SHARED = ROOT.parent / "shared" / "data"
SCENES = sorted(p for p in EXAMPLES.iterdir() if p.suffix in (".toml", ".xml"))


def needs_shared(scene: pathlib.Path) -> bool:
    return "shared/data" in scene.read_text()


def can_render(scene: pathlib.Path) -> bool:
    """Whether the meshes `scene` reads are here (the shared data sits beside the checkout)."""
    return not needs_shared(scene) or SHARED.is_dir() or bool(os.environ.get("LUCENT_DATA"))


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_every_example_equals_the_commands_pfm(scene, lucent_bin, tmp_path):
    if not can_render(scene):
        pytest.skip(f"{scene.name} reads the shared meshes, not beside this checkout")
    small = dict(width=40, height=30)
    img = lucent.load(scene).render(**small, progress=False)
    want = cli_render(lucent_bin, scene, tmp_path / "cli.pfm", "--width", "40", "--height", "30")
    assert img.shape == (30, 40, 3) and img.dtype == np.float32
    assert np.array_equal(np.asarray(img), want), f"{scene.name}: Python and the command differ"


def test_overrides_match_the_commands_flags(lucent_bin, tmp_path):
    scene = EXAMPLES / "cornell-glass.toml"
    img = lucent.load(scene).render(
        width=32, height=32, spp=3, integrator="path", seed=7, max_depth=4, threads=1,
        filter="gaussian", progress=False,
    )
    want = cli_render(
        lucent_bin, scene, tmp_path / "cli.pfm", "--width", "32", "--height", "32", "--spp",
        "3", "--integrator", "path", "--seed", "7", "--max-depth", "4", "--threads", "2",
        "--filter", "gaussian",
    )
    assert np.array_equal(np.asarray(img), want)
    assert img.meta["spp"] == 3 and img.meta["integrator"] == "path" and img.meta["seed"] == 7
    assert img.meta["complete"] and not img.meta["interrupted"]
    assert img.meta["rays"]["camera"] == 32 * 32 * 3


def test_media_render_from_python_and_count_their_scattering(lucent_bin, tmp_path):
    scene = EXAMPLES / "media.toml"
    img = lucent.load(scene).render(width=24, height=24, spp=4, threads=1, progress=False)
    want = cli_render(
        lucent_bin, scene, tmp_path / "cli.pfm", "--width", "24", "--height", "24", "--spp", "4",
    )
    assert np.array_equal(np.asarray(img), want)
    rays = img.meta["rays"]
    assert rays["scattered"] > 0 and rays["total"] >= rays["camera"] + rays["scattered"]


def test_a_scene_from_a_string_equals_its_file(tmp_path):
    scene = EXAMPLES / "whitted.toml"
    from_text = lucent.load_string(scene.read_text(), base_dir=EXAMPLES)
    a = from_text.render(width=24, height=18, progress=False)
    b = lucent.load(scene).render(width=24, height=18, progress=False)
    c = lucent.default_scene().render(width=24, height=18, progress=False)
    assert np.array_equal(a, b) and np.array_equal(b, c)
    assert from_text.path == "<string>"


def test_a_mitsuba_scene_from_a_string_equals_its_file():
    scene = EXAMPLES / "cornell-box.xml"
    small = dict(width=24, height=24, spp=2, progress=False)
    from_text = lucent.load_string(scene.read_text(), format="mitsuba", base_dir=EXAMPLES)
    assert from_text.path == "<string>"
    assert np.array_equal(from_text.render(**small), lucent.load(scene).render(**small))


def test_debug_views_render(lucent_bin, tmp_path):
    scene = EXAMPLES / "materials.toml"
    for view in ("debug:normals", "debug:depth", "debug:albedo"):
        img = lucent.load(scene).render(width=20, height=16, integrator=view, progress=False)
        want = cli_render(
            lucent_bin, scene, tmp_path / "v.pfm", "--width", "20", "--height", "16",
            "--integrator", view,
        )
        assert np.array_equal(np.asarray(img), want), view
    assert "debug:normals" in lucent.integrators()


def test_progress_reaches_the_total():
    calls = []
    lucent.load(EXAMPLES / "cornell-box.xml").render(
        width=48, height=48, spp=64, integrator="path", progress=lambda d, t: calls.append((d, t))
    )
    assert calls, "the callback was never called"
    assert calls[-1][0] == calls[-1][1] == 48 * 48 * 64
    assert all(d <= t for d, t in calls)


def test_an_error_in_the_progress_callback_stops_the_render():
    def fail(done, total):
        raise RuntimeError("stop here")

    start = time.monotonic()
    with pytest.raises(RuntimeError, match="stop here"):
        lucent.load(EXAMPLES / "cornell-box.xml").render(
            width=64, height=64, spp=100000, integrator="path", progress=fail
        )
    # Stopped at the first poll, not after the 400 million samples asked for.
    assert time.monotonic() - start < 10


def test_a_time_limit_ends_the_render():
    img = lucent.load(EXAMPLES / "cornell-box.xml").render(
        width=16, height=16, integrator="path", time_limit=0.3, progress=False
    )
    assert img.meta["timed_out"] and img.meta["complete"]
    assert img.meta["samples_range"][0] >= 1


def test_info_counts_the_scene():
    info = lucent.load(EXAMPLES / "cornell-box.xml").info()
    assert info["triangles"] == 36 and info["area_lights"] == 1
    assert (info["width"], info["height"], info["integrator"]) == (256, 256, "path")
    assert "cornell-box.xml" in lucent.load(EXAMPLES / "cornell-box.xml")._repr_markdown_()


def test_shadows_and_adaptive_sampling_match_the_command(lucent_bin, tmp_path):
    scene = lucent.default_scene()
    flat = scene.render(width=32, height=24, shadows=False, progress=False)
    want = cli_render(
        lucent_bin, None, tmp_path / "a.pfm", "--width", "32", "--height", "24", "--no-shadows"
    )
    assert np.array_equal(np.asarray(flat), want)
    assert not np.array_equal(flat, scene.render(width=32, height=24, progress=False))
    adaptive = scene.render(
        width=32, height=24, aa="adaptive", aa_threshold=0.05, aa_depth=2, progress=False
    )
    want = cli_render(
        lucent_bin, None, tmp_path / "b.pfm", "--width", "32", "--height", "24", "--aa",
        "adaptive", "--aa-threshold", "0.05", "--aa-depth", "2",
    )
    assert np.array_equal(np.asarray(adaptive), want)


def test_settings_that_do_not_go_together_are_named_as_keywords():
    with pytest.raises(ValueError, match=r'spp has no effect'):
        lucent.default_scene().render(aa="adaptive", spp=4, progress=False)
    with pytest.raises(ValueError, match=r'aa_block|aa_threshold, aa_depth'):
        lucent.default_scene().render(aa="uniform", aa_threshold=0.1, progress=False)
    with pytest.raises(ValueError, match=r'shadows=False applies to the whitted integrator'):
        lucent.default_scene().render(integrator="path", shadows=False, progress=False)


def test_other_threads_run_during_a_render():
    import threading

    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.01)

    t = threading.Thread(target=tick)
    t.start()
    try:
        img = lucent.load(EXAMPLES / "cornell-box.xml").render(
            width=64, height=64, integrator="path", time_limit=0.5, progress=False
        )
    finally:
        stop.set()
        t.join()
    assert img.meta["timed_out"]
    # About 50 ticks in half a second; with the GIL held through the render there would be ~1.
    assert len(ticks) >= 10, f"{len(ticks)} ticks"
