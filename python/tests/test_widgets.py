"""The teaching widget's re-render, without a browser."""

import numpy as np
import pytest

import lucent
from conftest import EXAMPLES
from lucent.widgets import Explorer

pytest.importorskip("tomllib", reason="the widget edits materials with tomllib (Python 3.11)")
SMALL = dict(width=24, height=18)


def test_the_files_values_give_its_picture_and_each_slider_changes_it():
    scene = lucent.load(EXAMPLES / "whitted.toml")
    explorer = Explorer(scene, **SMALL)
    assert explorer.has_ior and not explorer.has_roughness
    # The file's own values give the file's picture.
    same = explorer.render(max_depth=10, ior=1.5)
    assert np.array_equal(same, scene.render(max_depth=10, progress=False, **SMALL))
    # A glass of ior 1 bends nothing; a depth of 1 stops at the first bounce.
    assert not np.array_equal(explorer.render(max_depth=10, ior=1.0), same)
    assert not np.array_equal(explorer.render(max_depth=1, ior=1.5), same)
    assert explorer.image is not None and explorer.image.shape == (18, 24, 3)
    # The slider starts where the file is.
    assert explorer.ior == 1.5 and explorer.max_depth == 10


def test_explore_builds_the_sliders_the_scene_has():
    pytest.importorskip("ipywidgets")
    from lucent.widgets import explore

    box = explore(lucent.load(EXAMPLES / "whitted.toml"), **SMALL)
    names = [s.description for s in box.children[0].children]
    assert names == ["max depth", "ior glass"]
    assert box.explorer.image is not None
    assert [s.value for s in box.children[0].children] == [10, 1.5]
