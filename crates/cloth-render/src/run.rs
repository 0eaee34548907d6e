//! The picture of a finished run: the cloth coloured by warp strain beside the cloth
//! coloured by weft strain, the bodies grey in both, on the PLY output's colour scale.

use super::camera::View;
use super::figure::{figure, Panel};
use super::image::Image;
use super::legend::Legend;
use super::{MeshColours, RenderMesh, NEUTRAL_GREY};
use crate::strain_colours::{strain_colour, vertex_means};
use cloth_collide::TriSurface;
use cloth_core::{math::Vec3, ClothMesh, StrainReport};

/// Two panels, "warp strain" and "weft strain", each the bodies in grey and the cloth
/// coloured per vertex by the mean strain of its triangles (compression shown as 0), with
/// the legend; seen from the default [`View`].
///
/// `positions` has one entry per vertex of `mesh` (the run's result); `bodies` may be
/// empty (a pinned sheet).
pub fn render_run(
    mesh: &ClothMesh,
    positions: &[Vec3],
    bodies: &[TriSurface],
    width: u32,
    height: u32,
) -> Image {
    assert_eq!(
        positions.len(),
        mesh.vertex_count(),
        "render_run needs one position per cloth vertex"
    );
    let strain = StrainReport::new(mesh, positions);
    let cloth = |per_triangle: &[f64]| RenderMesh {
        positions: positions.to_vec(),
        triangles: mesh.triangles().to_vec(),
        colours: MeshColours::PerVertex(
            vertex_means(mesh.vertex_count(), mesh.triangles(), per_triangle)
                .into_iter()
                .map(strain_colour)
                .collect(),
        ),
    };
    let warp = cloth(&strain.warp);
    let weft = cloth(&strain.weft);
    let bodies: Vec<RenderMesh> = bodies
        .iter()
        .map(|b| RenderMesh::from_surface(b, NEUTRAL_GREY))
        .collect();
    let panel = |title: &str, cloth| Panel {
        title: title.to_string(),
        meshes: bodies.iter().chain([cloth]).collect(),
    };
    let panels = [panel("warp strain", &warp), panel("weft strain", &weft)];
    let legend = Legend {
        caption: "strain".to_string(),
    };
    figure(&panels, Some(&legend), &View::default(), width, height)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::GridBuilder;

    /// A 1 m sheet hanging in the x-z plane, stretched 3 % along the warp (x) only, with
    /// a sphere behind it.
    #[test]
    fn warp_stretch_shows_in_the_warp_panel_only() {
        let mesh = GridBuilder::new(41, 41)
            .size(1.0, 1.0)
            .axes(Vec3::x(), Vec3::z())
            .build()
            .unwrap();
        let positions: Vec<Vec3> = mesh
            .positions()
            .iter()
            .map(|p| Vec3::new(1.03 * p.x, 0.0, p.z))
            .collect();
        let sphere = TriSurface::icosphere(0.3, 3).unwrap();
        let sphere = sphere.transformed(&nalgebra::Isometry3::translation(0.5, 0.6, 0.5));
        let (w, h) = (600, 360);
        let image = render_run(&mesh, &positions, &[sphere], w, h);
        assert_eq!((image.width, image.height), (w, h));
        // 3 % on a 5 % scale is yellow-green; 0 % is pure blue.
        let expected = strain_colour(3.0);
        let like = |p: [u8; 3], c: [u8; 3]| {
            let (r, g, b) = (p[0] as f64, p[1] as f64, p[2] as f64);
            let sum = r + g + b + 1.0;
            let want = (c[0] as f64, c[1] as f64, c[2] as f64);
            let want_sum = want.0 + want.1 + want.2;
            // Shading scales the colour: compare chromaticity.
            (r / sum - want.0 / want_sum).abs() < 0.08
                && (g / sum - want.1 / want_sum).abs() < 0.08
                && (b / sum - want.2 / want_sum).abs() < 0.08
        };
        let legend_top = h - super::super::legend::strip_height(2);
        let count = |x0: u32, x1: u32, c: [u8; 3]| {
            (x0..x1)
                .flat_map(|x| (0..legend_top).map(move |y| (x, y)))
                .filter(|&(x, y)| image.pixel(x, y).is_some_and(|p| like(p, c)))
                .count()
        };
        let half = w / 2;
        let warp_panel = count(0, half, expected);
        let weft_panel = count(half, w, expected);
        let weft_blue = count(half, w, strain_colour(0.0));
        assert!(warp_panel > 20_000, "warp panel: {warp_panel} stretched pixels");
        assert!(
            weft_panel < warp_panel / 20,
            "weft panel: {weft_panel} stretched pixels"
        );
        assert!(weft_blue > 20_000, "weft panel: {weft_blue} unstretched pixels");
    }
}
