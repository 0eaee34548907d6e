//! The strain colour legend: a horizontal bar of the PLY's colour scale from 0 % to full
//! scale, ticked and labelled in percent, with a caption to its left.

use super::image::Image;
use super::raster::Rect;
use super::text::{draw_text, fit_text, text_width, GLYPH};
use crate::strain_colours::{colour, FULL_SCALE_PERCENT};

/// A legend for strain coloured as in the PLY output: [`colour`]`(s / FULL_SCALE_PERCENT)`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Legend {
    /// What the colours measure, e.g. "warp strain".
    pub caption: String,
}

/// Intervals between labels: at 5 % full scale, one per percent.
const TICKS: usize = 5;
pub(crate) const INK: [u8; 3] = [40, 44, 52];
const OUTLINE: [u8; 3] = [110, 114, 122];

/// The height of the strip a legend needs at text `scale`: margin, bar, tick, gap,
/// labels, margin, in glyph-pixel units.
pub(crate) fn strip_height(scale: u32) -> u32 {
    scale * (4 + 7 + 2 + 2 + GLYPH + 5)
}

fn label(value: f64) -> String {
    if (value - value.round()).abs() < 1e-9 {
        format!("{value:.0} %")
    } else {
        format!("{value:.1} %")
    }
}

/// Draws `legend` centred in the strip `rect`.
pub(crate) fn draw_legend(image: &mut Image, rect: Rect, legend: &Legend, scale: u32) {
    let s = scale.max(1) as i64;
    let bar_h = 7 * s;
    let gap = 6 * s;
    // The last label hangs over the end of the bar by half its width.
    let overhang = text_width(&label(FULL_SCALE_PERCENT), scale) as i64 / 2 + s;
    let room = rect.width as i64 - 2 * overhang;
    // Wide enough that two glyphs of space keep neighbouring labels apart, where there is
    // room: "0 % 1 %" is ambiguous at a glance.
    let spaced = TICKS as i64 * (text_width(&label(FULL_SCALE_PERCENT), scale) as i64 + 2 * GLYPH as i64 * s);
    let bar_w = ((rect.width as f64 * 0.4) as i64)
        .clamp(spaced, 700.max(spaced))
        .min(room - gap);
    if bar_w < 20 {
        return;
    }
    let caption = fit_text(&legend.caption, (room - gap - bar_w).max(0) as u32, scale);
    let caption_w = text_width(&caption, scale) as i64;
    let total = if caption.is_empty() {
        bar_w
    } else {
        caption_w + gap + bar_w
    };
    let left = rect.x as i64 + (rect.width as i64 - total) / 2;
    let bar_x = left + total - bar_w;
    let bar_y = rect.y as i64 + 4 * s;

    draw_text(
        image,
        left,
        bar_y + (bar_h - GLYPH as i64 * s) / 2,
        &caption,
        scale,
        INK,
    );
    for i in 0..bar_w {
        let c = colour((i as f64 + 0.5) / bar_w as f64);
        image.fill_rect(bar_x + i, bar_y, 1, bar_h, c);
    }
    image.fill_rect(bar_x - 1, bar_y - 1, bar_w + 2, 1, OUTLINE);
    image.fill_rect(bar_x - 1, bar_y + bar_h, bar_w + 2, 1, OUTLINE);
    image.fill_rect(bar_x - 1, bar_y, 1, bar_h, OUTLINE);
    image.fill_rect(bar_x + bar_w, bar_y, 1, bar_h, OUTLINE);
    let tick_w = (s / 2).max(1);
    for k in 0..=TICKS {
        let x = bar_x + (k as i64 * (bar_w - 1)) / TICKS as i64;
        image.fill_rect(x - tick_w / 2, bar_y + bar_h, tick_w, 2 * s, OUTLINE);
        let text = label(FULL_SCALE_PERCENT * k as f64 / TICKS as f64);
        let w = text_width(&text, scale) as i64;
        draw_text(image, x - w / 2, bar_y + bar_h + 4 * s, &text, scale, INK);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bar_runs_from_the_low_to_the_high_end_of_the_scale() {
        let scale = 2;
        let mut image = Image::new(800, strip_height(scale), [255; 3]);
        let rect = Rect {
            x: 0,
            y: 0,
            width: 800,
            height: strip_height(scale),
        };
        let legend = Legend {
            caption: "warp strain".into(),
        };
        draw_legend(&mut image, rect, &legend, scale);
        // Along the middle of the bar, the first and last coloured pixels are the scale's
        // ends.
        let y = 4 * scale + 3 * scale;
        let row: Vec<[u8; 3]> = (0..800).filter_map(|x| image.pixel(x, y)).collect();
        let bar: Vec<&[u8; 3]> = row
            .iter()
            .filter(|p| **p != [255; 3] && **p != INK && **p != OUTLINE)
            .collect();
        assert!(bar.len() > 200, "{} bar pixels", bar.len());
        let (first, last) = (bar[0], bar[bar.len() - 1]);
        let near = |a: &[u8; 3], b: [u8; 3]| (0..3).all(|j| (a[j] as i32 - b[j] as i32).abs() < 12);
        assert!(
            near(first, colour(0.0)) && near(last, colour(1.0)),
            "{first:?} {last:?}"
        );
        // Labels and caption are inked below and beside the bar, inside the strip.
        let ink = image.rgb.chunks_exact(3).filter(|p| *p == INK).count();
        assert!(ink > 100);
    }

    #[test]
    fn labels_read_in_percent() {
        assert_eq!(label(0.0), "0 %");
        assert_eq!(label(5.0), "5 %");
        assert_eq!(label(2.5), "2.5 %");
    }
}
