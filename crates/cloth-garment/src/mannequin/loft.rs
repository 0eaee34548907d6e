//! Closed tubes from stacked rings: the torso and the arms are both a stack of rings along
//! an axis, rounded off at each end by a dome and closed by a fan to a pole.

use cloth_core::math::Vec3;

use super::arclength::equal_steps;

/// A tube being built: rings from the bottom end to the top end, each with the same number
/// of points, counter-clockwise seen from the top end (so the surface faces outward).
#[derive(Debug, Default)]
pub(crate) struct Loft {
    rings: Vec<Vec<Vec3>>,
}

impl Loft {
    pub fn push(&mut self, ring: Vec<Vec3>) {
        debug_assert!(self.rings.last().is_none_or(|r| r.len() == ring.len()));
        self.rings.push(ring);
    }

    /// Closes both ends with domes, stepped about `spacing` apart, and returns the vertices
    /// and outward triangles.
    ///
    /// The caller guarantees at least one ring of at least three points.
    pub fn close(mut self, bottom: Cap, top: Cap, spacing: f64) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let last = self.rings.len() - 1;
        let (mut rings, bottom_pole) = dome(&self.rings[0], bottom, spacing);
        let (top_rings, top_pole) = dome(&self.rings[last], top, spacing);
        rings.reverse();
        rings.append(&mut self.rings);
        rings.extend(top_rings);
        fan_and_bands(&rings, bottom_pole, top_pole)
    }
}

/// How an end of a tube is rounded off: a dome rising `height` along `axis` (a unit vector
/// pointing away from the tube) from the end ring to the pole.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cap {
    pub axis: Vec3,
    pub height: f64,
}

fn centroid(ring: &[Vec3]) -> Vec3 {
    ring.iter().sum::<Vec3>() / ring.len() as f64
}

/// The rings of a dome over `ring` (ring itself excluded), from the rim towards the pole,
/// and the pole. A point at angle `phi` over the rim moves to `cos(phi)` of its distance from
/// the ring's centroid and `height sin(phi)` along `axis`: a quarter ellipse in every
/// meridian, tangent to the tube at the rim, so the surface stays smooth where a cap meets
/// it. With `height` equal to the radius it is a hemisphere; lower, a flattened cap.
///
/// Each time a ring has shrunk to half the size, every other point is dropped (down to 8),
/// so the triangles near the pole are not slivers.
fn dome(ring: &[Vec3], Cap { axis, height }: Cap, spacing: f64) -> (Vec<Vec<Vec3>>, Vec3) {
    let centre = centroid(ring);
    let radius = ring.iter().map(|p| (p - centre).norm()).sum::<f64>() / ring.len() as f64;
    let meridian: Vec<[f64; 2]> = (0..=256)
        .map(|i| {
            let phi = std::f64::consts::FRAC_PI_2 * i as f64 / 256.0;
            [radius * phi.cos(), height * phi.sin()]
        })
        .collect();
    let length = super::arclength::cumulative(&meridian)[256];
    let steps = ((length / spacing).ceil() as usize).max(2);
    let stations = equal_steps(&meridian, steps);
    let mut stride = 1;
    let rings = stations[1..steps]
        .iter()
        .map(|&[r, h]| {
            let shrink = r / radius;
            while shrink * (stride as f64) < 0.5
                && ring.len().is_multiple_of(4 * stride)
                && ring.len() / stride >= 16
            {
                stride *= 2;
            }
            ring.iter()
                .step_by(stride)
                .map(|p| centre + shrink * (p - centre) + h * axis)
                .collect()
        })
        .collect();
    (rings, centre + height * axis)
}

/// Bands between consecutive rings and a fan to each pole. Consecutive rings have the same
/// number of points, or one has twice the other's (a dome thinning out, see [`dome`]), its
/// even points matching the other's.
fn fan_and_bands(rings: &[Vec<Vec3>], bottom: Vec3, top: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut vertices = vec![bottom];
    let mut starts = Vec::with_capacity(rings.len());
    for ring in rings {
        starts.push(vertices.len());
        vertices.extend_from_slice(ring);
    }
    let top_index = vertices.len() as u32;
    vertices.push(top);
    let at = |j: usize, k: usize| (starts[j] + k % rings[j].len()) as u32;
    let mut triangles = Vec::new();
    for k in 0..rings[0].len() {
        triangles.push([0, at(0, k + 1), at(0, k)]);
    }
    for j in 0..rings.len() - 1 {
        let (lower, upper) = (rings[j].len(), rings[j + 1].len());
        let (l, u) = (|k| at(j, k), |k| at(j + 1, k));
        if lower == 2 * upper {
            for k in 0..upper {
                triangles.push([l(2 * k), l(2 * k + 1), u(k)]);
                triangles.push([l(2 * k + 1), l(2 * k + 2), u(k + 1)]);
                triangles.push([l(2 * k + 1), u(k + 1), u(k)]);
            }
        } else if upper == 2 * lower {
            for k in 0..lower {
                triangles.push([l(k), u(2 * k + 1), u(2 * k)]);
                triangles.push([l(k), l(k + 1), u(2 * k + 1)]);
                triangles.push([l(k + 1), u(2 * k + 2), u(2 * k + 1)]);
            }
        } else {
            debug_assert_eq!(lower, upper);
            for k in 0..lower {
                // The shorter diagonal: the better-shaped pair where a ring twists or shrinks.
                let p = |i: u32| vertices[i as usize];
                if (p(u(k + 1)) - p(l(k))).norm() <= (p(u(k)) - p(l(k + 1))).norm() {
                    triangles.push([l(k), l(k + 1), u(k + 1)]);
                    triangles.push([l(k), u(k + 1), u(k)]);
                } else {
                    triangles.push([l(k), l(k + 1), u(k)]);
                    triangles.push([l(k + 1), u(k + 1), u(k)]);
                }
            }
        }
    }
    let last = rings.len() - 1;
    for k in 0..rings[last].len() {
        triangles.push([at(last, k), at(last, k + 1), top_index]);
    }
    (vertices, triangles)
}
