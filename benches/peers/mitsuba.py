"""Path tracing against Mitsuba 3: bias, noise at equal spp and time to equal error, one thread.

    pip install mitsuba            # the Python API only
    apt-get install libllvm19      # for --variant llvm_ad_rgb, Mitsuba's vectorised CPU variant
    cargo build --release
    python3 benches/peers/mitsuba.py [--scenes cornell,pt_pointlights] [--size 128] [--runs 3]
                                     [--variant scalar_rgb|llvm_ad_rgb] [--sampler independent|ldsampler|...]
                                     [--raytracer BIN] [--ref-spp 4096] [--ladder 4,8,...,256]

Each scene is converted to a Mitsuba scene dictionary (`convert`), which maps exactly the subset
of the CGR scene format that both renderers define the same way and refuses anything else:

    diffuse  kd·diffusecolor/π                    -> twosided diffuse, reflectance kd·diffusecolor
    mirror   isreflective, reflectivity r, kd=ks=0 -> twosided conductor "none", specular_reflectance r
    glass    isrefractive, refractiveindex η, kd=ks=0 (spheres only) -> dielectric int_ior η, ext_ior 1
    point light, intensity I                       -> point emitter, intensity π·I (inverse square)
    quad area light, intensity I, area A, normal n -> rectangle (parallelogram mesh if sheared) with a
                                                      one-sided area emitter of radiance π·I/A on the
                                                      side of n, and a black BSDF (it reflects nothing)
    backgroundcolor c                              -> constant emitter of radiance c (none if black)
    nbounces N                                     -> path integrator, max_depth N + 2, default rr_depth
    camera (CGR pinhole)                           -> perspective, fov_axis y, look_at; hdrfilm, box
                                                      filter, rgb. CGR images have right = up × forward,
                                                      Mitsuba's forward × up: its image is mirrored
                                                      left-right before any comparison

Per scene it then measures:

1. references: Mitsuba (independent sampler) and ours at --ref-spp each, as --chunks renders with
   different seeds (their spread gives the noise of the means). Both are cached under target/mitsuba-cache/,
   keyed by the scene's bytes and the settings (ours also by the binary's bytes).
2. bias: mean radiance (RGB average) of each cell of a --grid × --grid split of the image, and of
   the whole image, ours vs Mitsuba, relative difference in % with its standard error.
3. noise at equal spp: MSE against the Mitsuba reference (median over --runs seeds), ours/Mitsuba.
   MSE is over pixels and RGB channels, less the reference's own estimated variance.
4. time to equal error: both renderers over the --ladder of spp, --runs seeds each. Mitsuba is timed
   around mi.render and reading its image back (the scene is loaded and warmed up first; a
   vectorised variant runs its kernel when the image is read); ours is the whole process
   (start-up, scene load, BVH, render, EXR write). The time each needs to reach the MSE that Mitsuba
   has at --target-spp is interpolated log-log on the medians; the ratio is ours/Mitsuba.

Prints Markdown tables; docs/path-tracing-vs-mitsuba.md has the measured ones. A benchmark, never
a test: not run by CI.
"""

import argparse
import hashlib
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENES = {
    "cornell": os.path.join(ROOT, "scenes", "cornell.json"),
    "pt_pointlights": os.path.join(HERE, "scenes", "pt_pointlights.json"),
}
CACHE = os.path.join(ROOT, "target", "mitsuba-cache")
# Bump when the conversion changes: cached Mitsuba references then render again.
CONVERTER_VERSION = 1

mi = None
dr = None


# Where Debian and Ubuntu put LLVM 19's shared library (`apt-get install libllvm19`), for the
# llvm_* variants when DRJIT_LIBLLVM_PATH is not set.
LIBLLVM = ["/usr/lib/llvm-19/lib/libLLVM.so.19.1", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1",
           "/usr/lib/aarch64-linux-gnu/libLLVM.so.19.1"]


def import_mitsuba(variant="scalar_rgb"):
    """Imports Mitsuba with `variant` (scalar_rgb, or llvm_ad_rgb: its vectorised CPU variant), on
    one thread."""
    global mi, dr
    if mi is not None:
        return
    if variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        found = [p for p in LIBLLVM if os.path.exists(p)]
        if not found:
            sys.exit("%s needs LLVM: apt-get install libllvm19, or set DRJIT_LIBLLVM_PATH" % variant)
        os.environ["DRJIT_LIBLLVM_PATH"] = found[0]
    # This file is itself named mitsuba.py: keep its folder off the path for the import.
    sys.path[:] = [p for p in sys.path if os.path.abspath(p or os.curdir) != HERE]
    sys.modules.pop("mitsuba", None)
    try:
        import drjit
        import mitsuba
    except ImportError:
        sys.exit("mitsuba is not installed: pip install mitsuba")
    mi, dr = mitsuba, drjit
    mi.set_variant(variant)
    dr.set_thread_count(1)
    mi.set_log_level(mi.LogLevel.Warn)


# ----------------------------------------------------------------------------------------------
# Scene conversion


class Unsupported(Exception):
    """The scene uses something outside the subset that maps exactly onto Mitsuba."""


LABELS = {"id", "name", "comment", "comments", "description", "note", "notes", "title"}


def check_keys(obj, allowed, where):
    if not isinstance(obj, dict):
        raise Unsupported("%s: expected an object" % where)
    for k in obj:
        if k in allowed or k.lower() in LABELS or k[:1] in "_#" or k.startswith("//"):
            continue
        raise Unsupported("%s: key '%s' is outside the subset this comparison maps (allowed: %s)"
                          % (where, k, ", ".join(sorted(allowed))))


def number(v, where, lo=None):
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise Unsupported("%s: expected a finite number, found %r" % (where, v))
    if lo is not None and v < lo:
        raise Unsupported("%s: must be >= %g, found %r" % (where, lo, v))
    return float(v)


def vec3(v, where):
    if not isinstance(v, list) or len(v) != 3:
        raise Unsupported("%s: expected an array of 3 numbers, found %r" % (where, v))
    return np.array([number(x, "%s[%d]" % (where, i)) for i, x in enumerate(v)])


def colour(v, where):
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return np.array([number(v, where)] * 3)
    return vec3(v, where)


def boolean(v, where):
    if isinstance(v, bool):
        return v
    if isinstance(v, (int, float)):
        return v != 0
    if isinstance(v, str) and v.lower() in ("true", "false"):
        return v.lower() == "true"
    raise Unsupported("%s: expected a bool, found %r" % (where, v))


def rgb(c):
    return {"type": "rgb", "value": [float(x) for x in c]}


def cycle_order(c, where):
    """The loader's quad rule: corners in 'Z order' (v3 opposite v0) have v2 and v3 swapped."""
    c = list(c)
    if np.linalg.norm(c[0] + c[3] - c[1] - c[2]) < np.linalg.norm(c[0] + c[2] - c[1] - c[3]):
        c[2], c[3] = c[3], c[2]
    if np.linalg.norm(np.cross(c[1] - c[0], c[3] - c[0])) <= 0:
        raise Unsupported("%s: a quad of zero area" % where)
    return c


MATERIAL_KEYS = {"kd", "ks", "diffusecolor", "specularcolor", "specularexponent", "isreflective",
                 "reflectivity", "isrefractive", "refractiveindex"}


def material(m, where, shape_type):
    """Returns (Mitsuba BSDF dict, kind)."""
    check_keys(m, MATERIAL_KEYS, where)
    kd = number(m.get("kd", 0.8), where + ".kd", 0)
    ks = number(m.get("ks", 0.0), where + ".ks", 0)
    c = colour(m.get("diffusecolor", 0.8), where + ".diffusecolor")
    kr = number(m.get("reflectivity", 0.0), where + ".reflectivity", 0)
    if "isreflective" in m:
        on = boolean(m["isreflective"], where + ".isreflective")
        kr = (kr if "reflectivity" in m else 1.0) if on else 0.0
    refractive = "isrefractive" in m and boolean(m["isrefractive"], where + ".isrefractive")
    eta = number(m.get("refractiveindex", 1.5), where + ".refractiveindex")
    if ks != 0:
        raise Unsupported("%s.ks: %g; the glossy lobe (normalised Blinn-Phong) has no Mitsuba twin: "
                          "use ks = 0" % (where, ks))
    if kr > 0 and refractive:
        raise Unsupported("%s: both reflective and refractive" % where)
    if kr > 0 or refractive:
        if kd != 0:
            raise Unsupported("%s.kd: %g on a %s; only pure materials map (kd = 0; a material "
                              "without kd has kd 0.8)" % (where, kd, "mirror" if kr > 0 else "glass"))
        if kr > 0:
            return ({"type": "twosided", "bsdf": {"type": "conductor", "material": "none",
                                                  "specular_reflectance": rgb([kr] * 3)}}, "mirror")
        if shape_type != "sphere":
            raise Unsupported("%s: glass maps only on spheres (closed, with an inside)" % where)
        if eta <= 0:
            raise Unsupported("%s.refractiveindex: must be > 0" % where)
        return {"type": "dielectric", "int_ior": eta, "ext_ior": 1.0}, "glass"
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(kd * c)}}, "diffuse"


def ply_text(vertices, faces):
    lines = ["ply", "format ascii 1.0", "element vertex %d" % len(vertices),
             "property float x", "property float y", "property float z",
             "element face %d" % len(faces), "property list uchar int vertex_indices", "end_header"]
    lines += ["%.9g %.9g %.9g" % tuple(v) for v in vertices]
    lines += ["3 %d %d %d" % tuple(f) for f in faces]
    return "\n".join(lines) + "\n"


def mesh(vertices, faces, meshdir, name):
    path = os.path.join(meshdir, name + ".ply")
    with open(path, "w") as f:
        f.write(ply_text(vertices, faces))
    return {"type": "ply", "filename": path, "face_normals": True}


def convert(path, meshdir, width=None, height=None):
    """The Mitsuba scene dictionary for a CGR scene, plus what the comparison needs to know."""
    try:
        with open(path, "rb") as f:
            doc = json.loads(f.read().decode("utf-8"))
    except ValueError as e:
        raise Unsupported("%s: not strict JSON (%s); comments and trailing commas are not mapped"
                          % (path, e))
    # pixelsample, lightsample and a light's samples/method change only how our renderer samples,
    # not the image it converges to: they are not mapped (Mitsuba's counts are set separately).
    check_keys(doc, {"rendermode", "nbounces", "pixelsample", "lightsample", "camera", "scene"}, "(root)")
    mode = doc.get("rendermode")
    if not isinstance(mode, str) or mode.lower() != "pathtrace":
        raise Unsupported('rendermode: must be "pathtrace" (a CGR path-tracing file), found %r' % mode)
    nb = doc.get("nbounces", 3)
    if isinstance(nb, bool) or not isinstance(nb, (int, float)) or nb < 0 or nb != int(nb):
        raise Unsupported("nbounces: expected a whole number, found %r" % nb)
    nb = int(nb)

    cam = doc.get("camera")
    check_keys(cam, {"type", "width", "height", "position", "lookAt", "upVector", "fov", "exposure"},
               "camera")
    if str(cam.get("type", "pinhole")).lower() not in ("pinhole", "perspective"):
        raise Unsupported("camera.type: only a pinhole camera maps, found %r" % cam.get("type"))
    if number(cam.get("exposure", 1.0), "camera.exposure") != 1.0:
        raise Unsupported("camera.exposure: must be 1 (comparisons are in linear radiance)")
    for k in ("width", "height", "position", "lookAt", "fov"):
        if k not in cam:
            raise Unsupported("camera: missing '%s'" % k)
    w0 = int(number(cam["width"], "camera.width", 1))
    h0 = int(number(cam["height"], "camera.height", 1))
    if width and not height:
        height = max(1, round(width * h0 / w0))
    w, h = width or w0, height or h0
    pos = vec3(cam["position"], "camera.position")
    target = vec3(cam["lookAt"], "camera.lookAt")
    up = vec3(cam.get("upVector", [0, 1, 0]), "camera.upVector")
    fov = number(cam["fov"], "camera.fov")
    if not 0 < fov < 180:
        raise Unsupported("camera.fov: must be between 0 and 180")
    fwd = target - pos
    if np.linalg.norm(fwd) == 0 or np.linalg.norm(np.cross(fwd, up)) <= 1e-9 * np.linalg.norm(fwd) * np.linalg.norm(up):
        raise Unsupported("camera: lookAt equals position, or upVector is parallel to the view")

    scene = doc.get("scene")
    check_keys(scene, {"backgroundcolor", "lightsources", "shapes"}, "scene")
    out = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": nb + 2},
        "sensor": {
            "type": "perspective", "fov_axis": "y", "fov": fov,
            "to_world": mi.ScalarTransform4f().look_at(origin=pos.tolist(), target=target.tolist(),
                                                       up=up.tolist()),
            "film": {"type": "hdrfilm", "width": w, "height": h, "pixel_format": "rgb",
                     "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": 1},
        },
    }
    bg = colour(scene.get("backgroundcolor", [0, 0, 0]), "scene.backgroundcolor")
    if (bg < 0).any():
        raise Unsupported("scene.backgroundcolor: negative")
    if bg.any():
        out["background"] = {"type": "constant", "radiance": rgb(bg)}

    lights = scene.get("lightsources", [])
    shapes = scene.get("shapes", [])
    if not isinstance(lights, list) or not isinstance(shapes, list):
        raise Unsupported("scene.lightsources and scene.shapes must be arrays")
    for i, L in enumerate(lights):
        where = "scene.lightsources[%d]" % i
        t = str(L.get("type", "")).lower() if isinstance(L, dict) else ""
        if t == "pointlight":
            check_keys(L, {"type", "position", "intensity"}, where)
            I = colour(L.get("intensity", 1.0), where + ".intensity")
            out["light_%d" % i] = {"type": "point", "position": vec3(L["position"], where + ".position").tolist(),
                                   "intensity": rgb(math.pi * I)}
        elif t == "arealight":
            check_keys(L, {"type", "v0", "v1", "v2", "v3", "normal", "intensity", "samples", "method"},
                       where)
            for k in ("v0", "v1", "v2", "v3", "normal"):
                if k not in L:
                    raise Unsupported("%s: only the v0..v3 + normal form maps; missing '%s'" % (where, k))
            c = cycle_order([vec3(L[k], "%s.%s" % (where, k)) for k in ("v0", "v1", "v2", "v3")], where)
            nrm = vec3(L["normal"], where + ".normal")
            e1, e2 = c[1] - c[0], c[3] - c[0]
            cr = np.cross(e1, e2)
            area = np.linalg.norm(cr)
            if np.linalg.norm(c[0] + c[2] - c[1] - c[3]) > 1e-6 * math.sqrt(area):
                raise Unsupported("%s: the corners are not a parallelogram" % where)
            geo_n = cr / area
            if np.dot(geo_n, nrm) < 0.999 * np.linalg.norm(nrm):
                if np.dot(-geo_n, nrm) < 0.999 * np.linalg.norm(nrm):
                    raise Unsupported("%s.normal: not perpendicular to the quad" % where)
                e1, e2, geo_n = e2, e1, -geo_n   # same parallelogram, +z of the frame along normal
            I = colour(L.get("intensity", 1.0), where + ".intensity")
            emitter = {"type": "area", "radiance": rgb(math.pi * I / area)}
            black = {"type": "diffuse", "reflectance": rgb([0, 0, 0])}
            if abs(np.dot(e1, e2)) <= 1e-6 * np.linalg.norm(e1) * np.linalg.norm(e2):
                centre = c[0] + 0.5 * (e1 + e2)
                m = np.identity(4)
                m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = 0.5 * e1, 0.5 * e2, geo_n, centre
                shape = {"type": "rectangle", "to_world": mi.ScalarTransform4f(m.tolist())}
            else:   # sheared: two triangles wound so that their normal is `normal`
                verts = [c[0], c[0] + e1, c[0] + e1 + e2, c[0] + e2]
                shape = mesh(verts, [(0, 1, 2), (0, 2, 3)], meshdir, "light_%d" % i)
            shape.update({"emitter": emitter, "bsdf": black})
            out["light_%d" % i] = shape
        else:
            raise Unsupported("%s.type: only pointlight and arealight map, found %r" % (where, t))

    for i, s in enumerate(shapes):
        where = "scene.shapes[%d]" % i
        t = str(s.get("type", "")).lower() if isinstance(s, dict) else ""
        if t == "sphere":
            check_keys(s, {"type", "center", "radius", "material"}, where)
            bsdf, _ = material(s.get("material", {}), where + ".material", t)
            out["shape_%d" % i] = {"type": "sphere", "center": vec3(s["center"], where + ".center").tolist(),
                                   "radius": number(s["radius"], where + ".radius", 1e-12), "bsdf": bsdf}
        elif t in ("quad", "triangle"):
            keys = ("v0", "v1", "v2", "v3") if t == "quad" else ("v0", "v1", "v2")
            check_keys(s, {"type", "material"} | set(keys), where)
            for k in keys:
                if k not in s:
                    raise Unsupported("%s: only the %s corner form maps; missing '%s'" % (where, "/".join(keys), k))
            c = [vec3(s[k], "%s.%s" % (where, k)) for k in keys]
            if t == "quad":
                c = cycle_order(c, where)
                faces = [(0, 1, 2), (0, 2, 3)]
            else:
                if np.linalg.norm(np.cross(c[1] - c[0], c[2] - c[0])) <= 0:
                    raise Unsupported("%s: a triangle of zero area" % where)
                faces = [(0, 1, 2)]
            bsdf, _ = material(s.get("material", {}), where + ".material", t)
            shape = mesh(c, faces, meshdir, "shape_%d" % i)
            shape["bsdf"] = bsdf
            out["shape_%d" % i] = shape
        else:
            raise Unsupported("%s.type: only sphere, quad and triangle map, found %r" % (where, t))
    return {"dict": out, "width": w, "height": h, "max_depth": nb + 2,
            # CGR files: image right = up × forward; Mitsuba's look_at camera: forward × up.
            "mirror_x": True}


# ----------------------------------------------------------------------------------------------
# Rendering


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


class Mitsuba:
    def __init__(self, scene_path, width, height, sampler):
        import_mitsuba()
        self.meshdir = tempfile.mkdtemp(prefix="mitsuba-peer-")
        conv = convert(scene_path, self.meshdir, width, height)
        conv["dict"]["sensor"]["sampler"] = {"type": sampler, "sample_count": 1}
        self.mirror_x = conv["mirror_x"]
        self.width, self.height = conv["width"], conv["height"]
        self.cpu_s = self.wall_s = 0.0   # totals over render(), to show contention
        t0 = time.perf_counter()
        self.scene = mi.load_dict(conv["dict"])
        mi.render(self.scene, spp=1, seed=0)   # warm-up: first-render set-up is not timed
        self.load_s = time.perf_counter() - t0

    def render(self, spp, seed):
        """(image as float64 h×w×3 in our orientation, seconds spent in mi.render)."""
        t0, c0 = time.perf_counter(), time.process_time()
        img = mi.render(self.scene, spp=spp, seed=seed)
        # Reading the image back is timed: a vectorised variant only runs its kernel then.
        a = np.array(img, dtype=np.float64)[:, :, :3]
        dt = time.perf_counter() - t0
        self.cpu_s += time.process_time() - c0
        self.wall_s += dt
        return (a[:, ::-1] if self.mirror_x else a), dt


class Ours:
    def __init__(self, binary, scene_path, width, height, extra):
        if not os.access(binary, os.X_OK):
            sys.exit("no raytracer binary at %s (cargo build --release, or --raytracer)" % binary)
        self.binary, self.scene, self.width, self.height = binary, scene_path, width, height
        helptext = subprocess.run([binary, "--help"], capture_output=True, text=True).stdout
        self.path_tracer = "--integrator" in helptext
        self.extra = (["--integrator", "path"] if self.path_tracer else []) + list(extra)
        self.tmp = tempfile.mkdtemp(prefix="raytracer-peer-")
        self.cpu_s = self.wall_s = 0.0

    def render(self, spp, seed, threads=1):
        out = os.path.join(self.tmp, "o.exr")
        cmd = [self.binary, self.scene, out, "--spp", str(spp), "--seed", str(seed),
               "--threads", str(threads), "--width", str(self.width), "--height", str(self.height),
               "-q"] + self.extra
        u0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True)
        dt = time.perf_counter() - t0
        u1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if r.returncode != 0:
            sys.exit("raytracer failed (%s):\n%s" % (" ".join(cmd), r.stderr[-2000:]))
        self.cpu_s += (u1.ru_utime - u0.ru_utime) + (u1.ru_stime - u0.ru_stime)
        self.wall_s += dt
        return read_exr(out), dt


def read_exr(path):
    try:
        import OpenEXR
    except ImportError:
        OpenEXR = None
    if OpenEXR is not None and hasattr(OpenEXR, "File"):
        with OpenEXR.File(path) as f:
            ch = f.channels()
            a = ch["RGB"].pixels if "RGB" in ch else np.stack([ch[c].pixels for c in "RGB"], axis=-1)
        return np.array(a, dtype=np.float64)[:, :, :3]
    # mi.Bitmap's EXR reader deadlocks with a one-thread pool (Mitsuba 3.9): read with two.
    import_mitsuba()
    dr.set_thread_count(2)
    try:
        return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]
    finally:
        dr.set_thread_count(1)


def chunked(render, spp, chunks, cache_file, label, seed0=1000):
    """Mean of `chunks` renders of spp/chunks each (seeds seed0, seed0 + 1, …) and the per-pixel
    variance of that mean, cached as .npz."""
    if os.path.exists(cache_file):
        d = np.load(cache_file)
        log("%s: cached %s" % (label, os.path.relpath(cache_file, ROOT)))
        return d["mean"], d["var"]
    per = max(1, spp // chunks)
    imgs = []
    for k in range(chunks):
        t0 = time.perf_counter()
        img, _ = render(per, seed0 + k)
        imgs.append(img)
        log("%s: chunk %d/%d, %d spp, %.1f s" % (label, k + 1, chunks, per, time.perf_counter() - t0))
    stack = np.stack(imgs)
    mean = stack.mean(axis=0)
    var = stack.var(axis=0, ddof=1) / chunks if chunks > 1 else np.zeros_like(mean)
    os.makedirs(os.path.dirname(cache_file), exist_ok=True)
    tmp = cache_file + ".tmp.npz"
    np.savez(tmp, mean=mean, var=var)
    os.replace(tmp, cache_file)
    return mean, var


# ----------------------------------------------------------------------------------------------
# Measures


def mse(img, ref, ref_var):
    """MSE over pixels and channels, less the reference's own variance (its expected share)."""
    return float(np.mean((img - ref) ** 2) - np.mean(ref_var))


def region_bias(ours, ours_var, ref, ref_var, grid):
    """[(label, ref mean, rel. diff %, standard error %)] for grid×grid cells and the image."""
    h, w = ref.shape[:2]
    rows = []
    cells = [("r%dc%d" % (i, j), slice(i * h // grid, (i + 1) * h // grid),
              slice(j * w // grid, (j + 1) * w // grid)) for i in range(grid) for j in range(grid)]
    cells.append(("image", slice(0, h), slice(0, w)))
    whole = ref.mean()
    for name, ys, xs in cells:
        o, r = ours[ys, xs].mean(), ref[ys, xs].mean()
        n = ours[ys, xs].size
        # variance of a cell mean from the per-pixel variances of the two means (pixels independent)
        se = math.sqrt((ours_var[ys, xs].sum() + ref_var[ys, xs].sum()) / n ** 2)
        if r <= 1e-3 * whole:
            rows.append((name, r, None, None))
        else:
            rows.append((name, r, 100 * (o - r) / r, 100 * se / r))
    return rows


def interp_time(ladder, target):
    """Seconds to reach MSE `target`, from {spp: (median time, median MSE)}: piecewise linear in
    log-log between the steps that bracket it. Returns (seconds, how): 'interpolated'; 'at most'
    when even the smallest spp is below the target (its time, an upper bound: the process's fixed
    costs make extrapolating below it meaningless); 'extrapolated' (from the two largest spp, MSE
    ∝ time^slope) when even the largest is above it."""
    steps = sorted(ladder)
    pts = [(math.log(ladder[s][1]), math.log(ladder[s][0])) for s in steps
           if ladder[s][1] > 0 and ladder[s][0] > 0]
    if len(pts) < 2:
        return float("nan"), "too few points"
    lt = math.log(target)
    if lt >= pts[0][0]:
        return math.exp(pts[0][1]), "at most"
    for (m0, t0), (m1, t1) in zip(pts, pts[1:]):
        if m1 <= lt <= m0 and m1 < m0:
            return math.exp(t0 + (t1 - t0) * (lt - m0) / (m1 - m0)), "interpolated"
    (m0, t0), (m1, t1) = pts[-2], pts[-1]
    if m1 >= m0:
        return float("nan"), "MSE not falling"
    return math.exp(t0 + (t1 - t0) * (lt - m0) / (m1 - m0)), "extrapolated"


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def fmt_pct(x, se):
    return "—" if x is None else "%+.2f ± %.2f" % (x, se)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(SCENES),
                    help="names (%s) or paths of CGR path-tracing scene files" % ", ".join(SCENES))
    ap.add_argument("--size", type=int, default=128, help="image width (height keeps the aspect)")
    ap.add_argument("--runs", type=int, default=3, help="seeds per ladder step (medians)")
    ap.add_argument("--raytracer", default=os.path.join(ROOT, "target", "release", "raytracer"))
    ap.add_argument("--ref-spp", type=int, default=4096, help="spp of both converged images")
    ap.add_argument("--chunks", type=int, default=4, help="renders the converged images are split into")
    ap.add_argument("--ref-seed", type=int, default=1000,
                    help="seed of the first chunk of the converged images (another value: an "
                         "independent pair of references, to check the bias table's error bars)")
    ap.add_argument("--ref-threads", type=int, default=1,
                    help="threads for the (untimed, cached) converged images")
    ap.add_argument("--ladder", default="1,2,4,8,16,32,64,128,256")
    ap.add_argument("--noise-spp", default="16,64", help="spp of the equal-spp noise table")
    ap.add_argument("--target-spp", type=int, default=64,
                    help="time to equal error: the MSE Mitsuba reaches at this spp")
    ap.add_argument("--grid", type=int, default=4)
    ap.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb"],
                    help="Mitsuba variant: scalar_rgb, or llvm_ad_rgb (vectorised; needs libllvm19)")
    ap.add_argument("--sampler", default="independent",
                    help="Mitsuba sampler: independent, multijitter, stratified, ldsampler")
    ap.add_argument("--our-args", default="", help="extra raytracer flags, e.g. '--pixel-sampler random'")
    ap.add_argument("--our-light-samples", type=int,
                    help="render ours from a copy of the scene with this top-level lightsample (shadow "
                         "rays per path vertex for every area light; the default is each light's own, "
                         "4×4 for a jittered light without 'samples')")
    ap.add_argument("--no-ladder", action="store_true", help="converged images and bias only")
    ap.add_argument("--no-bias", action="store_true",
                    help="skip our converged image and the bias table (noise and time only)")
    ap.add_argument("--save", help="folder for PNG previews (sRGB) of the converged images")
    ap.add_argument("--mitsuba-only", action="store_true",
                    help="render (and cache) the Mitsuba references only")
    ap.add_argument("--check", action="store_true",
                    help="convert the scenes and render Mitsuba at 16 spp only (no raytracer)")
    args = ap.parse_args()

    import_mitsuba(args.variant)
    ladder = [int(x) for x in args.ladder.split(",")]
    noise_spp = [int(x) for x in args.noise_spp.split(",")]
    for s in noise_spp + [args.target_spp]:
        if s not in ladder:
            sys.exit("--noise-spp and --target-spp must be steps of --ladder (%d is not)" % s)

    print("Mitsuba %s (%s, 1 thread; sampler %s, the references: independent), %d px wide, "
          "references %d spp in %d chunks; raytracer %s\n"
          % (mi.__version__, args.variant, args.sampler, args.size, args.ref_spp, args.chunks,
             args.raytracer))
    for name in args.scenes.split(","):
        path = SCENES.get(name, name)
        with open(path, "rb") as f:
            scene_bytes = f.read()
        try:
            m_ref = Mitsuba(path, args.size, None, "independent")
            m = m_ref if args.sampler == "independent" else Mitsuba(path, args.size, None, args.sampler)
        except Unsupported as e:
            sys.exit("%s: cannot be compared with Mitsuba: %s" % (path, e))
        w, h = m.width, m.height
        label = os.path.splitext(os.path.basename(path))[0]
        print("## %s (%d×%d)\n" % (label, w, h))

        if args.check:
            img, dt = m.render(16, 1)
            log("%s: Mitsuba 16 spp in %.2f s, mean radiance %.4f" % (label, dt, img.mean()))
            if args.save:
                save_png(img, os.path.join(args.save, label + "_mitsuba16.png"))
            continue

        settings = [w, h, args.ref_spp, args.chunks] + ([args.ref_seed] if args.ref_seed != 1000 else [])
        key = hashlib.sha256(json.dumps([CONVERTER_VERSION, mi.__version__, "independent"] + settings
                                        + ([args.variant] if args.variant != "scalar_rgb" else []))
                             .encode() + scene_bytes).hexdigest()[:16]
        if args.ref_threads != 1:
            dr.set_thread_count(args.ref_threads)
        ref, ref_var = chunked(m_ref.render, args.ref_spp, args.chunks,
                               os.path.join(CACHE, "%s-mitsuba-%s.npz" % (label, key)), label + " Mitsuba ref",
                               args.ref_seed)
        dr.set_thread_count(1)
        if args.mitsuba_only:
            log("%s: Mitsuba reference mean radiance %.4f, max %.4f" % (label, ref.mean(), ref.max()))
            if args.save:
                save_png(ref, os.path.join(args.save, label + "_mitsuba.png"))
            continue
        our_scene, our_bytes = path, scene_bytes
        if args.our_light_samples:
            # A copy of the scene with its area lights' sample count set: ours only.
            doc = json.loads(scene_bytes)
            doc["lightsample"] = args.our_light_samples
            our_bytes = json.dumps(doc, indent=1).encode()
            our_scene = os.path.join(m.meshdir, os.path.basename(path))
            with open(our_scene, "wb") as f:
                f.write(our_bytes)
            print("Our renderer: `\"lightsample\": %d` (shadow rays per vertex for each area light)\n"
                  % args.our_light_samples)
        ours = Ours(args.raytracer, our_scene, w, h, args.our_args.split())
        if not ours.path_tracer:
            log("warning: %s has no --integrator flag: its default renderer is compared, not a path tracer"
                % args.raytracer)
        if not args.no_bias:
            bias_table(args, label, ours, our_bytes, settings, ref, ref_var)
        if args.no_ladder:
            continue
        ladder_tables(args, label, ladder, noise_spp, m, ours, ref, ref_var)


def bias_table(args, label, ours, our_bytes, settings, ref, ref_var):
    """Our converged image (cached), the orientation check and the bias table."""
    okey = hashlib.sha256(json.dumps([sha256_file(args.raytracer), ours.extra] + settings)
                          .encode() + our_bytes).hexdigest()[:16]
    conv, conv_var = chunked(lambda spp, seed: ours.render(spp, seed, args.ref_threads),
                             args.ref_spp, args.chunks,
                             os.path.join(CACHE, "%s-ours-%s.npz" % (label, okey)), label + " ours ref",
                             args.ref_seed)
    if args.save:
        save_png(ref, os.path.join(args.save, label + "_mitsuba.png"))
        save_png(conv, os.path.join(args.save, label + "_ours.png"))

    # Orientation check: the documented mirroring should match far better than its opposite.
    straight = np.mean((conv - ref) ** 2)
    flipped = np.mean((conv - ref[:, ::-1]) ** 2)
    if flipped < straight:
        log("warning: %s: our image matches the left-right mirrored Mitsuba image better "
            "(MSE %.3g vs %.3g): the camera conventions disagree" % (label, flipped, straight))

    rows = region_bias(conv, conv_var, ref, ref_var, args.grid)
    print("Bias: converged images (%d spp each), mean radiance per region, ours vs Mitsuba, "
          "relative difference %% ± standard error (goal ≤ 1%%)\n" % args.ref_spp)
    print("| row \\ column | " + " | ".join(str(j) for j in range(args.grid)) + " |")
    print("|---" * (args.grid + 1) + "|")
    for i in range(args.grid):
        print("| %d | " % i + " | ".join(fmt_pct(r[2], r[3]) for r in rows[i * args.grid:(i + 1) * args.grid]) + " |")
    cellrows = [r for r in rows[:-1] if r[2] is not None]
    worst = max(cellrows, key=lambda r: abs(r[2]))
    whole = rows[-1]
    chan = [100 * (conv[..., c].mean() - ref[..., c].mean()) / ref[..., c].mean()
            if ref[..., c].mean() > 0 else float("nan") for c in range(3)]
    print("\n| measure | value |\n|---|---|")
    print("| whole image, RGB mean (Mitsuba %.4f) | %s %% |" % (whole[1], fmt_pct(whole[2], whole[3])))
    print("| whole image, R / G / B | %+.2f / %+.2f / %+.2f %% |" % tuple(chan))
    print("| worst region (%s, Mitsuba %.4f) | %s %% |" % (worst[0], worst[1], fmt_pct(worst[2], worst[3])))
    print("| regions skipped (mean ~0) | %d |" % sum(r[2] is None for r in rows[:-1]))
    print("| MSE ours converged vs Mitsuba reference (less both images' noise) | %.3g |"
          % (straight - ref_var.mean() - conv_var.mean()))
    print()


def ladder_tables(args, label, ladder, noise_spp, m, ours, ref, ref_var):
    """Both renderers over the ladder: the noise table, the ladder and the time to equal error."""
    results = {"mitsuba": {}, "ours": {}}
    load0 = os.getloadavg()[0]
    m.cpu_s = m.wall_s = ours.cpu_s = ours.wall_s = 0.0
    for spp in ladder:
        for run in range(args.runs):
            seed = 1 + run
            img, dt = m.render(spp, seed)
            results["mitsuba"].setdefault(spp, []).append((dt, mse(img, ref, ref_var)))
            img, dt = ours.render(spp, seed)
            results["ours"].setdefault(spp, []).append((dt, mse(img, ref, ref_var)))
        log("%s: %d spp: Mitsuba %.2f s, ours %.2f s" % (label, spp, results["mitsuba"][spp][-1][0],
                                                         results["ours"][spp][-1][0]))
    med = {who: {spp: (statistics.median(t for t, _ in v), statistics.median(e for _, e in v))
                 for spp, v in r.items()} for who, r in results.items()}

    print("Noise at equal spp: MSE vs the Mitsuba reference, median of %d seeds (goal: ratio ≤ 1)\n"
          % args.runs)
    print("| spp | MSE Mitsuba | MSE ours | ours / Mitsuba |\n|---|---|---|---|")
    for spp in noise_spp:
        a, b = med["mitsuba"][spp][1], med["ours"][spp][1]
        print("| %d | %.4g | %.4g | %.2f |" % (spp, a, b, b / a))
    print()

    print("Ladder: median time (s) and MSE, %d runs each, one thread (CPU time / wall time over "
          "the ladder: Mitsuba %.2f, ours %.2f; load average %.1f before, %.1f after)\n"
          % (args.runs, m.cpu_s / m.wall_s, ours.cpu_s / ours.wall_s, load0, os.getloadavg()[0]))
    print("| spp | Mitsuba s | Mitsuba MSE | ours s | ours MSE |\n|---|---|---|---|---|")
    for spp in ladder:
        (ta, ea), (tb, eb) = med["mitsuba"][spp], med["ours"][spp]
        print("| %d | %.3f | %.4g | %.3f | %.4g |" % (spp, ta, ea, tb, eb))
    print()

    target = med["mitsuba"][args.target_spp][1]
    ta, how_a = interp_time(med["mitsuba"], target)
    tb, how_b = interp_time(med["ours"], target)
    print("Time to equal error: MSE %.4g (Mitsuba at %d spp), goal ratio ≤ 0.5\n" % (target, args.target_spp))
    print("| Mitsuba s | ours s | ours / Mitsuba |\n|---|---|---|")
    print("| %.3f (%s) | %.3f (%s) | %s%.2f |\n" % (ta, how_a, tb, how_b,
                                                "≤ " if how_b == "at most" else "", tb / ta))
    sys.stdout.flush()


def save_png(img, path):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    x = np.clip(img, 0, 1)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    bmp = mi.Bitmap((x * 255 + 0.5).astype(np.uint8), mi.Bitmap.PixelFormat.RGB)
    bmp.write(path)


if __name__ == "__main__":
    main()
