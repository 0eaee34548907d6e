//! Ready-made bodies, centred on the origin with z up, each a valid outward surface.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use cloth_core::math::Vec3;
use nalgebra::Isometry3;

use super::{SurfaceError, SurfaceOptions, TriSurface};

/// Large enough to be seen as a body, small enough to fit in memory (1 310 720 triangles).
const MAX_ICOSPHERE_SUBDIVISIONS: usize = 8;

impl TriSurface {
    /// UV sphere: `segments` (>= 3) longitudes at angles `2 pi k / segments` from the +x axis
    /// and `rings` (>= 2) latitude bands, with poles on the z axis. With `segments` a
    /// multiple of 4 the vertices are mirror-symmetric in x, y and under x <-> y. Quads are
    /// split along diagonals alternating like a checkerboard, so the triangles share those
    /// symmetries when `segments` is a multiple of 8 (and the z mirror when `rings` is even).
    pub fn sphere(radius: f64, segments: usize, rings: usize) -> Result<Self, SurfaceError> {
        positive("radius", radius)?;
        at_least("segments", segments, 3, "at least 3 longitudes")?;
        at_least("rings", rings, 2, "at least 2 latitude bands")?;
        let circles: Vec<(f64, f64)> = (1..rings)
            .map(|j| {
                let polar = PI * j as f64 / rings as f64;
                (radius * polar.sin(), radius * polar.cos())
            })
            .collect();
        revolve(radius, &circles, -radius, segments)
    }

    /// Icosahedron whose faces are split `subdivisions` times (0..=8) into four, vertices
    /// pushed onto the sphere: evenly sized triangles for large smooth bodies
    /// (`20 * 4^subdivisions` triangles, e.g. 20 480 at 5 and 81 920 at 6).
    pub fn icosphere(radius: f64, subdivisions: usize) -> Result<Self, SurfaceError> {
        positive("radius", radius)?;
        if subdivisions > MAX_ICOSPHERE_SUBDIVISIONS {
            return Err(SurfaceError::Parameter {
                name: "subdivisions",
                value: subdivisions as f64,
                expected: "at most 8 (1 310 720 triangles)",
            });
        }
        let (mut vertices, mut triangles) = icosahedron();
        for _ in 0..subdivisions {
            triangles = subdivide(&mut vertices, &triangles);
        }
        let vertices = vertices.iter().map(|p| radius * p.normalize()).collect();
        build(vertices, triangles)
    }

    /// Box with the given half extents: 8 vertices, 12 triangles.
    pub fn cuboid(half_extents: Vec3) -> Result<Self, SurfaceError> {
        for (name, value) in ["half_extents.x", "half_extents.y", "half_extents.z"]
            .iter()
            .zip(half_extents.iter())
        {
            positive(name, *value)?;
        }
        // Vertex `i` has +half extent along axis `a` when bit `a` of `i` is set.
        let vertices = (0..8)
            .map(|i| {
                Vec3::from_fn(|a, _| {
                    if i & (1 << a) != 0 {
                        half_extents[a]
                    } else {
                        -half_extents[a]
                    }
                })
            })
            .collect();
        let mut triangles = Vec::with_capacity(12);
        for axis in 0..3 {
            let (u, v) = (1 << ((axis + 1) % 3), 1 << ((axis + 2) % 3));
            for side in [0, 1 << axis] {
                // Counter-clockwise around +axis (u x v = axis); reversed on the negative side.
                let mut quad = [side, side + u, side + u + v, side + v];
                if side == 0 {
                    quad.reverse();
                }
                triangles.push([quad[0], quad[1], quad[2]]);
                triangles.push([quad[0], quad[2], quad[3]]);
            }
        }
        build(vertices, triangles)
    }

    /// Capped cylinder along z: `segments` (>= 3) sides, caps as fans around their centres.
    pub fn cylinder(radius: f64, half_height: f64, segments: usize) -> Result<Self, SurfaceError> {
        positive("radius", radius)?;
        positive("half_height", half_height)?;
        at_least("segments", segments, 3, "at least 3 sides")?;
        revolve(
            half_height,
            &[(radius, half_height), (radius, -half_height)],
            -half_height,
            segments,
        )
    }

    /// Capsule along z: a cylinder of `half_height` (> 0) capped by hemispheres of `rings`
    /// (>= 1) latitude bands each, `segments` (>= 3) longitudes.
    pub fn capsule(
        radius: f64,
        half_height: f64,
        segments: usize,
        rings: usize,
    ) -> Result<Self, SurfaceError> {
        positive("radius", radius)?;
        positive("half_height", half_height)?;
        at_least("segments", segments, 3, "at least 3 longitudes")?;
        at_least("rings", rings, 1, "at least 1 latitude band per hemisphere")?;
        let polar = |j: usize| FRAC_PI_2 * j as f64 / rings as f64;
        let top = (1..=rings).map(|j| (radius * polar(j).sin(), half_height + radius * polar(j).cos()));
        let bottom = (1..=rings)
            .rev()
            .map(|j| (radius * polar(j).sin(), -half_height - radius * polar(j).cos()));
        let circles: Vec<(f64, f64)> = top.chain(bottom).collect();
        revolve(half_height + radius, &circles, -half_height - radius, segments)
    }

    /// Table: a box top whose upper face is at z = `height`, on four square legs of half
    /// width `leg_half_width` standing on z = 0 and touching the top's underside, their outer
    /// faces `leg_inset` in from the top's edges. Five closed components in one surface.
    pub fn table(
        top_half_extents: Vec3,
        height: f64,
        leg_half_width: f64,
        leg_inset: f64,
    ) -> Result<Self, SurfaceError> {
        let top = Self::cuboid(top_half_extents)?;
        positive("leg_half_width", leg_half_width)?;
        if !(leg_inset.is_finite() && leg_inset >= 0.0) {
            return Err(SurfaceError::Parameter {
                name: "leg_inset",
                value: leg_inset,
                expected: "a finite distance >= 0 m",
            });
        }
        let leg_length = height - 2.0 * top_half_extents.z;
        if !(leg_length.is_finite() && leg_length > 0.0) {
            return Err(SurfaceError::Parameter {
                name: "height",
                value: height,
                expected: "more than the top's thickness (2 * top_half_extents.z), so legs have length",
            });
        }
        let reach = leg_inset + 2.0 * leg_half_width;
        if reach >= top_half_extents.x.min(top_half_extents.y) {
            return Err(SurfaceError::Parameter {
                name: "leg_inset",
                value: leg_inset,
                expected: "below the smaller top half extent minus 2 * leg_half_width (legs must not touch)",
            });
        }
        let leg = Self::cuboid(Vec3::new(leg_half_width, leg_half_width, 0.5 * leg_length))?;
        let at = Isometry3::translation;
        let (lx, ly) = (
            top_half_extents.x - leg_inset - leg_half_width,
            top_half_extents.y - leg_inset - leg_half_width,
        );
        let mut parts = vec![top.transformed(&at(0.0, 0.0, height - top_half_extents.z))];
        for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            parts.push(leg.transformed(&at(sx * lx, sy * ly, 0.5 * leg_length)));
        }
        Ok(Self::merged(&parts))
    }
}

fn positive(name: &'static str, value: f64) -> Result<(), SurfaceError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SurfaceError::Parameter {
            name,
            value,
            expected: "a finite size > 0 m",
        })
    }
}

fn at_least(
    name: &'static str,
    value: usize,
    min: usize,
    expected: &'static str,
) -> Result<(), SurfaceError> {
    if value >= min {
        Ok(())
    } else {
        Err(SurfaceError::Parameter {
            name,
            value: value as f64,
            expected,
        })
    }
}

/// Primitives still go through validation: a bad tessellation (e.g. so fine that triangles
/// vanish in rounding) is reported, not returned. Weld distance 0 because the indices are
/// already shared.
fn build(vertices: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Result<TriSurface, SurfaceError> {
    let options = SurfaceOptions {
        weld_distance: Some(0.0),
        ..Default::default()
    };
    TriSurface::new(vertices, triangles, &options)
}

/// Surface of revolution about z: a pole at `top`, the `(radius, z)` circles from top to
/// bottom, a pole at `bottom`. Quads between circles are split along alternating diagonals.
fn revolve(
    top: f64,
    circles: &[(f64, f64)],
    bottom: f64,
    segments: usize,
) -> Result<TriSurface, SurfaceError> {
    let count = circles.len().saturating_mul(segments).saturating_add(2);
    if count > u32::MAX as usize {
        return Err(SurfaceError::Parameter {
            name: "segments",
            value: segments as f64,
            expected: "few enough segments and rings for fewer than 2^32 vertices",
        });
    }
    let longitude: Vec<(f64, f64)> = (0..segments)
        .map(|k| {
            let phi = TAU * k as f64 / segments as f64;
            (phi.cos(), phi.sin())
        })
        .collect();
    let mut vertices = Vec::with_capacity(count);
    vertices.push(Vec3::new(0.0, 0.0, top));
    for &(r, z) in circles {
        vertices.extend(longitude.iter().map(|&(c, s)| Vec3::new(r * c, r * s, z)));
    }
    vertices.push(Vec3::new(0.0, 0.0, bottom));
    let south = (count - 1) as u32;
    let at = |j: usize, k: usize| (1 + j * segments + k % segments) as u32;
    let mut triangles = Vec::with_capacity(2 * segments * circles.len());
    for k in 0..segments {
        triangles.push([0, at(0, k), at(0, k + 1)]);
    }
    for j in 0..circles.len() - 1 {
        for k in 0..segments {
            let (a, b, c, d) = (at(j, k), at(j, k + 1), at(j + 1, k + 1), at(j + 1, k));
            if (j + k) % 2 == 0 {
                triangles.extend([[b, a, c], [a, d, c]]);
            } else {
                triangles.extend([[b, a, d], [b, d, c]]);
            }
        }
    }
    let last = circles.len() - 1;
    for k in 0..segments {
        triangles.push([south, at(last, k + 1), at(last, k)]);
    }
    build(vertices, triangles)
}

fn icosahedron() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let vertices = [
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ]
    .map(Vec3::from)
    .to_vec();
    let triangles = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (vertices, triangles)
}

/// Splits every triangle into four at its edge midpoints, sharing each midpoint between
/// the two triangles of its edge.
fn subdivide(vertices: &mut Vec<Vec3>, triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut midpoint = std::collections::HashMap::new();
    let mut mid = |a: u32, b: u32| {
        *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
            vertices.push(0.5 * (vertices[a as usize] + vertices[b as usize]));
            (vertices.len() - 1) as u32
        })
    };
    let mut finer = Vec::with_capacity(4 * triangles.len());
    for &[a, b, c] in triangles {
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        finer.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    finer
}
