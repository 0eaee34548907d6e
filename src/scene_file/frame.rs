//! Turning a file's frame into ours: z up, the body facing -y.

use cloth_core::math::Vec3;
use cloth_formats::MeshFormat;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// The axis that points up in a mesh file. Most avatar assets (GarmentCode, SMPL,
/// Marvelous Designer exports) and every glTF file are y-up; our world is z-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UpAxis {
    Y,
    Z,
}

impl UpAxis {
    /// The file's up axis when the scene does not say: glTF's is y by definition, other
    /// formats are taken as written (z up).
    pub fn of_file(path: &std::path::Path) -> UpAxis {
        if matches!(MeshFormat::of(path), Ok(MeshFormat::Gltf)) {
            UpAxis::Y
        } else {
            UpAxis::Z
        }
    }

    /// The turn from this frame to ours: for y up, (x, y, z) -> (x, -z, y), a quarter turn
    /// about x, as Blender's importers do, so that a y-up asset facing +z faces -y.
    pub fn to_z_up(self) -> UnitQuaternion<f64> {
        match self {
            UpAxis::Z => UnitQuaternion::identity(),
            UpAxis::Y => UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
        }
    }

    /// `points` of our world in this frame: for y up, (x, y, z) -> (x, z, -y), the turn
    /// back of [`UpAxis::to_z_up`] (lengths and winding kept).
    pub fn turned_from_z_up(self, points: &[Vec3]) -> Vec<Vec3> {
        let turn = self.to_z_up().inverse();
        points.iter().map(|p| turn * p).collect()
    }

    /// The header lines of an OBJ or PLY file holding `what` in this frame: what wrote
    /// it, and the frame and units.
    pub fn file_header(self, what: &str) -> Vec<String> {
        let frame = match self {
            UpAxis::Z => "z up (the engine's frame), metres",
            UpAxis::Y => "y up, metres: turned from the engine's z up, (x, y, z) -> (x, z, -y)",
        };
        vec![
            format!("{what}, written by cloth {}", env!("CARGO_PKG_VERSION")),
            frame.to_string(),
        ]
    }
}

/// A file placed in our world: turned from its `up` axis to ours, then by `rotation`
/// (degrees about our x, then y, then z: Blender's XYZ Euler), then moved to `position`.
/// The reason is for the key `rotation` when an angle is not finite.
pub fn placement(up: UpAxis, rotation: [f64; 3], position: [f64; 3]) -> Result<Isometry3<f64>, String> {
    if let Some(a) = rotation.iter().find(|a| !a.is_finite()) {
        return Err(format!("{a} is not an angle: give [rx, ry, rz] in degrees"));
    }
    let [rx, ry, rz] = rotation.map(f64::to_radians);
    let turn = UnitQuaternion::from_euler_angles(rx, ry, rz) * up.to_z_up();
    Ok(Isometry3::from_parts(
        Translation3::from(Vector3::from(position)),
        turn,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    #[test]
    fn y_up_becomes_z_up_as_blender_turns_it() {
        let q = placement(UpAxis::Y, [0.0; 3], [0.0; 3]).unwrap();
        let p = q * Point3::new(1.0, 2.0, 3.0);
        assert!((p.coords - Vector3::new(1.0, -3.0, 2.0)).norm() < 1e-12, "{p}");
    }

    #[test]
    fn outputs_turn_back_to_y_up() {
        let p = [Vec3::new(1.0, 2.0, 3.0)];
        assert_eq!(UpAxis::Z.turned_from_z_up(&p), p);
        let q = UpAxis::Y.turned_from_z_up(&p)[0];
        assert!((q - Vec3::new(1.0, 3.0, -2.0)).norm() < 1e-12, "{q}");
        // The turn read in undoes it.
        let back = placement(UpAxis::Y, [0.0; 3], [0.0; 3]).unwrap() * nalgebra::Point3::from(q);
        assert!((back.coords - p[0]).norm() < 1e-12, "{back}");
    }

    #[test]
    fn rotations_are_about_x_then_y_then_z_in_degrees() {
        // 90 about x takes y to z; then 90 about z takes x to y.
        let q = placement(UpAxis::Z, [90.0, 0.0, 90.0], [1.0, 0.0, 0.0]).unwrap();
        let y = q * Point3::new(0.0, 1.0, 0.0);
        let x = q * Point3::new(1.0, 0.0, 0.0);
        assert!((y.coords - Vector3::new(1.0, 0.0, 1.0)).norm() < 1e-12, "{y}");
        assert!((x.coords - Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-12, "{x}");
        assert!(placement(UpAxis::Z, [f64::NAN, 0.0, 0.0], [0.0; 3]).is_err());
    }
}
