# Types of the extension module (python/src/lib.rs); the package's own API is lucent/__init__.py.
from typing import Any, Callable, Optional

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(Exception):
    """A scene that cannot be read or built."""

    file: str
    line: Optional[int]
    column: Optional[int]
    message: str

class Scene:
    @property
    def path(self) -> str: ...
    @property
    def base_dir(self) -> str: ...
    @property
    def text(self) -> str: ...
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
        progress: Optional[Callable[[int, int], Any]] = None,
    ) -> tuple[npt.NDArray[np.float32], dict[str, Any]]: ...
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
    ) -> list[dict[str, Any]]: ...
    def frameless_study(
        self,
        *,
        samples_per_second: float = 400000.0,
        refresh: float = 60.0,
        duration: float = 6.0,
        warmup: Optional[float] = None,
        rate_divisors: list[float] = ...,
        seed: int = 1,
        threads: int = 0,
        integrator: Optional[str] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
        progress: Optional[Callable[[int, int], Any]] = None,
    ) -> dict[str, Any]: ...
    def info(self) -> dict[str, Any]: ...

def load(path: str) -> Scene: ...
def load_string(text: str, format: str = "toml", base_dir: Optional[str] = None) -> Scene:
    """format: "toml" or "mitsuba"."""
def load_dict(scene: dict[str, Any], base_dir: Optional[str] = None) -> Scene: ...
def default_scene() -> Scene: ...
def moving_scene() -> Scene: ...
def write(pixels: npt.NDArray[np.float32], path: str) -> None: ...
def png_bytes(pixels: npt.NDArray[np.float32]) -> bytes: ...
def srgb8(pixels: npt.NDArray[np.float32]) -> npt.NDArray[np.uint8]: ...
def integrators() -> list[str]: ...
