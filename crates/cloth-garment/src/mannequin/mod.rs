//! The parametric dress form: a torso from the upper thigh to a neck stump, and optionally
//! two arms, generated from a dressmaker's measurements as closed, outward triangle
//! surfaces ready to be collision bodies.
//!
//! Frame: metres, z up, the floor at z = 0 (the form stands at its real height), the body's
//! centre line on the z axis, its front towards -y, its left side towards +x, mirror
//! symmetric in x. The torso is a stack of horizontal rings whose sections are smooth
//! ovals; at the bust, waist, hip and neck base the meshed ring's perimeter is the
//! measured girth, and the section through the shoulder points is the shoulder width
//! across.

mod arclength;
mod spline;
mod error;
mod loft;
mod measure;
mod measurements;
mod landmarks;
mod sections;
mod torso;
mod arms;
mod obj;

use cloth_collide::{Body, SurfaceOptions, TriSurface};

pub use arms::ArmAxis;
pub use error::MannequinError;
pub use landmarks::Landmarks;
pub use measurements::{ArmMeasurements, Measurements, ARM_LENGTH_FRACTION};

use torso::Rings;

/// Default points around the torso (arms get half): the bust's curve between the bust
/// points is then a few centimetres per edge, smooth enough for cloth to drape on.
pub const DEFAULT_SEGMENTS: usize = 64;
/// Default largest distance between rings along the body's profile, m.
pub const DEFAULT_RING_SPACING: f64 = 0.015;

/// Surface names, as used for the bodies and the OBJ objects.
const TORSO: &str = "torso";
const ARM_NAMES: [&str; 2] = ["left_arm", "right_arm"];

/// A generated dress form: its measurements, landmarks and surfaces.
#[derive(Debug, Clone)]
pub struct Mannequin {
    measurements: Measurements,
    landmarks: Landmarks,
    torso: TriSurface,
    arms: Vec<TriSurface>,
    arm_axes: Vec<ArmAxis>,
}

impl Mannequin {
    /// The form at the default resolution: [`DEFAULT_SEGMENTS`] points around, rings at
    /// most [`DEFAULT_RING_SPACING`] apart.
    pub fn new(m: &Measurements) -> Result<Self, MannequinError> {
        Self::build(m, Rings::Spacing(DEFAULT_RING_SPACING), DEFAULT_SEGMENTS)
    }

    /// The form with about `rings` rings up the torso's sides (a few more where a key level
    /// needs its own) and `segments` points around each (a multiple of 4, so the centre
    /// front, centre back and both sides are vertices; the arms get half as many).
    pub fn with_resolution(m: &Measurements, rings: usize, segments: usize) -> Result<Self, MannequinError> {
        if rings < 16 {
            return Err(MannequinError::Resolution {
                name: "rings",
                value: rings,
                expected: "at least 16 (the 15 key levels are rings already)",
            });
        }
        if segments < 16 || !segments.is_multiple_of(4) {
            return Err(MannequinError::Resolution {
                name: "segments",
                value: segments,
                expected: "a multiple of 4, at least 16",
            });
        }
        Self::build(m, Rings::Count(rings), segments)
    }

    fn build(m: &Measurements, rings: Rings, segments: usize) -> Result<Self, MannequinError> {
        m.validate()?;
        let landmarks = Landmarks::new(m);
        let options = SurfaceOptions::default();
        let mesh = torso::torso(m, &landmarks, rings, segments);
        let torso = TriSurface::new(mesh.vertices, mesh.triangles, &options)
            .map_err(|source| MannequinError::Surface { part: TORSO, source })?;
        let arm_axes: Vec<ArmAxis> = m
            .arms
            .map(|arms| arms::arm_axes(&arms, &landmarks).to_vec())
            .unwrap_or_default();
        let arms = match arm_axes.first() {
            None => Vec::new(),
            Some(left) => arms::arm_meshes(left, segments, mesh.spacing)
                .into_iter()
                .zip(ARM_NAMES)
                .map(|((vertices, triangles), part)| {
                    TriSurface::new(vertices, triangles, &options)
                        .map_err(|source| MannequinError::Surface { part, source })
                })
                .collect::<Result<Vec<_>, _>>()?,
        };
        Ok(Self {
            measurements: *m,
            landmarks,
            torso,
            arms,
            arm_axes,
        })
    }

    pub fn measurements(&self) -> &Measurements {
        &self.measurements
    }

    pub fn landmarks(&self) -> &Landmarks {
        &self.landmarks
    }

    pub fn torso(&self) -> &TriSurface {
        &self.torso
    }

    /// No arms, or the left (+x) and the right (-x) arm.
    pub fn arms(&self) -> &[TriSurface] {
        &self.arms
    }

    /// The arms' axes, in the order of [`Mannequin::arms`].
    pub fn arm_axes(&self) -> &[ArmAxis] {
        &self.arm_axes
    }

    /// Every surface with its name: "torso", then "left_arm" and "right_arm" if any.
    pub fn surfaces(&self) -> Vec<(&'static str, &TriSurface)> {
        std::iter::once((TORSO, &self.torso))
            .chain(ARM_NAMES.into_iter().zip(&self.arms))
            .collect()
    }

    /// One static collision body per surface, named as in [`Mannequin::surfaces`]: the arms
    /// overlap the torso, which separate bodies allow and one merged surface would not.
    pub fn bodies(&self) -> Vec<Body> {
        self.surfaces()
            .into_iter()
            .map(|(name, surface)| Body::new(name, surface.clone()))
            .collect()
    }

    /// The girths the measurements name, with the height each is taken at and its value:
    /// (name, z, girth), for bust, waist, hip and neck.
    pub fn measured_girths(&self) -> [(&'static str, f64, f64); 4] {
        let (lm, m) = (&self.landmarks, &self.measurements);
        [
            ("bust", lm.bust_z, m.bust),
            ("waist", lm.waist_z, m.waist),
            ("hip", lm.hip_z, m.hip),
            ("neck", lm.neck_z, m.neck_girth),
        ]
    }

    /// Perimeter of the torso's horizontal section at height `z` (0 outside the torso),
    /// measured on the mesh, as a tape measure would on the form.
    pub fn girth_at(&self, z: f64) -> f64 {
        measure::section_length(&self.torso, z)
    }

    /// Writes all surfaces to one OBJ file, one `o` object per surface.
    pub fn write_obj(&self, path: &std::path::Path) -> std::io::Result<()> {
        obj::write(self, path)
    }

    /// All surfaces as one (the arms kept as separate closed components): for drawing, or
    /// for tools that take a single mesh.
    pub fn merged(&self) -> TriSurface {
        let parts: Vec<TriSurface> = self.surfaces().into_iter().map(|(_, s)| s.clone()).collect();
        TriSurface::merged(&parts)
    }
}
