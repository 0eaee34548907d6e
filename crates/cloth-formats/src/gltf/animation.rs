//! The cloth's motion as one glTF binary, which Blender's importer and three.js play: the
//! mesh of the first frame, every later frame a morph target (its displacement from the
//! first, and its normals'), and an animation of the targets' weights that shows frame `k`
//! at its time with weight 1 on its target alone, blended linearly between, which is the
//! positions blended linearly.
//!
//! The frames are written as they come into a point cache beside the file (see
//! [`crate::pc2`]), so a long run holds one frame in memory; when the stage ends the cache
//! is read back, at most [`MAX_TARGETS`] frames evenly chosen (every frame is in a PC2
//! animation when more are wanted), and the file is put in place.

use super::cloth_vertices::ClothVertices;
use super::write::{vertex_normals, y_up, GlbDocument, GlbMaterial, GlbMesh, GlbMorphTarget};
use crate::atomic::write_atomically;
use crate::panels::PanelLabels;
use crate::pc2::{Pc2Reader, Pc2Writer};
use cloth_core::{math::Vec3, ClothMesh};
use serde_json::json;
use std::io::{Error, ErrorKind};
use std::path::{Path, PathBuf};

/// Morph targets kept in one file: a viewer blends every target of a mesh for each
/// vertex, and Blender makes each a shape key, so a few hundred is what they play well.
pub const MAX_TARGETS: usize = 150;

/// A glTF animation being written (dropped unfinished, it writes what it has).
#[derive(Debug)]
pub struct GlbAnimationWriter {
    path: PathBuf,
    /// The cache of the frames, and where it is put when finished.
    frames: Option<Pc2Writer>,
    frames_path: PathBuf,
    generator: String,
    triangles: Vec<[usize; 3]>,
    vertices: ClothVertices,
    panels: Option<PanelLabels>,
    /// Each frame's time, s.
    times: Vec<f64>,
}

impl GlbAnimationWriter {
    /// Starts the animation of `mesh` (z-up, as the engine's world; the file is y-up),
    /// its vertices labelled with `panels` if given. `generator` names the program.
    pub fn create(
        path: &Path,
        mesh: &ClothMesh,
        panels: Option<&PanelLabels>,
        generator: String,
    ) -> std::io::Result<Self> {
        let mut frames_path = path.as_os_str().to_owned();
        frames_path.push(".frames.pc2");
        let frames_path = PathBuf::from(frames_path);
        Ok(Self {
            path: path.to_path_buf(),
            frames: Some(Pc2Writer::create(&frames_path, mesh.vertex_count(), 0.0, 1.0)?),
            frames_path,
            generator,
            triangles: mesh.triangles().to_vec(),
            vertices: ClothVertices::new(mesh)?,
            panels: panels.cloned(),
            times: Vec::new(),
        })
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.times.len()
    }

    /// Appends the frame at `time` (s, after the last frame's): every vertex's position,
    /// z-up, m.
    pub fn push(&mut self, time: f64, positions: &[Vec3]) -> std::io::Result<()> {
        if self.times.last().is_some_and(|&last| time <= last) || !time.is_finite() {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!("a frame at {time} s after one at {:?} s", self.times.last()),
            ));
        }
        let points: Vec<[f32; 3]> = positions
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        self.frames
            .as_mut()
            .ok_or_else(|| Error::other("the animation is finished"))?
            .push(&points)?;
        self.times.push(time);
        Ok(())
    }

    /// Writes the file from the frames so far, and removes their cache.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.close()
    }

    fn close(&mut self) -> std::io::Result<()> {
        let Some(frames) = self.frames.take() else {
            return Ok(());
        };
        frames.finish()?;
        let written = self.write_from_cache();
        let _ = std::fs::remove_file(&self.frames_path);
        written
    }

    fn write_from_cache(&self) -> std::io::Result<()> {
        let mut cache = Pc2Reader::open(&self.frames_path).map_err(|e| Error::other(e.to_string()))?;
        let kept = kept_frames(cache.samples);
        let Some((&first, later)) = kept.split_first() else {
            return Ok(());
        };
        let mut frame = |k: usize| -> std::io::Result<(Vec<[f32; 3]>, Vec<[f32; 3]>)> {
            let points: Vec<Vec3> = cache
                .sample(k)
                .map_err(|e| Error::other(e.to_string()))?
                .iter()
                .map(|p| Vec3::new(p[0].into(), p[1].into(), p[2].into()))
                .collect();
            let positions = y_up(&points, &format!("frame {k}'s"))?;
            let normals = vertex_normals(&points, self.triangles.iter().copied());
            Ok((self.vertices.gather(&positions), self.vertices.gather(&normals)))
        };
        let (base, base_normals) = frame(first)?;
        let mut targets = Vec::with_capacity(later.len());
        for &k in later {
            let (positions, normals) = frame(k)?;
            let minus = |a: Vec<[f32; 3]>, b: &[[f32; 3]]| -> Vec<[f32; 3]> {
                a.iter()
                    .zip(b)
                    .map(|(a, b)| [a[0] - b[0], a[1] - b[1], a[2] - b[2]])
                    .collect()
            };
            targets.push(GlbMorphTarget {
                name: format!("frame_{:05}", k + 1),
                positions: minus(positions, &base),
                normals: minus(normals, &base_normals),
            });
        }

        let mut doc = GlbDocument::new(self.generator.clone());
        let material = doc.add_material(GlbMaterial {
            name: "cloth".into(),
            base_colour: [0.8, 0.8, 0.85, 1.0],
            roughness: 0.9,
            double_sided: true,
        });
        let start = self.times[first];
        let mut extras = json!({
            "TEXCOORD_0": "material coordinates (u along the warp, v along the weft), m",
            "frames": kept.iter().map(|&k| k + 1).collect::<Vec<_>>(),
            "start_time_s": start,
            "animation": "morph target k is frame k + 1's displacement from frame 1; \
                          times are the simulated time since frame 1, s",
        });
        let panel_of: Vec<f32>;
        let mut scalars: Vec<(&str, &[f32])> = Vec::new();
        if let Some(panels) = &self.panels {
            panel_of = self.vertices.panel_attribute(panels);
            scalars.push(("_PANEL", &panel_of));
            extras["_PANEL"] = json!("the vertex's panel: an index into `panels`");
            extras["panels"] = json!(panels.names());
        }
        let node = doc.add_mesh(GlbMesh {
            name: "cloth",
            positions: &base,
            normals: &base_normals,
            texcoords: Some(self.vertices.uv()),
            colours: None,
            scalars: &scalars,
            targets: &targets,
            indices: self.vertices.indices(),
            material,
            extras: Some(extras),
        })?;
        if !targets.is_empty() {
            // Keyframe j shows target j - 1 alone; keyframe 0 none.
            let n = targets.len();
            let mut weights = vec![0.0f32; (n + 1) * n];
            for j in 1..=n {
                weights[j * n + j - 1] = 1.0;
            }
            let times: Vec<f32> = kept.iter().map(|&k| (self.times[k] - start) as f32).collect();
            doc.add_weights_animation("cloth", node, &times, &weights)?;
        }
        let glb = doc.into_bytes()?;
        write_atomically(&self.path, |out| out.write_all(&glb))
    }
}

impl Drop for GlbAnimationWriter {
    fn drop(&mut self) {
        let _ = self.close();
    }
}

/// Which of `samples` frames to keep: all of them up to [`MAX_TARGETS`] + 1, else the
/// first, every `stride`-th and the last, `stride` the least that keeps the targets within
/// the bound.
fn kept_frames(samples: usize) -> Vec<usize> {
    if samples <= MAX_TARGETS + 1 {
        return (0..samples).collect();
    }
    let stride = (samples - 1).div_ceil(MAX_TARGETS);
    let mut kept: Vec<usize> = (0..samples - 1).step_by(stride).collect();
    kept.push(samples - 1);
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::mesh::GridBuilder;

    #[test]
    fn an_animation_dropped_unfinished_writes_its_frames() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cloth.glb");
        let mesh = GridBuilder::new(2, 2).size(1.0, 1.0).build().unwrap();
        let flat: Vec<Vec3> = (0..mesh.vertex_count())
            .map(|i| Vec3::new((i % 3) as f64, (i / 3) as f64, 1.0))
            .collect();
        let mut animation = GlbAnimationWriter::create(&path, &mesh, None, "test".into()).unwrap();
        for k in 0..3 {
            let lower: Vec<Vec3> = flat.iter().map(|p| p - Vec3::z() * (0.1 * k as f64)).collect();
            animation.push(0.5 * k as f64, &lower).unwrap();
        }
        assert!(
            animation.push(1.0, &flat).is_err(),
            "a frame no later than the last"
        );
        assert!(animation.push(f64::NAN, &flat).is_err());
        assert_eq!(animation.frames(), 3);
        assert!(!path.exists(), "in place only when finished");
        drop(animation);
        let doc = ::gltf::Gltf::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        let primitive = doc.meshes().next().unwrap().primitives().next().unwrap();
        let reader = primitive.reader(|_| doc.blob.as_deref());
        let targets: Vec<Vec<[f32; 3]>> = reader
            .read_morph_targets()
            .map(|(positions, _, _)| positions.unwrap().collect())
            .collect();
        // Down the engine's z is down glTF's y; the frames' cache is gone.
        assert_eq!(targets.len(), 2);
        for (k, target) in targets.iter().enumerate() {
            for d in target {
                let expected = [0.0, -0.1 * (k + 1) as f32, 0.0];
                assert!((0..3).all(|c| (d[c] - expected[c]).abs() < 1e-6), "{d:?}");
            }
        }
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1);
    }

    #[test]
    fn frames_are_thinned_evenly_keeping_the_first_and_last() {
        assert_eq!(kept_frames(0), Vec::<usize>::new());
        assert_eq!(kept_frames(3), vec![0, 1, 2]);
        assert_eq!(kept_frames(MAX_TARGETS + 1).len(), MAX_TARGETS + 1);
        for samples in [MAX_TARGETS + 2, 2 * MAX_TARGETS + 1, 1000, 12_345] {
            let kept = kept_frames(samples);
            assert!(
                kept.len() - 1 <= MAX_TARGETS,
                "{samples}: {} targets",
                kept.len() - 1
            );
            assert!(kept.len() - 1 > MAX_TARGETS / 2, "{samples}: thinned too far");
            assert_eq!((kept[0], *kept.last().unwrap()), (0, samples - 1));
            let gaps: Vec<usize> = kept.windows(2).map(|w| w[1] - w[0]).collect();
            let stride = gaps[0];
            assert!(gaps.iter().all(|&g| g >= 1 && g <= stride), "{samples}: {gaps:?}");
        }
    }
}
