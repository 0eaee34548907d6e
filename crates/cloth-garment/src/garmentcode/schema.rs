//! The records of a GarmentCode specification as the file spells them, read by serde so
//! that a syntax or schema error carries the line and column where it was found.
//!
//! Two records need hand-written readers: the panel map, because its order in the file is
//! the panel order when there is no `panel_order` (serde_json's `preserve_order` is off,
//! so a `Map` would come back sorted), and a stitch, which is a JSON array of two sides
//! and an optional `"right_wrong"` tag rather than an object.

use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use serde_json::Value;
use std::fmt;

/// The whole file. `parameters`, `parameter_order` and any other key are ignored: they
/// describe how GarmentCode varied the pattern, not the pattern.
#[derive(Debug, Deserialize)]
pub(super) struct Spec {
    pub pattern: PatternRecord,
    /// GarmentCode's loader reads this block unconditionally ("mandatory part",
    /// pygarment/pattern/core.py `reloadJSON`), so a file without it is not one of its.
    pub properties: Properties,
}

#[derive(Debug, Deserialize)]
pub(super) struct PatternRecord {
    pub panels: Panels,
    /// GarmentCode's box-mesh loader accepts a pattern without stitches.
    #[serde(default)]
    pub stitches: Vec<Stitch>,
    pub panel_order: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
pub(super) struct Properties {
    /// Missing means relative, the form GarmentCode writes.
    pub curvature_coords: Option<CurvatureCoords>,
    /// Missing means centimetres: GarmentCode then warns and does not rescale.
    pub units_in_meter: Option<f64>,
    #[serde(default)]
    pub normalize_panel_translation: bool,
    /// True when the edge loops follow GarmentCode's orientation convention (see
    /// `convert::stitch_orientation`).
    #[serde(default)]
    pub normalized_edge_loops: bool,
}

/// How curve control points are given: in the edge's own frame, or as panel points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum CurvatureCoords {
    Relative,
    Absolute,
}

#[derive(Debug, Deserialize)]
pub(super) struct PanelRecord {
    /// Missing means zero, as the Maya-era loader set it (Garment-Pattern-Generator,
    /// packages/mayaqltools/mayascene.py `_set_panel_3D_attr`).
    #[serde(default)]
    pub translation: [f64; 3],
    #[serde(default)]
    pub rotation: [f64; 3],
    pub vertices: Vec<[f64; 2]>,
    pub edges: Vec<EdgeRecord>,
    /// What the panel dresses: "body", "leg" or "arm" (others are kept as nothing).
    pub label: Option<String>,
}

#[derive(Debug, Deserialize)]
pub(super) struct EdgeRecord {
    pub endpoints: [usize; 2],
    /// Kept as JSON: its two forms (a bare `[x, y]` and `{type, params}`) are told apart
    /// in `curvature.rs`, which can then name the panel and edge in its errors.
    pub curvature: Option<Value>,
    /// What GarmentCode's simulator does with the edge: `lower_interface`,
    /// `strapless_top`, `right_collar` and `left_collar` are held (see
    /// `convert::attachment_direction`); others name it for segmentation only.
    pub label: Option<String>,
}

/// The panels in file order.
#[derive(Debug)]
pub(super) struct Panels(pub Vec<(String, PanelRecord)>);

impl<'de> Deserialize<'de> for Panels {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct InOrder;
        impl<'de> Visitor<'de> for InOrder {
            type Value = Panels;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a map from panel names to panels")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Panels, A::Error> {
                let mut panels: Vec<(String, PanelRecord)> = Vec::new();
                while let Some(name) = map.next_key::<String>()? {
                    if panels.iter().any(|(n, _)| *n == name) {
                        return Err(de::Error::custom(format!("panel '{name}' is defined twice")));
                    }
                    let record = map.next_value()?;
                    panels.push((name, record));
                }
                Ok(Panels(panels))
            }
        }
        deserializer.deserialize_map(InOrder)
    }
}

/// One side of a stitch: an edge by its index in the panel's edge list.
#[derive(Debug, Deserialize)]
pub(super) struct Side {
    pub panel: String,
    pub edge: usize,
}

/// `[side, side]` or `[side, side, tag]`.
#[derive(Debug)]
pub(super) struct Stitch {
    pub sides: [Side; 2],
    pub tag: Option<String>,
}

impl<'de> Deserialize<'de> for Stitch {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Sides;
        impl<'de> Visitor<'de> for Sides {
            type Value = Stitch;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a stitch: [{\"panel\": name, \"edge\": index}, {\"panel\": name, \"edge\": index}] \
                     with an optional \"right_wrong\" after the two sides",
                )
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Stitch, A::Error> {
                let a = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(0, &self))?;
                let b = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(1, &self))?;
                let tag = seq.next_element()?;
                if seq.next_element::<IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Stitch { sides: [a, b], tag })
            }
        }
        deserializer.deserialize_seq(Sides)
    }
}
