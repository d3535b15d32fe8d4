//! The tables of keys, one per kind of object: which keys each holds and the value each takes.
//! The documentation's list ([`markdown`]) and the JSON Schema ([`crate::scene::schema`]) are
//! generated from them.

use super::{
    camera, light, material, scene, shape, texture, Spelling, CAMERA_TYPES, CHECKER_SPACES,
    LIGHT_TYPES, MATERIAL_TYPES, RENDER_MODES, SAMPLING_METHODS, SHAPE_TYPES, TEXTURE_TYPES,
};

/// What a key's value may be, as the loader reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A finite number.
    Number,
    /// A whole number ≥ 0 (`2` or `2.0`).
    Whole,
    /// `true` or `false`, a number (non-zero is true), or the string `"true"` or `"false"`.
    Flag,
    Text,
    /// `[x, y, z]`.
    Vec3,
    /// `[r, g, b]`, or one number for grey.
    Colour,
    /// `[u, v]`.
    Pair,
    /// An array of numbers.
    Numbers,
    /// An array whose elements the loader reads by their form.
    Array,
    /// An object of the table of this entity.
    Object(&'static str),
    /// An array of objects of the table of this entity.
    ListOf(&'static str),
    /// A string naming one of these concepts, under any of its spellings.
    Word(&'static [Spelling]),
    /// Any of these.
    Either(&'static [Value]),
}

/// A concept of a table's keys: the names files spell it with and the value it takes.
pub struct Key {
    pub concept: &'static str,
    pub names: &'static [&'static str],
    pub value: Value,
    /// Numbered keys: each name is a prefix followed by a number (`v0`, `v1`, …).
    pub numbered: bool,
}

/// The spellings of one kind of object: its type names (the values of its `type`), its keys,
/// and the groups of keys of which a file must give one.
pub struct Table {
    /// The name of the object in the documentation and in the schema.
    pub entity: &'static str,
    pub types: &'static [Spelling],
    pub keys: Vec<Key>,
    pub required: &'static [&'static [&'static str]],
}

/// The tables, in the order the documentation shows them.
pub fn tables() -> Vec<Table> {
    vec![
        top_level_table(),
        settings_table(),
        scene_table(),
        camera_table(),
        light_table(),
        shape_table(),
        triangle_table(),
        material_table(),
        texture_table(),
    ]
}

/// One concept of a table's keys.
fn key(concept: &'static str, names: &'static [&'static str], value: Value) -> Key {
    Key {
        concept,
        names,
        value,
        numbered: false,
    }
}

/// Keys spelled `prefix` and a number.
fn numbered(concept: &'static str, prefixes: &'static [&'static str], value: Value) -> Key {
    Key {
        concept,
        names: prefixes,
        value,
        numbered: true,
    }
}

/// The table of a kind of object that has no types.
fn untyped(entity: &'static str, keys: Vec<Key>) -> Table {
    Table {
        entity,
        types: &[],
        keys,
        required: &[],
    }
}

/// How samples are placed, or (at the top level) the samples per pixel.
const SAMPLER: Value = Value::Either(&[Value::Word(SAMPLING_METHODS), Value::Whole]);

/// A shape's or a material's texture: a file or library name, or a texture object.
const TEXTURE: Value = Value::Either(&[Value::Text, Value::Object("texture")]);

/// The keys of the object that holds the scene's lists (`scene`, or the top level).
fn list_keys() -> Vec<Key> {
    vec![
        key("shape list", scene::SHAPE_LISTS, Value::ListOf("shape")),
        key("light list", scene::LIGHT_LISTS, Value::ListOf("light")),
        key(
            "named materials",
            scene::MATERIAL_LIBRARY,
            Value::ListOf("material"),
        ),
        key(
            "named textures",
            scene::TEXTURE_LIBRARY,
            Value::ListOf("texture"),
        ),
        key("background colour", scene::BACKGROUND, Value::Colour),
        key("ambient light", scene::AMBIENT, Value::Colour),
    ]
}

/// The spellings of the top level (which may also hold the scene's lists).
fn top_level_table() -> Table {
    let mut keys = vec![
        key("camera", scene::CAMERA, Value::Object("camera")),
        key("the scene's lists", scene::SCENE, Value::Object("scene")),
        key(
            "image size and samples",
            scene::SETTINGS,
            Value::Object("settings"),
        ),
        key("render mode", scene::RENDER_MODE, Value::Word(RENDER_MODES)),
        key("most bounces", scene::BOUNCES, Value::Whole),
        key("samples per pixel", scene::PIXEL_SAMPLES, Value::Whole),
        key(
            "shadow rays per area light",
            scene::LIGHT_SAMPLES,
            Value::Whole,
        ),
        key("sample placement", scene::SAMPLER, SAMPLER),
        key("jittered or random samples", scene::JITTER, Value::Flag),
        key("tone map", scene::TONE_MAP, Value::Text),
        key("Reinhard's tone map", scene::REINHARD, Value::Flag),
        key("thin-lens camera", scene::USE_DOF, Value::Flag),
        key("lens diameter", scene::LENS_DIAMETER, Value::Number),
        key("focus distance", scene::FOCUS, Value::Number),
        key("exposure", camera::EXPOSURE, Value::Number),
        key(
            "convergence switches (ignored)",
            scene::CONVERGENCE_SWITCHES,
            Value::Flag,
        ),
        key(
            "convergence counts (ignored)",
            scene::CONVERGENCE_COUNTS,
            Value::Number,
        ),
        key("denoiser (not applied)", scene::DENOISER, Value::Flag),
        key("Gaussian blur (not applied)", scene::BLUR, Value::Flag),
        key(
            "rays per bounce (ignored)",
            scene::PATH_SAMPLES,
            Value::Whole,
        ),
    ];
    keys.extend(list_keys());
    Table {
        entity: "top level",
        types: &[],
        keys,
        required: &[scene::CAMERA],
    }
}

/// The spellings of the `settings` object.
fn settings_table() -> Table {
    untyped(
        "settings",
        vec![
            key("image width", camera::WIDTH, Value::Whole),
            key("image height", camera::HEIGHT, Value::Whole),
            key("samples per pixel", scene::SETTINGS_SAMPLES, Value::Whole),
        ],
    )
}

/// The spellings of the `scene` object.
fn scene_table() -> Table {
    let mut keys = list_keys();
    keys.push(key(
        "rays per rough reflection (ignored)",
        scene::ROUGH_SAMPLES,
        Value::Whole,
    ));
    untyped("scene", keys)
}

/// The spellings of the camera.
fn camera_table() -> Table {
    Table {
        entity: "camera",
        types: CAMERA_TYPES,
        keys: vec![
            key("type", camera::TYPE, Value::Word(CAMERA_TYPES)),
            key("image width", camera::WIDTH, Value::Whole),
            key("image height", camera::HEIGHT, Value::Whole),
            key("position", camera::POSITION, Value::Vec3),
            key("point looked at", camera::LOOK, Value::Vec3),
            key("up", camera::UP, Value::Vec3),
            key("camera-to-world matrix", camera::MATRIX, Value::Numbers),
            key("vertical field of view", camera::FOV, Value::Number),
            key("horizontal field of view", camera::HFOV, Value::Number),
            key("exposure", camera::EXPOSURE, Value::Number),
            key("lens radius", camera::LENS_RADIUS, Value::Number),
            key("lens diameter", camera::LENS_DIAMETER, Value::Number),
            key("focus distance", camera::FOCUS, Value::Number),
            key(
                "focus distance beside a focal length",
                camera::FOCUS_DISTANCE,
                Value::Number,
            ),
            key(
                "focal length (with `d` or an f-number)",
                camera::FOCAL_LENGTH,
                Value::Number,
            ),
            key(
                "image distance (with a focal length)",
                camera::IMAGE_DISTANCE,
                Value::Number,
            ),
            key("f-number", camera::F_NUMBER, Value::Number),
            key("lens samples", camera::LENS_SAMPLES, Value::Whole),
            key("sample placement", scene::SAMPLER, SAMPLER),
            key("tone map", scene::TONE_MAP, Value::Text),
        ],
        required: &[camera::ANY_FOV],
    }
}

/// The spellings of lights.
fn light_table() -> Table {
    let [kc, kl, kq] = light::ATTENUATION;
    Table {
        entity: "light",
        types: LIGHT_TYPES,
        keys: vec![
            key("type", light::TYPE, Value::Word(LIGHT_TYPES)),
            key("position or centre", light::POSITION, Value::Vec3),
            key("intensity", light::INTENSITY, Value::Colour),
            key("colour", light::COLOUR, Value::Colour),
            key(
                "specular intensity",
                light::SPECULAR_INTENSITY,
                Value::Colour,
            ),
            key("diffuse intensity", light::DIFFUSE_INTENSITY, Value::Colour),
            key("diffuse factor", light::DIFFUSE, Value::Colour),
            key("specular factor", light::SPECULAR, Value::Colour),
            key("constant attenuation", kc, Value::Number),
            key("linear attenuation", kl, Value::Number),
            key("quadratic attenuation", kq, Value::Number),
            key("radius (sphere, disc)", light::RADIUS, Value::Number),
            key("normal (disc, quad)", light::NORMAL, Value::Vec3),
            numbered("corners `v0`..`v3` or `c1`..`c3`", &["v", "c"], Value::Vec3),
            key("corner (with two edges)", light::CORNER, Value::Vec3),
            key("first edge from the corner", light::EDGE_1, Value::Vec3),
            key("second edge from the corner", light::EDGE_2, Value::Vec3),
            key("first edge about the centre", light::AXIS_U, Value::Vec3),
            key("second edge about the centre", light::AXIS_V, Value::Vec3),
            key("first edge's length", light::WIDTH, Value::Number),
            key("second edge's length", light::HEIGHT, Value::Number),
            key(
                "side, or [width, depth]",
                light::SIZE,
                Value::Either(&[Value::Number, Value::Pair]),
            ),
            key("surface", light::SHAPE, Value::Object("shape")),
            key("surface: a shape's `id`", light::SHAPE_ID, Value::Text),
            key("shadow rays", light::SAMPLES, Value::Whole),
            key("sample placement", scene::SAMPLER, SAMPLER),
        ],
        required: &[light::TYPE],
    }
}

/// The spellings of shapes: a shape object also holds its material's keys when it has no
/// `material`, and its texture's.
fn shape_table() -> Table {
    let mut keys = vec![
        key("type", shape::TYPE, Value::Word(SHAPE_TYPES)),
        key(
            "material",
            shape::MATERIAL,
            Value::Either(&[Value::Object("material"), Value::Text]),
        ),
        key("label", shape::ID, Value::Text),
        key("centre", shape::CENTRE, Value::Vec3),
        key("radius", shape::RADIUS, Value::Number),
        key("cylinder's axis", shape::AXIS, Value::Vec3),
        key("width", shape::WIDTH, Value::Number),
        key("height", shape::HEIGHT, Value::Number),
        key("depth", shape::DEPTH, Value::Number),
        key("box's least corner", shape::MIN, Value::Vec3),
        key("box's greatest corner", shape::MAX, Value::Vec3),
        key("plane's normal", shape::NORMAL, Value::Vec3),
        key("plane's distance", shape::DISTANCE, Value::Number),
        key(
            "rectangle's first corner",
            shape::OPPOSITE_CORNERS[0],
            Value::Vec3,
        ),
        key(
            "rectangle's opposite corner",
            shape::OPPOSITE_CORNERS[1],
            Value::Vec3,
        ),
        numbered(
            "numbered corners or vertices",
            &[shape::VERTEX_PREFIX, shape::POINT_PREFIX, shape::P_PREFIX],
            Value::Vec3,
        ),
        key("corners as a list", shape::POINTS, Value::Array),
        numbered("corners' uv", &[shape::UV_PREFIX], Value::Pair),
        numbered(
            "axis-aligned rectangle's bounds",
            &["x", "y", "z"],
            Value::Number,
        ),
        key(
            "axis-aligned rectangle's constant coordinate",
            &["x", "y", "z", "k"],
            Value::Number,
        ),
    ];
    keys.extend(mesh_keys());
    keys.extend(material_keys());
    Table {
        entity: "shape",
        types: SHAPE_TYPES,
        keys,
        required: &[shape::TYPE],
    }
}

/// The keys of a mesh (written in the scene or read from a file), its placement and a set of
/// spheres.
fn mesh_keys() -> Vec<Key> {
    vec![
        key("mesh file", shape::MESH_FILE, Value::Text),
        key(
            "mesh file's vertex count",
            shape::VERTEX_COUNT,
            Value::Either(&[Value::Whole, Value::Array]),
        ),
        key(
            "mesh file's face count",
            shape::FACE_COUNT,
            Value::Either(&[Value::Whole, Value::Array]),
        ),
        key("vertices", shape::VERTICES, Value::Array),
        key(
            "vertex count (with `v0`, `v1`, …)",
            shape::COUNTED_VERTICES,
            Value::Either(&[Value::Whole, Value::Array]),
        ),
        key(
            "triangles as objects",
            shape::TRIANGLE_OBJECTS,
            Value::Either(&[Value::ListOf("triangle"), Value::Array]),
        ),
        key("polygon sizes", shape::FACE_SIZES, Value::Numbers),
        key("vertex indices", shape::FLAT_INDICES, Value::Numbers),
        key(
            "face count (with `f0`, `f1`, …)",
            shape::COUNTED_FACES,
            Value::Either(&[Value::Whole, Value::Array]),
        ),
        numbered("numbered faces", &[shape::FACE_PREFIX], Value::Numbers),
        key(
            "faces",
            shape::FACES,
            Value::Either(&[Value::Array, Value::Whole]),
        ),
        key(
            "uv per vertex, or a texture",
            shape::TEXTURE_MAP,
            Value::Either(&[Value::Array, Value::Text, Value::Object("texture")]),
        ),
        key("Euler angles", shape::EULER, Value::Vec3),
        numbered("rotation rows `r1`..`r3`", &["r"], Value::Vec3),
        key("scale", shape::SCALE, Value::Colour),
        key("translation", shape::TRANSLATION, Value::Vec3),
        key("number of spheres", shape::SPHERE_COUNT, Value::Whole),
        key("first sphere's x", shape::SPHERE_CENTRE[0], Value::Number),
        key("first sphere's y", shape::SPHERE_CENTRE[1], Value::Number),
        key("first sphere's z", shape::SPHERE_CENTRE[2], Value::Number),
    ]
}

/// The spellings of a mesh's triangle objects (`triangles`).
fn triangle_table() -> Table {
    untyped(
        "triangle",
        vec![
            key("type", shape::TYPE, Value::Word(SHAPE_TYPES)),
            key(
                "material (the mesh's is used)",
                shape::MATERIAL,
                Value::Either(&[Value::Object("material"), Value::Text]),
            ),
            numbered("corners `v0`..`v2`", &[shape::VERTEX_PREFIX], Value::Vec3),
        ],
    )
}

/// The keys of a material, and of its texture.
fn material_keys() -> Vec<Key> {
    vec![
        key("ambient weight", material::KA, Value::Number),
        key("diffuse weight", material::KD, Value::Number),
        key("specular weight", material::KS, Value::Number),
        key("specular exponent", material::EXPONENT, Value::Number),
        key("diffuse colour", material::DIFFUSE, Value::Colour),
        key(
            "diffuse colour or texture",
            material::DIFFUSE_OR_TEXTURE,
            Value::Either(&[Value::Colour, Value::Text]),
        ),
        key("specular colour", material::SPECULAR, Value::Colour),
        key("is a mirror", material::IS_REFLECTIVE, Value::Flag),
        key(
            "mirror weight",
            material::KR,
            Value::Either(&[Value::Number, Value::Text]),
        ),
        key("is glass", material::IS_REFRACTIVE, Value::Flag),
        key("transmission weight", material::KT, Value::Number),
        key("index of refraction", material::ETA, Value::Number),
        key("emitted radiance", material::EMISSION, Value::Colour),
        key("emitter's colour", material::EMITTER_COLOUR, Value::Colour),
        key(
            "emitter's strength",
            material::EMITTER_STRENGTH,
            Value::Number,
        ),
        key("glass tint", material::TRANSMIT_COLOUR, Value::Colour),
        key("roughness", material::ROUGHNESS, Value::Number),
        key("metal colour", material::METAL_COLOUR, Value::Colour),
        key("texture", texture::TEXTURE, TEXTURE),
        key("texture switch", texture::SWITCH, Value::Flag),
    ]
}

/// The spellings of materials.
fn material_table() -> Table {
    let mut keys = vec![key("type", material::TYPE, Value::Word(MATERIAL_TYPES))];
    keys.extend(material_keys());
    Table {
        entity: "material",
        types: MATERIAL_TYPES,
        keys,
        required: &[],
    }
}

/// The spellings of textures.
fn texture_table() -> Table {
    Table {
        entity: "texture",
        types: TEXTURE_TYPES,
        keys: vec![
            key("type", texture::TYPE, Value::Word(TEXTURE_TYPES)),
            key("image file", texture::PATH, Value::Text),
            key("constant colour", texture::COLOUR, Value::Colour),
            key("image's u offset", texture::OFFSET[0], Value::Number),
            key("image's v offset", texture::OFFSET[1], Value::Number),
            key(
                "checkerboard's first colour",
                texture::CHECKER_COLOURS[0],
                Value::Colour,
            ),
            key(
                "checkerboard's second colour",
                texture::CHECKER_COLOURS[1],
                Value::Colour,
            ),
            key(
                "checkerboard's squares per unit",
                texture::CHECKER_SCALE,
                Value::Number,
            ),
            key(
                "checkerboard's space",
                texture::CHECKER_SPACE,
                Value::Word(CHECKER_SPACES),
            ),
        ],
        required: &[],
    }
}

/// How a value is written, for the documentation.
pub fn describe(value: Value) -> String {
    match value {
        Value::Number => "number".into(),
        Value::Whole => "whole number".into(),
        Value::Flag => "true/false".into(),
        Value::Text => "string".into(),
        Value::Vec3 => "[x, y, z]".into(),
        Value::Colour => "[r, g, b] or number".into(),
        Value::Pair => "[u, v]".into(),
        Value::Numbers => "numbers".into(),
        Value::Array => "array".into(),
        Value::Object(e) => format!("{e} object"),
        Value::ListOf(e) => format!("{e} objects"),
        Value::Word(_) => "name".into(),
        Value::Either(vs) => vs
            .iter()
            .map(|v| describe(*v))
            .collect::<Vec<_>>()
            .join(" or "),
    }
}

/// The tables as Markdown, for `docs/scene-format.md`.
pub fn markdown() -> String {
    let list = |names: &[&str], numbered: bool| {
        names
            .iter()
            .map(|n| match numbered {
                true => format!("`{n}N`"),
                false => format!("`{n}`"),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut out = String::new();
    for t in tables() {
        out.push_str(&format!(
            "\n**{}**\n\n| concept | spellings | value |\n|---|---|---|\n",
            t.entity
        ));
        for s in t.types {
            out.push_str(&format!(
                "| type: {} | {} | |\n",
                s.concept,
                list(s.names, false)
            ));
        }
        for k in &t.keys {
            out.push_str(&format!(
                "| {} | {} | {} |\n",
                k.concept,
                list(k.names, k.numbered),
                describe(k.value)
            ));
        }
    }
    out
}
