#!/usr/bin/env bash
# The classic renderer against POV-Ray 3.7 on Whitted's scene (examples/whitted.toml, and the
# same scene in POV-Ray's language, bench/peers/whitted.pov), in one run on one machine:
# POV-Ray's parse + trace time as it reports it (its ~0.7 s of idle start-up left out), against
# lucent as a whole process (start, scene, render, PNG written). Two threads each, no
# anti-aliasing, depth 10; the median of --repeat runs (default 5).
#
#   bench/peers/povray_whitted.sh [--size 2400x1800] [--repeat 5] [--lucent PATH]
#
# Needs `povray` (Debian: apt-get install -y povray) and a release build of lucent.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
size=2400x1800
repeat=5
lucent="$root/target/release/lucent"
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size="$2"; shift 2 ;;
    --repeat) repeat="$2"; shift 2 ;;
    --lucent) lucent="$2"; shift 2 ;;
    *) echo "unknown option $1 (--size WxH, --repeat N, --lucent PATH)" >&2; exit 2 ;;
  esac
done
command -v povray >/dev/null || { echo "povray not found: apt-get install -y povray" >&2; exit 1; }
[ -x "$lucent" ] || { echo "$lucent missing: cargo build --release -p lucent-cli" >&2; exit 1; }
w="${size%x*}"; h="${size#*x}"
out="$root/target/peers/whitted"
mkdir -p "$out" "$HOME/.povray/3.7"
[ -f "$HOME/.povray/3.7/povray.conf" ] || cp /etc/povray/3.7/povray.conf "$HOME/.povray/3.7/"

median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

pov_times=()
for _ in $(seq "$repeat"); do
  log=$(povray +I"$root/bench/peers/whitted.pov" +O"$out/povray.png" +W"$w" +H"$h" -A +WT2 -D \
    2>&1 || true)
  parse=$(echo "$log" | sed -n 's/.*Parse Time:.*(\([0-9.]*\) seconds).*/\1/p' | head -1)
  trace=$(echo "$log" | sed -n 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' | head -1)
  [ -n "$trace" ] || { echo "POV-Ray printed no trace time:"; echo "$log" | tail -20; exit 1; } >&2
  pov_times+=("$(echo "$parse + $trace" | bc -l)")
done
lucent_times=()
for _ in $(seq "$repeat"); do
  start=$(date +%s.%N)
  "$lucent" render "$root/examples/whitted.toml" --width "$w" --height "$h" --threads 2 \
    -o "$out/lucent.png" >/dev/null 2>&1
  lucent_times+=("$(echo "$(date +%s.%N) - $start" | bc -l)")
done
pov=$(printf '%s\n' "${pov_times[@]}" | median)
luc=$(printf '%s\n' "${lucent_times[@]}" | median)
printf 'Whitted scene %s, 2 threads, median of %s\n' "$size" "$repeat"
printf '  POV-Ray 3.7 parse + trace   %6.3f s\n' "$pov"
printf '  lucent whole process        %6.3f s\n' "$luc"
printf '  lucent is %.2fx as fast\n' "$(echo "$pov / $luc" | bc -l)"
printf 'images: %s/povray.png, %s/lucent.png\n' "$out" "$out"
