//! Cones of directions: the spread of a patch's normals. A connected patch of cloth whose
//! normals all lie within less than a right angle of one axis is a gently curved sheet,
//! which cannot fold onto itself (Volino & Magnenat-Thalmann 1994; Provot 1997): the
//! search for the cloth's contacts with itself skips such a patch against itself.

use crate::math::Vec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Half-angle below which a connected patch counts as flat: a right angle less a margin
/// for the normals' turning within a step.
const FLAT: f64 = FRAC_PI_2 - 0.15;

/// Every direction within `half` (rad) of `axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cone {
    axis: Vec3,
    half: f64,
}

impl Cone {
    /// Every direction.
    pub const FULL: Cone = Cone {
        axis: Vec3::new(0.0, 0.0, 1.0),
        half: PI,
    };

    /// The unit direction `d`, or every direction if it is not one.
    pub fn along(d: Vec3) -> Self {
        let len = d.norm();
        if len > 0.0 && len.is_finite() {
            Self {
                axis: d / len,
                half: 0.0,
            }
        } else {
            Self::FULL
        }
    }

    /// The narrowest cone of this kind holding both.
    pub fn merge(&self, other: &Self) -> Self {
        if self.half >= PI || other.half >= PI {
            return Self::FULL;
        }
        let between = self.axis.dot(&other.axis).clamp(-1.0, 1.0).acos();
        if between + other.half <= self.half {
            return *self;
        }
        if between + self.half <= other.half {
            return *other;
        }
        let half = 0.5 * (between + self.half + other.half);
        // Towards the other axis, by what the new half-angle adds to this one's.
        let side = other.axis - self.axis.dot(&other.axis) * self.axis;
        let len = side.norm();
        if half >= PI || len < 1e-12 {
            return Self::FULL;
        }
        let turn = half - self.half;
        Self {
            axis: (self.axis * turn.cos() + (side / len) * turn.sin()).normalize(),
            half,
        }
    }

    pub fn axis(&self) -> &Vec3 {
        &self.axis
    }

    pub fn is_flat(&self) -> bool {
        self.half < FLAT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_cones_hold_every_direction_of_both() {
        let dirs: Vec<Vec3> = (0..40)
            .map(|k| {
                let a = 0.07 * k as f64;
                Vec3::new(a.sin() * 0.6, (1.3 * a).cos() * 0.5, 1.0).normalize()
            })
            .collect();
        let cone = dirs
            .iter()
            .fold(Cone::along(dirs[0]), |c, d| c.merge(&Cone::along(*d)));
        for d in &dirs {
            assert!(d.dot(&cone.axis).clamp(-1.0, 1.0).acos() <= cone.half + 1e-12);
        }
        assert!(cone.is_flat(), "{cone:?}");
        let folded = cone.merge(&Cone::along(-Vec3::z()));
        assert!(!folded.is_flat());
        assert_eq!(Cone::along(Vec3::zeros()), Cone::FULL);
    }
}
