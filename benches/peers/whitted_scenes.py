"""Whitted scenes written twice, as coursework JSON (CGR variant) and as POV-Ray 3.7 SDL, from
one description, so that both renderers trace the same geometry, lights, materials and samples.

Conventions that make the two agree (POV-Ray 3.7 documentation, "light_source", "finish"):
- lights have no fall-off: a CGR `intensity` light, a POV-Ray light without `fade_power`;
- an area light is a 2-D grid of point lights, each carrying 1/(n·n) of the power, every
  one tested with its own shadow ray (`jitter`, no `adaptive`);
- no ambient term (`ambientlight` 0; `ambient 0`), highlights are Blinn-Phong
  (`specular` with `roughness` 1/exponent), weighted by the share a CGR file leaves a surface's
  own shading beside its mirror and glass (docs/scene-format.md, "Energy"): none on the perfect
  mirrors and the glass;
- `nbounces` N secondary levels after the camera ray is POV-Ray's `max_trace_level` N + 1;
- CGR cameras put image right at up × forward, as POV-Ray's left-handed `right x` does; `angle` is horizontal,
  the JSON `fov` vertical, so the scenes are square.

`python3 whitted_scenes.py DIR` writes NAME.json and NAME.pov for every scene into DIR.
"""

import json
import math
import os
import sys

GROUND = {"kd": 0.8, "ks": 0.1, "exp": 10, "color": (1, 1, 1), "texture": "checker.png"}
RED = {"kd": 0.8, "ks": 0.4, "exp": 30, "color": (0.9, 0.2, 0.15)}
MIRROR = {"kd": 0.0, "ks": 0.2, "exp": 200, "color": (1, 1, 1), "mirror": 1.0}
GLASS = {"kd": 0.0, "ks": 0.6, "exp": 200, "color": (1, 1, 1), "glass": 1.5}


def material_mix(i):
    """Mostly diffuse, every fifth a mirror, every seventh glass (for the many-sphere scene)."""
    if i % 7 == 3:
        return GLASS
    if i % 5 == 1:
        return MIRROR
    return {"kd": 0.8, "ks": 0.3, "exp": 40, "color": hue(i)}


def hue(i):
    """The i-th of a sequence of well-spread colours."""
    h = (i * 0.61803) % 1.0
    return tuple(0.25 + 0.6 * (0.5 + 0.5 * math.cos(2 * math.pi * (h + k / 3))) for k in range(3))


def ground(half):
    return {"quad": [(-half, 0, half), (half, 0, half), (half, 0, -half), (-half, 0, -half)],
            "material": GROUND}


def whitted(samples, light_size=2.0):
    """The kind of scene POV-Ray is made for: a textured ground quad, three unit spheres
    (diffuse, mirror, glass of index 1.5), one point light and one square area light."""
    return {
        "size": 256, "nbounces": 8,
        "camera": {"position": (0, 2.6, 7.5), "lookat": (0, 0.9, 0), "fov": 40},
        "background": (0.1, 0.12, 0.16),
        "lights": [
            {"point": (-4, 6, 5), "intensity": 0.5},
            {"area": (1.5, 5, 2), "size": light_size, "samples": samples, "intensity": 0.6},
        ],
        "shapes": [
            ground(5),
            {"sphere": (-2.2, 1, 0), "radius": 1, "material": RED},
            {"sphere": (0, 1, -0.6), "radius": 1, "material": MIRROR},
            {"sphere": (2.2, 1, 0.4), "radius": 1, "material": GLASS},
        ],
    }


def many_spheres():
    """A 16×16 grid of small spheres of mixed materials under one point light and a small
    area light (4×4)."""
    shapes = [ground(6)]
    k = 0
    for i in range(16):
        for j in range(16):
            x, z = -4.5 + i * 0.6, -4.5 + j * 0.6
            shapes.append({"sphere": (x, 0.25, z), "radius": 0.25, "material": material_mix(k)})
            k += 1
    return {
        "size": 256, "nbounces": 8,
        "camera": {"position": (0, 5, 8), "lookat": (0, 0, -0.5), "fov": 45},
        "background": (0.1, 0.12, 0.16),
        "lights": [
            {"point": (-4, 7, 5), "intensity": 0.6},
            {"area": (3, 6, 2), "size": 1.0, "samples": 4, "intensity": 0.5},
        ],
        "shapes": shapes,
    }


def glass_and_mirrors():
    """Heavy in secondary rays: a 3×3 block of glass and mirror spheres in front of a mirror
    wall, one point light."""
    shapes = [ground(6),
              {"quad": [(-6, 0, -3), (6, 0, -3), (6, 5, -3), (-6, 5, -3)], "material": MIRROR}]
    for i in range(3):
        for j in range(3):
            m = GLASS if (i + j) % 2 == 0 else MIRROR
            shapes.append({"sphere": (-2.2 + 2.2 * i, 0.8, -1.8 + 1.8 * j), "radius": 0.8,
                           "material": m})
    return {
        "size": 256, "nbounces": 8,
        "camera": {"position": (0, 3, 7.5), "lookat": (0, 0.6, 0), "fov": 45},
        "background": (0.3, 0.35, 0.45),
        "lights": [{"point": (-3, 6, 5), "intensity": 0.9}],
        "shapes": shapes,
    }


def big_area_light():
    """A large (4×4) area light with 16×16 shadow rays over diffuse spheres: shadow rays are
    almost all the work."""
    shapes = [ground(6)]
    for i, x in enumerate((-2.4, -0.8, 0.8, 2.4)):
        shapes.append({"sphere": (x, 0.7, -0.3 * i), "radius": 0.7, "material": material_mix(2 * i)})
    return {
        "size": 256, "nbounces": 2,
        "camera": {"position": (0, 3, 7), "lookat": (0, 0.5, 0), "fov": 40},
        "background": (0.05, 0.05, 0.06),
        "lights": [{"area": (0, 4, 0.5), "size": 4.0, "samples": 16, "intensity": 1.0}],
        "shapes": shapes,
    }


def facing_mirrors():
    """Two mirror walls facing each other with a diffuse and a glass sphere between them: rays
    bounce to the last level (12) wherever the walls are seen."""
    def wall(x):
        return {"quad": [(x, 0, 6), (x, 0, -6), (x, 6, -6), (x, 6, 6)], "material": MIRROR}
    return {
        "size": 256, "nbounces": 12,
        "camera": {"position": (1.6, 1.5, 3.5), "lookat": (-2.2, 1.0, 0.5), "fov": 55},
        "background": (0.3, 0.35, 0.45),
        "lights": [{"point": (0, 3.6, 2.5), "intensity": 0.9}],
        "shapes": [ground(5), wall(-2.2), wall(2.2),
                   {"sphere": (-0.6, 0.8, -0.5), "radius": 0.8, "material": RED},
                   {"sphere": (1.0, 0.5, 1.2), "radius": 0.5, "material": GLASS}],
    }


def many_lights():
    """Twenty-four point lights in a ring and four small area lights (2×2) over a 5×5 grid of
    diffuse spheres: direct light is almost all the work."""
    lights = [{"point": (5 * math.cos(2 * math.pi * k / 24), 3 + (k % 3), 5 * math.sin(2 * math.pi * k / 24)),
               "intensity": 0.06} for k in range(24)]
    lights += [{"area": (x, 4.5, z), "size": 0.4, "samples": 2, "intensity": 0.12}
               for x in (-2, 2) for z in (-2, 2)]
    shapes = [ground(6)]
    for i in range(5):
        for j in range(5):
            m = {"kd": 0.8, "ks": 0.3, "exp": 40, "color": hue(5 * i + j)}
            shapes.append({"sphere": (-2.4 + 1.2 * i, 0.4, -2.4 + 1.2 * j), "radius": 0.4, "material": m})
    return {
        "size": 256, "nbounces": 2,
        "camera": {"position": (0, 5, 7), "lookat": (0, 0, 0), "fov": 45},
        "background": (0.05, 0.05, 0.06),
        "lights": lights,
        "shapes": shapes,
    }


def terrain(n=160, half=5.0):
    """A height field of 2·n² triangles: gentle hills of several frequencies."""
    def height(x, z):
        return 0.6 * math.sin(0.9 * x) * math.cos(0.7 * z) + 0.25 * math.sin(2.3 * x + 1.1 * z) \
            + 0.1 * math.cos(5.1 * z - 0.4 * x)
    verts = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -half + 2 * half * i / n, -half + 2 * half * j / n
            verts.append((round(x, 5), round(height(x, z), 5), round(z, 5)))
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            faces += [(a, d, c), (a, c, b)]
    return verts, faces


def large_mesh():
    """A 51,200-triangle height field with a mirror and a glass sphere on it, a point light and
    a small area light (4×4)."""
    verts, faces = terrain()
    land = {"kd": 0.8, "ks": 0.2, "exp": 20, "color": (0.55, 0.6, 0.4)}
    return {
        "size": 256, "nbounces": 8,
        "camera": {"position": (0, 4.5, 8), "lookat": (0, 0, 0), "fov": 45},
        "background": (0.3, 0.35, 0.45),
        "lights": [
            {"point": (-4, 7, 5), "intensity": 0.6},
            {"area": (3, 6, 2), "size": 1.0, "samples": 4, "intensity": 0.5},
        ],
        "shapes": [
            {"mesh": (verts, faces), "material": land},
            {"sphere": (-1.2, 1.6, 0.5), "radius": 0.8, "material": MIRROR},
            {"sphere": (1.4, 1.4, 1.5), "radius": 0.7, "material": GLASS},
        ],
    }


def thin_lens():
    """The first scene through a thin lens focused on the mirror sphere: 16 camera rays a
    pixel, each with its own shadow and secondary rays."""
    s = whitted(2)
    c = s["camera"]
    target = (0, 1, -0.6)
    focus = math.dist(c["position"], target)
    s["camera"] = dict(c, aperture=0.3, focus=focus, lens_samples=16)
    return s


SCENES = {
    "whitted": whitted(8),
    "whitted16": whitted(16),
    "spheres": many_spheres(),
    "glass": glass_and_mirrors(),
    "arealight": big_area_light(),
    "mirrors": facing_mirrors(),
    "lights": many_lights(),
    "mesh": large_mesh(),
    "thinlens": thin_lens(),
}


# ---- coursework JSON (CGR variant) ----

def json_material(m):
    out = {
        "kd": m["kd"], "ks": m["ks"], "specularexponent": m["exp"],
        "diffusecolor": list(m["color"]), "specularcolor": [1, 1, 1],
        "isreflective": "mirror" in m, "reflectivity": m.get("mirror", 0.0),
        "isrefractive": "glass" in m, "refractiveindex": m.get("glass", 1.0),
    }
    if "texture" in m:
        out["tPath"] = "../../../textures/" + m["texture"]
    return out


def to_json(s):
    lights = []
    for l in s["lights"]:
        i = [l["intensity"]] * 3
        if "point" in l:
            lights.append({"type": "pointlight", "position": list(l["point"]), "intensity": i})
        else:
            (x, y, z), h = l["area"], l["size"] / 2
            lights.append({"type": "arealight",
                           "v0": [x - h, y, z - h], "v1": [x + h, y, z - h],
                           "v2": [x + h, y, z + h], "v3": [x - h, y, z + h],
                           "samples": l["samples"], "method": "jittered", "intensity": i})
    shapes = []
    for sh in s["shapes"]:
        if "sphere" in sh:
            shapes.append({"type": "sphere", "center": list(sh["sphere"]), "radius": sh["radius"],
                           "material": json_material(sh["material"])})
        elif "mesh" in sh:
            verts, faces = sh["mesh"]
            shapes.append({"type": "trimesh", "vertices": [list(p) for p in verts],
                           "faces": [list(f) for f in faces],
                           "material": json_material(sh["material"])})
        else:
            q = sh["quad"]
            shapes.append({"type": "plane", "v0": list(q[0]), "v1": list(q[1]), "v2": list(q[2]),
                           "v3": list(q[3]), "material": json_material(sh["material"])})
    c = s["camera"]
    camera = {"type": "pinhole", "width": s["size"], "height": s["size"],
              "position": list(c["position"]), "lookAt": list(c["lookat"]),
              "upVector": [0, 1, 0], "fov": c["fov"], "exposure": 1.0}
    if "aperture" in c:
        camera.update({"type": "thinlens", "aperture": c["aperture"],
                       "focusdistance": c["focus"], "samplesize": c["lens_samples"]})
    return {
        "nbounces": s["nbounces"], "rendermode": "phong",
        "camera": camera,
        "scene": {"backgroundcolor": list(s["background"]), "ambientlight": [0, 0, 0],
                  "lightsources": lights, "shapes": shapes},
    }


# ---- POV-Ray 3.7 ----

def v(p):
    return "<%g, %g, %g>" % tuple(p)


def own_share(m):
    """What a CGR file leaves the surface's own shading: 1 less its mirror and glass weights."""
    mirror = min(m.get("mirror", 0.0), 1.0)
    glass = (1.0 - mirror) if "glass" in m else 0.0
    return 1.0 - mirror - glass


def pov_finish(m):
    own = own_share(m)
    f = "ambient 0 diffuse %g specular %g roughness %g" % (m["kd"] * own, m["ks"] * own, 1.0 / m["exp"])
    if "mirror" in m:
        f += " reflection %g" % m["mirror"]
    if "glass" in m:
        f += " reflection { 0, 1 fresnel on } conserve_energy"
    return "finish { %s }" % f


def pov_texture(m, uv=False):
    if "texture" in m:
        pig = 'pigment { uv_mapping image_map { png "%s" interpolate 2 } }' % m["texture"]
    elif "glass" in m:
        pig = "pigment { rgbf <1, 1, 1, 1> }"
    else:
        pig = "pigment { rgb %s }" % v(m["color"])
    tex = "texture { %s %s }" % (pig, pov_finish(m))
    if "glass" in m:
        tex += " interior { ior %g }" % m["glass"]
    return tex


def to_pov(s):
    c = s["camera"]
    lens = ""
    if "aperture" in c:
        # Focal blur with exactly the lens samples of the JSON camera (no adaptive stop), the
        # plane in focus through the point the focus distance reaches along the view.
        d = [b - a for a, b in zip(c["position"], c["lookat"])]
        n = math.sqrt(sum(x * x for x in d))
        focal = [a + c["focus"] * x / n for a, x in zip(c["position"], d)]
        lens = " aperture %g blur_samples %d, %d confidence 1 variance 0 focal_point %s" % (
            c["aperture"], c["lens_samples"], c["lens_samples"], v(focal))
    out = [
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level %d ambient_light 0 }"
        % (s["nbounces"] + 1),
        "background { rgb %s }" % v(s["background"]),
        "camera { perspective location %s look_at %s sky y right x up y angle %g%s }"
        % (v(c["position"]), v(c["lookat"]), c["fov"], lens),
    ]
    for l in s["lights"]:
        col = "rgb %g" % l["intensity"]
        if "point" in l:
            out.append("light_source { %s color %s }" % (v(l["point"]), col))
        else:
            n, a = l["samples"], l["size"]
            out.append("light_source { %s color %s area_light <%g, 0, 0>, <0, 0, %g>, %d, %d jitter }"
                       % (v(l["area"]), col, a, a, n, n))
    for sh in s["shapes"]:
        m = sh["material"]
        if "sphere" in sh:
            out.append("sphere { %s, %g %s }" % (v(sh["sphere"]), sh["radius"], pov_texture(m)))
        elif "mesh" in sh:
            verts, faces = sh["mesh"]
            out.append("mesh2 { vertex_vectors { %d, %s } face_indices { %d, %s } %s }"
                       % (len(verts), ", ".join(v(p) for p in verts), len(faces),
                          ", ".join("<%d, %d, %d>" % f for f in faces), pov_texture(m)))
        else:
            q = sh["quad"]
            out.append("mesh2 { vertex_vectors { 4, %s } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> }"
                       " face_indices { 2, <0, 1, 2>, <0, 2, 3> } %s }"
                       % (", ".join(v(p) for p in q), pov_texture(m)))
    return "\n".join(out) + "\n"


def write_all(folder):
    os.makedirs(folder, exist_ok=True)
    for name, s in SCENES.items():
        with open(os.path.join(folder, name + ".json"), "w") as f:
            json.dump(to_json(s), f, indent=1)
            f.write("\n")
        with open(os.path.join(folder, name + ".pov"), "w") as f:
            f.write(to_pov(s))


if __name__ == "__main__":
    write_all(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "scenes"))
