//! Our TOML pattern format. Lengths are in the file's `units` (centimetres unless it
//! says otherwise); angles in degrees.
//!
//! ```toml
//! name = "straight skirt"
//! units = "cm"
//!
//! [[panels]]
//! name = "front"
//! grain = [0, 1]                      # the warp runs along the panel's y
//! dresses = "legs"                    # or "torso", "arms"; legs pass thin parts sewn
//! # Each edge is given by its start; it ends where the next one starts.
//! outline = [
//!     { start = [-26, 0], name = "hem" },
//!     { start = [26, 0], name = "right" },
//!     { start = [19, 60], name = "waist", quadratic = [0, 62] },
//!     { start = [-19, 60], name = "left" },
//! ]
//! placement = { rotation = [90, 0, 0], translation = [0, -14, 40], wrap = { radius = 16 } }
//!
//! [[seams]]
//! a = { panel = "front", edge = "right" }
//! b = { panel = "back", edge = "left" }
//! orientation = "opposite"            # or "same", or "auto"
//!
//! [[attachments]]                     # the waist may rise but not sink below where placed
//! panel = "front"
//! edge = "waist"
//! direction = [0, 0, 1]               # the way it is free to move, in the world (z up)
//! ```

use super::{
    AttachedEdge, BodyPart, Curve, Edge, EdgeRef, Panel, Pattern, PatternError, Placement, Point2, Seam,
    SeamOrientation, Wrap,
};
use cloth_core::math::Vec3;
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PatternRecord {
    #[serde(default)]
    name: String,
    #[serde(default)]
    units: Units,
    panels: Vec<PanelRecord>,
    #[serde(default)]
    seams: Vec<SeamRecord>,
    #[serde(default)]
    attachments: Vec<AttachmentRecord>,
}

#[derive(Deserialize, Default, Clone, Copy)]
#[serde(rename_all = "lowercase")]
enum Units {
    #[default]
    Cm,
    Mm,
    M,
}

impl Units {
    fn metres(self) -> f64 {
        match self {
            Units::Cm => 0.01,
            Units::Mm => 0.001,
            Units::M => 1.0,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PanelRecord {
    name: String,
    outline: Vec<EdgeRecord>,
    #[serde(default)]
    holes: Vec<Vec<EdgeRecord>>,
    #[serde(default = "default_grain")]
    grain: [f64; 2],
    fabric: Option<String>,
    #[serde(default)]
    placement: PlacementRecord,
    dresses: Option<BodyPart>,
}

fn default_grain() -> [f64; 2] {
    [0.0, 1.0]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EdgeRecord {
    start: [f64; 2],
    name: Option<String>,
    quadratic: Option<[f64; 2]>,
    cubic: Option<[[f64; 2]; 2]>,
    arc: Option<ArcRecord>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ArcRecord {
    radius: f64,
    #[serde(default)]
    large: bool,
    #[serde(default = "yes")]
    ccw: bool,
}

fn yes() -> bool {
    true
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct PlacementRecord {
    #[serde(default)]
    rotation: [f64; 3],
    #[serde(default)]
    translation: [f64; 3],
    wrap: Option<WrapRecord>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WrapRecord {
    radius: f64,
    #[serde(default)]
    centre: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SeamRecord {
    a: SideRecord,
    b: SideRecord,
    #[serde(default)]
    orientation: OrientationRecord,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SideRecord {
    panel: String,
    edge: EdgeRef,
}

/// An edge held on one side of where it is placed, free to move along `direction` (in
/// the world, z up).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AttachmentRecord {
    panel: String,
    edge: EdgeRef,
    direction: [f64; 3],
}

#[derive(Deserialize, Default)]
#[serde(rename_all = "lowercase")]
enum OrientationRecord {
    #[default]
    Opposite,
    Same,
    Auto,
}

impl Pattern {
    /// Reads a pattern file in our TOML format (see the module documentation) and
    /// validates it.
    pub fn from_toml_path(path: &Path) -> Result<Pattern, PatternError> {
        let text = std::fs::read_to_string(path).map_err(|source| PatternError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_toml_str(&text, &path.display().to_string())
    }

    /// Parses and validates a pattern; `file` names the source in errors.
    pub fn from_toml_str(text: &str, file: &str) -> Result<Pattern, PatternError> {
        let record: PatternRecord = toml::from_str(text).map_err(|e| PatternError::Parse {
            file: file.into(),
            message: e.to_string(),
        })?;
        let scale = record.units.metres();
        let point = |p: [f64; 2]| Point2::new(p[0], p[1]) * scale;
        let edges = |records: &[EdgeRecord], panel: &str| -> Result<Vec<Edge>, PatternError> {
            let n = records.len();
            (0..n)
                .map(|k| {
                    let r = &records[k];
                    let curve = match (r.quadratic, r.cubic, &r.arc) {
                        (None, None, None) => Curve::Line,
                        (Some(c), None, None) => Curve::Quadratic { control: point(c) },
                        (None, Some([c, d]), None) => Curve::Cubic {
                            control: [point(c), point(d)],
                        },
                        (None, None, Some(a)) => Curve::Arc {
                            radius: a.radius * scale,
                            large: a.large,
                            ccw: a.ccw,
                        },
                        _ => {
                            return Err(PatternError::panel(
                                file,
                                panel,
                                Some(r.name.clone().unwrap_or_else(|| k.to_string())),
                                "gives more than one of quadratic, cubic and arc",
                            ))
                        }
                    };
                    Ok(Edge {
                        name: r.name.clone(),
                        start: point(r.start),
                        end: point(records[(k + 1) % n].start),
                        curve,
                    })
                })
                .collect()
        };
        let mut panels = Vec::with_capacity(record.panels.len());
        for p in &record.panels {
            let pl = &p.placement;
            let mut placement =
                Placement::from_euler_degrees(pl.rotation, Vec3::from(pl.translation) * scale);
            placement.wrap = pl.wrap.as_ref().map(|w| Wrap {
                radius: w.radius * scale,
                centre: w.centre * scale,
            });
            panels.push(Panel {
                name: p.name.clone(),
                outline: edges(&p.outline, &p.name)?,
                holes: p
                    .holes
                    .iter()
                    .map(|h| edges(h, &p.name))
                    .collect::<Result<_, _>>()?,
                grain: Point2::new(p.grain[0], p.grain[1]),
                fabric: p.fabric.clone(),
                placement,
                dresses: p.dresses,
            });
        }
        let mut pattern = Pattern {
            name: record.name,
            panels,
            seams: Vec::with_capacity(record.seams.len()),
            attachments: Vec::new(),
        };
        for (s, seam) in record.seams.iter().enumerate() {
            let side = |r: &SideRecord| {
                pattern
                    .find_edge(&r.panel, &r.edge)
                    .map_err(|reason| PatternError::seam(file, s, reason))
            };
            let (a, b) = (side(&seam.a)?, side(&seam.b)?);
            let orientation = match seam.orientation {
                OrientationRecord::Opposite => SeamOrientation::Opposite,
                OrientationRecord::Same => SeamOrientation::Same,
                OrientationRecord::Auto => SeamOrientation::Auto,
            };
            pattern.seams.push(Seam { a, b, orientation });
        }
        for (k, attached) in record.attachments.iter().enumerate() {
            let edge = pattern
                .find_edge(&attached.panel, &attached.edge)
                .map_err(|reason| PatternError::Pattern {
                    file: file.into(),
                    reason: format!("attachment {k}: {reason}"),
                })?;
            let direction = Vec3::from(attached.direction)
                .try_normalize(1e-12)
                .filter(|d| d.iter().all(|c| c.is_finite()))
                .ok_or_else(|| PatternError::Pattern {
                    file: file.into(),
                    reason: format!("attachment {k}: the direction is not a direction (zero or not finite)"),
                })?;
            pattern.attachments.push(AttachedEdge { edge, direction });
        }
        pattern.validate(file)?;
        Ok(pattern)
    }
}
