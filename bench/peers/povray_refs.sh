#!/usr/bin/env bash
# POV-Ray 3.7's images of the sample scenes lucent's POV-Ray reader is held to
# (crates/lucent-scene/tests/povray/scenes.txt), written to that folder's references/ as PNG:
# each scene rendered from its own folder at the listed size, without anti-aliasing, with
# Debian's include files.
#
#   bench/peers/povray_refs.sh
#
# Needs `povray`, `povray-examples` and `povray-includes` (Debian: apt-get install -y povray
# povray-examples povray-includes).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
suite="$root/crates/lucent-scene/tests/povray"
examples=/usr/share/doc/povray/examples
include=/usr/share/povray-3.7/include
command -v povray >/dev/null || { echo "povray not found: apt-get install -y povray" >&2; exit 1; }
[ -d "$examples" ] || { echo "$examples missing: apt-get install -y povray-examples" >&2; exit 1; }
mkdir -p "$suite/references" "$HOME/.povray/3.7"
[ -f "$HOME/.povray/3.7/povray.conf" ] || cp /etc/povray/3.7/povray.conf "$HOME/.povray/3.7/"
grep -v '^#' "$suite/scenes.txt" | while IFS=$'\t' read -r scene w h _tol; do
  [ -n "$scene" ] || continue
  name="$(echo "${scene%.pov}" | sed 's#/#__#g')"
  dir="$examples/$(dirname "$scene")"
  (cd "$dir" && povray "+I$(basename "$scene")" "+O$suite/references/$name.png" "+W$w" "+H$h" \
    -A +WT1 -D -V +FN "+L$include" "+L$dir" >/dev/null 2>&1) \
    || { echo "povray failed on $scene" >&2; exit 1; }
  echo "$scene"
done
