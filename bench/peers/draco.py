#!/usr/bin/env python3
"""Writes crates/lucent-scene/tests/data/draco-sphere.gltf: a small sphere twice, as mesh 0
compressed by KHR_draco_mesh_compression (the stream made by Google's own Draco encoder, through
DracoPy) and as mesh 1 in plain accessors, so that a test can hold lucent's decoding of the
first to the second.

    target/peers-venv/bin/pip install DracoPy numpy
    target/peers-venv/bin/python bench/peers/draco.py

Positions are quantized to 14 bits over the sphere's bounding cube (2 units), so decoded
positions lie within 2 / 2^14 of the originals; the encoder keeps the order of the points and
faces (preserve_order), so they can be compared one by one. DracoPy adds the positions as the
stream's first attribute: unique id 0. Deterministic.
"""
import base64
import json
import math
import os

import DracoPy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "..", "crates", "lucent-scene", "tests", "data", "draco-sphere.gltf")

rings, segments = 6, 8
points = [(0.0, 1.0, 0.0)]
for i in range(1, rings):
    theta = math.pi * i / rings
    for j in range(segments):
        phi = 2 * math.pi * j / segments
        points.append((math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
points.append((0.0, -1.0, 0.0))
bottom = len(points) - 1
faces = []
for j in range(segments):
    faces.append((0, 1 + j, 1 + (j + 1) % segments))
for i in range(rings - 2):
    for j in range(segments):
        a, b = 1 + i * segments + j, 1 + i * segments + (j + 1) % segments
        faces += [(a, a + segments, b), (b, a + segments, b + segments)]
last = 1 + (rings - 2) * segments
for j in range(segments):
    faces.append((last + j, bottom, last + (j + 1) % segments))

pts = np.array(points, dtype=np.float32)
tris = np.array(faces, dtype=np.uint32)
draco = DracoPy.encode(pts, tris, quantization_bits=14, compression_level=7, preserve_order=True)

plain_pos = pts.tobytes()
plain_idx = tris.astype(np.uint16).tobytes()
blob = bytearray()
views = []
for chunk in (draco, plain_pos, plain_idx):
    while len(blob) % 4:
        blob.append(0)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(chunk)})
    blob += chunk
lo, hi = pts.min(0).tolist(), pts.max(0).tolist()
doc = {
    "asset": {"version": "2.0", "generator": "bench/peers/draco.py (DracoPy %s)" % getattr(DracoPy, "__version__", "")},
    "extensionsUsed": ["KHR_draco_mesh_compression"],
    "extensionsRequired": ["KHR_draco_mesh_compression"],
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    "bufferViews": views,
    "accessors": [
        {"componentType": 5126, "count": len(points), "type": "VEC3", "min": lo, "max": hi},
        {"componentType": 5125, "count": 3 * len(faces), "type": "SCALAR"},
        {"bufferView": 1, "componentType": 5126, "count": len(points), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": 2, "componentType": 5123, "count": 3 * len(faces), "type": "SCALAR"},
    ],
    "meshes": [
        {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                         "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}}]},
        {"primitives": [{"attributes": {"POSITION": 2}, "indices": 3}]},
    ],
    "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [3, 0, 0]}],
    "scenes": [{"nodes": [0, 1]}],
}
with open(OUT, "w") as f:
    json.dump(doc, f, indent=1)
print(f"wrote {OUT}: {len(points)} points, {len(faces)} faces, a Draco stream of {len(draco)} bytes")
