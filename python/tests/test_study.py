"""`Scene.frameless_study`: the study's table as rows, against `lucent study frameless`."""

import csv
import subprocess

import pytest

import lucent

SMALL = dict(
    width=32, height=24, samples_per_second=20_000, refresh=30, duration=0.5, warmup=0.2,
    rate_divisors=[2, 4],
)


def test_the_rows_and_refreshes_are_the_commands(lucent_bin, tmp_path):
    study = lucent.moving_scene().frameless_study(**SMALL, progress=False)
    rows = study["rows"]
    assert [(r["mode"], r["samples_per_second"]) for r in rows] == [
        ("double-buffer", 20_000), ("frameless", 20_000), ("adaptive", 20_000),
        ("frameless", 10_000), ("adaptive", 10_000), ("frameless", 5_000), ("adaptive", 5_000),
    ]
    assert all(r["refreshes"] == 15 and r["mean_rmse"] > 0 for r in rows)
    assert not study["interrupted"] and study["rays"] > 0
    csv_path, plot = tmp_path / "study.csv", tmp_path / "study.svg"
    done = subprocess.run(
        [lucent_bin, "study", "frameless", "--width", "32", "--height", "24",
         "--samples-per-second", "20000", "--refresh", "30", "--duration", "0.5", "--warmup",
         "0.2", "--rate-divisors", "2,4", "--csv", str(csv_path), "--plot", str(plot)],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    with open(csv_path, newline="") as f:
        want = list(csv.DictReader(f))
    got = study["refreshes"]
    assert len(got) == len(want) == 7 * 15
    for g, w in zip(got, want):
        assert g["mode"] == w["mode"] and g["samples_per_second"] == float(w["samples_per_second"])
        for key, column in (("time", "time_s"), ("rmse", "rmse"), ("stale_fraction", "stale_fraction")):
            assert g[key] == pytest.approx(float(w[column]), abs=1e-6)
    # The command's summary table has the same mean errors.
    for r in rows[:3]:
        assert f"{r['mode']:<14} {r['mean_rmse']:>10.5f}" in done.stdout, done.stdout


def test_a_still_scene_warns_and_a_random_integrator_is_refused():
    still = lucent.default_scene()
    with pytest.warns(UserWarning, match="does not move"):
        still.frameless_study(width=8, height=6, samples_per_second=2000, duration=0.1,
                              warmup=0.0, rate_divisors=[], progress=False)
    with pytest.raises(ValueError, match="deterministic integrator"):
        still.frameless_study(integrator="path", progress=False)
    with pytest.raises(ValueError, match="duration must be a positive number"):
        still.frameless_study(duration=0, progress=False)
