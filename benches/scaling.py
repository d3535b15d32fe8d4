"""How close two threads come to the machine's ceiling, the throughput of two independent
single-threaded renders at once (which shares caches, memory and clock with the two-thread
render, so it isolates what the renderer loses to splitting one image).

    cargo build --release
    python3 benches/scaling.py [--runs 5] [--raytracer BIN]

For each scene: the median wall time of one render on one thread (t1), of one render on two
threads (t2), and of two one-thread renders started together (tc, until both end). Efficiency is
(1 / t2) / (2 / tc) = tc / (2 · t2): 100% when two threads render one image as fast as two workers
render two. Runs alternate between the three. A benchmark, never a test: run it on an idle machine.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# (name, scene, extra flags): sized so that start-up and scene load are a small part of a run.
SCENES = [
    ("cornell (path)", "scenes/cornell.json", ["--integrator", "path", "--spp", "16", "--width", "160"]),
    ("whitted", "benches/peers/scenes/whitted.json", ["--width", "768"]),
    ("glass", "benches/peers/scenes/glass.json", ["--width", "1024"]),
    ("lights", "benches/peers/scenes/lights.json", ["--width", "512"]),
    ("thinlens", "benches/peers/scenes/thinlens.json", ["--width", "320"]),
]


def command(binary, scene, out, threads, extra, tmp):
    path = os.path.join(ROOT, scene)
    with open(path) as f:
        text = f.read().replace("../../../textures/", os.path.join(ROOT, "textures") + "/")
    local = os.path.join(tmp, os.path.basename(scene))
    with open(local, "w") as f:
        f.write(text)
    # The scene's own folder resolves its assets (meshes, textures) as before.
    return [binary, local, out, "--threads", str(threads), "-q",
            "--asset-dir", os.path.dirname(path)] + extra


def wall(cmds):
    t0 = time.perf_counter()
    procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for c in cmds]
    for p, c in zip(procs, cmds):
        _, err = p.communicate()
        if p.returncode != 0:
            sys.exit("failed: %s\n%s" % (" ".join(c), err.decode()[-2000:]))
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--raytracer", default=os.path.join(ROOT, "target", "release", "raytracer"))
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="raytracer-scaling-")
    print("| scene | 1 thread s | 2 threads s | two 1-thread renders at once s | speed-up | of the ceiling |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, scene, extra in SCENES:
        out = [os.path.join(tmp, "a.png"), os.path.join(tmp, "b.png")]
        one = command(args.raytracer, scene, out[0], 1, extra, tmp)
        two = command(args.raytracer, scene, out[0], 2, extra, tmp)
        pair = [one, command(args.raytracer, scene, out[1], 1, extra, tmp)]
        t1, t2, tc = [], [], []
        for _ in range(args.runs):
            t1.append(wall([one]))
            t2.append(wall([two]))
            tc.append(wall(pair))
        a, b, c = statistics.median(t1), statistics.median(t2), statistics.median(tc)
        print("| %s | %.3f | %.3f | %.3f | %.2f× | %.0f%% |" % (name, a, b, c, a / b, 100 * c / (2 * b)))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
