#!/usr/bin/env python3
"""A finer spot for the equal-error scene: every triangle of ../shared/data/meshes/spot.obj split
in four at its edges' midpoints, `levels` times (5,856 triangles become 93,696 at 2 levels), the
texture coordinates split the same way. The surface keeps its shape (the midpoints lie on the
old triangles); what grows is the work of tracing it. Midpoints are shared between neighbouring
triangles, so the mesh stays closed and its vertex normals smooth.

    python bench/peers/spot_mesh.py OUT.obj [--levels 2]

The data folder is $LUCENT_DATA, else ../shared/data beside the project root.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent


def data_dir() -> Path:
    return Path(os.environ.get("LUCENT_DATA", ROOT.parent / "shared" / "data"))


def read_obj(path: Path) -> tuple[list[tuple[float, ...]], list[tuple[float, ...]], list[list[tuple[int, int]]]]:
    """Positions, texture coordinates and triangles as (position, texcoord) index pairs (0-based)."""
    v, vt, faces = [], [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            v.append(tuple(map(float, parts[1:4])))
        elif parts[0] == "vt":
            vt.append(tuple(map(float, parts[1:3])))
        elif parts[0] == "f":
            corners = [tuple(int(x) - 1 for x in c.split("/")[:2]) for c in parts[1:]]
            if len(corners) != 3 or any(len(c) != 2 for c in corners):
                raise SystemExit(f"error: {path}: expected triangles with v/vt indices, got `{line}`")
            faces.append(corners)
    return v, vt, faces


def split(v: list, vt: list, faces: list) -> list:
    """One level: each triangle into four, midpoints shared through their edge's key."""
    mid_v: dict[tuple[int, int], int] = {}
    mid_t: dict[tuple[int, int], int] = {}

    def midpoint(points: list, cache: dict, a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in cache:
            cache[key] = len(points)
            points.append(tuple((x + y) / 2 for x, y in zip(points[a], points[b])))
        return cache[key]

    out = []
    for (a, b, c) in faces:
        ab = (midpoint(v, mid_v, a[0], b[0]), midpoint(vt, mid_t, a[1], b[1]))
        bc = (midpoint(v, mid_v, b[0], c[0]), midpoint(vt, mid_t, b[1], c[1]))
        ca = (midpoint(v, mid_v, c[0], a[0]), midpoint(vt, mid_t, c[1], a[1]))
        out += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    return out


def write(out: Path, levels: int) -> int:
    """Writes the split mesh to `out`; its triangle count."""
    v, vt, faces = read_obj(data_dir() / "meshes" / "spot.obj")
    for _ in range(levels):
        faces = split(v, vt, faces)
    out.parent.mkdir(parents=True, exist_ok=True)
    lines = [f"# spot.obj (Keenan Crane), each triangle split in four {levels} times"]
    lines += [f"v {x:.7g} {y:.7g} {z:.7g}" for x, y, z in v]
    lines += [f"vt {s:.7g} {t:.7g}" for s, t in vt]
    lines += ["f " + " ".join(f"{p + 1}/{t + 1}" for p, t in f) for f in faces]
    tmp = out.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    tmp.replace(out)
    return len(faces)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out", type=Path)
    p.add_argument("--levels", type=int, default=2)
    a = p.parse_args()
    print(f"wrote {a.out}: {write(a.out, a.levels)} triangles")


if __name__ == "__main__":
    main()
