//! One GarmentCode panel as our `Panel`: its outline in metres, chained into a closed loop,
//! and its placement moved from GarmentCode's world into ours.

use crate::pattern::{BodyPart, Curve, Edge, Panel, PatternError, Placement, Point2};
use cloth_core::math::Vec3;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};

use super::curvature;
use super::schema::{CurvatureCoords, PanelRecord};

/// What every panel of a file is converted with.
pub(super) struct Frame {
    /// File units to metres: `1 / units_in_meter`.
    pub scale: f64,
    pub offset: Vec3,
    pub coords: CurvatureCoords,
    /// The file's `normalize_panel_translation`.
    pub normalize_translation: bool,
}

/// The panel, and for each of its edges whether the file lists it end to start.
///
/// GarmentCode orients every loop counter-clockwise seen from outside the garment
/// (Garment-Pattern-Generator's Patterns/template_spec_with_comments.json: "Counterclockwise
/// tracing of vertices with edges defines the front of a panel (outside of the body)"), and
/// draws its back panels clockwise with no rotation, their outside towards -z of their own
/// frame (e.g. `skirt_back` in GarmentCode's assets/Patterns/flare_skirt_specification.json).
/// Our `Placement` has a panel's outside towards +z of its frame, and the welded garment
/// needs every panel's triangles wound the same way round, so a clockwise outline is
/// mirrored in x and its placement turned half round the panel's y axis: the same move
/// GarmentCode's loader makes (core.py `_normalize_edge_loop`), and the 3D points do not
/// change. Such a panel's 2D coordinates are the file's with x negated.
pub(super) fn panel(
    name: &str,
    record: &PanelRecord,
    frame: &Frame,
    file: &str,
) -> Result<(Panel, Vec<bool>), PatternError> {
    let fail = |edge: Option<usize>, reason: String| {
        PatternError::panel(file, name, edge.map(|k| k.to_string()), reason)
    };
    let finite = |v: &[f64]| v.iter().all(|c| (c * frame.scale).is_finite());
    if let Some(k) = record.vertices.iter().position(|v| !finite(v)) {
        return Err(fail(None, format!("vertex {k} is not a finite point")));
    }
    if !finite(&record.translation) || !record.rotation.iter().all(|c| c.is_finite()) {
        return Err(fail(None, "translation or rotation is not finite".into()));
    }
    let vertices: Vec<Point2> = record.vertices.iter().map(|&[x, y]| Point2::new(x, y)).collect();
    let ends: Vec<[usize; 2]> = record.edges.iter().map(|e| e.endpoints).collect();
    for (k, &[a, b]) in ends.iter().enumerate() {
        if let Some(bad) = [a, b].into_iter().find(|&i| i >= vertices.len()) {
            return Err(fail(
                Some(k),
                format!(
                    "endpoint {bad} is out of range: the panel has {} vertices",
                    vertices.len()
                ),
            ));
        }
        if a == b {
            return Err(fail(Some(k), format!("starts and ends at vertex {a}")));
        }
    }
    let reversed = chain(&ends, &vertices).map_err(|(k, reason)| fail(Some(k), reason))?;

    let mut outline = Vec::with_capacity(ends.len());
    for (k, (edge, &flip)) in record.edges.iter().zip(&reversed).enumerate() {
        let [a, b] = edge.endpoints.map(|i| vertices[i]);
        let curve = curvature::curve(edge.curvature.as_ref(), a, b, frame.coords, frame.scale)
            .map_err(|reason| fail(Some(k), reason))?;
        let (a, b) = (a * frame.scale, b * frame.scale);
        outline.push(match flip {
            false => Edge {
                curve,
                ..Edge::line(a, b)
            },
            true => Edge {
                curve: curvature::reversed(curve),
                ..Edge::line(b, a)
            },
        });
    }
    let mirrored = signed_area(&outline) < 0.0;
    if mirrored {
        outline = outline.into_iter().map(mirror).collect();
    }
    let panel = Panel {
        name: name.to_string(),
        outline,
        holes: Vec::new(),
        // GarmentCode has no grain line; the panel's vertical is the usual one for the
        // way its panels are drawn (waist or shoulder up, hem down). Mirroring keeps it.
        grain: Point2::new(0.0, 1.0),
        fabric: None,
        placement: placement(record, &vertices, mirrored, frame),
        dresses: match record.label.as_deref() {
            Some("body") => Some(BodyPart::Torso),
            Some("leg") => Some(BodyPart::Legs),
            Some("arm") => Some(BodyPart::Arms),
            _ => None,
        },
    };
    Ok((panel, reversed))
}

/// The signed area of the outline's polyline (curves at 16 pieces, enough for the sign):
/// positive when the loop runs counter-clockwise.
fn signed_area(outline: &[Edge]) -> f64 {
    let points: Vec<Point2> = outline
        .iter()
        .flat_map(|e| {
            let pieces = if matches!(e.curve, Curve::Line) { 1 } else { 16 };
            let mut p = e.resample(pieces);
            p.pop();
            p
        })
        .collect();
    let n = points.len();
    0.5 * (0..n).map(|i| points[i].perp(&points[(i + 1) % n])).sum::<f64>()
}

/// The edge reflected in the panel's y axis: its ends, control points and turning sense.
fn mirror(edge: Edge) -> Edge {
    let m = |p: Point2| Point2::new(-p.x, p.y);
    let curve = match edge.curve {
        Curve::Line => Curve::Line,
        Curve::Quadratic { control } => Curve::Quadratic { control: m(control) },
        Curve::Cubic { control: [c, d] } => Curve::Cubic {
            control: [m(c), m(d)],
        },
        Curve::Arc { radius, large, ccw } => Curve::Arc {
            radius,
            large,
            ccw: !ccw,
        },
    };
    Edge {
        start: m(edge.start),
        end: m(edge.end),
        curve,
        ..edge
    }
}

/// Which edges run end to start when the list is followed as a closed loop, or the edge
/// where the loop breaks and why. Two vertices are the same point when they are the same
/// index or have the same coordinates (GarmentCode's panel assembly joins edges by
/// coordinates too).
fn chain(ends: &[[usize; 2]], vertices: &[Point2]) -> Result<Vec<bool>, (usize, String)> {
    let n = ends.len();
    if n < 2 {
        return Err((
            0,
            format!("the panel has {n} edge(s); an outline needs at least two"),
        ));
    }
    let same = |i: usize, j: usize| i == j || vertices[i] == vertices[j];
    // The first edge runs towards the vertex it shares with the second (forwards when
    // both ends are shared, as in a loop of two edges).
    let [a, b] = ends[0];
    let touches = |v: usize| ends[1].iter().any(|&w| same(v, w));
    let first = if touches(b) {
        false
    } else if touches(a) {
        true
    } else {
        return Err((
            1,
            format!(
                "joins vertices {} and {}, which edge 0 does not touch: the edges do not form a loop",
                ends[1][0], ends[1][1]
            ),
        ));
    };
    let mut reversed = vec![first];
    let mut at = if first { a } else { b };
    for (k, &[a, b]) in ends.iter().enumerate().skip(1) {
        let flip = if same(a, at) {
            false
        } else if same(b, at) {
            true
        } else {
            return Err((
                k,
                format!(
                    "joins vertices {a} and {b}, but edge {} ends at vertex {at}: the edges do not form a loop",
                    k - 1
                ),
            ));
        };
        reversed.push(flip);
        at = if flip { a } else { b };
    }
    let start = if first { b } else { a };
    if !same(at, start) {
        return Err((
            n - 1,
            format!("ends at vertex {at}, but edge 0 starts at vertex {start}: the outline is not closed"),
        ));
    }
    Ok(reversed)
}

/// GarmentCode places a panel's 2D point `p` (file units) at `R (p, 0) + t`, with `R` from
/// the `rotation` Euler angles in degrees as `Rz(z) Ry(y) Rx(x)`: x applied first, about
/// fixed axes (pygarment/pattern/rotation.py `euler_xyz_to_R`, used by core.py
/// `_point_in_3D` and boxmeshgen's `Panel.rot_trans_vertex`; Maya's default rotate order,
/// which the Maya-era loader relied on). nalgebra's `from_euler_angles(x, y, z)` is the
/// same product. Its world is y-up, the body facing +z, in file units; ours is z-up, the
/// body facing -y, in metres, so a point `(x, y, z)` of its world is ours at
/// `(x, -z, y) / units_in_meter + offset`: a quarter turn about x after the scaling.
fn placement(record: &PanelRecord, vertices: &[Point2], mirrored: bool, frame: &Frame) -> Placement {
    let [x, y, z] = record.rotation.map(f64::to_radians);
    let rotation = Rotation3::from_euler_angles(x, y, z);
    let mut translation = Vec3::from(record.translation);
    if frame.normalize_translation && !vertices.is_empty() {
        // GarmentCode's loader moves the vertices' mean to the panel origin and adds that
        // mean to the translation without rotating it (core.py `_normalize_template`), so
        // a rotated panel ends up elsewhere than its raw numbers say. Keeping our vertices
        // where they are, the same world points come from t + o - R o.
        let mean = vertices.iter().sum::<Point2>() / vertices.len() as f64;
        let o = Vec3::new(mean.x, mean.y, 0.0);
        translation += o - rotation * o;
    }
    #[rustfmt::skip]
    let to_ours = Rotation3::from_matrix_unchecked(Matrix3::new(
        1.0, 0.0, 0.0,
        0.0, 0.0, -1.0,
        0.0, 1.0, 0.0,
    ));
    // A mirrored outline (x -> -x) lands on the same points when the panel is first turned
    // half round its own y axis.
    let unmirror = Rotation3::from_matrix_unchecked(Matrix3::from_diagonal(&Vec3::new(-1.0, 1.0, -1.0)));
    let rotation = if mirrored { rotation * unmirror } else { rotation };
    Placement {
        rotation: UnitQuaternion::from_rotation_matrix(&(to_ours * rotation)),
        translation: to_ours * translation * frame.scale + frame.offset,
        wrap: None,
    }
}
