//! What the bridge's tests share: byte views, grid and select descriptions,
//! and a build without progress.

use super::octree::{build_with, HybridOctreeHandle};
use super::{CameraDesc, GridDesc, RegionDesc, ScalarType, SelectDesc, ViewDesc};

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
        texel_format: 0,
        isosurface_values: Vec::new(),
        gradient_opacity_points: Vec::new(),
        region: no_region(),
        transfer_2d_size: [0, 0],
        transfer_2d_rgba: Vec::new(),
        transfer_2d_range: [0.0, 0.0],
        slice_plane: [0.0; 6],
        view: data_view(),
    }
}

/// The data-space selection (no view importance), with a valid camera and viewport.
pub(crate) fn data_view() -> ViewDesc {
    ViewDesc {
        view_selection: 0,
        camera: ball_camera(),
        viewport: [64, 64],
        min_texel_pixels: 1.0,
        surface_opacity: 0.0,
        opacity_unit_distance: 1.0,
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

/// Samples per axis of [`ball`].
pub(crate) const BALL_N: usize = 17;

/// A ball, `1 - r / 10` around sample (8, 7, 9) of a [`BALL_N`]^3 grid, x fastest.
pub(crate) fn ball() -> Vec<f32> {
    (0..BALL_N * BALL_N * BALL_N)
        .map(|i| {
            let n = BALL_N;
            let (x, y, z) = ((i % n) as f32 - 8.0, ((i / n) % n) as f32 - 7.0, (i / (n * n)) as f32 - 9.0);
            1.0 - (x * x + y * y + z * z).sqrt() / 10.0
        })
        .collect()
}

/// [`ball`]'s grid, anisotropic and moved: world box x in [-3, 13], y in [2, 26], z in [5, 13].
pub(crate) fn ball_desc() -> GridDesc {
    GridDesc {
        scalar_type: ScalarType::F32,
        dims: [BALL_N; 3],
        spacing: [1.0, 1.5, 0.5],
        origin: [-3.0, 2.0, 5.0],
        components: 1,
        component: -1,
    }
}

/// A perspective camera that sees all of [`ball_desc`]'s box, obliquely.
pub(crate) fn ball_camera() -> CameraDesc {
    CameraDesc {
        position: [30.0, -20.0, 40.0],
        focal_point: [5.0, 14.0, 9.0],
        view_up: [0.0, 0.0, 1.0],
        parallel: false,
        parallel_scale: 1.0,
        view_angle: 30.0,
    }
}
