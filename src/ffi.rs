//! The only `#[cxx::bridge]` of the crate: what `cpp/vtkHybridOctreeBridge.cxx`
//! may call. No other module knows C++ exists.
//!
//! Every function body runs under [`std::panic::catch_unwind`] and returns
//! `Result`, so a Rust panic becomes a `rust::Error` exception on the C++ side
//! (reported with `vtkErrorMacro`) instead of aborting ParaView.
//!
//! Volume data crosses borrowed: `bytes` is the VTK array's storage
//! (`GetVoidPointer(0)`, `GetDataSize() * GetDataTypeSize()` bytes); nothing is
//! copied.

use crate::error::Error;
use crate::grid::{Grid, GridShape, Samples, ScalarType as GridScalarType};
use crate::octree::{BuildOptions, VolumeOctree};
use crate::surface::{distance, Surface, SurfaceOptions};
use std::panic::{catch_unwind, AssertUnwindSafe};

#[cxx::bridge(namespace = "hybrid_octree")]
mod bridge {
    // ---- Shared structs -------------------------------------------------

    /// The scalar type of the VTK array (VTK_UNSIGNED_CHAR -> U8, ...).
    #[derive(Debug)]
    enum ScalarType {
        U8,
        I8,
        U16,
        I16,
        U32,
        I32,
        F32,
        F64,
    }

    /// Layout of the borrowed image: dims, spacing, origin, components and
    /// the chosen component (-1: none chosen, allowed for 1-component arrays).
    #[derive(Debug)]
    struct GridDesc {
        scalar_type: ScalarType,
        dims: [usize; 3],
        spacing: [f64; 3],
        origin: [f64; 3],
        components: usize,
        component: i32,
    }

    /// Summary of a built Volume Octree.
    #[derive(Debug)]
    struct OctreeSummary {
        /// Nodes reachable from the root (terminal nodes are not refined).
        node_count: usize,
        /// Terminal nodes: homogeneous nodes plus leaf bricks.
        terminal_count: usize,
        /// Nodes whose e_0 is 0 (trilinear over their box).
        homogeneous_count: usize,
        /// Number of levels: the root is level 0, leaves are level `levels - 1`.
        levels: u32,
        /// Cells per axis of a leaf brick.
        leaf_size: u32,
        /// Cells per axis of the (virtually padded) root.
        root_size: u32,
        /// Bytes the octree owns (the borrowed samples not included).
        octree_bytes: usize,
        /// Bytes of the input samples of the chosen component.
        input_bytes: usize,
        /// Wall-clock build time.
        build_ms: f64,
        /// Data range, used to normalise nodal errors (NaN left out).
        value_min: f64,
        value_max: f64,
        /// NaN samples of the chosen component: no data, transparent and
        /// outside every isosurface.
        nan_samples: usize,
    }

    /// The boxes of an octree cut, one entry per node, world coordinates.
    #[derive(Debug)]
    struct CutBoxes {
        /// 6 values per node: xmin, xmax, ymin, ymax, zmin, zmax (VTK bounds order).
        bounds: Vec<f64>,
        /// The node's id in the level-by-level numbering (what SurfaceOutput::polygon_node names).
        node_id: Vec<u32>,
        level: Vec<u32>,
        /// e_0 of the node normalised by the data range.
        nodal_error: Vec<f32>,
        /// The node's scalar range, NaN left out; NaN for a box of NaN only.
        min: Vec<f64>,
        max: Vec<f64>,
    }

    /// What `ftb_display` draws (paper 2's display).
    struct FtbDesc {
        /// Inside: value >= isovalue (unless `use_label`).
        isovalue: f64,
        /// Inside: value == label instead.
        use_label: bool,
        label: f64,
        /// View plane normal, towards the viewer.
        vpn: [f64; 3],
        /// Image side in pixels.
        image_size: usize,
        /// Meagher's back-to-front display instead of front to back with blocking quadtrees.
        back_to_front: bool,
    }

    /// A depth image and what drawing it took.
    #[derive(Debug)]
    struct FtbImage {
        size: usize,
        /// Per pixel, rows from the top: distance from the view plane (smaller
        /// is nearer), NaN where nothing was painted.
        depth: Vec<f32>,
        /// Per pixel: 0 nothing, 1 + the axis of the face painted.
        face: Vec<u8>,
        /// Per pixel: the shaded picture, RGB, 0 where nothing was painted.
        shaded: Vec<u8>,
        white_visited: usize,
        black_visited: usize,
        gray_visited: usize,
        faces: usize,
        scanlines: usize,
        pixels: usize,
        display_ms: f64,
        build_ms: f64,
        bitmap_bytes: usize,
        white_octants: usize,
        black_octants: usize,
        gray_octants: usize,
        resolution: u32,
        /// "XYZ", "XY", ... (the view case).
        view_case: String,
    }

    /// What `generate_points` makes (paper 3's points; see `crate::points`).
    struct PointsDesc {
        /// Low-resolution factor: 2, 4 or 8.
        factor: usize,
        /// Points where |error| exceeds this fraction of the data range ...
        threshold: f64,
        /// ... or, when `use_budget`, the `budget` largest errors.
        use_budget: bool,
        budget: usize,
        /// Only where the low resolution underestimates (e > 0).
        underestimates_only: bool,
        /// The optimized low resolution's bound (fraction of the data range); negative: plain subsampling.
        max_overestimate: f64,
        /// Also write the point file here (empty: do not).
        file_name: String,
    }

    /// The points of the hybrid representation, dequantised as stored.
    #[derive(Debug)]
    struct PointsOutput {
        /// Grid index of each point, 3 per point.
        ijk: Vec<u32>,
        /// Original value (quantised to 8 bits over the data range, as stored).
        value: Vec<f32>,
        /// Error f - T_f (quantised to 8 bits, as stored).
        error: Vec<f32>,
        /// Unit normal from the 256-direction table, 3 per point.
        normal: Vec<f32>,
        factor: usize,
        /// Bytes of the points as stored (6 or 9 a point).
        point_bytes: usize,
        /// Points with e > 0.
        underestimates: usize,
        generate_ms: f64,
    }

    /// Points kept for drawing, as the renderer needs them.
    #[derive(Debug)]
    struct PointsDrawing {
        /// 3 per point: the sample's world position (the grid's frame).
        position: Vec<f32>,
        /// Original value f (dequantised as stored).
        value: Vec<f32>,
        /// Error e = f - T_f (dequantised as stored): the volume shows f - e there.
        error: Vec<f32>,
        /// The low-resolution factor the points complete.
        factor: usize,
        /// Bytes of all the points as stored (6 or 9 a point).
        point_bytes: usize,
    }

    /// Which isosurface the Hybrid Octree keeps.
    #[derive(Debug)]
    enum SurfaceMode {
        /// Discretized Marching Cubes, coplanar facets merged (lossless).
        Discretized,
        /// Classic Marching Cubes, vertices interpolated along edges.
        Interpolated,
    }

    /// An extracted isosurface, ready for a vtkPolyData.
    #[derive(Debug)]
    struct SurfaceOutput {
        /// 3 per point, world coordinates.
        points: Vec<f64>,
        /// 3 per point: unit outward normals (from values >= isovalue towards values below it).
        normals: Vec<f32>,
        /// Polygon (triangle) i uses connectivity[offsets[i] .. offsets[i + 1]]; offsets.len() = polygons + 1.
        offsets: Vec<i64>,
        connectivity: Vec<i64>,
        /// Per polygon: the terminal octree node holding it and its level.
        polygon_node: Vec<u32>,
        polygon_level: Vec<u32>,
        /// Per polygon: the merged coplanar face it triangulates.
        polygon_face: Vec<u32>,
        polygons: u64,
        /// Merged coplanar faces (DiscMC with compression), else the triangles.
        faces: u64,
        /// Triangles in the output (= polygons).
        triangles: u64,
        /// Triangles before face compression.
        uncompressed_triangles: u64,
        vertices: u64,
        /// Polygon edges on the volume's faces (0 for a closed surface).
        boundary_edges: u64,
        extract_ms: f64,
        compress_ms: f64,
        /// DiscMC vs interpolated distance in voxel units (sampled, symmetric); -1 when not measured.
        distance_mean: f64,
        distance_max: f64,
    }

    /// What to select (see `select::SelectOptions`; f32 texels, bricks up to
    /// 128 cells per axis).
    #[derive(Debug)]
    struct SelectDesc {
        /// Texture budget in bytes (> 0).
        budget_bytes: usize,
        /// Error tolerance, a fraction of the data range (>= 0).
        tolerance: f64,
        /// Refine around a region of interest.
        has_roi: bool,
        /// ROI centre, WORLD coordinates (turned into index space with the
        /// image's origin and spacing).
        roi_center: [f64; 3],
        /// ROI radius, world units (> 0), turned into index units by dividing
        /// by the smallest spacing: with anisotropic spacing the index-space
        /// sphere covers at least the world sphere.
        roi_radius: f64,
        /// The scalar opacity transfer function, (value, opacity) pairs
        /// flattened, values increasing: nodes over whose range it is 0 are
        /// skipped (no texture). Empty: every node shows.
        opacity_points: Vec<f64>,
        /// With an isosurface: nodes holding the isovalue always show.
        has_isovalue: bool,
        isovalue: f64,
    }

    /// Summary of a selection.
    #[derive(Debug)]
    struct SelectionSummary {
        bricks: usize,
        /// Sum of the bricks' bytes (f32 texels).
        texture_bytes: usize,
        budget_bytes: usize,
        /// The estimated error (`select::estimated_error`): the largest nodal
        /// error e_p of the bricks visible under the opacity points, a fraction
        /// of the data range; 0 when they all draw the full-resolution field.
        estimated_error: f64,
        /// Nodes left out as fully transparent.
        skipped: usize,
        /// "" when none (else: the budget is below the coarsest representation,
        /// or the tolerance was not reached).
        warning: String,
        /// Points of the hybrid representation bought within the budget (0 without points).
        points: usize,
        /// Their bytes (counted in the budget with the textures).
        point_bytes: usize,
    }

    /// A camera as vtkCamera gives it (world coordinates).
    #[derive(Debug)]
    struct CameraDesc {
        position: [f64; 3],
        focal_point: [f64; 3],
        view_up: [f64; 3],
        /// GetParallelProjection().
        parallel: bool,
        /// GetParallelScale(): half the view height, world units.
        parallel_scale: f64,
        /// GetViewAngle(): full vertical angle, degrees.
        view_angle: f64,
    }

    /// A DrawList for one camera, flattened per brick in drawing order (back
    /// to front), with the surface passes when drawn with a surface.
    #[derive(Debug)]
    struct DrawListOutput {
        /// Index of the brick in the selection (for brick_texels).
        brick: Vec<usize>,
        node_id: Vec<u32>,
        /// 6 per brick, world: xmin, xmax, ymin, ymax, zmin, zmax.
        bounds: Vec<f64>,
        /// 3 per brick: texels per axis (x, y, z). Texture coordinate of a
        /// world point along axis a, in texels: (x - xmin) / (stride * spacing[a]),
        /// clamped to [0, texels - 1] (the last texel of a clipped brick is closer).
        texels: Vec<usize>,
        /// Cells between texels.
        stride: Vec<usize>,
        /// World distance d between the brick's slices.
        slice_spacing: Vec<f64>,
        /// d / d0: opacity correction a' = 1 - (1 - a)^(d / d0).
        opacity_ratio: Vec<f64>,
        /// Brick i's slices are slices[slice_offsets[i] .. slice_offsets[i + 1]].
        slice_offsets: Vec<usize>,
        /// View depths (position-relative, along `forward`), back to front:
        /// the plane of depth z is {x : (x - camera position) . forward = z}.
        slices: Vec<f64>,
        /// The plan's passes in order, comma-joined ("volume", "" with no brick).
        passes: String,
        /// d0, world units.
        reference_spacing: f64,
        /// The camera's unit view direction.
        forward: [f64; 3],
        /// Translucent surface: brick i's triangle batches are batches
        /// batch_offsets[i] .. batch_offsets[i + 1], back to front (empty
        /// lists without one).
        batch_offsets: Vec<usize>,
        /// Per batch: the slab s within its brick (between slices s - 1 and s;
        /// 0 behind the first slice, slices-count in front of the last).
        batch_slab: Vec<usize>,
        /// Per batch: surface triangles [first, end) (polygon ids of the SurfaceHandle's mesh).
        batch_first: Vec<u32>,
        batch_end: Vec<u32>,
        /// Per batch, 2 values: clip to view depths near <= depth < far; (-inf, inf): no clip needed.
        batch_clip: Vec<f64>,
        /// Opaque surface: the surface pass draws triangles 0 .. this first (0 otherwise).
        opaque_triangles: usize,
        /// Points (a selection made with points): brick i's point buckets are
        /// buckets bucket_offsets[i] .. bucket_offsets[i + 1], back to front
        /// (empty lists without points).
        bucket_offsets: Vec<usize>,
        /// Per bucket: the slab within its brick, as batch_slab.
        bucket_slab: Vec<usize>,
        /// Bucket k's points are bucket_points[bucket_point_offsets[k] .. bucket_point_offsets[k + 1]].
        bucket_point_offsets: Vec<usize>,
        /// Point ids (into the PointsHandle's points), in grid order within a bucket.
        bucket_points: Vec<u32>,
    }

    // ---- C++ types for Rust ------------------------------------------------

    unsafe extern "C++" {
        include!("hybrid-octree/cpp/Filters/vtkHybridOctreeBuildProgress.h");
        /// The build's progress sink (cpp/Filters/vtkHybridOctreeBuildProgress.h).
        type BuildProgress;
        /// `fraction` of the build done, in (0, 1]; false asks the build to stop.
        fn report(self: &BuildProgress, fraction: f64) -> bool;
    }

    // ---- Rust types and functions for C++ --------------------------------

    extern "Rust" {
        /// A built Volume Octree, owned by the C++ filter.
        type VolumeOctreeHandle;

        /// Builds the Volume Octree of the borrowed image, reporting progress
        /// to `progress` between chunks of leaf bricks (on the calling
        /// thread); its `false` cancels the build (the error names the
        /// cancel; nothing is kept).
        fn build_volume_octree_with_progress(
            bytes: &[u8],
            desc: &GridDesc,
            leaf_size: u32,
            progress: &BuildProgress,
        ) -> Result<Box<VolumeOctreeHandle>>;
        /// Node counts, levels, memory and build time.
        fn summary(self: &VolumeOctreeHandle) -> Result<OctreeSummary>;
        /// The cut at normalised tolerance `tolerance` (the first nodes from the
        /// root whose e_0 <= tolerance, or leaf bricks).
        fn cut_boxes(self: &VolumeOctreeHandle, tolerance: f64) -> Result<CutBoxes>;
        /// Extracts the isosurface of the image the handle was built from (the
        /// same bytes and description). An isovalue outside the data range gives
        /// an empty surface; a non-finite one is an error.
        fn extract_surface(
            self: &VolumeOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            isovalue: f64,
            mode: SurfaceMode,
            measure_distance: bool,
        ) -> Result<SurfaceOutput>;

        /// The binary octree of the borrowed image drawn along `options.vpn`
        /// (errors: a zero or non-finite VPN, a non-finite isovalue or label,
        /// an image size outside 8..=8192).
        fn ftb_display(bytes: &[u8], desc: &GridDesc, options: &FtbDesc) -> Result<FtbImage>;

        /// The points completing the borrowed image's low resolution (errors:
        /// a factor other than 2, 4 or 8, a threshold or bound outside [0, 1],
        /// a grid too small for the factor, a file that cannot be written).
        fn generate_points(bytes: &[u8], desc: &GridDesc, options: &PointsDesc) -> Result<PointsOutput>;

        /// Points of the hybrid representation kept for drawing with a selection.
        type PointsHandle;

        /// The points completing the borrowed image's stride-`factor`
        /// textures (plain subsampling: `max_overestimate` must be < 0, the
        /// textures being the image itself), kept for `select_bricks_with_points`.
        fn points_for_drawing(
            self: &VolumeOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            options: &PointsDesc,
        ) -> Result<Box<PointsHandle>>;
        /// The kept points' positions, values and errors.
        fn drawing(self: &PointsHandle) -> Result<PointsDrawing>;
        /// What each point adds under the transfer function of `colors`
        /// ((value, r, g, b) flattened) and `opacities` ((value, opacity)):
        /// 4 floats a point, straight colour and opacity, averaged over its
        /// voxel (see `points::shade`); `bytes` and `desc`: the image the
        /// points were made from.
        fn shades(
            self: &PointsHandle,
            bytes: &[u8],
            desc: &GridDesc,
            colors: &[f64],
            opacities: &[f64],
        ) -> Result<Vec<f32>>;

        /// A selection of the octree's nodes and texture levels, for drawing.
        type SelectionHandle;

        /// As `select_bricks`, spending the budget on textures and on
        /// `points` (made from this octree's image): a brick at the points'
        /// stride takes its points when they remove more error per byte than
        /// refining it. Its DrawLists then bucket the bought points into the slabs.
        fn select_bricks_with_points(
            self: &VolumeOctreeHandle,
            options: &SelectDesc,
            points: &PointsHandle,
        ) -> Result<Box<SelectionHandle>>;

        /// Selects bricks within the budget (errors: budget 0, a tolerance
        /// that is not a number >= 0, a bad ROI or opacity points).
        fn select_bricks(self: &VolumeOctreeHandle, options: &SelectDesc) -> Result<Box<SelectionHandle>>;
        /// Bricks, bytes, error, skipped nodes, warning.
        fn summary(self: &SelectionHandle) -> Result<SelectionSummary>;
        /// The DrawList of the selection for `camera` (`octree`: the handle
        /// the selection was made from).
        fn draw_list(
            self: &SelectionHandle,
            octree: &VolumeOctreeHandle,
            camera: &CameraDesc,
        ) -> Result<DrawListOutput>;
        /// Brick `brick`'s texels as f32, x fastest (see
        /// `render::texture::brick_texels_f32`), from the image the octree
        /// was built from.
        fn brick_texels(self: &SelectionHandle, bytes: &[u8], desc: &GridDesc, brick: usize) -> Result<Vec<f32>>;

        /// The CPU compositor's picture of the selection's DrawList for
        /// `camera` (volume only), `width x height`, premultiplied RGBA
        /// (4 floats per pixel, rows from the top), with the transfer function
        /// of `colors` ((value, r, g, b) flattened) and `opacities` ((value,
        /// opacity) flattened), over the image the octree was built from;
        /// a selection made with points draws them, with Gaussian footprints
        /// when `gaussian_points`, else square ones.
        #[allow(clippy::too_many_arguments)]
        fn composite(
            self: &SelectionHandle,
            octree: &VolumeOctreeHandle,
            camera: &CameraDesc,
            bytes: &[u8],
            desc: &GridDesc,
            colors: &[f64],
            opacities: &[f64],
            gaussian_points: bool,
            width: usize,
            height: usize,
        ) -> Result<Vec<f32>>;

        /// As `composite`, with `surface` drawn in colour and opacity
        /// `surface_rgba` (4 values; opacity 1: the opaque pass, below 1: the
        /// batches in the slabs), headlight-shaded.
        #[allow(clippy::too_many_arguments)]
        fn composite_with_surface(
            self: &SelectionHandle,
            octree: &VolumeOctreeHandle,
            camera: &CameraDesc,
            bytes: &[u8],
            desc: &GridDesc,
            colors: &[f64],
            opacities: &[f64],
            gaussian_points: bool,
            surface: &SurfaceHandle,
            surface_rgba: &[f64],
            width: usize,
            height: usize,
        ) -> Result<Vec<f32>>;

        /// An isosurface kept for drawing with a selection.
        type SurfaceHandle;

        /// Extracts the isosurface (as extract_surface, no distance) and keeps it for drawing.
        fn surface_for_drawing(
            self: &VolumeOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            isovalue: f64,
            mode: SurfaceMode,
        ) -> Result<Box<SurfaceHandle>>;
        /// The kept surface as a mesh (its polygon ids are the DrawList's
        /// triangle ids); `octree`: the handle it was extracted from.
        fn mesh(self: &SurfaceHandle, octree: &VolumeOctreeHandle) -> Result<SurfaceOutput>;
        /// The DrawList with `surface` at `surface_opacity` (1: opaque pass
        /// first; (0, 1): batches in the slabs; 0: hidden). The selection's
        /// SlabPolygons are made on the first call and kept for this surface.
        fn draw_list_with_surface(
            self: &SelectionHandle,
            octree: &VolumeOctreeHandle,
            camera: &CameraDesc,
            surface: &SurfaceHandle,
            surface_opacity: f64,
        ) -> Result<DrawListOutput>;
    }
}

use crate::ffi_ftb::ftb_display;
use crate::ffi_points::generate_points;
pub use crate::ffi_points::PointsHandle;
pub use crate::ffi_render::{SelectionHandle, SurfaceHandle};
pub use bridge::{
    CameraDesc, CutBoxes, DrawListOutput, FtbDesc, FtbImage, GridDesc, OctreeSummary, PointsDesc, PointsDrawing,
    PointsOutput, ScalarType, SelectDesc, SelectionSummary, SurfaceMode, SurfaceOutput,
};

/// A Volume Octree together with the geometry needed to place its boxes.
#[derive(Debug)]
pub struct VolumeOctreeHandle {
    pub(crate) octree: VolumeOctree,
    pub(crate) shape: GridShape,
    input_bytes: usize,
    nan_samples: usize,
    /// Unique per build: a selection remembers the octree it was made from.
    pub(crate) id: u64,
}

static NEXT_OCTREE_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

/// Runs `f`, turning a panic into [`Error::Internal`] so it never crosses the bridge.
pub(crate) fn guarded<T>(f: impl FnOnce() -> crate::error::Result<T>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(e)) => Err(e.to_string()),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            Err(Error::Internal(what).to_string())
        }
    }
}

fn scalar_type(t: ScalarType) -> crate::error::Result<GridScalarType> {
    Ok(match t {
        ScalarType::U8 => GridScalarType::U8,
        ScalarType::I8 => GridScalarType::I8,
        ScalarType::U16 => GridScalarType::U16,
        ScalarType::I16 => GridScalarType::I16,
        ScalarType::U32 => GridScalarType::U32,
        ScalarType::I32 => GridScalarType::I32,
        ScalarType::F32 => GridScalarType::F32,
        ScalarType::F64 => GridScalarType::F64,
        _ => return Err(Error::InvalidArgument("unknown scalar type code from C++".into())),
    })
}

/// The checked grid over the borrowed bytes.
pub(crate) fn grid_of<'a>(bytes: &'a [u8], desc: &GridDesc) -> crate::error::Result<Grid<'a>> {
    let samples = Samples::from_bytes(bytes, scalar_type(desc.scalar_type)?)?;
    let shape = GridShape { dims: desc.dims, spacing: desc.spacing, origin: desc.origin };
    let component = usize::try_from(desc.component).ok();
    Grid::new(samples, shape, desc.components, component)
}

/// `grid` is the image of `shape`, the one the octree (and its selections
/// and points) was made from: same dims, spacing and origin.
pub(crate) fn same_image(shape: &GridShape, grid: &Grid<'_>) -> crate::error::Result<()> {
    if grid.shape() == shape {
        Ok(())
    } else {
        Err(Error::InvalidArgument(
            "the image changed since the octree was built (dims, spacing or origin); rebuild it".into(),
        ))
    }
}

/// As [`grid_of`] without the non-finite scan (see [`Grid::unscanned`]).
pub(crate) fn grid_unscanned<'a>(bytes: &'a [u8], desc: &GridDesc) -> crate::error::Result<Grid<'a>> {
    let samples = Samples::from_bytes(bytes, scalar_type(desc.scalar_type)?)?;
    let shape = GridShape { dims: desc.dims, spacing: desc.spacing, origin: desc.origin };
    Grid::unscanned(samples, shape, desc.components, usize::try_from(desc.component).ok())
}

/// Builds without progress (the bridge tests' entry point).
#[cfg(test)]
pub(crate) fn build_volume_octree(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
) -> Result<Box<VolumeOctreeHandle>, String> {
    build_with(bytes, desc, leaf_size, &mut |_| true)
}

pub(crate) fn build_volume_octree_with_progress(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &bridge::BuildProgress,
) -> Result<Box<VolumeOctreeHandle>, String> {
    build_with(bytes, desc, leaf_size, &mut |fraction| progress.report(fraction))
}

/// Builds through [`VolumeOctree::build_with_progress`]: `progress(fraction)`
/// between chunks of leaf bricks, `false` cancels.
fn build_with(
    bytes: &[u8],
    desc: &GridDesc,
    leaf_size: u32,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Box<VolumeOctreeHandle>, String> {
    guarded(|| {
        let grid = grid_of(bytes, desc)?;
        let options = BuildOptions { leaf_size: leaf_size as usize };
        let octree = VolumeOctree::build_with_progress(&grid, &options, progress)?;
        let id = NEXT_OCTREE_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(Box::new(VolumeOctreeHandle {
            octree,
            shape: *grid.shape(),
            input_bytes: grid.input_bytes(),
            nan_samples: grid.nan_count(),
            id,
        }))
    })
}

impl VolumeOctreeHandle {
    pub(crate) fn extract_surface(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        isovalue: f64,
        mode: SurfaceMode,
        measure_distance: bool,
    ) -> Result<SurfaceOutput, String> {
        guarded(|| {
            let grid = grid_of(bytes, desc)?;
            let surface = self.extract(&grid, isovalue, mode)?;
            let (distance_mean, distance_max) = if measure_distance {
                let d = distance::discretized_to_interpolated(&grid, &self.octree, isovalue)?;
                (d.mean, d.max)
            } else {
                (-1.0, -1.0)
            };
            Ok(self.surface_output(&surface, distance_mean, distance_max))
        })
    }

    /// The isosurface of `grid` (checked to be the image the octree was built from).
    pub(crate) fn extract(&self, grid: &Grid<'_>, isovalue: f64, mode: SurfaceMode) -> crate::error::Result<Surface> {
        same_image(&self.shape, grid)?;
        let options = match mode {
            SurfaceMode::Discretized => SurfaceOptions::discretized(isovalue),
            SurfaceMode::Interpolated => SurfaceOptions::interpolated(isovalue),
            _ => return Err(Error::InvalidArgument("unknown surface mode code from C++".into())),
        };
        Surface::extract(grid, &self.octree, &options)
    }

    /// `surface` for C++ (world points).
    pub(crate) fn surface_output(&self, surface: &Surface, distance_mean: f64, distance_max: f64) -> SurfaceOutput {
        let st = &surface.stats;
        SurfaceOutput {
            points: surface.points.iter().flat_map(|p| self.shape.world(*p)).collect(),
            normals: surface.normals.iter().flatten().copied().collect(),
            offsets: surface.offsets.iter().map(|&o| o as i64).collect(),
            connectivity: surface.connectivity.iter().map(|&c| c as i64).collect(),
            polygon_node: surface.polygon_node.iter().map(|n| n.0).collect(),
            polygon_level: surface.polygon_node.iter().map(|&n| self.octree.node(n).level as u32).collect(),
            polygon_face: surface.polygon_face.clone(),
            polygons: st.polygons as u64,
            faces: st.faces as u64,
            triangles: st.triangles as u64,
            uncompressed_triangles: st.uncompressed_triangles as u64,
            vertices: st.vertices as u64,
            boundary_edges: st.boundary_edges as u64,
            extract_ms: st.extract_ms,
            compress_ms: st.compress_ms,
            distance_mean,
            distance_max,
        }
    }

    fn summary(&self) -> Result<OctreeSummary, String> {
        guarded(|| {
            let s = self.octree.stats();
            Ok(OctreeSummary {
                node_count: s.node_count,
                terminal_count: s.terminal_count,
                homogeneous_count: s.homogeneous_count,
                levels: s.levels as u32,
                leaf_size: s.leaf_size as u32,
                root_size: s.root_size as u32,
                octree_bytes: s.octree_bytes,
                input_bytes: self.input_bytes,
                build_ms: s.build_ms,
                value_min: s.value_range.0,
                value_max: s.value_range.1,
                nan_samples: self.nan_samples,
            })
        })
    }

    fn cut_boxes(&self, tolerance: f64) -> Result<CutBoxes, String> {
        guarded(|| {
            let cut = self.octree.cut(tolerance)?;
            let mut out = CutBoxes {
                bounds: Vec::with_capacity(cut.len() * 6),
                node_id: Vec::with_capacity(cut.len()),
                level: Vec::with_capacity(cut.len()),
                nodal_error: Vec::with_capacity(cut.len()),
                min: Vec::with_capacity(cut.len()),
                max: Vec::with_capacity(cut.len()),
            };
            for id in cut {
                let node = self.octree.node(id);
                let lo = self.shape.world(node.lo.map(|v| v as f64));
                let hi = self.shape.world(node.hi.map(|v| v as f64));
                out.bounds.extend_from_slice(&[lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]);
                out.node_id.push(id.0);
                out.level.push(node.level as u32);
                out.nodal_error.push(node.errors.first().copied().unwrap_or(0.0));
                let empty = node.min > node.max; // a box of NaN only: (+inf, -inf)
                out.min.push(if empty { f64::NAN } else { node.min });
                out.max.push(if empty { f64::NAN } else { node.max });
            }
            Ok(out)
        })
    }
}

/// The bytes of an f32 slice, as the C++ side hands them over (tests).
#[cfg(test)]
pub(crate) fn as_bytes(data: &[f32]) -> &[u8] {
    // SAFETY: f32 has no padding; the byte view covers exactly the slice's storage.
    unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, std::mem::size_of_val(data)) }
}

/// A single-component f32 grid of `dims` with unit spacing at the origin (tests).
#[cfg(test)]
pub(crate) fn f32_desc(dims: [usize; 3]) -> GridDesc {
    GridDesc { scalar_type: ScalarType::F32, dims, spacing: [1.0; 3], origin: [0.0; 3], components: 1, component: -1 }
}

/// Select options of the bridge tests: `budget_bytes`, no tolerance, ROI, opacity or isovalue.
#[cfg(test)]
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_not_an_abort() {
        let r: Result<(), String> = guarded(|| panic!("boom"));
        let e = r.unwrap_err();
        assert!(e.contains("internal error") && e.contains("boom"), "{e}");
    }

    #[test]
    fn bridge_builds_and_cuts() {
        let data: Vec<f32> = (0..27).map(|i| (i * i) as f32).collect();
        // SAFETY: f32 has no padding; the byte view covers exactly the vector's storage.
        let bytes = unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, data.len() * 4) };
        let desc = GridDesc {
            scalar_type: ScalarType::F32,
            dims: [3, 3, 3],
            spacing: [1.0, 2.0, 3.0],
            origin: [0.0; 3],
            components: 1,
            component: -1,
        };
        let h = build_volume_octree(bytes, &desc, 2).unwrap();
        h.octree.validate().unwrap();
        let s = h.summary().unwrap();
        assert_eq!(s.input_bytes, 27 * 4);
        let cut = h.cut_boxes(0.0).unwrap();
        assert_eq!(cut.bounds.len(), cut.level.len() * 6);
        assert_eq!(cut.bounds[..6], [0.0, 2.0, 0.0, 4.0, 0.0, 6.0]);
        let bad = GridDesc { component: 3, ..desc };
        assert!(build_volume_octree(bytes, &bad, 2).unwrap_err().contains("component 3"));
    }

    /// A 64^3 ramp (4096 leaf bricks of 4: 16 progress chunks of 256).
    fn ramp64() -> (Vec<f32>, GridDesc) {
        let data: Vec<f32> = (0..64 * 64 * 64).map(|i| (i % 977) as f32).collect();
        (data, f32_desc([64; 3]))
    }

    #[test]
    fn progress_increases_to_one_and_the_build_is_unchanged() {
        let (data, desc) = ramp64();
        let mut seen = Vec::new();
        let h = build_with(as_bytes(&data), &desc, 4, &mut |f| {
            seen.push(f);
            true
        })
        .unwrap();
        assert_eq!(seen.len(), 16, "one report per chunk of 256 leaves: {seen:?}");
        assert!(seen.windows(2).all(|w| w[0] < w[1]) && seen[0] > 0.0, "{seen:?}");
        assert_eq!(*seen.last().unwrap(), 1.0);
        let plain = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        assert_eq!(h.summary().unwrap().node_count, plain.summary().unwrap().node_count);
        assert_eq!(h.cut_boxes(0.0).unwrap().bounds, plain.cut_boxes(0.0).unwrap().bounds);
    }

    #[test]
    fn a_false_report_cancels_at_once_with_a_clear_error() {
        let (data, desc) = ramp64();
        let mut calls = 0;
        let err = build_with(as_bytes(&data), &desc, 4, &mut |_| {
            calls += 1;
            calls < 3
        })
        .expect_err("a cancelled build returns no octree");
        assert_eq!(calls, 3, "no report after the one that said stop");
        assert!(err.contains("cancelled") && err.contains("nothing was produced"), "{err}");
    }
}
