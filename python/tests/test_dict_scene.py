"""Scenes built from Python dicts against the same TOML, bit for bit."""

import numpy as np
import pytest

import lucent
from conftest import EXAMPLES
from test_render import can_render

tomllib = pytest.importorskip("tomllib", reason="tomllib comes with Python 3.11")
TOML_SCENES = sorted(p for p in EXAMPLES.glob("*.toml") if can_render(p))


@pytest.mark.parametrize("scene", TOML_SCENES, ids=lambda p: p.name)
def test_a_dict_of_every_example_renders_as_its_file(scene):
    desc = tomllib.loads(scene.read_text())
    small = dict(width=32, height=24, progress=False)
    from_dict = lucent.load_dict(desc, base_dir=EXAMPLES).render(**small)
    from_file = lucent.load(scene).render(**small)
    assert np.array_equal(from_dict, from_file), f"{scene.name}: the dict and the file differ"
    assert from_dict.meta["integrator"] == from_file.meta["integrator"]


def _respelled(value, as_vector):
    """`value` with every list of numbers spelled by `as_vector`, and None keys added."""
    if isinstance(value, dict):
        return {**{k: _respelled(v, as_vector) for k, v in value.items()}, "unused": None}
    if isinstance(value, list):
        if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return as_vector(value)
        return [_respelled(v, as_vector) for v in value]
    return value


@pytest.mark.parametrize(
    "as_vector",
    [tuple, np.array, lambda v: np.array(v, dtype=np.float64)],
    ids=["tuple", "numpy", "numpy-float64"],
)
def test_tuples_and_numpy_arrays_mean_what_lists_do(as_vector):
    scene = EXAMPLES / "whitted.toml"
    desc = _respelled(tomllib.loads(scene.read_text()), as_vector)
    # Every table also has `unused = None`: a None key is left out, as if not given (scene
    # files refuse keys they do not know, so this fails if it is not).
    got = lucent.load_dict(desc).render(width=24, height=18, progress=False)
    want = lucent.load(scene).render(width=24, height=18, progress=False)
    assert np.array_equal(got, want)


def test_a_bad_value_is_a_scene_error_quoting_its_line():
    desc = {"render": {"spp": "many"}}
    with pytest.raises(lucent.SceneError) as e:
        lucent.load_dict(desc)
    err = e.value
    assert err.file == "<dict>" and err.line is not None and err.column is not None
    assert 'spp = "many"' in str(err), str(err)


def test_a_value_toml_cannot_hold_names_its_key():
    with pytest.raises(ValueError, match=r"material\[0\]\.kd: a object has no place"):
        lucent.load_dict({"material": [{"name": "m", "kd": object()}]})
    with pytest.raises(ValueError, match="keys are strings"):
        lucent.load_dict({"render": {1: 2}})


def test_a_dict_that_contains_itself_is_refused_not_a_crash():
    looped = {"camera": {}}
    looped["camera"]["again"] = looped
    with pytest.raises(ValueError, match="nested more than 32 deep"):
        lucent.load_dict(looped)
    deep: list = []
    for _ in range(100_000):
        deep = [deep]
    with pytest.raises(ValueError, match="nested more than"):
        lucent.load_dict({"object": deep})
