//! The course's pinhole camera (docs/rendering.md, Camera): at the origin, looking along +z, with a
//! 45 degree horizontal field of view and the image plane at z = 1.

use glam::DVec3;

use crate::course::RowStep;
use crate::geometry::{normalise, Ray};

/// Maps pixel coordinates to primary rays for one image size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub width: u32,
    pub height: u32,
    /// Width of the image plane at distance 1: `2 tan(22.5 deg)`.
    plane_width: f64,
    plane_height: f64,
    /// Width of one pixel on the image plane.
    step: f64,
    /// Height of one pixel on the image plane: `step` (2016-17), or `plane_height / height`
    /// computed on its own (later years), one ulp apart at some sizes.
    row_step: f64,
}

impl Camera {
    /// Horizontal field of view in degrees; kept for every image size.
    pub const FOV_DEGREES: f64 = 45.0;

    /// The 2016-17 camera: square pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Camera::with_rows(width, height, RowStep::Columns)
    }

    /// The camera of a year whose rows step as `rows` says (`Course::row_step`).
    pub fn with_rows(width: u32, height: u32, rows: RowStep) -> Self {
        let plane_width = 2.0 * (Self::FOV_DEGREES / 2.0).to_radians().tan();
        let aspect = f64::from(width) / f64::from(height);
        let plane_height = plane_width / aspect;
        let step = plane_width / f64::from(width);
        Camera {
            width,
            height,
            plane_width,
            plane_height,
            step,
            row_step: match rows {
                RowStep::Columns => step,
                RowStep::PlaneHeight => plane_height / f64::from(height),
            },
        }
    }

    /// The image-plane point the course aims pixel (x, y) at, y = 0 the top row, evaluated in
    /// the course's order so the ray matches the reference to the bit.
    ///
    /// Note the rows: `(step + h)/2 - y*step` is `h/2 - (y - 0.5)*step`, half a pixel *above*
    /// the top edge for row 0, so the whole picture sits one row lower than true pixel centres
    /// would put it. docs/rendering.md calls these "the pixel centres", but the reference image is
    /// only reproduced with the formula as written, so the formula is what we implement.
    pub fn plane_point(&self, x: u32, y: u32) -> (f64, f64) {
        let x_pos = (self.step - self.plane_width) / 2.0 + f64::from(x) * self.step;
        let y_pos = (self.row_step + self.plane_height) / 2.0 - f64::from(y) * self.row_step;
        (x_pos, y_pos)
    }

    /// The course's ray for pixel (x, y): through `plane_point`, direction normalised by
    /// division.
    pub fn pixel_centre_ray(&self, x: u32, y: u32) -> Ray {
        let (x_pos, y_pos) = self.plane_point(x, y);
        Ray::new(DVec3::ZERO, normalise(DVec3::new(x_pos, y_pos, 1.0)))
    }

    /// The ray through offset (u, v) within pixel (x, y), u and v in [0, 1) from the pixel's
    /// top-left corner, for supersampling. It uses the same grid as `pixel_centre_ray` (rows
    /// one pixel lower than true centres), so u = v = 0.5 is the tick ray up to rounding and
    /// supersampled images line up with the tick image.
    pub fn sub_pixel_ray(&self, x: u32, y: u32, u: f64, v: f64) -> Ray {
        let x_pos = -self.plane_width / 2.0 + (f64::from(x) + u) * self.step;
        let y_pos = self.plane_height / 2.0 - (f64::from(y) + v - 1.0) * self.row_step;
        Ray::new(DVec3::ZERO, normalise(DVec3::new(x_pos, y_pos, 1.0)))
    }

    /// OpenEXR's `worldToNDC` for this camera (Imath convention: row vectors, `p * M`, then
    /// divide by w). NDC has x right and y down, with (0, 0) and (1, 1) the top-left and
    /// bottom-right corners of the display window. Columns are centred on the image plane;
    /// rows follow the course's aiming, so the window's top edge is at `h/2 + step` and its
    /// bottom at `-h/2 + step` (see `plane_point`). World space is camera space here.
    pub fn world_to_ndc(&self) -> [[f64; 4]; 4] {
        let (w, h) = (self.plane_width, self.plane_height);
        let top = h / 2.0 + self.row_step;
        [
            [1.0 / w, 0.0, 0.0, 0.0],
            [0.0, -1.0 / h, 0.0, 0.0],
            [0.5, top / h, 1.0, 1.0],
            [0.0, 0.0, 0.0, 0.0],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_size_and_step_match_the_spec_constants() {
        let c = Camera::new(640, 480);
        assert_eq!(c.plane_width, 0.8284271247461901);
        assert_eq!(c.plane_height, 0.6213203435596426);
        assert_eq!(c.step, 0.8284271247461901 / 640.0);
    }

    #[test]
    fn columns_are_centred_and_rows_sit_one_pixel_low() {
        let c = Camera::new(640, 480);
        let (left, top) = c.plane_point(0, 0);
        let (right, bottom) = c.plane_point(639, 479);
        assert!((left + right).abs() < 1e-15);
        assert!((left - (-c.plane_width / 2.0 + 0.5 * c.step)).abs() < 1e-15);
        assert!((top - (c.plane_height / 2.0 + 0.5 * c.step)).abs() < 1e-15);
        assert!((bottom - (-c.plane_height / 2.0 + 1.5 * c.step)).abs() < 1e-15);
        let d = c.pixel_centre_ray(0, 0).direction;
        assert!((d.length() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn sub_pixel_centre_is_the_pixel_centre_ray_to_rounding() {
        let c = Camera::new(64, 48);
        let a = c.pixel_centre_ray(10, 7).direction;
        let b = c.sub_pixel_ray(10, 7, 0.5, 0.5).direction;
        assert!((a - b).length() < 1e-15);
    }

    #[test]
    fn world_to_ndc_maps_pixel_rays_to_their_pixels() {
        let c = Camera::new(640, 480);
        let m = c.world_to_ndc();
        for (x, y) in [(0, 0), (639, 479), (320, 100), (17, 400)] {
            let p = c.pixel_centre_ray(x, y).direction * 3.7;
            let row = [p.x, p.y, p.z, 1.0];
            let out: Vec<f64> = (0..4)
                .map(|j| (0..4).map(|i| row[i] * m[i][j]).sum())
                .collect();
            let (u, v) = (out[0] / out[3], out[1] / out[3]);
            assert!((u * 640.0 - (f64::from(x) + 0.5)).abs() < 1e-9, "{x} {u}");
            assert!((v * 480.0 - (f64::from(y) + 0.5)).abs() < 1e-9, "{y} {v}");
        }
    }
}
