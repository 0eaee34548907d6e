//! Body measurements, in metres, and the ranges the generator accepts.

use serde::{Deserialize, Serialize};

use super::MannequinError;

/// The measurements a dressmaker takes, in metres. Girths are tape-measure perimeters of
/// horizontal sections; missing fields in a scene file take the [`Default`] values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Measurements {
    /// Standing height; every landmark height is a proportion of it.
    pub height: f64,
    /// Girth over the bust points.
    pub bust: f64,
    /// Girth at the natural waist.
    pub waist: f64,
    /// Girth at the fullest part of the seat.
    pub hip: f64,
    /// Distance between the two shoulder points (across the widest section at shoulder level).
    pub shoulder_width: f64,
    /// Girth at the base of the neck.
    pub neck_girth: f64,
    /// `None`: a form without arms, as most dress forms are.
    pub arms: Option<ArmMeasurements>,
}

/// Arm measurements, in metres and degrees. Missing fields in a scene file take the
/// [`Default`] values, an average adult's whatever the height ([`Measurements::with_arms`]
/// scales the length to the body).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArmMeasurements {
    /// From the shoulder point to the wrist, along the arm.
    pub length: f64,
    /// Girth of the upper arm at its fullest, where the arm leaves the shoulder.
    pub upper_arm_girth: f64,
    /// Girth at the wrist.
    pub wrist_girth: f64,
    /// Angle of the arm from the vertical, in the x-z plane (an A-pose; 90 is a T-pose).
    pub angle_degrees: f64,
}

/// A typical adult woman, 1.68 m tall, 92-76-98 cm: mid-range in women's sizing tables,
/// so garments drafted for a "medium" fit it.
impl Default for Measurements {
    fn default() -> Self {
        Self {
            height: 1.68,
            bust: 0.92,
            waist: 0.76,
            hip: 0.98,
            shoulder_width: 0.40,
            neck_girth: 0.36,
            arms: None,
        }
    }
}

/// Fraction of the height from the shoulder point to the wrist: upper arm 0.186 H plus
/// forearm 0.146 H (Drillis and Contini's segment lengths, as tabulated in Winter,
/// "Biomechanics and Motor Control of Human Movement").
pub const ARM_LENGTH_FRACTION: f64 = 0.332;

/// An average adult arm (0.332 x 1.68 m long, 28 cm upper arm, 15.5 cm wrist) held 42
/// degrees out, far enough from the torso that cloth can fall between them.
impl Default for ArmMeasurements {
    fn default() -> Self {
        Self {
            length: ARM_LENGTH_FRACTION * 1.68,
            upper_arm_girth: 0.28,
            wrist_girth: 0.155,
            angle_degrees: 42.0,
        }
    }
}

impl Measurements {
    /// The same body with default arms whose length follows this body's height, so a short
    /// or tall form does not get an average person's arms.
    pub fn with_arms(self) -> Self {
        Self {
            arms: Some(ArmMeasurements {
                length: ARM_LENGTH_FRACTION * self.height,
                ..ArmMeasurements::default()
            }),
            ..self
        }
    }

    /// Checks every measurement. The ranges are wide (they admit any adult body we know of)
    /// but keep out what the section shapes cannot represent: a waist far over the hip would
    /// need a belly the ovals do not have, shoulders barely wider than the neck leave no
    /// shoulder slope, and girths far from the height's scale give a form that is a disc or
    /// a pole.
    pub fn validate(&self) -> Result<(), MannequinError> {
        let lengths = [
            ("height", self.height),
            ("bust", self.bust),
            ("waist", self.waist),
            ("hip", self.hip),
            ("shoulder_width", self.shoulder_width),
            ("neck_girth", self.neck_girth),
        ];
        for (field, value) in lengths {
            positive(field, value)?;
        }
        let h = self.height;
        within(
            "height",
            h,
            1.2,
            2.3,
            "an adult standing height, the proportions are adult ones",
        )?;
        relative("bust", self.bust, h, 0.3, 1.0)?;
        relative("waist", self.waist, h, 0.25, 1.0)?;
        relative("hip", self.hip, h, 0.3, 1.0)?;
        relative("neck_girth", self.neck_girth, h, 0.12, 0.3)?;
        if self.waist > 1.2 * self.hip {
            return Err(measurement(
                "waist",
                self.waist,
                format!("at most 1.2 x hip = {:.4} m", 1.2 * self.hip),
            ));
        }
        if self.neck_girth > 0.6 * self.bust {
            return Err(measurement(
                "neck_girth",
                self.neck_girth,
                format!("at most 0.6 x bust = {:.4} m", 0.6 * self.bust),
            ));
        }
        let neck_width = self.neck_girth / std::f64::consts::PI;
        if self.shoulder_width < 1.5 * neck_width {
            return Err(measurement(
                "shoulder_width",
                self.shoulder_width,
                format!(
                    "at least 1.5 x the neck's width (neck_girth / pi = {neck_width:.4} m), i.e. \
                     {:.4} m: shoulders must reach beyond the neck",
                    1.5 * neck_width
                ),
            ));
        }
        relative("shoulder_width", self.shoulder_width, h, 0.15, 0.35)?;
        if let Some(arms) = &self.arms {
            arms.validate(self)?;
        }
        Ok(())
    }
}

impl ArmMeasurements {
    fn validate(&self, body: &Measurements) -> Result<(), MannequinError> {
        positive("arms.length", self.length)?;
        positive("arms.upper_arm_girth", self.upper_arm_girth)?;
        positive("arms.wrist_girth", self.wrist_girth)?;
        relative("arms.length", self.length, body.height, 0.2, 0.5)?;
        if self.upper_arm_girth > 0.6 * body.bust {
            return Err(measurement(
                "arms.upper_arm_girth",
                self.upper_arm_girth,
                format!("at most 0.6 x bust = {:.4} m", 0.6 * body.bust),
            ));
        }
        if self.wrist_girth > self.upper_arm_girth {
            return Err(measurement(
                "arms.wrist_girth",
                self.wrist_girth,
                format!(
                    "at most the upper arm girth ({} m): the arm tapers to the wrist",
                    self.upper_arm_girth
                ),
            ));
        }
        // Closer to vertical than this, the arm runs inside the torso's side all the way.
        if !(10.0..=90.0).contains(&self.angle_degrees) {
            return Err(MannequinError::Angle {
                field: "arms.angle_degrees",
                value: self.angle_degrees,
                expected: "10 to 90 degrees from vertical (90 is a T-pose; below 10 the arm is \
                           inside the torso)"
                    .into(),
            });
        }
        Ok(())
    }
}

fn measurement(field: &'static str, value: f64, expected: String) -> MannequinError {
    MannequinError::Measurement {
        field,
        value,
        expected,
    }
}

fn positive(field: &'static str, value: f64) -> Result<(), MannequinError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(measurement(field, value, "a finite length > 0".into()))
    }
}

fn within(field: &'static str, value: f64, lo: f64, hi: f64, why: &str) -> Result<(), MannequinError> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(measurement(field, value, format!("{lo} to {hi} m ({why})")))
    }
}

/// A girth or length within a range of fractions of the height.
fn relative(field: &'static str, value: f64, height: f64, lo: f64, hi: f64) -> Result<(), MannequinError> {
    if (lo * height..=hi * height).contains(&value) {
        Ok(())
    } else {
        Err(measurement(
            field,
            value,
            format!(
                "{lo} to {hi} x height, i.e. {:.4} to {:.4} m for a height of {height} m",
                lo * height,
                hi * height
            ),
        ))
    }
}
