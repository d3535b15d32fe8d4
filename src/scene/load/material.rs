//! Materials: the Blinn-Phong keys, the physically based types, emission.

use super::spellings::texture;
use super::spellings::{material, shape, type_names, type_of, MATERIAL_TYPES};
use super::texture::Libraries;
use super::{nearest, opt_f32, Loader, DEFAULT_ETA};
use crate::material::{roughness_exponent, Material};
use crate::math::Vec3;
use crate::scene::json::Node;
use crate::scene::{RenderMode, SceneError};

impl Loader<'_> {
    /// Reads the material of shape `s` into the scene's materials and returns its index.
    pub(super) fn material(
        &mut self,
        s: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
    ) -> Result<u32, SceneError> {
        let mut m = Material::default();
        let node = material_node(s, libraries)?;
        // Whether `node` is a material object rather than the shape standing in for one (whose
        // `type` is the shape's).
        let own_material = s.contains_any(shape::MATERIAL);
        self.material_keys(&node, own_material, &mut m)?;
        self.material_texture(s, &node, mode, libraries, &mut m)?;
        self.materials.push(m);
        Ok(self.materials.len() as u32 - 1)
    }

    /// Reads the material object `n` into `m`: the Blinn-Phong weights and colours, mirror and
    /// glass, emission, and the physically based `type` if `n` is a material of its own.
    fn material_keys(
        &mut self,
        n: &Node,
        own_material: bool,
        m: &mut Material,
    ) -> Result<(), SceneError> {
        if !n.is_object() {
            return Err(n.error(format!("a material is an object, found {}", n.kind())));
        }
        phong_keys(n, m)?;
        self.mirror_weight(n, m)?;
        let eta_node = transmission(n, m)?;
        for (keys, v) in [
            (material::KA, m.ka),
            (material::KD, m.kd),
            (material::KS, m.ks),
            (material::KR, m.kr),
            (material::KT, m.kt),
        ] {
            if v < 0.0 {
                let at = n.get_any(keys).unwrap_or_else(|| n.clone());
                return Err(at.error(format!("{} must be ≥ 0, found {v}", keys[0])));
            }
        }
        Self::emission(n, m)?;
        // A metal's roughness is its own (see `material_kind`); any other material's blurs
        // its mirror part.
        let roughness_read = own_material && self.material_kind(n, m)?;
        if let Some(r) = n.get_any(material::ROUGHNESS).filter(|_| !roughness_read) {
            m.mirror_exponent = self.mirror_roughness(&r, m.kr)?;
        }
        // Checked once the material's `type` has said whether it transmits.
        if let Some(e) = eta_node.filter(|_| m.eta <= 0.0 && m.kt > 0.0) {
            return Err(e.error(format!(
                "the index of refraction must be > 0, found {}",
                m.eta
            )));
        }
        Ok(())
    }

    /// The mirror weight `kr` (a texture there is warned about and ignored), switched on or off
    /// by `isReflective`.
    fn mirror_weight(&mut self, n: &Node, m: &mut Material) -> Result<(), SceneError> {
        let reflective = n
            .get_any(material::IS_REFLECTIVE)
            .map(|b| b.bool())
            .transpose()?;
        let kr_node = n.get_any(material::KR);
        if let Some(t) = kr_node.as_ref().filter(|k| k.str().is_ok()) {
            self.warn(
                t,
                format!(
                    "a mirror weight from a texture ('{}') is not supported; the material \
                     has no mirror",
                    t.str()?
                ),
            );
        }
        let kr = kr_node
            .filter(|k| k.str().is_err())
            .map(|k| k.f32())
            .transpose()?;
        if let Some(v) = kr {
            m.kr = if reflective == Some(false) { 0.0 } else { v };
        } else if reflective == Some(true) {
            m.kr = 1.0;
        }
        Ok(())
    }

    /// The texture of shape `s` with material `node`, unless the mode draws none or a switch
    /// turns it off. The texture keys count as read in every mode.
    fn material_texture(
        &mut self,
        s: &Node,
        node: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
        m: &mut Material,
    ) -> Result<(), SceneError> {
        node.mark_read(texture::TEXTURE);
        s.mark_read(texture::TEXTURE);
        node.mark_read(material::DIFFUSE_OR_TEXTURE);
        // A switch that turns the texture off leaves the diffuse colour alone.
        let switched_on = match node.get_any(texture::SWITCH) {
            Some(b) => b.bool()?,
            None => true,
        };
        if mode != RenderMode::Binary && switched_on {
            let tex_node = node
                .get_any(texture::TEXTURE)
                .or_else(|| {
                    node.get_any(material::DIFFUSE_OR_TEXTURE)
                        .filter(|d| d.str().is_ok())
                })
                .or_else(|| s.get_any(texture::TEXTURE));
            if let Some(t) = tex_node {
                m.texture = self.texture(&t, libraries)?;
            }
        }
        Ok(())
    }

    /// The mirror lobe's exponent for a Blinn-Phong material's `roughness` r ≥ 0: microfacet
    /// roughness α = r² (Burley, "Physically Based Shading at Disney", SIGGRAPH 2012), so 0 keeps
    /// a perfect mirror; past 1 it is taken as 1, with a warning if there is a mirror to blur.
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

    /// The radiance any material may emit: a colour, or a number that scales the diffuse
    /// colour.
    fn emission(n: &Node, m: &mut Material) -> Result<(), SceneError> {
        if let Some(e) = n.get_any(material::EMISSION) {
            m.emission = match e.f32() {
                Ok(strength) => strength * m.diffuse,
                Err(_) => e.color()?,
            };
            if !(m.emission.min_element() >= 0.0 && m.emission.is_finite()) {
                return Err(e.error("emitted radiance must be finite and ≥ 0"));
            }
        }
        Ok(())
    }

    /// The physically based forms of a material's `type` (`albedo`, `roughness`, `ior`, an
    /// emitted `colour` × `intensity`): see `docs/scene-format.md`, "Material types". Returns
    /// whether the type read `roughness` as its own (a metal's).
    pub(super) fn material_kind(&mut self, n: &Node, m: &mut Material) -> Result<bool, SceneError> {
        let Some(t) = n.get_any(material::TYPE) else {
            return Ok(false);
        };
        let name = t.str()?;
        let Some(kind) = type_of(MATERIAL_TYPES, name) else {
            self.warn(
                &t,
                format!(
                    "unknown material type '{name}' (nearest known: '{}'); shaded as Phong from \
                     its other keys",
                    nearest(name, &type_names(MATERIAL_TYPES))
                ),
            );
            return Ok(false);
        };
        match kind {
            "diffuse" => {
                // The type's defaults, where the file gives no weight of its own.
                if !n.contains_any(material::KD) {
                    m.kd = 1.0;
                }
                if !n.contains_any(material::KS) {
                    m.ks = 0.0;
                }
            }
            "metal" => {
                let tint = match n.get_any(material::METAL_COLOUR) {
                    Some(c) => c.color()?,
                    None => m.specular,
                };
                let roughness = match n.get_any(material::ROUGHNESS) {
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
            "glass" => {
                m.kd = 0.0;
                m.ks = 0.0;
                m.kt = 1.0;
                if let Some(c) = n.get_any(material::TRANSMIT_COLOUR) {
                    m.transmit = c.color()?;
                }
            }
            "emissive" => {
                let colour = match n.get_any(material::EMITTER_COLOUR) {
                    Some(c) => c.color()?,
                    None => Vec3::ONE,
                };
                let strength = opt_f32(n, material::EMITTER_STRENGTH)?.unwrap_or(1.0);
                if !(strength >= 0.0 && strength.is_finite()) {
                    let at = n.get_any(material::EMITTER_STRENGTH).unwrap_or(t);
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

/// The material of shape `s`: its `material` object, the library material its `material` string
/// names, or (without a `material`) the shape itself, which may carry the material's keys.
fn material_node<'a, 't>(
    s: &Node<'a, 't>,
    libraries: &Libraries<'a, 't>,
) -> Result<Node<'a, 't>, SceneError> {
    let node = s.get_any(shape::MATERIAL).unwrap_or_else(|| s.clone());
    let Ok(named) = node.str() else {
        return Ok(node);
    };
    match libraries.materials.find(named) {
        Some((_, def)) => Ok(def.clone()),
        None => {
            let names = libraries.materials.names();
            Err(node.error(format!(
                "no material named '{named}' (the scene defines: {})",
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                }
            )))
        }
    }
}

/// The Blinn-Phong weights `ka`, `kd`, `ks`, the specular exponent and the diffuse and specular
/// colours (a `diffuse` string is a texture, read with the texture).
fn phong_keys(n: &Node, m: &mut Material) -> Result<(), SceneError> {
    if let Some(v) = opt_f32(n, material::KA)? {
        m.ka = v;
    }
    if let Some(v) = opt_f32(n, material::KD)? {
        m.kd = v;
    }
    if let Some(v) = opt_f32(n, material::KS)? {
        m.ks = v;
    }
    if let Some(v) = opt_f32(n, material::EXPONENT)? {
        if v < 0.0 {
            return Err(n.error(format!("the specular exponent must be ≥ 0, found {v}")));
        }
        m.exponent = v;
    }
    if let Some(c) = n.get_any(material::DIFFUSE) {
        m.diffuse = c.color()?;
    } else if let Some(c) = n
        .get_any(material::DIFFUSE_OR_TEXTURE)
        .filter(|c| c.str().is_err())
    {
        m.diffuse = c.color()?;
    }
    if let Some(c) = n.get_any(material::SPECULAR) {
        m.specular = c.color()?;
    }
    Ok(())
}

/// The transmission weight `kt`, switched on or off by `isRefractive`, and the index of
/// refraction; returns the node of the index, if the material gives one (checked later).
fn transmission<'a, 't>(
    n: &Node<'a, 't>,
    m: &mut Material,
) -> Result<Option<Node<'a, 't>>, SceneError> {
    let refractive = n
        .get_any(material::IS_REFRACTIVE)
        .map(|b| b.bool())
        .transpose()?;
    if let Some(v) = opt_f32(n, material::KT)? {
        m.kt = if refractive == Some(false) { 0.0 } else { v };
    } else if refractive == Some(true) {
        m.kt = 1.0;
    }
    let eta_node = n.get_any(material::ETA);
    m.eta = match &eta_node {
        Some(e) => e.f32()?,
        None => DEFAULT_ETA,
    };
    Ok(eta_node)
}
