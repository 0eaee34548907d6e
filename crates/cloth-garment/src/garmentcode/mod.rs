//! Import of GarmentCode sewing-pattern specifications (`*_specification.json`).
//!
//! GarmentCode (Korosteleva & Sorkine-Hornung 2023, github.com/maria-korosteleva/
//! GarmentCode) and its predecessor Garment-Pattern-Generator (Korosteleva & Lee 2021,
//! the "Dataset of 3D garments with sewing patterns") share one JSON layout:
//!
//! ```text
//! { "pattern": {
//!     "panels": { NAME: { "translation": [x, y, z], "rotation": [rx, ry, rz],
//!                         "vertices": [[x, y], ...],
//!                         "edges": [{"endpoints": [i, j], "curvature": ...}, ...] } },
//!     "stitches": [[{"panel": NAME, "edge": k}, {"panel": NAME, "edge": k}], ...],
//!     "panel_order": [NAME, ...] },
//!   "properties": { "units_in_meter": 100, "curvature_coords": "relative",
//!                   "normalize_panel_translation": false, "normalized_edge_loops": true },
//!   "parameters": {...}, "parameter_order": [...] }
//! ```
//!
//! (pygarment/pattern/core.py `pattern_spec_template`; real files: GarmentCode's
//! assets/Patterns/*_specification.json, Garment-Pattern-Generator's
//! data_generation/Patterns/skirts/skirt_2_panels.json.) What each part means, and where
//! that is established, is documented where it is converted: curves in `curvature.rs`,
//! rotation and the change of frame in `panel.rs`, stitch direction in `convert.rs`.
//!
//! Each panel becomes a `Panel` whose outline edges are the file's edges in the file's
//! order, so a seam's edge index is the file's. An edge listed end to start (the loop
//! `[0, 1], [2, 1], ...`) is turned round, its curve with it, and the seams on it keep
//! their meaning. A panel drawn clockwise (GarmentCode's back panels, whose outside faces
//! -z of their own frame) is mirrored in x with its placement turned to match, so that
//! every outline runs counter-clockwise with the outside towards +z as our `Placement`
//! has it; its 3D points are unchanged. Edges get no names (GarmentCode's `label`s are not unique), holes
//! stay empty (the format has none), the grain is the panel's vertical (GarmentCode has
//! no grain line), and the fabric is the garment's.

mod schema;
mod curvature;
mod panel;
mod convert;

use std::path::Path;

use crate::pattern::{Pattern, PatternError};
use cloth_core::math::Vec3;

/// How a GarmentCode file is placed in our world.
///
/// GarmentCode's world is y-up in centimetres, the body facing +z, its feet on y = 0:
/// the body program puts the waist at `height - head_l - waist_line` above y = 0
/// (assets/body_measurments/body_params.py `eval_dependencies`, `_waist_level`), the
/// panels are translated to that level (e.g. assets/Patterns/flare_skirt_specification.json:
/// waistband at y = 108.8 cm for the mean body of assets/bodies/mean_all_tpose.yaml,
/// 172 cm tall), and its body mesh assets/bodies/mean_all.obj has the top of the head at
/// y = 1.72 m and the face at +z. Ours is z-up in metres, the body facing -y, the floor
/// at z = 0, so a GarmentCode point `(x, y, z)` is ours at `(x, -z, y) / units_in_meter`
/// plus `offset`: with a zero offset a GarmentCode garment lands on a body standing on
/// our floor, centred on the z axis.
///
/// Garment-Pattern-Generator's datasets were simulated around SMPL bodies whose origin is
/// near the pelvis, not at the feet (its skirt_2_panels.json puts the skirt's waist at
/// y = -5 cm), so their garments need an `offset` of about +1 m in z (the pelvis height
/// of the body they are draped on).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImportOptions {
    /// Added to every panel's translation after the change of frame, in metres.
    pub offset: Vec3,
}

/// Reads a GarmentCode specification from `text`; `file` names it in errors and gives the
/// pattern its name (the file stem without `_specification`, or the folder's name for
/// GarmentCode's generic `specification.json`). The result has passed
/// [`Pattern::validate`].
pub fn from_json_str(text: &str, file: &str, options: &ImportOptions) -> Result<Pattern, PatternError> {
    let spec: schema::Spec = serde_json::from_str(text).map_err(|e| parse_error(file, &e))?;
    convert::pattern(spec, pattern_name(file), file, options)
}

/// Reads the GarmentCode specification at `path`.
pub fn from_path(path: &Path, options: &ImportOptions) -> Result<Pattern, PatternError> {
    let text = std::fs::read_to_string(path).map_err(|source| PatternError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    from_json_str(&text, &path.display().to_string(), options)
}

/// "line 3, column 7: expected `,` or `}`": serde_json's message with its position first.
fn parse_error(file: &str, e: &serde_json::Error) -> PatternError {
    let text = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    let message = text.strip_suffix(&suffix).unwrap_or(&text);
    PatternError::Parse {
        file: file.into(),
        message: format!("line {}, column {}: {message}", e.line(), e.column()),
    }
}

/// The name GarmentCode gives the pattern in `file` (pygarment/pattern/core.py
/// `BasicPattern.name_from_path`): the file stem without `_specification`, or the folder's
/// name for its generic `specification.json`.
pub fn pattern_name(file: &str) -> String {
    let path = Path::new(file);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or(file);
    let name = stem.strip_suffix("_specification").unwrap_or(stem);
    if ["specification", "template", "prediction"].contains(&name) {
        if let Some(folder) = path.parent().and_then(Path::file_name).and_then(|s| s.to_str()) {
            return folder.to_string();
        }
    }
    name.to_string()
}
