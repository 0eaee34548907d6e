//! Where the picture is taken from: a perspective camera on a sphere around what is drawn,
//! aimed at its centre, then zoomed and shifted on the image plane so that the projection
//! fills the viewport with a small margin whatever the direction.

use cloth_core::math::Vec3;

/// The direction the camera looks from. The world has z up and bodies face -y, so azimuth
/// 0 and elevation 0 look at the front; a positive azimuth moves the camera towards +x
/// (counter-clockwise seen from above), a positive elevation raises it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub azimuth_deg: f64,
    pub elevation_deg: f64,
}

impl Default for View {
    /// From the front, a little from the side and above: flat on, folds and drape hide.
    fn default() -> Self {
        Self {
            azimuth_deg: -25.0,
            elevation_deg: 15.0,
        }
    }
}

/// Half the vertical opening of the lens that sets the distance: wide enough for some
/// depth, narrow enough that nearer parts are not distorted.
const HALF_FOV_DEG: f64 = 15.0;
/// The share of the viewport's limiting dimension the projection fills.
const FILL: f64 = 0.92;
/// Straight up or down the horizon has no direction; stop short of it.
const MAX_ELEVATION_DEG: f64 = 89.0;

/// A camera fitted to a viewport of `width` x `height` pixels, with (0, 0) its top left.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Camera {
    pub eye: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// Pixels per unit of (lateral offset / depth).
    zoom: f64,
    /// The pixel straight ahead of the eye.
    centre: [f64; 2],
}

/// A point as the camera sees it: pixel coordinates and its distance along the view axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Projected {
    pub x: f64,
    pub y: f64,
    pub depth: f64,
}

impl Camera {
    /// Frames the finite points of `sets` from `view`; with none, frames the unit cube.
    pub fn fit(view: &View, sets: &[&[Vec3]], width: f64, height: f64) -> Self {
        let finite = || {
            sets.iter()
                .flat_map(|s| s.iter())
                .filter(|p| p.iter().all(|c| c.is_finite()))
        };
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for p in finite() {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        if lo.x > hi.x {
            (lo, hi) = (Vec3::zeros(), Vec3::repeat(1.0));
        }
        let target = (lo + hi) / 2.0;
        let radius = ((hi - lo).norm() / 2.0).max(1e-9);

        let az = view.azimuth_deg.to_radians();
        let el = view
            .elevation_deg
            .clamp(-MAX_ELEVATION_DEG, MAX_ELEVATION_DEG)
            .to_radians();
        let from = Vec3::new(az.sin() * el.cos(), -az.cos() * el.cos(), el.sin());
        let forward = -from;
        let right = forward.cross(&Vec3::z()).normalize();
        let up = right.cross(&forward);
        // Far enough that the bounding sphere lies in front of the eye and inside the lens.
        let eye = target + from * (radius / HALF_FOV_DEG.to_radians().sin());

        let mut camera = Self {
            eye,
            right,
            up,
            forward,
            zoom: 1.0,
            centre: [0.0, 0.0],
        };
        let (mut x0, mut x1, mut y0, mut y1) =
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in finite() {
            let q = camera.project(p);
            x0 = x0.min(q.x);
            x1 = x1.max(q.x);
            y0 = y0.min(q.y);
            y1 = y1.max(q.y);
        }
        if !(x0 <= x1 && y0 <= y1) {
            (x0, x1, y0, y1) = (0.0, 0.0, 0.0, 0.0);
        }
        let zoom_x = if x1 > x0 {
            width * FILL / (x1 - x0)
        } else {
            f64::INFINITY
        };
        let zoom_y = if y1 > y0 {
            height * FILL / (y1 - y0)
        } else {
            f64::INFINITY
        };
        let zoom = zoom_x.min(zoom_y);
        camera.zoom = if zoom.is_finite() { zoom } else { 1.0 };
        // With zoom 1 and centre 0, `project` gave the image-plane coordinates themselves.
        camera.centre = [
            width / 2.0 - camera.zoom * (x0 + x1) / 2.0,
            height / 2.0 - camera.zoom * (y0 + y1) / 2.0,
        ];
        camera
    }

    /// Pixel coordinates (y down) and depth of a world point.
    pub fn project(&self, p: &Vec3) -> Projected {
        let v = p - self.eye;
        let depth = v.dot(&self.forward);
        Projected {
            x: self.centre[0] + self.zoom * v.dot(&self.right) / depth,
            y: self.centre[1] - self.zoom * v.dot(&self.up) / depth,
            depth,
        }
    }

    /// A world direction in camera axes: x right, y up, z towards the viewer.
    pub fn direction(&self, d: &Vec3) -> [f32; 3] {
        [
            d.dot(&self.right) as f32,
            d.dot(&self.up) as f32,
            -d.dot(&self.forward) as f32,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An elongated, off-centre cloud of points.
    fn cloud() -> Vec<Vec3> {
        let mut points = Vec::new();
        for i in 0..7 {
            for j in 0..5 {
                for k in 0..9 {
                    points.push(Vec3::new(
                        3.0 + 0.4 * i as f64,
                        -2.0 + 0.1 * j as f64 + 0.03 * k as f64,
                        1.0 + 0.25 * k as f64,
                    ));
                }
            }
        }
        points
    }

    #[test]
    fn fit_keeps_every_point_inside_and_fills_the_frame() {
        let points = cloud();
        let (w, h) = (640.0, 400.0);
        for (az, el) in [
            (-25.0, 15.0),
            (0.0, 0.0),
            (90.0, 30.0),
            (170.0, -60.0),
            (-120.0, 89.5),
        ] {
            let view = View {
                azimuth_deg: az,
                elevation_deg: el,
            };
            let camera = Camera::fit(&view, &[&points], w, h);
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for p in &points {
                let q = camera.project(p);
                assert!(q.depth > 0.0, "point behind the eye at {view:?}");
                x0 = x0.min(q.x);
                x1 = x1.max(q.x);
                y0 = y0.min(q.y);
                y1 = y1.max(q.y);
            }
            assert!(
                x0 >= 0.0 && x1 <= w && y0 >= 0.0 && y1 <= h,
                "{view:?}: {x0} {x1} {y0} {y1}"
            );
            let filled = ((x1 - x0) / w).max((y1 - y0) / h);
            assert!(filled > 0.85, "{view:?} fills only {filled}");
            // Centred: equal margins on the limiting sides.
            assert!(
                (x0 - (w - x1)).abs() < 1.0 && (y0 - (h - y1)).abs() < 1.0,
                "{view:?}"
            );
        }
    }

    #[test]
    fn the_default_view_looks_at_the_front_from_above() {
        let camera = Camera::fit(&View::default(), &[&cloud()], 100.0, 100.0);
        let target = Vec3::new(4.2, -1.5, 2.0);
        let from = camera.eye - target;
        assert!(from.y < 0.0 && from.z > 0.0, "eye at {:?}", camera.eye);
        // Up in the world is up in the picture.
        let low = camera.project(&target);
        let high = camera.project(&(target + Vec3::z() * 0.1));
        assert!(high.y < low.y);
    }
}
