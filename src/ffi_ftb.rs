//! The bridge's front-to-back display (paper 2): the bodies behind
//! `ffi::ftb_display`, for `vtkHybridOctreeDepthImage`.

use crate::error::{Error, Result};
use crate::ffi::{grid_of, guarded, FtbDesc, FtbImage, GridDesc};
use crate::ftb::{back_to_front, front_to_back, shade, BinaryOctree, Inside, View};
use std::time::Instant;

/// Largest image side the bridge draws.
const MAX_IMAGE_SIZE: usize = 8192;

/// Builds the binary octree of the borrowed image and draws it along `options.vpn`.
pub(crate) fn ftb_display(bytes: &[u8], desc: &GridDesc, options: &FtbDesc) -> std::result::Result<FtbImage, String> {
    guarded(|| display(bytes, desc, options))
}

fn display(bytes: &[u8], desc: &GridDesc, options: &FtbDesc) -> Result<FtbImage> {
    if !(8..=MAX_IMAGE_SIZE).contains(&options.image_size) {
        return Err(Error::InvalidArgument(format!(
            "the image size {} is out of range: use 8 to {MAX_IMAGE_SIZE} pixels",
            options.image_size
        )));
    }
    let view = View::new(options.vpn)?;
    let inside = if options.use_label { Inside::Label(options.label) } else { Inside::AtOrAbove(options.isovalue) };
    let grid = grid_of(bytes, desc)?;
    let started = Instant::now();
    let octree = BinaryOctree::from_grid(&grid, inside)?;
    let build_ms = started.elapsed().as_secs_f64() * 1e3;
    let (shown, bitmap_bytes) = if options.back_to_front {
        (back_to_front::display(&octree, &view, options.image_size), 0)
    } else {
        front_to_back::display(&octree, &view, options.image_size)
    };
    let picture = shade::shade(&shown.image, &view);
    let counts = octree.counts();
    let c = shown.counters;
    Ok(FtbImage {
        size: shown.image.size,
        depth: shown.image.depth.iter().map(|&z| if z.is_finite() { z as f32 } else { f32::NAN }).collect(),
        face: shown.image.face,
        shaded: picture
            .over([0.0; 3])
            .iter()
            .flat_map(|p| p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
            .collect(),
        white_visited: c.white_visited,
        black_visited: c.black_visited,
        gray_visited: c.gray_visited,
        faces: c.faces,
        scanlines: c.scanlines,
        pixels: c.pixels,
        display_ms: shown.ms,
        build_ms,
        bitmap_bytes,
        white_octants: counts.white,
        black_octants: counts.black,
        gray_octants: counts.gray,
        resolution: octree.n,
        view_case: format!("{:?}", view.case()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::{as_bytes, f32_desc};

    fn ball() -> (Vec<f32>, GridDesc) {
        let n = 20;
        let c = (n as f32 - 1.0) / 2.0;
        let data: Vec<f32> = (0..n * n * n)
            .map(|i| {
                let (x, y, z) = ((i % n) as f32 - c, ((i / n) % n) as f32 - c, (i / (n * n)) as f32 - c);
                (x * x + y * y + z * z).sqrt()
            })
            .collect();
        (data, f32_desc([n; 3]))
    }

    #[test]
    fn front_to_back_and_back_to_front_draw_the_same_depth() {
        let (data, desc) = ball();
        // Inside: distance >= 6 (everything but a central ball; the padding is white).
        let mut options = FtbDesc {
            isovalue: 6.0,
            use_label: false,
            label: 0.0,
            vpn: [1.0, -1.0, 1.0],
            image_size: 64,
            back_to_front: false,
        };
        let f = ftb_display(as_bytes(&data), &desc, &options).unwrap();
        options.back_to_front = true;
        let b = ftb_display(as_bytes(&data), &desc, &options).unwrap();
        assert_eq!(f.face, b.face);
        assert!(f.depth.iter().zip(&b.depth).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(f.faces < b.faces && f.bitmap_bytes > 0 && b.bitmap_bytes == 0);
        assert_eq!(f.view_case, "XYZ");
        assert_eq!(f.shaded.len(), 3 * 64 * 64);
        assert!(f.face.iter().any(|&x| x != 0));
    }

    #[test]
    fn bad_options_are_clear_errors() {
        let (data, desc) = ball();
        let ok = FtbDesc {
            isovalue: 6.0,
            use_label: false,
            label: 0.0,
            vpn: [0.0, 0.0, 1.0],
            image_size: 64,
            back_to_front: false,
        };
        let zero = FtbDesc { vpn: [0.0; 3], ..ok };
        assert!(ftb_display(as_bytes(&data), &desc, &zero).err().unwrap().contains("(0, 0, 0)"));
        let small = FtbDesc { image_size: 2, ..ok };
        assert!(ftb_display(as_bytes(&data), &desc, &small).err().unwrap().contains("image size"));
        let nan = FtbDesc { isovalue: f64::NAN, ..ok };
        assert!(ftb_display(as_bytes(&data), &desc, &nan).err().unwrap().contains("not a finite"));
    }
}
