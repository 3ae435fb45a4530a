//! A rendered picture: premultiplied RGBA in `[0, 1]`, row by row from the
//! top, and its PNG.
//!
//! Shown over a background colour `B` (straight RGB), a pixel `(C, A)` is
//!
//! ```text
//! shown = C + (1 - A) B                                 (C premultiplied)
//! luminance = 0.2126 R + 0.7152 G + 0.0722 B            (Rec. 709 weights)
//! ```
//!
//! The PNG is 8-bit RGB, `round(255 clamp(shown, 0, 1))`, its one IDAT chunk a
//! zlib stream (flate2), each chunk closed by the CRC-32 of ISO 3309
//! (polynomial 0xEDB88320, reflected).

use crate::base::error::{Error, Result};
use std::io::Write;
use std::path::Path;

/// The background pictures are shown over (ParaView's default blue-grey).
pub const BACKGROUND: [f32; 3] = [0.32, 0.34, 0.43];

/// A `width x height` picture of premultiplied RGBA values.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Premultiplied `[r, g, b, a]` in `[0, 1]`, pixel `(x, y)` at `x + width * y`, `y = 0` on top.
    pub rgba: Vec<[f32; 4]>,
}

impl Image {
    /// A fully transparent picture.
    pub fn new(width: usize, height: usize) -> Image {
        Image { width, height, rgba: vec![[0.0; 4]; width * height] }
    }

    /// Each pixel shown over `background`: `C + (1 - A) B`.
    pub fn over(&self, background: [f32; 3]) -> Vec<[f32; 3]> {
        self.rgba.iter().map(|p| std::array::from_fn(|k| p[k] + (1.0 - p[3]) * background[k])).collect()
    }

    /// Rec. 709 luminance of each pixel shown over `background`.
    pub fn luminance(&self, background: [f32; 3]) -> Vec<f64> {
        self.over(background)
            .iter()
            .map(|c| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64)
            .collect()
    }

    /// Writes the picture over [`BACKGROUND`] as an 8-bit RGB PNG.
    pub fn to_png(&self, path: impl AsRef<Path>) -> Result<()> {
        self.to_png_over(path, BACKGROUND)
    }

    /// Writes the picture over `background` as an 8-bit RGB PNG.
    pub fn to_png_over(&self, path: impl AsRef<Path>, background: [f32; 3]) -> Result<()> {
        let path = path.as_ref();
        let fail = |message: String| Error::Write { path: path.display().to_string(), message };
        let bytes = self.png_bytes(background).map_err(|e| fail(format!("cannot encode the PNG: {e}")))?;
        std::fs::write(path, bytes).map_err(|e| fail(format!("{e}; check the folder exists and is writable")))
    }

    /// The PNG file: signature, IHDR, IDAT, IEND.
    fn png_bytes(&self, background: [f32; 3]) -> std::io::Result<Vec<u8>> {
        if self.width == 0 || self.height == 0 || self.width > u32::MAX as usize || self.height > u32::MAX as usize {
            return Err(std::io::Error::other(format!("a {}x{} picture cannot be a PNG", self.width, self.height)));
        }
        let shown = self.over(background);
        let mut raw = Vec::with_capacity(self.height * (1 + 3 * self.width));
        for row in shown.chunks(self.width) {
            raw.push(0); // filter type None
            raw.extend(row.iter().flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)));
        }
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(&raw)?;
        let idat = z.finish()?;
        let mut header = Vec::with_capacity(13);
        header.extend((self.width as u32).to_be_bytes());
        header.extend((self.height as u32).to_be_bytes());
        header.extend([8, 2, 0, 0, 0]); // bit depth 8, colour type RGB, deflate, filter 0, no interlace
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        chunk(&mut png, b"IHDR", &header);
        chunk(&mut png, b"IDAT", &idat);
        chunk(&mut png, b"IEND", &[]);
        Ok(png)
    }
}

/// Appends a PNG chunk: length, type, data, CRC-32 of type and data.
fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend(kind);
    out.extend(data);
    let crc = crc32(&out[start..]);
    out.extend(crc.to_be_bytes());
}

/// CRC-32 (ISO 3309, as PNG and zlib's `crc32`): table of the reflected
/// polynomial 0xEDB88320, register starting at and finally xored with 0xFFFFFFFF.
fn crc32(bytes: &[u8]) -> u32 {
    const TABLE: [u32; 256] = {
        let mut table = [0u32; 256];
        let mut n = 0;
        while n < 256 {
            let mut c = n as u32;
            let mut k = 0;
            while k < 8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
                k += 1;
            }
            table[n] = c;
            n += 1;
        }
        table
    };
    !bytes.iter().fold(!0u32, |c, &b| TABLE[((c ^ b as u32) & 0xFF) as usize] ^ (c >> 8))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b"IEND"), 0xAE42_6082); // the CRC every PNG ends with
    }

    #[test]
    fn png_round_trips_through_its_chunks() {
        let mut img = Image::new(3, 2);
        img.rgba[0] = [1.0, 0.0, 0.0, 1.0];
        img.rgba[4] = [0.25, 0.25, 0.25, 0.5];
        let png = img.png_bytes([0.0, 0.0, 1.0]).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        // Walk the chunks, checking each CRC; inflate the IDAT.
        let (mut at, mut kinds, mut raw) = (8, Vec::new(), Vec::new());
        while at < png.len() {
            let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
            let body = &png[at + 4..at + 8 + len];
            assert_eq!(crc32(body), u32::from_be_bytes(png[at + 8 + len..at + 12 + len].try_into().unwrap()));
            kinds.push(String::from_utf8(body[..4].to_vec()).unwrap());
            if &body[..4] == b"IDAT" {
                flate2::read::ZlibDecoder::new(&body[4..]).read_to_end(&mut raw).unwrap();
            }
            at += 12 + len;
        }
        assert_eq!(kinds, ["IHDR", "IDAT", "IEND"]);
        assert_eq!(raw.len(), 2 * (1 + 9));
        assert_eq!(&raw[..4], &[0, 255, 0, 0]); // filter byte, red
        assert_eq!(&raw[4..7], &[0, 0, 255]); // transparent: the background
        assert_eq!(&raw[10..11], &[0]);
        assert_eq!(&raw[14..17], &[64, 64, 191]); // 0.25 + 0.5 * (0, 0, 1)
        let path = std::env::temp_dir().join(format!("hybrid-octree-image-{}.png", std::process::id()));
        img.to_png(&path).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 50);
        std::fs::remove_file(&path).unwrap();
        assert!(img.to_png("/nonexistent-folder/x.png").unwrap_err().to_string().contains("folder exists"));
    }

    #[test]
    fn luminance_weights_sum_to_one() {
        let mut img = Image::new(1, 1);
        img.rgba[0] = [1.0, 1.0, 1.0, 1.0];
        assert!((img.luminance(BACKGROUND)[0] - 1.0).abs() < 1e-6);
        assert_eq!(Image::new(1, 1).luminance([0.0; 3])[0], 0.0);
    }
}
