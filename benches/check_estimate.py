#!/usr/bin/env python3
"""How good `raytracer check`'s time estimate is: for each scene, the estimate against the
wall-clock time of the render it describes (same flags, same threads), as the ratio
real / estimate. Scenes: the bundled ones and a seeded sample of the corpora.

    cargo build --release
    python3 benches/check_estimate.py [--corpus 20] [--threads 2] [--seed 1]
"""
import argparse
import glob
import json
import os
import random
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "coursework")


def corpus_files(n, seed):
    files = sorted(glob.glob(os.path.join(SHARED, "corpus", "*.json")))
    files += sorted(glob.glob(os.path.join(SHARED, "corpus2", "scenes", "*.json")))
    random.Random(seed).shuffle(files)
    return files[:n]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--raytracer", default=os.path.join(ROOT, "target", "release", "raytracer"))
    ap.add_argument("--corpus", type=int, default=20, help="corpus files to sample")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120, help="skip renders longer than this")
    args = ap.parse_args()
    scenes = sorted(glob.glob(os.path.join(ROOT, "scenes", "*.json")))
    scenes += corpus_files(args.corpus, args.seed)
    threads = ["--threads", str(args.threads)]
    ratios = []
    print("| scene | estimate s | render s | render / estimate |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as out:
        for scene in scenes:
            check = subprocess.run([args.raytracer, "check", scene, "--json"] + threads,
                                   capture_output=True, text=True)
            report = json.loads(check.stdout or "[{}]")[0]
            estimate = (report.get("estimate") or {}).get("seconds")
            if estimate is None:
                continue  # the scene does not load: nothing to estimate
            start = time.perf_counter()
            try:
                r = subprocess.run([args.raytracer, scene, os.path.join(out, "o.png"), "--quiet"]
                                   + threads, capture_output=True, timeout=args.timeout)
            except subprocess.TimeoutExpired:
                print("| %s | %.3f | > %.0f | — |" % (os.path.basename(scene), estimate, args.timeout))
                continue
            real = time.perf_counter() - start
            if r.returncode != 0:
                continue
            ratios.append(real / estimate)
            print("| %s | %.3f | %.3f | %.2f |" % (os.path.basename(scene), estimate, real, real / estimate))
    if ratios:
        q = statistics.quantiles(ratios, n=20) if len(ratios) > 1 else ratios
        print("\n%d scenes: render / estimate median %.2f, min %.2f, max %.2f, 5%%–95%% %.2f–%.2f"
              % (len(ratios), statistics.median(ratios), min(ratios), max(ratios), q[0], q[-1]))


if __name__ == "__main__":
    main()
