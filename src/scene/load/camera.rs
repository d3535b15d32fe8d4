//! The camera: pose, field of view, image size, exposure and lens.

use super::spellings::{camera, scene, type_names, type_of, CAMERA_TYPES};
use super::{is_cgr, nearest, opt_f32, opt_vec3, required, Loader};
use crate::camera::{Camera, Handedness, Lens};
use crate::math::Vec3;
use crate::scene::json::Node;
use crate::scene::SceneError;

impl Loader<'_> {
    /// The camera, its exposure, and (for a thin-lens camera) its count of lens samples per pixel.
    pub(super) fn camera<'a, 't>(
        &mut self,
        root: &Node<'a, 't>,
        cam: &Node<'a, 't>,
    ) -> Result<(Camera, f32, Option<Node<'a, 't>>), SceneError> {
        if !cam.is_object() {
            return Err(cam.error(format!("expected an object, found {}", cam.kind())));
        }
        let thin_lens = self.is_thin_lens(root, cam)?;
        let (width, height) = self.image_size(root, cam)?;
        let fov_y = fov_y(cam, width as f32 / height as f32)?;
        let (position, dir, up, dir_node, looks_at_point) = self.pose(cam)?;
        let exposure = exposure(root, cam)?;

        // Without a focus distance, a lens focuses on the point looked at, if any.
        let target_distance = looks_at_point.then(|| dir.length());
        let lens = self.lens(root, cam, thin_lens, target_distance)?;
        // A camera with a lens is a thin lens whatever its type says.
        let thin_lens = lens.is_some();

        let handedness = if is_cgr(root, cam) {
            Handedness::UpCrossForward
        } else {
            Handedness::ForwardCrossUp
        };
        let camera = Camera::new(position, dir, up, handedness, width, height, fov_y, lens)
            .ok_or_else(|| dir_node.error("the viewing direction is zero"))?;

        // A thin-lens camera's rays per pixel; a pinhole camera's count is ignored, as the files'
        // renderers do (one ray through each pixel).
        let lens_samples = if thin_lens {
            cam.get_any(camera::LENS_SAMPLES)
        } else {
            cam.mark_read(camera::LENS_SAMPLES);
            None
        };
        Ok((camera, exposure, lens_samples))
    }

    /// Whether the camera's `type` (or a top-level `use_dof`) makes it a thin lens; an unknown
    /// type is a pinhole, with a warning.
    fn is_thin_lens(&mut self, root: &Node, cam: &Node) -> Result<bool, SceneError> {
        // A top-level `use_dof` (with `aperture` and `focus_distance` beside it) turns the
        // camera into a thin lens, as the files of one CGR renderer write it.
        let use_dof = match root.get_any(scene::USE_DOF) {
            Some(n) => n.bool()?,
            None => false,
        };
        Ok(match cam.get_any(camera::TYPE) {
            _ if use_dof => true,
            None => false,
            Some(t) => match type_of(CAMERA_TYPES, t.str()?) {
                Some("pinhole") => false,
                Some(_) => true,
                None => {
                    self.warn(
                        &t,
                        format!(
                            "unknown camera type '{}' (nearest known: '{}'); using a pinhole \
                             camera, with a lens if it gives an aperture",
                            t.str()?,
                            nearest(t.str()?, &type_names(CAMERA_TYPES))
                        ),
                    );
                    false
                }
            },
        })
    }

    /// The image's width and height: the file's (from the camera or a `settings` object),
    /// overridden by the options, checked against the pixel limit.
    fn image_size(&self, root: &Node, cam: &Node) -> Result<(u32, u32), SceneError> {
        let settings = root.get_any(scene::SETTINGS).filter(|n| n.is_object());
        let size_holder = match &settings {
            Some(st) if !cam.has_any(camera::WIDTH) && st.has_any(camera::WIDTH) => st.clone(),
            _ => cam.clone(),
        };
        let width_node = required(&size_holder, camera::WIDTH)?;
        let height_node = required(&size_holder, camera::HEIGHT)?;
        let (w0, h0) = (width_node.u32()?, height_node.u32()?);
        if w0 == 0 || h0 == 0 {
            let n = if w0 == 0 { &width_node } else { &height_node };
            return Err(n.error("the image size must be at least 1×1"));
        }
        let (width, height) = match (self.options.width, self.options.height) {
            (Some(w), Some(h)) => (w, h),
            (Some(w), None) => (
                w,
                ((w as f64 * h0 as f64 / w0 as f64).round() as u32).max(1),
            ),
            (None, Some(h)) => (
                ((h as f64 * w0 as f64 / h0 as f64).round() as u32).max(1),
                h,
            ),
            (None, None) => (w0, h0),
        };
        if width == 0 || height == 0 {
            return Err(width_node.error("the image size must be at least 1×1"));
        }
        if width as u64 * height as u64 > self.options.max_pixels {
            return Err(width_node.error(format!(
                "an image of {width}×{height} is over the limit of {} pixels (raise it with --max-pixels)",
                self.options.max_pixels
            )));
        }
        Ok((width, height))
    }

    /// The camera's position, viewing direction, up hint, the node that gave the direction, and
    /// whether the direction leads to a point the file names: from a camera-to-world matrix, or
    /// a position with a point looked at (or the 2021–23 skeleton's direction) and an up vector.
    #[allow(clippy::type_complexity)]
    fn pose<'a, 't>(
        &mut self,
        cam: &Node<'a, 't>,
    ) -> Result<(Vec3, Vec3, Vec3, Node<'a, 't>, bool), SceneError> {
        if let Some(m) = cam.get_any(camera::MATRIX) {
            let (position, dir, up) = camera_to_world(&m)?;
            return Ok((position, dir, up, m, false));
        }
        let position = opt_vec3(cam, camera::POSITION)?;
        let look = cam.get_any(camera::LOOK);
        let is_direction = |n: &Node| n.key() == Some(camera::DIRECTION);
        let looks_at_point = look.as_ref().is_some_and(|n| !is_direction(n));
        let direction = if let Some(n) = look.clone().filter(is_direction) {
            // The 2021–23 skeleton's `lookat`, spelled just so, is a direction, not a point;
            // every other spelling (CGR's `lookAt`) is the point looked at. Some files write a
            // target point in `lookat`; a zero direction can only mean that.
            let d = n.vec3()?;
            if d == Vec3::ZERO && position.is_some_and(|p| p != Vec3::ZERO) {
                self.warn(
                    &n,
                    "'lookat' is a direction, and [0,0,0] is none; read as the point to look at",
                );
                Some((-position.unwrap_or(Vec3::ZERO), n))
            } else {
                Some((d, n))
            }
        } else if let Some(n) = look {
            Some((n.vec3()? - position.unwrap_or(Vec3::ZERO), n))
        } else {
            None
        };
        let up = opt_vec3(cam, camera::UP)?;
        let (position, dir, up, dir_node) = match (position, direction) {
            (None, None) => (Vec3::ZERO, -Vec3::Z, up.unwrap_or(Vec3::Y), cam.clone()),
            (p, Some((d, n))) => (p.unwrap_or(Vec3::ZERO), d, up.unwrap_or(Vec3::Y), n),
            (Some(p), None) => {
                self.warn(
                    cam,
                    "the camera has a position but no viewing direction; looking along −z",
                );
                (p, -Vec3::Z, up.unwrap_or(Vec3::Y), cam.clone())
            }
        };
        // An up hint parallel to the view needs a stand-in.
        let up = if dir.cross(up).length_squared() > 0.0 {
            up
        } else if dir.cross(Vec3::Y).length_squared() > 0.0 {
            self.warn(
                &dir_node,
                "the up vector is parallel to the viewing direction; using +y",
            );
            Vec3::Y
        } else {
            self.warn(
                &dir_node,
                "the up vector is parallel to the viewing direction; using +z",
            );
            Vec3::Z
        };
        Ok((position, dir, up, dir_node, looks_at_point))
    }

    /// The camera's lens, if it has one: a thin-lens camera's, or any camera's that gives an
    /// aperture (docs/scene-format.md, "Camera"). `target_distance` is the focus distance of a
    /// camera that gives none: the distance to the point it looks at, if it names one.
    fn lens(
        &mut self,
        root: &Node,
        cam: &Node,
        thin_lens: bool,
        target_distance: Option<f32>,
    ) -> Result<Option<Lens>, SceneError> {
        // A real lens: focal length, image distance and f-number.
        if cam.contains_any(camera::FOCAL_LENGTH) && cam.contains_any(camera::IMAGE_DISTANCE) {
            let f = required(cam, camera::FOCAL_LENGTH)?.f32()?;
            let d = required(cam, camera::IMAGE_DISTANCE)?.f32()?;
            let n_node = required(cam, camera::LENS_F_NUMBER)?;
            let n = n_node.f32()?;
            if !(f > 0.0 && d > f && n > 0.0) {
                return Err(cam.error(format!(
                    "a lens needs a focal length > 0, an image distance 'd' beyond it and an \
                     f-number 'aperture' > 0; found {f}, {d} and {n}"
                )));
            }
            cam.mark_read(camera::LENS_DIAMETER);
            cam.mark_read(camera::FOCUS);
            return Ok(Some(Lens {
                radius: f / (2.0 * n),
                focus_distance: f * d / (d - f),
            }));
        }
        // A photographer's lens: focal length in millimetres and an f-number.
        if let Some(n_node) = cam.get_any(camera::F_NUMBER) {
            let n = n_node.f32()?;
            let f = required(cam, camera::FOCAL_LENGTH)?.f32()?;
            if !(f > 0.0 && n > 0.0) {
                return Err(n_node.error(format!(
                    "a lens needs a focal length > 0 (millimetres) and an f-number > 0; found \
                     {f} and {n}"
                )));
            }
            let focus = required(cam, camera::FOCUS_DISTANCE)?;
            let focus_distance = focus.f32()?;
            if focus_distance <= 0.0 {
                return Err(focus.error(format!(
                    "the focus distance must be > 0, found {focus_distance}"
                )));
            }
            return Ok(Some(Lens {
                radius: 0.001 * f / (2.0 * n),
                focus_distance,
            }));
        }
        let radius = if let Some(r) = opt_f32(cam, camera::LENS_RADIUS)? {
            Some(r)
        } else if let Some(d) = opt_f32(cam, camera::LENS_DIAMETER)? {
            Some(0.5 * d)
        } else if thin_lens {
            opt_f32(root, scene::LENS_DIAMETER)?.map(|d| 0.5 * d)
        } else {
            root.mark_read(scene::LENS_DIAMETER);
            None
        };
        let focus = match opt_f32(cam, camera::FOCUS)? {
            Some(f) => Some(f),
            None if thin_lens => opt_f32(root, scene::FOCUS)?,
            None => {
                root.mark_read(scene::FOCUS);
                None
            }
        };
        match radius {
            Some(r) if r < 0.0 => Err(cam.error(format!("the aperture must be ≥ 0, found {r}"))),
            Some(r) if r > 0.0 => {
                let Some(focus) = focus.or(target_distance) else {
                    return Err(cam.error(
                        "a camera with an aperture needs a focus distance ('focusdistance' or a \
                         spelling listed in docs/scene-format.md)",
                    ));
                };
                if focus <= 0.0 {
                    return Err(cam.error(format!("the focus distance must be > 0, found {focus}")));
                }
                Ok(Some(Lens {
                    radius: r,
                    focus_distance: focus,
                }))
            }
            Some(_) => Ok(None),
            None if thin_lens => {
                self.warn(
                    cam,
                    "a thin-lens camera without an aperture; rendering as a pinhole",
                );
                Ok(None)
            }
            None => Ok(None),
        }
    }
}

/// Position, viewing direction and up of a camera given by its 4 × 4 camera-to-world matrix,
/// written row by row with the translation in the last column, looking down its −z axis with
/// +y up (the convention of the files that give one).
fn camera_to_world(m: &Node) -> Result<(Vec3, Vec3, Vec3), SceneError> {
    let v = m.numbers()?;
    if v.len() != 16 {
        return Err(m.error(format!(
            "a camera-to-world matrix has 16 numbers, found {}",
            v.len()
        )));
    }
    let at = |r: usize, c: usize| v[4 * r + c] as f32;
    let column = |c: usize| Vec3::new(at(0, c), at(1, c), at(2, c));
    let (up, back, position) = (column(1), column(2), column(3));
    if up.cross(back).length_squared() == 0.0 {
        return Err(m.error(
            "the camera-to-world matrix has no orientation (its axes are parallel or zero)",
        ));
    }
    Ok((position, -back, up))
}

/// The vertical field of view in degrees: `fov`, or `hfov` converted for the image's `aspect`
/// ratio (width / height).
fn fov_y(cam: &Node, aspect: f32) -> Result<f32, SceneError> {
    if let Some(n) = cam.get_any(camera::FOV) {
        let f = n.f32()?;
        if !(f > 0.0 && f < 180.0) {
            return Err(n.error(format!("fov must be between 0 and 180 degrees, found {f}")));
        }
        Ok(f)
    } else if let Some(n) = cam.get_any(camera::HFOV) {
        let f = n.f32()?;
        if !(f > 0.0 && f < 180.0) {
            return Err(n.error(format!("hfov must be between 0 and 180 degrees, found {f}")));
        }
        Ok(2.0 * ((0.5 * f.to_radians()).tan() / aspect).atan().to_degrees())
    } else {
        Err(required(cam, camera::ANY_FOV)
            .err()
            .unwrap_or_else(|| cam.error("missing fov")))
    }
}

/// The camera's `exposure` (or a top-level one), 1 when neither gives it.
fn exposure(root: &Node, cam: &Node) -> Result<f32, SceneError> {
    match cam
        .get_any(camera::EXPOSURE)
        .or_else(|| root.get_any(camera::EXPOSURE))
    {
        Some(n) => {
            let e = n.f32()?;
            if e < 0.0 {
                return Err(n.error(format!("exposure must be ≥ 0, found {e}")));
            }
            Ok(e)
        }
        None => Ok(1.0),
    }
}
