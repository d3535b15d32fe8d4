//! Area lights whose surface is a sphere or a shape of the scene: reading the light's `shape`,
//! and tying a `shapeid` to the shape with that `id` once the shapes are read.
//!
//! ```json
//! { "type": "arealight", "intensity": [20, 20, 20], "samplesize": 10,
//!   "shape": { "type": "sphere", "center": [-2, 2, 2], "radius": 1 } }
//! { "type": "arealight", "shape": { "type": "plane", "points": [[-3, -8, -3], [-3, -8, 3], [3, -8, 3], [3, -8, -3]] }, … }
//! { "type": "arealight", "shapeid": "myarealightshape", "is": [100, 100, 100], "id": [100, 100, 100] }
//! …
//! "shapes": [ { "id": "myarealightshape", "type": "plane", "v0": […], "v1": […], "v2": […], "v3": […],
//!               "material": { … } } ]
//! ```
//! A light's `shape` is geometry of the light alone: it is not a shape of the scene, so camera
//! rays do not see it (like a quad light). A `shapeid` names a shape of the scene's `shapes` by its
//! `id`: that shape stays a shape (camera rays see its material, and it shadows other lights), and
//! it is also the light's surface, which its own shadow rays pass through. Shapes are read after
//! lights, so a `shapeid` is only noted when its light is read ([`ShapeLights::want`]) and resolved
//! once every shape is known ([`ShapeLights::resolve`]).
//!
//! Only flat shapes (`triangle`, `plane` and the other quad spellings) and spheres can emit: the
//! samples of a flat shape or of a sphere's visible cap see the shading point directly, but a
//! mesh, a box or a cylinder would shine through itself, since its own primitives never block its
//! shadow rays.

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use super::error::{Location, SceneError, Warning};
use super::json::Node;
use super::load::spellings::{self, type_of, SHAPE_TYPES};
use super::load::{required, required_positive};
use crate::geometry::{Primitive, Primitives, Shape};
use crate::light::{cumulative_areas, Intensity, Light};
use crate::math::Vec3;
use crate::sampling::Method;

/// Most shape ids listed in the message of a `shapeid` that names none.
const LISTED_IDS: usize = 20;

/// The sphere of a light's `"shape": {"type": "sphere", "center": …, "radius": …}`: the centre
/// (`center`, `centre` or `position`) and a radius > 0.
pub(super) fn sphere(shape: &Node) -> Result<(Vec3, f32), SceneError> {
    let center = required(shape, spellings::shape::CENTRE)?.vec3()?;
    let radius = required_positive(shape, spellings::shape::RADIUS)?;
    Ok((center, radius))
}

/// The corners of a shape of this `type` if it is a triangle or a quad: the shapes, with
/// spheres, that can be an area light's surface.
pub(super) fn flat_corners(kind: &str) -> Option<usize> {
    match type_of(SHAPE_TYPES, kind) {
        Some("triangle") => Some(3),
        Some("quad") => Some(4),
        _ => None,
    }
}

/// A shape's `type`, lower case (empty when it has none or it is not a string).
fn shape_kind(s: &Node) -> String {
    s.get_any(spellings::shape::TYPE)
        .and_then(|n| n.str().ok().map(str::to_ascii_lowercase))
        .unwrap_or_default()
}

/// A light waiting for the shape its `shapeid` names.
struct Wanted {
    /// Index of its placeholder in the loader's lights.
    light: usize,
    id: String,
    /// The `shapeid` value.
    at: Location,
    intensity: Intensity,
    samples: u32,
    method: Method,
}

/// A shape with a string `id`.
struct Named {
    id: String,
    /// Its `type`, lower case.
    kind: String,
    at: Location,
    primitives: Range<u32>,
}

/// A shape whose material emits.
struct Glowing {
    kind: String,
    at: Location,
    primitives: Range<u32>,
    /// The radiance it emits.
    radiance: Vec3,
}

/// The `shapeid`s of the lights read so far, the ids of the shapes, and the shapes whose
/// material emits.
#[derive(Default)]
pub(super) struct ShapeLights {
    wanted: Vec<Wanted>,
    shapes: Vec<Named>,
    glowing: Vec<Glowing>,
}

impl ShapeLights {
    /// Notes that the light at index `light` (a placeholder for now) is the shape named by the
    /// string `shapeid`.
    pub(super) fn want(
        &mut self,
        light: usize,
        shapeid: &Node,
        intensity: Intensity,
        samples: u32,
        method: Method,
    ) -> Result<(), SceneError> {
        self.wanted.push(Wanted {
            light,
            id: shapeid.str()?.to_string(),
            at: shapeid.location(),
            intensity,
            samples,
            method,
        });
        Ok(())
    }

    /// Records the shape `s`, whose primitives are `primitives`, if it has a string `id`.
    pub(super) fn note_shape(&mut self, s: &Node, primitives: Range<usize>) {
        let Some(id) = s
            .get_any(spellings::shape::ID)
            .and_then(|n| n.str().ok().map(str::to_string))
        else {
            return;
        };
        let kind = shape_kind(s);
        self.shapes.push(Named {
            id,
            kind,
            at: s.location(),
            primitives: primitives.start as u32..primitives.end as u32,
        });
    }

    /// Records that the shape `s`, whose primitives are `primitives`, has a material emitting
    /// `radiance`: an area light once resolved.
    pub(super) fn note_glowing(&mut self, s: &Node, primitives: Range<usize>, radiance: Vec3) {
        let kind = shape_kind(s);
        self.glowing.push(Glowing {
            kind,
            at: s.location(),
            primitives: primitives.start as u32..primitives.end as u32,
            radiance,
        });
    }

    /// Replaces every waiting light's placeholder in `lights` by the light its shape makes, and
    /// adds a light for each shape whose material emits. A `shapeid` naming no shape, or a shape
    /// that cannot emit, is an error; one naming a shape that was skipped (unknown `type`) skips
    /// the light, with a warning.
    pub(super) fn resolve(
        self,
        lights: &mut Vec<Light>,
        primitives: &Primitives,
        warnings: &mut Vec<Warning>,
    ) -> Result<(), SceneError> {
        // Each id's first shape and how many shapes have it, in one pass (a scene can name
        // hundreds of thousands of shapes).
        let mut by_id: HashMap<&str, (usize, usize)> = HashMap::new();
        for (i, s) in self.shapes.iter().enumerate() {
            by_id.entry(s.id.as_str()).or_insert((i, 0)).1 += 1;
        }
        let mut skipped = HashSet::new();
        for w in &self.wanted {
            match self.wanted_light(w, &by_id, primitives, warnings)? {
                Some(light) => lights[w.light] = light,
                None => {
                    skipped.insert(w.light);
                }
            }
        }
        for g in &self.glowing {
            match glowing_light(g, primitives) {
                Some(l) => lights.push(l),
                None => warnings.push(Warning {
                    location: g.at.clone(),
                    message: format!(
                        "only a sphere, a triangle or a quad can emit; this '{}' is drawn with \
                         its emission ignored",
                        g.kind
                    ),
                }),
            }
        }
        if !skipped.is_empty() {
            let mut i = 0;
            lights.retain(|_| {
                i += 1;
                !skipped.contains(&(i - 1))
            });
        }
        Ok(())
    }

    /// The light of the shape `w` waits for (found through `by_id`, each id's first shape and
    /// count), or `None` when that shape was skipped.
    fn wanted_light(
        &self,
        w: &Wanted,
        by_id: &HashMap<&str, (usize, usize)>,
        primitives: &Primitives,
        warnings: &mut Vec<Warning>,
    ) -> Result<Option<Light>, SceneError> {
        let Some(&(first, count)) = by_id.get(w.id.as_str()) else {
            return Err(invalid(&w.at, self.no_such_id(&w.id)));
        };
        let shape = &self.shapes[first];
        if count > 1 {
            warnings.push(Warning {
                location: w.at.clone(),
                message: format!(
                    "several shapes have the id '{}'; the first ({}) is the light",
                    w.id, shape.at.path
                ),
            });
        }
        let prims = &primitives.range(shape.primitives.clone())[..];
        if prims.is_empty() {
            warnings.push(Warning {
                location: w.at.clone(),
                message: format!(
                    "the shape '{}' ({}) was skipped, so this light is skipped too",
                    w.id, shape.at.path
                ),
            });
            return Ok(None);
        }
        let light = surface_light(
            &shape.kind,
            prims,
            shape.primitives.clone(),
            |_| w.intensity,
            w.samples,
            w.method,
        );
        match light {
            Some(light) => Ok(Some(light)),
            None => Err(not_an_emitter(w, shape, prims)),
        }
    }

    /// The message for a `shapeid` that names no shape: the ids there are.
    fn no_such_id(&self, id: &str) -> String {
        let mut seen = HashSet::new();
        let ids: Vec<&str> = self
            .shapes
            .iter()
            .map(|s| s.id.as_str())
            .filter(|id| seen.insert(*id))
            .collect();
        let listed = if ids.is_empty() {
            "no shape has an 'id'".to_string()
        } else {
            let shown: Vec<String> = ids
                .iter()
                .take(LISTED_IDS)
                .map(|i| format!("'{i}'"))
                .collect();
            let more = ids.len().saturating_sub(LISTED_IDS);
            let tail = if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            };
            format!("the shapes' ids are: {}{tail}", shown.join(", "))
        };
        format!("no shape has the id '{id}' ({listed})")
    }
}

/// The light a shape whose material emits makes, or `None` if its shape cannot be one: intensity
/// `radiance · A / π` for its area `A`, falling off as `1/d²`, which `integrator::emitters` turns
/// back into `radiance` (Whitted shading sees that light and the shape's own emission).
fn glowing_light(g: &Glowing, primitives: &Primitives) -> Option<Light> {
    let prims = &primitives.range(g.primitives.clone())[..];
    surface_light(
        &g.kind,
        prims,
        g.primitives.clone(),
        |area| {
            let i = g.radiance * (area / std::f32::consts::PI);
            Intensity {
                diffuse: i,
                specular: i,
                falloff: crate::light::Falloff::InverseSquare { scale: 1.0 },
            }
        },
        1,
        Method::Sobol,
    )
}

/// The error for a `shapeid` that names `shape`, whose primitives `prims` cannot be a light.
fn not_an_emitter(w: &Wanted, shape: &Named, prims: &[Primitive]) -> SceneError {
    let kind = if matches!(
        prims,
        [Primitive {
            shape: Shape::Plane(_),
            ..
        }]
    ) {
        "an infinite plane, which has no finite area to sample".to_string()
    } else {
        format!("a '{}'", shape.kind)
    };
    invalid(
        &w.at,
        format!(
            "the shape '{}' ({}) is {kind}; only a sphere, a triangle or a quad \
             (a 'plane' with corners) can be an area light",
            w.id, shape.at.path
        ),
    )
}

/// The area light whose surface is the primitives `prims` (numbered `range`) of a shape of type
/// `kind`: a sphere, or the triangles of a flat shape; `None` for any other. `intensity` is given
/// the light's area.
fn surface_light(
    kind: &str,
    prims: &[Primitive],
    range: Range<u32>,
    intensity: impl Fn(f32) -> Intensity,
    samples: u32,
    method: Method,
) -> Option<Light> {
    if type_of(SHAPE_TYPES, kind) == Some("sphere") {
        match prims {
            [Primitive {
                shape: Shape::Sphere(s),
                ..
            }] => Some(Light::Sphere {
                center: s.center,
                radius: s.radius,
                intensity: intensity(4.0 * std::f32::consts::PI * s.radius * s.radius),
                samples,
                method,
                surface: range,
            }),
            _ => None,
        }
    } else if flat_corners(kind).is_some() {
        let triangles: Vec<[Vec3; 3]> = prims
            .iter()
            .map(|p| match &p.shape {
                Shape::Triangle(t) => Some(t.p),
                _ => None,
            })
            .collect::<Option<_>>()?;
        let cumulative_area = cumulative_areas(&triangles);
        let area = cumulative_area.last().copied().unwrap_or(0.0);
        (area > 0.0).then(|| Light::Triangles {
            cumulative_area,
            triangles,
            intensity: intensity(area),
            samples,
            method,
            surface: range,
        })
    } else {
        None
    }
}

/// An error at `at`.
fn invalid(at: &Location, message: String) -> SceneError {
    SceneError::Invalid {
        location: at.clone(),
        message,
    }
}
