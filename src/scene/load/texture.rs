//! Textures: image files, and the named texture and material libraries.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use super::spellings::{scene, texture, type_names, type_of, CHECKER_SPACES, TEXTURE_TYPES};
use super::{nearest, opt_f32, required, Loader};
use crate::files::shown;
use crate::image_io::ReadLimits;
use crate::math::Vec2;
use crate::math::Vec3;
use crate::scene::json::{NameIndex, Node};
use crate::scene::SceneError;
use crate::texture::{Checker, Texture};

/// Materials defined once by name (`"materials": [{"name": "red", …}]`) and referred to by it,
/// in file order; a name defined twice means its first definition. Found through an index, as a
/// scene can define and use tens of thousands.
#[derive(Default)]
pub(super) struct Library<'a, 't> {
    defs: Vec<(String, Node<'a, 't>)>,
    index: NameIndex,
}

impl<'a, 't> Library<'a, 't> {
    fn push(&mut self, def: (String, Node<'a, 't>)) {
        self.index.push(&def.0);
        self.defs.push(def);
    }

    /// The first definition named `name`.
    pub(super) fn find(&self, name: &str) -> Option<&(String, Node<'a, 't>)> {
        let i = self.index.find(name, |i| self.defs[i].0.as_str())?;
        Some(&self.defs[i])
    }

    /// Every defined name, in file order.
    pub(super) fn names(&self) -> Vec<&str> {
        self.defs.iter().map(|(n, _)| n.as_str()).collect()
    }
}

/// The named definitions shapes refer to: materials and textures (top-level or `scene`-level
/// `materials` and `textures` arrays), with what has been made of the textures so far.
#[derive(Default)]
pub(super) struct Libraries<'a, 't> {
    pub(super) materials: Library<'a, 't>,
    pub(super) textures: Library<'a, 't>,
    /// Library textures already loaded: name → index into the scene's textures.
    pub(super) loaded: HashMap<String, u32>,
    /// Texture names already warned about (a name that is neither defined nor a file).
    pub(super) warned: HashSet<String>,
}

impl<'a, 't> Libraries<'a, 't> {
    /// Reads the `materials` and `textures` arrays of `holders`, in order. Entries without a
    /// `name` cannot be referred to and are passed over.
    pub(super) fn read(holders: &[&Node<'a, 't>]) -> Result<Self, SceneError> {
        let mut libs = Libraries::default();
        for holder in holders {
            for (keys, lib) in [
                (scene::MATERIAL_LIBRARY, &mut libs.materials),
                (scene::TEXTURE_LIBRARY, &mut libs.textures),
            ] {
                if let Some(list) = holder.get_any(keys) {
                    for m in list.elements()? {
                        // Not a read of the entry: one that nothing uses stays unread.
                        if let Some(name) = m.peek(scene::ENTRY_NAME) {
                            lib.push((name.str()?.to_string(), m.clone()));
                        }
                    }
                }
            }
        }
        Ok(libs)
    }
}

impl Loader<'_> {
    /// A texture reference: the name of a texture library entry, a path string, or an object
    /// with a path.
    pub(super) fn texture(
        &mut self,
        t: &Node,
        libraries: &mut Libraries,
    ) -> Result<Option<u32>, SceneError> {
        if matches!(t.value, jsonc_parser::ast::Value::Array(_)) {
            return Ok(None); // texture coordinates (`texturemap` on meshes), read with the mesh
        }
        if t.is_object() && t.contains_any(texture::TYPE) {
            return self.library_texture(t).map(Some);
        }
        let (node, rel) = if t.is_object() {
            match t.get_any(texture::PATH) {
                Some(p) => {
                    let s = p.str()?;
                    (p, s)
                }
                None => {
                    self.warn(t, "a texture object without a 'path'; ignored");
                    return Ok(None);
                }
            }
        } else {
            let s = t.str()?;
            (t.clone(), s)
        };
        if !t.is_object() {
            if let Some(&done) = libraries.loaded.get(rel) {
                return Ok(Some(done));
            }
            if let Some((name, def)) = libraries.textures.find(rel) {
                let (name, def) = (name.clone(), def.clone());
                let done = self.library_texture(&def)?;
                libraries.loaded.insert(name, done);
                return Ok(Some(done));
            }
        }
        if rel.is_empty() {
            self.warn(&node, "an empty texture file name; texture ignored");
            return Ok(None);
        }
        if type_of(TEXTURE_TYPES, rel) == Some("checkerboard") {
            // A checkerboard named alone: ten black and white squares across the uv square.
            self.textures.push(Texture::checker(Checker {
                colours: [Vec3::ZERO, Vec3::ONE],
                scale: DEFAULT_CHECKER_SCALE,
                solid: false,
            }));
            let done = self.textures.len() as u32 - 1;
            libraries.loaded.insert(rel.to_string(), done);
            return Ok(Some(done));
        }
        if Path::new(rel).extension().is_none() {
            if libraries.warned.contains(rel) {
                return Ok(None); // looked for, and warned about, already
            }
            // An image named without its folder and extension (`wood` for
            // `textures/wood.ppm`, as one renderer looks it up).
            for ext in ["ppm", "png", "jpg"] {
                for folder in ["", "textures/"] {
                    let candidate = format!("{folder}{rel}.{ext}");
                    if let Ok(path) = self.find_asset(&node, &candidate) {
                        let done = self.image_texture_at(&node, path, Vec2::ZERO)?;
                        libraries.loaded.insert(rel.to_string(), done);
                        return Ok(Some(done));
                    }
                }
            }
            // A procedural texture of the file's own program (`wood`, `rainbow`), or a typo.
            if libraries.warned.insert(rel.to_string()) {
                self.warn(
                    &node,
                    format!(
                        "no texture named '{rel}' is defined and it is not an image file; the \
                         material's diffuse colour is used (warned once per name)"
                    ),
                );
            }
            return Ok(None);
        }
        self.image_texture(&node, rel, Vec2::ZERO).map(Some)
    }

    /// A texture given by its `type`: an entry of the texture library or a texture object (see
    /// [`crate::texture`] and docs/scene-format.md, "Texture", for the forms).
    pub(super) fn library_texture(&mut self, def: &Node) -> Result<u32, SceneError> {
        let type_node = required(def, texture::TYPE)?;
        let name = type_node.str()?;
        match type_of(TEXTURE_TYPES, name) {
            Some("constant") => {
                let c = required(def, texture::COLOUR)?.color()?;
                self.textures.push(Texture::constant(c));
                Ok(self.textures.len() as u32 - 1)
            }
            Some("image") => {
                let img = required(def, texture::PATH)?;
                let rel = img.str()?;
                // The file's own program reads image row (1 − v − offset_v)·height: its v grows
                // up the image, so its offset moves the lookup up (−v here).
                let offset = Vec2::new(
                    opt_f32(def, texture::OFFSET[0])?.unwrap_or(0.0),
                    -opt_f32(def, texture::OFFSET[1])?.unwrap_or(0.0),
                );
                self.image_texture(&img, rel, offset)
            }
            Some(_) => {
                let checker = checker(def)?;
                self.textures.push(Texture::checker(checker));
                Ok(self.textures.len() as u32 - 1)
            }
            None => Err(type_node.error(format!(
                "unknown texture type '{name}' (nearest known: '{}'; known: {})",
                nearest(name, &type_names(TEXTURE_TYPES)),
                type_names(TEXTURE_TYPES).join(", ")
            ))),
        }
    }

    /// The image file `rel` (resolved as assets are) as a texture with uv offset `offset`, loaded
    /// once per file and offset.
    pub(super) fn image_texture(
        &mut self,
        node: &Node,
        rel: &str,
        offset: Vec2,
    ) -> Result<u32, SceneError> {
        let path = self.find_asset(node, rel)?;
        self.image_texture_at(node, path, offset)
    }

    /// The image file at `path` (found already) as a texture with uv offset `offset`, loaded
    /// once per file and offset.
    fn image_texture_at(
        &mut self,
        node: &Node,
        path: PathBuf,
        offset: Vec2,
    ) -> Result<u32, SceneError> {
        let key = (path.clone(), [offset.x.to_bits(), offset.y.to_bits()]);
        if let Some(&i) = self.texture_index.get(&key) {
            return Ok(i);
        }
        // The same file under another offset: a copy of its texels, not a second read.
        if let Some((_, &i)) = self.texture_index.iter().find(|((p, _), _)| *p == path) {
            let moved = self.textures[i as usize].clone().with_offset(offset);
            self.textures.push(moved);
            let i = self.textures.len() as u32 - 1;
            self.texture_index.insert(key, i);
            return Ok(i);
        }
        let limits = ReadLimits {
            max_pixels: self.options.max_texture_pixels,
            flag: Some("--max-texture-pixels"),
        };
        let tex = Texture::load_with(&path, &limits)
            .map_err(|e| node.error(format!("cannot load the texture: {e}")))?;
        if tex.width == 0 || tex.height == 0 {
            return Err(node.error(format!("the texture {} is empty", shown(&path))));
        }
        self.textures.push(tex.with_offset(offset));
        let i = self.textures.len() as u32 - 1;
        self.texture_index.insert(key, i);
        Ok(i)
    }
}

/// Squares across a unit of uv of a checkerboard that gives no scale (as one renderer's
/// `"checkerboard"` texture name makes it).
const DEFAULT_CHECKER_SCALE: f32 = 10.0;

/// A checkerboard object: two colours (white and black by default), squares per unit, and the
/// space they are laid out in (`uv` by default, or `3d`).
fn checker(def: &Node) -> Result<Checker, SceneError> {
    let mut colours = [Vec3::ONE, Vec3::ZERO];
    for (c, keys) in colours.iter_mut().zip(texture::CHECKER_COLOURS) {
        if let Some(n) = def.get_any(keys) {
            *c = n.color()?;
        }
    }
    let scale = match def.get_any(texture::CHECKER_SCALE) {
        Some(n) => {
            let v = n.f32()?;
            if !(v > 0.0 && v.is_finite()) {
                return Err(n.error(format!(
                    "a checkerboard's scale (squares per unit) must be > 0, found {v}"
                )));
            }
            v
        }
        None => 1.0,
    };
    let solid = match def.get_any(texture::CHECKER_SPACE) {
        Some(n) => match type_of(CHECKER_SPACES, n.str()?) {
            Some(space) => space == "3d",
            None => {
                return Err(n.error(format!(
                    "a checkerboard's space is 'uv' or '3d', found '{}'",
                    n.str()?
                )))
            }
        },
        None => false,
    };
    Ok(Checker {
        colours,
        scale,
        solid,
    })
}
