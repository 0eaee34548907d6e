//! Why a mannequin was refused: the measurement at fault, its value and what would do.

use cloth_collide::SurfaceError;

/// A mannequin that cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum MannequinError {
    /// A measurement out of range, e.g. `field = "waist"` or `field = "arms.length"`.
    #[error("measurement `{field}` = {value} m is invalid: expected {expected}")]
    Measurement {
        field: &'static str,
        value: f64,
        expected: String,
    },
    /// An angle out of range (kept apart from lengths so the message has the right unit).
    #[error("measurement `{field}` = {value} degrees is invalid: expected {expected}")]
    Angle {
        field: &'static str,
        value: f64,
        expected: String,
    },
    /// A mesh resolution too coarse to carry the shape.
    #[error("resolution `{name}` = {value} is invalid: expected {expected}")]
    Resolution {
        name: &'static str,
        value: usize,
        expected: &'static str,
    },
    /// The generated mesh failed the surface checks: a bug in the generator, not in the
    /// measurements, reported rather than hidden.
    #[error("the generated {part} is not a valid closed surface: {source}")]
    Surface {
        part: &'static str,
        #[source]
        source: SurfaceError,
    },
}

impl MannequinError {
    /// The measurement or resolution parameter at fault, so callers (a scene loader, a UI)
    /// can point at it without parsing the message.
    pub fn field(&self) -> Option<&'static str> {
        match self {
            Self::Measurement { field, .. } | Self::Angle { field, .. } => Some(field),
            Self::Resolution { name, .. } => Some(name),
            Self::Surface { .. } => None,
        }
    }
}
