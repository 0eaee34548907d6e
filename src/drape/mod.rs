//! Draping many patterns on one body: what `cloth drape` and Python's
//! `cloth.batch.drape` do. Each pattern becomes a scene (written beside its outputs, so
//! `cloth run DIR/<name>/scene.toml` runs it again), runs into a folder of its own, and
//! one summary (`summary.json`, `summary.md`) lists how every pattern ended.

mod patterns;
mod summary;

pub use patterns::{find_patterns, PatternInput};
pub use summary::{write_summary, SummaryEntry, SUMMARY_JSON, SUMMARY_MD};

use crate::scene_file::{SceneFile, SceneFileError, UpAxis};
use std::path::{Path, PathBuf};

/// Written into a pattern's folder when its run finished: the request it finished, so a
/// later batch with the same request skips it.
pub const FINISHED_FILE: &str = "finished.json";

/// The thinnest the body's contact layer is made where it is flat, m (see
/// `cloth_collide::Body::with_thinned_layer`): a fabric's thickness and a half. Uniform at
/// the body's 3 mm, GarmentCode's close-fitting designs were stretched past 5 % by the
/// layer's own girth (rand_1_010 to 5.6 % p99, rand_1_100 to 5.5 %; 4.6 % and 4.7 % on
/// this one, with no edge through the body).
pub const DEFAULT_BODY_MIN_THICKNESS: f64 = 0.001;

/// The floor of the body's layer a batch asks for (see [`DEFAULT_BODY_MIN_THICKNESS`]),
/// as [`DrapeRequest::body_min_thickness`] holds it: `None` at the body's own thickness (a
/// uniform layer). Refused, saying why, unless positive and at most that thickness.
pub fn body_min_thickness(floor: f64) -> Result<Option<f64>, String> {
    let layer = cloth_collide::DEFAULT_THICKNESS;
    if !(floor > 0.0 && floor <= layer) {
        return Err(format!(
            "{floor} must be a positive length in m, at most the body's contact thickness ({layer} m)"
        ));
    }
    Ok((floor < layer).then_some(floor))
}

/// What to drape every pattern with.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DrapeRequest {
    /// The body mesh (absolute, as every run's scene names it).
    pub body: PathBuf,
    /// The body file's up axis (`None`: the format's own, y for glTF, z otherwise).
    pub body_up_axis: Option<UpAxis>,
    /// A fabric preset.
    pub fabric: String,
    /// Target edge length, m.
    pub edge_length: f64,
    /// The body's contact layer thinned where it is flat down to this, m (`None`: the
    /// body's thickness everywhere).
    pub body_min_thickness: Option<f64>,
    /// The up axis of the OBJ and PLY outputs (`None`: z, the engine's).
    #[serde(default)]
    pub up_axis: Option<UpAxis>,
}

/// Something wrong with the batch as a whole (not with one pattern).
#[derive(Debug, thiserror::Error)]
pub enum DrapeError {
    #[error("{0}")]
    Input(String),
    #[error("cannot read '{path}': {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

impl DrapeRequest {
    /// The scene that drapes `pattern`: a garment of it on the body, the outputs of
    /// `cloth run`.
    pub fn scene(&self, pattern: &PatternInput) -> Result<SceneFile, SceneFileError> {
        let text = self.scene_toml(pattern);
        SceneFile::from_toml_str(&text, &format!("the scene for {}", pattern.path.display()))
    }

    /// The scene as a TOML file's text.
    pub fn scene_toml(&self, pattern: &PatternInput) -> String {
        let mut body = toml::Table::new();
        body.insert("file".into(), self.body.display().to_string().into());
        let axis = |up| match up {
            UpAxis::Y => "y",
            UpAxis::Z => "z",
        };
        if let Some(up) = self.body_up_axis {
            body.insert("up_axis".into(), axis(up).into());
        }
        if let Some(floor) = self.body_min_thickness {
            body.insert("min_thickness".into(), floor.into());
        }
        let mut garment = toml::Table::new();
        garment.insert("pattern".into(), pattern.path.display().to_string().into());
        garment.insert("edge_length".into(), self.edge_length.into());
        let mut scene = toml::Table::new();
        scene.insert("name".into(), pattern.name.clone().into());
        scene.insert(
            "cloth".into(),
            toml::Value::Table([("garment".to_string(), garment.into())].into_iter().collect()),
        );
        scene.insert(
            "fabric".into(),
            toml::Value::Table(
                [("preset".to_string(), self.fabric.clone().into())]
                    .into_iter()
                    .collect(),
            ),
        );
        scene.insert("bodies".into(), toml::Value::Array(vec![body.into()]));
        if let Some(up) = self.up_axis {
            let output = [("up_axis".to_string(), axis(up).into())].into_iter().collect();
            scene.insert("output".into(), toml::Value::Table(output));
        }
        format!(
            "# Written by `cloth drape`: {} on {}.\n{}",
            pattern.path.display(),
            self.body.display(),
            toml::to_string(&scene).expect("a table of strings and numbers serialises")
        )
    }

    /// Whether `folder` holds a finished run of this request.
    pub fn finished_in(&self, folder: &Path) -> bool {
        std::fs::read_to_string(folder.join(FINISHED_FILE))
            .ok()
            .and_then(|text| serde_json::from_str::<DrapeRequest>(&text).ok())
            .is_some_and(|done| done == *self)
    }

    /// Marks `folder` as holding a finished run of this request.
    pub fn mark_finished(&self, folder: &Path) -> std::io::Result<()> {
        let text = serde_json::to_string_pretty(self).expect("a request serialises");
        std::fs::write(folder.join(FINISHED_FILE), text)
    }
}
