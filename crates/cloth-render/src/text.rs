//! Labels in the 8 x 8 bitmap font of the `font8x8` crate, drawn at a whole-number scale.
//! Only ASCII is available (the crate's Unicode tables are not enabled); anything else is
//! shown as '?'.

use super::image::Image;
use font8x8::legacy::BASIC_LEGACY;

/// Glyph cell size at scale 1, pixels.
pub(crate) const GLYPH: u32 = 8;

/// The width of `text` at `scale`, pixels.
pub(crate) fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * GLYPH * scale
}

/// `text` cut to at most `width` pixels at `scale`, ending in ".." when cut.
pub(crate) fn fit_text(text: &str, width: u32, scale: u32) -> String {
    let room = (width / (GLYPH * scale.max(1))) as usize;
    if text.chars().count() <= room {
        return text.to_string();
    }
    let keep = room.saturating_sub(2);
    text.chars()
        .take(keep)
        .chain("..".chars().take(room - keep))
        .collect()
}

/// Draws `text` with its top left corner at (`x`, `y`); clipped to the image.
pub(crate) fn draw_text(image: &mut Image, x: i64, y: i64, text: &str, scale: u32, colour: [u8; 3]) {
    let s = scale.max(1) as i64;
    for (k, ch) in text.chars().enumerate() {
        let code = if ch.is_ascii() { ch as usize } else { '?' as usize };
        let glyph = BASIC_LEGACY[code];
        let left = x + k as i64 * GLYPH as i64 * s;
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..GLYPH as i64 {
                // Bit 0 is the leftmost pixel of the row.
                if bits >> col & 1 == 1 {
                    image.fill_rect(left + col * s, y + row as i64 * s, s, s, colour);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn_inside_its_box_and_scales() {
        for scale in [1, 2, 3] {
            let mut image = Image::new(100, 40, [255; 3]);
            draw_text(&mut image, 5, 6, "0 %", scale, [0; 3]);
            let (mut inked, mut x_max, mut y_max) = (0, 0, 0);
            for y in 0..40 {
                for x in 0..100 {
                    if image.pixel(x, y) == Some([0; 3]) {
                        inked += 1;
                        assert!(x >= 5 && y >= 6);
                        x_max = x_max.max(x);
                        y_max = y_max.max(y);
                    }
                }
            }
            assert!(inked > 0);
            assert!(x_max < 5 + text_width("0 %", scale) && y_max < 6 + GLYPH * scale);
            // The '0' glyph differs from the '%' glyph: the font is really read.
            let ink = |x0: u32| (x0..x0 + 8 * scale).flat_map(|x| (6..6 + 8 * scale).map(move |y| (x, y)));
            let left: Vec<bool> = ink(5).map(|(x, y)| image.pixel(x, y) == Some([0; 3])).collect();
            let right: Vec<bool> = ink(5 + 16 * scale)
                .map(|(x, y)| image.pixel(x, y) == Some([0; 3]))
                .collect();
            assert_ne!(left, right);
        }
    }

    #[test]
    fn long_text_is_cut_to_fit() {
        assert_eq!(fit_text("warp strain", 16 * 11, 2), "warp strain");
        assert_eq!(fit_text("warp strain", 16 * 6, 2), "warp..");
        assert_eq!(fit_text("warp", 16, 2), ".");
    }
}
