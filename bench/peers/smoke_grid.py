"""Writes the smoke plume density grids (Mitsuba `.vol`, one channel): a rising, widening,
curling column with ripples, fading to 0 at the box's faces (so lucent, which reads 0 outside a
grid, and Mitsuba, which clamps its edges outward, agree wherever the bounding box lies).

    python3 bench/peers/smoke_grid.py            # both files
Needs numpy. Output: examples/smoke.vol (32×40×32) and the conformance cases'
crates/lucent-scene/tests/conformance/textures/smoke.vol (20×24×20) and smoke-albedo.vol
(10×12×10, three channels: sooty and dark low down, whitening as it rises, bluish at one side).
"""
import os
import struct

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))


def plume(nx, ny, nz):
    # Voxel centres in the unit cube; y is up.
    x = (np.arange(nx) + 0.5) / nx
    y = (np.arange(ny) + 0.5) / ny
    z = (np.arange(nz) + 0.5) / nz
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    cx = 0.5 + 0.13 * np.sin(5.0 * Y)
    cz = 0.5 + 0.10 * np.cos(4.0 * Y + 1.0)
    r = 0.07 + 0.2 * Y
    d2 = ((X - cx) ** 2 + (Z - cz) ** 2) / r**2
    ripples = 0.65 + 0.35 * np.sin(17 * X + 3 * Y) * np.sin(13 * Z - 9 * Y) * np.cos(11 * Y)
    core = np.exp(-d2) * ripples * (1.1 - 0.6 * Y)

    def fade(t):
        # 0 at the faces, 1 from 12% inwards.
        s = np.clip(np.minimum(t, 1 - t) / 0.12, 0, 1)
        return s * s * (3 - 2 * s)

    density = core * fade(X) * fade(Y) * fade(Z)
    return np.clip(density / density.max(), 0, None).astype("<f4")


def albedo(nx, ny, nz):
    x = (np.arange(nx) + 0.5) / nx
    y = (np.arange(ny) + 0.5) / ny
    z = (np.arange(nz) + 0.5) / nz
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    grey = 0.35 + 0.6 * Y
    rgb = np.stack([grey * (1 - 0.25 * X), grey * (1 - 0.1 * X), grey * (0.8 + 0.2 * X)], axis=-1)
    return np.clip(rgb, 0, 1).astype("<f4")


def write(path, grid):
    nz, ny, nx = grid.shape[:3]
    channels = grid.shape[3] if grid.ndim == 4 else 1
    with open(path, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<iiiii", 1, nx, ny, nz, channels))
        f.write(struct.pack("<6f", 0, 0, 0, 1, 1, 1))
        f.write(grid.tobytes())  # z, y, x(, channel) order: x fastest, channels interleaved


write(os.path.join(ROOT, "examples", "smoke.vol"), plume(32, 40, 32))
write(
    os.path.join(ROOT, "crates", "lucent-scene", "tests", "conformance", "textures", "smoke.vol"),
    plume(20, 24, 20),
)
write(
    os.path.join(ROOT, "crates", "lucent-scene", "tests", "conformance", "textures", "smoke-albedo.vol"),
    albedo(10, 12, 10),
)
