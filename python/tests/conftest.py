"""What the tests share: the repository's folders, the `lucent` command to compare against, and
a reader for the PFM files it writes."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def lucent_bin() -> str:
    """The `lucent` command: $LUCENT_BIN (the Rust test that runs pytest sets it), else one on
    PATH."""
    path = os.environ.get("LUCENT_BIN") or shutil.which("lucent")
    if not path:
        pytest.fail("set LUCENT_BIN to the lucent command (cargo build --release -p lucent-cli)")
    return path


def read_pfm(path: pathlib.Path) -> np.ndarray:
    """A colour PFM file as an H×W×3 float32 array, rows from the top."""
    data = path.read_bytes()
    header, rest = data.split(b"\n", 3)[:3], data.split(b"\n", 3)[3]
    assert header[0] == b"PF", header
    width, height = (int(v) for v in header[1].split())
    scale = float(header[2])
    dtype = "<f4" if scale < 0 else ">f4"
    pixels = np.frombuffer(rest, dtype=dtype, count=width * height * 3)
    return pixels.reshape(height, width, 3)[::-1].astype(np.float32)


def cli_render(lucent_bin: str, scene, out: pathlib.Path, *flags: str) -> np.ndarray:
    """`lucent render` of `scene` (None: the built-in one) with `flags`, read back from PFM."""
    args = [lucent_bin, "render"]
    if scene is not None:
        args.append(str(scene))
    args += [*flags, "-o", str(out)]
    done = subprocess.run(args, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return read_pfm(out)
