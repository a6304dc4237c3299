#!/usr/bin/env bash
# Runs bench/peers/mitsuba.py (lucent against Mitsuba 3) in the venv target/peers-venv, making it
# and installing mitsuba==3.9.1 and numpy first when they are missing. Arguments go to the script.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="$root/target/peers-venv"

if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import sys, numpy, mitsuba; sys.exit(mitsuba.MI_VERSION != "3.9.1")' 2>/dev/null; then
    "$venv/bin/pip" install --quiet mitsuba==3.9.1 numpy
fi

# Mitsuba's llvm_ad_rgb aborts with Debian 12's LLVM 14/15; it runs with LLVM 19.
llvm=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
    if [ -e "$llvm" ]; then
        export DRJIT_LIBLLVM_PATH="$llvm"
    else
        echo "warning: $llvm not found: Mitsuba's llvm_ad_rgb may fail (apt-get install -y libllvm19)" >&2
    fi
fi

# `run.sh conformance …` and `run.sh metals` run the other scripts here; anything else goes to
# mitsuba.py (the Cornell box comparison).
case "${1:-}" in
    conformance) shift; exec "$venv/bin/python" "$root/bench/peers/conformance.py" "$@" ;;
    metals) shift; exec "$venv/bin/python" "$root/bench/peers/metals.py" "$@" ;;
esac
exec "$venv/bin/python" "$root/bench/peers/mitsuba.py" "$@"
