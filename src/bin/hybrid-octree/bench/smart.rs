//! The `vtk-smart` baseline of `bench render`: what VTK's
//! `vtkSmartVolumeMapper` uploads when its GPU mapper may use `B` bytes
//! (`MaxMemoryInBytes x MaxMemoryFraction`), drawn by the reference ray caster.
//!
//! `vtkOpenGLGPUVolumeRayCastMapper::GetReductionRatio` (VTK 9.3 and later)
//! asks for the same factor `r` on each of the `D` axes of more than one
//! sample (`D = 3` here), from the bytes of the volume at its scalar size:
//!
//! ```text
//! size = n_x n_y n_z (bytes of one scalar)
//! r    = 1 - (1 - B / size) / D      when size > B,   else 1 (no resampling)
//! ```
//!
//! `r` is not `(B / size)^(1/D)`: it never goes below `1 - 1/D = 2/3`, so the
//! resampled volume holds at least `(2/3)^3`, 30 %, of the samples whatever
//! `B`. `vtkSmartVolumeMapper` (with `LowResMode` `LowResModeResample`)
//! resamples with `vtkImageResample` by `r` on each axis, cubic
//! (its default `InterpolationMode` `VTK_RESLICE_CUBIC`; see
//! `hybrid_octree::data::resample`), and its low-resolution GPU mapper
//! uploads that volume as `vtkVolumeTexture` does: 8-bit types in 1 byte a
//! sample, 16-bit in 2, every other type as 32-bit floats.
//!
//! In VTK 9.2 `GetReductionRatio` of the OpenGL mapper returns 1 whatever the
//! memory: the smart mapper of ParaView 5.11 uploads the whole volume.
//!
//! `vtk-smart@bytes` is the same resampling at truly equal bytes: the factor
//! `r = (B / size')^(1/3)` (`size'` the uploaded bytes of the whole volume),
//! lowered until the resampled volume's uploaded bytes are at most `B`.

use crate::scene::{reference_image_at, Loaded, SceneArgs};
use hybrid_octree::data::resample::{resample_cubic, resampled_shape};
use hybrid_octree::grid::{Grid, ScalarType};
use hybrid_octree::plan::texel_format::TexelFormat;
use hybrid_octree::render::image::Image;
use hybrid_octree::Result;
use std::time::Instant;

/// The texel format `vtkVolumeTexture` uploads `scalar` as (its bytes a sample).
pub fn vtk_texel(scalar: ScalarType) -> TexelFormat {
    match scalar {
        ScalarType::U8 | ScalarType::I8 => TexelFormat::Unorm8,
        ScalarType::U16 | ScalarType::I16 => TexelFormat::Unorm16,
        _ => TexelFormat::Float32,
    }
}

/// `GetReductionRatio`'s factor per axis for `dims` of `scalar_bytes`
/// bytes a sample under a memory limit of `max_bytes` (module documentation).
pub fn reduction_ratio(dims: [usize; 3], scalar_bytes: usize, max_bytes: usize) -> [f64; 3] {
    let size = dims.iter().product::<usize>() as f64 * scalar_bytes as f64;
    let dimension = dims.iter().filter(|&&n| n > 1).count().max(1) as f64;
    if size <= max_bytes as f64 {
        return [1.0; 3];
    }
    let r = 1.0 - (1.0 - max_bytes as f64 / size) / dimension;
    // VTK sets axis 0 always, axes 1 and 2 unless they hold one sample.
    [r, if dims[1] != 1 { r } else { 1.0 }, if dims[2] != 1 { r } else { 1.0 }]
}

/// The uploaded bytes of `dims` resampled by `r` on every axis, `texel_bytes` a sample.
fn resampled_bytes(dims: [usize; 3], r: f64, texel_bytes: usize) -> usize {
    dims.iter().map(|&n| ((n - 1) as f64 * r).floor() as usize + 1).product::<usize>() * texel_bytes
}

/// The factor of `vtk-smart@bytes` (module documentation): the cube root of
/// `max_bytes` over the uploaded bytes, lowered by bisection until the
/// resampled volume's bytes are at most `max_bytes`; 1 when the whole volume fits.
pub fn equal_bytes_ratio(dims: [usize; 3], texel_bytes: usize, max_bytes: usize) -> f64 {
    let size = dims.iter().product::<usize>() as f64 * texel_bytes as f64;
    if size <= max_bytes as f64 {
        return 1.0;
    }
    let r = (max_bytes as f64 / size).cbrt();
    if resampled_bytes(dims, r, texel_bytes) <= max_bytes {
        return r;
    }
    let (mut lo, mut hi) = (0.0, r);
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if resampled_bytes(dims, mid, texel_bytes) <= max_bytes {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// What the baseline uploads and draws at one factor.
pub struct Smart {
    /// Magnification factor per axis.
    pub ratio: [f64; 3],
    /// Samples per axis of the resampled volume.
    pub dims: [usize; 3],
    /// The texel format it is uploaded in.
    pub texel: TexelFormat,
    /// Its uploaded bytes.
    pub bytes: usize,
    /// The resampling, ms.
    pub resample_ms: f64,
    /// The reference ray caster's frame of it, ms.
    pub render_ms: f64,
    /// That frame.
    pub image: Image,
}

/// `grid` resampled by `ratio` and drawn by the reference ray caster with
/// the scene's view and the full grid's opacity unit; `None` (with a note
/// on stderr) when the factor leaves fewer than 2 samples on an axis.
pub fn draw(grid: &Grid<'_>, scene: &Loaded, args: &SceneArgs, ratio: [f64; 3]) -> Result<Option<Smart>> {
    if let Err(e) = resampled_shape(grid.shape(), ratio) {
        eprintln!("note: no VTK smart mapper row at factor {ratio:?}: {e}");
        return Ok(None);
    }
    let texel = vtk_texel(grid.samples().scalar_type());
    let started = Instant::now();
    let low = resample_cubic(grid, ratio)?;
    let resample_ms = started.elapsed().as_secs_f64() * 1e3;
    let low_grid = low.grid(None)?;
    let started = Instant::now();
    let d0 = hybrid_octree::spacing::reference_spacing(grid.shape());
    let image = reference_image_at(&low_grid, scene, args, Some(d0))?;
    let render_ms = started.elapsed().as_secs_f64() * 1e3;
    let dims = low.shape.dims;
    let bytes = dims.iter().product::<usize>() * texel.bytes();
    Ok(Some(Smart { ratio, dims, texel, bytes, resample_ms, render_ms, image }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// VTK's formula by hand: 197x233x189 u8 (8,675,289 bytes) under 1 MB.
    #[test]
    fn reduction_ratio_is_vtks_per_axis_formula() {
        let dims = [197, 233, 189];
        let r = 1.0 - (1.0 - 1e6 / 8_675_289.0) / 3.0;
        assert_eq!(reduction_ratio(dims, 1, 1_000_000), [r; 3]);
        assert!((r - 0.7051).abs() < 1e-4, "{r}");
        assert_eq!(reduction_ratio(dims, 1, 8_675_289), [1.0; 3]);
        // Whatever the limit, no axis goes below 2/3.
        assert!(reduction_ratio(dims, 4, 1)[0] > 2.0 / 3.0);
    }

    #[test]
    fn equal_bytes_ratio_fits_the_bytes() {
        for (dims, texel, budget) in [([197, 233, 189], 1, 1_000_000), ([256; 3], 2, 4_300_000), ([33; 3], 4, 10_000)] {
            let r = equal_bytes_ratio(dims, texel, budget);
            let bytes = resampled_bytes(dims, r, texel);
            assert!(bytes <= budget && bytes as f64 > 0.8 * budget as f64, "{dims:?}: {bytes} of {budget}");
        }
        assert_eq!(equal_bytes_ratio([9; 3], 1, 729), 1.0);
    }
}
