//! Paper 2's front-to-back display through the bridge, for
//! `vtkHybridOctreeDepthImage`: the depth image drawn into the host's arrays.

use super::grid::grid_of;
use super::guard::{check_len, guarded, Bridged};
use super::{FtbDesc, FtbSummary, GridDesc};
use crate::error::{Error, Result};
use crate::ftb::{back_to_front, front_to_back, shade, BinaryOctree, Inside, View};
use std::time::Instant;

/// Largest image side the bridge draws.
const MAX_IMAGE_SIZE: usize = 8192;

/// Builds the binary octree of the borrowed image and draws it along `options.vpn`.
pub(crate) fn ftb_display(
    bytes: &[u8],
    desc: &GridDesc,
    options: &FtbDesc,
    depth: &mut [f32],
    face: &mut [u8],
    shaded: &mut [u8],
) -> Bridged<FtbSummary> {
    guarded(|| display(bytes, desc, options, depth, face, shaded))
}

fn display(
    bytes: &[u8],
    desc: &GridDesc,
    options: &FtbDesc,
    depth: &mut [f32],
    face: &mut [u8],
    shaded: &mut [u8],
) -> Result<FtbSummary> {
    let n = options.image_size;
    if !(8..=MAX_IMAGE_SIZE).contains(&n) {
        return Err(Error::InvalidArgument(format!(
            "the image size {n} is out of range: use 8 to {MAX_IMAGE_SIZE} pixels"
        )));
    }
    check_len("depth", depth, n * n)?;
    check_len("faces", face, n * n)?;
    check_len("shaded pixels", shaded, 3 * n * n)?;
    let view = View::new(options.vpn)?;
    let inside = if options.use_label { Inside::Label(options.label) } else { Inside::AtOrAbove(options.isovalue) };
    let grid = grid_of(bytes, desc)?;
    let started = Instant::now();
    let octree = BinaryOctree::from_grid(&grid, inside)?;
    let build_ms = started.elapsed().as_secs_f64() * 1e3;
    let (shown, bitmap_bytes) = if options.back_to_front {
        (back_to_front::display(&octree, &view, n), 0)
    } else {
        front_to_back::display(&octree, &view, n)
    };
    let picture = shade::shade(&shown.image, &view).over([0.0; 3]);
    // The display's rows go top down, VTK's images bottom up: pixel
    // (x, row from the top) goes to (x, n - 1 - row).
    for row in 0..n {
        let (from, to) = (row * n, (n - 1 - row) * n);
        for x in 0..n {
            let z = shown.image.depth[from + x];
            depth[to + x] = if z.is_finite() { z as f32 } else { f32::NAN };
            face[to + x] = shown.image.face[from + x];
            let rgb = picture[from + x].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
            shaded[3 * (to + x)..3 * (to + x) + 3].copy_from_slice(&rgb);
        }
    }
    let counts = octree.counts();
    let c = shown.counters;
    Ok(FtbSummary {
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
    use super::super::test_support::{as_bytes, f32_desc};
    use super::*;

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

    /// A drawn image: depth, faces, shaded pixels and the summary.
    struct Drawn {
        depth: Vec<f32>,
        face: Vec<u8>,
        shaded: Vec<u8>,
        summary: FtbSummary,
    }

    fn draw(data: &[f32], desc: &GridDesc, options: &FtbDesc) -> std::result::Result<Drawn, String> {
        let n = options.image_size;
        let (mut depth, mut face, mut shaded) = (vec![0.0; n * n], vec![0; n * n], vec![0; 3 * n * n]);
        let summary = ftb_display(as_bytes(data), desc, options, &mut depth, &mut face, &mut shaded)?;
        Ok(Drawn { depth, face, shaded, summary })
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
        let f = draw(&data, &desc, &options).unwrap();
        options.back_to_front = true;
        let b = draw(&data, &desc, &options).unwrap();
        assert_eq!(f.face, b.face);
        assert!(f.depth.iter().zip(&b.depth).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(f.summary.faces < b.summary.faces && f.summary.bitmap_bytes > 0 && b.summary.bitmap_bytes == 0);
        assert_eq!(f.summary.view_case, "XYZ");
        assert!(f.face.iter().any(|&x| x != 0));
        assert!(f.shaded.iter().any(|&x| x != 0));
    }

    #[test]
    fn rows_go_bottom_up_as_in_a_vtk_image() {
        let (data, desc) = ball();
        let options = FtbDesc {
            isovalue: 6.0,
            use_label: false,
            label: 0.0,
            vpn: [0.0, 0.0, 1.0],
            image_size: 16,
            back_to_front: false,
        };
        let drawn = draw(&data, &desc, &options).unwrap();
        let view = View::new(options.vpn).unwrap();
        let grid = grid_of(as_bytes(&data), &desc).unwrap();
        let octree = BinaryOctree::from_grid(&grid, Inside::AtOrAbove(6.0)).unwrap();
        let (shown, _) = front_to_back::display(&octree, &view, 16);
        for row in 0..16 {
            let top_down = &shown.image.face[row * 16..row * 16 + 16];
            assert_eq!(&drawn.face[(15 - row) * 16..(15 - row) * 16 + 16], top_down, "row {row}");
        }
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
        assert!(draw(&data, &desc, &zero).err().unwrap().contains("(0, 0, 0)"));
        let small = FtbDesc { image_size: 2, ..ok };
        assert!(draw(&data, &desc, &small).err().unwrap().contains("image size"));
        let nan = FtbDesc { isovalue: f64::NAN, ..ok };
        assert!(draw(&data, &desc, &nan).err().unwrap().contains("not a finite"));
        let (mut depth, mut face, mut shaded) = (vec![0.0; 10], vec![0; 64 * 64], vec![0; 3 * 64 * 64]);
        let e = ftb_display(as_bytes(&data), &desc, &ok, &mut depth, &mut face, &mut shaded).unwrap_err();
        assert!(e.contains("depth") && e.contains("10 values"), "{e}");
    }
}
