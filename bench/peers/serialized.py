#!/usr/bin/env python3
"""Mitsuba's `serialized` meshes, written here and read by Mitsuba 3, for lucent's reader to be
held to: a file of two shapes, and each shape as Mitsuba loaded it, written back by Mitsuba as
a PLY.

    target/peers-venv/bin/python bench/peers/serialized.py [--out DIR]

Mitsuba 3 writes no serialized files, but it has the stream its reader inflates: each shape's
data goes through Mitsuba's own `ZStream` (zlib, as Mitsuba 0.x wrote them) over a
`FileStream`, with the header and the end-of-file dictionary around them (layout in
crates/lucent-scene/src/serialized.rs and Mitsuba's src/shapes/serialized.cpp).

The shapes:
  0: a cube with each face cut 3 x 3, its own vertices per face (normals along the face,
     texture coordinates across it), single precision;
  1: a small UV sphere with normals, texture coordinates and vertex colours (which Mitsuba 3
     reads past), double precision.

`mi.load_dict({'type': 'serialized', 'filename': ..., 'shape_index': k})` loads each, and
`mesh.write_ply` writes what it loaded. The same shapes in a version-3 file must load the same,
and so must a file whose streams Python's zlib wrote: the script stops with an error otherwise.

Writes, to DIR (default crates/lucent-scene/tests/data, where the test
crates/lucent-scene/tests/mitsuba/serialized.rs reads them):
  mitsuba-shapes.serialized, mitsuba-shapes-0.ply, mitsuba-shapes-1.ply

Needs mitsuba==3.9.1 and numpy (bench/peers/run.sh makes the venv). Deterministic: running it
again writes the same bytes.
"""

from __future__ import annotations

import argparse
import math
import os
import struct
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path = [p for p in sys.path if os.path.abspath(p or ".") != HERE]

import numpy as np  # noqa: E402

try:
    import mitsuba as mi  # noqa: E402
except ImportError as e:
    sys.exit(f"error: {e}; run bench/peers/run.sh once, which installs mitsuba==3.9.1 in a venv")

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
DATA = os.path.join(ROOT, "crates", "lucent-scene", "tests", "data")

FORMAT_ID = 0x041C
HAS_NORMALS, HAS_UVS, HAS_COLORS = 0x0001, 0x0002, 0x0008
SINGLE, DOUBLE = 0x1000, 0x2000


# ----------------------------------------------------------------------------------------------
# The meshes.


def cube(cuts=3):
    """[-1, 1]^3, each face a grid of cuts x cuts quads with vertices of its own."""
    pos, nrm, uv, tris = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            # (s, t) span the face; s x t points along n, so triangles wind outwards.
            s_axis, t_axis = (axis + 1) % 3, (axis + 2) % 3
            if sign < 0:
                s_axis, t_axis = t_axis, s_axis
            base = len(pos) // 3
            for j in range(cuts + 1):
                for i in range(cuts + 1):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = sign
                    p[s_axis] = -1.0 + 2.0 * i / cuts
                    p[t_axis] = -1.0 + 2.0 * j / cuts
                    pos += p
                    nrm += n
                    uv += [i / cuts, j / cuts]
            for j in range(cuts):
                for i in range(cuts):
                    a = base + j * (cuts + 1) + i
                    b, c, d = a + 1, a + cuts + 2, a + cuts + 1
                    tris += [a, b, c, a, c, d]
    return pos, nrm, uv, None, tris


def sphere(rings=5, segments=8, radius=0.75):
    """A UV sphere: poles as rings of their own vertices, a seam of duplicated vertices."""
    pos, nrm, uv, col, tris = [], [], [], [], []
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2.0 * math.pi * i / segments
            d = [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)]
            pos += [radius * x for x in d]
            nrm += d
            uv += [i / segments, j / rings]
            col += [0.5 + 0.5 * x for x in d]
    for j in range(rings):
        for i in range(segments):
            a = j * (segments + 1) + i
            b, c, d = a + segments + 1, a + segments + 2, a + 1
            if j > 0:
                tris += [a, b, d]
            if j < rings - 1:
                tris += [d, b, c]
    return pos, nrm, uv, col, tris


# ----------------------------------------------------------------------------------------------
# The format.


def shape_data(version, name, flags, arrays):
    """One shape's stream before compression."""
    pos, nrm, uv, col, tris = arrays
    fmt = "d" if flags & DOUBLE else "f"
    out = struct.pack("<I", flags)
    if version == 4:
        out += name.encode() + b"\0"
    out += struct.pack("<QQ", len(pos) // 3, len(tris) // 3)
    for flag, values in ((0, pos), (HAS_NORMALS, nrm), (HAS_UVS, uv), (HAS_COLORS, col)):
        if flag == 0 or flags & flag:
            out += struct.pack(f"<{len(values)}{fmt}", *values)
    return out + struct.pack(f"<{len(tris)}I", *tris)


def write_with_mitsuba(path, version, shapes):
    """The shapes through Mitsuba's ZStream, each after its header; then the dictionary."""
    fs = mi.FileStream(path, mi.FileStream.ETruncReadWrite)
    fs.set_byte_order(mi.Stream.ELittleEndian)
    offsets = []
    for data in shapes:
        offsets.append(fs.tell())
        fs.write_uint16(FORMAT_ID)
        fs.write_uint16(version)
        z = mi.ZStream(fs)
        z.write(data)
        z.close()  # ends the zlib stream; the file stream stays open
    for o in offsets:
        (fs.write_uint64 if version == 4 else fs.write_uint32)(o)
    fs.write_uint32(len(offsets))
    fs.close()


def write_with_zlib(path, version, shapes):
    out = b""
    offsets = []
    for data in shapes:
        offsets.append(len(out))
        out += struct.pack("<HH", FORMAT_ID, version) + zlib.compress(data, 9)
    out += struct.pack(f"<{len(offsets)}{'Q' if version == 4 else 'I'}", *offsets)
    out += struct.pack("<I", len(offsets))
    with open(path, "wb") as f:
        f.write(out)


# ----------------------------------------------------------------------------------------------


def loaded(path, index):
    """What Mitsuba loads: positions, normals, texture coordinates and faces as arrays."""
    m = mi.load_dict({"type": "serialized", "filename": path, "shape_index": index})
    return m, [
        np.array(m.vertex_positions_buffer()),
        np.array(m.vertex_normals_buffer()),
        np.array(m.vertex_texcoords_buffer()),
        np.array(m.faces_buffer()),
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=DATA, help="where to write the files (default: %(default)s)")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    os.makedirs(args.out, exist_ok=True)

    meshes = [
        ("cube", SINGLE | HAS_NORMALS | HAS_UVS, cube()),
        ("sphere", DOUBLE | HAS_NORMALS | HAS_UVS | HAS_COLORS, sphere()),
    ]
    target = os.path.join(args.out, "mitsuba-shapes.serialized")
    write_with_mitsuba(target, 4, [shape_data(4, n, f, a) for n, f, a in meshes])

    # The same shapes as version 3, and through Python's zlib: Mitsuba must load them alike.
    with tempfile.TemporaryDirectory() as tmp:
        others = []
        for version, write in ((3, write_with_mitsuba), (4, write_with_zlib), (3, write_with_zlib)):
            p = os.path.join(tmp, f"v{version}-{write.__name__}.serialized")
            write(p, version, [shape_data(version, n, f, a) for n, f, a in meshes])
            others.append(p)
        for k, (name, flags, arrays) in enumerate(meshes):
            mesh, ours = loaded(target, k)
            for p in others:
                _, theirs = loaded(p, k)
                for a, b in zip(ours, theirs):
                    if a.shape != b.shape or not np.array_equal(a, b):
                        sys.exit(f"error: shape {k} of {os.path.basename(p)} loads differently")
            # The arrays as written (positions in single precision) are what Mitsuba holds.
            pos, nrm, uv, _, tris = arrays
            assert np.allclose(ours[0], np.array(pos, dtype=np.float32), atol=0)
            assert np.allclose(ours[2], np.array(uv, dtype=np.float32), atol=0), "uv as written"
            assert np.array_equal(ours[3], np.array(tris, dtype=np.uint32))
            ply = os.path.join(args.out, f"mitsuba-shapes-{k}.ply")
            mesh.write_ply(ply)
            print(
                f"shape {k} ({name}, flags {flags:#06x}): {mesh.vertex_count()} vertices, "
                f"{mesh.face_count()} triangles, normals {mesh.has_vertex_normals()}, "
                f"uvs {mesh.has_vertex_texcoords()} -> {os.path.relpath(ply, ROOT)} "
                f"({os.path.getsize(ply)} bytes)"
            )
    print(f"{os.path.relpath(target, ROOT)}: {os.path.getsize(target)} bytes, written through Mitsuba's ZStream")


if __name__ == "__main__":
    main()
