//! Light: smooth vertex normals, and a key light, a weak fill and ambient fixed to the
//! camera, so every view is lit the same way. Both sides of a surface are lit (the normal
//! is turned towards the viewer before shading), so the inside of a garment is not black.

use cloth_core::math::Vec3;

/// Light that reaches everything: the floor of the brightness of a surface turned away.
const AMBIENT: f32 = 0.3;
/// From the upper left, a little in front: camera axes x right, y up, z towards the viewer.
const KEY_DIR: [f32; 3] = [-0.42, 0.55, 0.72];
const KEY: f32 = 0.66;
/// From the lower right, so the side the key misses keeps its shape.
const FILL_DIR: [f32; 3] = [0.62, -0.25, 0.74];
const FILL: f32 = 0.16;
/// Lambert wrapped this far round the terminator: soft light, as under an overcast sky,
/// suits cloth better than a hard edge.
const WRAP: f32 = 0.3;
/// The back side of a surface is drawn slightly darker, to tell inside from outside.
pub(crate) const BACK_FACE: f32 = 0.8;
/// Faces meeting at more than this angle form a crease (a box edge, a sharp fold): each
/// side is shaded on its own, not smeared across it.
const CREASE_COS: f64 = 0.643; // cos 50 deg

/// Normals at the corners of triangles, smooth except across creases: at a corner, the
/// area-weighted mean of the normals of the triangles around its vertex that are within
/// the crease angle of the triangle's own.
pub(crate) struct CornerNormals {
    /// Unit normals of the triangles; zero for degenerate or invalid ones.
    face: Vec<Vec3>,
    /// Normals scaled by twice the area.
    weighted: Vec<Vec3>,
    /// The triangles around vertex `v` are `around[start[v]..start[v + 1]]`.
    start: Vec<usize>,
    around: Vec<usize>,
}

impl CornerNormals {
    pub fn new(positions: &[Vec3], triangles: &[[usize; 3]]) -> Self {
        let n = positions.len();
        let weighted: Vec<Vec3> = triangles
            .iter()
            .map(|t| {
                if t.iter().any(|&i| i >= n) {
                    return Vec3::zeros();
                }
                let [a, b, c] = t.map(|i| positions[i]);
                // The cross product's length is twice the area: the weighting comes free.
                let w = (b - a).cross(&(c - a));
                if w.iter().all(|x| x.is_finite()) {
                    w
                } else {
                    Vec3::zeros()
                }
            })
            .collect();
        let face: Vec<Vec3> = weighted
            .iter()
            .map(|w| w.try_normalize(1e-300).unwrap_or_else(Vec3::zeros))
            .collect();
        let mut start = vec![0usize; n + 1];
        for (t, f) in triangles.iter().zip(&face) {
            if *f != Vec3::zeros() {
                for &i in t {
                    start[i + 1] += 1;
                }
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut around = vec![0usize; start[n]];
        for (k, (t, f)) in triangles.iter().zip(&face).enumerate() {
            if *f != Vec3::zeros() {
                for &i in t {
                    around[next[i]] = k;
                    next[i] += 1;
                }
            }
        }
        Self {
            face,
            weighted,
            start,
            around,
        }
    }

    /// The unit normal of triangle `t`, zero if it has none.
    pub fn face(&self, t: usize) -> Vec3 {
        self.face[t]
    }

    /// The unit normal at the corner of triangle `t` on `vertex`.
    pub fn corner(&self, t: usize, vertex: usize) -> Vec3 {
        let own = self.face[t];
        let sum: Vec3 = self.around[self.start[vertex]..self.start[vertex + 1]]
            .iter()
            .filter(|&&k| self.face[k].dot(&own) >= CREASE_COS)
            .map(|&k| self.weighted[k])
            .sum();
        sum.try_normalize(1e-300).unwrap_or(own)
    }
}

fn unit(v: [f32; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn wrapped(n: [f32; 3], l: [f32; 3]) -> f32 {
    ((dot(n, l) + WRAP) / (1.0 + WRAP)).max(0.0)
}

/// The lights, in camera axes, normalised once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lights {
    key: [f32; 3],
    fill: [f32; 3],
}

impl Lights {
    pub fn new() -> Self {
        Self {
            key: unit(KEY_DIR),
            fill: unit(FILL_DIR),
        }
    }

    /// The colour of a surface of `base` colour (0-255 per channel) with normal `n` (camera
    /// axes, towards the viewer, any length).
    #[inline]
    pub fn shade(&self, n: [f32; 3], base: [f32; 3]) -> [u8; 3] {
        let l = dot(n, n).sqrt();
        let k = if l > 0.0 {
            let n = [n[0] / l, n[1] / l, n[2] / l];
            AMBIENT + KEY * wrapped(n, self.key) + FILL * wrapped(n, self.fill)
        } else {
            AMBIENT + KEY * 0.5
        };
        base.map(|c| (c * k).clamp(0.0, 255.0) as u8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turned_away_is_darker_but_not_black() {
        let lights = Lights::new();
        let grey = [200.0; 3];
        let facing_key = lights.shade(lights.key, grey)[0];
        let edge_on = lights.shade([1.0, 0.0, 0.0], grey)[0];
        let away = lights.shade(lights.key.map(|x| -x), grey)[0];
        assert!(
            facing_key > edge_on && edge_on > away,
            "{facing_key} {edge_on} {away}"
        );
        assert!(away as f32 >= 200.0 * AMBIENT - 1.0);
    }

    #[test]
    fn normals_are_smooth_on_a_gentle_bend_and_split_at_a_crease() {
        // Two squares sharing the edge from (0,0,0) to (0,1,0), the second tilted by `angle`.
        for (angle, smooth) in [(20f64, true), (80.0, false)] {
            let (s, c) = angle.to_radians().sin_cos();
            let p = [
                Vec3::new(-1.0, 0.0, 0.0),
                Vec3::zeros(),
                Vec3::y(),
                Vec3::new(-1.0, 1.0, 0.0),
                Vec3::new(c, 0.0, s),
                Vec3::new(c, 1.0, s),
            ];
            let triangles = [[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]];
            let normals = CornerNormals::new(&p, &triangles);
            let flat = normals.face(0);
            assert!((flat - Vec3::z()).norm() < 1e-12);
            // At the shared vertex 1, triangle 0 either leans towards the tilted side or
            // keeps its own normal.
            let at_edge = normals.corner(0, 1);
            assert!((at_edge.norm() - 1.0).abs() < 1e-12);
            assert_eq!(
                at_edge.dot(&flat) < 1.0 - 1e-9,
                smooth,
                "{angle} deg: {at_edge:?}"
            );
            // Away from the edge, vertex 0 only has flat triangles around it.
            assert!((normals.corner(0, 0) - flat).norm() < 1e-12);
        }
    }
}
