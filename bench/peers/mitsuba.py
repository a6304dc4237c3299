#!/usr/bin/env python3
"""lucent's path tracer against Mitsuba 3 on the Cornell box, in one run on one machine.

    python bench/peers/mitsuba.py [compare] [--scene cbox|showcase] [--spp 16 64 256] ...
    python bench/peers/mitsuba.py refs [--force]

`--scene showcase` runs the same comparison on the second scene (bench/peers/showcase.xml: a
textured mesh of 93,696 triangles, glass, rough gold and an environment map), whose mesh
bench/peers/spot_mesh.py makes from ../shared/data; its files are named showcase-… instead of
cbox-… (reference target/peers/showcase-256-ref.exr, table target/peers/mitsuba-showcase.csv).

`compare` (the default):
  1. renders, or reuses when present, the reference target/peers/cbox-256-ref.exr (Mitsuba
     llvm_ad_rgb, 4096 spp; cbox-256-box-ref.exr with --rfilter box);
  2. for each sample count, renders examples/cornell-box.xml with Mitsuba scalar_rgb and
     llvm_ad_rgb (2 threads; LLVM after a warm-up render of the same size, so its JIT compilation
     is left out of the time) and measures wall time and error against the reference;
  3. runs lucent on the same file at equal time (`--time-limit T`, T = each Mitsuba variant's
     wall time) and at equal samples (`--spp N`), reads its EXR and measures the same errors;
  4. prints one table and writes it to target/peers/mitsuba.csv.

`refs`: the references to keep: cbox-256-ref.exr; cbox-64-ref.exr and .pfm (64x64, 65536 spp);
the same at another seed (cbox-64-ref-seed2.exr) with the error between the two (the
reference's own noise floor); and cbox-64-box-ref.exr/.pfm (box pixel filter).

Errors, over every pixel and channel, of an image a against the reference b:
  relMSE = mean((a-b)^2 / (b^2 + 1e-2));  MSE = mean((a-b)^2);  MSE/mean^2 = MSE / mean(b)^2.

Needs only mitsuba==3.9.1 and numpy (bench/peers/run.sh sets up both). Python 3.11.
"""

from __future__ import annotations

import argparse
import csv
import functools
import hashlib
import importlib.util
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
# This file is itself named mitsuba.py: drop its folder from the path so that `import mitsuba`
# finds the package, not this script.
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != HERE]

import numpy as np  # noqa: E402

try:
    import drjit as dr  # noqa: E402
    import mitsuba as mi  # noqa: E402
except ImportError as e:
    sys.exit(f"error: {e}; run bench/peers/run.sh, which installs mitsuba==3.9.1 and numpy in a venv")

ROOT = HERE.parent.parent
CBOX = ROOT / "examples" / "cornell-box.xml"
SHOWCASE = HERE / "showcase.xml"
# The scene compared: "cbox" or "showcase" (set once by main from --scene).
SCENE_NAME = "cbox"
OUT = ROOT / "target" / "peers"
LUCENT = ROOT / "target" / "release" / "lucent"
LLVM = "llvm_ad_rgb"
SCALAR = "scalar_rgb"
# Lanes in one Mitsuba pass of the multi-pass references (bounds the LLVM wavefront's memory).
PASS_LANES = 1 << 24


# --------------------------------------------------------------------------------------------
# The scene and its variants


@functools.cache
def base_text() -> str:
    """The compared scene's XML as both renderers read it: the Cornell box's file, or the
    showcase's with its mesh (made on first use), texture and sky as absolute paths."""
    if SCENE_NAME == "cbox":
        return CBOX.read_text()
    spec = importlib.util.spec_from_file_location("spot_mesh", HERE / "spot_mesh.py")
    spot_mesh = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(spot_mesh)
    data = spot_mesh.data_dir()
    mesh = OUT / "scenes" / "spot-2.obj"
    if not mesh.exists():
        if not (data / "meshes" / "spot.obj").exists():
            sys.exit(f"error: {data}/meshes/spot.obj not found: the showcase needs ../shared/data "
                     "(or LUCENT_DATA)")
        print(f"showcase: {rel(mesh)}: {spot_mesh.write(mesh, 2)} triangles", flush=True)
    texture = data / "gltf" / "CesiumMilkTruck" / "glTF" / "CesiumMilkTruck.png"
    text = SHOWCASE.read_text()
    for token, path in [("@MESH@", mesh), ("@TEXTURE@", texture), ("@SKY@", ROOT / "examples" / "sky.hdr")]:
        text = text.replace(token, str(path.resolve()))
    return text


def scene_text(width: int, height: int, rfilter: str) -> str:
    """The compared scene's XML with another resolution and pixel filter (spp is given at render)."""
    text = base_text()
    for pattern, value in [
        (r'(<integer name="width" value=")\d+(")', width),
        (r'(<integer name="height" value=")\d+(")', height),
        (r'(<rfilter type=")\w+(")', rfilter),
    ]:
        text, n = re.subn(pattern, rf"\g<1>{value}\g<2>", text)
        if n != 1:
            sys.exit(f"error: the {SCENE_NAME} scene does not have exactly one match for {pattern}")
    return text


def scene_file(width: int, height: int, rfilter: str) -> Path:
    """The committed scene itself when nothing changes, else a modified copy under target/peers."""
    text = scene_text(width, height, rfilter)
    if SCENE_NAME == "cbox" and text == CBOX.read_text():
        return CBOX
    stem = "cornell-box" if SCENE_NAME == "cbox" else SCENE_NAME
    path = OUT / "scenes" / f"{stem}-{width}x{height}-{rfilter}.xml"
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)
    return path


def scene_hash(width: int, height: int, rfilter: str) -> str:
    return hashlib.sha256(scene_text(width, height, rfilter).encode()).hexdigest()[:16]


def load(variant: str, width: int, height: int, rfilter: str):
    mi.set_variant(variant)
    return mi.load_file(str(scene_file(width, height, rfilter)))


# --------------------------------------------------------------------------------------------
# Mitsuba renders


def render(scene, spp: int, seed: int) -> tuple[np.ndarray, float]:
    """One Mitsuba render: the image (H x W x 3, float32, linear) and its wall time in seconds.

    JIT variants trace lazily: the time runs until the image is evaluated and copied out."""
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    arr = np.array(img, dtype=np.float32)
    return arr, time.perf_counter() - t0


def render_passes(scene, width: int, height: int, spp: int, seed: int) -> tuple[np.ndarray, float, int]:
    """A high-spp render as the mean of equal passes (seeds seed, seed+1, …) of at most
    PASS_LANES samples each; the image, the total wall time, and the spp of one pass."""
    per_pass = max(1, min(spp, PASS_LANES // (width * height)))
    while spp % per_pass:
        per_pass -= 1
    passes = spp // per_pass
    acc = np.zeros((height, width, 3), np.float64)
    total = 0.0
    for k in range(passes):
        img, t = render(scene, per_pass, seed + k)
        acc += img
        total += t
        print(f"    pass {k + 1}/{passes}: {per_pass} spp, {t:.1f} s", file=sys.stderr, flush=True)
    return (acc / passes).astype(np.float32), total, per_pass


# --------------------------------------------------------------------------------------------
# Images


def read_exr(path: Path) -> np.ndarray:
    """An EXR (or any image Mitsuba reads) as linear float32 RGB, H x W x 3."""
    bmp = mi.Bitmap(str(path))
    if bmp.pixel_format() != mi.Bitmap.PixelFormat.RGB or bmp.component_format() != mi.Struct.Type.Float32:
        bmp = bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    return np.array(bmp, dtype=np.float32)


def write_exr(path: Path, img: np.ndarray) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32)).write(str(path))


def write_pfm(path: Path, img: np.ndarray) -> None:
    """Portable Float Map: `PF`, size, -1.0 (little-endian), float32 RGB rows bottom to top."""
    h, w, _ = img.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{w} {h}\n-1.0\n".encode("ascii"))
        f.write(np.ascontiguousarray(img[::-1], dtype="<f4").tobytes())


def write_png(path: Path, img: np.ndarray) -> None:
    """An sRGB 8-bit preview."""
    bmp = mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32))
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(str(path))


def errors(img: np.ndarray, ref: np.ndarray) -> dict[str, float]:
    if img.shape != ref.shape:
        raise ValueError(f"image is {img.shape[1]}x{img.shape[0]}, reference {ref.shape[1]}x{ref.shape[0]}")
    a = img.astype(np.float64)
    b = ref.astype(np.float64)
    d2 = (a - b) ** 2
    mse = float(d2.mean())
    return {
        "rel_mse": float((d2 / (b * b + 1e-2)).mean()),
        "mse": mse,
        "mse_over_mean2": mse / float(b.mean()) ** 2,
    }


# --------------------------------------------------------------------------------------------
# References (rendered once, reused while their description matches)


@dataclass
class Reference:
    name: str  # file stem under target/peers
    width: int
    height: int
    spp: int
    rfilter: str
    seed: int  # of the first pass

    @property
    def exr(self) -> Path:
        return OUT / f"{self.name}.exr"

    @property
    def meta(self) -> Path:
        return OUT / f"{self.name}.json"

    def describe(self) -> dict:
        return {
            "renderer": f"mitsuba {mi.MI_VERSION} {LLVM}",
            "width": self.width,
            "height": self.height,
            "spp": self.spp,
            "rfilter": self.rfilter,
            "seed": self.seed,
            "scene_sha256": scene_hash(self.width, self.height, self.rfilter),
        }

    def get(self, threads: int, force: bool = False) -> tuple[np.ndarray, dict]:
        """The reference image and its metadata, rendering it unless a matching one exists."""
        want = self.describe()
        if self.exr.exists() and not force:
            img = read_exr(self.exr)
            meta = json.loads(self.meta.read_text()) if self.meta.exists() else None
            if meta is None:
                if img.shape == (self.height, self.width, 3):
                    print(f"reference: reusing {rel(self.exr)} (no {self.meta.name}: not checked)")
                    return img, {**want, "wall_s": float("nan")}
            elif all(meta.get(k) == v for k, v in want.items()):
                print(f"reference: reusing {rel(self.exr)} ({self.spp} spp, rendered in {meta['wall_s']:.1f} s)")
                return img, meta
            print(f"reference: {rel(self.exr)} does not match {want}; rendering it again")
        print(f"reference: rendering {rel(self.exr)}: Mitsuba {LLVM}, {self.width}x{self.height}, "
              f"{self.spp} spp, {self.rfilter} filter, {threads} threads", flush=True)
        scene = load(LLVM, self.width, self.height, self.rfilter)
        img, wall, per_pass = render_passes(scene, self.width, self.height, self.spp, self.seed)
        write_exr(self.exr, img)
        meta = {**want, "wall_s": wall, "spp_per_pass": per_pass, "threads": threads,
                "date": time.strftime("%Y-%m-%d %H:%M:%S")}
        self.meta.write_text(json.dumps(meta, indent=2) + "\n")
        print(f"reference: wrote {rel(self.exr)} in {wall:.1f} s "
              f"({self.width * self.height * self.spp / wall / 1e6:.2f} M samples/s)")
        return img, meta


def reference_256(rfilter: str) -> Reference:
    name = f"{SCENE_NAME}-256-ref" if rfilter == "gaussian" else f"{SCENE_NAME}-256-{rfilter}-ref"
    return Reference(name, 256, 256, 4096, rfilter, seed=1_000_000)


# --------------------------------------------------------------------------------------------
# lucent


class LucentError(Exception):
    pass


@dataclass
class LucentRun:
    image: np.ndarray
    wall_s: float  # of the whole process: start, scene load, render, EXR write
    spp: str | None  # as lucent's summary line gives it: "64", or "37..38" in a time limit
    samples: int | None  # camera rays, one per sample
    render_s: float | None  # the render time lucent reports
    stdout: str


def parse_summary(text: str) -> tuple[str | None, int | None, float | None]:
    """spp, camera rays and seconds from lucent's summary line
    `OUT: W×H, 37..38 spp in the time limit, N rays (camera C, …), S s, …`."""
    spp = re.search(r"(\d+(?:\.\.\d+)?)(?: of \d+)? spp\b", text)
    camera = re.search(r"\bcamera (\d+)", text)
    secs = re.search(r"\), ([\d.]+) s\b", text)
    return (spp.group(1) if spp else None,
            int(camera.group(1)) if camera else None,
            float(secs.group(1)) if secs else None)


def run_lucent(lucent: Path, scene: Path, args: list[str], threads: int, out: Path) -> LucentRun:
    cmd = [str(lucent), "render", str(scene), "--integrator", "path", *args,
           "-o", str(out), "--threads", str(threads)]
    out.unlink(missing_ok=True)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    if proc.returncode != 0 or not out.exists():
        raise LucentError(f"`{' '.join(cmd)}` failed (exit {proc.returncode}):\n"
                          f"{(proc.stderr or proc.stdout).strip()}")
    spp, samples, secs = parse_summary(proc.stdout)
    return LucentRun(read_exr(out), wall, spp, samples, secs, proc.stdout)


def check_lucent(lucent: Path, scene: Path, threads: int) -> None:
    """Fail early, before the long renders, when lucent is missing or lacks a flag we use."""
    if not lucent.is_file():
        sys.exit(f"error: {rel(lucent)} is missing. Build it first (cargo build --release -p lucent-cli),\n"
                 "or pass --mitsuba-only to measure Mitsuba alone.")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "probe.exr"
        for args in (["--spp", "1"], ["--time-limit", "0.05"]):
            try:
                run_lucent(lucent, scene, ["--width", "16", "--height", "16", *args], threads, out)
            except LucentError as e:
                sys.exit(f"error: lucent cannot run the comparison's renders "
                         f"(they use `--integrator path`, `--spp` and `--time-limit`):\n{e}")


# --------------------------------------------------------------------------------------------
# The table


@dataclass
class Row:
    renderer: str
    spp: str | None  # None: not known
    samples: int | None  # in the whole image; None: not known
    wall_s: float
    err: dict[str, float]
    note: str = ""
    time_limit_s: float | None = None
    reported_s: float | None = None  # lucent's own render time

    @property
    def msamples(self) -> float | None:
        return None if self.samples is None else self.samples / self.wall_s / 1e6


COLUMNS = ["renderer", "spp", "wall s", "M samples/s", "relMSE", "MSE", "note"]


def print_table(rows: list[Row]) -> None:
    body = [[r.renderer, r.spp or "?", f"{r.wall_s:.3f}",
             "?" if r.msamples is None else f"{r.msamples:.2f}",
             f"{r.err['rel_mse']:.3e}", f"{r.err['mse']:.3e}", r.note] for r in rows]
    widths = [max(len(x) for x in col) for col in zip(COLUMNS, *body)]

    def line(cells: list[str]) -> str:
        return "  ".join(c.ljust(w) if i in (0, 6) else c.rjust(w)
                         for i, (c, w) in enumerate(zip(cells, widths))).rstrip()

    print(line(COLUMNS))
    print(line(["-" * w for w in widths]))
    for cells in body:
        print(line(cells))


def write_csv(path: Path, rows: list[Row], width: int, height: int, rfilter: str, threads: int) -> None:
    def num(v: float | None, f: str) -> str:
        return "" if v is None else format(v, f)

    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["renderer", "spp", "wall_s", "msamples_per_s", "rel_mse", "mse", "mse_over_mean2",
                    "time_limit_s", "reported_render_s", "samples", "width", "height", "rfilter",
                    "threads", "note"])
        for r in rows:
            w.writerow([r.renderer, r.spp or "", f"{r.wall_s:.4f}", num(r.msamples, ".4f"),
                        f"{r.err['rel_mse']:.6e}", f"{r.err['mse']:.6e}", f"{r.err['mse_over_mean2']:.6e}",
                        num(r.time_limit_s, ".4f"), num(r.reported_s, ".4f"),
                        "" if r.samples is None else r.samples, width, height, rfilter, threads, r.note])


# --------------------------------------------------------------------------------------------
# Commands


def compare(a: argparse.Namespace) -> None:
    w = h = 256
    scene = scene_file(w, h, a.rfilter)
    if not a.mitsuba_only:
        check_lucent(a.lucent, scene, a.threads)
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; "
          f"Mitsuba {mi.MI_VERSION}, {a.threads} threads; scene {rel(scene)} at {w}x{h}, "
          f"{a.rfilter} filter")
    reference = reference_256(a.rfilter)
    ref, ref_meta = reference.get(a.threads, force=a.rerender_ref)

    rows: list[Row] = []
    for spp in a.spp:
        walls: dict[str, float] = {}
        for variant in (SCALAR, LLVM):
            sc = load(variant, w, h, a.rfilter)
            notes = []
            if variant == LLVM:
                # Same size and seed as the timed renders, so that they find its kernels cached.
                _, cold = render(sc, spp, seed=0)
                notes.append(f"after a warm-up render: JIT excluded (warm-up {cold:.2f} s)")
            times = []
            for _ in range(a.repeat):
                img, t = render(sc, spp, seed=0)
                times.append(t)
            if a.repeat > 1:
                notes.append(f"median of {a.repeat}")
            walls[variant] = statistics.median(times)
            rows.append(Row(f"mitsuba {variant}", str(spp), w * h * spp, walls[variant],
                            errors(img, ref), "; ".join(notes)))
            print(f"  mitsuba {variant:11s} {spp:5d} spp: {walls[variant]:.3f} s", flush=True)
            if a.keep_images:
                write_exr(OUT / f"mitsuba-{SCENE_NAME}-{variant}-{spp}spp.exr", img)
        if a.mitsuba_only:
            continue

        runs = [(["--time-limit", f"{walls[v]:.3f}"], f"equal time: mitsuba {v} at {spp} spp", walls[v])
                for v in (SCALAR, LLVM)]
        runs.append((["--spp", str(spp)], "equal samples", None))
        for args, note, limit in runs:
            tag = f"{spp}spp" if limit is None else f"{limit:.3f}s"
            out = OUT / f"lucent-{SCENE_NAME}-{tag}.exr"
            try:
                run = run_lucent(a.lucent, scene, args, a.threads, out)
            except LucentError as e:
                sys.exit(f"error: {e}")
            if limit is None:  # equal samples: known even if lucent's summary line changes
                run.spp, run.samples = run.spp or str(spp), run.samples or w * h * spp
            rows.append(Row("lucent path", run.spp, run.samples, run.wall_s, errors(run.image, ref),
                            note + " (wall of the process)", limit, run.render_s))
            print(f"  lucent {' '.join(args)}: {run.wall_s:.3f} s, {run.spp or '?'} spp", flush=True)
            if not a.keep_images:
                out.unlink(missing_ok=True)

    print()
    print(f"reference: {rel(reference.exr)} (Mitsuba {LLVM}, {ref_meta['spp']} spp, {a.rfilter} filter). "
          "Errors over all pixels and channels: relMSE = mean((a-b)^2/(b^2+1e-2)), MSE = mean((a-b)^2).")
    print_table(rows)
    csv_path = OUT / ("mitsuba.csv" if SCENE_NAME == "cbox" else f"mitsuba-{SCENE_NAME}.csv")
    write_csv(csv_path, rows, w, h, a.rfilter, a.threads)
    print(f"\nwrote {rel(csv_path)} (also MSE/mean(ref)^2, lucent's own render time, samples)")


def refs(a: argparse.Namespace) -> None:
    """The references to keep, and the noise floor of the small one."""
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; "
          f"Mitsuba {mi.MI_VERSION} {LLVM}, {a.threads} threads")
    big, big_meta = reference_256("gaussian").get(a.threads, a.force)
    small = Reference("cbox-64-ref", 64, 64, 65536, "gaussian", seed=2_000_000)
    other = Reference("cbox-64-ref-seed2", 64, 64, 65536, "gaussian", seed=3_000_000)
    box = Reference("cbox-64-box-ref", 64, 64, 65536, "box", seed=4_000_000)
    results = {}
    for r in (small, other, box):
        img, meta = r.get(a.threads, a.force)
        results[r.name] = (img, meta)
    for r in (small, box):
        write_pfm(OUT / f"{r.name}.pfm", results[r.name][0])
        write_png(OUT / f"{r.name}.png", results[r.name][0])
    write_png(OUT / "cbox-256-ref.png", big)

    print("\nreference wall times (Mitsuba llvm_ad_rgb, JIT included):")
    for name, meta in [("cbox-256-ref", big_meta)] + [(k, m) for k, (_, m) in results.items()]:
        n = meta["width"] * meta["height"] * meta["spp"]
        print(f"  {name:18s} {meta['width']}x{meta['height']} {meta['spp']:6d} spp: "
              f"{meta['wall_s']:7.1f} s = {n / meta['wall_s'] / 1e6:.2f} M samples/s")
    e = errors(results[other.name][0], results[small.name][0])
    print(f"\nnoise floor, {other.name} against {small.name} (two seeds, 65536 spp each):")
    print(f"  relMSE {e['rel_mse']:.3e}   MSE {e['mse']:.3e}   MSE/mean^2 {e['mse_over_mean2']:.3e}")
    print("  (each image's own error against the limit is about half of these)")
    f = errors(results[box.name][0], results[small.name][0])
    print(f"box against gaussian filter, 64x64: relMSE {f['rel_mse']:.3e}   MSE {f['mse']:.3e}   "
          f"MSE/mean^2 {f['mse_over_mean2']:.3e}")


def rel(p: Path) -> str:
    try:
        return str(p.resolve().relative_to(ROOT))
    except ValueError:
        return str(p)


def main() -> None:
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--threads", type=int, default=2, help="render threads, for every renderer (default 2)")
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", metavar="{compare,refs}")
    c = sub.add_parser("compare", parents=[common], help="the comparison table (the default command)")
    c.add_argument("--scene", choices=["cbox", "showcase"], default="cbox",
                   help="the Cornell box (default) or the showcase (textured 94k-triangle mesh, glass, "
                        "rough gold, environment map)")
    c.add_argument("--spp", type=int, nargs="+", default=[16, 64, 256], help="sample counts (default 16 64 256)")
    c.add_argument("--rfilter", choices=["gaussian", "box"], default="gaussian",
                   help="the pixel filter written into the scene both render (default gaussian, as in the file)")
    c.add_argument("--repeat", type=int, default=1, help="timed renders per cell; their median (default 1)")
    c.add_argument("--lucent", type=lambda s: Path(s).resolve(), default=LUCENT,
                   help=f"lucent binary (default {rel(LUCENT)})")
    c.add_argument("--mitsuba-only", action="store_true", help="skip lucent (the Mitsuba rows alone)")
    c.add_argument("--keep-images", action="store_true", help="keep every render's EXR under target/peers")
    c.add_argument("--rerender-ref", action="store_true", help="render the reference even if present")
    r = sub.add_parser("refs", parents=[common], help="render the references to keep (64x64, noise floor, box filter)")
    r.add_argument("--force", action="store_true", help="render every reference again, even those present")
    argv = sys.argv[1:]
    if not any(x in ("compare", "refs", "-h", "--help") for x in argv):
        argv = ["compare", *argv]  # the default command
    a = p.parse_args(argv)
    global SCENE_NAME
    SCENE_NAME = getattr(a, "scene", "cbox")

    OUT.mkdir(parents=True, exist_ok=True)
    mi.set_variant(LLVM if LLVM in mi.variants() else SCALAR)  # Bitmap I/O needs a variant
    dr.set_thread_count(a.threads)
    mi.set_log_level(mi.LogLevel.Warn)
    if LLVM not in mi.variants():
        sys.exit(f"error: this Mitsuba has no {LLVM} variant")
    try:
        if a.command == "refs":
            refs(a)
        else:
            compare(a)
    except RuntimeError as e:
        if "LLVM" in str(e) and "DRJIT_LIBLLVM_PATH" not in os.environ:
            sys.exit(f"error: {e}\nMitsuba's LLVM variant needs libLLVM: apt-get install -y libllvm19 and "
                     "DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so (run.sh sets it)")
        raise


if __name__ == "__main__":
    main()
