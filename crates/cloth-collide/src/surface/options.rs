//! How a mesh is turned into a surface.

use super::SurfaceError;

/// Relative weld distance used when none is given: far below any real feature size, far
/// above the rounding of coordinates written as decimal text or as f32.
pub(super) const DEFAULT_WELD_FRACTION: f64 = 1e-7;

/// How [`TriSurface::new`](super::TriSurface::new) and the file readers build a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceOptions {
    /// Vertices on open edges within this distance (m, after scaling) are joined, because
    /// STL files repeat every corner and exporters split vertices along texture seams.
    /// Vertices of a closed surface are never joined. `None` uses 1e-7 times the
    /// bounding-box diagonal; `Some(0.0)` joins only exactly coincident ones.
    pub weld_distance: Option<f64>,
    /// Scale applied to the coordinates (e.g. 0.01 for a file in centimetres).
    pub scale: f64,
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        Self {
            weld_distance: None,
            scale: 1.0,
        }
    }
}

impl SurfaceOptions {
    pub(super) fn check(&self) -> Result<(), SurfaceError> {
        // A negative scale would mirror the body and turn it inside out.
        if !(self.scale.is_finite() && self.scale > 0.0) {
            return Err(SurfaceError::Parameter {
                name: "scale",
                value: self.scale,
                expected: "a finite number > 0",
            });
        }
        if let Some(d) = self.weld_distance {
            if !(d.is_finite() && d >= 0.0) {
                return Err(SurfaceError::Parameter {
                    name: "weld_distance",
                    value: d,
                    expected: "a finite distance >= 0 m, or None for the default",
                });
            }
        }
        Ok(())
    }
}
