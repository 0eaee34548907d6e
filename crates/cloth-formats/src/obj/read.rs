//! Reading OBJ: the geometry statements (`v`, `vt`, `f`), with the file's own numbering,
//! so a vertex is the same number for everyone who reads the file (a cloth's pins, a body's
//! errors, a picture). Normals, groups, objects, materials, points and lines shape nothing
//! and are skipped.

use crate::error::{read_bytes, FormatError};
use crate::mesh::fan;
use cloth_core::math::Vec3;
use std::path::Path;

/// A face: its line, its corners' vertices and, when every corner has one, their texture
/// coordinates (all 0-based).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjFace {
    pub line: usize,
    pub vertices: Vec<usize>,
    pub texcoords: Option<Vec<usize>>,
}

/// What was wrong, and on which line (1-based).
#[derive(Debug, Clone, PartialEq)]
pub struct ObjSyntaxError {
    pub line: usize,
    pub message: String,
}

/// The geometry of an OBJ file, every vertex in the file's order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjFile {
    pub positions: Vec<Vec3>,
    /// The line of each vertex.
    pub position_lines: Vec<usize>,
    /// Each vertex's colour (`v x y z r g b`, 0 to 1) where the file gives one.
    pub colours: Vec<Option<[f64; 3]>>,
    /// Texture coordinates (`vt u v`; v is 0 when left out).
    pub texcoords: Vec<[f64; 2]>,
    pub first_texcoord_line: Option<usize>,
    pub faces: Vec<ObjFace>,
}

impl ObjFile {
    /// Reads `path`; text that is not UTF-8 (a comment in Latin-1) is read lossily.
    pub fn read(path: &Path) -> Result<Self, FormatError> {
        let bytes = read_bytes(path)?;
        Self::parse(&String::from_utf8_lossy(&bytes)).map_err(|e| FormatError::Parse {
            path: path.to_path_buf(),
            line: Some(e.line),
            message: e.message,
        })
    }

    /// Parses OBJ text. Coordinates must be finite; face corners name vertices already
    /// given (from 1, or counting back from the last with negative numbers).
    pub fn parse(text: &str) -> Result<Self, ObjSyntaxError> {
        let mut obj = ObjFile::default();
        for (n, raw) in text.lines().enumerate() {
            let line = n + 1;
            let fail = |message: String| ObjSyntaxError { line, message };
            let content = raw.split('#').next().unwrap_or("");
            let mut words = content.split_whitespace();
            match words.next() {
                Some("v") => {
                    let numbers = finite_numbers(words)
                        .filter(|p| p.len() >= 3)
                        .ok_or_else(|| fail("a vertex (v) needs 3 finite numbers".into()))?;
                    obj.positions.push(Vec3::new(numbers[0], numbers[1], numbers[2]));
                    obj.position_lines.push(line);
                    // `v x y z r g b`, as many tools write vertex colours (`v x y z w` has
                    // a weight, which a mesh does not use).
                    obj.colours
                        .push((numbers.len() >= 6).then(|| [numbers[3], numbers[4], numbers[5]]));
                }
                Some("vt") => {
                    let numbers = finite_numbers(words)
                        .filter(|t| !t.is_empty())
                        .ok_or_else(|| fail("a texture coordinate (vt) needs finite numbers".into()))?;
                    obj.texcoords
                        .push([numbers[0], numbers.get(1).copied().unwrap_or(0.0)]);
                    obj.first_texcoord_line.get_or_insert(line);
                }
                Some("f") => {
                    let face = obj.face(line, words).map_err(fail)?;
                    obj.faces.push(face);
                }
                _ => {}
            }
        }
        Ok(obj)
    }

    /// The faces as triangles: each polygon a fan from its first corner.
    pub fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        self.faces.iter().flat_map(|f| fan(&f.vertices))
    }

    fn face<'a>(&self, line: usize, corners: impl Iterator<Item = &'a str>) -> Result<ObjFace, String> {
        let (mut vertices, mut texcoords) = (Vec::new(), Vec::new());
        for corner in corners {
            let mut parts = corner.split('/');
            let index = |part: Option<&str>, count: usize, what: &str| -> Result<Option<usize>, String> {
                let Some(part) = part.filter(|p| !p.is_empty()) else {
                    return Ok(None);
                };
                let i: i64 = part
                    .parse()
                    .map_err(|_| format!("'{corner}' is not a face corner"))?;
                let resolved = if i > 0 { i - 1 } else { count as i64 + i };
                if i == 0 || resolved < 0 || resolved >= count as i64 {
                    return Err(format!(
                        "the face names {what} {i}, which does not exist ({count} so far)"
                    ));
                }
                Ok(Some(resolved as usize))
            };
            let vertex = index(parts.next(), self.positions.len(), "vertex")?
                .ok_or_else(|| format!("'{corner}' names no vertex"))?;
            vertices.push(vertex);
            texcoords.push(index(parts.next(), self.texcoords.len(), "texture coordinate")?);
        }
        if vertices.len() < 3 {
            return Err("a face needs at least 3 corners".into());
        }
        let texcoords = if texcoords.iter().all(Option::is_some) {
            Some(texcoords.into_iter().flatten().collect())
        } else if texcoords.iter().all(Option::is_none) {
            None
        } else {
            return Err("some corners of the face have texture coordinates and some do not".into());
        };
        Ok(ObjFace {
            line,
            vertices,
            texcoords,
        })
    }
}

/// Every word as a finite number, or `None` if one is not.
fn finite_numbers<'a>(words: impl Iterator<Item = &'a str>) -> Option<Vec<f64>> {
    words
        .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertices_keep_the_files_numbers_and_faces_their_lines() {
        // Faces use the vertices out of order, one as a quad, with negative indices and
        // normals; vertex 5 is used last and vertex 6 by nothing.
        let obj = ObjFile::parse(
            "o sheet\nv 0 0.1 1\nv 0.1 0.1 1\nv 0.1 0 1\nv 0 0 1\nv 0.05 -0.1 1\nv 9 9 9 # loose\n\
             vn 0 0 1\ng a\nf 4//1 3//1 2//1 1//1\nf -4 -3 -2\nl 1 2\np 3\n",
        )
        .unwrap();
        assert_eq!(obj.positions.len(), 6);
        assert_eq!(obj.positions[4], Vec3::new(0.05, -0.1, 1.0));
        assert_eq!(obj.position_lines, vec![2, 3, 4, 5, 6, 7]);
        assert_eq!(obj.faces[0].line, 10);
        assert_eq!(obj.faces[1].vertices, vec![2, 3, 4]);
        let triangles: Vec<_> = obj.triangles().collect();
        assert_eq!(triangles, vec![[3, 2, 1], [3, 1, 0], [2, 3, 4]]);
        assert!(obj.colours.iter().all(Option::is_none));
    }

    #[test]
    fn texture_coordinates_and_colours_are_read() {
        let obj =
            ObjFile::parse("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0.5 1\nvt 0 0\nvt 1\nvt 0 1\nf 1/1 2/2 3/3\n")
                .unwrap();
        assert_eq!(
            obj.colours,
            vec![Some([1.0, 0.0, 0.0]), None, Some([0.0, 0.5, 1.0])]
        );
        assert_eq!(obj.texcoords, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(obj.first_texcoord_line, Some(4));
        assert_eq!(obj.faces[0].texcoords, Some(vec![0, 1, 2]));
    }

    #[test]
    fn errors_name_the_line() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", 2, "3 finite numbers"),
            ("v 0 0 0\nv 1 0 NaN\n", 2, "3 finite numbers"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", 4, "vertex 7"),
            ("v 0 0 0\nv 1 0 0\nf 1 2 0\n", 3, "vertex 0"),
            ("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "3 corners"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n",
                5,
                "some corners",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n", 4, "'x'"),
            ("vt a b\n", 1, "texture coordinate"),
        ];
        for (text, line, says) in cases {
            let e = ObjFile::parse(text).unwrap_err();
            assert_eq!(e.line, line, "{text:?}: {e:?}");
            assert!(e.message.contains(says), "{text:?}: {e:?}");
        }
    }
}
