//! A garment's panels on its mesh, as the writers label them: each triangle's panel and the
//! panels' names, each vertex's panels (two or more where a seam joins them), and the
//! segmentation file.

use crate::atomic::write_atomically;
use std::path::Path;

/// Each triangle's panel (an index into `names`) and the panels' names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PanelLabels {
    names: Vec<String>,
    of_triangle: Vec<usize>,
}

impl PanelLabels {
    /// Labels for a mesh with `of_triangle.len()` triangles; the error names the first
    /// triangle whose panel is not one of `names`.
    pub fn new(names: Vec<String>, of_triangle: Vec<usize>) -> Result<Self, String> {
        if let Some((t, p)) = of_triangle.iter().enumerate().find(|(_, &p)| p >= names.len()) {
            return Err(format!(
                "triangle {t} is of panel {p}, but there are {} panels",
                names.len()
            ));
        }
        Ok(Self { names, of_triangle })
    }

    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Each triangle's panel.
    pub fn of_triangle(&self) -> &[usize] {
        &self.of_triangle
    }

    /// Each of `vertices` vertices' panels, ascending: one inside a panel, two or more on
    /// a seam, none for a vertex no triangle uses.
    pub fn of_vertex(&self, triangles: &[[usize; 3]], vertices: usize) -> Vec<Vec<usize>> {
        let mut panels = vec![Vec::new(); vertices];
        for (tri, &p) in triangles.iter().zip(&self.of_triangle) {
            for &v in tri {
                if let Some(list) = panels.get_mut(v) {
                    if let Err(at) = list.binary_search(&p) {
                        list.insert(at, p);
                    }
                }
            }
        }
        panels
    }

    /// Each vertex's one label for formats with a number per vertex (PLY, glTF): its
    /// lowest-numbered panel, -1 for a vertex no triangle uses.
    pub fn vertex_label(&self, triangles: &[[usize; 3]], vertices: usize) -> Vec<i32> {
        self.of_vertex(triangles, vertices)
            .iter()
            .map(|p| p.first().map_or(-1, |&p| p as i32))
            .collect()
    }

    /// Writes the segmentation file: a line per vertex, in the mesh's numbering, naming
    /// its panel, or the panels a seam vertex joins separated by commas (as GarmentCode's
    /// `_segmentation.txt` lists a stitched vertex's stitches), empty for a vertex no
    /// triangle uses.
    pub fn write_segmentation(
        &self,
        path: &Path,
        triangles: &[[usize; 3]],
        vertices: usize,
    ) -> std::io::Result<()> {
        let of_vertex = self.of_vertex(triangles, vertices);
        write_atomically(path, |out| {
            for panels in &of_vertex {
                let names: Vec<&str> = panels.iter().map(|&p| self.names[p].as_str()).collect();
                writeln!(out, "{}", names.join(","))?;
            }
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two panels sewn along the edge 1-2: its vertices belong to both.
    fn two_panels() -> (PanelLabels, Vec<[usize; 3]>) {
        let labels = PanelLabels::new(vec!["front".into(), "back".into()], vec![0, 1]).unwrap();
        (labels, vec![[0, 1, 2], [2, 1, 3]])
    }

    #[test]
    fn seam_vertices_belong_to_both_panels() {
        let (labels, triangles) = two_panels();
        assert_eq!(
            labels.of_vertex(&triangles, 5),
            vec![vec![0], vec![0, 1], vec![0, 1], vec![1], vec![]]
        );
        assert_eq!(labels.vertex_label(&triangles, 5), vec![0, 0, 0, 1, -1]);
    }

    #[test]
    fn the_segmentation_file_has_a_line_per_vertex() {
        let (labels, triangles) = two_panels();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("segmentation.txt");
        labels.write_segmentation(&path, &triangles, 5).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text, "front\nfront,back\nfront,back\nback\n\n");
    }

    #[test]
    fn a_triangle_of_no_panel_is_refused() {
        let e = PanelLabels::new(vec!["front".into()], vec![0, 1]).unwrap_err();
        assert!(e.contains("triangle 1"), "{e}");
    }
}
