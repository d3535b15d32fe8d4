//! Axis-aligned rectangles given by their ranges on two axes and the constant third coordinate:
//!
//! ```json
//! { "type": "rectangleXY", "x0": -0.7, "x1": -0.4, "y0": -0.6, "y1": -0.2, "z": -0.4 }
//! { "type": "rectangleXZ", "x0": 0, "x1": 5, "z0": 0, "z1": 5, "y": 0 }
//! { "type": "rectangleYZ", "y0": 0, "y1": 5, "z0": 0, "z1": 5, "x": 0 }
//! ```
//! The constant coordinate may also be spelled `k`. The ends of a range may come in either
//! order, but must differ.
//!
//! Texture coordinates put the image upright seen from the positive side of the constant axis:
//! `rectangleXY` has `u` along +x and `v` along −y (image row 0 at the top edge, y1), seen from +z
//! with +y up; `rectangleXZ` has `u` along +x and `v` along +z (the frame of an infinite floor,
//! see [`crate::geometry::plane`]); `rectangleYZ` has `u` along −z and `v` along −y, seen from +x
//! with +y up.

use super::error::SceneError;
use super::json::Node;
use super::load::spellings::shape;
use crate::math::{Vec2, Vec3};

/// The shape types of this module (lower case, as the loader compares them).
pub const TYPES: [&str; 3] = ["rectanglexy", "rectanglexz", "rectangleyz"];

/// A rectangle's four corners in cycle order and their texture coordinates.
pub struct Rectangle {
    pub corners: [Vec3; 4],
    pub uvs: [Vec2; 4],
}

/// Reads the rectangle of type `kind` (one of [`TYPES`]).
pub fn read(s: &Node, kind: &str) -> Result<Rectangle, SceneError> {
    // (first axis, second axis, constant axis) and the names of the keys.
    let (a, b, c) = match kind {
        "rectanglexy" => (0, 1, 2),
        "rectanglexz" => (0, 2, 1),
        _ => (1, 2, 0),
    };
    let names = shape::RECTANGLE_AXES;
    let range = |axis: usize| -> Result<(f32, f32), SceneError> {
        let lo_key = format!("{}0", names[axis]);
        let hi_key = format!("{}1", names[axis]);
        let lo = required(s, &lo_key)?.f32()?;
        let hi_node = required(s, &hi_key)?;
        let hi = hi_node.f32()?;
        if lo == hi {
            return Err(hi_node.error(format!(
                "{lo_key} and {hi_key} are both {lo}: the rectangle has no area"
            )));
        }
        Ok((lo.min(hi), lo.max(hi)))
    };
    let (a0, a1) = range(a)?;
    let (b0, b1) = range(b)?;
    let k = match s.get_any(&[names[c], shape::RECTANGLE_LEVEL[0]]) {
        Some(n) => n.f32()?,
        None => {
            return Err(s.error(format!(
                "missing required key '{}' (or k): the rectangle's {} coordinate",
                names[c], names[c]
            )))
        }
    };
    let point = |u: f32, v: f32| {
        let mut p = Vec3::ZERO;
        p[a] = u;
        p[b] = v;
        p[c] = k;
        p
    };
    let corners = [point(a0, b0), point(a1, b0), point(a1, b1), point(a0, b1)];
    // uv of the corners (a0,b0), (a1,b0), (a1,b1), (a0,b1) for the frames described above.
    let uvs = match kind {
        // u = (x − x0)/(x1 − x0), v = (y1 − y)/(y1 − y0).
        "rectanglexy" => [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)],
        // u = (x − x0)/(x1 − x0), v = (z − z0)/(z1 − z0).
        "rectanglexz" => [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)],
        // a = y, b = z: u = (z1 − z)/(z1 − z0), v = (y1 − y)/(y1 − y0).
        _ => [(1.0, 1.0), (1.0, 0.0), (0.0, 0.0), (0.0, 1.0)],
    };
    Ok(Rectangle {
        corners,
        uvs: uvs.map(|(u, v)| Vec2::new(u, v)),
    })
}

/// The member `key` of `s`, which must be present.
fn required<'a, 't>(s: &Node<'a, 't>, key: &str) -> Result<Node<'a, 't>, SceneError> {
    s.get(key)
        .ok_or_else(|| s.error(format!("missing required key '{key}'")))
}
