#!/usr/bin/env bash
# Runs lucent's parser fuzz targets for a while each: ./run.sh [SECONDS] [TARGET...]
#
# SECONDS defaults to 60 and the targets to all of them. Each run starts from the seeds
# (fuzz/seeds/TARGET, committed) and what earlier runs found (fuzz/corpus/TARGET, not
# committed); for `obj` and `ply`, the first 64 KiB of the shared test meshes are added when
# the data folder ($LUCENT_DATA, else ../shared/data beside the workspace) exists. Crashes,
# timeouts and out-of-memory inputs are written to fuzz/artifacts/TARGET.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scene_toml obj mtl ply gltf mitsuba povray serialized film ies)
fi
data="${LUCENT_DATA:-$here/../../shared/data}"
# The machine is shared: build with one job.
export CARGO_BUILD_JOBS="${CARGO_BUILD_JOBS:-1}"

extra="$(mktemp -d)"
trap 'rm -rf "$extra"' EXIT

for target in "${targets[@]}"; do
    mkdir -p "corpus/$target"
    dirs=("corpus/$target" "seeds/$target")
    # Head-truncated copies of the real meshes: their headers and first few thousand lines
    # (whole files would make every execution slow).
    case "$target" in
        obj) pattern='*.obj' ;;
        ply) pattern='*.ply' ;;
        *) pattern='' ;;
    esac
    if [ -n "$pattern" ] && [ -d "$data/meshes" ]; then
        mkdir -p "$extra/$target"
        for f in "$data"/meshes/$pattern; do
            [ -f "$f" ] && head -c 65536 "$f" > "$extra/$target/$(basename "$f")"
        done
        dirs+=("$extra/$target")
    fi
    echo "== $target: ${seconds} s"
    # Address Sanitizer (cargo-fuzz's default) is kept: libFuzzer's -malloc_limit_mb (which
    # defaults to -rss_limit_mb) needs its allocation hooks to catch one huge allocation.
    cargo +nightly fuzz run "$target" "${dirs[@]}" -- \
        -max_total_time="$seconds" -rss_limit_mb=1024 -timeout=5 \
        -max_len=65536 -dict="dicts/$target.dict" -print_final_stats=1
done
