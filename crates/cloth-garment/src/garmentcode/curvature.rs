//! An edge's `curvature` record as one of our curves.
//!
//! The forms, as GarmentCode reads them (pygarment/meshgen/boxmeshgen.py `Edge.init_curve`):
//! - absent: a straight line;
//! - `[x, y]` (the original form, Garment-Pattern-Generator's datasets): the control point
//!   of a quadratic Bezier;
//! - `{"type": "quadratic", "params": [[x, y]]}` and `{"type": "cubic", "params": [[x, y],
//!   [x, y]]}`: Bezier control points;
//! - `{"type": "circle", "params": [radius, large_arc, right]}`: an SVG-style arc.
//!
//! Control points are "relative" by default: `x` runs along the edge from start (0) to end
//! (1) and `y` along the edge vector turned a quarter turn counter-clockwise, `(-e.y,
//! e.x)`, so `y > 0` is left of the direction of travel; both are fractions of the edge
//! length (pygarment/pattern/utils.py `rel_to_abs_2d`; the same formula is
//! Garment-Pattern-Generator's packages/pattern/core.py `_control_to_abs_coord`). With
//! `"curvature_coords": "absolute"` the legacy `[x, y]` is a point in the panel's own
//! coordinates (core.py `_normalize_template` converts it); GarmentCode never writes the
//! newer forms that way and its loader would fail on them, so we read their control points
//! as panel points too, the only meaning the word can have.
//!
//! The circle's `radius` is a length in the file's units. `large_arc` picks the longer of
//! the two arcs through the ends, and `right` is set when the arc bulges to the right of
//! the direction of travel (pygarment/garmentcode/edge.py `CircleEdge.as_radius_flag`:
//! `right = control_y < 0`). boxmeshgen hands `right` to svgpathtools as the sweep flag,
//! i.e. the angle increases from start to end: a counter-clockwise turn in the panel's
//! y-up plane, which is our `Curve::Arc::ccw`. GarmentCode's own flared skirt
//! (assets/Patterns/flare_skirt_specification.json) bears this out: its hem and waist
//! arcs, one with `right = 1` running left to right, the other with `right = 0` running
//! right to left, are concentric only when read this way.

use crate::pattern::{Curve, Point2};
use serde_json::Value;

use super::schema::CurvatureCoords;

/// The curve of an edge running from `a` to `b` as listed, both in the file's units; the
/// control points and radius it returns are multiplied by `scale` (file units to metres).
pub(super) fn curve(
    curvature: Option<&Value>,
    a: Point2,
    b: Point2,
    coords: CurvatureCoords,
    scale: f64,
) -> Result<Curve, String> {
    let Some(value) = curvature else {
        return Ok(Curve::Line);
    };
    // Where a control point given in the file lands in the panel, still in file units.
    let control = |p: Point2| match coords {
        CurvatureCoords::Relative => {
            let e = b - a;
            a + e * p.x + Point2::new(-e.y, e.x) * p.y
        }
        CurvatureCoords::Absolute => p,
    };
    match value {
        Value::Array(_) => {
            let p = point(value).ok_or("curvature must be [x, y] or {\"type\": ..., \"params\": ...}")?;
            Ok(Curve::Quadratic {
                control: control(p) * scale,
            })
        }
        Value::Object(map) => {
            let kind = map
                .get("type")
                .ok_or("curvature has no \"type\"")?
                .as_str()
                .ok_or("curvature \"type\" must be a string")?;
            let params = map
                .get("params")
                .ok_or_else(|| format!("{kind} curvature has no \"params\""))?;
            let points = |n: usize| -> Option<Vec<Point2>> {
                let list = params.as_array().filter(|l| l.len() == n)?;
                list.iter().map(point).collect()
            };
            match kind {
                "quadratic" => {
                    let p = points(1).ok_or("quadratic params must be [[x, y]]")?;
                    Ok(Curve::Quadratic {
                        control: control(p[0]) * scale,
                    })
                }
                "cubic" => {
                    let p = points(2).ok_or("cubic params must be [[x, y], [x, y]]")?;
                    Ok(Curve::Cubic {
                        control: [control(p[0]) * scale, control(p[1]) * scale],
                    })
                }
                "circle" => circle(params, scale),
                other => Err(format!(
                    "unknown curvature type '{other}' (GarmentCode writes quadratic, cubic or circle)"
                )),
            }
        }
        _ => Err("curvature must be [x, y] or {\"type\": ..., \"params\": ...}".into()),
    }
}

/// `[radius, large_arc, right]`, the flags as 0/1 (what GarmentCode writes) or booleans.
fn circle(params: &Value, scale: f64) -> Result<Curve, String> {
    const SHAPE: &str = "circle params must be [radius, large_arc, right]";
    let list = params.as_array().filter(|l| l.len() == 3).ok_or(SHAPE)?;
    let radius = list[0].as_f64().ok_or(SHAPE)?;
    let flag = |v: &Value| match v {
        Value::Bool(b) => Some(*b),
        Value::Number(n) => n.as_f64().map(|x| x != 0.0),
        _ => None,
    };
    let (large, right) = (flag(&list[1]).ok_or(SHAPE)?, flag(&list[2]).ok_or(SHAPE)?);
    let radius = radius * scale;
    if !(radius.is_finite() && radius > 0.0) {
        return Err(format!("circle radius {} must be positive and finite", list[0]));
    }
    Ok(Curve::Arc {
        radius,
        large,
        ccw: right,
    })
}

fn point(v: &Value) -> Option<Point2> {
    match v.as_array()?.as_slice() {
        [x, y] => Some(Point2::new(x.as_f64()?, y.as_f64()?)),
        _ => None,
    }
}

/// The same curve traversed from its end to its start: Bezier control points in reverse
/// order, an arc turning the other way (the same geometric points either way).
pub(super) fn reversed(curve: Curve) -> Curve {
    match curve {
        Curve::Cubic { control: [c, d] } => Curve::Cubic { control: [d, c] },
        Curve::Arc { radius, large, ccw } => Curve::Arc {
            radius,
            large,
            ccw: !ccw,
        },
        other => other,
    }
}
