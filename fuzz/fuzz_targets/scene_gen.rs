//! Structure-aware scene generator: the fuzz bytes drive a generator that writes a *well-formed*
//! scene file in the coursework format (any of its three variants, every key spelling the loader
//! reads), with values drawn from a pool of hostile numbers (signed zeros, subnormals, values at
//! and past the `f32` range, huge integers, negative counts, now and then `NaN` or `Infinity`)
//! and, now and then, very large arrays or objects with many keys. The forms include infinite
//! planes, `rectangleXY`/`XZ`/`YZ`, centred and rotated boxes and rectangles, mesh placements
//! (`euler`, `r1`..`r3`), poly spheres (`n`, `locX`..`locZ`), a `textures` library named by
//! materials, area lights with a `shape` or a `shapeid`, attenuation (`kc`, `kl`, `kq`), ambient
//! light, and the scene-level sample counts. The text then goes through
//! exactly what the `scene_loader` target does with a scene: `load_str` with the same small
//! limits, the same scratch folder of bundled meshes and textures, and a 4×4 render of a scene
//! that loads.
//!
//! Checked: no panic; an error starts with the scene's path; a loaded scene renders to 16 pixels
//! and tone-maps; and when every number in the file came from the moderate part of the pool
//! (|x| ≤ 10, on a 0.01 grid), every rendered pixel is finite.
//!
//! With the environment variable `SCENE_GEN_PRINT` set, each input's scene is printed to stderr
//! (for replaying an artifact).
//!
//! Random byte inputs rarely get past the JSON parser or the first required key; this target
//! spends nearly all of its time past them, in the conversion, the limits, the mesh and texture
//! readers and the renderer.
#![no_main]

mod common;

use std::fmt::Write as _;
use std::path::Path;
use std::sync::OnceLock;

use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;
use raytracer::scene::load_str;

/// Upper bound on the JSON text of one input, in bytes (approximate: the generator stops adding
/// large parts once it is spent).
const BUDGET: usize = 900_000;

fuzz_target!(|data: &[u8]| {
    let mut g = Gen::new(data);
    let root = g.scene();
    let style = Style {
        trailing_commas: g.chance(1, 16),
        comments: g.chance(1, 16),
        pretty: g.chance(1, 4),
    };
    let choice = common::RenderChoice {
        spp: 1 + g.range(0, 1),
        plain_list: g.chance(1, 3),
    };
    let mut text = String::new();
    write_json(&root, &style, 0, &mut text);
    assert!(text.len() < 2 * BUDGET, "generator overran its budget");
    if std::env::var_os("SCENE_GEN_PRINT").is_some() {
        // For replaying an input: the scene it stands for.
        eprintln!("{text}");
    }

    let opts = common::load_options();
    let path = scene_path();
    let scene = match load_str(&text, path, &opts) {
        Ok(scene) => scene,
        Err(e) => {
            common::check_scene_error(path, &e);
            return;
        }
    };
    let film = common::render_scene(&scene, choice);
    if !g.hostile {
        assert!(
            film.pixels.iter().all(|p| p.is_finite()),
            "a scene of moderate numbers rendered non-finite pixels: {:?}",
            film.pixels
        );
    }
});

/// The scene's path in the scratch folder (see `common::scene_path`), with three-by-two texel
/// textures in every readable format written beside the bundled ones on first use.
fn scene_path() -> &'static Path {
    static PATH: OnceLock<&'static Path> = OnceLock::new();
    PATH.get_or_init(|| {
        let path = common::scene_path();
        let dir = common::scratch().join("textures");
        let img = image::RgbImage::from_fn(3, 2, |x, y| {
            image::Rgb([(x * 100) as u8, (y * 200) as u8, 255 - (x * 40) as u8])
        });
        for name in ["tiny.png", "tiny.jpg", "tiny.ppm"] {
            img.save(dir.join(name)).expect("write a small texture");
        }
        image::DynamicImage::ImageRgb8(img)
            .to_rgb32f()
            .save(dir.join("tiny.exr"))
            .expect("write a small texture");
        path
    })
}

// ---------------------------------------------------------------------------------------------
// A small JSON tree and its writer (numbers are kept as their literal text, so that `-0`, `1e999`,
// `NaN` and `Infinity` can be written as such).

enum J {
    /// A number, `true`, `false` or `null`, as written.
    Lit(String),
    Str(String),
    Arr(Vec<J>),
    Obj(Vec<(String, J)>),
}

fn lit(s: &str) -> J {
    J::Lit(s.to_string())
}

fn s(text: &str) -> J {
    J::Str(text.to_string())
}

struct Style {
    trailing_commas: bool,
    comments: bool,
    pretty: bool,
}

fn write_str(text: &str, out: &mut String) {
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn newline(style: &Style, depth: usize, out: &mut String) {
    if style.pretty {
        out.push('\n');
        for _ in 0..depth {
            out.push_str("  ");
        }
    }
}

fn write_json(v: &J, style: &Style, depth: usize, out: &mut String) {
    match v {
        J::Lit(t) => out.push_str(t),
        J::Str(t) => write_str(t, out),
        J::Arr(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_json(item, style, depth + 1, out);
            }
            if style.trailing_commas && !items.is_empty() {
                out.push(',');
            }
            out.push(']');
        }
        J::Obj(entries) => {
            out.push('{');
            for (i, (k, item)) in entries.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                newline(style, depth + 1, out);
                if style.comments && i == 0 {
                    out.push_str("/* keys */ ");
                }
                write_str(k, out);
                out.push(':');
                write_json(item, style, depth + 1, out);
            }
            if style.trailing_commas && !entries.is_empty() {
                out.push(',');
            }
            if style.comments {
                out.push_str(" // end\n");
            }
            newline(style, depth, out);
            out.push('}');
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Value pools.

/// Hostile numbers for any numeric key.
const HOSTILE_NUMBERS: &[&str] = &[
    "0",
    "-0",
    "-0.0",
    "1e-40",
    "-1e-40",
    "1e-45",
    "1.17549435e-38",
    "1e-7",
    "-1e-7",
    "1e38",
    "-1e38",
    "3.4e38",
    "-3.4e38",
    "3.4028235e38",
    "3.4028236e38",
    "1e30",
    "-1e30",
    "4294967296",
    "4294967295",
    "2147483648",
    "-2147483649",
    "18446744073709551616",
    "9007199254740993",
    "65536",
    "65537",
    "1e9",
    "180",
    "179.99999",
    "1.0000001",
    "0.99999994",
    "1e-300",
    "1e300",
    "NaN",
    "Infinity",
    "-Infinity",
    "1e999",
    "-1",
    "+.5",
];

/// Hostile values for whole-number keys (sizes, counts, indices).
const HOSTILE_COUNTS: &[&str] = &[
    "0",
    "-0",
    "-1",
    "-2147483648",
    "1",
    "2",
    "2.5",
    "255",
    "256",
    "257",
    "4096",
    "65535",
    "65536",
    "65537",
    "1e9",
    "1e30",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "3.4e38",
    "1e-40",
    "NaN",
    "Infinity",
];

/// Hostile refractive indices: at and near 1, zero, tiny, huge, negative.
const ODD_ETA: &[&str] = &[
    "1",
    "1.0000001",
    "0.99999994",
    "0",
    "-0",
    "-1.5",
    "1e-40",
    "1e-7",
    "1e38",
    "3.4e38",
    "NaN",
];

/// Texture paths, relative to the scene's folder. The `tiny.*` images (3×2 pixels) are written
/// by this harness; they keep most inputs fast.
const TEXTURES: &[&str] = &[
    "../textures/tiny.png",
    "../textures/tiny.png",
    "../textures/tiny.jpg",
    "../textures/tiny.ppm",
    "../textures/tiny.exr",
    "..\\textures\\tiny.png",
    "textures/tiny.png",
    "build/../../textures/tiny.jpg",
    "./../textures/./tiny.ppm",
    "../textures/tiny.PNG",
    "../textures/nope.png",
    "meshes/crate.obj",
    "meshes/blob.ply",
    "fuzz.json",
    "",
    "noext",
    "../textures",
    "meshes/",
    "/dev/zero.png",
];

/// The bundled textures (hundreds of thousands of texels each: slow to decode), used now and
/// then.
const BUNDLED_TEXTURES: &[&str] = &[
    "../textures/checker.png",
    "../textures/uvgrid.png",
    "../textures/sicily.jpg",
    "../textures/sky-map.jpg",
];

const MESH_FILES: &[&str] = &[
    "meshes/crate.obj",
    "meshes/crate.obj",
    "meshes\\crate.obj",
    "meshes/crate.obj",
    "meshes/blob.ply",
    "meshes/torus.ply",
    "meshes/BLOB.PLY",
    "meshes/generate.py",
    "meshes/missing.ply",
    "../textures/checker.png",
    "meshes",
    "fuzz.json",
    "meshes/blob.stl",
    "",
];

// ---------------------------------------------------------------------------------------------
// The generator.

struct Gen<'a> {
    u: Unstructured<'a>,
    /// Approximate JSON bytes still to spend on large parts.
    budget: usize,
    /// Whether any number came from the hostile pools.
    hostile: bool,
    /// One number in `rate` is hostile (0: none), chosen per input, so that some inputs are
    /// ordinary scenes that load and render and others are hostile throughout.
    rate: u32,
    /// Names of the materials defined so far.
    material_names: Vec<String>,
}

impl<'a> Gen<'a> {
    fn new(data: &'a [u8]) -> Self {
        let mut g = Gen {
            u: Unstructured::new(data),
            budget: BUDGET,
            hostile: false,
            rate: 0,
            material_names: Vec::new(),
        };
        g.rate = g.pick(&[0, 64, 16, 4]);
        g
    }

    /// Whether the next value is to be hostile (and then records that one was).
    fn go_hostile(&mut self) -> bool {
        let yes = self.rate > 0 && self.chance(1, self.rate);
        self.hostile |= yes;
        yes
    }

    fn range(&mut self, lo: u32, hi: u32) -> u32 {
        self.u.int_in_range(lo..=hi).unwrap_or(lo)
    }

    /// True with probability `n / d`; once the input is used up, the likelier outcome, so that
    /// the rest of the scene is the most ordinary one.
    fn chance(&mut self, n: u32, d: u32) -> bool {
        if self.u.is_empty() {
            return 2 * n > d;
        }
        self.u.ratio(n, d).unwrap_or(false)
    }

    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.u.choose_index(items.len()).unwrap_or(0)]
    }

    fn spend(&mut self, bytes: usize) {
        self.budget = self.budget.saturating_sub(bytes);
    }

    /// A length for an array or a key count: small mostly, now and then large (up to `big`),
    /// never more than the budget allows at about `each` bytes an element.
    fn length(&mut self, small: u32, big: u32, each: usize) -> usize {
        let n = if self.chance(1, 64) {
            self.range(0, big) as usize
        } else {
            self.range(0, small) as usize
        };
        let n = n.min(self.budget / each.max(1));
        self.spend(n * each);
        n
    }

    /// A moderate number: a multiple of 0.01 in [-10, 10], or a small integer.
    fn moderate(&mut self) -> String {
        if self.chance(1, 2) {
            format!("{}", self.range(0, 12) as i32 - 2)
        } else {
            let v = self.range(0, 2000) as i32 - 1000;
            format!("{}", v as f64 / 100.0)
        }
    }

    /// Any number: moderate, or hostile at the input's rate.
    fn num(&mut self) -> J {
        if self.go_hostile() {
            lit(self.pick(HOSTILE_NUMBERS))
        } else {
            J::Lit(self.moderate())
        }
    }

    /// A positive moderate number (radii, sizes, focus distances), now and then hostile.
    fn positive(&mut self) -> J {
        if self.go_hostile() {
            lit(self.pick(HOSTILE_NUMBERS))
        } else {
            let v = self.range(1, 500);
            J::Lit(format!("{}", v as f64 / 100.0))
        }
    }

    /// A whole number below `hi`, now and then from the hostile counts.
    fn count(&mut self, hi: u32) -> J {
        if self.go_hostile() {
            lit(self.pick(HOSTILE_COUNTS))
        } else {
            J::Lit(self.range(0, hi).to_string())
        }
    }

    /// A field of view in degrees.
    fn fov(&mut self) -> J {
        if self.chance(5, 6) {
            lit(self.pick(&["45", "30", "60", "90", "40", "1", "179", "35.5"]))
        } else {
            self.num()
        }
    }

    fn bool(&mut self) -> J {
        lit(self.pick(&[
            "true",
            "false",
            "true",
            "false",
            "1",
            "0",
            "2.5",
            "\"true\"",
            "\"FALSE\"",
            "\"yes\"",
            "null",
        ]))
    }

    /// Three numbers, now and then the wrong shape.
    fn vec3(&mut self) -> J {
        self.spend(24);
        if self.go_hostile() && self.chance(1, 8) {
            return match self.range(0, 3) {
                0 => {
                    let n = self.range(0, 5) as usize;
                    J::Arr((0..n).map(|_| self.num()).collect())
                }
                1 => J::Arr(vec![self.num(), s("1"), self.num()]),
                2 => self.num(),
                _ => s("0 0 0"),
            };
        }
        J::Arr(vec![self.num(), self.num(), self.num()])
    }

    /// A colour: three numbers, or one.
    fn colour(&mut self) -> J {
        if self.chance(1, 5) {
            self.num()
        } else {
            self.vec3()
        }
    }

    /// Texture coordinates `[u, v]`, now and then the wrong length.
    fn uv(&mut self) -> J {
        let n = if self.chance(1, 20) {
            self.range(0, 4) as usize
        } else {
            2
        };
        J::Arr((0..n).map(|_| self.num()).collect())
    }

    /// Now and then, extra keys: unknown ones (many of them, now and then), or a repeat of a key
    /// already present (the loader uses the first).
    fn extra_keys(&mut self, obj: &mut Vec<(String, J)>) {
        if self.chance(1, 12) {
            let n = self.length(4, 2000, 16);
            for i in 0..n {
                let v = if i % 2 == 0 { self.num() } else { s("x") };
                obj.push((format!("k{i}"), v));
            }
        }
        if !obj.is_empty() && self.chance(1, 16) {
            let i = self.u.choose_index(obj.len()).unwrap_or(0);
            let key = obj[i].0.clone();
            let v = self.num();
            obj.push((key, v));
        }
        if obj.len() > 1 && self.chance(1, 8) {
            // Key order should not matter.
            let i = self.u.choose_index(obj.len()).unwrap_or(0);
            let last = obj.len() - 1;
            obj.swap(i, last);
        }
    }

    // --- the scene -----------------------------------------------------------------------------

    fn scene(&mut self) -> J {
        // 0: 2019, 1: 2021–23, 2: CGR.
        let variant = self.range(0, 2);
        let mut root = Vec::new();
        if variant == 2 || self.chance(1, 30) {
            let mode = match self.range(0, 7) {
                0 => self.num(),
                1 => s("binary"),
                2 => s("pathtracer"),
                3 => s("BINARY"),
                4 => s("pathtrace"),
                5 => s(self.pick(&["PathTrace", "pt", "path", "pathtracing", "raytrace"])),
                _ => s("phong"),
            };
            root.push(("rendermode".to_string(), mode));
        }
        let bounce_key = self.pick(&["nbounces", "nbounces", "maxdepth", "max_depth"]);
        if self.chance(7, 8) {
            let n = self.count(8);
            root.push((bounce_key.to_string(), n));
        }
        let camera = self.camera(variant);
        root.push(("camera".to_string(), camera));
        if self.chance(1, 10) {
            let e = self.num();
            root.push(("exposure".to_string(), e));
        }
        if self.chance(1, 12) {
            let a = self.positive();
            root.push(("aperture".to_string(), a));
        }
        if self.chance(1, 12) {
            let key = self.pick(&["focus_distance", "focusdistance"]);
            let f = self.positive();
            root.push((key.to_string(), f));
        }
        if self.chance(1, 10) {
            let w = self.count(16);
            let h = self.count(16);
            root.push((
                "settings".to_string(),
                J::Obj(vec![("width".to_string(), w), ("height".to_string(), h)]),
            ));
        }
        self.sample_counts(&mut root);
        let textures_at_root = self.chance(1, 2);
        let textures = if self.chance(1, 5) {
            Some(self.texture_library())
        } else {
            None
        };
        let materials_at_root = self.chance(1, 2);
        let materials = if self.chance(1, 5) {
            Some(self.materials())
        } else {
            None
        };
        let mut body = Vec::new();
        if self.chance(9, 10) {
            let key = self.pick(&[
                "backgroundcolor",
                "backgroundcolor",
                "backgroundcolour",
                "background",
            ]);
            let c = self.colour();
            body.push((key.to_string(), c));
        }
        if variant == 2 && self.chance(1, 3) || self.chance(1, 10) {
            let key = self.pick(&["ambientlight", "ambientintensity", "ambient"]);
            let c = self.colour();
            body.push((key.to_string(), c));
        }
        if self.chance(9, 10) {
            let key = self.pick(&["lightsources", "lightsources", "lights", "lightSources"]);
            let n = self.length(3, 300, 120);
            let lights = (0..n).map(|_| self.light()).collect();
            body.push((key.to_string(), J::Arr(lights)));
        }
        if self.chance(19, 20) {
            let key = self.pick(&["shapes", "shapes", "objects", "geometry"]);
            let n = self.length(4, 500, 200);
            let shapes = (0..n).map(|_| self.shape()).collect();
            body.push((key.to_string(), J::Arr(shapes)));
        } else if self.chance(1, 2) {
            body.push(("shapes".to_string(), self.num()));
        }
        if let Some(t) = textures {
            if textures_at_root {
                root.push(("textures".to_string(), t));
            } else {
                body.push(("textures".to_string(), t));
            }
        }
        if let Some(m) = materials {
            if materials_at_root {
                root.push(("materials".to_string(), m));
            } else {
                body.push(("materials".to_string(), m));
            }
        }
        self.extra_keys(&mut body);
        if self.chance(1, 10) {
            // No `scene` object: the root holds the scene's keys.
            root.extend(body);
        } else {
            root.push(("scene".to_string(), J::Obj(body)));
        }
        self.extra_keys(&mut root);
        J::Obj(root)
    }

    fn camera(&mut self, variant: u32) -> J {
        let mut cam = Vec::new();
        let ty = if self.chance(4, 5) {
            "pinhole"
        } else {
            self.pick(&[
                "perspective",
                "PinHole",
                "thinlens",
                "thinlen",
                "thin_lens",
                "lens",
                "aperture",
                "dof",
                "orthographic",
            ])
        };
        if self.chance(15, 16) {
            cam.push(("type".to_string(), s(ty)));
        }
        if self.chance(15, 16) {
            let w = self.count(1000);
            cam.push(("width".to_string(), w));
        }
        if self.chance(15, 16) {
            let h = self.count(1000);
            cam.push(("height".to_string(), h));
        }
        if self.chance(11, 12) {
            let f = self.fov();
            cam.push(("fov".to_string(), f));
        }
        if self.chance(1, 10) {
            let f = self.fov();
            cam.push(("hfov".to_string(), f));
        }
        if variant >= 1 {
            if self.chance(7, 8) {
                let key = self.pick(&[
                    "position", "position", "location", "origin", "lookfrom", "camPos", "eye",
                ]);
                let p = self.vec3();
                cam.push((key.to_string(), p));
            }
            if self.chance(7, 8) {
                let key = if variant == 1 {
                    "lookat"
                } else {
                    self.pick(&["lookAt", "lookAt", "look_at", "look", "camView", "target"])
                };
                let d = self.vec3();
                cam.push((key.to_string(), d));
            }
            if self.chance(7, 8) {
                let key = if variant == 1 {
                    self.pick(&["up", "up", "vup", "camAxis"])
                } else {
                    "upVector"
                };
                let up = self.vec3();
                cam.push((key.to_string(), up));
            }
            if variant == 2 && self.chance(1, 2) {
                let e = self.num();
                cam.push(("exposure".to_string(), e));
            }
        }
        if self.chance(1, 6) {
            let m = self.sampler_name();
            cam.push(("sampler".to_string(), m));
        }
        if ty != "pinhole" || self.chance(1, 10) {
            if self.chance(1, 4) {
                let key = self.pick(&["samplesize", "nsamples"]);
                let n = self.count(16);
                cam.push((key.to_string(), n));
            }
            if self.chance(3, 4) {
                let key = self.pick(&[
                    "size",
                    "lensRadius",
                    "lensradius",
                    "lens_radius",
                    "radius",
                    "aperture",
                    "aperture_size",
                    "diameter",
                    "ap",
                    "d",
                ]);
                let a = if self.chance(1, 5) {
                    self.num()
                } else {
                    self.positive()
                };
                cam.push((key.to_string(), a));
            }
            if self.chance(3, 4) {
                let key = self.pick(&[
                    "focusdistance",
                    "focus_distance",
                    "focalDistance",
                    "focusDistance",
                    "focus_dist",
                    "focalLength",
                    "focal_length",
                    "focal",
                    "focus",
                    "f",
                ]);
                let f = if self.chance(1, 5) {
                    self.num()
                } else {
                    self.positive()
                };
                cam.push((key.to_string(), f));
            }
        }
        self.extra_keys(&mut cam);
        J::Obj(cam)
    }

    fn materials(&mut self) -> J {
        let n = self.length(3, 200, 200);
        let mut list = Vec::new();
        for i in 0..n {
            let mut m = self.material_fields();
            let name = if self.chance(1, 10) {
                self.pick(&["", "glass", "m0"]).to_string()
            } else {
                format!("m{i}")
            };
            if self.chance(15, 16) {
                m.insert(0, ("name".to_string(), s(&name)));
            }
            self.material_names.push(name);
            list.push(J::Obj(m));
        }
        J::Arr(list)
    }

    /// A shape's `material`: an object, a name, or the wrong type.
    fn material(&mut self) -> J {
        if !self.material_names.is_empty() && self.chance(1, 3) {
            let i = self.u.choose_index(self.material_names.len()).unwrap_or(0);
            return J::Str(self.material_names[i].clone());
        }
        match self.range(0, 30) {
            0 => s("undefined-material"),
            1 => self.num(),
            _ => J::Obj(self.material_fields()),
        }
    }

    fn material_fields(&mut self) -> Vec<(String, J)> {
        let mut m = Vec::new();
        if self.chance(1, 4) {
            let v = self.num();
            m.push(("ka".to_string(), v));
        }
        if self.chance(3, 4) {
            let v = self.num();
            m.push(("kd".to_string(), v));
        }
        if self.chance(2, 3) {
            let v = self.num();
            m.push(("ks".to_string(), v));
        }
        if self.chance(2, 3) {
            let key = self.pick(&[
                "specularexponent",
                "specular_exponent",
                "shininess",
                "exponent",
                "alpha",
            ]);
            let v = self.num();
            m.push((key.to_string(), v));
        }
        if self.chance(3, 4) {
            let key = self.pick(&[
                "diffusecolor",
                "diffusecolour",
                "diffuse_color",
                "color",
                "colour",
                "diffuse",
            ]);
            let v = self.colour();
            m.push((key.to_string(), v));
        }
        if self.chance(1, 3) {
            let key = self.pick(&["specularcolor", "specularcolour", "specular_color"]);
            let v = self.colour();
            m.push((key.to_string(), v));
        }
        if self.chance(1, 3) {
            let key = self.pick(&["kr", "reflectivity", "reflection", "reflectance"]);
            let v = self.num();
            m.push((key.to_string(), v));
        }
        if self.chance(1, 4) {
            let key = self.pick(&["isreflective", "isReflective"]);
            let v = self.bool();
            m.push((key.to_string(), v));
        }
        let glass = self.chance(1, 3);
        if glass {
            let key = self.pick(&["kt", "transparency", "transmit", "transmittance"]);
            let v = if self.chance(3, 4) {
                lit(self.pick(&["1", "0.9", "0.5"]))
            } else {
                self.num()
            };
            m.push((key.to_string(), v));
        }
        if glass || self.chance(1, 6) {
            let key = self.pick(&["isrefractive", "isRefractive", "isGlass"]);
            let v = self.bool();
            m.push((key.to_string(), v));
        }
        if glass || self.chance(1, 6) {
            let key = self.pick(&[
                "eta",
                "refractiveindex",
                "refractiveIndex",
                "refractive_index",
                "ior",
            ]);
            let v = if self.go_hostile() {
                self.pick(ODD_ETA)
            } else {
                self.pick(&["1.5", "1", "0.5", "2.4", "1.33", "100"])
            };
            m.push((key.to_string(), lit(v)));
        }
        if self.chance(1, 5) {
            self.texture(&mut m);
        }
        if self.chance(1, 5) {
            // A texture of the library, by name (`diffuse` as a string is a texture).
            let key = self.pick(&["texture", "diffuse", "diffuse", "tPath", "texturepath"]);
            let v = self.texture_name();
            m.push((key.to_string(), v));
        }
        self.extra_keys(&mut m);
        m
    }

    /// The name of a texture of the library (`t0`..`t3`), one it does not define, or the wrong
    /// type.
    fn texture_name(&mut self) -> J {
        match self.range(0, 15) {
            0 => s("wood"),
            1 => s(""),
            2 => self.num(),
            3 => s(self.pick(TEXTURES)),
            _ => J::Str(format!("t{}", self.range(0, 3))),
        }
    }

    /// A `textures` library: constant colours and images (with uv offsets), by name.
    fn texture_library(&mut self) -> J {
        let n = self.length(4, 300, 100);
        let mut list = Vec::new();
        for i in 0..n {
            let mut t = Vec::new();
            if self.chance(15, 16) {
                let name = if self.chance(1, 10) {
                    J::Str(
                        self.pick(&["", "t0", "wood", "../textures/tiny.png"])
                            .to_string(),
                    )
                } else if self.chance(1, 40) {
                    self.num()
                } else {
                    J::Str(format!("t{i}"))
                };
                t.push(("name".to_string(), name));
            }
            match self.range(0, 8) {
                0..=3 => {
                    if self.chance(15, 16) {
                        let ty = self.pick(&["constant", "constant", "Constant", "CONSTANT"]);
                        t.push(("type".to_string(), s(ty)));
                    }
                    if self.chance(15, 16) {
                        let key = self.pick(&["colour", "colour", "color"]);
                        let c = self.colour();
                        t.push((key.to_string(), c));
                    }
                }
                4..=6 => {
                    if self.chance(15, 16) {
                        let ty = self.pick(&["image", "image", "Image"]);
                        t.push(("type".to_string(), s(ty)));
                    }
                    if self.chance(15, 16) {
                        let key = self.pick(&["image", "image", "path", "file", "filename"]);
                        let path = if self.chance(1, 16) {
                            self.pick(BUNDLED_TEXTURES)
                        } else {
                            self.pick(TEXTURES)
                        };
                        let v = if self.chance(1, 20) {
                            self.num()
                        } else {
                            s(path)
                        };
                        t.push((key.to_string(), v));
                    }
                    for key in ["offset_u", "offset_v"] {
                        if self.chance(1, 2) {
                            let v = self.num();
                            t.push((key.to_string(), v));
                        }
                    }
                }
                _ => {
                    let ty = if self.chance(1, 4) {
                        self.num()
                    } else {
                        s(self.pick(&["checker", "wood", "", "noise", "images"]))
                    };
                    t.push(("type".to_string(), ty));
                    let c = self.colour();
                    t.push(("colour".to_string(), c));
                    t.push(("image".to_string(), s("../textures/tiny.png")));
                }
            }
            self.extra_keys(&mut t);
            list.push(J::Obj(t));
        }
        J::Arr(list)
    }

    /// The scene's sample counts (each now and then): samples per pixel, shadow rays per area
    /// light, and the path tracer's count that is only warned about.
    fn sample_counts(&mut self, root: &mut Vec<(String, J)>) {
        if self.chance(1, 4) {
            let key = self.pick(&[
                "pixelsample",
                "pixel_sample_num",
                "nspp",
                "sample_number",
                "camera samples",
                "nsamples",
            ]);
            let n = self.count(20);
            root.push((key.to_string(), n));
        }
        if self.chance(1, 5) {
            let key = self.pick(&["lightsample", "shadow samples", "spp", "sample_number"]);
            let n = self.count(20);
            root.push((key.to_string(), n));
        }
        if self.chance(1, 20) {
            let n = self.count(20);
            root.push(("path_sample_num".to_string(), n));
        }
    }

    /// A sampling method's name, now and then an unknown one or the wrong type.
    fn sampler_name(&mut self) -> J {
        if self.chance(1, 20) {
            return self.num();
        }
        s(self.pick(&[
            "jittered",
            "stratified",
            "jitter",
            "random",
            "uniform",
            "sobol",
            "SOBOL",
            "halton",
            "",
        ]))
    }

    /// A texture key: a path string, an object holding one (or none), plus ignored size keys.
    fn texture(&mut self, obj: &mut Vec<(String, J)>) {
        let key = self.pick(&[
            "tPath",
            "tPath",
            "texture",
            "texturepath",
            "texture_file",
            "texturemap",
            "texture_path",
            "tpath",
        ]);
        let path = if self.chance(1, 16) {
            self.pick(BUNDLED_TEXTURES)
        } else {
            self.pick(TEXTURES)
        };
        let v = match self.range(0, 7) {
            0 => {
                let pkey = self.pick(&["path", "file", "filename", "tPath", "name"]);
                J::Obj(vec![(pkey.to_string(), s(path))])
            }
            1 => self.num(),
            _ => s(path),
        };
        obj.push((key.to_string(), v));
        if self.chance(1, 3) {
            let w = self.count(1000);
            let h = self.count(1000);
            obj.push(("tWidth".to_string(), w));
            obj.push(("tHeight".to_string(), h));
        }
    }

    // --- lights ----------------------------------------------------------------------------

    fn light(&mut self) -> J {
        let mut l = Vec::new();
        match self.range(0, 10) {
            9 => {
                let ty = self.pick(&["ambient", "ambient", "ambientlight", "Ambient"]);
                l.push(("type".to_string(), s(ty)));
                if self.chance(15, 16) {
                    let key = self.pick(&["intensity", "color", "colour"]);
                    let c = self.colour();
                    l.push((key.to_string(), c));
                }
                self.extra_keys(&mut l);
                return J::Obj(l);
            }
            0..=4 => {
                let ty = self.pick(&[
                    "pointlight",
                    "pointlight",
                    "point",
                    "point_light",
                    "PointLight",
                ]);
                l.push(("type".to_string(), s(ty)));
                if self.chance(15, 16) {
                    let key = self.pick(&["position", "position", "pos"]);
                    let p = self.vec3();
                    l.push((key.to_string(), p));
                }
            }
            5..=8 => {
                let ty = self.pick(&["arealight", "arealight", "area", "area_light", "quadlight"]);
                l.push(("type".to_string(), s(ty)));
                self.area_geometry(&mut l);
                if self.chance(3, 4) {
                    let key = self.pick(&["samples", "samples", "nsamples", "samplesize", "cell"]);
                    let n = self.count(5);
                    l.push((key.to_string(), n));
                }
                if self.chance(2, 3) {
                    let key = self.pick(&["method", "sampler", "sampling"]);
                    let m = self.sampler_name();
                    l.push((key.to_string(), m));
                }
            }
            _ => {
                if self.chance(3, 4) {
                    let ty = self.pick(&["pointlightss", "spotlight", "directional", ""]);
                    l.push(("type".to_string(), s(ty)));
                }
                let p = self.vec3();
                l.push(("position".to_string(), p));
            }
        }
        self.light_power(&mut l);
        self.extra_keys(&mut l);
        J::Obj(l)
    }

    fn light_power(&mut self, l: &mut Vec<(String, J)>) {
        if self.chance(1, 2) {
            if self.chance(5, 6) {
                let c = self.colour();
                l.push(("is".to_string(), c));
            }
            if self.chance(5, 6) {
                let c = self.colour();
                l.push(("id".to_string(), c));
            }
        } else if self.chance(5, 6) {
            let key = self.pick(&["intensity", "intensity", "power"]);
            let c = self.colour();
            l.push((key.to_string(), c));
        }
        for key in ["color", "colour", "diffuse", "specular"] {
            if self.chance(1, 10) {
                let c = self.colour();
                l.push((key.to_string(), c));
            }
        }
        if self.chance(1, 4) {
            // Attenuation coefficients: 1/(kc + kl·d + kq·d²).
            for key in ["kc", "kl", "kq"] {
                if self.chance(2, 3) {
                    let v = if self.chance(3, 4) {
                        self.positive()
                    } else {
                        self.num()
                    };
                    l.push((key.to_string(), v));
                }
            }
        }
    }

    fn area_geometry(&mut self, l: &mut Vec<(String, J)>) {
        match self.range(0, 11) {
            8 => {
                // A sphere light.
                let mut sh = Vec::new();
                if self.chance(15, 16) {
                    let ty = self.pick(&["sphere", "sphere", "uvsphere", "Sphere"]);
                    sh.push(("type".to_string(), s(ty)));
                }
                self.centre(&mut sh);
                if self.chance(15, 16) {
                    let r = self.positive();
                    sh.push(("radius".to_string(), r));
                }
                self.extra_keys(&mut sh);
                l.push(("shape".to_string(), J::Obj(sh)));
                return;
            }
            9 => {
                // A quad or triangle light, by its corners.
                let mut sh = Vec::new();
                let ty = self.pick(&[
                    "plane",
                    "quad",
                    "rectangle",
                    "planarquad",
                    "triangle",
                    "triangle",
                    "box",
                    "",
                ]);
                if self.chance(15, 16) {
                    sh.push(("type".to_string(), s(ty)));
                }
                if ty == "triangle" {
                    self.triangle(&mut sh);
                } else {
                    self.corners(
                        &mut sh,
                        &[
                            &["v0", "v1", "v2", "v3"],
                            &["point1", "point2", "point3", "point4"],
                        ],
                        &[&["uv0", "uv1", "uv2", "uv3"]],
                    );
                }
                let v = if self.chance(1, 30) {
                    self.num()
                } else {
                    J::Obj(sh)
                };
                l.push(("shape".to_string(), v));
                return;
            }
            10 => {
                // A shape of the scene, by its `id`.
                let id = self.shape_id();
                l.push(("shapeid".to_string(), id));
                return;
            }
            _ => {}
        }
        let names: &[&str] = match self.range(0, 7) {
            0 => &["v0", "v1", "v2", "v3"],
            1 => &["v0", "v1", "v2"],
            2 => &["c1", "c2", "c3"],
            3 => &["p", "e0", "e1"],
            4 => &["position", "u", "v"],
            5 => &["position"],
            6 => &[],
            _ => &["v0", "v1", "v2", "v3"],
        };
        for name in names {
            let v = self.vec3();
            l.push((name.to_string(), v));
        }
        if names == ["position", "u", "v"] && self.chance(1, 2) {
            let w = self.positive();
            let h = self.positive();
            l.push(("width".to_string(), w));
            l.push(("height".to_string(), h));
        }
        if names == ["position"] && self.chance(2, 3) {
            let size = if self.chance(1, 2) {
                self.positive()
            } else {
                J::Arr(vec![self.positive(), self.positive()])
            };
            l.push(("size".to_string(), size));
        }
        if names.is_empty() && self.chance(1, 2) {
            let key = self.pick(&["center", "centre", "position"]);
            let c = self.vec3();
            l.push(("shape".to_string(), J::Obj(vec![(key.to_string(), c)])));
        }
    }

    // --- shapes ----------------------------------------------------------------------------

    fn shape(&mut self) -> J {
        let mut sh = Vec::new();
        let kind = self.range(0, 17);
        let ty = match kind {
            13 => self.pick(&[
                "rectangleXY",
                "rectangleXZ",
                "rectangleYZ",
                "rectanglexy",
                "RECTANGLEXZ",
                "rectangleyz",
            ]),
            14 => self.pick(&["plane", "plane", "quad", "rectangle"]),
            15 => self.pick(&["plane", "plane", "Plane", "quad"]),
            16 => self.pick(&["trimesh", "mesh", "trianglemesh"]),
            0 | 1 => self.pick(&["sphere", "sphere", "uvsphere", "SPHERE"]),
            2 => self.pick(&["cylinder", "uvcylinder"]),
            3 | 4 => "triangle",
            5 | 6 => self.pick(&["plane", "planarquad", "planerquad", "quad", "rectangle"]),
            7 => "box",
            8..=11 => self.pick(&["trimesh", "mesh", "ply", "trianglemesh", "tris"]),
            _ => self.pick(&["traingle", "meshss", "torus", "", "pointlight"]),
        };
        if self.chance(31, 32) {
            sh.push(("type".to_string(), s(ty)));
        }
        match kind {
            0 | 1 => {
                self.centre(&mut sh);
                if self.chance(15, 16) {
                    let r = self.positive();
                    sh.push(("radius".to_string(), r));
                }
            }
            2 => {
                self.centre(&mut sh);
                let a = self.vec3();
                sh.push(("axis".to_string(), a));
                let r = self.positive();
                sh.push(("radius".to_string(), r));
                let h = self.positive();
                sh.push(("height".to_string(), h));
            }
            3 | 4 => self.triangle(&mut sh),
            5 | 6 => self.quad(&mut sh),
            7 => self.boxed(&mut sh),
            8..=11 => self.mesh(&mut sh),
            13 => self.axis_rectangle(&mut sh, ty),
            14 => {
                // A rectangle by its centre, width (x) and height (z), turned about its centre.
                self.centre_key(&mut sh);
                for k in ["width", "height"] {
                    if self.chance(15, 16) {
                        let v = self.positive();
                        sh.push((k.to_string(), v));
                    }
                }
                if self.chance(1, 2) {
                    self.euler(&mut sh);
                }
            }
            15 => {
                // An infinite plane.
                if self.chance(31, 32) {
                    let n = if self.chance(3, 4) {
                        let axes = ["[0,1,0]", "[0,-1,0]", "[1,0,0]", "[0,0,1]", "[0,0,-1]"];
                        lit(self.pick(&axes))
                    } else {
                        self.vec3()
                    };
                    sh.push(("normal".to_string(), n));
                }
                if self.chance(31, 32) {
                    let d = self.num();
                    sh.push(("distance".to_string(), d));
                }
            }
            16 => self.poly_sphere(&mut sh),
            _ => {
                // A skipped shape may hold anything.
                let v = self.vec3();
                sh.push(("v0".to_string(), v));
                let r = self.num();
                sh.push(("radius".to_string(), r));
            }
        }
        if self.chance(7, 8) {
            let m = self.material();
            sh.push(("material".to_string(), m));
        }
        if self.chance(1, 12) {
            // Texture keys on the shape, read when the material has none.
            self.texture(&mut sh);
        }
        if self.chance(1, 6) {
            let id = self.shape_id();
            sh.push(("id".to_string(), id));
        }
        self.extra_keys(&mut sh);
        J::Obj(sh)
    }

    /// A shape id an area light's `shapeid` may name: a few shared names, mostly; now and then
    /// one no shape has, or the wrong type.
    fn shape_id(&mut self) -> J {
        match self.range(0, 19) {
            0 => s("nope"),
            1 => s(""),
            2 => self.num(),
            _ => J::Str(format!("a{}", self.range(0, 2))),
        }
    }

    /// `center` or `centre`, nearly always.
    fn centre_key(&mut self, sh: &mut Vec<(String, J)>) {
        if self.chance(15, 16) {
            let key = self.pick(&["center", "center", "centre"]);
            let c = self.vec3();
            sh.push((key.to_string(), c));
        }
    }

    /// Euler angles in degrees: quarter turns mostly, or any numbers.
    fn euler(&mut self, sh: &mut Vec<(String, J)>) {
        let key = self.pick(&["rot", "rotation", "euler"]);
        let r = if self.chance(1, 2) {
            let angles = [
                "0", "90", "-90", "180", "45", "270", "360", "30", "-0", "720",
            ];
            J::Arr(vec![
                lit(self.pick(&angles)),
                lit(self.pick(&angles)),
                lit(self.pick(&angles)),
            ])
        } else {
            self.vec3()
        };
        sh.push((key.to_string(), r));
    }

    /// `rectangleXY`/`XZ`/`YZ`: two ranges and the constant coordinate (or `k`).
    fn axis_rectangle(&mut self, sh: &mut Vec<(String, J)>, ty: &str) {
        let (a, b, c) = match ty.to_ascii_lowercase().as_str() {
            "rectanglexy" => ("x", "y", "z"),
            "rectanglexz" => ("x", "z", "y"),
            _ => ("y", "z", "x"),
        };
        for axis in [a, b] {
            let lo = self.num();
            let hi = if self.chance(1, 16) {
                match &lo {
                    J::Lit(t) => J::Lit(t.clone()), // the same end twice: no area
                    _ => self.num(),
                }
            } else {
                self.num()
            };
            if self.chance(31, 32) {
                sh.push((format!("{axis}0"), lo));
            }
            if self.chance(31, 32) {
                sh.push((format!("{axis}1"), hi));
            }
        }
        if self.chance(15, 16) {
            let key = if self.chance(1, 3) { "k" } else { c };
            let k = self.num();
            sh.push((key.to_string(), k));
        }
        if self.chance(1, 16) {
            // The constant key of another orientation as well.
            let other = self.pick(&["x", "y", "z", "k"]);
            let v = self.num();
            sh.push((other.to_string(), v));
        }
    }

    /// A generated poly sphere: `n` faceted spheres at `locX`, `locY`, `locZ` with `scale`.
    fn poly_sphere(&mut self, sh: &mut Vec<(String, J)>) {
        let n = if self.go_hostile() {
            lit(self.pick(HOSTILE_COUNTS))
        } else if self.chance(1, 20) {
            lit(self.pick(&["0", "8", "30", "256", "257"]))
        } else {
            J::Lit(self.range(1, 3).to_string())
        };
        sh.push(("n".to_string(), n));
        for key in ["locX", "locY", "locZ"] {
            if self.chance(7, 8) {
                let v = self.num();
                sh.push((key.to_string(), v));
            }
        }
        if self.chance(3, 4) {
            let v = if self.chance(1, 6) {
                self.num()
            } else {
                self.positive()
            };
            sh.push(("scale".to_string(), v));
        }
        if self.chance(1, 16) {
            // A mesh file as well: the file wins.
            let p = self.pick(MESH_FILES);
            sh.push(("mPath".to_string(), s(p)));
        }
    }

    fn centre(&mut self, sh: &mut Vec<(String, J)>) {
        if self.chance(15, 16) {
            let key = self.pick(&["center", "center", "centre", "position"]);
            let c = self.vec3();
            sh.push((key.to_string(), c));
        }
    }

    fn corners(&mut self, sh: &mut Vec<(String, J)>, sets: &[&[&str]], uv_sets: &[&[&str]]) {
        let names = sets[self.u.choose_index(sets.len()).unwrap_or(0)];
        let drop = if self.chance(1, 20) {
            Some(self.range(0, names.len() as u32 - 1) as usize)
        } else {
            None
        };
        for (i, name) in names.iter().enumerate() {
            if Some(i) != drop {
                let v = self.vec3();
                sh.push((name.to_string(), v));
            }
        }
        if self.chance(1, 5) {
            let uvs = uv_sets[self.u.choose_index(uv_sets.len()).unwrap_or(0)];
            for name in uvs {
                let uv = self.uv();
                sh.push((name.to_string(), uv));
            }
        }
    }

    fn point_list(&mut self, sh: &mut Vec<(String, J)>, usual: u32) {
        let key = self.pick(&["points", "vertices"]);
        let n = if self.chance(7, 8) {
            usual
        } else {
            self.range(0, 6)
        };
        let pts = (0..n).map(|_| self.vec3()).collect();
        sh.push((key.to_string(), J::Arr(pts)));
    }

    fn triangle(&mut self, sh: &mut Vec<(String, J)>) {
        if self.chance(1, 6) {
            self.point_list(sh, 3);
            return;
        }
        self.corners(
            sh,
            &[
                &["v0", "v1", "v2"],
                &["v1", "v2", "v3"],
                &["point1", "point2", "point3"],
                &["p0", "p1", "p2"],
            ],
            &[&["uv0", "uv1", "uv2"], &["uv1", "uv2", "uv3"]],
        );
    }

    fn quad(&mut self, sh: &mut Vec<(String, J)>) {
        match self.range(0, 9) {
            0 => {
                let usual = if self.chance(1, 2) { 4 } else { 3 };
                self.point_list(sh, usual);
            }
            1 => {
                let a = self.vec3();
                let mut b = self.vec3();
                // Opposite corners sharing one coordinate: an axis-aligned rectangle.
                if let (J::Arr(av), J::Arr(bv)) = (&a, &mut b) {
                    if av.len() == 3 && bv.len() == 3 && self.chance(3, 4) {
                        let k = self.range(0, 2) as usize;
                        if let J::Lit(t) = &av[k] {
                            bv[k] = J::Lit(t.clone());
                        }
                    }
                }
                sh.push(("corner1".to_string(), a));
                sh.push(("corner2".to_string(), b));
            }
            2 => {
                let n = self.vec3();
                sh.push(("normal".to_string(), n));
                let d = self.num();
                sh.push(("distance".to_string(), d));
            }
            _ => self.corners(
                sh,
                &[
                    &["v0", "v1", "v2", "v3"],
                    &["v1", "v2", "v3", "v4"],
                    &["point1", "point2", "point3", "point4"],
                    &["p0", "p1", "p2", "p3"],
                ],
                &[&["uv0", "uv1", "uv2", "uv3"], &["uv1", "uv2", "uv3", "uv4"]],
            ),
        }
    }

    fn boxed(&mut self, sh: &mut Vec<(String, J)>) {
        if self.chance(1, 2) {
            let key = self.pick(&["center", "centre"]);
            let c = self.vec3();
            sh.push((key.to_string(), c));
            for k in ["width", "height", "depth"] {
                if self.chance(15, 16) {
                    let v = self.positive();
                    sh.push((k.to_string(), v));
                }
            }
        } else {
            let a = self.vec3();
            sh.push(("min".to_string(), a));
            if self.chance(15, 16) {
                let b = self.vec3();
                sh.push(("max".to_string(), b));
            }
        }
        if self.chance(1, 4) {
            self.euler(sh);
        }
    }

    /// A vertex index: in range mostly, now and then out of range or not a whole number.
    fn index(&mut self, nverts: usize) -> J {
        if self.chance(15, 16) {
            J::Lit(self.range(0, nverts.max(1) as u32 - 1).to_string())
        } else if !self.go_hostile() {
            J::Lit(nverts.to_string())
        } else {
            lit(self.pick(HOSTILE_COUNTS))
        }
    }

    /// A polygon's size: 3 mostly, now and then 0 to 6 or hostile.
    fn face_size(&mut self) -> usize {
        if self.chance(3, 4) {
            3
        } else {
            self.range(0, 6) as usize
        }
    }

    fn face(&mut self, nverts: usize) -> J {
        let n = self.face_size();
        J::Arr((0..n).map(|_| self.index(nverts)).collect())
    }

    fn vertex_list(&mut self) -> Vec<J> {
        let n = self
            .length(8, 6000, 24)
            .max(if self.chance(7, 8) { 3 } else { 0 });
        (0..n).map(|_| self.vec3()).collect()
    }

    fn mesh(&mut self, sh: &mut Vec<(String, J)>) {
        match self.range(0, 7) {
            0..=2 => {
                let key = self.pick(&[
                    "mPath",
                    "mPath",
                    "plyPath",
                    "modelpath",
                    "model",
                    "path",
                    "file",
                    "filename",
                ]);
                let p = self.pick(MESH_FILES);
                sh.push((key.to_string(), s(p)));
            }
            3 => {
                // Vertex list and face list.
                let vkey = self.pick(&["vertices", "vertices", "vs", "vertex", "points"]);
                let verts = self.vertex_list();
                let nv = verts.len();
                sh.push((vkey.to_string(), J::Arr(verts)));
                let fkey = self.pick(&["faces", "faces", "fs", "tris", "triangles", "face"]);
                let nf = self.length(6, 6000, 12);
                let faces = (0..nf).map(|_| self.face(nv)).collect();
                sh.push((fkey.to_string(), J::Arr(faces)));
                self.texturemap(sh, nv);
            }
            4 => {
                // Numbered keys.
                let nv = self.length(6, 2000, 30);
                let claimed_v = if self.chance(7, 8) {
                    J::Lit(nv.to_string())
                } else {
                    self.count(10)
                };
                sh.push(("vertex".to_string(), claimed_v));
                for i in 0..nv {
                    let v = self.vec3();
                    sh.push((format!("v{i}"), v));
                }
                let nf = self.length(4, 2000, 20);
                let claimed_f = if self.chance(7, 8) {
                    J::Lit(nf.to_string())
                } else {
                    self.count(10)
                };
                sh.push(("face".to_string(), claimed_f));
                for i in 0..nf {
                    let f = self.face(nv);
                    sh.push((format!("f{i}"), f));
                }
            }
            5 => {
                // Flat index list with polygon sizes; their lengths need not agree.
                let verts = self.vertex_list();
                let nv = verts.len();
                sh.push(("vertices".to_string(), J::Arr(verts)));
                let npoly = self.length(6, 6000, 4);
                let mut sizes = Vec::new();
                let mut total = 0usize;
                for _ in 0..npoly {
                    if self.go_hostile() && self.chance(1, 4) {
                        sizes.push(lit(self.pick(HOSTILE_COUNTS)));
                    } else {
                        let n = self.face_size();
                        total += n;
                        sizes.push(J::Lit(n.to_string()));
                    }
                }
                let nidx = match self.range(0, 5) {
                    0 => total.saturating_sub(1),
                    1 => total + 1,
                    2 => self.range(0, 12) as usize,
                    _ => total,
                };
                let nidx = nidx.min(self.budget / 6 + 12);
                self.spend(nidx * 6);
                let idx = (0..nidx).map(|_| self.index(nv)).collect();
                sh.push(("vertexindex".to_string(), J::Arr(idx)));
                sh.push(("faceindex".to_string(), J::Arr(sizes)));
                self.texturemap(sh, nv);
            }
            6 => {
                // Triangle objects.
                let n = self.length(4, 3000, 80);
                let tris = (0..n)
                    .map(|_| {
                        let mut t = Vec::new();
                        for k in ["v0", "v1", "v2"] {
                            if self.chance(31, 32) {
                                t.push((k.to_string(), self.vec3()));
                            }
                        }
                        J::Obj(t)
                    })
                    .collect();
                sh.push(("triangles".to_string(), J::Arr(tris)));
            }
            _ => {
                // Points only: triples, or one polygon.
                let verts = self.vertex_list();
                sh.push(("points".to_string(), J::Arr(verts)));
            }
        }
        if self.chance(1, 3) {
            let key = self.pick(&["scale", "sizeScale", "size"]);
            let c = self.colour();
            sh.push((key.to_string(), c));
        }
        if self.chance(1, 3) {
            let key = self.pick(&[
                "position",
                "pos",
                "offset",
                "translate",
                "translation",
                "center",
            ]);
            let p = self.vec3();
            sh.push((key.to_string(), p));
        }
        match self.range(0, 11) {
            0 | 1 => self.euler(sh),
            2 => {
                // Rows: the images of the axes (a permutation with signs, mostly).
                let rows = [
                    "[1,0,0]", "[0,1,0]", "[0,0,1]", "[-1,0,0]", "[0,-1,0]", "[0,0,-1]", "[0,0,0]",
                ];
                for key in ["r1", "r2", "r3"] {
                    if self.chance(15, 16) {
                        let r = if self.chance(3, 4) {
                            lit(self.pick(&rows))
                        } else {
                            self.vec3()
                        };
                        sh.push((key.to_string(), r));
                    }
                }
            }
            _ => {}
        }
    }

    fn texturemap(&mut self, sh: &mut Vec<(String, J)>, nverts: usize) {
        if self.chance(1, 4) {
            let n = if self.chance(3, 4) {
                nverts
            } else {
                self.range(0, 8) as usize
            };
            self.spend(n * 12);
            let uvs = (0..n).map(|_| self.uv()).collect();
            sh.push(("texturemap".to_string(), J::Arr(uvs)));
        }
    }
}
