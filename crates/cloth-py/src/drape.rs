//! What `cloth.batch.drape` needs of the library: the patterns a batch drapes and their
//! scenes, and the summary `cloth drape` writes, so that both write the same. Private to
//! the package (`cloth.batch.drape` is the public face).

use crate::errors::input;
use cloth::drape::{find_patterns, write_summary, DrapeRequest, PatternInput, SummaryEntry};
use cloth::scene_file::UpAxis;
use pyo3::prelude::*;
use std::path::PathBuf;

/// The patterns named by `inputs` (files, or folders searched for `.toml` and `.json`
/// patterns) as `(name, path, scene)`: the folder name its outputs go under, the pattern
/// file, and the text of the scene that drapes it on `body` (as `cloth drape` writes it
/// beside the outputs), its OBJ and PLY written `up_axis` up. ValueError for a missing
/// input, a folder without patterns, two patterns of one name, an unknown fabric, a bad
/// edge length or minimum thickness.
#[pyfunction(name = "_drape_scenes")]
#[pyo3(signature = (inputs, body, *, body_up_axis = None, fabric = "cotton_poplin", edge_length = 0.015, min_thickness = None, up_axis = None))]
pub fn drape_scenes(
    inputs: Vec<PathBuf>,
    body: PathBuf,
    body_up_axis: Option<&str>,
    fabric: &str,
    edge_length: f64,
    min_thickness: Option<f64>,
    up_axis: Option<&str>,
) -> PyResult<Vec<(String, String, String)>> {
    if !(edge_length.is_finite() && edge_length > 0.0) {
        return Err(input(format!(
            "edge_length {edge_length} must be a positive length in m"
        )));
    }
    let body_min_thickness =
        cloth::drape::body_min_thickness(min_thickness.unwrap_or(cloth::drape::DEFAULT_BODY_MIN_THICKNESS))
            .map_err(|e| input(format!("min_thickness {e}")))?;
    cloth::presets::FabricLibrary::builtin()
        .fabric(fabric)
        .map_err(input)?;
    let body_up_axis: Option<UpAxis> = body_up_axis.map(crate::convert::up_axis).transpose()?;
    let up_axis: Option<UpAxis> = up_axis.map(crate::convert::up_axis).transpose()?;
    let request = DrapeRequest {
        body: std::path::absolute(&body).map_err(input)?,
        body_up_axis,
        fabric: fabric.to_string(),
        edge_length,
        body_min_thickness,
        up_axis,
    };
    let patterns = find_patterns(&inputs).map_err(input)?;
    Ok(patterns
        .iter()
        .map(|p| {
            (
                p.name.clone(),
                p.path.display().to_string(),
                request.scene_toml(p),
            )
        })
        .collect())
}

/// Writes `summary.json` and `summary.md` into `out_dir` for `runs`, each `(name, pattern,
/// skipped, error)`: the entry of a run is read from its folder's report; a run without
/// one (refused before it started) is a failure with `error`. Returns the entries as
/// JSON text.
#[pyfunction(name = "_write_drape_summary")]
pub fn write_drape_summary(
    out_dir: PathBuf,
    runs: Vec<(String, PathBuf, bool, Option<String>)>,
) -> PyResult<String> {
    let entries: Vec<SummaryEntry> = runs
        .into_iter()
        .map(|(name, pattern, skipped, error)| {
            let p = PatternInput { name, path: pattern };
            SummaryEntry::from_report(&p.name, &p.path, &out_dir.join(&p.name), skipped).unwrap_or_else(
                || {
                    SummaryEntry::refused(
                        &p.name,
                        &p.path,
                        error.unwrap_or_else(|| "no report was written".into()),
                        0.0,
                    )
                },
            )
        })
        .collect();
    write_summary(&out_dir, &entries)
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", out_dir.display())))?;
    Ok(serde_json::to_string(&entries).expect("entries serialise"))
}
