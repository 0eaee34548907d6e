//! Heights of the body's landmarks, as proportions of the standing height.
//!
//! Sources and assumptions (fractions of the height H, floor at 0):
//! - shoulder point (acromion) 0.818 H and chest (bust) level 0.720 H: Drillis and Contini's
//!   segment proportions (1966), as tabulated in D. A. Winter, "Biomechanics and Motor
//!   Control of Human Movement", fig. 4.1;
//! - natural waist 0.615 H, seat (hip girth) level 0.500 H and crotch 0.460 H: the ratios of
//!   the waist, hip and crotch heights to the stature in women's sizing surveys (ISO 8559
//!   body dimensions, ASTM D5585 tables), which sit at 0.60-0.63, 0.49-0.51 and 0.45-0.47;
//! - our assumptions where the tables are silent about a dress form: the armpit 0.063 H
//!   (about 10 cm) under the shoulder point; the underbust 0.045 H (about 7.5 cm) under the
//!   bust; the side of the neck base 0.030 H (5 cm) over the shoulder point, a shoulder
//!   slope of about 19 degrees from the neck to the shoulder point; the neck stump ending
//!   0.028 H higher, about the chin's height (0.870 H in Drillis and Contini); the form
//!   ending at 0.430 H, about 5 cm under the crotch, in one piece.

use serde::{Deserialize, Serialize};

use super::Measurements;

/// Depth of the section through the shoulder points as a fraction of the bust girth
/// (14 cm for a 92 cm bust: the upper chest and back at the collar bones).
pub(super) const SHOULDER_DEPTH: f64 = 0.155;
/// How far behind the centre line the shoulder points sit, as a fraction of the shoulder
/// section's depth: the shoulders are set back a little from the chest.
pub(super) const SHOULDER_SHIFT: f64 = 0.035;

const TOP: f64 = 0.876;
const NECK: f64 = 0.848;
const SHOULDER: f64 = 0.818;
const ARMPIT: f64 = 0.755;
const BUST: f64 = 0.720;
const UNDERBUST: f64 = 0.675;
const WAIST: f64 = 0.615;
const HIP: f64 = 0.500;
const CROTCH: f64 = 0.460;
const BOTTOM: f64 = 0.430;

/// Where the body's landmarks are, in metres, in the mannequin's frame (floor z = 0,
/// centre line on the z axis, facing -y).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Landmarks {
    /// Highest point: the top of the neck stump.
    pub top_z: f64,
    /// Base of the neck at its side, where the shoulder line starts; the section there has
    /// the neck girth.
    pub neck_z: f64,
    /// Shoulder points: the widest section, `2 shoulder_x` across.
    pub shoulder_z: f64,
    pub armpit_z: f64,
    /// Bust points; the section there has the bust girth.
    pub bust_z: f64,
    pub underbust_z: f64,
    /// Natural waist; the section there has the waist girth.
    pub waist_z: f64,
    /// Fullest part of the seat; the section there has the hip girth.
    pub hip_z: f64,
    /// Crotch level of the person; the form goes on, in one piece, below it.
    pub crotch_z: f64,
    /// Lowest point of the form, on the upper thigh.
    pub bottom_z: f64,
    /// x of the shoulder points (half the shoulder width); the body's left side is +x.
    pub shoulder_x: f64,
    /// y of the shoulder points, a little behind the centre line (+y).
    pub shoulder_y: f64,
}

impl Landmarks {
    /// The landmarks of a body with these measurements (not validated here).
    pub fn new(m: &Measurements) -> Self {
        let h = m.height;
        Self {
            top_z: TOP * h,
            neck_z: NECK * h,
            shoulder_z: SHOULDER * h,
            armpit_z: ARMPIT * h,
            bust_z: BUST * h,
            underbust_z: UNDERBUST * h,
            waist_z: WAIST * h,
            hip_z: HIP * h,
            crotch_z: CROTCH * h,
            bottom_z: BOTTOM * h,
            shoulder_x: 0.5 * m.shoulder_width,
            shoulder_y: shoulder_y(m),
        }
    }
}

/// y of the shoulder points: the widest points of the section through them.
fn shoulder_y(m: &Measurements) -> f64 {
    SHOULDER_SHIFT * SHOULDER_DEPTH * m.bust
}
