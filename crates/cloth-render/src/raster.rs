//! The rasteriser: triangles into a z-buffer at several samples per pixel, then averaged
//! down onto whatever the image already holds there (so the background and anti-aliased
//! edges come for free).
//!
//! Samples only remember which triangle won them and where; shading waits until then and
//! is done once per triangle per pixel, at the mean of its samples there: light varies
//! slowly across a pixel, and shading every sample of every triangle drawn (most of them
//! later hidden) was most of the time spent.
//!
//! The viewport is cut into bands of rows, each rendered by one task with its own small
//! sample buffers; triangles are sorted into the bands they touch beforehand, so a band
//! only looks at its own.

use super::camera::Camera;
use super::image::Image;
use super::shading::{CornerNormals, Lights, BACK_FACE};
use super::RenderMesh;
use cloth_core::math::Vec3;
use rayon::prelude::*;

/// Samples per pixel along each axis (3 x 3 per pixel).
pub(crate) const SUPERSAMPLE: usize = 3;
/// Pixel rows per band: small enough for many tasks, large enough that few triangles
/// straddle two.
const BAND_ROWS: usize = 16;
/// Samples exactly on a shared edge belong to both triangles (the z-buffer settles it),
/// with a little slack so rounding never leaves a crack between them.
const EDGE_SLACK: f32 = 1e-5;

/// A rectangle of pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Rect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

/// A triangle ready to fill: every attribute as its value at corner 0 plus its changes to
/// corners 1 and 2, weighted by the barycentric coordinates `l1`, `l2`.
struct Tri {
    /// Sample columns and rows touched, inclusive, relative to the viewport.
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
    /// Corner 0, in samples.
    origin: [f32; 2],
    /// How `l1` and `l2` change per sample along x and y.
    d1: [f32; 2],
    d2: [f32; 2],
    /// 1 / depth: unlike depth itself, linear across the projected triangle.
    inv_z: [f32; 3],
    normal: [[f32; 3]; 3],
    colour: [[f32; 3]; 3],
}

/// Draws `meshes` as `camera` sees them into `rect` of `image` (clipped to it); the
/// camera's pixel (0, 0) is the rectangle's top left corner.
pub(crate) fn draw(image: &mut Image, rect: Rect, camera: &Camera, meshes: &[&RenderMesh]) {
    let width = rect.width.min(image.width.saturating_sub(rect.x)) as usize;
    let height = rect.height.min(image.height.saturating_sub(rect.y)) as usize;
    if width == 0 || height == 0 {
        return;
    }
    let mut tris = Vec::new();
    for mesh in meshes {
        setup(mesh, camera, width, height, &mut tris);
    }
    // Samples name their triangle in 32 bits; beyond that there is no memory to draw anyway.
    tris.truncate(Sample::NONE as usize);

    // Counting sort of the triangles into the bands they touch.
    let band_samples = BAND_ROWS * SUPERSAMPLE;
    let bands = height.div_ceil(BAND_ROWS);
    let mut start = vec![0usize; bands + 1];
    for t in &tris {
        for b in t.y0 / band_samples..=t.y1 / band_samples {
            start[b + 1] += 1;
        }
    }
    for b in 0..bands {
        start[b + 1] += start[b];
    }
    let mut next = start.clone();
    let mut order = vec![0usize; start[bands]];
    for (i, t) in tris.iter().enumerate() {
        for b in t.y0 / band_samples..=t.y1 / band_samples {
            order[next[b]] = i;
            next[b] += 1;
        }
    }

    let lights = Lights::new();
    let stride = 3 * image.width as usize;
    let x_offset = 3 * rect.x as usize;
    let first = rect.y as usize * stride;
    let rows = &mut image.rgb[first..first + height * stride];
    rows.par_chunks_mut(BAND_ROWS * stride)
        .enumerate()
        .for_each_init(Vec::new, |samples, (b, chunk)| {
            let band_rows = chunk.len() / stride;
            let ws = width * SUPERSAMPLE;
            samples.clear();
            samples.resize(ws * band_rows * SUPERSAMPLE, Sample::EMPTY);
            let band = Band {
                row0: b * band_samples,
                rows: band_rows * SUPERSAMPLE,
                width: ws,
            };
            for &i in &order[start[b]..start[b + 1]] {
                band.fill(&tris[i], i as u32, samples);
            }
            let pixels = Pixels {
                stride,
                x_offset,
                width,
            };
            pixels.resolve(chunk, samples, &tris, &lights);
        });
}

/// Projects a mesh and keeps the triangles that can cover a sample.
fn setup(mesh: &RenderMesh, camera: &Camera, width: usize, height: usize, out: &mut Vec<Tri>) {
    let s = SUPERSAMPLE as f64;
    let projected: Vec<[f64; 3]> = mesh
        .positions
        .par_iter()
        .map(|p| {
            let q = camera.project(p);
            [q.x * s, q.y * s, 1.0 / q.depth]
        })
        .collect();
    let normals = CornerNormals::new(&mesh.positions, &mesh.triangles);
    let (ws, hs) = ((width * SUPERSAMPLE) as f64, (height * SUPERSAMPLE) as f64);
    let n = mesh.positions.len();
    out.par_extend(mesh.triangles.par_iter().enumerate().filter_map(|(k, t)| {
        if t.iter().any(|&i| i >= n) {
            return None;
        }
        let [a, b, c] = t.map(|i| projected[i]);
        if ![a, b, c].iter().flatten().all(|v| v.is_finite()) || a[2] <= 0.0 || b[2] <= 0.0 || c[2] <= 0.0 {
            return None;
        }
        // Sample centres are at half-integer coordinates.
        let lo = |i: usize| (a[i].min(b[i]).min(c[i]) - 0.5).ceil().max(0.0);
        let hi = |i: usize, limit: f64| (a[i].max(b[i]).max(c[i]) - 0.5).floor().min(limit - 1.0);
        let (x0, x1, y0, y1) = (lo(0), hi(0, ws), lo(1), hi(1, hs));
        if x0 > x1 || y0 > y1 {
            return None;
        }
        let e1 = [b[0] - a[0], b[1] - a[1]];
        let e2 = [c[0] - a[0], c[1] - a[1]];
        let area = e1[0] * e2[1] - e1[1] * e2[0];
        if area == 0.0 {
            return None;
        }
        let inv = 1.0 / area;

        let face = normals.face(k);
        if face == Vec3::zeros() {
            return None;
        }
        let front = face.dot(&(camera.eye - mesh.positions[t[0]])) > 0.0;
        let (sign, dim) = if front { (1.0, 1.0) } else { (-1.0, BACK_FACE) };
        let normal = t.map(|i| camera.direction(&(normals.corner(k, i) * sign)));
        let colour = t.map(|i| mesh.colour(i).map(|c| c as f32 * dim));
        let delta = |v: [[f32; 3]; 3]| {
            [
                v[0],
                [0, 1, 2].map(|k| v[1][k] - v[0][k]),
                [0, 1, 2].map(|k| v[2][k] - v[0][k]),
            ]
        };
        Some(Tri {
            x0: x0 as usize,
            x1: x1 as usize,
            y0: y0 as usize,
            y1: y1 as usize,
            origin: [a[0] as f32, a[1] as f32],
            d1: [(e2[1] * inv) as f32, (-e2[0] * inv) as f32],
            d2: [(-e1[1] * inv) as f32, (e1[0] * inv) as f32],
            inv_z: [a[2] as f32, (b[2] - a[2]) as f32, (c[2] - a[2]) as f32],
            normal: delta(normal),
            colour: delta(colour),
        })
    }));
}

/// What a sample holds: the nearest triangle so far, and where on it.
#[derive(Debug, Clone, Copy)]
struct Sample {
    /// 1 / depth; 0 while nothing is drawn (every drawn sample has 1 / depth > 0).
    inv_z: f32,
    tri: u32,
    /// Barycentric coordinates of corners 1 and 2.
    l: [f32; 2],
}

impl Sample {
    const NONE: u32 = u32::MAX;
    const EMPTY: Sample = Sample {
        inv_z: 0.0,
        tri: Self::NONE,
        l: [0.0; 2],
    };
}

/// The sample rows one task fills.
struct Band {
    row0: usize,
    rows: usize,
    width: usize,
}

impl Band {
    fn fill(&self, t: &Tri, id: u32, samples: &mut [Sample]) {
        let y_lo = t.y0.max(self.row0);
        let y_hi = t.y1.min(self.row0 + self.rows - 1);
        for sy in y_lo..=y_hi {
            let py = sy as f32 + 0.5 - t.origin[1];
            let px = t.x0 as f32 + 0.5 - t.origin[0];
            let mut l1 = px * t.d1[0] + py * t.d1[1];
            let mut l2 = px * t.d2[0] + py * t.d2[1];
            let row = (sy - self.row0) * self.width;
            for sample in &mut samples[row + t.x0..=row + t.x1] {
                if l1 >= -EDGE_SLACK && l2 >= -EDGE_SLACK && 1.0 - l1 - l2 >= -EDGE_SLACK {
                    let z = t.inv_z[0] + l1 * t.inv_z[1] + l2 * t.inv_z[2];
                    if z > sample.inv_z {
                        *sample = Sample {
                            inv_z: z,
                            tri: id,
                            l: [l1, l2],
                        };
                    }
                }
                l1 += t.d1[0];
                l2 += t.d2[0];
            }
        }
    }
}

/// Where a band's pixels are in its rows of the image.
struct Pixels {
    stride: usize,
    x_offset: usize,
    width: usize,
}

impl Pixels {
    /// Averages each pixel's samples into `chunk`: each triangle seen in the pixel shaded
    /// once, weighted by its samples; undrawn samples take the colour already there.
    fn resolve(&self, chunk: &mut [u8], samples: &[Sample], tris: &[Tri], lights: &Lights) {
        const PER_PIXEL: usize = SUPERSAMPLE * SUPERSAMPLE;
        let s = SUPERSAMPLE;
        let ws = self.width * s;
        let lerp =
            |v: &[[f32; 3]; 3], l: [f32; 2]| [0, 1, 2].map(|k| v[0][k] + l[0] * v[1][k] + l[1] * v[2][k]);
        for r in 0..chunk.len() / self.stride {
            for px in 0..self.width {
                // (triangle, samples, summed barycentrics), on the stack.
                let mut seen = [(Sample::NONE, 0u32, [0f32; 2]); PER_PIXEL];
                let mut distinct = 0;
                let mut empty = 0u32;
                for sy in 0..s {
                    let base = (r * s + sy) * ws + px * s;
                    for sample in &samples[base..base + s] {
                        if sample.tri == Sample::NONE {
                            empty += 1;
                            continue;
                        }
                        let slot = match seen[..distinct].iter().position(|g| g.0 == sample.tri) {
                            Some(i) => i,
                            None => {
                                seen[distinct].0 = sample.tri;
                                distinct += 1;
                                distinct - 1
                            }
                        };
                        seen[slot].1 += 1;
                        seen[slot].2[0] += sample.l[0];
                        seen[slot].2[1] += sample.l[1];
                    }
                }
                let at = r * self.stride + self.x_offset + 3 * px;
                // The row's width was clipped to the image, so the pixel is in it.
                let out = &mut chunk[at..at + 3];
                let mut sum = [0, 1, 2].map(|j| out[j] as u32 * empty);
                for &(tri, count, l) in &seen[..distinct] {
                    let t = &tris[tri as usize];
                    let l = l.map(|x| x / count as f32);
                    let c = lights.shade(lerp(&t.normal, l), lerp(&t.colour, l));
                    for j in 0..3 {
                        sum[j] += c[j] as u32 * count;
                    }
                }
                let n = PER_PIXEL as u32;
                for j in 0..3 {
                    out[j] = ((sum[j] + n / 2) / n) as u8;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::camera::View;
    use super::super::MeshColours;
    use super::*;

    const BACKGROUND: [u8; 3] = [255, 255, 255];

    fn front_view() -> View {
        View {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        }
    }

    fn whole(image: &Image) -> Rect {
        Rect {
            x: 0,
            y: 0,
            width: image.width,
            height: image.height,
        }
    }

    fn covered(image: &Image) -> usize {
        image.rgb.chunks_exact(3).filter(|p| *p != BACKGROUND).count()
    }

    /// Twice the signed area of a polygon (shoelace).
    fn polygon_area(points: &[[f64; 2]]) -> f64 {
        let n = points.len();
        (0..n)
            .map(|i| {
                let (p, q) = (points[i], points[(i + 1) % n]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            .abs()
            / 2.0
    }

    #[test]
    fn a_square_facing_the_camera_covers_its_projected_area() {
        // In the x-z plane, so it faces -y, the front; placed off-centre within a larger
        // frame so the fit does not simply fill the image with it.
        let square = RenderMesh {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(0.0, 0.0, 1.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            colours: MeshColours::Uniform([90, 120, 200]),
        };
        let frame = [Vec3::new(-0.7, 0.0, -0.2), Vec3::new(1.3, 0.0, 1.9)];
        for (w, h, view) in [
            (200, 160, front_view()),
            (300, 200, View::default()),
            (
                120,
                240,
                View {
                    azimuth_deg: 50.0,
                    elevation_deg: -30.0,
                },
            ),
        ] {
            let mut image = Image::new(w, h, BACKGROUND);
            let camera = Camera::fit(&view, &[&square.positions, &frame], w as f64, h as f64);
            let rect = whole(&image);
            draw(&mut image, rect, &camera, &[&square]);
            let corners: Vec<[f64; 2]> = square
                .positions
                .iter()
                .map(|p| camera.project(p))
                .map(|q| [q.x, q.y])
                .collect();
            let expected = polygon_area(&corners);
            let got = covered(&image) as f64;
            // Edge pixels partly covered count whole: allow a pixel's width along the rim.
            let rim = corners
                .iter()
                .zip(corners.iter().cycle().skip(1))
                .map(|(p, q)| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt())
                .sum::<f64>();
            assert!(
                expected > 0.05 * (w * h) as f64,
                "{view:?}: square too small to test"
            );
            assert!(
                got >= expected - 0.5 * rim && got <= expected + rim + 4.0,
                "{view:?}: {got} pixels covered, {expected} expected (rim {rim})"
            );
        }
    }

    #[test]
    fn the_nearer_of_two_overlapping_triangles_shows() {
        let tri = |y: f64, colour: [u8; 3]| RenderMesh {
            positions: vec![
                Vec3::new(-1.0, y, -1.0),
                Vec3::new(1.0, y, -1.0),
                Vec3::new(0.0, y, 1.0),
            ],
            triangles: vec![[0, 1, 2]],
            colours: MeshColours::Uniform(colour),
        };
        let near = tri(-0.5, [220, 30, 30]);
        let far = tri(0.5, [30, 30, 220]);
        for order in [[&near, &far], [&far, &near]] {
            let mut image = Image::new(64, 64, BACKGROUND);
            let camera = Camera::fit(&front_view(), &[&near.positions, &far.positions], 64.0, 64.0);
            let rect = whole(&image);
            draw(&mut image, rect, &camera, &order);
            let Some([r, _, b]) = image.pixel(32, 36) else {
                panic!("no centre pixel")
            };
            assert!(r > 100 && b < 60, "centre is {r}, {b}: the far triangle shows");
        }
    }

    #[test]
    fn back_faces_are_lit() {
        // Wound so that it faces +y: the camera at the front sees its back.
        let sheet = RenderMesh {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(1.0, 0.0, 0.0),
            ],
            triangles: vec![[0, 1, 2]],
            colours: MeshColours::Uniform([200, 200, 200]),
        };
        let flipped = RenderMesh {
            triangles: vec![[0, 2, 1]],
            ..sheet.clone()
        };
        let mut lit = Vec::new();
        for mesh in [&sheet, &flipped] {
            let mut image = Image::new(40, 40, [0, 0, 0]);
            let camera = Camera::fit(&front_view(), &[&mesh.positions], 40.0, 40.0);
            let rect = whole(&image);
            draw(&mut image, rect, &camera, &[mesh]);
            lit.push(image.pixel(12, 26).map(|p| p[0]).unwrap_or(0));
        }
        // The back is a little darker than the front, nowhere near black.
        assert!(
            lit[0] > 100 && lit[0] < lit[1],
            "back {}, front {}",
            lit[0],
            lit[1]
        );
    }

    #[test]
    fn bad_triangles_are_skipped() {
        let mesh = RenderMesh {
            positions: vec![Vec3::zeros(), Vec3::x(), Vec3::new(f64::NAN, 0.0, 1.0), Vec3::z()],
            triangles: vec![[0, 1, 7], [0, 1, 2], [0, 0, 1]],
            colours: MeshColours::PerVertex(vec![]),
        };
        let mut image = Image::new(30, 20, BACKGROUND);
        let camera = Camera::fit(&front_view(), &[&mesh.positions], 30.0, 20.0);
        let rect = whole(&image);
        draw(&mut image, rect, &camera, &[&mesh]);
        assert_eq!(covered(&image), 0);
    }
}
