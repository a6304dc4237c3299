"""Bad input as Python exceptions with their place; images written and shown."""

import re

import numpy as np
import pytest

import lucent
from conftest import EXAMPLES, read_pfm


def test_a_bad_scene_file_names_file_line_and_column(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[image]\nwidth = 64\nheight = \"tall\"\n")
    with pytest.raises(lucent.SceneError) as caught:
        lucent.load(bad)
    e = caught.value
    assert e.file == str(bad)
    assert (e.line, e.column) == (3, 10)
    assert str(e).startswith(f"{bad}:3:10: ")


def test_an_error_found_at_build_has_its_place_too(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        (EXAMPLES / "whitted.toml").read_text().replace("ior = 1.5", "ior = -2.0")
    )
    scene = lucent.load(bad)  # parses; the build checks the value
    with pytest.raises(lucent.SceneError) as caught:
        scene.render(width=8, height=6, progress=False)
    assert caught.value.file == str(bad) and caught.value.line is not None
    assert "ior" in caught.value.message


def test_a_missing_file_is_a_scene_error_without_a_line(tmp_path):
    with pytest.raises(lucent.SceneError) as caught:
        lucent.load(tmp_path / "nowhere.toml")
    assert caught.value.line is None and caught.value.column is None
    assert "no such scene file" in str(caught.value)


def test_a_bad_string_scene_names_the_string():
    with pytest.raises(lucent.SceneError) as caught:
        lucent.load_string("[image]\nwidth = -3\n")
    assert (caught.value.file, caught.value.line) == ("<string>", 2)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(integrator="magic"), "integrator"),
        (dict(filter="blurry"), "filter"),
        (dict(time_limit=-1.0), "time_limit must be a positive number of seconds, not -1"),
        (dict(integrator="path", width=0), "width must be between 1 and 65536, not 0"),
        (dict(spp=0), "spp must be between 1 and 1048576, not 0"),
        (dict(spp=-3), "spp must be zero or more"),
        (dict(max_depth=1001), "max_depth must be between 0 and 1000, not 1001"),
        (dict(aa="quadtree", aa_block=9), "aa_block must be between 1 and 4, not 9"),
        (dict(aa_block=2), 'aa_threshold, aa_depth and aa_block need aa="adaptive" or quadtree'),
    ],
)
def test_bad_settings_raise_value_errors_naming_the_keyword(kwargs, message):
    # A ValueError, not a SceneError: the scene file is not at fault.
    with pytest.raises(ValueError, match=re.escape(message)):
        lucent.default_scene().render(progress=False, **kwargs)


def test_writing_names_what_went_wrong(tmp_path):
    img = lucent.default_scene().render(width=8, height=6, progress=False)
    with pytest.raises(ValueError, match="jpg"):
        lucent.write(img, tmp_path / "out.jpg")
    with pytest.raises(OSError, match="cannot create"):
        lucent.write(img, tmp_path / "no-such-folder" / "out.png")


def test_unsupported_string_formats_are_refused():
    with pytest.raises(ValueError, match='"toml" or "mitsuba"'):
        lucent.load_string("{}", format="gltf")


def test_a_bad_mitsuba_string_names_its_line():
    text = '<scene version="3.0.0">\n  <shape type="sphere">\n    <float name="radius" value="big"/>\n  </shape>\n</scene>\n'
    with pytest.raises(lucent.SceneError) as e:
        lucent.load_string(text, format="mitsuba")
    err = e.value
    assert err.file == "<string>" and err.line == 3, (err.file, err.line, str(err))
    assert '<float name="radius" value="big"/>' in str(err), str(err)


@pytest.mark.parametrize("ext", [".pfm", ".exr"])
def test_written_files_give_the_pixels_back(tmp_path, ext):
    img = lucent.default_scene().render(width=20, height=10, progress=False)
    out = tmp_path / f"out{ext}"
    lucent.write(img, out)
    if ext == ".pfm":
        assert np.array_equal(read_pfm(out), np.asarray(img))
    else:
        assert out.stat().st_size > 0


def test_png_and_srgb8_show_the_image(tmp_path):
    img = lucent.default_scene().render(width=20, height=10, progress=False)
    png = img._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    lucent.write(img, tmp_path / "a.png")
    assert (tmp_path / "a.png").read_bytes() == png
    rgb = lucent.srgb8(img)
    assert rgb.shape == (10, 20, 3) and rgb.dtype == np.uint8
    # The sky is blue.
    assert rgb[0, 0, 2] > rgb[0, 0, 0]


def test_arrays_of_the_wrong_shape_are_refused(tmp_path):
    with pytest.raises(ValueError, match="H×W×3"):
        lucent.write(np.zeros((4, 4)), tmp_path / "x.png")
    with pytest.raises(ValueError, match="H×W×3"):
        lucent.srgb8(np.zeros((4, 4, 4)))


def test_an_image_stays_an_array_with_its_meta():
    img = lucent.default_scene().render(width=8, height=6, progress=False)
    assert isinstance(img, np.ndarray) and isinstance(img, lucent.Image)
    half = img[:3]
    assert half.meta["width"] == 8
    assert float((img * 2).sum()) == pytest.approx(2 * float(img.sum()))
