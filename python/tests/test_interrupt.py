"""Ctrl-C in the middle of a render: the render stops promptly and the partial image comes back."""

import json
import select
import signal
import subprocess
import sys
import time

from conftest import EXAMPLES

# The child takes Ctrl-C as Python's KeyboardInterrupt whatever it inherited: a process started
# with SIGINT ignored (as a shell's background jobs are) passes that on, and Python then
# installs no handler of its own.
SCRIPT = """
import json, signal, sys, warnings
signal.signal(signal.SIGINT, signal.default_int_handler)
import lucent
started = False
def progress(done, total):
    global started
    if not started and done > 0:
        started = True
        print("started", flush=True)
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    img = lucent.load(sys.argv[1]).render(
        width=64, height=64, spp=1_000_000, integrator="path", progress=progress)
print(json.dumps({
    "interrupted": img.meta["interrupted"],
    "complete": img.meta["complete"],
    "shape": list(img.shape),
    "least": img.meta["samples_range"][0],
    "most": img.meta["samples_range"][1],
    "finite": bool((img == img).all()),
    "warned": [str(w.message) for w in caught],
}), flush=True)
"""


def test_ctrl_c_returns_the_partial_image_promptly():
    proc = subprocess.Popen(
        [sys.executable, "-c", SCRIPT, str(EXAMPLES / "cornell-box.xml")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        # The child says when its render has started (a hung child fails, not hangs, the test).
        ready, _, _ = select.select([proc.stdout], [], [], 60)
        assert ready, "the render never started"
        assert proc.stdout.readline().strip() == "started"
        time.sleep(0.3)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=20)
        took = time.monotonic() - sent
    finally:
        proc.kill()
    assert proc.returncode == 0, err
    result = json.loads(out.strip().splitlines()[-1])
    assert result["interrupted"] and not result["complete"]
    assert result["shape"] == [64, 64, 3] and result["finite"]
    assert result["most"] >= 1 and result["least"] < 1_000_000
    assert any("interrupted" in w for w in result["warned"])
    # Promptly: a 50 ms poll and one sample per thread, not the million samples asked for.
    assert took < 5.0, f"returned {took:.1f} s after Ctrl-C"
