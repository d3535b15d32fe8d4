//! Placing shapes: the scale, rotation and translation keys of meshes and boxes, read into one
//! affine map `x ↦ L·x + t`.
//!
//! ```json
//! { "type": "ply", "path": "teddy.ply", "scale": [0.01, 0.01, 0.01],
//!   "euler": [13, 137, 6], "offset": [0.5, 0.1, 1.0] }
//! { "type": "trimesh", "modelpath": "dragon.ply", "scale": 15, "pos": [0, 2.7, -0.5],
//!   "r1": [1, 0, 0], "r2": [0, 0, 1], "r3": [0, -1, 0] }
//! { "type": "box", "center": [1.5, 0.5, -1.5], "rot": [0, 45, 0], "width": 1, "height": 1, "depth": 1 }
//! ```
//!
//! Euler angles (`euler`, `rotation`, `rot`) are degrees about the world axes, applied x first,
//! then y, then z: `R = Rz(γ)·Ry(β)·Rx(α)`, each a right-handed rotation (counter-clockwise
//! looking down the axis towards the origin). Every reader in the coursework corpus that has
//! these keys uses exactly this convention. `r1`, `r2`, `r3` are the images of the x, y and z
//! axes (`x·r1 + y·r2 + z·r3`, a row vector times the matrix with rows r1..r3, as the file's own
//! reader multiplies).
//!
//! Meshes are scaled, then rotated, then translated. Normals go through the inverse transpose
//! of the linear part.

use super::error::SceneError;
use super::json::Node;
use super::load::spellings::shape;
use glam::Mat3;

use crate::math::Vec3;

/// An affine map `x ↦ linear·x + translation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    pub linear: Mat3,
    pub translation: Vec3,
}

impl Affine {
    pub const IDENTITY: Affine = Affine {
        linear: Mat3::IDENTITY,
        translation: Vec3::ZERO,
    };

    pub fn point(&self, p: Vec3) -> Vec3 {
        self.linear * p + self.translation
    }

    /// The map for normals: the inverse transpose of the linear part, or `None` when it is
    /// singular (a zero scale flattens the shape; its normals are then those of its faces).
    pub fn normal_map(&self) -> Option<Mat3> {
        let det = self.linear.determinant();
        (det != 0.0 && det.is_finite()).then(|| self.linear.inverse().transpose())
    }

    pub fn is_identity(&self) -> bool {
        *self == Affine::IDENTITY
    }
}

/// `(sin, cos)` of an angle in degrees, exact at multiples of 90° (so that a quarter turn maps
/// axis-aligned geometry onto axis-aligned geometry, bit for bit).
pub fn sin_cos_degrees(deg: f32) -> (f32, f32) {
    // `rem_euclid` can round a tiny negative angle up to exactly 360: fold that back to 0.
    let turn = deg.rem_euclid(360.0);
    if turn.fract() == 0.0 && (turn as u32).is_multiple_of(90) {
        return match turn as u32 % 360 {
            0 => (0.0, 1.0),
            90 => (1.0, 0.0),
            180 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        };
    }
    (
        f64::from(deg).to_radians().sin() as f32,
        f64::from(deg).to_radians().cos() as f32,
    )
}

/// The rotation of Euler angles `[α, β, γ]` in degrees: `Rz(γ)·Ry(β)·Rx(α)`.
pub fn euler_degrees(angles: Vec3) -> Mat3 {
    let (sx, cx) = sin_cos_degrees(angles.x);
    let (sy, cy) = sin_cos_degrees(angles.y);
    let (sz, cz) = sin_cos_degrees(angles.z);
    // Columns of each right-handed axis rotation.
    let rx = Mat3::from_cols(Vec3::X, Vec3::new(0.0, cx, sx), Vec3::new(0.0, -sx, cx));
    let ry = Mat3::from_cols(Vec3::new(cy, 0.0, -sy), Vec3::Y, Vec3::new(sy, 0.0, cy));
    let rz = Mat3::from_cols(Vec3::new(cz, sz, 0.0), Vec3::new(-sz, cz, 0.0), Vec3::Z);
    rz * ry * rx
}

/// The rotation a shape gives with Euler angles ([`shape::EULER`]), or rows `r1`, `r2`, `r3`;
/// `None` if it gives none.
pub fn rotation(s: &Node) -> Result<Option<Mat3>, SceneError> {
    if let Some(n) = s.get_any(shape::EULER) {
        return Ok(Some(euler_degrees(n.vec3()?)));
    }
    let [r1, r2, r3] = shape::ROTATION_ROWS;
    if let Some(first) = s.get_any(r1) {
        let row = |k: &[&str]| -> Result<Vec3, SceneError> {
            match s.get_any(k) {
                Some(n) => n.vec3(),
                None => Err(s.error(format!("'{}' is given but '{}' is missing", r1[0], k[0]))),
            }
        };
        let rows = [first.vec3()?, row(r2)?, row(r3)?];
        // Row vector times the matrix of rows: the rows are the images of the axes, i.e. the
        // columns of the column-vector matrix.
        let m = Mat3::from_cols(rows[0], rows[1], rows[2]);
        if m.determinant() == 0.0 {
            return Err(first.error("the rows r1, r2, r3 are linearly dependent (determinant 0)"));
        }
        return Ok(Some(m));
    }
    Ok(None)
}

/// A mesh's placement: `scale` (`sizeScale`, `size`; a number or per axis), then the rotation
/// ([`rotation`]), then the translation (`position`, `pos`, `offset`, `translate`,
/// `translation`, `center`).
pub fn mesh_placement(s: &Node) -> Result<Affine, SceneError> {
    let scale = match s.get_any(shape::SCALE) {
        Some(n) => n.color()?,
        None => Vec3::ONE,
    };
    let rot = rotation(s)?.unwrap_or(Mat3::IDENTITY);
    let translation = match s.get_any(shape::TRANSLATION) {
        Some(n) => n.vec3()?,
        None => Vec3::ZERO,
    };
    Ok(Affine {
        linear: rot * Mat3::from_diagonal(scale),
        translation,
    })
}

/// Applies `a` to mesh positions and (if any) vertex normals, in place. Normals are
/// renormalised; under a singular map they are dropped.
pub fn place_mesh(a: &Affine, positions: &mut [Vec3], normals: &mut Option<Vec<Vec3>>) {
    if a.is_identity() {
        return;
    }
    positions.iter_mut().for_each(|p| *p = a.point(*p));
    match a.normal_map() {
        Some(m) => {
            if let Some(ns) = normals.as_mut() {
                ns.iter_mut()
                    .for_each(|n| *n = (m * *n).normalize_or_zero());
            }
        }
        None => *normals = None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-6
    }

    #[test]
    fn a_tiny_negative_angle_is_no_turn_at_all() {
        // −1e-6 rem_euclid 360 rounds to exactly 360 in f32.
        assert_eq!((-1e-6f32).rem_euclid(360.0), 360.0);
        let (sin, cos) = sin_cos_degrees(-1e-6);
        assert!(sin.abs() < 1e-6 && cos == 1.0, "{sin} {cos}");
    }

    #[test]
    fn quarter_turns_are_exact_and_right_handed() {
        // About y by +90°: z goes to x, x goes to −z.
        let r = euler_degrees(Vec3::new(0.0, 90.0, 0.0));
        assert_eq!(r * Vec3::Z, Vec3::X);
        assert_eq!(r * Vec3::X, -Vec3::Z);
        // About z by −90°: y goes to x (the wall of the box-and-planes example).
        let r = euler_degrees(Vec3::new(0.0, 0.0, -90.0));
        assert_eq!(r * Vec3::Y, Vec3::X);
        // About x by 90°: y goes to z.
        assert_eq!(euler_degrees(Vec3::new(90.0, 0.0, 0.0)) * Vec3::Y, Vec3::Z);
        assert_eq!(sin_cos_degrees(-270.0), (1.0, 0.0));
    }

    #[test]
    fn x_turns_first_then_y_then_z() {
        // x by 90° takes y to z; y by 90° then takes z to x; z by 90° takes x to y.
        let r = euler_degrees(Vec3::new(90.0, 90.0, 90.0));
        assert_eq!(r * Vec3::Y, Vec3::Y);
        // The other order (z first) would give a different image of y.
        let zyx = euler_degrees(Vec3::new(90.0, 0.0, 0.0))
            * euler_degrees(Vec3::new(0.0, 90.0, 0.0))
            * euler_degrees(Vec3::new(0.0, 0.0, 90.0));
        assert_ne!(zyx * Vec3::Y, Vec3::Y);
        // A general angle: the composition of single-axis rotations.
        let a = Vec3::new(13.0, 137.0, 6.0);
        let m = euler_degrees(Vec3::new(0.0, 0.0, a.z))
            * euler_degrees(Vec3::new(0.0, a.y, 0.0))
            * euler_degrees(Vec3::new(a.x, 0.0, 0.0));
        let p = Vec3::new(0.3, -1.2, 2.0);
        assert!(close(euler_degrees(a) * p, m * p));
        assert!((euler_degrees(a).determinant() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn scale_rotate_translate_and_normals_by_the_inverse_transpose() {
        let a = Affine {
            linear: euler_degrees(Vec3::new(0.0, 0.0, 90.0))
                * Mat3::from_diagonal(Vec3::new(2.0, 1.0, 1.0)),
            translation: Vec3::new(0.0, 0.0, 5.0),
        };
        // x is scaled by 2, then turned onto y, then lifted by 5.
        assert!(close(a.point(Vec3::X), Vec3::new(0.0, 2.0, 5.0)));
        // The plane x + y = 0 (normal (1, 1, 0)/√2, containing (1, −1, 0)) maps to a plane whose
        // normal is the inverse transpose image of the old one, not its plain image.
        let mut positions = vec![Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)];
        let mut normals = Some(vec![Vec3::new(1.0, 1.0, 0.0).normalize(); 2]);
        place_mesh(&a, &mut positions, &mut normals);
        let n = normals.unwrap()[0];
        let along = positions[0] - a.translation; // a direction in the image plane
        assert!(
            n.dot(along).abs() < 1e-6,
            "{n} is not perpendicular to {along}"
        );
        assert!((n.length() - 1.0).abs() < 1e-6);
        // A zero scale drops the normals.
        let flat = Affine {
            linear: Mat3::from_diagonal(Vec3::new(1.0, 0.0, 1.0)),
            translation: Vec3::ZERO,
        };
        let mut normals = Some(vec![Vec3::Y]);
        place_mesh(&flat, &mut positions, &mut normals);
        assert!(normals.is_none());
    }
}
