//! Cameras: pinhole and thin lens.
//!
//! ```json
//! "camera": { "type": "pinhole", "width": 800, "height": 800, "fov": 35,
//!             "position": [0, -3.5, 2], "lookat": [0, 1, -0.1], "up": [0, 0, 0.5] }
//! "camera": { "type": "thinlens", …, "aperture": 0.1, "focusdistance": 5.0 }
//! ```
//! The loader turns every variant's keys into an eye point, a unit viewing direction and an up
//! hint; this module only builds rays. `fov` is the full **vertical** angle in degrees (see
//! `docs/scene-format.md`); pixel `(0, 0)` is the top-left; right = forward × up.

use crate::math::{Vec2, Vec3};
use crate::ray::Ray;
use crate::sampling::concentric_disk;

/// Which way the image's x axis points. The 2019 and 2021–23 variants use `forward × up` (the
/// official reference render shows the wall at x = −2 on the left); CGR files use `up × forward`
/// (renders of the CGR test scenes are mirrored otherwise).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Handedness {
    /// right = forward × up.
    #[default]
    ForwardCrossUp,
    /// right = up × forward.
    UpCrossForward,
}

/// The depth-of-field part of a thin-lens camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lens {
    /// Radius of the aperture, in scene units.
    pub radius: f32,
    /// Distance from the eye, along the viewing direction, of the plane in sharp focus.
    pub focus_distance: f32,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    /// Unit vector to the right of the image.
    pub right: Vec3,
    /// Unit vector to the top of the image.
    pub up: Vec3,
    pub width: u32,
    pub height: u32,
    /// Full vertical field of view, radians.
    fov_y: f32,
    /// `tan(fov_y / 2)`: half the image plane's height at unit distance.
    tan_half_fov: f32,
    /// `None` for a pinhole.
    pub lens: Option<Lens>,
}

impl Camera {
    /// A camera at `position` looking along `direction` with the up hint `up` (any length, not
    /// necessarily orthogonal to `direction`). `None` when `direction` is zero or parallel to `up`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        position: Vec3,
        direction: Vec3,
        up: Vec3,
        handedness: Handedness,
        width: u32,
        height: u32,
        fov_y_degrees: f32,
        lens: Option<Lens>,
    ) -> Option<Camera> {
        let forward = direction.try_normalize()?;
        let right = forward.cross(up).try_normalize()?;
        let up = right.cross(forward);
        let right = match handedness {
            Handedness::ForwardCrossUp => right,
            Handedness::UpCrossForward => -right,
        };
        Some(Camera {
            position,
            forward,
            right,
            up,
            width,
            height,
            fov_y: fov_y_degrees.to_radians(),
            tan_half_fov: (0.5 * fov_y_degrees.to_radians()).tan(),
            lens,
        })
    }

    /// Full vertical field of view, radians.
    pub fn fov_y(&self) -> f32 {
        self.fov_y
    }

    /// The primary ray through image point `(x + film.x, y + film.y)` in pixel units (so
    /// `film = (0.5, 0.5)` is the centre of pixel `(x, y)`), with `lens_u ∈ [0,1)²` choosing the
    /// point on the aperture for a thin lens. Directions are unit length.
    pub fn generate_ray(&self, x: u32, y: u32, film: Vec2, lens_u: Vec2) -> Ray {
        let tan = self.tan_half_fov;
        let aspect = self.width as f32 / self.height as f32;
        let sx = (2.0 * (x as f32 + film.x) / self.width as f32 - 1.0) * tan * aspect;
        let sy = (1.0 - 2.0 * (y as f32 + film.y) / self.height as f32) * tan;
        let dir = (self.forward + sx * self.right + sy * self.up).normalize();
        match self.lens {
            None => Ray::new(self.position, dir),
            Some(lens) => {
                // The pinhole ray meets the focal plane (perpendicular to `forward`) at `focus`;
                // every lens ray through that point is in focus there.
                let focus = self.position + dir * (lens.focus_distance / dir.dot(self.forward));
                let d = concentric_disk(lens_u) * lens.radius;
                let origin = self.position + d.x * self.right + d.y * self.up;
                Ray::new(origin, (focus - origin).normalize())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(lens: Option<Lens>) -> Camera {
        Camera::new(
            Vec3::ZERO,
            Vec3::Y,
            Vec3::Z,
            Handedness::default(),
            200,
            100,
            90.0,
            lens,
        )
        .unwrap()
    }

    #[test]
    fn basis_follows_forward_cross_up() {
        let c = cam(None);
        assert_eq!(c.right, Vec3::X);
        assert_eq!(c.up, Vec3::Z);
        let mirrored = Camera::new(
            Vec3::ZERO,
            Vec3::Y,
            Vec3::Z,
            Handedness::UpCrossForward,
            8,
            8,
            35.0,
            None,
        )
        .unwrap();
        assert_eq!(mirrored.right, -Vec3::X);
        assert_eq!(mirrored.up, Vec3::Z);
        // An up hint that is not unit length nor orthogonal is orthonormalised.
        let c = Camera::new(
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, -0.1),
            Vec3::new(0.0, 0.0, 0.5),
            Handedness::default(),
            8,
            8,
            35.0,
            None,
        )
        .unwrap();
        assert!(c.up.dot(c.forward).abs() < 1e-6 && (c.up.length() - 1.0).abs() < 1e-6);
        assert!(Camera::new(
            Vec3::ZERO,
            Vec3::Z,
            Vec3::Z,
            Handedness::default(),
            8,
            8,
            35.0,
            None
        )
        .is_none());
        assert!(Camera::new(
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::Z,
            Handedness::default(),
            8,
            8,
            35.0,
            None
        )
        .is_none());
    }

    #[test]
    fn corner_rays_span_the_vertical_fov() {
        let c = cam(None);
        // Top edge, centre column: 45° up from forward.
        let r = c.generate_ray(100, 0, Vec2::new(0.0, 0.0), Vec2::ZERO);
        assert!((r.dir.z - r.dir.y).abs() < 1e-6 && r.dir.z > 0.0);
        // Left edge, middle row: the horizontal half-angle is atan(aspect · tan 45°) = atan 2.
        let r = c.generate_ray(0, 50, Vec2::new(0.0, 0.0), Vec2::ZERO);
        assert!((r.dir.x / r.dir.y + 2.0).abs() < 1e-5);
    }

    #[test]
    fn thin_lens_rays_converge_on_the_focal_plane() {
        let lens = Lens {
            radius: 0.5,
            focus_distance: 4.0,
        };
        let c = cam(Some(lens));
        let pin = cam(None).generate_ray(30, 70, Vec2::splat(0.5), Vec2::ZERO);
        let focus = pin.at(4.0 / pin.dir.dot(Vec3::Y));
        for u in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.9, 0.5),
            Vec2::new(0.5, 0.99),
        ] {
            let r = c.generate_ray(30, 70, Vec2::splat(0.5), u);
            assert!(r.origin.distance(Vec3::ZERO) <= 0.5 + 1e-6);
            let t = (focus - r.origin).dot(r.dir);
            assert!(r.at(t).distance(focus) < 1e-4);
        }
    }
}
