//! A pinhole camera. Pixel `(px, py)`, `py = 0` the top row, shoots through its centre:
//! with `f = normalize(target - eye)`, `r = normalize(f x up)`, `u = r x f`,
//! `a = width/height`, `h = tan(fov_y/2)`:
//! `direction = f + (2(px+0.5)/width - 1)*h*a*r + (1 - 2(py+0.5)/height)*h*u`.
//!
//! A camera may be a window onto its image ([`Camera::window`]): a tile of a poster, or a band
//! with a margin. Its pixels are then the whole image's pixels in that rectangle, the same rays
//! bit for bit, and sample positions are seeded by their place in the whole image.

use crate::compact::Compact;
use crate::geometry::Ray;
use glam::DVec3;
use thiserror::Error;

/// Why a camera could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CameraError {
    /// The eye, target or up vector (named) has a NaN or infinite component.
    #[error("camera {0} must be finite")]
    NotFinite(&'static str),
    /// A coordinate or distance (named) beyond `MOST_COORDINATE`: no view of a map needs
    /// it, and the camera's vectors would overflow.
    #[error("camera {what} is out of range: {value:e} is beyond ±{MOST_COORDINATE:e}")]
    OutOfRange {
        /// What it is ("eye", "orbit distance", ...).
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// Eye and target are the same point: no viewing direction.
    #[error("camera eye and target coincide")]
    EyeIsTarget,
    /// The up vector is parallel to the viewing direction (or zero).
    #[error(
        "camera up vector is zero or parallel to the viewing direction; give one across it, \
         such as [0, 0, 1] for a camera that does not look straight down"
    )]
    UpParallel,
    /// A vertical field of view outside (0, 180) degrees.
    #[error("field of view must be between 0 and 180 degrees, got {}", Compact(*.0))]
    BadFov(f64),
    /// An image size with no pixels (width, height).
    #[error("image size must be at least 1x1, got {0}x{1}")]
    EmptyImage(u32, u32),
    /// An image size of more than [`MAX_PIXELS`] (width, height).
    #[error(
        "image size {0}x{1} is more than the limit of {MAX_PIXELS} pixels (8192x4096): a \
         frame keeps statistics with every pixel, about 24 bytes each"
    )]
    HugeImage(u32, u32),
}

/// The most pixels an image may have: a frame holds several bytes a pixel, and a size typed
/// with a digit too many must be refused, not abort on an allocation of tens of gigabytes.
pub const MAX_PIXELS: u64 = 1 << 25;

/// The largest coordinate or distance a camera takes: far beyond any map (heights are within
/// the same bound), and small enough that no vector built from it overflows.
pub const MOST_COORDINATE: f64 = 1e15;

/// A validated pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// The window's size in pixels.
    width: u32,
    height: u32,
    /// The window's top-left pixel in the whole image.
    offset: (u32, u32),
    /// The whole image's size, which the rays are spread over.
    whole: (u32, u32),
    /// Which frame of a flythrough this is: sample positions are seeded with it too.
    frame: u64,
    /// How far ahead of the eye the target it was aimed at lies (in its coordinates when made).
    target_distance: f64,
}

/// A rectangle of an image's pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Its left column.
    pub x: u32,
    /// Its top row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Camera {
    /// A camera at `eye` looking at `target`.
    pub fn look_at(
        eye: [f64; 3],
        target: [f64; 3],
        up: [f64; 3],
        fov_y_deg: f64,
        (width, height): (u32, u32),
    ) -> Result<Camera, CameraError> {
        let (eye, target, up) = (DVec3::from(eye), DVec3::from(target), DVec3::from(up));
        for (name, v) in [("eye", eye), ("target", target), ("up", up)] {
            if !v.is_finite() {
                return Err(CameraError::NotFinite(name));
            }
            if let Some(&value) = v.to_array().iter().find(|c| c.abs() > MOST_COORDINATE) {
                return Err(CameraError::OutOfRange { what: name, value });
            }
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
            return Err(CameraError::BadFov(fov_y_deg));
        }
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage(width, height));
        }
        if u64::from(width) * u64::from(height) > MAX_PIXELS {
            return Err(CameraError::HugeImage(width, height));
        }
        let forward = (target - eye)
            .try_normalize()
            .ok_or(CameraError::EyeIsTarget)?;
        let right = forward
            .cross(up)
            .try_normalize()
            .ok_or(CameraError::UpParallel)?;
        let h = (fov_y_deg.to_radians() / 2.0).tan();
        let aspect = f64::from(width) / f64::from(height);
        Ok(Camera {
            eye,
            forward,
            right: right * h * aspect,
            up: right.cross(forward) * h,
            width,
            height,
            offset: (0, 0),
            whole: (width, height),
            frame: 0,
            target_distance: (target - eye).length(),
        })
    }

    /// A camera orbiting `target`: `yaw` from +x towards +y, `pitch` above the horizon.
    pub fn orbit(
        target: [f64; 3],
        yaw_deg: f64,
        pitch_deg: f64,
        distance: f64,
        fov_y_deg: f64,
        size: (u32, u32),
    ) -> Result<Camera, CameraError> {
        if distance.abs() > MOST_COORDINATE {
            return Err(CameraError::OutOfRange {
                what: "orbit distance",
                value: distance,
            });
        }
        let offset = super::framing::eye_direction(yaw_deg, pitch_deg);
        let eye = DVec3::from(target) + offset * distance;
        Camera::look_at(eye.into(), target, [0.0, 0.0, 1.0], fov_y_deg, size)
    }

    /// The same camera in grid coordinates, for a terrain whose world coordinates are its
    /// grid coordinates scaled per axis by `world_from_grid` (see
    /// [`Terrain::world_from_grid`](crate::Terrain::world_from_grid)): each pixel's ray becomes
    /// the grid ray through the same points at the same `t`.
    pub fn in_grid(self, world_from_grid: Option<[f64; 3]>) -> Camera {
        let Some(scale) = world_from_grid.map(DVec3::from) else {
            return self;
        };
        Camera {
            eye: self.eye / scale,
            forward: self.forward / scale,
            right: self.right / scale,
            up: self.up / scale,
            ..self
        }
    }

    /// Image width and height in pixels (the window's, for a window).
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The whole image's width and height, of which a window shows a part.
    pub fn whole_size(&self) -> (u32, u32) {
        self.whole
    }

    /// The same view showing only `window` of its whole image: pixel `(px, py)` of the result
    /// is pixel `(window.x + px, window.y + py)` of the whole. `None` if the window is empty or
    /// reaches beyond the image.
    pub fn window(self, window: Window) -> Option<Camera> {
        let (w, h) = self.whole;
        let fits = |start: u32, len: u32, whole: u32| {
            len > 0 && start.checked_add(len).is_some_and(|end| end <= whole)
        };
        (fits(window.x, window.width, w) && fits(window.y, window.height, h)).then_some(Camera {
            width: window.width,
            height: window.height,
            offset: (window.x, window.y),
            ..self
        })
    }

    /// The same view as frame `frame` of a flythrough: its sample positions are seeded with
    /// the frame's number as well as the pixel's place (frame 0 is a still's).
    pub fn for_frame(self, frame: u64) -> Camera {
        Camera { frame, ..self }
    }

    /// The frame number sample positions are seeded with (see [`Camera::for_frame`]).
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// Where pixel `(px, py)` of this window lies in the whole image.
    pub fn in_image(&self, px: u32, py: u32) -> (u32, u32) {
        (px + self.offset.0, py + self.offset.1)
    }

    /// The eye, every primary ray's origin.
    pub fn eye(&self) -> [f64; 3] {
        self.eye.into()
    }

    /// The primary ray through the centre of pixel `(px, py)` (of the window).
    pub fn ray(&self, px: u32, py: u32) -> Ray {
        let (x, y) = self.in_image(px, py);
        self.ray_at(f64::from(x) + 0.5, f64::from(y) + 0.5)
    }

    /// The ray through the point `(x, y)` of the whole image, in pixels from its top-left
    /// corner (a pixel's centre is at `+0.5`), for several samples per pixel.
    pub fn ray_at(&self, x: f64, y: f64) -> Ray {
        let sx = 2.0 * x / f64::from(self.whole.0) - 1.0;
        let sy = 1.0 - 2.0 * y / f64::from(self.whole.1);
        let dir = self.forward + sx * self.right + sy * self.up;
        // `forward` is a unit vector orthogonal to `right` and `up`, so `dir` is never zero,
        // and every input was checked finite.
        Ray::new_checked_by_caller(self.eye.into(), dir.into())
    }

    /// The distance from the eye to the target the camera was aimed at.
    pub fn target_distance(&self) -> f64 {
        self.target_distance
    }

    /// The unit direction the camera looks in.
    pub fn forward(&self) -> [f64; 3] {
        self.forward.into()
    }

    /// Where `point` shows in the whole image, in pixels from its top-left corner (the inverse
    /// of [`Camera::ray_at`]); `None` for a point level with the eye or behind it.
    pub fn project(&self, point: [f64; 3]) -> Option<[f64; 2]> {
        let v = DVec3::from(point) - self.eye;
        let depth = v.dot(self.forward);
        if depth.is_nan() || depth <= 0.0 {
            return None;
        }
        let sx = v.dot(self.right) / (self.right.length_squared() * depth);
        let sy = v.dot(self.up) / (self.up.length_squared() * depth);
        let (w, h) = (f64::from(self.whole.0), f64::from(self.whole.1));
        Some([(sx + 1.0) * 0.5 * w, (1.0 - sy) * 0.5 * h])
    }

    /// The viewing direction (unit in the world, not in grid coordinates) and the steps of the
    /// ray direction from one pixel to the next across and up the image: pixel `(x, y)`'s ray
    /// runs along `forward + (x - W/2) * across - (y - H/2) * up` (see [`Camera::ray_at`]).
    pub fn pixel_steps(&self) -> [[f64; 3]; 3] {
        let (w, h) = (f64::from(self.whole.0), f64::from(self.whole.1));
        [
            self.forward.into(),
            (self.right * (2.0 / w)).into(),
            (self.up * (2.0 / h)).into(),
        ]
    }

    /// World length one pixel spans, across the view, at `depth` along the viewing direction.
    pub fn pixel_span_at(&self, depth: f64) -> f64 {
        2.0 * depth * self.up.length() / f64::from(self.whole.1)
    }

    /// Every pixel's primary ray, row by row from the top.
    pub fn rays(&self) -> impl Iterator<Item = Ray> + '_ {
        (0..self.height).flat_map(move |y| (0..self.width).map(move |x| self.ray(x, y)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_looks_at_target_and_corners_follow_the_convention() {
        let cam = Camera::look_at(
            [0.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
            [0.0, 0.0, 1.0],
            90.0,
            (2, 2),
        )
        .unwrap();
        // fov 90: h = 1. Pixel (0,0) is the top-left: x = -0.5, z = +0.5.
        let d = cam.ray(0, 0).dir();
        assert!(
            (d[0] + 0.5).abs() < 1e-12 && (d[1] - 1.0).abs() < 1e-12 && (d[2] - 0.5).abs() < 1e-12
        );
        assert_eq!(
            Camera::look_at([1.0; 3], [1.0; 3], [0.0, 0.0, 1.0], 45.0, (1, 1)),
            Err(CameraError::EyeIsTarget)
        );
    }

    #[test]
    fn coordinates_beyond_any_map_are_out_of_range() {
        let far = Camera::look_at([1e308, 0.0, 0.0], [0.0; 3], [0.0, 0.0, 1.0], 45.0, (4, 4));
        assert_eq!(
            far,
            Err(CameraError::OutOfRange {
                what: "eye",
                value: 1e308
            })
        );
        let orbit = Camera::orbit([0.0; 3], 0.0, 30.0, 1e308, 45.0, (4, 4));
        assert!(
            matches!(
                orbit,
                Err(CameraError::OutOfRange {
                    what: "orbit distance",
                    ..
                })
            ),
            "{orbit:?}"
        );
    }

    #[test]
    fn images_too_large_for_memory_are_refused() {
        let look = |size| Camera::look_at([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 45.0, size);
        assert!(look((8192, 4096)).is_ok());
        assert_eq!(look((8192, 4097)), Err(CameraError::HugeImage(8192, 4097)));
        assert_eq!(
            look((16384, 16384)),
            Err(CameraError::HugeImage(16384, 16384))
        );
        assert_eq!(
            look((100_000, 100_000)),
            Err(CameraError::HugeImage(100_000, 100_000))
        );
        assert_eq!(
            look((u32::MAX, 1)),
            Err(CameraError::HugeImage(u32::MAX, 1))
        );
    }
}
