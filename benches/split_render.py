#!/usr/bin/env python3
"""What splitting a render costs: one process against N tiles as N processes, and the merge.

For a scene, renders (1) the whole image in one process, one thread; (2) each tile of a
COLS×ROWS grid in its own process, one thread, one after another; (3) the merge of the tiles;
(4) the whole image in one process with T threads, and the tiles run T processes at a time
(GNU parallel style). Runs are interleaved and repeated; prints medians and ratios, and checks
that the merged image's bytes equal the whole render's.

  python3 benches/split_render.py [--scene scenes/arealight_jittered.json] [--spp 16]
                                  [--grid 4,4] [--runs 3] [--threads 2] [--bin PATH]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor


def timed(cmd):
    start = time.perf_counter()
    subprocess.run(cmd, check=True)
    return time.perf_counter() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="scenes/arealight_jittered.json")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--grid", default="4,4")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--bin", default="target/release/raytracer")
    a = ap.parse_args()
    cols, rows = (int(v) for v in a.grid.split(","))
    bin_ = os.path.abspath(a.bin)
    scene = os.path.abspath(a.scene)
    common = ["--spp", str(a.spp), "--quiet"]
    times = {k: [] for k in ["whole", "tiles", "merge", "whole_mt", "tiles_mt"]}
    with tempfile.TemporaryDirectory() as d:
        whole = os.path.join(d, "whole.png")
        merged = os.path.join(d, "merged.png")
        cells = [(c, r) for r in range(rows) for c in range(cols)]

        def tile_cmd(c, r):
            out = os.path.join(d, f"tile-{c}-{r}.exr")
            return [bin_, scene, out, "--tile", f"{c},{r}", "--tiles", a.grid,
                    "--threads", "1", *common]

        tiles = [os.path.join(d, f"tile-{c}-{r}.exr") for c, r in cells]
        for _ in range(a.runs):
            times["whole"].append(timed([bin_, scene, whole, "--threads", "1", *common]))
            times["tiles"].append(sum(timed(tile_cmd(c, r)) for c, r in cells))
            times["merge"].append(timed([bin_, "merge", merged, *tiles, "--quiet"]))
            times["whole_mt"].append(
                timed([bin_, scene, whole, "--threads", str(a.threads), *common]))
            start = time.perf_counter()
            with ThreadPoolExecutor(a.threads) as pool:
                list(pool.map(lambda cr: subprocess.run(tile_cmd(*cr), check=True), cells))
            times["tiles_mt"].append(time.perf_counter() - start)
        with open(whole, "rb") as f, open(merged, "rb") as g:
            same = f.read() == g.read()
        tile_bytes = sum(os.path.getsize(t) for t in tiles)
    m = {k: statistics.median(v) for k, v in times.items()}
    n = len(cells)
    print(f"{os.path.basename(scene)}, {a.spp} spp, {cols}×{rows} = {n} tiles, "
          f"median of {a.runs}; merged bytes equal the whole render: {same}")
    print("| what | seconds | against one process |")
    print("|---|---:|---:|")
    print(f"| whole image, 1 process, 1 thread | {m['whole']:.3f} | 1.00× |")
    print(f"| {n} tiles, {n} processes of 1 thread, one after another | {m['tiles']:.3f} "
          f"| {m['tiles'] / m['whole']:.2f}× |")
    print(f"| merge of the {n} tiles ({tile_bytes / 1e6:.1f} MB of EXR) | {m['merge']:.3f} "
          f"| {m['merge'] / m['whole']:.3f}× |")
    print(f"| whole image, 1 process, {a.threads} threads | {m['whole_mt']:.3f} | "
          f"{m['whole_mt'] / m['whole']:.2f}× |")
    print(f"| {n} tiles, {a.threads} processes at a time, + merge | "
          f"{m['tiles_mt'] + m['merge']:.3f} | {(m['tiles_mt'] + m['merge']) / m['whole']:.2f}× |")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
