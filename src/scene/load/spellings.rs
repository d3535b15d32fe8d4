//! Every spelling the loader reads: one table per kind of thing (the scene's top level, camera,
//! light, shape, material, texture), each listing its type names and the keys of each concept.
//! The loader reads through these lists, the unknown-key warnings suggest from them, and
//! `docs/scene-format.md` shows them ([`markdown`]; `tests/spellings.rs` keeps the two equal).
//!
//! Keys match without regard to case and the separators `_`, `-` and space
//! ([`crate::scene::json::same_key`]), so one spelling stands for all of those; the first of each
//! list is the one the documentation leads with. A new spelling is one more string here.

use crate::scene::json::same_key;

/// One concept and the names files give it.
pub struct Spelling {
    /// What it is, for the documentation.
    pub concept: &'static str,
    pub names: &'static [&'static str],
}

/// The spellings of one kind of thing: its type names (the values of its `type`) and its keys.
pub struct Table {
    pub entity: &'static str,
    pub types: &'static [Spelling],
    pub keys: Vec<Spelling>,
}

/// The concept of `types` that `name` spells, if any.
pub fn type_of(types: &[Spelling], name: &str) -> Option<&'static str> {
    types
        .iter()
        .find(|t| t.names.iter().any(|n| same_key(n, name)))
        .map(|t| t.concept)
}

/// Every type name of `types`, for suggestions.
pub fn type_names(types: &[Spelling]) -> Vec<&'static str> {
    types.iter().flat_map(|t| t.names.iter().copied()).collect()
}

/// The scene's top level and its `scene` object.
pub mod scene {
    pub const SHAPE_LISTS: &[&str] = &["shapes", "objects", "geometry"];
    pub const LIGHT_LISTS: &[&str] = &["lightsources", "lights"];
    pub const BOUNCES: &[&str] = &["nbounces", "maxdepth"];
    pub const BACKGROUND: &[&str] = &["backgroundcolor", "backgroundcolour", "background"];
    pub const AMBIENT: &[&str] = &["ambientlight", "ambientintensity", "ambient"];
    /// Samples per pixel, each the total per pixel (`sample_number` also sets the light
    /// samples); `settings.samples` in files with a `settings` object.
    pub const PIXEL_SAMPLES: &[&str] = &[
        "pixelsample",
        "pixelsamplenum",
        "nspp",
        "camera samples",
        "nsamples",
        "sample_number",
    ];
    /// Shadow rays per area light and shading point (the total).
    pub const LIGHT_SAMPLES: &[&str] = &["lightsample", "shadow samples", "spp", "sample_number"];
    /// How pixel samples are placed: `jittered`, `random`, `sobol` (and spellings).
    pub const SAMPLER: &[&str] = &["method", "sampler", "sampling"];
    /// `true`: jittered pixel and light samples; `false`: random ones.
    pub const JITTER: &[&str] = &["use_jitter_sample"];
    /// A tone map by name, in the camera or at the top level.
    pub const TONE_MAP: &[&str] = &["tone_mapping", "tonemapper", "tonemap"];
}

/// The camera.
pub mod camera {
    pub const POSITION: &[&str] = &[
        "position", "location", "origin", "lookfrom", "campos", "eye", "from",
    ];
    /// The point looked at; `lookat` spelled just so is the 2021–23 skeleton's direction.
    pub const LOOK: &[&str] = &["lookat", "look", "camview", "target", "to"];
    pub const UP: &[&str] = &["up", "upvector", "vup", "camaxis"];
    /// A 4 × 4 camera-to-world matrix, row by row (translation in the last column), looking
    /// down its −z axis with +y up: replaces position, look and up.
    pub const MATRIX: &[&str] = &["cameratoworld"];
    pub const FOV: &[&str] = &["fov"];
    pub const HFOV: &[&str] = &["hfov"];
    pub const EXPOSURE: &[&str] = &["exposure"];
    pub const LENS_RADIUS: &[&str] = &["lensradius", "radius", "aperturesize", "apertureradius"];
    /// `size` is the side of the square aperture of one renderer, read as the diameter of a
    /// round one.
    pub const LENS_DIAMETER: &[&str] = &["aperture", "diameter", "ap", "size"];
    pub const FOCUS: &[&str] = &[
        "focusdistance",
        "focaldistance",
        "focusdist",
        "focallength",
        "focal",
        "focus",
        "f",
    ];
    /// A focus distance proper: what a lens given by its focal length focuses at.
    pub const FOCUS_DISTANCE: &[&str] = &["focusdistance", "focaldistance", "focusdist"];
    /// A real lens's focal length (millimetres beside an f-number `fstop`).
    pub const FOCAL_LENGTH: &[&str] = &["focal", "focallength"];
    /// A real lens: its focal length (`focal`), the image distance behind it (`d`) and its
    /// f-number (`aperture`); the lens radius is focal / (2 · f-number) and the plane in focus
    /// lies at focal · d / (d − focal).
    pub const IMAGE_DISTANCE: &[&str] = &["d"];
    pub const F_NUMBER: &[&str] = &["fstop", "fnumber"];
    /// A thin-lens camera's rays per pixel (the total).
    pub const LENS_SAMPLES: &[&str] = &["samplesize", "nsamples"];
}

/// Lights.
pub mod light {
    pub const POSITION: &[&str] = &["position", "pos", "center", "centre"];
    /// Power (`is`/`id` are separate keys: specular and diffuse intensity).
    pub const INTENSITY: &[&str] = &["intensity", "power"];
    pub const COLOUR: &[&str] = &["color", "colour"];
    pub const RADIUS: &[&str] = &["radius"];
    pub const NORMAL: &[&str] = &["normal"];
    /// A parallelogram's corner and two edges.
    pub const CORNER: &[&str] = &["p", "corner"];
    pub const EDGE_1: &[&str] = &["e0", "edge1", "edgeu"];
    pub const EDGE_2: &[&str] = &["e1", "edge2", "edgev"];
    /// A parallelogram's two edges about its centre (`position`).
    pub const AXIS_U: &[&str] = &["u", "uaxis"];
    pub const AXIS_V: &[&str] = &["v", "vaxis"];
    pub const SAMPLES: &[&str] = &["samples", "nsamples", "samplesize", "cell", "numsamples"];
}

/// Shapes.
pub mod shape {
    pub const CENTRE: &[&str] = &["center", "centre", "position"];
}

/// Materials.
pub mod material {
    pub const EXPONENT: &[&str] = &["specularexponent", "shininess", "exponent", "alpha"];
    pub const DIFFUSE: &[&str] = &[
        "diffusecolor",
        "diffusecolour",
        "color",
        "colour",
        "albedo",
        "basecolor",
    ];
    pub const SPECULAR: &[&str] = &["specularcolor", "specularcolour"];
    pub const IS_REFLECTIVE: &[&str] = &["isreflective"];
    /// The mirror's weight (`metallic`: one renderer's additive mirror weight).
    pub const KR: &[&str] = &[
        "kr",
        "reflectivity",
        "reflection",
        "reflectance",
        "metallic",
    ];
    pub const IS_REFRACTIVE: &[&str] = &["isrefractive", "isglass"];
    pub const KT: &[&str] = &["kt", "transparency", "transmit", "transmittance"];
    pub const ETA: &[&str] = &["eta", "refractiveindex", "ior"];
    /// Radiance emitted: a colour, or a number that scales the diffuse colour.
    pub const EMISSION: &[&str] = &[
        "emission",
        "emissioncolor",
        "emissioncolour",
        "emittance",
        "emittence",
        "emissive",
    ];
    /// The tint of light through a glass.
    pub const TRANSMIT_COLOUR: &[&str] = &["transmittancecolor", "transmittancecolour"];
    pub const ROUGHNESS: &[&str] = &["roughness", "fuzz"];
    /// A metal's colour, tinting what it reflects.
    pub const METAL_COLOUR: &[&str] = &["albedo", "basecolor", "color", "colour", "specularcolor"];
}

/// Textures.
pub mod texture {
    /// A texture: a file, a library name, or an object (an image's `path`, or a procedural
    /// `type`).
    pub const TEXTURE: &[&str] = &[
        "texture",
        "tpath",
        "texturepath",
        "texturefile",
        "texturefilename",
        "texturedir",
        "texturemap",
    ];
    /// A switch that turns the texture on (`false`: the diffuse colour alone).
    pub const SWITCH: &[&str] = &["hastexture", "usetexture"];
    pub const PATH: &[&str] = &["path", "file", "filename", "tpath", "image"];
    pub const CHECKER_COLOURS: [&[&str]; 2] = [
        &["color1", "colour1", "even", "color_a"],
        &["color2", "colour2", "odd", "color_b"],
    ];
    /// Squares per unit of the shape's uv (or of world space, for a 3D checkerboard).
    pub const CHECKER_SCALE: &[&str] = &["scale", "frequency", "squares"];
    /// `uv` (default) or `3d`/`world`/`solid`: where the squares are laid out.
    pub const CHECKER_SPACE: &[&str] = &["space", "mapping"];
}

/// Camera types.
pub const CAMERA_TYPES: &[Spelling] = &[
    Spelling {
        concept: "pinhole",
        names: &["pinhole", "perspective"],
    },
    Spelling {
        concept: "thin lens (an aperture and a focus distance)",
        names: &[
            "thinlens",
            "thinlen",
            "lens",
            "aperture",
            "dof",
            "finiteaperture",
            "depthoffield",
            "realistic",
        ],
    },
];

/// Light types.
pub const LIGHT_TYPES: &[Spelling] = &[
    Spelling {
        concept: "point",
        names: &["pointlight", "point"],
    },
    Spelling {
        concept: "area",
        names: &[
            "arealight",
            "area",
            "quadlight",
            "rectlight",
            "rectanglelight",
        ],
    },
    Spelling {
        concept: "sphere",
        names: &["spherelight", "sphericallight"],
    },
    Spelling {
        concept: "disc",
        names: &["disclight", "disklight", "disc", "disk"],
    },
    Spelling {
        concept: "ambient",
        names: &["ambient", "ambientlight"],
    },
];

/// Shape types.
pub const SHAPE_TYPES: &[Spelling] = &[
    Spelling {
        concept: "sphere",
        names: &["sphere", "uvsphere"],
    },
    Spelling {
        concept: "cylinder",
        names: &["cylinder", "uvcylinder"],
    },
    Spelling {
        concept: "triangle",
        names: &["triangle"],
    },
    Spelling {
        concept: "quad",
        names: &["plane", "planarquad", "planerquad", "quad", "rectangle"],
    },
    Spelling {
        concept: "box",
        names: &["box"],
    },
    Spelling {
        concept: "rectanglexy",
        names: &["rectanglexy"],
    },
    Spelling {
        concept: "rectanglexz",
        names: &["rectanglexz"],
    },
    Spelling {
        concept: "rectangleyz",
        names: &["rectangleyz"],
    },
    Spelling {
        concept: "mesh",
        names: &["trimesh", "mesh", "ply", "trianglemesh", "tris"],
    },
];

/// Material types.
pub const MATERIAL_TYPES: &[Spelling] = &[
    Spelling {
        concept: "phong",
        names: &["phong", "blinnphong", "plastic"],
    },
    Spelling {
        concept: "diffuse",
        names: &["diffuse", "lambertian", "matte", "orennayer", "gooch"],
    },
    Spelling {
        concept: "metal",
        names: &["metal", "conductor", "mirror", "reflective"],
    },
    Spelling {
        concept: "glass",
        names: &["glass", "dielectric", "transparent", "refractive"],
    },
    Spelling {
        concept: "emissive",
        names: &["emissive", "emitter", "light", "emission"],
    },
];

/// Texture types (a library entry's or a texture object's `type`).
pub const TEXTURE_TYPES: &[Spelling] = &[
    Spelling {
        concept: "image",
        names: &["image", "file", "bitmap"],
    },
    Spelling {
        concept: "constant",
        names: &["constant", "solid"],
    },
    Spelling {
        concept: "checkerboard",
        names: &[
            "checkerboard",
            "checker",
            "checkered",
            "chessboard",
            "checkers",
        ],
    },
];

/// The tables, in the order the documentation shows them.
pub fn tables() -> Vec<Table> {
    vec![
        top_level_table(),
        camera_table(),
        light_table(),
        shape_table(),
        material_table(),
        texture_table(),
    ]
}

/// One concept of a table's keys.
fn key(concept: &'static str, names: &'static [&'static str]) -> Spelling {
    Spelling { concept, names }
}

/// The spellings of the top level and the `scene` object.
fn top_level_table() -> Table {
    Table {
        entity: "top level and `scene`",
        types: &[],
        keys: vec![
            key("shape list", scene::SHAPE_LISTS),
            key("light list", scene::LIGHT_LISTS),
            key("most bounces", scene::BOUNCES),
            key("background colour", scene::BACKGROUND),
            key("ambient light", scene::AMBIENT),
            key("samples per pixel", scene::PIXEL_SAMPLES),
            key("shadow rays per area light", scene::LIGHT_SAMPLES),
            key("sample placement", scene::SAMPLER),
            key("jittered or random samples", scene::JITTER),
            key("tone map (camera or top level)", scene::TONE_MAP),
        ],
    }
}

/// The spellings of the camera.
fn camera_table() -> Table {
    Table {
        entity: "camera",
        types: CAMERA_TYPES,
        keys: vec![
            key("position", camera::POSITION),
            key("point looked at", camera::LOOK),
            key("up", camera::UP),
            key("camera-to-world matrix", camera::MATRIX),
            key("vertical field of view", camera::FOV),
            key("horizontal field of view", camera::HFOV),
            key("exposure", camera::EXPOSURE),
            key("lens radius", camera::LENS_RADIUS),
            key("lens diameter", camera::LENS_DIAMETER),
            key("focus distance", camera::FOCUS),
            key(
                "focus distance beside a focal length",
                camera::FOCUS_DISTANCE,
            ),
            key(
                "focal length (with `d` or an f-number)",
                camera::FOCAL_LENGTH,
            ),
            key(
                "image distance (with a focal length)",
                camera::IMAGE_DISTANCE,
            ),
            key("f-number", camera::F_NUMBER),
            key("lens samples", camera::LENS_SAMPLES),
        ],
    }
}

/// The spellings of lights.
fn light_table() -> Table {
    Table {
        entity: "light",
        types: LIGHT_TYPES,
        keys: vec![
            key("position or centre", light::POSITION),
            key("intensity", light::INTENSITY),
            key("colour", light::COLOUR),
            key("radius (sphere, disc)", light::RADIUS),
            key("normal (disc, quad)", light::NORMAL),
            key("corner (with two edges)", light::CORNER),
            key("first edge from the corner", light::EDGE_1),
            key("second edge from the corner", light::EDGE_2),
            key("first edge about the centre", light::AXIS_U),
            key("second edge about the centre", light::AXIS_V),
            key("shadow rays", light::SAMPLES),
        ],
    }
}

/// The spellings of shapes.
fn shape_table() -> Table {
    Table {
        entity: "shape",
        types: SHAPE_TYPES,
        keys: vec![key("centre", shape::CENTRE)],
    }
}

/// The spellings of materials.
fn material_table() -> Table {
    Table {
        entity: "material",
        types: MATERIAL_TYPES,
        keys: vec![
            key("specular exponent", material::EXPONENT),
            key("diffuse colour", material::DIFFUSE),
            key("specular colour", material::SPECULAR),
            key("is a mirror", material::IS_REFLECTIVE),
            key("mirror weight", material::KR),
            key("is glass", material::IS_REFRACTIVE),
            key("transmission weight", material::KT),
            key("index of refraction", material::ETA),
            key("emitted radiance", material::EMISSION),
            key("glass tint", material::TRANSMIT_COLOUR),
            key("roughness", material::ROUGHNESS),
            key("metal colour", material::METAL_COLOUR),
        ],
    }
}

/// The spellings of textures.
fn texture_table() -> Table {
    Table {
        entity: "texture",
        types: TEXTURE_TYPES,
        keys: vec![
            key("texture", texture::TEXTURE),
            key("texture switch", texture::SWITCH),
            key("image file", texture::PATH),
            key("checkerboard's first colour", texture::CHECKER_COLOURS[0]),
            key("checkerboard's second colour", texture::CHECKER_COLOURS[1]),
            key("checkerboard's squares per unit", texture::CHECKER_SCALE),
            key("checkerboard's space", texture::CHECKER_SPACE),
        ],
    }
}

/// The tables as Markdown, for `docs/scene-format.md`.
pub fn markdown() -> String {
    let list = |names: &[&str]| {
        names
            .iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut out = String::new();
    for t in tables() {
        out.push_str(&format!(
            "\n**{}**\n\n| concept | spellings |\n|---|---|\n",
            t.entity
        ));
        for s in t.types {
            out.push_str(&format!("| type: {} | {} |\n", s.concept, list(s.names)));
        }
        for s in &t.keys {
            out.push_str(&format!("| {} | {} |\n", s.concept, list(s.names)));
        }
    }
    out
}
