//! The uniform selection: the whole grid at one stride.

use super::brick::{make_brick, Selection};
use super::estimate::{estimated_error, estimated_rms_error};
use crate::base::error::{Error, Result};
use crate::octree::VolumeOctree;

/// Uniform downsampling at one stride, what a mapper does when a volume does
/// not fit (VTK's smart mapper resamples the whole volume into one texture):
/// the root drawn at the level `p = L - log2(stride)`, one texture of
///
/// ```text
/// texels_a = ceil((dims_a - 1) / stride) + 1        (per axis)
/// ```
///
/// samples, the last one clamped to the grid's last sample (as
/// [`Brick::texel_positions`](super::Brick::texel_positions)). Its reconstruction equals every node's T_p at
/// that stride, so the picture is that of all terminal nodes at one stride,
/// without their shared borders' bytes. No transfer function is given: its
/// [`estimated_error`] takes the volume as visible.
pub fn uniform(octree: &VolumeOctree, stride: usize, bytes_per_texel: usize) -> Result<Selection> {
    let layout = octree.layout();
    let l = layout.root_log2 as usize;
    if !stride.is_power_of_two() || stride > layout.root_size() {
        return Err(Error::InvalidArgument(format!(
            "uniform stride {stride} must be a power of two up to the root size {}",
            layout.root_size()
        )));
    }
    let root = octree.node(octree.root());
    let brick = make_brick(octree, &root, l - stride.trailing_zeros() as usize, 1.0, bytes_per_texel, false);
    let max_error = brick.error as f64;
    Ok(Selection {
        bricks: vec![brick],
        texture_bytes: brick.bytes,
        point_bytes: 0,
        budget_bytes: brick.bytes,
        max_error,
        estimated_error: estimated_error(octree, &[brick], |_, _| true),
        estimated_rms_error: estimated_rms_error(octree, &[brick], |_, _| true),
        skipped: 0,
        warning: None,
    })
}
