//! The torso: key sections at the landmarks, smooth sections between them, rings stacked
//! up the body and domed caps at the thigh and the neck.
//!
//! The key sections' proportions (depth to width, how much lies in front of the widest
//! points, how square the sides are) are our reading of average adult female sections, as
//! in body-scan atlases and dress-form catalogues: a waist about 0.74 as deep as wide, a
//! seat 0.68 with more of it behind, a bust 0.80 with more of it in front, a broad and
//! shallow section across the shoulder points. Their size comes from the measurements.

use cloth_core::math::Vec3;

use super::arclength::{cumulative, equal_steps};
use super::landmarks::{SHOULDER_DEPTH, SHOULDER_SHIFT};
use super::loft::{Cap, Loft};
use super::sections::{with_girth, with_girth_at_width, Section, PARAMETERS};
use super::spline::MonotoneCubic;
use super::{Landmarks, Measurements};

/// Girth of the form's bottom (upper thighs taken together, as a one-piece form is) as a
/// fraction of the hip girth.
const BOTTOM_GIRTH: f64 = 0.94;
/// Underbust girth between waist and bust: an average B-cup's underbust is some 12 cm
/// under the bust, about 0.45 of the way up from a 76 cm waist to a 92 cm bust.
const UNDERBUST_BLEND: f64 = 0.45;
/// Girth of the chest just under the arms as a fraction of the bust: the "high bust" is
/// some 5 cm under the bust for an average woman.
const ARMPIT_GIRTH: f64 = 0.95;
/// The armpit section may be at most this fraction of the shoulder width, so the form
/// widens from the armpit up to the shoulder points; unless the bust is wider still
/// (narrow shoulders, full bust), when it may be this fraction of the bust's width, so the
/// chest does not pinch in between bust and shoulders.
const ARMPIT_WIDTH: f64 = 0.85;
const ARMPIT_TO_BUST_WIDTH: f64 = 0.95;
/// Radius of the shoulder's rounded end and of the turn into the neck, as fractions of the
/// shoulder line's run from the neck to the shoulder point.
const SHOULDER_TIP: f64 = 0.1;
const NECK_FILLET: f64 = 0.06;
/// Key sections along the shoulder line between the shoulder point and the neck.
const SHOULDER_KNOTS: usize = 6;
/// Girth at the top of the neck stump as a fraction of the neck base's.
const NECK_TOP_GIRTH: f64 = 0.95;
/// Height of the domed caps as a fraction of the end section's smaller half-extent: low
/// enough to look like a cut-off form, round enough that cloth slides over the rim.
const CAP_HEIGHT: f64 = 0.2;
/// Samples per interval between key levels when measuring the side profile's length.
const PROFILE_SAMPLES: usize = 200;

/// How finely to ring the torso along its height.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Rings {
    /// Rings at most this far apart along the profile (m).
    Spacing(f64),
    /// About this many rings between the end rings.
    Count(usize),
}

/// A key level: a height and the section there.
struct Knot {
    z: f64,
    section: Section,
}

/// The torso's vertices and triangles (closed and outward by construction), and the ring
/// spacing used, which the arms take too.
pub(crate) struct TorsoMesh {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub spacing: f64,
}

pub(crate) fn torso(m: &Measurements, lm: &Landmarks, rings: Rings, segments: usize) -> TorsoMesh {
    let (knots, caps) = key_sections(m, lm, segments);
    let zs: Vec<f64> = knots.iter().map(|k| k.z).collect();
    let splines: Vec<MonotoneCubic> = (0..PARAMETERS)
        .map(|i| {
            MonotoneCubic::new(
                zs.clone(),
                knots.iter().map(|k| k.section.to_array()[i]).collect(),
            )
        })
        .collect();
    let section_at = |z: f64| Section::from_array(std::array::from_fn(|i| splines[i].at(z)));

    // The side profile (width, front and back against height) in each interval between key
    // levels: rings go evenly along its length, so the steep shoulder slope gets as many
    // rings per centimetre of surface as the nearly vertical waist.
    let profiles: Vec<Vec<[f64; 4]>> = zs
        .windows(2)
        .map(|w| {
            (0..=PROFILE_SAMPLES)
                .map(|i| {
                    let z = w[0] + (w[1] - w[0]) * i as f64 / PROFILE_SAMPLES as f64;
                    let s = section_at(z);
                    [z, s.half_width, s.front_y(), s.back_y()]
                })
                .collect()
        })
        .collect();
    let lengths: Vec<f64> = profiles.iter().map(|p| cumulative(p)[PROFILE_SAMPLES]).collect();
    let spacing = match rings {
        Rings::Spacing(s) => s,
        Rings::Count(n) => lengths.iter().sum::<f64>() / n as f64,
    };
    let mut heights = vec![zs[0]];
    for (profile, length) in profiles.iter().zip(lengths) {
        let steps = ((length / spacing - 1e-9).ceil() as usize).max(1);
        heights.extend(equal_steps(profile, steps)[1..].iter().map(|p| p[0]));
    }

    let mut loft = Loft::default();
    for z in heights {
        let ring = section_at(z).ring(segments);
        loft.push(ring.iter().map(|&[x, y]| Vec3::new(x, y, z)).collect());
    }
    let (vertices, triangles) = loft.close(
        Cap {
            axis: -Vec3::z(),
            height: caps.0,
        },
        Cap {
            axis: Vec3::z(),
            height: caps.1,
        },
        spacing,
    );
    TorsoMesh {
        vertices,
        triangles,
        spacing,
    }
}

/// A section of unit half-width with the given depth-to-width ratio, share of the depth
/// in front of the widest points, shift of the widest points backwards (as a fraction of
/// the depth), and exponents.
fn shape(aspect: f64, front_share: f64, shift: f64, side: f64, front: f64, back: f64) -> Section {
    let depth = 2.0 * aspect;
    Section {
        half_width: 1.0,
        front: front_share * depth,
        back: (1.0 - front_share) * depth,
        centre_y: shift * depth,
        side_exponent: side,
        front_exponent: front,
        back_exponent: back,
    }
}

/// The key sections from the bottom ring to the top ring, and the heights of the bottom
/// and top caps. Sections with a measured girth are scaled so their meshed ring has that
/// girth exactly; the shoulder section has the shoulder width exactly.
fn key_sections(m: &Measurements, lm: &Landmarks, n: usize) -> (Vec<Knot>, (f64, f64)) {
    let bottom = with_girth(shape(0.62, 0.45, 0.05, 2.5, 2.0, 2.2), BOTTOM_GIRTH * m.hip, n);
    let hip = with_girth(shape(0.68, 0.40, 0.0, 2.3, 2.0, 2.2), m.hip, n);
    let waist = with_girth(shape(0.74, 0.50, 0.0, 2.1, 2.0, 2.0), m.waist, n);
    let underbust_girth = m.waist + UNDERBUST_BLEND * (m.bust - m.waist);
    let underbust = with_girth(shape(0.74, 0.52, 0.0, 2.2, 2.0, 2.0), underbust_girth, n);
    // A fuller front: more of the depth ahead of the widest points, and squarer there.
    let bust = with_girth(shape(0.80, 0.58, 0.0, 2.2, 2.4, 2.0), m.bust, n);
    let armpit_girth = ARMPIT_GIRTH * m.bust;
    let mut armpit = with_girth(shape(0.70, 0.50, 0.0, 2.6, 2.0, 2.0), armpit_girth, n);
    let widest = (ARMPIT_WIDTH * lm.shoulder_x).max(ARMPIT_TO_BUST_WIDTH * bust.half_width);
    if armpit.half_width > widest {
        let narrowed = armpit.scaled(widest / armpit.half_width);
        armpit = with_girth_at_width(narrowed, armpit_girth, n);
    }
    // Broad and shallow, its sides squared off into the rounded ends of the shoulders.
    let depth = SHOULDER_DEPTH * m.bust;
    let shoulder = Section {
        half_width: lm.shoulder_x,
        ..shape(1.0, 0.46, SHOULDER_SHIFT, 4.0, 2.0, 2.0).scaled(0.5 * depth)
    };
    debug_assert!((shoulder.centre_y - lm.shoulder_y).abs() < 1e-12);
    let neck = with_girth(shape(1.05, 0.50, 0.10, 2.0, 2.0, 2.0), m.neck_girth, n);
    let neck_top = with_girth(
        shape(1.05, 0.50, 0.05, 2.0, 2.0, 2.0),
        NECK_TOP_GIRTH * m.neck_girth,
        n,
    );

    // Sections along the shoulder line: their width follows the line, everything else
    // goes from the shoulder section to the neck's in proportion to height.
    let rise = lm.neck_z - lm.shoulder_z;
    let line = shoulder_line(lm.shoulder_x, neck.half_width, lm.shoulder_z, lm.neck_z);
    let slope = line.iter().map(|&[x, z]| Knot {
        z,
        section: Section {
            half_width: x,
            ..blend(shoulder, neck, (z - lm.shoulder_z) / rise)
        },
    });

    let cap = |s: &Section| CAP_HEIGHT * s.half_width.min(0.5 * s.depth());
    let caps = (cap(&bottom), cap(&neck_top));
    let knot = |z: f64, section: Section| Knot { z, section };
    let mut knots = vec![
        knot(lm.bottom_z + caps.0, bottom),
        knot(lm.hip_z, hip),
        knot(lm.waist_z, waist),
        knot(lm.underbust_z, underbust),
        knot(lm.bust_z, bust),
        knot(lm.armpit_z, armpit),
        knot(lm.shoulder_z, shoulder),
    ];
    knots.extend(slope);
    knots.push(knot(lm.neck_z, neck));
    knots.push(knot(lm.top_z - caps.1, neck_top));
    (knots, caps)
}

/// Points (x, z) strictly between the ends of the shoulder line seen from the front, from
/// the shoulder point `(shoulder_x, shoulder_z)` to the side of the neck `(neck_x, neck_z)`:
/// a rounded shoulder end (vertical where the side of the form comes up to it), a straight
/// slope, and a concave turn up into the neck. The slope's angle is whatever makes the
/// three pieces meet the two ends.
fn shoulder_line(shoulder_x: f64, neck_x: f64, shoulder_z: f64, neck_z: f64) -> Vec<[f64; 2]> {
    let (run, rise) = (shoulder_x - neck_x, neck_z - shoulder_z);
    // Radii kept under the rise, so a straight piece with a positive slope always fits.
    let tip = (SHOULDER_TIP * run).min(0.3 * rise);
    let fillet = (NECK_FILLET * run).min(0.2 * rise);
    let radii = tip + fillet;
    // What is left of the rise at slope angle `g` once the arcs are in; it falls from
    // rise - radii > 0 at g = 0 to minus infinity near 90 degrees.
    let left = |g: f64| rise - radii * g.cos() - (run - radii + radii * g.sin()) * g.tan();
    let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if left(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let turn = std::f64::consts::FRAC_PI_2 - lo;
    let arc = |i: usize| turn * i as f64 / 64.0;
    let mut dense: Vec<[f64; 2]> = (0..=64)
        .map(|i| {
            [
                shoulder_x - tip + tip * arc(i).cos(),
                shoulder_z + tip * arc(i).sin(),
            ]
        })
        .collect();
    dense.extend((0..=64).rev().map(|i| {
        [
            neck_x + fillet - fillet * arc(i).cos(),
            neck_z - fillet * arc(i).sin(),
        ]
    }));
    let points = equal_steps(&dense, SHOULDER_KNOTS + 1);
    points[1..=SHOULDER_KNOTS].to_vec()
}

/// Every parameter a fraction `t` of the way from `a` to `b`.
fn blend(a: Section, b: Section, t: f64) -> Section {
    let (a, b) = (a.to_array(), b.to_array());
    Section::from_array(std::array::from_fn(|i| a[i] + t * (b[i] - a[i])))
}
