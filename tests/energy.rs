//! No material makes light: a white furnace for the Whitted integrator, per variant.
//!
//! A sphere sits in a uniform white world: background 1 in every direction, ambient light 1 (a
//! CGR file's default: its background; the 2019 and 2021–23 files are given one), no other
//! light. Whatever the sphere reflects, transmits or shades of that world, no pixel may come out
//! brighter than the world itself, 1 (Pharr, Jakob and Humphreys, "Physically Based Rendering",
//! 4th ed., the white furnace test). Every combination of the material flags is tried (mirror
//! on or off, glass on or off, a diffuse and a highlight weight of 0, a half or all) over mirror
//! weights 0.3–1.5 and indices of refraction 1–2.4, in each variant's spelling. A pure mirror
//! and a glass of index 1 must also return the whole world (1 within rounding): the test would
//! notice light lost as well as light made there.

use std::path::Path;

use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load_str, LoadOptions};

#[derive(Clone, Copy, Debug)]
enum Variant {
    Cgr,
    V2021,
    V2019,
}

#[derive(Clone, Copy, Debug)]
struct Case {
    kd: f32,
    ks: f32,
    /// Mirror weight, if the material reflects.
    mirror: Option<f32>,
    /// Index of refraction, if the material transmits.
    glass: Option<f32>,
}

fn scene(variant: Variant, c: Case) -> String {
    let mut material = format!(
        r#""kd": {}, "ks": {}, "specularexponent": 20, "diffusecolor": [1, 1, 1], "specularcolor": [1, 1, 1]"#,
        c.kd, c.ks
    );
    match variant {
        Variant::Cgr => {
            material += &format!(
                r#", "isreflective": {}, "reflectivity": {}, "isrefractive": {}, "refractiveindex": {}"#,
                c.mirror.is_some(),
                c.mirror.unwrap_or(1.0),
                c.glass.is_some(),
                c.glass.unwrap_or(1.0)
            );
        }
        Variant::V2021 | Variant::V2019 => {
            if let Some(kr) = c.mirror {
                material += &format!(r#", "kr": {kr}"#);
            }
            if let Some(eta) = c.glass {
                material += &format!(r#", "kt": 1, "eta": {eta}"#);
            }
        }
    }
    let (top, camera, ambient) = match variant {
        Variant::Cgr => (
            r#""rendermode": "phong","#,
            r#""width": 24, "height": 24, "fov": 40, "position": [0, 0, 0], "lookAt": [0, 0, -1],
               "upVector": [0, 1, 0], "exposure": 0.1"#,
            "",
        ),
        Variant::V2021 => (
            "",
            r#""width": 24, "height": 24, "fov": 40, "position": [0, 0, 0], "lookat": [0, 0, -1],
               "up": [0, 1, 0]"#,
            r#""ambientlight": [1, 1, 1], "#,
        ),
        Variant::V2019 => (
            "",
            r#""type": "pinhole", "width": 24, "height": 24, "fov": 40"#,
            r#""ambientlight": [1, 1, 1], "#,
        ),
    };
    format!(
        r#"{{ {top} "nbounces": 12, "camera": {{ {camera} }},
             "scene": {{ {ambient} "backgroundcolor": [1, 1, 1],
               "shapes": [ {{ "type": "sphere", "center": [0, 0, -4], "radius": 1,
                              "material": {{ {material} }} }} ] }} }}"#
    )
}

/// The brightest and the dimmest channel over the pixels that see the sphere's middle.
fn furnace(variant: Variant, c: Case) -> (f32, f32) {
    let text = scene(variant, c);
    let s = load_str(&text, Path::new("furnace.json"), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{variant:?} {c:?}: {e}\n{text}"));
    let film = render(&s, &RenderOptions::default()).unwrap().film;
    let (mut hi, mut lo) = (0.0f32, f32::INFINITY);
    for y in 8..16 {
        for x in 8..16 {
            let p = film.get(x, y);
            hi = hi.max(p.max_element());
            lo = lo.min(p.min_element());
        }
    }
    (hi, lo)
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    for kd in [0.0, 0.5, 1.0] {
        for ks in [0.0, 0.5, 1.0] {
            for mirror in [None, Some(0.3), Some(0.8), Some(1.0), Some(1.5)] {
                for glass in [None, Some(1.0), Some(1.5), Some(2.4)] {
                    out.push(Case {
                        kd,
                        ks,
                        mirror,
                        glass,
                    });
                }
            }
        }
    }
    out
}

/// Rounding in the sums of a deep ray tree.
const SLACK: f32 = 1e-4;

#[test]
fn no_material_returns_more_than_the_white_world_gives() {
    let mut failures = Vec::new();
    let mut brightest = 0.0f32;
    for variant in [Variant::Cgr, Variant::V2021, Variant::V2019] {
        for c in cases() {
            let (hi, _) = furnace(variant, c);
            brightest = brightest.max(hi);
            if hi > 1.0 + SLACK {
                failures.push(format!("{variant:?} {c:?}: {hi}"));
            }
        }
    }
    println!("brightest pixel over every case: {brightest}");
    assert!(
        failures.is_empty(),
        "{} cases make light:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn lossless_materials_return_the_whole_world() {
    for variant in [Variant::Cgr, Variant::V2021, Variant::V2019] {
        let white = |c: Case| {
            let (hi, lo) = furnace(variant, c);
            assert!(
                (hi - 1.0).abs() < SLACK && (lo - 1.0).abs() < SLACK,
                "{variant:?} {c:?}: {lo}..{hi}"
            );
        };
        // A perfect mirror, and a glass of index 1 (the world seen straight through it).
        for (kd, ks) in [(0.0, 0.0), (1.0, 1.0)] {
            white(Case {
                kd,
                ks,
                mirror: Some(1.0),
                glass: None,
            });
            white(Case {
                kd,
                ks,
                mirror: None,
                glass: Some(1.0),
            });
        }
        // A white diffuse surface with nothing else reflects all of the ambient light.
        white(Case {
            kd: 1.0,
            ks: 0.0,
            mirror: None,
            glass: None,
        });
    }
}
