#!/usr/bin/env python3
"""The CGR conventions worked out from the course's own renders of its test scenes.

    cargo build --release
    python3 benches/cgr_official.py fit              # the evidence tables of docs/scene-format.md
    python3 benches/cgr_official.py sheet OUT.png    # the course's pictures beside ours (README)

Needs numpy, scipy, Pillow and OpenEXR (`pip install numpy scipy pillow openexr`) and
../shared/coursework/official/cgr2024. Not run by CI: tests/official_cgr.rs asserts the figures.

`fit` first measures patches of the course's pictures that separate the terms (the background,
surfaces lit by the ambient light alone), then renders the three shaded pictures with our
renderer as linear radiance (EXR) under each hypothesis about the light (ambient, fall-off,
highlight), fits the two constants of the display transform (k, s of src/film/cgr.rs) to the
course's pictures for each, and prints the mean absolute difference of 8-bit RGB that each
hypothesis reaches at its best. Last, with the chosen light, it compares display transforms.
"""
import json, subprocess, sys, tempfile
from pathlib import Path

import numpy as np
import OpenEXR
from PIL import Image, ImageDraw
from scipy.optimize import least_squares

ROOT = Path(__file__).resolve().parent.parent
OFFICIAL = ROOT.parent / "shared/coursework/official/cgr2024"
BINARY = ROOT / "target/release/raytracer"
# (picture, scene file, render mode to switch to)
SHADED = [("scene_phong", "scene.json", "phong"), ("simple_phong", "simple_phong.json", None),
          ("mirror_image", "mirror_image.json", None)]
BINARY_MODE = [("scene_binary", "scene.json", None), ("binary_primitives", "binary_primitives.json", None)]
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
K, S = 1.4, 1.08  # src/film/cgr.rs


def picture(name):
    return np.asarray(Image.open(OFFICIAL / f"{name}.png").convert("RGB"), float)


def scene(file, mode, edit=None):
    s = json.loads((OFFICIAL / file).read_text())
    if mode:
        s["rendermode"] = mode
    if edit:
        edit(s)
    return s


def render(s, out, tmp, *flags):
    path = Path(tmp) / "scene.json"
    path.write_text(json.dumps(s))
    subprocess.run([str(BINARY), str(path), str(out), "-q", *flags], check=True)


def radiance(s, tmp):
    out = Path(tmp) / "out.exr"
    render(s, out, tmp)
    with OpenEXR.File(str(out)) as f:
        ch = f.channels()
        rgb = ch["RGB"].pixels if "RGB" in ch else np.stack([ch[c].pixels for c in "RGB"], -1)
    return np.asarray(rgb, float)


def display(x, k, s, per_channel=False):
    """src/film/cgr.rs in numpy; `per_channel` applies the curve to each channel alone."""
    x = np.maximum(x, 0)
    if per_channel:
        return np.clip(np.log1p(k * x) / np.log1p(k), 0, 1)
    y = np.maximum(x @ LUMINANCE, 1e-12)[..., None]
    return np.clip(np.log1p(k * y) / np.log1p(k) * (x / y) ** s, 0, 1)


def mad(a, b):
    return float(np.abs(a - b).mean())


def fit_display(xs, refs, fix_s=None, per_channel=False):
    """Best (k, s) for radiance images `xs` against the course's pictures, and the error of each."""
    rng = np.random.default_rng(0)
    idx = [rng.choice(x.shape[0] * x.shape[1], 40000, replace=False) for x in xs]
    flat = [(x.reshape(-1, 3)[i], r.reshape(-1, 3)[i]) for x, r, i in zip(xs, refs, idx)]

    def resid(q):
        k, s = q[0], (fix_s if fix_s is not None else q[1])
        return np.concatenate([(255 * display(x, k, s, per_channel) - r).ravel() for x, r in flat])

    q0 = [1.4] if fix_s is not None else [1.4, 1.1]
    q = least_squares(resid, q0, bounds=([1e-3] + [0.5] * (len(q0) - 1), [100] + [3] * (len(q0) - 1)),
                      loss="soft_l1", f_scale=3).x
    k, s = q[0], (fix_s if fix_s is not None else q[1])
    errs = [mad(np.floor(255 * display(x, k, s, per_channel) + 0.5), r) for x, r in zip(xs, refs)]
    return k, s, errs


def patches():
    """Regions where only the ambient light reaches the surface, and the background."""
    print("## What the course's pictures show where only the ambient light arrives\n")
    print("| picture | region | diffuse colour | pixels (mode) |")
    print("|---|---|---|---|")
    regions = [("simple_phong", "background", None, (10, 10, 200, 100)),
               ("simple_phong", "floor in the sphere's shadow", "[0.5, 0.8, 0.5]", (365, 485, 30, 20)),
               ("simple_phong", "sphere, side away from the light", "[0.8, 0.5, 0.5]", (470, 500, 20, 8)),
               ("simple_phong", "cylinder, side away from the light", "[0.5, 0.5, 0.8]", (748, 380, 8, 80)),
               ("scene_phong", "ground in both lights' shadows, in the mirror", "[0.5, 1.0, 0.5]",
                (882, 251, 16, 8))]
    for name, what, colour, (x, y, w, h) in regions:
        px = picture(name)[y:y + h, x:x + w].reshape(-1, 3).astype(int)
        values, counts = np.unique(px, axis=0, return_counts=True)
        mode = values[np.argmax(counts)]
        print(f"| {name} | {what} | {colour or '[0.25, 0.25, 0.25] (background)'} | "
              f"{[int(v) for v in mode]} ({counts.max()}/{len(px)}) |")
    print()


def hypotheses():
    def ambient(value):
        return lambda s: s["scene"].__setitem__("ambientlight", value)

    def falloff(kc, kl, kq):
        def edit(s):
            for light in s["scene"]["lightsources"]:
                light.update({"kc": kc, "kl": kl, "kq": kq})
        return edit

    def no_highlight(s):
        for shape in s["scene"]["shapes"]:
            shape["material"]["ks"] = 0.0

    return [("chosen: ambient = background, no fall-off, Blinn-Phong highlight as given", None),
            ("no ambient light", ambient([0, 0, 0])),
            ("ambient 0.2 grey (the earlier convention)", ambient([0.2, 0.2, 0.2])),
            ("ambient 0.35 grey", ambient([0.35, 0.35, 0.35])),
            ("fall-off 1/d", falloff(0, 1, 0)),
            ("fall-off 1/d²", falloff(0, 0, 1)),
            ("fall-off 1/(1 + 0.22d + 0.2d²)", falloff(1, 0.22, 0.2)),
            ("no highlight (ks = 0)", no_highlight)]


def fit():
    refs = [picture(name) for name, _, _ in SHADED]
    patches()
    print("## The light, each hypothesis with the display transform fitted to it\n")
    print("| hypothesis | k | s | " + " | ".join(n for n, _, _ in SHADED) + " |")
    print("|---|---:|---:|" + "---:|" * len(SHADED))
    chosen = None
    with tempfile.TemporaryDirectory() as tmp:
        for label, edit in hypotheses():
            xs = [radiance(scene(f, m, edit), tmp) for _, f, m in SHADED]
            chosen = chosen or xs
            k, s, errs = fit_display(xs, refs)
            print(f"| {label} | {k:.2f} | {s:.2f} | " + " | ".join(f"{e:.2f}" for e in errs) + " |")
    print("\n## The display transform, with the chosen light\n")
    print("| transform | k | s | " + " | ".join(n for n, _, _ in SHADED) + " |")
    print("|---|---:|---:|" + "---:|" * len(SHADED))
    linear = [mad(np.floor(255 * np.clip(x, 0, 1)), r) for x, r in zip(chosen, refs)]
    print("| linear (value × 255, clamped) | | | " + " | ".join(f"{e:.2f}" for e in linear) + " |")
    for label, kwargs in [("log curve on each channel alone", dict(fix_s=1.0, per_channel=True)),
                          ("log curve on luminance, colour scaled by T/Y (s = 1)", dict(fix_s=1.0)),
                          ("log curve on luminance, colour exponent s fitted", {})]:
        k, s, errs = fit_display(chosen, refs, **kwargs)
        print(f"| {label} | {k:.2f} | {s:.2f} | " + " | ".join(f"{e:.2f}" for e in errs) + " |")
    errs = [mad(np.floor(255 * display(x, K, S) + 0.5), r) for x, r in zip(chosen, refs)]
    print(f"| the constants kept (src/film/cgr.rs) | {K} | {S} | " + " | ".join(f"{e:.2f}" for e in errs) + " |")
    print("\nk near 1.4 is pinned by the background: 1.33 ≤ k ≤ 1.42 show 0.25 as 87.")
    for k in (1.3, 1.35, 1.4, 1.45):
        print(f"  k = {k}: background 0.25 → {255 * np.log1p(0.25 * k) / np.log1p(k):.2f}")


def sheet(out):
    """The three shaded pictures: the course's on the left, ours on the right, with the figures."""
    tile = (480, 320)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, file, mode in SHADED:
            path = Path(tmp) / f"{name}.png"
            render(scene(file, mode), path, tmp)
            ours = Image.open(path).convert("RGB")
            course = Image.open(OFFICIAL / f"{name}.png").convert("RGB")
            d = mad(np.asarray(ours, float), np.asarray(course, float))
            print(f"{name}: {d:.2f}/255")
            rows.append((name, course, ours, d))
    label = 22
    img = Image.new("RGB", (2 * tile[0] + 12, len(rows) * (tile[1] + label) + 4), "white")
    draw = ImageDraw.Draw(img)
    for i, (name, course, ours, d) in enumerate(rows):
        y = i * (tile[1] + label)
        draw.text((4, y + 5), f"{name}: the course's render (left) and ours (right), "
                              f"mean absolute difference {d:.2f}/255", fill="black")
        img.paste(course.resize(tile, Image.LANCZOS), (0, y + label))
        img.paste(ours.resize(tile, Image.LANCZOS), (tile[0] + 12, y + label))
    img.save(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "fit":
        fit()
    elif len(sys.argv) == 3 and sys.argv[1] == "sheet":
        sheet(sys.argv[2])
    else:
        sys.exit(__doc__)
