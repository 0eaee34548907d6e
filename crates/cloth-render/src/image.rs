//! An RGB picture in memory, and its PNG file.

use cloth_formats::atomic::write_atomically;
use std::path::Path;

/// The picture sizes drawn, pixels a side: smaller has no room for the titles, larger is
/// surely a typo.
pub const IMAGE_SIDES: std::ops::RangeInclusive<u32> = 32..=16384;

/// Whether a picture of `width` x `height` pixels can be drawn; if not, why.
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    if IMAGE_SIDES.contains(&width) && IMAGE_SIDES.contains(&height) {
        Ok(())
    } else {
        Err(format!(
            "{width} x {height} pixels: each side must be {} to {}",
            IMAGE_SIDES.start(),
            IMAGE_SIDES.end()
        ))
    }
}

/// 8-bit RGB pixels, row by row from the top left, 3 bytes each.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

impl Image {
    /// An image filled with one colour.
    pub fn new(width: u32, height: u32, colour: [u8; 3]) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            rgb: colour.repeat(n),
        }
    }

    /// The pixel at column `x`, row `y`; `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        self.rgb.get(i..i + 3).map(|p| [p[0], p[1], p[2]])
    }

    /// Sets a pixel; coordinates outside the image are ignored, so callers may draw
    /// shapes that overhang the edge.
    pub(crate) fn put(&mut self, x: i64, y: i64, colour: [u8; 3]) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        if let Some(p) = self.rgb.get_mut(i..i + 3) {
            p.copy_from_slice(&colour);
        }
    }

    /// Fills `w` x `h` pixels from (`x`, `y`), clipped to the image.
    pub(crate) fn fill_rect(&mut self, x: i64, y: i64, w: i64, h: i64, colour: [u8; 3]) {
        for yy in y.max(0)..(y + h).min(self.height as i64) {
            for xx in x.max(0)..(x + w).min(self.width as i64) {
                self.put(xx, yy, colour);
            }
        }
    }

    /// Writes an 8-bit RGB PNG, atomically (see [`write_atomically`]).
    pub fn write_png(&self, path: &Path) -> std::io::Result<()> {
        let expected = 3 * self.width as usize * self.height as usize;
        if self.rgb.len() != expected || expected == 0 {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "a {}x{} image needs {expected} bytes of pixels (at least one pixel), it has {}",
                    self.width,
                    self.height,
                    self.rgb.len()
                ),
            ));
        }
        write_atomically(path, |out| {
            let mut encoder = png::Encoder::new(out, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&self.rgb)?;
            writer.finish()?;
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_reads_back_the_same_pixels() {
        let mut image = Image::new(5, 3, [10, 20, 30]);
        image.put(4, 2, [200, 100, 0]);
        image.put(-1, 7, [1, 1, 1]);
        let path = std::env::temp_dir().join(format!("cloth-render-{}-image.png", std::process::id()));
        image.write_png(&path).unwrap();
        let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!((info.width, info.height), (5, 3));
        assert_eq!(&buf[..info.buffer_size()], &image.rgb[..]);
        assert_eq!(image.pixel(4, 2), Some([200, 100, 0]));
        assert_eq!(image.pixel(5, 0), None);
    }
}
