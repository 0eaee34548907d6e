//! Where a flat panel starts in 3D before sewing.

use super::Point2;
use cloth_core::math::Vec3;
use nalgebra::{Rotation3, UnitQuaternion};

/// A panel's starting pose: its 2D point (x, y) is first laid at (x, y, 0) in the panel's
/// own frame (its front faces +z), optionally bent around a vertical axis, then rotated
/// and translated into the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    pub rotation: UnitQuaternion<f64>,
    pub translation: Vec3,
    pub wrap: Option<Wrap>,
}

/// Bends a panel around an axis parallel to its y axis, `radius` behind its plane (on
/// the -z side, where the body is), so it starts curved around the body. The panel's
/// line `x = centre` stays where it was; a point at distance `s` from it along x moves
/// to the angle `s / radius` round the axis, so lengths along x are kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wrap {
    pub radius: f64,
    pub centre: f64,
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            rotation: UnitQuaternion::identity(),
            translation: Vec3::zeros(),
            wrap: None,
        }
    }
}

impl Placement {
    /// A placement from Euler angles in degrees, applied about x, then y, then z (fixed
    /// axes), and a translation.
    pub fn from_euler_degrees(angles: [f64; 3], translation: Vec3) -> Self {
        let [x, y, z] = angles.map(f64::to_radians);
        Self {
            rotation: UnitQuaternion::from_rotation_matrix(&Rotation3::from_euler_angles(x, y, z)),
            translation,
            wrap: None,
        }
    }

    /// The 3D point where the panel's 2D point `p` starts.
    pub fn place(&self, p: Point2) -> Vec3 {
        let local = match self.wrap {
            Some(Wrap { radius, centre }) => {
                let angle = (p.x - centre) / radius;
                Vec3::new(centre + radius * angle.sin(), p.y, -radius * (1.0 - angle.cos()))
            }
            None => Vec3::new(p.x, p.y, 0.0),
        };
        self.translation + self.rotation * local
    }

    /// The panel's front (+z of its frame) in the world at its 2D point `p`.
    pub fn normal(&self, p: Point2) -> Vec3 {
        let local = match self.wrap {
            Some(Wrap { radius, centre }) => {
                let angle = (p.x - centre) / radius;
                Vec3::new(angle.sin(), 0.0, angle.cos())
            }
            None => Vec3::z(),
        };
        self.rotation * local
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping_keeps_lengths_along_x() {
        let placement = Placement {
            wrap: Some(Wrap {
                radius: 0.2,
                centre: 0.1,
            }),
            ..Placement::from_euler_degrees([90.0, 0.0, 0.0], Vec3::new(0.0, -0.3, 1.0))
        };
        let n = 200;
        let length: f64 = (0..n)
            .map(|k| {
                let a = placement.place(Point2::new(0.1 + 0.3 * k as f64 / n as f64, 0.05));
                let b = placement.place(Point2::new(0.1 + 0.3 * (k + 1) as f64 / n as f64, 0.05));
                (b - a).norm()
            })
            .sum();
        assert!((length - 0.3).abs() < 1e-5, "{length}");
        // The rotation takes the panel's y to the world's z and its front to -y.
        let p = placement.place(Point2::new(0.1, 0.05));
        assert!((p - Vec3::new(0.1, -0.3, 1.05)).norm() < 1e-12, "{p}");
        assert!((placement.normal(Point2::new(0.1, 0.0)) + Vec3::y()).norm() < 1e-12);
    }
}
