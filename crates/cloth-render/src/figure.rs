//! A figure: panels side by side in one image, each framing its own meshes under a short
//! title, over a light gradient, with an optional strain legend along the bottom.

use super::camera::{Camera, View};
use super::image::Image;
use super::legend::{draw_legend, strip_height, Legend, INK};
use super::raster::{draw, Rect};
use super::text::{draw_text, fit_text, text_width, GLYPH};
use super::RenderMesh;

/// One picture of a figure: what to draw, and what to call it.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel<'a> {
    pub title: String,
    pub meshes: Vec<&'a RenderMesh>,
}

/// Background, top and bottom: light, a little darker below so the eye reads a ground
/// without a floor to frame.
const SKY: [f64; 3] = [251.0, 251.0, 253.0];
const GROUND: [f64; 3] = [219.0, 223.0, 230.0];
const DIVIDER: [u8; 3] = [208, 212, 219];

/// How much the 8-pixel font is enlarged: twice from small pictures on, more for big ones.
fn text_scale(width: u32, height: u32) -> u32 {
    if width < 320 || height < 240 {
        1
    } else {
        (height / 500).clamp(2, 4)
    }
}

fn background(width: u32, height: u32) -> Image {
    let mut image = Image::new(width, height, [0; 3]);
    let stride = 3 * width as usize;
    if stride == 0 {
        return image;
    }
    for (y, row) in image.rgb.chunks_exact_mut(stride).enumerate() {
        let t = y as f64 / (height.max(2) - 1) as f64;
        let c = [0, 1, 2].map(|j| (SKY[j] + (GROUND[j] - SKY[j]) * t).round() as u8);
        for p in row.chunks_exact_mut(3) {
            p.copy_from_slice(&c);
        }
    }
    image
}

/// Draws `panels` side by side, each seen from `view` and fitted to its own meshes, in a
/// `width` x `height` image, with `legend` along the bottom if given.
pub fn figure(panels: &[Panel<'_>], legend: Option<&Legend>, view: &View, width: u32, height: u32) -> Image {
    let mut image = background(width, height);
    let scale = text_scale(width, height);
    let s = scale as i64;
    let title_h = if panels.iter().any(|p| !p.title.is_empty()) {
        scale * (GLYPH + 10)
    } else {
        scale * 4
    };
    let legend_h = legend.map_or(0, |_| strip_height(scale));
    let margin = 4 * scale;
    let bottom = height.saturating_sub(legend_h + margin);

    let n = panels.len() as u32;
    for (i, panel) in panels.iter().enumerate() {
        let x0 = (i as u64 * width as u64 / n as u64) as u32;
        let x1 = ((i as u64 + 1) * width as u64 / n as u64) as u32;
        let panel_w = x1 - x0;
        if i > 0 {
            image.fill_rect(
                x0 as i64,
                title_h as i64 / 2,
                1,
                bottom as i64 - title_h as i64 / 2,
                DIVIDER,
            );
        }
        let title = fit_text(&panel.title, panel_w.saturating_sub(2 * margin), scale);
        let title_x = x0 as i64 + (panel_w as i64 - text_width(&title, scale) as i64) / 2;
        draw_text(&mut image, title_x, 6 * s, &title, scale, INK);

        let rect = Rect {
            x: x0 + margin,
            y: title_h,
            width: panel_w.saturating_sub(2 * margin),
            height: bottom.saturating_sub(title_h),
        };
        if rect.width == 0 || rect.height == 0 {
            continue;
        }
        let sets: Vec<&[cloth_core::math::Vec3]> = panel.meshes.iter().map(|m| &m.positions[..]).collect();
        let camera = Camera::fit(view, &sets, rect.width as f64, rect.height as f64);
        draw(&mut image, rect, &camera, &panel.meshes);
    }
    if let Some(legend) = legend {
        let rect = Rect {
            x: 0,
            y: height.saturating_sub(legend_h),
            width,
            height: legend_h,
        };
        draw_legend(&mut image, rect, legend, scale);
    }
    image
}

#[cfg(test)]
mod tests {
    use super::super::MeshColours;
    use super::*;
    use cloth_core::math::Vec3;

    fn box_mesh(colour: [u8; 3]) -> RenderMesh {
        let positions: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    (i & 1) as f64,
                    ((i >> 1) & 1) as f64 * 0.5,
                    ((i >> 2) & 1) as f64 * 2.0,
                )
            })
            .collect();
        let triangles = vec![
            [0, 2, 3],
            [0, 3, 1],
            [4, 5, 7],
            [4, 7, 6],
            [0, 1, 5],
            [0, 5, 4],
            [2, 6, 7],
            [2, 7, 3],
            [0, 4, 6],
            [0, 6, 2],
            [1, 3, 7],
            [1, 7, 5],
        ];
        RenderMesh {
            positions,
            triangles,
            colours: MeshColours::Uniform(colour),
        }
    }

    /// Columns holding a pixel of roughly this hue among the first `rows` rows.
    fn columns_with(image: &Image, rows: u32, hue: impl Fn([u8; 3]) -> bool) -> Vec<u32> {
        (0..image.width)
            .filter(|&x| (0..rows).any(|y| image.pixel(x, y).is_some_and(&hue)))
            .collect()
    }

    #[test]
    fn panels_sit_side_by_side_at_the_requested_size() {
        let red = box_mesh([220, 40, 40]);
        let blue = box_mesh([40, 40, 220]);
        let panels = [
            Panel {
                title: "red".into(),
                meshes: vec![&red],
            },
            Panel {
                title: "blue".into(),
                meshes: vec![&blue],
            },
        ];
        let legend = Legend {
            caption: "strain".into(),
        };
        let image = figure(&panels, Some(&legend), &View::default(), 500, 300);
        assert_eq!(
            (image.width, image.height, image.rgb.len()),
            (500, 300, 500 * 300 * 3)
        );
        // The legend's bar holds both hues too: look above it.
        let above = 300 - strip_height(2);
        let reds = columns_with(&image, above, |[r, g, b]| r > 120 && g < 60 && b < 60);
        let blues = columns_with(&image, above, |[r, g, b]| b > 120 && r < 60 && g < 60);
        assert!(
            reds.len() > 50 && blues.len() > 50,
            "{} {}",
            reds.len(),
            blues.len()
        );
        assert!(reds.iter().all(|&x| x < 250), "red box leaves its panel");
        assert!(blues.iter().all(|&x| x >= 250), "blue box leaves its panel");
        // The legend is drawn below, up to the red end of the scale.
        let legend_reds = (0..500).filter(|&x| {
            (above..300).any(|y| {
                image
                    .pixel(x, y)
                    .is_some_and(|[r, g, b]| r > 240 && g < 30 && b < 30)
            })
        });
        assert!(legend_reds.count() > 0);
    }

    #[test]
    fn an_empty_figure_is_just_background() {
        let image = figure(&[], None, &View::default(), 64, 48);
        assert_eq!(image.pixel(10, 0), Some([251, 251, 253]));
        assert_eq!(image.pixel(10, 47), Some([219, 223, 230]));
    }
}
