"""Side-by-side timing against POV-Ray 3.7 on the scenes of whitted_scenes.py, one thread.

    apt-get install -y --no-install-recommends povray
    cargo build --release
    python3 benches/peers/povray.py [--runs 7] [--scenes whitted,glass] [--threads 1]

For each scene, runs alternate between the two renderers. POV-Ray is timed by its own printed
"Trace Time" (parse, bounding and start-up excluded); raytracer by its whole process (scene load,
BVH build, render and PNG encode included), and by the render time it prints (load, build and
encode excluded: the part that compares with POV-Ray's Trace Time). Prints medians and the ratios
raytracer / POV-Ray as a Markdown table, then their spread over the scenes; `--adc` also runs both
with POV-Ray's default adc_bailout (1/255) in place of the full ray tree. Not run by CI: a
benchmark, never a test.
"""

import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import whitted_scenes  # noqa: E402

TRACE_TIME = re.compile(r"Trace Time:.*\(([0-9.]+) seconds\)")
RAYS = re.compile(r" ([0-9]+) rays")
RENDER = re.compile(r", ([0-9.]+) s \(build")


def pov_time(pov, out, size, threads, bailout):
    cmd = ["povray", "+I" + pov, "+O" + out, "+W%d" % size, "+H%d" % size, "-A", "-D",
           "+WT%d" % threads, "+L" + os.path.join(ROOT, "textures"), "+FN", "File_Gamma=1.0",
           "Bounding_Threshold=1"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = TRACE_TIME.search(r.stderr + r.stdout)
    if r.returncode != 0 or not m:
        sys.exit("povray failed on %s:\n%s" % (pov, r.stderr[-2000:]))
    return float(m.group(1))


def our_time(binary, scene, out, threads, extra):
    cmd = [binary, scene, out, "--threads", str(threads)] + extra
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit("raytracer failed on %s:\n%s" % (scene, r.stderr[-2000:]))
    m, t = RAYS.search(r.stderr), RENDER.search(r.stderr)
    return dt, int(m.group(1)) if m else 0, float(t.group(1)) if t else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--scenes", default=",".join(whitted_scenes.SCENES))
    ap.add_argument("--raytracer", default=os.path.join(ROOT, "target", "release", "raytracer"))
    ap.add_argument("--baseline", help="another raytracer binary (an older build) timed in the same runs")
    ap.add_argument("--adc", action="store_true",
                    help="POV-Ray's default adc_bailout 1/255 on both sides (ours: --adc-bailout)")
    args = ap.parse_args()

    tmp = tempfile.mkdtemp(prefix="povray-peer-")
    whitted_scenes.write_all(tmp)
    rows = []
    for name in args.scenes.split(","):
        s = whitted_scenes.SCENES[name]
        pov = os.path.join(tmp, name + ".pov")
        if not args.adc:
            # Both prune rays below 1/255 by default; adc_bailout 0 traces the full tree (ours:
            # --adc-bailout 0, which older builds, timed with --baseline, take too).
            with open(pov) as f:
                text = f.read()
            text = text.replace("global_settings {", "global_settings { adc_bailout 0", 1)
            with open(pov, "w") as f:
                f.write(text)
        extra = ["--adc-bailout", str(1 / 255) if args.adc else "0"]
        # Point the JSON's texture paths at the repository's textures from the temporary folder.
        scene = os.path.join(tmp, name + ".json")
        with open(scene) as f:
            text = f.read().replace("../../../textures/", os.path.join(ROOT, "textures") + "/")
        with open(scene, "w") as f:
            f.write(text)
        ours, traced, theirs, base, rays = [], [], [], [], 0
        for _ in range(args.runs):
            dt, rays, trace = our_time(args.raytracer, scene, os.path.join(tmp, name + ".png"),
                                       args.threads, extra)
            ours.append(dt)
            traced.append(trace)
            if args.baseline:
                base.append(our_time(args.baseline, scene, os.path.join(tmp, name + "-base.png"),
                                     args.threads, extra)[0])
            theirs.append(pov_time(pov, os.path.join(tmp, name + "-pov.png"), s["size"], args.threads,
                                   args.adc))
        a, b = statistics.median(ours), statistics.median(theirs)
        t = statistics.median(traced)
        c = statistics.median(base) if base else None
        rows.append((name, rays, a, t, b, c))
        print("%s: raytracer %.3f s (render %.3f s), POV-Ray %.3f s, ratio %.2f (%.2f)"
              % (name, a, t, b, a / b, t / b), file=sys.stderr)
    head = "| scene | rays (ours) | raytracer s | render s | POV-Ray trace s | ratio | render ratio |"
    rule = "|---|---:|---:|---:|---:|---:|---:|"
    if args.baseline:
        head += " baseline s | baseline ratio |"
        rule += "---:|---:|"
    print(head)
    print(rule)
    for name, rays, a, t, b, c in rows:
        line = "| %s | %d | %.3f | %.3f | %.3f | %.2f× | %.2f× |" % (name, rays, a, t, b, a / b, t / b)
        if c is not None:
            line += " %.3f | %.2f× |" % (c, c / b)
        print(line)
    for label, k in (("ratio", 2), ("render ratio", 3)):
        r = sorted(row[k] / row[4] for row in rows)
        gm = math.exp(sum(math.log(x) for x in r) / len(r))
        print("\n%s over %d scenes: median %.2f×, geometric mean %.2f×, range %.2f–%.2f×"
              % (label, len(r), statistics.median(r), gm, r[0], r[-1]), end="")
    print()


if __name__ == "__main__":
    main()
