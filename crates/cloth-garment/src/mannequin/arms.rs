//! Arms: tapered tubes with rounded ends, hanging from the shoulder joints in an A-pose.
//!
//! Each arm is its own closed surface that starts inside the torso, so the two overlap at
//! the shoulder; as separate collision bodies they need not be joined.

use std::f64::consts::PI;

use cloth_core::math::Vec3;
use serde::{Deserialize, Serialize};

use super::loft::{Cap, Loft};
use super::{ArmMeasurements, Landmarks};

/// Fewest points around an arm: below this a wrist looks like a prism to the cloth.
const MIN_ARM_SEGMENTS: usize = 12;

/// Where an arm is, in metres: its straight axis and the radii at its ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ArmAxis {
    /// Centre of the shoulder joint (the axis' upper end, inside the torso).
    pub joint: [f64; 3],
    /// Centre of the wrist (the axis' lower end); the rounded end goes one wrist radius on.
    pub wrist: [f64; 3],
    /// Upper arm radius, from the upper arm girth.
    pub joint_radius: f64,
    /// Wrist radius, from the wrist girth.
    pub wrist_radius: f64,
}

/// The left (+x) and right (-x) arm axes. The arm's outer side runs through the shoulder
/// point, so the top of the arm continues the shoulder's line; the joint centre is one
/// upper-arm radius inside it, and the wrist is `length` from the shoulder point.
pub(crate) fn arm_axes(arms: &ArmMeasurements, lm: &Landmarks) -> [ArmAxis; 2] {
    let joint_radius = arms.upper_arm_girth / (2.0 * PI);
    let wrist_radius = arms.wrist_girth / (2.0 * PI);
    let (sin, cos) = arms.angle_degrees.to_radians().sin_cos();
    // Validation keeps the length well over the upper arm radius.
    let along = (arms.length.powi(2) - joint_radius.powi(2)).max(0.0).sqrt();
    [1.0, -1.0].map(|side| {
        let down = Vec3::new(side * sin, 0.0, -cos);
        let outward = Vec3::new(side * cos, 0.0, sin);
        let shoulder = Vec3::new(side * lm.shoulder_x, lm.shoulder_y, lm.shoulder_z);
        let joint = shoulder - joint_radius * outward;
        let wrist = joint + along * down;
        ArmAxis {
            joint: joint.into(),
            wrist: wrist.into(),
            joint_radius,
            wrist_radius,
        }
    })
}

/// Vertices and outward triangles of the left arm along `left`, and of the right arm: its
/// mirror image in x (triangles reversed to stay outward), so the form is exactly symmetric.
pub(crate) fn arm_meshes(left: &ArmAxis, segments: usize, spacing: f64) -> [(Vec<Vec3>, Vec<[u32; 3]>); 2] {
    let (vertices, triangles) = arm_mesh(left, segments, spacing);
    let mirrored = vertices.iter().map(|p| Vec3::new(-p.x, p.y, p.z)).collect();
    let reversed = triangles.iter().map(|&[a, b, c]| [a, c, b]).collect();
    [(vertices, triangles), (mirrored, reversed)]
}

/// The arm's vertices and outward triangles: circles along the axis from the wrist up to
/// the joint, their radius easing from the wrist's to the upper arm's along a half cosine
/// (flat at both ends, so the hemispherical ends meet the tube without a crease).
fn arm_mesh(axis: &ArmAxis, segments: usize, spacing: f64) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let segments = (segments / 2).max(MIN_ARM_SEGMENTS).next_multiple_of(2);
    let (joint, wrist) = (Vec3::from(axis.joint), Vec3::from(axis.wrist));
    let length = (joint - wrist).norm();
    let up = (joint - wrist) / length;
    // A right-handed frame (u, v, up), so circles counter-clockwise about `up` face outward.
    let v = Vec3::y();
    let u = v.cross(&up);
    let steps = ((length / spacing).ceil() as usize).max(1);
    let mut loft = Loft::default();
    for i in 0..=steps {
        let t = i as f64 / steps as f64;
        let ease = 0.5 - 0.5 * (PI * t).cos();
        let radius = axis.wrist_radius + (axis.joint_radius - axis.wrist_radius) * ease;
        let centre = wrist + t * length * up;
        loft.push(
            (0..segments)
                .map(|k| {
                    // Half a step off the x-z plane: no vertex on the arm's outer line,
                    // which runs through the torso's shoulder point and would weld to it.
                    let (s, c) = (2.0 * PI * (k as f64 + 0.5) / segments as f64).sin_cos();
                    centre + radius * (c * u + s * v)
                })
                .collect(),
        );
    }
    loft.close(
        Cap {
            axis: -up,
            height: axis.wrist_radius,
        },
        Cap {
            axis: up,
            height: axis.joint_radius,
        },
        spacing,
    )
}
