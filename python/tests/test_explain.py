"""`Scene.explain`: the ray trees of a pixel as nested dicts, against `lucent explain`."""

import re
import subprocess

import numpy as np
import pytest

import lucent
from conftest import EXAMPLES

WHITTED = EXAMPLES / "whitted.toml"
SMALL = dict(width=40, height=30)


def walk(node):
    yield node
    for child in node["children"]:
        yield from walk(child)


def test_every_sample_is_the_sum_of_its_rays_contributions():
    scene = lucent.load(WHITTED)
    samples = scene.explain(20, 15, spp=4, **SMALL)
    assert [s["sample"] for s in samples] == [0, 1, 2, 3]
    for s in samples:
        tree = s["tree"]
        assert tree["kind"] == "camera"
        total = np.sum([n["contribution"] for n in walk(tree)], axis=0)
        np.testing.assert_allclose(total, s["radiance"], rtol=1e-4, atol=1e-6)


def test_the_glass_sphere_spawns_refracted_rays():
    scene = lucent.load(WHITTED)
    kinds = set()
    for x in range(0, 40, 2):
        for s in scene.explain(x, 12, spp=1, **SMALL):
            kinds |= {n["kind"] for n in walk(s["tree"])}
    assert kinds == {"camera", "reflected", "refracted"}, kinds


def test_the_pixel_value_is_the_commands(lucent_bin):
    scene = lucent.load(WHITTED)
    samples = scene.explain(20, 15, spp=4, **SMALL)
    done = subprocess.run(
        [lucent_bin, "explain", str(WHITTED), "--pixel", "20,15", "--spp", "4", "--width", "40",
         "--height", "30"],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    line = re.search(r"pixel value:\s+(\S+) (\S+) (\S+)", done.stdout)
    assert line, done.stdout
    want = [float(v) for v in line.groups()]
    got = np.mean([s["radiance"] for s in samples], axis=0)
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-7)
    assert done.stdout.count("\nsample ") == len(samples)


def test_one_sample_is_the_same_tree_as_among_all():
    scene = lucent.load(WHITTED)
    every = scene.explain(7, 9, spp=4, **SMALL)
    one = scene.explain(7, 9, spp=4, sample=2, **SMALL)
    assert one == [every[2]]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(integrator="path"), 'integrator="whitted"'),
        (dict(aa="adaptive"), 'aa="uniform"'),
        (dict(spp=100), "sample=K"),
        (dict(spp=2, sample=2), "sample 2 does not exist"),
        (dict(x=40), "outside the 40×30 image"),
    ],
)
def test_what_cannot_be_explained_says_what_to_pass(kwargs, message):
    scene = lucent.load(WHITTED)
    where = dict(x=kwargs.pop("x", 3), y=3)
    with pytest.raises(ValueError, match=re.escape(message)):
        scene.explain(where["x"], where["y"], **SMALL, **kwargs)
