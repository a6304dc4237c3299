#!/usr/bin/env bash
# lucent against POV-Ray 3.7 on the sample scenes the test suite holds to POV-Ray's images
# (crates/lucent-scene/tests/povray/scenes.txt), in one run on this machine: each scene at the
# same size (800 × 600 unless given), without anti-aliasing, 2 threads each. lucent is timed as
# a whole process (reading, building, rendering, writing the PNG); POV-Ray by the parse,
# bounding and trace times it reports (its ~0.6 s of start-up left out).
#
#   bench/peers/povray_speed.sh [WIDTH HEIGHT]
#
# Prints a row per scene (seconds each, and POV-Ray's over lucent's) and the totals. Needs
# `povray`, `povray-examples`, `povray-includes` and `target/release/lucent`
# (cargo build --release -p lucent-cli).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
w="${1:-800}"
h="${2:-600}"
lucent="$root/target/release/lucent"
examples=/usr/share/doc/povray/examples
include=/usr/share/povray-3.7/include
[ -x "$lucent" ] || { echo "build lucent first: cargo build --release -p lucent-cli" >&2; exit 1; }
command -v povray >/dev/null || { echo "povray not found: apt-get install -y povray" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf '%-40s %9s %9s %7s\n' scene lucent povray ratio
grep -v '^#' "$root/crates/lucent-scene/tests/povray/scenes.txt" | cut -f1 | while read -r scene; do
  [ -n "$scene" ] || continue
  dir="$examples/$(dirname "$scene")"
  file="$(basename "$scene")"
  (cd "$dir" && /usr/bin/time -f '%e' "$lucent" render "$file" -o "$out/l.png" \
    --width "$w" --height "$h" --spp 1 --threads 2 >/dev/null 2>"$out/l.err")
  ours=$(tail -1 "$out/l.err")
  theirs=$(cd "$dir" && povray "+I$file" "+O$out/p.png" "+W$w" "+H$h" -A +WT2 -D +FN \
      "+L$include" "+L$dir" 2>&1 \
    | sed -n 's/.*Time: .*(\([0-9.]*\) seconds).*/\1/p' | awk '{s += $1} END {printf "%.3f", s}')
  awk -v s="$scene" -v l="$ours" -v p="$theirs" 'BEGIN {printf "%-40s %9.3f %9.3f %7.2f\n", s, l, p, p / l}'
done | tee "$out/rows"
awk '{l += $2; p += $3} END {printf "%-40s %9.3f %9.3f %7.2f\n", "total", l, p, p / l}' "$out/rows"
