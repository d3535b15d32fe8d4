"""Ray for ray against Embree 4: the same triangles and the same rays, one thread each, one run.

    pip install embreex            # Embree 4 through its Python binding
    cargo build --release
    python3 benches/peers/embree.py [--runs 5] [--huge] [--quick] [--raytracer BIN]

`raytracer bench --rays --threads 1 --export DIR` measures our BVH on the sphere grids (G=4, S=16:
8,194 triangles; G=16, S=32: 524,290; with --huge G=32, S=64: 8,388,610) and writes each grid's
triangles and ray sets to DIR (`raytracer bench --help`). This script then loads the same files
into Embree (one triangle mesh, default scene flags, build quality medium) and times:

- secondary rays start 1e-5 of the scene's diagonal further along for Embree: it begins every
  ray at tnear = 0, where its own test would hit the surface a ray leaves;
- build: `TriangleMesh(...)` and the scene commit (the first query commits it), median of --runs;
- primary and incoherent rays: closest hit (`run(..., query='INTERSECT')`), shadow rays: any hit
  up to the distance to the light (`query='OCCLUDED'`, tfar = that distance), each the median of
  --runs. embreex traces an array of rays in a compiled loop of single-ray queries
  (rtcIntersect1/rtcOccluded1), so no Python runs per ray.

Both run pinned to one CPU (`os.sched_setaffinity`), in the same invocation, so the ratios hold
even where absolute figures drift. The hit counts of both are printed: they agree to a few rays
in a million (rays through shared edges and grazing hits are where two correct tests can differ).
A benchmark, never a test: CI does not run it. The measured table is in docs/performance.md.

`--instructions` counts instead of timing (needs valgrind): each ray set of the G=4 grid traced
once under callgrind, by Embree (only `rtcIntersect1`/`rtcOccluded1` counted) and by each of our
trees (`cargo build --release --example ray_set`: only its tracing functions counted), printed as
instructions per ray. Counts do not drift with the machine's load as times do. Under valgrind
Embree takes its AVX2 code (valgrind offers no AVX-512), as our eight-wide tree does.
"""

import argparse
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def load(path, width):
    a = np.fromfile(path, dtype="<f4")
    return a.reshape(-1, width)


# The ray sets: name, floats a ray in the exported file, Embree's query.
SETS = (("primary", 6, "INTERSECT"), ("shadow", 7, "OCCLUDED"), ("incoherent", 6, "INTERSECT"))


def load_triangles(prefix):
    return load(prefix + ".tris.f32", 9).reshape(-1, 3, 3).astype(np.float32)


def embree_build(tris):
    """Embree's scene of `tris`, built: the first query commits it."""
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh

    scene = rtcs.EmbreeScene()
    TriangleMesh(scene, tris)
    scene.run(np.zeros((1, 3), np.float32), np.array([[0, 0, 1]], np.float32))
    return scene


def embree_rays(prefix, name, width, tris):
    """Set `name` of grid `prefix` as Embree traces it: origins, directions, and for shadow rays
    the distances to the light (else None)."""
    rays = load("%s.%s.f32" % (prefix, name), width)
    # Embree starts every ray at tnear = 0 and its test is not the one our origins were offset
    # for, so secondary rays would hit the surface they leave. They start a little further along
    # instead (1e-5 of the scene's diagonal), for Embree only.
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    eps = np.float32(1e-5 * np.linalg.norm(hi - lo))
    o = rays[:, 0:3]
    d = np.ascontiguousarray(rays[:, 3:6])
    if name != "primary":
        o = o + eps * d
    o = np.ascontiguousarray(o, dtype=np.float32)
    dists = np.ascontiguousarray(rays[:, 6] - eps) if width == 7 else None
    return o, d, dists


def embree_trace(scene, rays, query):
    o, d, dists = rays
    if dists is None:
        return scene.run(o, d, query=query)
    return scene.run(o, d, dists=dists, query=query)


def embree_grid(prefix, runs):
    tris = load_triangles(prefix)
    builds = []
    scene = None
    for _ in range(runs):
        scene = None
        t0 = time.perf_counter()
        scene = embree_build(tris)
        builds.append(time.perf_counter() - t0)
    out = {"triangles": len(tris), "build_s": statistics.median(builds)}
    for name, width, query in SETS:
        rays = embree_rays(prefix, name, width, tris)
        times = []
        hits = 0
        for _ in range(runs):
            t0 = time.perf_counter()
            r = embree_trace(scene, rays, query)
            times.append(time.perf_counter() - t0)
            # Both queries answer -1 for a miss (the primitive hit, or 0, otherwise).
            hits = int(np.count_nonzero(np.asarray(r) != -1))
        out[name] = {"rays": len(rays[0]), "s": statistics.median(times), "hits": hits}
    return out


def embree_trace_once(prefix, name):
    """Builds grid `prefix` in Embree and traces its set `name` once (run under callgrind)."""
    tris = load_triangles(prefix)
    scene = embree_build(tris)
    width, query = next((w, q) for n, w, q in SETS if n == name)
    embree_trace(scene, embree_rays(prefix, name, width, tris), query)


def callgrind_instructions(cmd, toggles):
    """Instructions callgrind counts inside the functions `toggles` while `cmd` runs."""
    fd, out = tempfile.mkstemp(prefix="raytracer-callgrind-")
    os.close(fd)
    try:
        subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out]
                       + ["--toggle-collect=" + t for t in toggles] + cmd,
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(out) as f:
            for line in f:
                if line.startswith(("summary:", "totals:")):
                    return int(line.split()[1])
    finally:
        os.remove(out)
    raise RuntimeError("callgrind wrote no totals for %s" % " ".join(cmd))


def instructions(args, tmp):
    """Instructions per ray on the G=4 grid, Embree's and each of our trees' (see the docs)."""
    example = os.path.join(os.path.dirname(args.raytracer), "examples", "ray_set")
    if not os.path.exists(example):
        sys.exit("no %s (cargo build --release --example ray_set)" % example)
    cmd = [args.raytracer, "bench", "--rays", "--threads", "1", "--runs", "1", "--export", tmp]
    print("$ " + " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    prefix = os.path.join(tmp, "grid_G4_S16")
    trees = ("sah", "sah4", "sah8", "sah8-baseline")
    print("Instructions per ray (callgrind), G=4, S=16 (8,194 triangles), one query a ray\n")
    print("| set | Embree | " + " | ".join("`%s`" % t for t in trees) + " |")
    print("|---|---:|" + "---:|" * len(trees))
    for name, width, _ in SETS:
        rays = len(load("%s.%s.f32" % (prefix, name), width))
        theirs = callgrind_instructions(
            [sys.executable, os.path.abspath(__file__), "--embree-trace", prefix, name],
            ["rtcIntersect1", "rtcOccluded1"]) / rays
        cells = []
        for tree in trees:
            mine = callgrind_instructions([example, "4", tree, name], ["ray_set::trace*"]) / rays
            cells.append("%.0f (%.2f×)" % (mine, mine / theirs))
        print("| %s | %.0f | %s |" % (name, theirs, " | ".join(cells)))
        sys.stdout.flush()


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--embree-trace":
        embree_trace_once(sys.argv[2], sys.argv[3])
        return
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--raytracer", default=os.path.join(ROOT, "target", "release", "raytracer"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--huge", action="store_true", help="also the 8.4 M-triangle grid (about 3 GB)")
    ap.add_argument("--quick", action="store_true", help="the small smoke grid only")
    ap.add_argument("--cpu", type=int, default=None, help="the CPU both run on (default: the first allowed)")
    ap.add_argument("--instructions", action="store_true",
                    help="instructions per ray under callgrind instead of times (needs valgrind)")
    args = ap.parse_args()
    try:
        import embreex  # noqa: F401
    except ImportError:
        sys.exit("embreex is not installed: pip install embreex")
    if not os.path.exists(args.raytracer):
        sys.exit("no raytracer binary at %s (cargo build --release, or --raytracer)" % args.raytracer)
    cpu = args.cpu if args.cpu is not None else min(os.sched_getaffinity(0))
    os.sched_setaffinity(0, {cpu})
    tmp = tempfile.mkdtemp(prefix="raytracer-embree-")
    if args.instructions:
        try:
            instructions(args, tmp)
        finally:
            shutil.rmtree(tmp)
        return
    ours_csv = os.path.join(tmp, "ours.csv")
    cmd = [args.raytracer, "bench", "--rays", "--threads", "1", "--runs", str(args.runs),
           "--export", tmp, "--csv", ours_csv]
    if args.huge:
        cmd.append("--huge")
    if args.quick:
        cmd.append("--quick")
    print("$ " + " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    ours = {}
    with open(ours_csv) as f:
        for row in csv.DictReader(f):
            # A tree appears once per instruction set its queries were measured with.
            tree = "%s (%s)" % (row["accel"], row.get("simd", "baseline"))
            ours.setdefault(row["grid"], {}).setdefault(tree, {})[row["set"]] = row

    print("Embree 4 (embreex %s) and raytracer, one thread each on CPU %d, medians of %d runs\n"
          % (embreex_version(), cpu, args.runs))
    print("| grid | triangles | set | Embree Mrays/s | raytracer tree | Mrays/s | ratio | hits (ours / Embree) |")
    print("|---|---:|---|---:|---|---:|---:|---|")
    builds = []
    for grid, trees in ours.items():
        g, s = grid[1:].split("S")
        prefix = os.path.join(tmp, "grid_G%s_S%s" % (g, s))
        e = embree_grid(prefix, args.runs)
        for name, _, _ in SETS:
            theirs = e[name]["rays"] / e[name]["s"] / 1e6
            for accel, rows in trees.items():
                r = rows[name]
                mine = float(r["mrays_1t"])
                print("| %s | %d | %s | %.2f | %s | %.2f | %.2f× | %s / %d |"
                      % (grid, e["triangles"], name, theirs, accel, mine, mine / theirs,
                         r["hits"], e[name]["hits"]))
        built = set()
        for rows in trees.values():
            first = next(iter(rows.values()))
            if first["accel"] in built:
                continue  # the same build, measured again with other instructions
            built.add(first["accel"])
            builds.append((grid, first["accel"], float(first["build_ms"]), e["build_s"] * 1e3,
                           float(first["bytes_per_tri"])))
        sys.stdout.flush()
    print("\n| grid | raytracer tree | build ms | Embree build ms | ours / Embree | raytracer bytes per triangle |")
    print("|---|---|---:|---:|---:|---:|")
    for grid, accel, mine, theirs, bpt in builds:
        print("| %s | %s | %.1f | %.1f | %.2f× | %.1f |" % (grid, accel, mine, theirs, mine / theirs, bpt))
    for name in os.listdir(tmp):
        os.remove(os.path.join(tmp, name))
    os.rmdir(tmp)


def embreex_version():
    try:
        from importlib.metadata import version
        return version("embreex")
    except Exception:
        return "?"


if __name__ == "__main__":
    main()
