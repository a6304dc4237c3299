#!/usr/bin/env bash
# Renders Khronos' glTF sample models from ../shared/data/gltf (see its README for credits) for
# docs/materials.md: each converted to lucent's TOML (`lucent convert`, which writes every
# material and texture the reader took), then lit by a studio light (a grey sky and a sun from
# above the camera's left, as the Khronos screenshots' viewers light them) and path traced.
# TwoSidedPlane and BoxVertexColors are seen from above (`--view iso`, as their screenshots; the
# framing camera sees the plane edge on), and TextureCoordinateTest from −z, the side its README
# says it faces.
#
#   bench/peers/gltf_samples.sh [out-dir] [spp]     (default docs/images/materials, 256)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="$root/../shared/data/gltf"
out="${1:-$root/docs/images/materials}"
spp="${2:-256}"
lucent="$root/target/release/lucent"
[ -x "$lucent" ] || (cd "$root" && cargo build --release -p lucent-cli)
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

for model in Avocado NormalTangentTest ClearCoatTest Duck CesiumMilkTruck TextureSettingsTest \
    BoxVertexColors TextureCoordinateTest TextureTransformTest TwoSidedPlane; do
    scene="$tmp/$model.toml"
    view=()
    case "$model" in TwoSidedPlane | BoxVertexColors) view=(--view iso) ;; esac
    "$lucent" convert "$data/$model/glTF/$model.gltf" "$scene" "${view[@]}" >/dev/null 2>"$tmp/$model.warnings"
    if [ "$model" = TextureCoordinateTest ]; then
        # The framing camera's eye mirrored through the model's centre along z.
        awk '/^eye = /{gsub(/[\[\],]/," "); print "eye = [" $3 ", " $4 ", " (-$5) "]"; next} {print}' \
            "$scene" >"$scene.tmp" && mv "$scene.tmp" "$scene"
    fi
    # The path tracer, and light that shows the materials: the sky fills in, the sun shades.
    sed -i 's/^integrator = .*/integrator = "path"/' "$scene"
    cat >>"$scene" <<'EOF'

[[light]]
type = "environment"
intensity = 0.6

[[light]]
type = "directional"
direction = [0.4, -1.0, -0.6]
intensity = 2.0
EOF
    "$lucent" render "$scene" --spp "$spp" --width 480 --height 360 -o "$out/$model.png" 2>&1 | tail -n 1
    sed "s|$data/||g" "$tmp/$model.warnings"
done
