#!/usr/bin/env bash
# The light gallery of docs/lights.md: one stage (a floor, a back wall, a sphere and a box)
# lit by each kind of light in turn, path traced; one PNG per kind under docs/images/lights/.
#
#   bench/lights_figure.sh [spp]      (default 128)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
spp="${1:-128}"
out="$root/docs/images/lights"
lucent="$root/target/release/lucent"
[ -x "$lucent" ] || (cd "$root" && cargo build --release -p lucent-cli)
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

stage() {
    cat <<TOML
[image]
width = 240
height = 160
samples = $spp

[camera]
eye = [0, 1.6, 5.5]
look_at = [0, 0.7, 0]
fov = 40

[render]
integrator = "path"
max_depth = 6

[world]
background = 0

[[material]]
name = "floor"
type = "diffuse"
reflectance = 0.6

[[material]]
name = "red"
type = "roughplastic"
reflectance = [0.7, 0.08, 0.05]
roughness = 0.2

[[material]]
name = "glow"
type = "diffuse"
reflectance = 0
emission = 12

[[object]]
type = "rectangle"
scale = 5
rotate = [-90, 0, 0]
material = "floor"

[[object]]
type = "rectangle"
scale = 5
translate = [0, 0, -2]
material = "floor"

[[object]]
type = "sphere"
center = [-0.8, 0.6, 0]
radius = 0.6
material = "red"

[[object]]
type = "cube"
scale = 0.45
rotate = [0, 30, 0]
translate = [0.9, 0.45, 0.2]
material = "floor"
TOML
}

light() {
    case "$1" in
    point) printf '[[light]]\ntype = "point"\nposition = [1.5, 3, 2]\nintensity = 25\nfalloff = "quadratic"\n' ;;
    spot) printf '[[light]]\ntype = "spot"\nposition = [1.5, 3, 2]\ndirection = [-1.5, -2.6, -2]\ncutoff = 22\ncutoff_start = 14\nintensity = 60\nfalloff = "quadratic"\n' ;;
    directional) printf '[[light]]\ntype = "directional"\ndirection = [-0.6, -1, -0.5]\nintensity = 1.8\n' ;;
    environment) printf '[[light]]\ntype = "environment"\nfile = "%s/examples/sky.hdr"\n' "$root" ;;
    area) printf '[[object]]\ntype = "rectangle"\nscale = [0.6, 0.6, 1]\nrotate = [90, 0, 0]\ntranslate = [0.3, 2.6, 0.6]\nmaterial = "glow"\n' ;;
    photometric) printf '[[light]]\ntype = "photometric"\nfile = "%s/examples/lamps/street.ies"\nposition = [0, 2.6, 0.8]\nintensity = 3\n' "$root" ;;
    goniometric) printf '[[light]]\ntype = "goniometric"\nfile = "%s/examples/lights/lantern.png"\nmapping = "latlong"\nposition = [0, 1.4, 1.2]\nintensity = 6\n' "$root" ;;
    projection) printf '[[light]]\ntype = "projection"\nfile = "%s/examples/lights/slide.png"\nposition = [0, 1.0, 4]\ndirection = [0, -0.05, -1]\nfov = 24\nintensity = 60\n' "$root" ;;
    textured-spot) printf '[[light]]\ntype = "spot"\nfile = "%s/examples/lights/window.png"\nposition = [1.5, 3, 2]\ndirection = [-1.5, -2.6, -2]\ncutoff = 22\nintensity = 60\nfalloff = "quadratic"\n' "$root" ;;
    esac
}

for kind in point spot directional environment area photometric goniometric projection textured-spot; do
    { stage; light "$kind"; } > "$tmp/$kind.toml"
    "$lucent" render "$tmp/$kind.toml" -o "$out/$kind.png"
done
