#!/usr/bin/env python3
"""Writes the images the light examples read (standard library only):

- window.png: a window's frame, 4 x 3 panes, for a spot light's `file` (a gobo);
- lantern.png: a pierced-tin lantern as a lat-long map of intensity for a goniometric light:
  rings of holes below its equator and a bright open top.

The slide the projector shows (slide.png) is lucent's own default scene:
`cargo run --release -- render --width 192 --height 144 -o examples/lights/slide.png`.
"""
import math
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).parent


def write_png(path, width, height, pixel):
    """An 8-bit RGB PNG; `pixel(x, y)` gives (r, g, b) in 0..255."""
    rows = b"".join(
        b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height)
    )

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    path.write_bytes(
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(rows, 9))
        + chunk(b"IEND", b"")
    )


def window(x, y, size=128):
    """Light through the panes, none through the frame (bars 6 texels wide)."""
    u, v = x / size, y / size
    frame = min(u, 1 - u, v, 1 - v) < 0.06
    bar_x = any(abs(u - k / 4) < 0.025 for k in (1, 2, 3))
    bar_y = any(abs(v - k / 3) < 0.025 for k in (1, 2))
    lit = not (frame or bar_x or bar_y)
    return (255, 244, 220) if lit else (0, 0, 0)


def lantern(x, y, width=1024, height=512):
    """Rows from the top (up) to the bottom (down); columns turn about the up axis."""
    theta = (y + 0.5) / height * math.pi
    phi = (x + 0.5) / width * 2 * math.pi
    if theta < 0.35:  # the open top
        return (255, 230, 170)
    # Rings of round holes between 60 and 150 degrees from the top.
    for ring, count in ((1.1, 12), (1.55, 16), (2.0, 12), (2.45, 8)):
        spacing = 2 * math.pi / count
        offset = spacing / 2 if count in (16, 8) else 0.0
        d_phi = (phi - offset + spacing / 2) % spacing - spacing / 2
        dist = math.hypot((theta - ring) / 0.07, d_phi * math.sin(theta) / 0.07)
        if dist < 1:
            return (255, 200, 120)
    return (0, 0, 0)


write_png(HERE / "window.png", 128, 128, window)
write_png(HERE / "lantern.png", 1024, 512, lantern)
