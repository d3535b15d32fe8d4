//! Every key the loader reads, and every name it accepts for a type: one table per kind of
//! object in a scene file (the top level, `settings`, `scene`, camera, light, shape, a mesh's
//! triangle, material, texture), each listing its type names and, for each concept, the keys
//! files spell it with and the value it takes. The loader reads through these lists (no key is
//! written anywhere else), the unknown-key warnings suggest from them, `docs/scene-format.md`
//! shows them ([`markdown`]) and the JSON Schema is generated from them
//! ([`crate::scene::schema`]).
//!
//! Keys match without regard to case and the separators `_`, `-` and space
//! ([`crate::scene::json::same_key`]), so one spelling stands for all of those; the first of each
//! list is the one the documentation leads with. A new spelling is one more string here.

mod tables;

pub use tables::{describe, markdown, tables, Key, Table, Value};

use crate::scene::json::same_key;

/// One concept and the names files give it.
#[derive(Debug, PartialEq)]
pub struct Spelling {
    /// What it is, for the documentation.
    pub concept: &'static str,
    pub names: &'static [&'static str],
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

/// The scene's top level, its `settings` and its `scene` object.
pub mod scene {
    pub const CAMERA: &[&str] = &["camera"];
    /// The object holding the lists (the top level holds them when it is absent).
    pub const SCENE: &[&str] = &["scene"];
    /// An object of image size and samples, beside the camera.
    pub const SETTINGS: &[&str] = &["settings"];
    pub const RENDER_MODE: &[&str] = &["rendermode"];
    pub const SHAPE_LISTS: &[&str] = &["shapes", "objects", "geometry"];
    pub const LIGHT_LISTS: &[&str] = &["lightsources", "lights"];
    /// Libraries of named materials and textures that shapes refer to by name.
    pub const MATERIAL_LIBRARY: &[&str] = &["materials"];
    pub const TEXTURE_LIBRARY: &[&str] = &["textures"];
    /// The name a library entry is referred to by.
    pub const ENTRY_NAME: &str = "name";
    pub const BOUNCES: &[&str] = &["nbounces", "maxdepth"];
    pub const BACKGROUND: &[&str] = &["backgroundcolor", "backgroundcolour", "background"];
    pub const AMBIENT: &[&str] = &["ambientlight", "ambientintensity", "ambient"];
    /// Samples per pixel, each the total per pixel (`sample_number` also sets the light
    /// samples).
    pub const PIXEL_SAMPLES: &[&str] = &[
        "pixelsample",
        "pixelsamplenum",
        "nspp",
        "camera samples",
        "nsamples",
        "sample_number",
    ];
    /// Samples per pixel in a `settings` object.
    pub const SETTINGS_SAMPLES: &[&str] = &["samples"];
    /// One renderer's rays per rough reflection, in the `scene` object: each camera sample
    /// traces one here.
    pub const ROUGH_SAMPLES: &[&str] = &["nsamples"];
    /// Shadow rays per area light and shading point (the total).
    pub const LIGHT_SAMPLES: &[&str] = &["lightsample", "shadow samples", "spp", "sample_number"];
    /// How samples are placed (a [`SAMPLING_METHODS`](super::SAMPLING_METHODS) name), in the
    /// top level, the camera or a light; a number at the top level is the samples per pixel.
    pub const SAMPLER: &[&str] = &["method", "sampler", "sampling"];
    /// `true`: jittered pixel and light samples; `false`: random ones.
    pub const JITTER: &[&str] = &["use_jitter_sample"];
    /// A tone map by name, in the camera or at the top level.
    pub const TONE_MAP: &[&str] = &["tone_mapping", "tonemapper", "tonemap"];
    /// `true`: Reinhard's tone map.
    pub const REINHARD: &[&str] = &["use_tone_mapping"];
    /// `true`: a thin-lens camera.
    pub const USE_DOF: &[&str] = &["use_dof"];
    /// A lens's diameter and focus distance given beside the camera, for `use_dof`.
    pub const LENS_DIAMETER: &[&str] = &["aperture"];
    pub const FOCUS: &[&str] = &["focusdistance"];
    /// Switches of how fast an image converges, not what to: read and otherwise ignored.
    pub const CONVERGENCE_SWITCHES: &[&str] = &[
        "use_stratified_sampling",
        "use_importance_sampling",
        "usegi",
        "usecaustics",
        "lens_sampling",
    ];
    pub const CONVERGENCE_COUNTS: &[&str] = &[
        "importance_sampling_min_samples",
        "importance_sampling_max_samples",
    ];
    /// Post-processes not done here: warned about when on.
    pub const DENOISER: &[&str] = &["use_denoiser"];
    pub const BLUR: &[&str] = &["use_gaussian_blur"];
    /// A branching path tracer's rays per bounce: warned about.
    pub const PATH_SAMPLES: &[&str] = &["path_sample_num"];
}

/// The camera.
pub mod camera {
    pub const TYPE: &[&str] = &["type"];
    pub const WIDTH: &[&str] = &["width"];
    pub const HEIGHT: &[&str] = &["height"];
    pub const POSITION: &[&str] = &[
        "position", "location", "origin", "lookfrom", "campos", "eye", "from",
    ];
    /// The point looked at; `lookat` spelled just so is the 2021–23 skeleton's direction.
    pub const LOOK: &[&str] = &["lookat", "look", "camview", "target", "to"];
    /// The spelling of [`LOOK`] that is a direction, not a point.
    pub const DIRECTION: &str = "lookat";
    pub const UP: &[&str] = &["up", "upvector", "vup", "camaxis"];
    /// Keys only the 2021–23 camera has.
    pub const V2021_KEYS: &[&str] = &["position", "lookat", "up"];
    /// Keys only the CGR camera has (some CGR files have no `rendermode`).
    pub const CGR_KEYS: &[&str] = &["upVector", "exposure"];
    /// A 4 × 4 camera-to-world matrix, row by row (translation in the last column), looking
    /// down its −z axis with +y up: replaces position, look and up.
    pub const MATRIX: &[&str] = &["cameratoworld"];
    pub const FOV: &[&str] = &["fov"];
    pub const HFOV: &[&str] = &["hfov"];
    /// One of the two fields of view.
    pub const ANY_FOV: &[&str] = &["fov", "hfov"];
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
    /// The f-number of a lens given with an image distance `d`.
    pub const LENS_F_NUMBER: &[&str] = &["aperture", "fstop", "fnumber"];
    /// A thin-lens camera's rays per pixel (the total).
    pub const LENS_SAMPLES: &[&str] = &["samplesize", "nsamples"];
}

/// Lights.
pub mod light {
    pub const TYPE: &[&str] = &["type"];
    pub const POSITION: &[&str] = &["position", "pos", "center", "centre"];
    /// Power, or with `is`/`id` the strength they are scaled to.
    pub const INTENSITY: &[&str] = &["intensity", "power"];
    pub const COLOUR: &[&str] = &["color", "colour"];
    /// An ambient light's level.
    pub const AMBIENT_LEVEL: &[&str] = &["intensity", "color", "colour"];
    /// Specular and diffuse intensity, each a colour.
    pub const SPECULAR_INTENSITY: &[&str] = &["is"];
    pub const DIFFUSE_INTENSITY: &[&str] = &["id"];
    /// Factors of the intensity for diffuse and specular shading.
    pub const DIFFUSE: &[&str] = &["diffuse"];
    pub const SPECULAR: &[&str] = &["specular"];
    /// Attenuation 1 / (kc + kl·d + kq·d²).
    pub const ATTENUATION: [&[&str]; 3] = [&["kc"], &["kl"], &["kq"]];
    pub const RADIUS: &[&str] = &["radius"];
    pub const NORMAL: &[&str] = &["normal"];
    /// Four corners in order around a quad (the fourth may be left out).
    pub const CORNERS: [&[&str]; 4] = [&["v0"], &["v1"], &["v2"], &["v3"]];
    /// Three corners of a rectangle, the right angle at the middle one.
    pub const RIGHT_ANGLE_CORNERS: [&[&str]; 3] = [&["c1"], &["c2"], &["c3"]];
    /// A parallelogram's corner and two edges.
    pub const CORNER: &[&str] = &["p", "corner"];
    pub const EDGE_1: &[&str] = &["e0", "edge1", "edgeu"];
    pub const EDGE_2: &[&str] = &["e1", "edge2", "edgev"];
    /// A parallelogram's two edges about its centre (`position`).
    pub const AXIS_U: &[&str] = &["u", "uaxis"];
    pub const AXIS_V: &[&str] = &["v", "vaxis"];
    /// The lengths the two edges are scaled to.
    pub const WIDTH: &[&str] = &["width"];
    pub const HEIGHT: &[&str] = &["height"];
    /// A square's side, or `[width, depth]`, about the position, in the xz plane.
    pub const SIZE: &[&str] = &["size"];
    /// The light's surface: a shape object, or the `id` of a shape of the scene.
    pub const SHAPE: &[&str] = &["shape"];
    pub const SHAPE_ID: &[&str] = &["shapeid"];
    pub const SAMPLES: &[&str] = &["samples", "nsamples", "samplesize", "cell", "numsamples"];
}

/// Shapes, and the meshes, rectangles and sphere sets they become.
pub mod shape {
    pub const TYPE: &[&str] = &["type"];
    /// A material object, or the name of one in the `materials` library; without it the
    /// shape's own keys are its material.
    pub const MATERIAL: &[&str] = &["material"];
    /// A label an area light's `shapeid` refers to.
    pub const ID: &[&str] = &["id"];
    pub const CENTRE: &[&str] = &["center", "centre", "position"];
    /// The centre of a box or a rectangle (not `position`, which a box's translation spells).
    pub const BOX_CENTRE: &[&str] = &["center", "centre"];
    pub const RADIUS: &[&str] = &["radius"];
    pub const AXIS: &[&str] = &["axis"];
    pub const WIDTH: &[&str] = &["width"];
    pub const HEIGHT: &[&str] = &["height"];
    pub const DEPTH: &[&str] = &["depth"];
    pub const MIN: &[&str] = &["min"];
    pub const MAX: &[&str] = &["max"];
    /// An infinite plane: its normal and its distance from the origin along it.
    pub const NORMAL: &[&str] = &["normal"];
    pub const DISTANCE: &[&str] = &["distance"];
    /// Two opposite corners of an axis-aligned rectangle.
    pub const OPPOSITE_CORNERS: [&[&str]; 2] = [&["corner1"], &["corner2"]];
    /// The corners of a triangle or quad, in each of the numberings files use.
    pub const CORNER_NAMES: [[&str; 4]; 4] = [
        ["v0", "v1", "v2", "v3"],
        ["v1", "v2", "v3", "v4"],
        ["point1", "point2", "point3", "point4"],
        ["p0", "p1", "p2", "p3"],
    ];
    /// Numbered corners (and an inline mesh's numbered vertices): `v0`, `v1`, ….
    pub const VERTEX_PREFIX: &str = "v";
    pub const POINT_PREFIX: &str = "point";
    pub const P_PREFIX: &str = "p";
    /// The corners as a list.
    pub const POINTS: &[&str] = &["points", "vertices"];
    /// Texture coordinates of the corners, in either numbering.
    pub const CORNER_UVS: [[&str; 4]; 2] =
        [["uv0", "uv1", "uv2", "uv3"], ["uv1", "uv2", "uv3", "uv4"]];
    pub const UV_PREFIX: &str = "uv";
    /// Any key that gives corners (a quad with none is an infinite plane or a centred
    /// rectangle).
    pub const ANY_CORNERS: &[&str] = &["v0", "v1", "point1", "p0", "points", "vertices", "corner1"];
    /// An axis-aligned rectangle's bounds (`x0`, `x1`, …) and its constant coordinate (`z`,
    /// or `k`).
    pub const RECTANGLE_AXES: [&str; 3] = ["x", "y", "z"];
    pub const RECTANGLE_LEVEL: &[&str] = &["k"];
    /// A mesh file.
    pub const MESH_FILE: &[&str] = &[
        "mPath",
        "plyPath",
        "modelpath",
        "model",
        "path",
        "file",
        "filename",
    ];
    /// The vertex and face counts a scene repeats from its mesh file's header.
    pub const VERTEX_COUNT: &[&str] = &["vs"];
    pub const FACE_COUNT: &[&str] = &["fs"];
    /// An inline mesh's vertices: a list of `[x, y, z]`.
    pub const VERTICES: &[&str] = &["vertices", "vs", "vertex", "points"];
    /// An inline mesh's vertex count, its vertices then in `v0`, `v1`, ….
    pub const COUNTED_VERTICES: &[&str] = &["vertex"];
    /// An inline mesh's triangles as objects with corners `v0`, `v1`, `v2`.
    pub const TRIANGLE_OBJECTS: &[&str] = &["triangles"];
    /// Polygon sizes with one flat list of vertex indices.
    pub const FACE_SIZES: &[&str] = &["faceindex", "numVerticesOnEachFace"];
    pub const FLAT_INDICES: &[&str] = &["vertexindex", "verticesOnEachFace"];
    /// A face count, the faces then in `f0`, `f1`, ….
    pub const COUNTED_FACES: &[&str] = &["face"];
    pub const FACE_PREFIX: &str = "f";
    /// A list of faces, each a list of vertex indices (`faces` may also be a count that the
    /// faces' sizes are checked against).
    pub const FACES: &[&str] = &["faces", "fs", "tris", "triangles", "face"];
    /// The face count given beside polygon sizes.
    pub const FACE_TOTAL: &[&str] = &["faces"];
    /// One `[u, v]` per vertex of a mesh.
    pub const TEXTURE_MAP: &[&str] = &["texturemap"];
    /// Euler angles in degrees, or the rows of a rotation matrix.
    pub const EULER: &[&str] = &["euler", "rotation", "rot"];
    pub const ROTATION_ROWS: [&[&str]; 3] = [&["r1"], &["r2"], &["r3"]];
    /// A mesh's scale (a number or per axis) and translation.
    pub const SCALE: &[&str] = &["scale", "sizeScale", "size"];
    pub const TRANSLATION: &[&str] = &[
        "position",
        "pos",
        "offset",
        "translate",
        "translation",
        "center",
    ];
    /// A set of spheres: their count and the first one's centre.
    pub const SPHERE_COUNT: &[&str] = &["n"];
    pub const SPHERE_CENTRE: [&[&str]; 3] = [&["locX"], &["locY"], &["locZ"]];
    /// The keys of an inline mesh's vertices, whose presence rules out a set of spheres.
    pub const INLINE_VERTICES: &[&str] = &["vertices", "vs", "vertex", "points", "triangles"];
}

/// Materials.
pub mod material {
    pub const TYPE: &[&str] = &["type"];
    pub const KA: &[&str] = &["ka"];
    pub const KD: &[&str] = &["kd"];
    pub const KS: &[&str] = &["ks"];
    pub const EXPONENT: &[&str] = &["specularexponent", "shininess", "exponent", "alpha"];
    pub const DIFFUSE: &[&str] = &[
        "diffusecolor",
        "diffusecolour",
        "color",
        "colour",
        "albedo",
        "basecolor",
    ];
    /// A diffuse colour, or the name of a texture.
    pub const DIFFUSE_OR_TEXTURE: &[&str] = &["diffuse"];
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
    /// An emissive material's colour and the strength it is scaled by.
    pub const EMITTER_COLOUR: &[&str] = &["colour", "color", "emission", "emittance"];
    pub const EMITTER_STRENGTH: &[&str] = &["intensity", "strength"];
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
    pub const TYPE: &[&str] = &["type"];
    pub const PATH: &[&str] = &["path", "file", "filename", "tpath", "image"];
    /// A constant texture's colour.
    pub const COLOUR: &[&str] = &["colour", "color"];
    /// An image's uv offset.
    pub const OFFSET: [&[&str]; 2] = [&["offset_u"], &["offset_v"]];
    pub const CHECKER_COLOURS: [&[&str]; 2] = [
        &["color1", "colour1", "even", "color_a"],
        &["color2", "colour2", "odd", "color_b"],
    ];
    /// Squares per unit of the shape's uv (or of world space, for a 3D checkerboard).
    pub const CHECKER_SCALE: &[&str] = &["scale", "frequency", "squares"];
    /// Where the squares are laid out: a [`CHECKER_SPACES`](super::CHECKER_SPACES) name.
    pub const CHECKER_SPACE: &[&str] = &["space", "mapping"];
}

/// Render modes (the top level's `rendermode`).
pub const RENDER_MODES: &[Spelling] = &[
    Spelling {
        concept: "binary",
        names: &["binary"],
    },
    Spelling {
        concept: "phong",
        names: &["phong"],
    },
    Spelling {
        concept: "path",
        names: &["pathtrace", "pathtracer", "pathtracing", "path", "pt"],
    },
];

/// How samples are placed.
pub const SAMPLING_METHODS: &[Spelling] = &[
    Spelling {
        concept: "random",
        names: &["random", "uniform"],
    },
    Spelling {
        concept: "jittered",
        names: &["jittered", "stratified", "jitter", "jittering", "grid"],
    },
    Spelling {
        concept: "sobol",
        names: &["sobol"],
    },
];

/// Where a checkerboard's squares are laid out.
pub const CHECKER_SPACES: &[Spelling] = &[
    Spelling {
        concept: "uv",
        names: &["uv"],
    },
    Spelling {
        concept: "3d",
        names: &["3d", "world", "solid", "xyz"],
    },
];

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
