#!/usr/bin/env bash
# The texture-filtering figure of docs/materials.md: a checkered plane receding to the horizon,
# ray cast at 1 sample per pixel with each image filter, and the 1024-spp average without
# prefiltering; the four stacked top to bottom into one PNG. (The figures are measured by the
# test `texture_filtering`; this only draws them.)
#
#   bench/filtering_figure.sh [out.png]      (default docs/images/materials/filtering.png)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/docs/images/materials/filtering.png}"
lucent="$root/target/release/lucent"
[ -x "$lucent" ] || (cd "$root" && cargo build --release -p lucent-cli)
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# A 256² checker of 16-texel squares, as an 8-bit grey PNG.
python3 - "$tmp/checker.png" <<'EOF'
import struct, sys, zlib
n, s = 256, 16
body = b"".join(
    b"\x00" + bytes(255 if (x // s + y // s) % 2 == 0 else 0 for x in range(n)) for y in range(n)
)
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 0, 0, 0, 0))
open(sys.argv[1], "wb").write(png + chunk(b"IDAT", zlib.compress(body)) + chunk(b"IEND", b""))
EOF

parts=()
for filter in anisotropic trilinear bilinear reference; do
    f="$filter"
    spp=1
    if [ "$filter" = reference ]; then f=bilinear; spp=1024; fi
    cat >"$tmp/$filter.toml" <<EOF
[image]
width = 384
height = 256
samples = $spp

[camera]
eye = [0, 1, 0]
look_at = [0, 0.75, -10]
fov = 50

[render]
integrator = "raycast"

[[material]]
name = "floor"
kd = { image = "checker.png", encoding = "linear", filter = "$f", scale = [100, 100] }

[[object]]
type = "rectangle"
scale = 200
rotate = [-90, 0, 0]
material = "floor"
EOF
    "$lucent" render "$tmp/$filter.toml" -o "$tmp/$filter.png" 2>&1 | tail -n 1
    parts+=("$tmp/$filter.png")
done
mkdir -p "$(dirname "$out")"
python3 - "$out" "${parts[@]}" <<'EOF'
# Stacks the PNGs vertically (8-bit RGB, as lucent writes them), with only the standard library.
import struct, sys, zlib

def read_png(path):
    data = open(path, "rb").read()
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), "8-bit RGB(A) PNGs only"
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev = zlib.decompress(idat), [], bytearray(w * bpp)
    stride = w * bpp + 1
    for y in range(h):
        f, line = raw[y * stride], bytearray(raw[y * stride + 1:(y + 1) * stride])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if bpp == 3 else bytes(v for j, v in enumerate(line) if j % 4 != 3))
        prev = line
    return w, rows

out, paths = sys.argv[1], sys.argv[2:]
images = [read_png(p) for p in paths]
w = images[0][0]
# Each without the empty sky above its horizon (at row 122 of 256).
rows = [r for _, rs in images for r in rs[104:]]
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
body = b"".join(b"\x00" + r for r in rows)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, len(rows), 8, 2, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(body, 9)) + chunk(b"IEND", b"")
open(out, "wb").write(png)
EOF
echo "wrote $out"
