"""lucent for Python: load scenes, render them into numpy arrays, see them in notebooks.

    import lucent
    img = lucent.load("examples/cornell-box.xml").render(spp=16, integrator="path")

``img`` is a float32 numpy array (H×W×3, linear radiance, rows from the top) carrying the
render's ``meta`` dict; in Jupyter it shows as a picture. ``lucent.write(img, "out.exr")``
writes it as ``lucent render`` writes its images.
"""

from __future__ import annotations

import os
import warnings
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np

from . import _lucent
from ._lucent import SceneError, integrators

__all__ = [
    "Image",
    "Scene",
    "SceneError",
    "default_scene",
    "integrators",
    "load",
    "load_dict",
    "load_string",
    "moving_scene",
    "srgb8",
    "write",
]
__version__: str = _lucent.__version__

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[int, int], Any]


class Image(np.ndarray):
    """A rendered image: an H×W×3 float32 array of linear radiance, with the render's ``meta``.

    It is a numpy array (every numpy operation applies to it) that Jupyter shows as a picture.
    """

    meta: dict

    def __new__(cls, pixels: Any, meta: Optional[dict] = None) -> "Image":
        img = np.asarray(pixels).view(cls)
        img.meta = dict(meta or {})
        return img

    def __array_finalize__(self, obj: Any) -> None:
        # A copy: a slice's meta changed does not change the image's.
        self.meta = dict(getattr(obj, "meta", {})) if obj is not None else {}

    def _repr_png_(self) -> Optional[bytes]:
        if self.ndim != 3 or self.shape[2] != 3 or self.size == 0:
            return None
        return _lucent.png_bytes(_pixels(self))


def _pixels(img: Any) -> np.ndarray:
    """``img`` as a C-contiguous H×W×3 float32 array (no copy when it already is one)."""
    a = np.ascontiguousarray(np.asarray(img), dtype=np.float32)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"an image is an H×W×3 array, not one of shape {a.shape}")
    return a


def srgb8(img: Any) -> np.ndarray:
    """The image as its PNG file holds it: 8-bit sRGB, H×W×3 uint8."""
    return _lucent.srgb8(_pixels(img))


def write(img: Any, path: PathLike) -> None:
    """Writes an H×W×3 array of linear radiance as an image file, in the format its extension
    names (.png, .exr, .pfm), as ``lucent render`` writes its images."""
    _lucent.write(_pixels(img), os.fspath(path))


def _bar(
    progress: Union[bool, Progress, None], unit: str = "sample"
) -> tuple[Optional[Progress], Callable[[], None]]:
    """The callback a render reports to, and what closes it afterwards."""
    if callable(progress):
        return progress, lambda: None
    if progress is False:
        return None, lambda: None
    if progress is not None and progress is not True:
        raise TypeError(
            f"progress is None or True (a bar), False (none) or a callable, not {progress!r}"
        )
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None, lambda: None
    bar = tqdm(total=1, unit=unit, unit_scale=True, leave=False)

    def update(done: int, total: int) -> None:
        if total and bar.total != total:
            bar.total = total
        bar.n = done
        bar.refresh()

    return update, bar.close


class Scene:
    """A scene read from a file or a string; each render may override its settings."""

    def __init__(self, inner: "_lucent.Scene") -> None:
        self._inner = inner

    @property
    def path(self) -> str:
        """The file the scene came from (``<string>`` for ``load_string``)."""
        return self._inner.path

    @property
    def base_dir(self) -> str:
        """The folder relative file names in the scene start from."""
        return self._inner.base_dir

    @property
    def text(self) -> str:
        """The scene file's text (empty for a file imported from another format): edit it and
        ``load_string`` the result to change what the keywords of ``render`` do not reach."""
        return self._inner.text

    def render(
        self,
        *,
        spp: Optional[int] = None,
        integrator: Optional[str] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
        threads: int = 0,
        seed: Optional[int] = None,
        time_limit: Optional[float] = None,
        max_depth: Optional[int] = None,
        filter: Optional[str] = None,
        shadows: bool = True,
        aa: Optional[str] = None,
        aa_threshold: Optional[float] = None,
        aa_depth: Optional[int] = None,
        aa_block: Optional[int] = None,
        progress: Union[bool, Progress, None] = None,
    ) -> Image:
        """Renders the scene into an :class:`Image` (linear radiance, float32, H×W×3).

        Arguments left None keep the scene file's settings (as ``lucent render``'s flags do);
        ``threads=0`` uses every core. ``shadows=False`` leaves Whitted's shadow rays out;
        ``aa="adaptive"`` (or ``"quadtree"``) samples pixel corners and subdivides where they
        differ by more than ``aa_threshold``, ``aa_depth`` levels at most (``aa_block``: the
        quadtree's block size, log2). ``progress``: None shows a tqdm bar when tqdm is
        installed, False shows none, a callable is called with (samples done, samples to do).
        Ctrl-C (KeyboardInterrupt) stops the render and returns the partial image with
        ``meta["interrupted"]`` set and a warning.
        """
        report, close = _bar(progress)
        try:
            pixels, meta = self._inner.render(
                spp=spp,
                integrator=integrator,
                width=width,
                height=height,
                threads=threads,
                seed=seed,
                time_limit=time_limit,
                max_depth=max_depth,
                filter=filter,
                shadows=shadows,
                aa=aa,
                aa_threshold=aa_threshold,
                aa_depth=aa_depth,
                aa_block=aa_block,
                progress=report,
            )
        finally:
            close()
        if meta["interrupted"]:
            least, most = meta["samples_range"]
            warnings.warn(
                f"render interrupted at {least}..{most} of {meta['spp']} samples per pixel: "
                "the image is partial",
                RuntimeWarning,
                stacklevel=2,
            )
        return Image(pixels, meta)

    def explain(
        self,
        x: int,
        y: int,
        *,
        sample: Optional[int] = None,
        spp: Optional[int] = None,
        integrator: Optional[str] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
        seed: Optional[int] = None,
        max_depth: Optional[int] = None,
        shadows: bool = True,
        aa: Optional[str] = None,
    ) -> list[dict]:
        """The ray trees of pixel (x, y), as ``lucent explain`` prints them: one dict per sample
        (``sample``, ``through``, ``radiance``, ``tree``). A tree is a dict per ray: ``kind``
        (camera, reflected, refracted), ``origin``, ``dir``, ``weight``, ``hit`` (None or
        ``t``, ``point``, ``object``, ``material``, ``entering``), ``lights`` (its shadow rays),
        ``local``, ``cuts`` (why a ray was not traced), ``contribution`` (what it adds to the
        pixel) and ``children``. The samples are the render's own (same seed, same camera
        rays), traced by the Whitted integrator; ``sample`` picks one."""
        return self._inner.explain(
            x,
            y,
            sample=sample,
            spp=spp,
            integrator=integrator,
            width=width,
            height=height,
            seed=seed,
            max_depth=max_depth,
            shadows=shadows,
            aa=aa,
        )

    def frameless_study(
        self,
        *,
        samples_per_second: float = 400_000.0,
        refresh: float = 60.0,
        duration: float = 6.0,
        warmup: Optional[float] = None,
        rate_divisors: Sequence[float] = (2, 4, 8, 16, 32),
        seed: int = 1,
        threads: int = 0,
        integrator: Optional[str] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
        progress: Union[bool, Progress, None] = None,
    ) -> dict:
        """The frameless study (``lucent study frameless``): double buffering, frameless and
        adaptive frameless rendering of this moving scene on the same sample budget, each
        refresh compared with the ideal image. Returns a dict: ``rows`` (one per run: ``mode``,
        ``samples_per_second``, ``mean_rmse``, ``mean_stale``, ``mean_latency_ms``,
        ``latency_p95_ms``, ``unseen``, ``samples``; ``pandas.DataFrame(study["rows"])`` makes
        the table), ``refreshes`` (every refresh, as the CLI's CSV), ``matching`` (per frameless
        mode, the rate that matches double buffering's error) and the conditions. Ctrl-C stops
        it after the refresh under way with what was measured (``interrupted`` set)."""
        report, close = _bar(progress, unit="refresh")
        try:
            study = self._inner.frameless_study(
                samples_per_second=samples_per_second,
                refresh=refresh,
                duration=duration,
                warmup=warmup,
                rate_divisors=[float(d) for d in rate_divisors],
                seed=seed,
                threads=threads,
                integrator=integrator,
                width=width,
                height=height,
                progress=report,
            )
        finally:
            close()
        if study["interrupted"]:
            warnings.warn(
                f"study interrupted: {study['settings']['duration']:.2f} s of {duration} s measured",
                RuntimeWarning,
                stacklevel=2,
            )
        return study

    def info(self) -> dict:
        """What the scene holds (counts, bounds) and the settings its file gives."""
        return self._inner.info()

    def _repr_markdown_(self) -> str:
        i = self.info()
        return (
            f"**lucent scene** `{i['path']}`: {i['objects']} objects "
            f"({i['triangles']} triangles), {i['lights']} lights, "
            f"{i['width']}×{i['height']}, {i['spp']} spp, integrator `{i['integrator']}`"
        )

    def __repr__(self) -> str:
        return f"lucent.Scene({self.path!r})"


def load(path: PathLike) -> Scene:
    """Reads a scene file: lucent's TOML, Mitsuba XML, glTF/GLB, OBJ or PLY.

    Raises :class:`SceneError` (with ``file``, ``line`` and ``column``) for a bad file."""
    return Scene(_lucent.load(os.fspath(path)))


def load_string(text: str, format: str = "toml", base_dir: Optional[PathLike] = None) -> Scene:
    """A scene from text: ``format="toml"`` (lucent's format) or ``"mitsuba"`` (Mitsuba 3 XML);
    relative file names in it start from ``base_dir`` (default: the current folder)."""
    base = None if base_dir is None else os.fspath(base_dir)
    return Scene(_lucent.load_string(text, format=format, base_dir=base))


def default_scene() -> Scene:
    """The built-in default scene (Whitted's picture), as ``lucent render`` renders it."""
    return Scene(_lucent.default_scene())


def load_dict(scene: dict, base_dir: Optional[PathLike] = None) -> Scene:
    """A scene built from Python: a dict shaped like lucent's TOML file, e.g.
    ``{"camera": {"eye": [0, 1, 5], ...}, "material": [{...}], "object": [{...}]}`` (tables
    as dicts, arrays of tables as lists of dicts, vectors as lists, tuples or numpy arrays;
    None leaves a key out). It means what the same TOML means and renders the same bits.
    ``tomllib.loads(text)`` of a scene file gives such a dict. Relative file names start from
    ``base_dir`` (default: the current folder). Errors name the line of the dict's TOML
    (``lucent.SceneError``) or the key (``ValueError``)."""
    base = None if base_dir is None else os.fspath(base_dir)
    return Scene(_lucent.load_dict(scene, base_dir=base))


def moving_scene() -> Scene:
    """The built-in moving scene ``lucent study frameless`` studies without a file."""
    return Scene(_lucent.moving_scene())
