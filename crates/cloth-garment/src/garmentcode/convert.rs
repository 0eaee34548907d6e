//! A parsed specification as our `Pattern`: units, panel order, panels and stitches.

use std::collections::HashMap;

use crate::pattern::{AttachedEdge, Pattern, PatternError, Seam, SeamOrientation, SeamSide};
use cloth_core::math::Vec3;

use super::panel::{panel, Frame};
use super::schema::{CurvatureCoords, PanelRecord, Spec, Stitch};
use super::ImportOptions;

/// GarmentCode's units when a file does not say: centimetres.
const DEFAULT_UNITS_IN_METER: f64 = 100.0;

/// The one stitch tag GarmentCode knows (pygarment/garmentcode/connector.py
/// `StitchingRule.assembly`).
const RIGHT_WRONG: &str = "right_wrong";

pub(super) fn pattern(
    spec: Spec,
    name: String,
    file: &str,
    options: &ImportOptions,
) -> Result<Pattern, PatternError> {
    let properties = &spec.properties;
    let units = properties.units_in_meter.unwrap_or(DEFAULT_UNITS_IN_METER);
    if !(units.is_finite() && units > 0.0 && units.recip().is_finite()) {
        return Err(PatternError::Pattern {
            file: file.into(),
            reason: format!(
                "properties.units_in_meter is {units}: it must be a positive number (100 for centimetres)"
            ),
        });
    }
    let frame = Frame {
        scale: units.recip(),
        offset: options.offset,
        coords: properties.curvature_coords.unwrap_or(CurvatureCoords::Relative),
        normalize_translation: properties.normalize_panel_translation,
    };
    let records = ordered(spec.pattern.panels.0, spec.pattern.panel_order, file)?;
    let mut panels = Vec::with_capacity(records.len());
    let mut reversed = Vec::with_capacity(records.len());
    for (name, record) in &records {
        let (p, flips) = panel(name, record, &frame, file)?;
        panels.push(p);
        reversed.push(flips);
    }
    let index: HashMap<&str, usize> = records
        .iter()
        .enumerate()
        .map(|(k, (n, _))| (n.as_str(), k))
        .collect();
    let seams = spec
        .pattern
        .stitches
        .iter()
        .enumerate()
        .map(|(s, stitch)| {
            seam(
                stitch,
                &index,
                &records,
                &reversed,
                properties.normalized_edge_loops,
            )
            .map_err(|reason| PatternError::seam(file, s, reason))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let attachments = records
        .iter()
        .enumerate()
        .flat_map(|(panel, (_, record))| {
            record.edges.iter().enumerate().filter_map(move |(edge, e)| {
                let direction = attachment_direction(e.label.as_deref()?)?;
                Some(AttachedEdge {
                    edge: SeamSide { panel, edge },
                    direction,
                })
            })
        })
        .collect();
    let pattern = Pattern {
        name,
        panels,
        seams,
        attachments,
    };
    pattern.validate(file)?;
    Ok(pattern)
}

/// The edge labels GarmentCode's simulator holds, and the way each is free to move, in
/// our frame (GarmentCode's up, +y, is our +z; its +x is ours). Its simulator
/// (pygarment/meshgen/garment.py `_add_attachment_labels`, with the one-sided constraint of
/// its Warp fork) keeps a lower garment's waist (`lower_interface`) and a strapless top's
/// upper edge (`strapless_top`) from sinking, and the right and left halves of a neckline
/// (`right_collar` on -x, `left_collar` on +x) from sliding outwards. It puts the planes
/// at levels taken from the body's measurements; the sewing puts them by where the
/// pattern places each edge (see `sewing::attachments_as_placed`).
fn attachment_direction(label: &str) -> Option<Vec3> {
    match label {
        "lower_interface" | "strapless_top" => Some(Vec3::z()),
        "right_collar" => Some(Vec3::x()),
        "left_collar" => Some(-Vec3::x()),
        _ => None,
    }
}

/// The panels in `panel_order` when the file has one (it must name each panel once),
/// else in file order. The order does not change the physics; it keeps panel indices
/// the same from run to run.
fn ordered(
    mut panels: Vec<(String, PanelRecord)>,
    order: Option<Vec<String>>,
    file: &str,
) -> Result<Vec<(String, PanelRecord)>, PatternError> {
    let Some(order) = order else {
        return Ok(panels);
    };
    let fail = |reason: String| PatternError::Pattern {
        file: file.into(),
        reason,
    };
    let mut out = Vec::with_capacity(panels.len());
    for name in order {
        match panels.iter().position(|(n, _)| *n == name) {
            Some(k) => out.push(panels.swap_remove(k)),
            None if out.iter().any(|(n, _)| *n == name) => {
                return Err(fail(format!("panel_order lists '{name}' twice")))
            }
            None => {
                return Err(fail(format!(
                    "panel_order names '{name}', which is not among the panels"
                )))
            }
        }
    }
    if let Some((name, _)) = panels.first() {
        return Err(fail(format!("panel '{name}' is missing from panel_order")));
    }
    Ok(out)
}

/// A stitch as a seam between outline edges, with the edge indices of the file (the
/// importer reverses edges in place, it never reorders them).
fn seam(
    stitch: &Stitch,
    index: &HashMap<&str, usize>,
    records: &[(String, PanelRecord)],
    reversed: &[Vec<bool>],
    normalized_loops: bool,
) -> Result<Seam, String> {
    let side = |k: usize| -> Result<SeamSide, String> {
        let side = &stitch.sides[k];
        let panel = *index.get(side.panel.as_str()).ok_or_else(|| {
            format!(
                "side {k} names panel '{}', which the pattern does not have",
                side.panel
            )
        })?;
        let count = records[panel].1.edges.len();
        if side.edge >= count {
            return Err(format!(
                "side {k}: panel '{}' has no edge {} (it has {count} edges, 0 to {})",
                side.panel,
                side.edge,
                count.saturating_sub(1)
            ));
        }
        Ok(SeamSide {
            panel,
            edge: side.edge,
        })
    };
    let (a, b) = (side(0)?, side(1)?);
    // GarmentCode's own writer chains every loop head to tail (pygarment/garmentcode/
    // panel.py `Panel.assembly`), so an edge listed end to start comes from a file made
    // elsewhere, whose edge directions carry no stitching convention: pair by distance.
    let listed_backwards = reversed[a.panel][a.edge] || reversed[b.panel][b.edge];
    let orientation = if listed_backwards {
        SeamOrientation::Auto
    } else {
        stitch_orientation(stitch.tag.as_deref(), normalized_loops)
    };
    Ok(Seam { a, b, orientation })
}

/// GarmentCode's box mesh pairs the end of the first edge with the start of the second
/// (`Seam.swap = True`, "connects right side to the right side of fabric") unless the
/// stitch carries `"right_wrong"`, which pairs start with start (pygarment/meshgen/
/// boxmeshgen.py `read_stitches` and `_swap_stitch_ranges`). That rule rests on loops
/// that run counter-clockwise seen from outside the garment, which the file promises with
/// `normalized_edge_loops: true` (GarmentCode's loader would otherwise re-orient them
/// first). Without that promise (older files; the Maya-era simulator Qualoth chose the
/// pairing itself) the nearer pairing is the safe reading. Other tags are ignored, as
/// GarmentCode ignores them.
fn stitch_orientation(tag: Option<&str>, normalized_loops: bool) -> SeamOrientation {
    if tag == Some(RIGHT_WRONG) {
        SeamOrientation::Same
    } else if normalized_loops {
        SeamOrientation::Opposite
    } else {
        SeamOrientation::Auto
    }
}
