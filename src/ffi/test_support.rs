//! What the bridge's tests share: byte views, grid and select descriptions,
//! and a build without progress.

use super::octree::{build_with, HybridOctreeHandle};
use super::{GridDesc, RegionDesc, ScalarType, SelectDesc};

/// The bytes of an f32 slice, as the C++ side hands them over.
pub(crate) fn as_bytes(data: &[f32]) -> &[u8] {
    // SAFETY: f32 has no padding; the byte view covers exactly the slice's storage.
    unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, std::mem::size_of_val(data)) }
}

/// A single-component f32 grid of `dims` with unit spacing at the origin.
pub(crate) fn f32_desc(dims: [usize; 3]) -> GridDesc {
    GridDesc { scalar_type: ScalarType::F32, dims, spacing: [1.0; 3], origin: [0.0; 3], components: 1, component: -1 }
}

/// Select options: `budget_bytes`, no tolerance, ROI, opacity or isovalue.
pub(crate) fn select_desc(budget_bytes: usize) -> SelectDesc {
    SelectDesc {
        budget_bytes,
        tolerance: 0.0,
        has_roi: false,
        roi_center: [0.0; 3],
        roi_radius: 1.0,
        opacity_points: Vec::new(),
        has_isovalue: false,
        isovalue: 0.0,
        gradient_border: false,
        blend_mode: 0,
        average_range: [f64::MIN, f64::MAX],
        isosurface_values: Vec::new(),
        gradient_opacity_points: Vec::new(),
        region: no_region(),
        slice_plane: [0.0; 6],
    }
}

/// No cropping, no clipping planes.
pub(crate) fn no_region() -> RegionDesc {
    RegionDesc { cropping: false, cropping_planes: [0.0; 6], cropping_flags: 0, clipping_planes: Vec::new() }
}

/// Builds without progress.
pub(crate) fn build_volume_octree(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
) -> Result<Box<HybridOctreeHandle>, String> {
    build_with(bytes, desc, leaf_size, &mut |_| true)
}
