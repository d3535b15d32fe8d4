//! Materials: the Blinn-Phong keys, the physically based types, emission.

use super::texture::{Libraries, TEXTURE_KEYS};
use super::{opt_f32, Loader, DEFAULT_ETA};
use crate::material::{roughness_exponent, Material};
use crate::math::Vec3;
use crate::scene::json::Node;
use crate::scene::{RenderMode, SceneError};

/// Material `type`s the loader knows: the Blinn-Phong model the other keys describe, and the
/// physically based forms of path-tracing files (see `Loader::material_kind`).
const MATERIAL_TYPES: &[&str] = &[
    "phong",
    "blinnphong",
    "blinn-phong",
    "blinn_phong",
    "diffuse",
    "lambertian",
    "matte",
    "metal",
    "conductor",
    "mirror",
    "dielectric",
    "glass",
    "emissive",
    "emitter",
    "light",
    "emission",
];

impl Loader<'_> {
    pub(super) fn material(
        &mut self,
        s: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
    ) -> Result<u32, SceneError> {
        let mut m = Material::default();
        // A shape without a `material` may carry the material's keys itself (as some files do).
        let mut node = s.get("material").or_else(|| Some(s.clone()));
        // Whether `node` is a material object rather than the shape standing in for one (whose
        // `type` is the shape's).
        let own_material = s.peek("material").is_some();
        if let Some(named) = node.as_ref().and_then(|n| n.str().ok()) {
            match libraries.materials.find(named) {
                Some((_, def)) => node = Some(def.clone()),
                None => {
                    let names = libraries.materials.names();
                    let at = node.unwrap_or_else(|| s.clone());
                    return Err(at.error(format!(
                        "no material named '{named}' (the scene defines: {})",
                        if names.is_empty() {
                            "none".to_string()
                        } else {
                            names.join(", ")
                        }
                    )));
                }
            }
        }
        if let Some(n) = &node {
            if !n.is_object() {
                return Err(n.error(format!("a material is an object, found {}", n.kind())));
            }
            if let Some(v) = opt_f32(n, &["ka"])? {
                m.ka = v;
            }
            if let Some(v) = opt_f32(n, &["kd"])? {
                m.kd = v;
            }
            if let Some(v) = opt_f32(n, &["ks"])? {
                m.ks = v;
            }
            if let Some(v) = opt_f32(
                n,
                &[
                    "specularexponent",
                    "specular_exponent",
                    "shininess",
                    "exponent",
                    "alpha",
                ],
            )? {
                if v < 0.0 {
                    return Err(n.error(format!("the specular exponent must be ≥ 0, found {v}")));
                }
                m.exponent = v;
            }
            if let Some(c) = n.get_any(&[
                "diffusecolor",
                "diffusecolour",
                "diffuse_color",
                "color",
                "colour",
            ]) {
                m.diffuse = c.color()?;
            } else if let Some(c) = n.get("diffuse").filter(|c| c.str().is_err()) {
                m.diffuse = c.color()?; // `diffuse` as a string is a texture (below)
            }
            if let Some(c) = n.get_any(&["specularcolor", "specularcolour", "specular_color"]) {
                m.specular = c.color()?;
            }
            let reflective = n
                .get_any(&["isreflective", "isReflective"])
                .map(|b| b.bool())
                .transpose()?;
            if let Some(v) = opt_f32(n, &["kr", "reflectivity", "reflection", "reflectance"])? {
                m.kr = if reflective == Some(false) { 0.0 } else { v };
            } else if reflective == Some(true) {
                m.kr = 1.0;
            }
            let refractive = n
                .get_any(&["isrefractive", "isRefractive", "isGlass"])
                .map(|b| b.bool())
                .transpose()?;
            if let Some(v) = opt_f32(n, &["kt", "transparency", "transmit", "transmittance"])? {
                m.kt = if refractive == Some(false) { 0.0 } else { v };
            } else if refractive == Some(true) {
                m.kt = 1.0;
            }
            let eta_node = n.get_any(&[
                "eta",
                "refractiveindex",
                "refractiveIndex",
                "refractive_index",
                "ior",
            ]);
            m.eta = match &eta_node {
                Some(e) => e.f32()?,
                None => DEFAULT_ETA,
            };
            for (name, v) in [
                ("ka", m.ka),
                ("kd", m.kd),
                ("ks", m.ks),
                ("kr", m.kr),
                ("kt", m.kt),
            ] {
                if v < 0.0 {
                    let at = n.get(name).unwrap_or_else(|| n.clone());
                    return Err(at.error(format!("{name} must be ≥ 0, found {v}")));
                }
            }
            // A metal's roughness is its own (see `material_kind`); any other material's blurs
            // its mirror part.
            let roughness_read = own_material && self.material_kind(n, &mut m)?;
            if let Some(r) = n.get("roughness").filter(|_| !roughness_read) {
                m.mirror_exponent = self.mirror_roughness(&r, m.kr)?;
            }
            // Checked once the material's `type` has said whether it transmits.
            if let Some(e) = eta_node.filter(|_| m.eta <= 0.0 && m.kt > 0.0) {
                return Err(e.error(format!(
                    "the index of refraction must be > 0, found {}",
                    m.eta
                )));
            }
        }
        node.iter()
            .chain([s])
            .for_each(|n| n.mark_read(&TEXTURE_KEYS)); // known in every mode
        if let Some(n) = &node {
            n.mark_read(&["diffuse"]);
        }
        if mode != RenderMode::Binary {
            let tex_node = node
                .as_ref()
                .and_then(|n| {
                    n.get_any(&TEXTURE_KEYS)
                        .or_else(|| n.get("diffuse").filter(|d| d.str().is_ok()))
                })
                .or_else(|| s.get_any(&TEXTURE_KEYS));
            if let Some(t) = tex_node {
                m.texture = self.texture(&t, libraries)?;
            }
        }
        self.materials.push(m);
        Ok(self.materials.len() as u32 - 1)
    }

    /// The mirror lobe's exponent for a Blinn-Phong material's `roughness` r ≥ 0 (some CGR files
    /// give one; their renderers blur the mirror part with a GGX lobe of α = r², the convention
    /// of Burley's "Physically Based Shading at Disney", SIGGRAPH 2012 course notes): a
    /// microfacet roughness α = r², so 0 keeps a perfect mirror. Past 1 it is taken as 1 (the
    /// roughest lobe) with a warning where there is a mirror to blur; a material without a
    /// mirror part has nothing it applies to.
    pub(super) fn mirror_roughness(&mut self, r: &Node, kr: f32) -> Result<f32, SceneError> {
        let v = r.f32()?;
        if !(v >= 0.0 && v.is_finite()) {
            return Err(r.error(format!("roughness must be a finite number ≥ 0, found {v}")));
        }
        if v > 1.0 && kr > 0.0 {
            self.warn(r, format!("roughness is at most 1, found {v}; taken as 1"));
        }
        let alpha = v.min(1.0);
        Ok(roughness_exponent(alpha * alpha))
    }

    /// The physically based material forms path-tracing files use (`"type"` with `albedo`,
    /// `roughness`, `ior`, an emitted `colour` × `intensity`), and `emittance` on any material:
    /// see `docs/scene-format.md`, "Material types". Returns whether the type read `roughness`
    /// as its own (a metal's).
    pub(super) fn material_kind(&mut self, n: &Node, m: &mut Material) -> Result<bool, SceneError> {
        if let Some(e) = n.get("emittance") {
            m.emission = e.color()?;
        }
        let Some(t) = n.peek("type") else {
            return Ok(false);
        };
        let Ok(kind) = t.str().map(str::to_ascii_lowercase) else {
            return Ok(false); // not a type name: left for the unknown-key warning
        };
        if !MATERIAL_TYPES.contains(&kind.as_str()) {
            return Ok(false); // a model of another renderer: left for the unknown-key warning
        }
        n.mark_read(&["type"]);
        let albedo = match n.get("albedo") {
            Some(a) => Some(a.color()?),
            None => None,
        };
        match kind.as_str() {
            "diffuse" | "lambertian" | "matte" => {
                m.kd = 1.0;
                m.ks = 0.0;
                m.diffuse = albedo.unwrap_or(m.diffuse);
            }
            "metal" | "conductor" | "mirror" => {
                let tint = albedo.unwrap_or(m.specular);
                let roughness = match n.get_any(&["roughness", "fuzz"]) {
                    Some(r) => {
                        let v = r.f32()?;
                        if !(0.0..=1.0).contains(&v) {
                            return Err(
                                r.error(format!("a metal's roughness is in [0, 1], found {v}"))
                            );
                        }
                        v
                    }
                    None => 0.0,
                };
                m.kd = 0.0;
                if roughness == 0.0 {
                    m.ks = 0.0;
                    m.kr = 1.0;
                    m.mirror = tint;
                } else {
                    m.ks = 1.0;
                    m.specular = tint;
                    m.exponent = roughness_exponent(roughness);
                }
                return Ok(true);
            }
            "dielectric" | "glass" => {
                m.kd = 0.0;
                m.ks = 0.0;
                m.kt = 1.0;
            }
            "emissive" | "emitter" | "light" | "emission" => {
                let colour = match n.get_any(&["colour", "color", "emission", "emittance"]) {
                    Some(c) => c.color()?,
                    None => Vec3::ONE,
                };
                let strength = opt_f32(n, &["intensity", "strength"])?.unwrap_or(1.0);
                if !(strength >= 0.0 && strength.is_finite()) {
                    let at = n.get_any(&["intensity", "strength"]).unwrap_or(t);
                    return Err(at.error(format!(
                        "an emitter's intensity must be a finite number ≥ 0, found {strength}"
                    )));
                }
                m.emission = colour * strength;
                m.kd = 0.0;
                m.ks = 0.0;
                m.diffuse = Vec3::ZERO;
            }
            _ => {} // Blinn-Phong: the keys already say it all
        }
        Ok(false)
    }
}
