//! The camera: pose, field of view, image size, exposure and lens.

use super::{is_cgr, opt_f32, opt_vec3, required, Loader};
use crate::camera::{Camera, Handedness, Lens};
use crate::math::Vec3;
use crate::scene::json::Node;
use crate::scene::SceneError;

/// A thin-lens camera's lens radius.
const LENS_RADIUS_KEYS: &[&str] = &["lensRadius", "lensradius", "lens_radius", "radius"];
/// A thin-lens camera's lens diameter.
/// `size` is the side of the square aperture of one renderer (TsFreddie's jittered lens sampler
/// spreads samples over `[−size/2, size/2]²`), read as the diameter of our round one.
const LENS_DIAMETER_KEYS: &[&str] = &["aperture", "aperture_size", "diameter", "ap", "d", "size"];
/// The lens diameter at the top level.
const ROOT_DIAMETER_KEYS: &[&str] = &["aperture"];
/// A thin-lens camera's focus distance.
const FOCUS_KEYS: &[&str] = &[
    "focusdistance",
    "focus_distance",
    "focalDistance",
    "focusDistance",
    "focus_dist",
    "focalLength",
    "focal_length",
    "focal",
    "focus",
    "f",
];
/// The focus distance at the top level.
const ROOT_FOCUS_KEYS: &[&str] = &["focus_distance", "focusdistance"];
/// A thin-lens camera's rays per pixel (the total).
const LENS_SAMPLE_KEYS: &[&str] = &["samplesize", "nsamples"];

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
        let kind = match cam.get("type") {
            Some(t) => t.str()?.to_ascii_lowercase(),
            None => "pinhole".into(),
        };
        // A top-level `use_dof` (with `aperture` and `focus_distance` beside it) turns the
        // camera into a thin lens, as the files of one CGR renderer write it.
        let use_dof = match root.get("use_dof") {
            Some(n) => n.bool()?,
            None => false,
        };
        let thin_lens = match kind.as_str() {
            _ if use_dof => true,
            "pinhole" | "perspective" => false,
            "thinlens" | "thinlen" | "thin_lens" | "lens" | "aperture" | "dof" => true,
            other => {
                let t = cam.get("type").unwrap_or_else(|| cam.clone());
                self.warn(
                    &t,
                    format!("unknown camera type '{other}'; using a pinhole camera"),
                );
                false
            }
        };
        let settings = root.get("settings").filter(|n| n.is_object());
        let size_holder = match &settings {
            Some(st) if !cam.has_any(&["width"]) && st.has_any(&["width"]) => st.clone(),
            _ => cam.clone(),
        };
        let width_node = required(&size_holder, &["width"])?;
        let height_node = required(&size_holder, &["height"])?;
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
        let aspect = width as f32 / height as f32;
        let fov_y = if let Some(n) = cam.get("fov") {
            let f = n.f32()?;
            if !(f > 0.0 && f < 180.0) {
                return Err(n.error(format!("fov must be between 0 and 180 degrees, found {f}")));
            }
            f
        } else if let Some(n) = cam.get("hfov") {
            let f = n.f32()?;
            if !(f > 0.0 && f < 180.0) {
                return Err(n.error(format!("hfov must be between 0 and 180 degrees, found {f}")));
            }
            2.0 * ((0.5 * f.to_radians()).tan() / aspect).atan().to_degrees()
        } else {
            return Err(required(cam, &["fov", "hfov"])
                .err()
                .unwrap_or_else(|| cam.error("missing fov")));
        };

        let position_keys = [
            "position", "location", "origin", "lookfrom", "camPos", "eye",
        ];
        let position = opt_vec3(cam, &position_keys)?;
        let look = cam.get_any(&["lookat", "look_at", "look", "camView", "target"]);
        let direction = if let Some(n) = look.clone().filter(|n| n.key() == Some("lookat")) {
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
        let up = opt_vec3(cam, &["up", "upVector", "vup", "camAxis"])?;
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

        let exposure = match cam.get("exposure").or_else(|| root.get("exposure")) {
            Some(n) => {
                let e = n.f32()?;
                if e < 0.0 {
                    return Err(n.error(format!("exposure must be ≥ 0, found {e}")));
                }
                e
            }
            None => 1.0,
        };

        let lens = if thin_lens {
            let radius = if let Some(r) = opt_f32(cam, LENS_RADIUS_KEYS)? {
                Some(r)
            } else if let Some(d) = opt_f32(cam, LENS_DIAMETER_KEYS)? {
                Some(0.5 * d)
            } else {
                opt_f32(root, ROOT_DIAMETER_KEYS)?.map(|d| 0.5 * d)
            };
            let focus = match opt_f32(cam, FOCUS_KEYS)? {
                Some(f) => Some(f),
                None => opt_f32(root, ROOT_FOCUS_KEYS)?,
            };
            match radius {
                Some(r) if r < 0.0 => {
                    return Err(cam.error(format!("the aperture must be ≥ 0, found {r}")))
                }
                Some(r) if r > 0.0 => {
                    let focus = match (focus, cam.peek("lookat").filter(|n| n.key() != Some("lookat")).or_else(|| cam.peek("target"))) {
                        (Some(f), _) => f,
                        // Without a focus distance, focus on the point looked at.
                        (None, Some(_)) => dir.length(),
                        (None, None) => {
                            return Err(cam.error(
                                "a thin-lens camera needs a focus distance ('focusdistance' or a spelling listed in docs/scene-format.md)",
                            ))
                        }
                    };
                    if focus <= 0.0 {
                        return Err(
                            cam.error(format!("the focus distance must be > 0, found {focus}"))
                        );
                    }
                    Some(Lens {
                        radius: r,
                        focus_distance: focus,
                    })
                }
                Some(_) => None,
                None => {
                    self.warn(
                        cam,
                        "a thin-lens camera without an aperture; rendering as a pinhole",
                    );
                    None
                }
            }
        } else {
            // A pinhole camera has no lens: its lens keys are known but have nothing to set.
            for keys in [LENS_RADIUS_KEYS, LENS_DIAMETER_KEYS, FOCUS_KEYS] {
                cam.mark_read(keys);
            }
            root.mark_read(ROOT_DIAMETER_KEYS);
            root.mark_read(ROOT_FOCUS_KEYS);
            None
        };

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
            cam.get_any(LENS_SAMPLE_KEYS)
        } else {
            cam.mark_read(LENS_SAMPLE_KEYS);
            None
        };
        Ok((camera, exposure, lens_samples))
    }
}
