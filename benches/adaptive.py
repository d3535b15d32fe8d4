#!/usr/bin/env python3
"""Adaptive against uniform sampling at equal error.

For each scene: a high-spp reference (EXR); uniform renders at several spp and adaptive renders
(--adaptive, --spp MAX) at several noise thresholds, each timed (whole process, one thread,
median of --runs) and scored by the MSE of its linear EXR against the reference. The uniform
runs give time as a function of MSE (interpolated in log-log); each adaptive run's time is
divided by the uniform time at its MSE: the equal-error time ratio (below 1: adaptive wins).

  python3 benches/adaptive.py [--runs 1] [--max-spp 256]
                              [--scenes penumbra,thinlens,arealight,cornell]
                              [--bin target/release/raytracer] [--also BIN2,BIN3]
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

# The Whitted scenes' thresholds; a path-traced image is far noisier, and at these every pixel
# of it would run to the cap (docs/adaptive.md), so it takes thresholds of its own.
THRESHOLDS = [0.04, 0.02, 0.01, 0.005]
SCENES = [
    # (name, scene file, extra flags, reference spp, thresholds)
    ("penumbra (area light)", "scenes/penumbra.json", [], 4096, THRESHOLDS),
    ("thinlens (depth of field)", "scenes/thinlens.json", ["--width", "160"], 4096, THRESHOLDS),
    ("arealight_jittered (area light)", "scenes/arealight_jittered.json", ["--width", "160"],
     4096, THRESHOLDS),
    ("cornell (path tracing)", "scenes/cornell.json", ["--width", "128"], 4096,
     [0.64, 0.32, 0.16, 0.08]),
]


def run(bin_, scene, out, flags, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run([bin_, scene, out, "--quiet", "--threads", "1", *flags], check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def mse(bin_, ref, test):
    out = subprocess.run([bin_, "compare", ref, test], check=True, capture_output=True,
                         text=True).stdout
    return float(out.split()[1])


def interp_time(curve, e):
    """Uniform time at MSE e, log-log interpolation (or extrapolation) between neighbours."""
    pts = sorted(curve)  # (mse, time), ascending mse
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if e0 <= e <= e1 or (e < pts[0][0] and (e0, t0) == pts[0]) or \
                (e > pts[-1][0] and (e1, t1) == pts[-1]):
            w = (math.log(e) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0)))
    return float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--bin", default="target/release/raytracer")
    ap.add_argument("--max-spp", type=int, default=256,
                    help="adaptive cap; uniform runs go from 8 up to it, doubling")
    ap.add_argument("--scenes", default="penumbra,thinlens,arealight,cornell")
    ap.add_argument("--also", default="",
                    help="other binaries, comma-separated, whose adaptive rows are measured in "
                         "the same run (against the first one's uniform curve)")
    a = ap.parse_args()
    uniform = [n for n in (2 ** k for k in range(3, 21)) if n <= a.max_spp]
    wanted = a.scenes.split(",")
    bin_ = os.path.abspath(a.bin)
    with tempfile.TemporaryDirectory() as d:
        for name, scene, extra, ref_spp, thresholds in SCENES:
            if not any(w in scene for w in wanted):
                continue
            ref = os.path.join(d, "ref.exr")
            subprocess.run([bin_, scene, ref, "--quiet", "--spp", str(ref_spp), *extra],
                           check=True)
            curve = []
            print(f"\n{name}: reference {ref_spp} spp; one thread, median of {a.runs}")
            print("| render | seconds | MSE | uniform time at that MSE | ratio |")
            print("|---|---:|---:|---:|---:|")
            out = os.path.join(d, "out.exr")
            for spp in uniform:
                t = run(bin_, scene, out, ["--spp", str(spp), *extra], a.runs)
                e = mse(bin_, ref, out)
                curve.append((e, t))
                print(f"| uniform {spp} spp | {t:.3f} | {e:.3e} | | |")
            others = [b for b in a.also.split(",") if b]
            bins = [("", bin_)] + [(f" ({os.path.basename(b)})", os.path.abspath(b))
                                   for b in others]
            for th in thresholds:
                for label, b in bins:
                    flags = ["--spp", str(a.max_spp), "--adaptive", "--noise-threshold", str(th),
                             *extra]
                    t = run(b, scene, out, flags, a.runs)
                    e = mse(bin_, ref, out)
                    tu = interp_time(curve, e)
                    print(f"| adaptive ≤{a.max_spp} spp, T = {th}{label} | {t:.3f} | {e:.3e} "
                          f"| {tu:.3f} | {t / tu:.2f}× |")
            sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
