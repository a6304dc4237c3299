"""A teaching widget: sliders that re-render a scene as they move (ipywidgets, optional).

    from lucent.widgets import explore
    explore(lucent.default_scene())

The maximum depth is a render setting; the index of refraction and the roughness are those
of the first of the scene's materials that has one, changed in the scene's TOML (read with
``tomllib``, Python 3.11+) and rebuilt with :func:`lucent.load_dict`. A slider appears only
for what the scene has.
"""

from __future__ import annotations

from typing import Any, Optional

from . import Image, Scene, load_dict


def _materials(scene: Scene) -> Optional[dict]:
    """The scene's TOML as a dict, or None when it has none (an imported file) or Python is
    older than 3.11."""
    if not scene.text:
        return None
    try:
        import tomllib
    except ImportError:
        return None
    return tomllib.loads(scene.text)


def _with(desc: dict, key: str, value: float) -> dict:
    """``desc`` with the first material that has ``key`` given ``value`` instead."""
    materials = list(desc.get("material", []))
    for i, m in enumerate(materials):
        if key in m:
            materials[i] = dict(m, **{key: value})
            break
    return dict(desc, material=materials)


def _first(materials: list, key: str) -> tuple[Optional[float], str]:
    """The first material's ``key`` that has one, and that material's name."""
    for m in materials:
        if key in m:
            return m[key], m.get("name", "")
    return None, ""


class Explorer:
    """The widget's state and its re-render, apart from the widgets (tested without a browser)."""

    def __init__(self, scene: Scene, **render: Any) -> None:
        self.scene = scene
        self.render_args = dict(progress=False, **render)
        self.desc = _materials(scene)
        materials = (self.desc or {}).get("material", [])
        # The sliders move the first material that has the setting (named on the slider).
        self.ior, self.ior_material = _first(materials, "ior")
        self.roughness, self.roughness_material = _first(materials, "roughness")
        self.has_ior = self.ior is not None
        self.has_roughness = self.roughness is not None
        # The file's maximum depth, else the scene files' default.
        self.max_depth = int((self.desc or {}).get("render", {}).get("max_depth", 10))
        self.image: Optional[Image] = None

    def render(
        self, max_depth: int, ior: Optional[float] = None, roughness: Optional[float] = None
    ) -> Image:
        """The scene with these settings."""
        scene = self.scene
        if self.desc is not None and (ior is not None or roughness is not None):
            desc = self.desc
            if ior is not None and self.has_ior:
                desc = _with(desc, "ior", ior)
            if roughness is not None and self.has_roughness:
                desc = _with(desc, "roughness", roughness)
            scene = load_dict(desc, base_dir=self.scene.base_dir)
        self.image = scene.render(max_depth=max_depth, **self.render_args)
        return self.image


def explore(scene: Scene, width: int = 320, height: int = 240, **render: Any) -> Any:
    """Sliders for the maximum depth, and for the index of refraction and roughness where the
    scene's materials have them; the picture below re-renders as they move."""
    import ipywidgets as w
    from IPython.display import display

    explorer = Explorer(scene, width=width, height=height, **render)
    sliders: dict = {
        "max_depth": w.IntSlider(
            value=min(explorer.max_depth, 12), min=0, max=12, description="max depth"
        ),
    }
    # A material's setting: its range, and the material's name on the slider.
    for key, value, material, least, most in (
        ("ior", explorer.ior, explorer.ior_material, 1.0, 2.5),
        ("roughness", explorer.roughness, explorer.roughness_material, 0.0, 1.0),
    ):
        if value is not None:
            sliders[key] = w.FloatSlider(
                value=value, min=least, max=most, step=0.01, description=f"{key} {material}".strip()
            )
    out = w.interactive_output(lambda **v: display(explorer.render(**v)), sliders)
    box = w.VBox([w.HBox(list(sliders.values())), out])
    box.explorer = explorer
    return box
