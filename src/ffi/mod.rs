//! The only `#[cxx::bridge]` of the crate: what `cpp/Filters/vtkHybridOctreeBridge.cxx`
//! may call. No other module knows C++ exists.
//!
//! The host holds one object, the Hybrid Octree ([`HybridOctreeHandle`]: the
//! Volume Octree, and the isosurface and points integrated into it when asked),
//! and the selections made from it ([`SelectionHandle`]).
//!
//! Every function body runs under `guard::guarded` and returns `Result`, so
//! a Rust panic becomes a `rust::Error` exception on the C++ side (reported
//! with `vtkErrorMacro`) instead of aborting ParaView.
//!
//! Volume data crosses borrowed: `bytes` is the VTK array's storage
//! (`GetVoidPointer(0)`, `GetDataSize() * GetDataTypeSize()` bytes); nothing is
//! copied. Large outputs cross the other way into the caller's memory: the
//! host learns the sizes from a summary, allocates its VTK arrays or staging
//! buffers, and passes them as `&mut [T]` for Rust to fill (a length that
//! does not match is an error; after any error the buffer's contents are
//! unspecified).

#[cfg(test)]
mod crop_tests;
mod dependent;
mod ftb;
mod geometry;
#[cfg(test)]
mod gradient_opacity_tests;
mod grid;
mod guard;
mod loading;
#[cfg(test)]
mod loading_tests;
mod octree;
mod points;
mod render;
#[cfg(test)]
mod render_tests;
mod reselect;
mod rgba;
mod scattering;
#[cfg(test)]
mod scattering_tests;
#[cfg(test)]
mod shade_tests;
mod slice;
mod store;
#[cfg(test)]
mod store_tests;
mod surface;
#[cfg(test)]
mod test_support;
mod timed;
#[cfg(test)]
mod timed_tests;
mod transfer;
mod transfer2d;
#[cfg(test)]
mod transfer2d_tests;
mod view;
#[cfg(test)]
mod view_tests;

#[cxx::bridge(namespace = "hybrid_octree")]
mod bridge {
    // ---- Shared enums (defined in C++, checked against these) ---------------

    /// The scalar type of the VTK array (VTK_UNSIGNED_CHAR -> U8, ...). The
    /// C++ definition (cpp/Filters/vtkHybridOctreeBridgeEnums.h) is the one the host
    /// uses; cxx checks it against this one at compile time.
    #[derive(Debug)]
    #[repr(u8)]
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

    /// Which isosurface the Hybrid Octree keeps (C++ definition as ScalarType's).
    #[derive(Debug)]
    #[repr(u8)]
    enum SurfaceMode {
        /// Discretized Marching Cubes, coplanar facets merged (lossless).
        Discretized,
        /// Classic Marching Cubes, vertices interpolated along edges.
        Interpolated,
    }

    // ---- Shared structs -------------------------------------------------

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

    /// What an open OME-Zarr image holds (`ffi::store`).
    #[derive(Debug)]
    struct StoreSummary {
        /// Samples per axis (x, y, z), spacing and origin of the full resolution.
        dims: [usize; 3],
        spacing: [f64; 3],
        origin: [f64; 3],
        scalar_type: ScalarType,
        /// Resolution levels `read_level` reads: level `p` holds the samples
        /// `min(i 2^p, n - 1)` per axis.
        levels: usize,
        /// Samples per axis of each level, 3 a level (x, y, z).
        level_dims: Vec<usize>,
        /// Written here: the levels are stored and the Volume Octree with them;
        /// else the octree is built from the full resolution read into memory.
        has_octree: bool,
        /// The image's name.
        name: String,
        /// The NGFF version its metadata declares.
        version: String,
        /// What the reader left out or assumed ("" when nothing), joined by "; ".
        warnings: String,
    }

    /// A frame's loading from a store in the background (`ffi::loading`).
    #[derive(Debug)]
    struct LoadingSummary {
        /// Bricks of the selection drawn by a stand-in: still loading.
        stand_ins: usize,
        /// Bricks of the selection read in the background, waiting for upload.
        loaded: usize,
        /// Bricks the background reader has still to read.
        queued: usize,
        /// Bytes of the read bricks waiting for upload (at most the memory budget and one brick).
        waiting_bytes: usize,
        /// Bytes of samples read from the store so far, by the frames and in the background.
        bytes_read: u64,
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
        /// The node's id in the level-by-level numbering (what a surface polygon's node names).
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
        /// Image side in pixels: the image is `image_size^2` pixels.
        image_size: usize,
        /// Meagher's back-to-front display instead of front to back with blocking quadtrees.
        back_to_front: bool,
    }

    /// What drawing a depth image took (the pixels go to the caller's buffers).
    #[derive(Debug)]
    struct FtbSummary {
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

    /// What `generate_points` and `integrate_points` make (paper 3's points; see `crate::points`).
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

    /// Points of the hybrid representation: how many, and what making them took.
    #[derive(Debug)]
    struct PointsSummary {
        points: usize,
        /// The low-resolution factor the points complete.
        factor: usize,
        /// Bytes of the points as stored (6 or 9 a point).
        point_bytes: usize,
        /// Points with e > 0.
        underestimates: usize,
        generate_ms: f64,
    }

    /// An isosurface integrated into the Hybrid Octree: its sizes (for the
    /// caller's arrays) and what extracting it took.
    #[derive(Debug)]
    struct SurfaceSummary {
        vertices: usize,
        /// Polygons (triangles): `polygons + 1` offsets.
        polygons: usize,
        /// Connectivity entries (3 per triangle).
        connectivity: usize,
        /// Merged coplanar faces (DiscMC with compression), else the triangles.
        faces: u64,
        /// Triangles in the output (= polygons).
        triangles: u64,
        /// Triangles before face compression.
        uncompressed_triangles: u64,
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
        /// Count one border texel per side of each brick in its bytes (the
        /// volume is shaded: the gradient reads them; see `brick_texels_bordered`).
        gradient_border: bool,
        /// The blend mode, VTK's `vtkVolumeMapper::BlendModes` value (0
        /// composite, 1 maximum, 2 minimum, 3 average intensity, 4 additive;
        /// 5 isosurface; 6 slice; others are refused). It changes the selection (MIP and MinIP keep
        /// nodes that hold a ray's extreme, and coarse bricks get peak-keeping
        /// texels) and the plan (`volume-mip`, ...).
        blend_mode: i32,
        /// VTK's AverageIPScalarRange: the values an average intensity counts.
        average_range: [f64; 2],
        /// The brick texel format asked for (`plan::texel_format`): 0 auto
        /// (the data's own width), 1 float32, 2 float16, 3 unorm16, 4
        /// unorm8. Its bytes are what the budget counts; a narrower format
        /// adds its quantization error to every brick's. Dependent
        /// components are always float32.
        texel_format: i32,
        /// The isosurface values of blend mode 5 (vtkVolumeProperty's
        /// IsoSurfaceValues; 1 to 16 finite values), ignored by the others.
        isosurface_values: Vec<f64>,
        /// vtkVolumeProperty's GradientOpacity as VTK's GPU ray caster reads
        /// it, (magnitude, opacity) pairs flattened, magnitudes per mean
        /// voxel spacing (`transfer::gradient_opacity`, `from_vtk`); empty:
        /// none. One that is 0 everywhere hides every node; one that is not
        /// constant counts the gradient border as `gradient_border` does.
        gradient_opacity_points: Vec<f64>,
        /// VTK's cropping and clipping planes: nodes whose box they remove
        /// get no texture (counted as skipped), and the selection's
        /// DrawLists keep only their samples (`plan::crop`).
        region: RegionDesc,
        /// vtkVolumeProperty's TransferFunction2D in TF_2D mode (`ffi::transfer2d`):
        /// its dimensions `[width, height]` (`[0, 0]`: none, the 1D functions
        /// classify), its texels `rgba` (4 floats in [0, 1] per texel,
        /// row-major, x the scalar value, y the gradient magnitude) and
        /// `range`, the data array's finite range its scalar axis spans (the
        /// gradient axis is VTK's). Composite only: nodes over whose range it
        /// is 0 at every gradient are skipped, and the border is counted.
        transfer_2d_size: [usize; 2],
        transfer_2d_rgba: Vec<f32>,
        transfer_2d_range: [f64; 2],
        /// The plane of blend mode 6 (vtkVolumeProperty's SliceFunction, a
        /// vtkPlane, in the octree's frame: the image's data coordinates):
        /// origin x, y, z, normal x, y, z (finite, the normal not 0);
        /// ignored by the other modes. Only nodes whose box it cuts get a
        /// texture (`plan::slice`).
        slice_plane: [f64; 6],
        /// The view the selection is made for (`ffi::view`).
        view: ViewDesc,
    }

    /// The view a selection weighs nodes by (`plan::select::ViewImportance`):
    /// what the camera sees of each node on the viewport.
    #[derive(Debug)]
    struct ViewDesc {
        /// `plan::select::ViewSelection`: 0 data (no view: the camera and
        /// viewport are checked, not read), 1 screen space, 2 visibility, 3 both.
        view_selection: i32,
        /// The camera in the octree's frame (the DrawList's).
        camera: CameraDesc,
        /// The viewport, pixels (width, height; at least 1 each).
        viewport: [usize; 2],
        /// Refinement stops below texels of this many pixels (>= 0; 1 by default).
        min_texel_pixels: f64,
        /// The opacity of the isosurface drawn with the volume (`has_isovalue`,
        /// `isovalue`), in [0, 1]: it hides what is behind it (0: not drawn).
        surface_opacity: f64,
        /// The distance, in the octree's frame, over which `opacity_points`
        /// give their opacity (VTK's ScalarOpacityUnitDistance; > 0).
        opacity_unit_distance: f64,
    }

    /// VTK's cropping (`vtkVolumeMapper`) and clipping planes
    /// (`vtkAbstractMapper`) in the octree's frame, the image's world
    /// coordinates (origin + index * spacing): see `plan::crop`.
    #[derive(Debug)]
    struct RegionDesc {
        /// GetCropping(): off, the cropping planes and flags are not read.
        cropping: bool,
        /// GetCroppingRegionPlanes(): xmin, xmax, ymin, ymax, zmin, zmax.
        cropping_planes: [f64; 6],
        /// GetCroppingRegionFlags(): bit i + 3 j + 9 k keeps region (i, j, k).
        cropping_flags: u32,
        /// 6 per plane (origin x, y, z, normal x, y, z), at most 8 planes:
        /// samples with normal . (x - origin) >= 0 are kept.
        clipping_planes: Vec<f64>,
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
        /// The estimated RMS error (`select::estimated_rms_error`): the
        /// visible bricks' squared nodal errors over their samples, a
        /// fraction of the data range.
        estimated_rms_error: f64,
        /// Nodes left out as fully transparent.
        skipped: usize,
        /// "" when none (else: the budget is below the coarsest representation,
        /// or the tolerance was not reached).
        warning: String,
        /// Points of the hybrid representation bought within the budget (0 without points).
        points: usize,
        /// Their bytes (counted in the budget with the textures).
        point_bytes: usize,
        /// The view importance the selection was weighed by
        /// (`ViewSelection::name`: "data", "screen", "visibility", "both"):
        /// the one asked for, without visibility where it does not apply
        /// (`ffi::view`).
        view_selection: String,
    }

    /// The volume's shading (see `transfer::lighting`): vtkVolumeProperty's
    /// Shade, Ambient, Diffuse, Specular and SpecularPower and the
    /// renderer's lights, directions in world coordinates.
    #[derive(Debug)]
    struct ShadingDesc {
        /// GetShade(): off, nothing else is read.
        shade: bool,
        ambient: f64,
        diffuse: f64,
        specular: f64,
        specular_power: f64,
        /// vtkRenderer's TwoSidedLighting.
        two_sided: bool,
        /// VTK's default lighting (one headlight of intensity 1): the first
        /// light's diffuse and specular colours are used, its direction and
        /// ambient colour are not.
        headlight: bool,
        /// 3 per light: direction of travel (focal point minus position), world.
        light_directions: Vec<f64>,
        /// 3 per light each: colour times intensity.
        light_ambient: Vec<f64>,
        light_diffuse: Vec<f64>,
        light_specular: Vec<f64>,
    }

    /// Volumetric scattering (see `transfer::scattering`): the mapper's
    /// VolumetricScatteringBlending [0, 2] and GlobalIlluminationReach [0, 1],
    /// vtkVolumeProperty's ScatteringAnisotropy [-1, 1], and the headlight's
    /// ambient colour times intensity (read under VTK's default lighting).
    #[derive(Debug)]
    struct ScatteringDesc {
        blending: f64,
        reach: f64,
        anisotropy: f64,
        headlight_ambient: [f64; 3],
        /// VTK's sample distance, world units (0: the reference spacing).
        sample_distance: f64,
    }

    /// What the brick shader's HO_SCATTERING variant reads (see `render::scattering`).
    #[derive(Debug)]
    struct ScatteringFrameDesc {
        blending: f64,
        anisotropy: f64,
        headlight_ambient: [f64; 3],
        /// VTK's shading-gradient length per unit of the world gradient, 2 / (hi - lo).
        gradient_scale: f64,
        /// World position of VTK's texture point 0 and the texture cube's world size.
        texture_corner: [f64; 3],
        texture_size: [f64; 3],
        /// The shadow rays' reach extent, texture units.
        extent: f64,
        /// VTK's sample distance d, world units.
        distance: f64,
        /// d / d0: a table opacity (per reference spacing d0) to VTK's (per d).
        to_vtk: f64,
        /// The shadow volume's points per axis (`shadow_volume_texels`).
        shadow_dims: [usize; 3],
        /// Its texture coordinate of texture point t: t * shadow_scale + shadow_shift.
        shadow_scale: [f64; 3],
        shadow_shift: [f64; 3],
        /// The most samples a shadow ray takes.
        max_steps: usize,
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
        /// The plan's volume effects in order, comma-joined: per sample
        /// "gradient-opacity" or "opacity-scale", then "shading", then what
        /// removes samples in every pass, "cropping", "clipping"
        /// (e.g. "gradient-opacity,shading,cropping"; "" none); first
        /// "transfer-2d" when the 2D transfer function classifies.
        effects: String,
        /// With the effect "transfer-2d": its axes, the scalar range
        /// `[lo, hi]` and the gradient magnitude `g_max` of its last row
        /// (data units per world unit); zeros otherwise.
        transfer_2d_axes: [f64; 3],
        /// The samples take gradients (shading, gradient opacity or the 2D
        /// transfer function): the
        /// brick textures carry the gradient border (`brick_texels_bordered`).
        gradients: bool,
        /// The brick textures carry one border texel per side
        /// (`brick_texels_bordered`): with gradients, or the Isosurface
        /// blend mode (the sample before a brick's first reads it).
        bordered: bool,
        /// The volume's blend mode as drawn, VTK's value (0 composite,
        /// 1 maximum, 2 minimum, 3 average intensity, 4 additive,
        /// 5 isosurface).
        blend_mode: i32,
        /// The samples are shaded (the plan's "shading" effect).
        shading: bool,
        /// The brick textures' texel format as resolved for the data (1
        /// float32: R32F, 2 float16: R16F, 3 unorm16: R16, 4 unorm8: R8;
        /// `brick_texels_encoded`) and its decoding: a texture read `t`
        /// (normalized for R16 and R8) is the value `texel_bias + texel_scale t`.
        texel_format: i32,
        texel_scale: f64,
        texel_bias: f64,
        /// Bytes of one texel on the GPU (all fields): for an RGBA volume
        /// ("rgba-components") 4 (RGBA8, u8 data, texel_format 4 unorm8,
        /// red, the gradient's channel, decoded with texel_scale 255) or 16 (RGBA32F).
        texel_bytes: usize,
        /// With "rgba-components": VTK 9.2's reading of a texture read t
        /// (normalized for RGBA8; `transfer::direct_colour`): the colour
        /// channels' `s = scale t + bias`, the three scales then the three
        /// biases, then channel a's value for the opacity function, `v' =
        /// scale t + bias` (the table clamps it); empty otherwise.
        rgba_reading: Vec<f64>,
        /// Every sample's opacity times this before the correction (1: none).
        opacity_scale: f64,
        /// With the effect "gradient-opacity": the function at magnitudes
        /// k end / (n - 1), k = 0 .. n (data units per world unit of the
        /// octree's frame), held past the ends; empty otherwise.
        gradient_opacity_table: Vec<f32>,
        /// The magnitude of the table's last entry.
        gradient_opacity_end: f64,
        /// The cropping and planes that act (those of the selection's
        /// region that remove part of the volume; `cropping` false and no
        /// planes when nothing does).
        region: RegionDesc,
        /// Under the Slice blend mode (pass "volume-slice[-shaded]") its
        /// plane, origin x, y, z, normal x, y, z; empty otherwise.
        slice_plane: Vec<f64>,
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
        /// Per batch: surface triangles [first, end) (polygon ids of the octree's surface).
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
        /// Point ids (into the octree's points), in grid order within a bucket.
        bucket_points: Vec<u32>,
    }

    /// A frame to draw within a time (`ffi::timed`): the target, and what
    /// its DrawList is planned with, as the mapper plans the frame's own
    /// (the same camera, viewport, surface opacity and effects).
    #[derive(Debug)]
    struct TimedFrameDesc {
        /// The frame-time target, ms (above 0, at most ten minutes).
        target_ms: f64,
        /// The camera, in the octree's frame (the DrawList's).
        camera: CameraDesc,
        /// The viewport, pixels.
        width: usize,
        height: usize,
        /// The octree's surface drawn at this opacity (0: hidden).
        surface_opacity: f64,
        /// The frame's shading, gradient opacity (VTK's points), jittering,
        /// ray sample distance and scattering, as set on the selection.
        shading: ShadingDesc,
        gradient_opacity_points: Vec<f64>,
        jittering: bool,
        sample_distance: f64,
        scattering: ScatteringDesc,
    }

    /// What a FrameTimer chose for its last frame and what that frame took.
    #[derive(Debug)]
    struct TimedSummary {
        /// The target, ms.
        target_ms: f64,
        /// The chosen frame's predicted drawing time, ms.
        predicted_ms: f64,
        /// The last observed frame's drawing time, ms (0 before one).
        measured_ms: f64,
        /// The budget the chosen selection was made under, bytes.
        budget_bytes: usize,
        /// Its slices' least spacing in multiples of d0 (1: the strides').
        slice_factor: u32,
        /// "warm-up" (a calibration frame: budgets spread from the coarsest
        /// to the limit), "met", "full" or "below-fastest" (`plan::cost::Outcome`).
        outcome: String,
        /// Candidates the search evaluated (1 for a warm-up frame).
        evaluations: usize,
        /// The chosen selection's estimated RMS error (fraction of the data range).
        estimated_rms_error: f64,
        /// Warm-up frames still to measure before the model is fitted.
        warm_up_left: usize,
        /// The online correction: measured over modelled time.
        ratio: f64,
        /// Said when the target is below the fastest frame ("" otherwise).
        note: String,
    }

    /// What the OpenGL mapper's vertices of a frame are made from (see
    /// `plan::draw_geometry`), borrowed from the host: the camera (`eye`,
    /// `view_up`; `forward` the DrawList's), the image spacing, the DrawList's
    /// parts as DrawListOutput names them, the transfer function's table (4
    /// floats a cell, cells over [table_lo, table_hi]), per brick its block
    /// ranges (`brick_block_ranges`); when `with_surface` (and the list has
    /// batches) the surface triangles as uploaded (6 floats a vertex:
    /// position, normal; 3 vertex ids a triangle), when `with_points` (and
    /// the list has buckets) the points' positions (3 a point) and shades (4
    /// a point: straight colour, opacity).
    struct BrickGeometryDesc<'a> {
        eye: [f64; 3],
        forward: [f64; 3],
        view_up: [f64; 3],
        spacing: [f64; 3],
        bounds: &'a [f64],
        texels: &'a [usize],
        stride: &'a [usize],
        slice_offsets: &'a [usize],
        slices: &'a [f64],
        batch_offsets: &'a [usize],
        batch_first: &'a [u32],
        batch_end: &'a [u32],
        bucket_offsets: &'a [usize],
        bucket_slab: &'a [usize],
        bucket_point_offsets: &'a [usize],
        bucket_points: &'a [u32],
        table: &'a [f32],
        table_lo: f64,
        table_hi: f64,
        block_ranges: &'a [&'a [f32]],
        with_surface: bool,
        surface_vertices: &'a [f32],
        surface_triangles: &'a [u32],
        with_points: bool,
        point_positions: &'a [f32],
        point_shades: &'a [f32],
        gaussian_points: bool,
        /// The DrawList's `slice_plane` (Slice: 6 values, each brick drawn as
        /// the plane's polygon in it, `plan::draw_geometry::slice_plane`;
        /// empty: the slices and boxes of the other modes).
        slice_plane: &'a [f64],
    }

    /// The vertices of every brick of a frame (`plan::draw_geometry::brick_geometry`).
    #[derive(Debug)]
    struct BrickGeometryOutput {
        /// 11 floats a vertex: position, normal, clip interval (near, far),
        /// primitive kind (0 slice, 1 surface triangle, 2 ray-marched box, 3
        /// square point, 4 Gaussian point), point opacity, the brick's index.
        vertices: Vec<f32>,
        /// Brick i's vertices are brick_first[i] .. brick_first[i + 1].
        brick_first: Vec<usize>,
        /// Per brick, 1: drawn as its ray-marched box (no triangle or point between its slices).
        ray_marched: Vec<u8>,
        /// Per brick, 1: some block is visible under the table (else nothing of its volume is drawn).
        drawn: Vec<u8>,
        /// 6 per brick: the box its slices are clipped to, its visible blocks (VTK order; 0 when not drawn).
        boxes: Vec<f64>,
        /// The view's up, unit and perpendicular to forward: a point quad's up.
        point_up: [f32; 3],
        /// Surface triangle copies placed (a triangle in several slabs counted each time).
        triangles_placed: usize,
        /// Points placed.
        points_placed: usize,
    }

    // ---- C++ types for Rust ------------------------------------------------

    unsafe extern "C++" {
        include!("hybrid-octree/cpp/Filters/vtkHybridOctreeBuildProgress.h");
        /// The build's progress sink (cpp/Filters/vtkHybridOctreeBuildProgress.h).
        type BuildProgress;
        /// `fraction` of the build done, in (0, 1]; false asks the build to stop.
        fn report(self: &BuildProgress, fraction: f64) -> bool;

        include!("hybrid-octree/cpp/Filters/vtkHybridOctreeBridgeEnums.h");
        type ScalarType;
        type SurfaceMode;
    }

    // ---- Rust types and functions for C++ --------------------------------

    extern "Rust" {
        /// The Hybrid Octree, owned by the C++ filter or mapper: the Volume
        /// Octree, and the isosurface and points integrated into it.
        type HybridOctreeHandle;

        /// Builds the Volume Octree of the borrowed image (no surface, no
        /// points yet), reporting progress to `progress` between chunks of
        /// leaf bricks (on the calling thread); its `false` cancels the build
        /// (the error names the cancel; nothing is kept).
        fn build_hybrid_octree(
            bytes: &[u8],
            desc: &GridDesc,
            leaf_size: u32,
            progress: &BuildProgress,
        ) -> Result<Box<HybridOctreeHandle>>;
        /// Builds the octrees of a 2-component image with dependent
        /// components (`desc.components` 2, `desc.component` not read):
        /// colour from component 0, opacity from component 1 (VTK's
        /// IndependentComponentsOff; ParaView's Use Separate Opacity Array).
        /// Its selections are made on the opacity field's ranges and both
        /// fields' errors, count 8 bytes a texel, and their DrawLists say
        /// `dependent-components` (Composite); read their texels with
        /// `brick_texels_dependent`. A 4-component image is an RGBA volume
        /// (VTK's IndependentComponentsOff on 4 components): colour from
        /// components 0, 1, 2 as VTK 9.2 reads them, opacity from component
        /// 3, gradient from component 0; its selections count 4 bytes a texel for u8 data
        /// (RGBA8) and 16 otherwise, their DrawLists say `rgba-components`
        /// (Composite); read their texels with `brick_texels_rgba`. Errors:
        /// another component count (1 or 3: refused with the reason), and
        /// those of `build_hybrid_octree`.
        fn build_dependent_octree(
            bytes: &[u8],
            desc: &GridDesc,
            leaf_size: u32,
            progress: &BuildProgress,
        ) -> Result<Box<HybridOctreeHandle>>;
        /// An open OME-Zarr image (NGFF 0.4 or 0.5; `crate::store::Store`).
        type StoreHandle;
        /// Opens the OME-Zarr image in the folder `path` (errors: not a
        /// folder, no or damaged NGFF metadata, an unsupported type or axes).
        fn open_store(path: &str) -> Result<Box<StoreHandle>>;
        /// Its full resolution's dims, spacing, origin and type, its levels, name.
        fn summary(self: &StoreHandle) -> Result<StoreSummary>;
        /// The closed box `lo ..= hi` (level indices, x, y, z) of level
        /// `level` into the caller's `bytes` (the box's samples x fastest,
        /// native byte order, the store's type; errors: a box outside the
        /// level, a missing or damaged chunk, more memory than allowed).
        fn read_level(self: &StoreHandle, level: usize, lo: &[usize], hi: &[usize], bytes: &mut [u8]) -> Result<()>;
        /// Bytes of samples read from the store so far (brick texels, by
        /// the frames and by the background reader).
        fn bytes_read(self: &StoreHandle) -> u64;
        /// The Hybrid Octree of a store: the stored Volume Octree (its own
        /// leaf size; `leaf_size` is not read), or for an image written
        /// elsewhere the one built from its full resolution read into memory
        /// with leaves of `leaf_size` cells. Its grid is the full resolution.
        fn build_octree_from_store(store: &StoreHandle, leaf_size: u32) -> Result<Box<HybridOctreeHandle>>;

        /// Node counts, levels, memory and build time.
        fn summary(self: &HybridOctreeHandle) -> Result<OctreeSummary>;
        /// The cut at normalised tolerance `tolerance` (the first nodes from the
        /// root whose e_0 <= tolerance, or leaf bricks).
        fn cut_boxes(self: &HybridOctreeHandle, tolerance: f64) -> Result<CutBoxes>;

        /// Surface data integration: extracts the isosurface of the image the
        /// octree was built from (the same bytes and description) and keeps
        /// it, replacing any. An isovalue outside the data range gives an
        /// empty surface; a non-finite one is an error (the octree then holds
        /// no surface).
        fn integrate_surface(
            self: &mut HybridOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            isovalue: f64,
            mode: SurfaceMode,
            measure_distance: bool,
        ) -> Result<SurfaceSummary>;
        /// Drops the isosurface.
        fn remove_surface(self: &mut HybridOctreeHandle) -> Result<()>;
        /// The isosurface as a mesh, world coordinates, into the caller's
        /// arrays (sizes from its SurfaceSummary): `points` 3 per vertex,
        /// `normals` 3 per vertex (unit, from values >= isovalue towards
        /// values below it), polygon i uses connectivity[offsets[i] ..
        /// offsets[i + 1]] (`polygons + 1` offsets), and per polygon the
        /// terminal node holding it, its level and the merged coplanar face
        /// it triangulates. Node ids and levels must fit an `i32`.
        #[allow(clippy::too_many_arguments)]
        fn surface_mesh(
            self: &HybridOctreeHandle,
            points: &mut [f64],
            normals: &mut [f32],
            offsets: &mut [i64],
            connectivity: &mut [i64],
            polygon_node: &mut [i32],
            polygon_level: &mut [i32],
            polygon_face: &mut [i64],
        ) -> Result<()>;
        /// The isosurface as the GPU draws it: `vertices` 6 floats a vertex
        /// (world position, then unit normal), `indices` 3 a triangle (the
        /// DrawList's triangle ids are these triangles' positions).
        fn surface_triangles(self: &HybridOctreeHandle, vertices: &mut [f32], indices: &mut [u32]) -> Result<()>;

        /// The binary octree of the borrowed image drawn along `options.vpn`
        /// into the caller's `image_size^2` pixels, rows from the BOTTOM (VTK
        /// image order): `depth` the distance from the view plane (smaller is
        /// nearer, NaN where nothing was painted), `face` 0 for nothing, 1 +
        /// the axis of the face painted, `shaded` RGB (3 a pixel, 0 where
        /// nothing was painted). Errors: a zero or non-finite VPN, a
        /// non-finite isovalue or label, an image size outside 8..=8192.
        fn ftb_display(
            bytes: &[u8],
            desc: &GridDesc,
            options: &FtbDesc,
            depth: &mut [f32],
            face: &mut [u8],
            shaded: &mut [u8],
        ) -> Result<FtbSummary>;

        /// Points completing a low resolution of a borrowed image, made by
        /// `generate_points` and read out once their count is known.
        type GeneratedPoints;

        /// The points completing the borrowed image's low resolution (errors:
        /// a factor other than 2, 4 or 8, a threshold or bound outside [0, 1],
        /// a grid too small for the factor, a file that cannot be written).
        fn generate_points(bytes: &[u8], desc: &GridDesc, options: &PointsDesc) -> Result<Box<GeneratedPoints>>;
        /// Count, factor, bytes, underestimates, time.
        fn summary(self: &GeneratedPoints) -> Result<PointsSummary>;
        /// The points into the caller's arrays (one entry a point, 3 for
        /// `ijk` and `normal`): grid index, original value and error
        /// f - T_f (both quantised to 8 bits, as stored), unit normal from
        /// the 256-direction table.
        fn fill(
            self: &GeneratedPoints,
            ijk: &mut [u32],
            value: &mut [f32],
            error: &mut [f32],
            normal: &mut [f32],
        ) -> Result<()>;

        /// Points data integration: the points completing the borrowed
        /// image's stride-`factor` textures (plain subsampling:
        /// `max_overestimate` must be < 0, the textures being the image
        /// itself), kept for the selections, replacing any.
        fn integrate_points(
            self: &mut HybridOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            options: &PointsDesc,
        ) -> Result<PointsSummary>;
        /// Drops the points.
        fn remove_points(self: &mut HybridOctreeHandle) -> Result<()>;
        /// The points as the renderer draws them, into the caller's arrays
        /// (one entry a point, 3 for `position`): the sample's world
        /// position (the grid's frame), its original value f and error e =
        /// f - T_f (dequantised as stored: the volume shows f - e there).
        fn points_drawing(
            self: &HybridOctreeHandle,
            position: &mut [f32],
            value: &mut [f32],
            error: &mut [f32],
        ) -> Result<()>;
        /// What each point adds under the transfer function of `colors`
        /// ((value, r, g, b) flattened) and `opacities` ((value, opacity)),
        /// into `shades`: 4 floats a point, straight colour and opacity,
        /// averaged over its voxel (see `points::shade`); `bytes` and `desc`:
        /// the image the points were made from.
        fn point_shades(
            self: &HybridOctreeHandle,
            bytes: &[u8],
            desc: &GridDesc,
            colors: &[f64],
            opacities: &[f64],
            shades: &mut [f32],
        ) -> Result<()>;

        /// A selection of the octree's nodes and texture levels, for drawing.
        type SelectionHandle;

        /// The model of what a frame costs on this machine, calibrated on
        /// warm-up frames and corrected online (`ffi::timed`), owned by the
        /// mapper across octrees.
        type FrameTimer;
        /// A timer with the prior model, its warm-up to come.
        fn new_frame_timer() -> Box<FrameTimer>;
        /// The selection of `options` (its budget the hard memory limit)
        /// of least estimated error whose frame is predicted within
        /// `frame.target_ms`; during the warm-up, the next calibration
        /// budget's. Errors: a bad target, and those of `select_bricks`.
        fn select_for_time(
            self: &mut FrameTimer,
            octree: &HybridOctreeHandle,
            options: &SelectDesc,
            frame: &TimedFrameDesc,
        ) -> Result<Box<SelectionHandle>>;
        /// Feeds a frame drawn from `selection` (made by `select_for_time`,
        /// its effects set as `frame` says) that uploaded `uploaded_bytes`
        /// and took `ms` to draw to the model. True when the next frame
        /// should select again: a warm-up frame, the model just fitted, or
        /// the correction moved more than a quarter since the last search.
        fn observe_frame(
            self: &mut FrameTimer,
            selection: &SelectionHandle,
            octree: &HybridOctreeHandle,
            frame: &TimedFrameDesc,
            uploaded_bytes: usize,
            ms: f64,
        ) -> Result<bool>;
        /// What the last `select_for_time` chose and the last frame took.
        fn summary(self: &FrameTimer) -> TimedSummary;

        /// Selects bricks within the budget (errors: budget 0, a tolerance
        /// that is not a number >= 0, a bad ROI or opacity points). With
        /// points integrated, the budget goes to textures and points: a brick
        /// at the points' stride takes its points when they remove more error
        /// per byte than refining it, and the DrawLists bucket the points
        /// bought into the slabs.
        fn select_bricks(self: &HybridOctreeHandle, options: &SelectDesc) -> Result<Box<SelectionHandle>>;
        /// What a selection of `options` with the visibility importance
        /// needs from the image (`bytes`, `desc`: the one the octree was
        /// built from): the medium the estimate marches through, made once
        /// per transfer function and kept in the handle (`ffi::view`).
        /// Nothing when `options` does not use the visibility.
        fn prepare_view(self: &HybridOctreeHandle, bytes: &[u8], desc: &GridDesc, options: &SelectDesc) -> Result<()>;
        /// Bricks, bytes, error, skipped nodes, warning.
        fn summary(self: &SelectionHandle) -> Result<SelectionSummary>;
        /// How far the view moved from camera `a` to camera `b` around
        /// `centre` (x, y, z; degrees, `plan::select::view_change_degrees`);
        /// an error for a camera that is not one.
        fn view_change_degrees(a: &CameraDesc, b: &CameraDesc, centre: &[f64]) -> Result<f64>;
        /// The DrawList of the selection for `camera` (`octree`: the one the
        /// selection was made from), with the octree's surface, when it holds
        /// one, at `surface_opacity` (1: opaque pass first; (0, 1): batches
        /// in the slabs, whose SlabPolygons are made on the first call and
        /// kept for this surface; 0: hidden).
        fn draw_list(
            self: &SelectionHandle,
            octree: &HybridOctreeHandle,
            camera: &CameraDesc,
            surface_opacity: f64,
        ) -> Result<DrawListOutput>;
        /// Brick `brick`'s texels as f32, x fastest (see
        /// `render::texture::brick_texels_f32`), from the image the octree
        /// was built from, into `texels` (the brick's texel count).
        fn brick_texels(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            brick: usize,
            texels: &mut [f32],
        ) -> Result<()>;
        /// Brick `brick`'s texels with the gradient border of a shaded
        /// volume: (texels + 2) per axis, texel i at lo + (i - 1) stride
        /// clamped to the grid (`render::texture::bordered_position`); a
        /// world point's texture coordinate is then (x - xmin) / (stride *
        /// spacing[a]) + 1 texels.
        fn brick_texels_bordered(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            brick: usize,
            texels: &mut [f32],
        ) -> Result<()>;
        /// Brick `brick`'s texels in the selection's texel format
        /// (`DrawListOutput::texel_format`), with the gradient border when
        /// `bordered`: into `decoded` the values they decode to (f32, for
        /// the block ranges) and into `encoded` what the GPU uploads, the
        /// texel count of: bytes (unorm8), native-endian u16 (unorm16), or
        /// f32 (float16: each the exact value of a half float, uploaded
        /// into R16F; float32: the values).
        fn brick_texels_encoded(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            brick: usize,
            bordered: bool,
            decoded: &mut [f32],
            encoded: &mut [u8],
        ) -> Result<()>;
        /// Brick `brick`'s texels read from `store` (the volume the octree
        /// was built from, `build_octree_from_store`): the texels
        /// `brick_texels_bordered` (`bordered`) or `brick_texels` give in
        /// memory into `texels` when `encoded` is empty, else those of
        /// `brick_texels_encoded` into `texels` (decoded) and `encoded`.
        /// `octree`: the one the selection was made from; the brick's own
        /// samples must lie in its node's stored range (a chunk missing from
        /// the store reads as the fill value: found so). Errors: dependent or
        /// RGBA selections, coarse bricks of a maximum or minimum intensity
        /// (their peaks are not stored), a read failure, samples outside the range.
        fn brick_texels_from_store(
            self: &SelectionHandle,
            octree: &HybridOctreeHandle,
            store: &StoreHandle,
            brick: usize,
            bordered: bool,
            texels: &mut [f32],
            encoded: &mut [u8],
        ) -> Result<()>;
        /// Plans a frame's loading from `store` in the background: the
        /// selected bricks above two texels a side whose textures are not
        /// resident (`resident_nodes[i]`, `resident_strides[i]`) are read
        /// by a thread of the store's, most important first, holding at
        /// most `memory_bytes` of read bricks waiting for upload; until one
        /// is read, the DrawLists and brick texels made after this call
        /// draw it by its stand-in (the same node two levels coarser, 1/64
        /// of the texels, read at once). Errors: another octree or store, a read of the
        /// background thread that failed (a missing or damaged chunk).
        fn plan_loading(
            self: &SelectionHandle,
            octree: &HybridOctreeHandle,
            store: &StoreHandle,
            resident_nodes: &[u32],
            resident_strides: &[usize],
            memory_bytes: usize,
        ) -> Result<LoadingSummary>;
        /// The DrawLists and brick texels made after this call draw the
        /// selection's own bricks (no stand-ins).
        fn draw_selected(self: &SelectionHandle);
        /// Brick `brick`'s texels of both fields of a selection made from
        /// `build_dependent_octree`'s octree: (colour, opacity) f32 pairs,
        /// texels x fastest, `2 x` the texel count (with the gradient border
        /// of `brick_texels_bordered` when `bordered`).
        fn brick_texels_dependent(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            brick: usize,
            bordered: bool,
            texels: &mut [f32],
        ) -> Result<()>;
        /// Brick `brick`'s texels of the four components of a selection made
        /// from an RGBA volume's octree (`build_dependent_octree` of a
        /// 4-component image), texels x fastest, with the gradient border
        /// when `bordered`: into `decoded` the values as f32 quadruples
        /// (`4 x` the texel count), and, for u8 data, into `encoded` the
        /// RGBA8 bytes the GPU uploads (`4 x` the texel count; empty for
        /// other types, whose `decoded` floats are uploaded as RGBA32F).
        fn brick_texels_rgba(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            brick: usize,
            bordered: bool,
            decoded: &mut [f32],
            encoded: &mut [u8],
        ) -> Result<()>;
        /// The shading of the DrawLists and pictures made after this call
        /// (errors: a bad number; a shade without lights or lights not in
        /// threes). The plan then says "volume-shaded" unless it changes no colour.
        fn set_shading(self: &SelectionHandle, shading: &ShadingDesc) -> Result<()>;
        /// The gradient opacity of the DrawLists and pictures made after
        /// this call: vtkVolumeProperty's GradientOpacity points as
        /// `SelectDesc::gradient_opacity_points` (empty: none; errors: an odd
        /// count, magnitudes not finite or decreasing, opacities outside
        /// [0, 1]). The plan's effects then say "gradient-opacity", or
        /// "opacity-scale" for a constant other than 1.
        fn set_gradient_opacity(self: &SelectionHandle, points: &[f64]) -> Result<()>;
        /// The volumetric scattering of the DrawLists and pictures made
        /// after this call (errors: a value out of its range); the plan's
        /// effects then say "volume-scattering" when it runs.
        fn set_scattering(self: &SelectionHandle, scattering: &ScatteringDesc) -> Result<()>;
        /// What the brick shader reads for the scattering last set.
        fn scattering_frame(self: &SelectionHandle) -> Result<ScatteringFrameDesc>;
        /// The shadow volume of the image the octree was built from into
        /// `texels` (the product of `shadow_dims` floats, x fastest).
        fn shadow_volume_texels(
            self: &SelectionHandle,
            bytes: &[u8],
            desc: &GridDesc,
            texels: &mut [f32],
        ) -> Result<()>;

        /// Jittering (VTK's UseJittering) of the DrawLists and pictures made
        /// after this call: the plan's effects then end with "jittering" when
        /// it applies (a volume not in Slice, no translucent surface or points
        /// between the slices; see `plan::jitter`).
        fn set_jittering(self: &SelectionHandle, on: bool) -> Result<()>;

        /// The ray sample distance (world units; VTK's SampleDistance) of the
        /// DrawLists and pictures made after this call: the Isosurface blend
        /// mode and the 2D transfer function slice every `distance / d0` of
        /// a lattice step when it is below `d0` (effect "sample-distance";
        /// see `plan::sampling`); 0 (the default): one slice a lattice step.
        /// A negative or non-finite distance is an error.
        fn set_sample_distance(self: &SelectionHandle, distance: f64) -> Result<()>;

        /// Floats of the block ranges of a brick of `dims` texels (x, y, z):
        /// 2 per block of 4^3 cells (see `plan::draw_geometry::occupancy`).
        fn block_ranges_len(dims: &[usize]) -> Result<usize>;
        /// A brick's block value ranges ([min, max] per block, NaN left out)
        /// from its `texels` (`dims`, x fastest), into the caller's `ranges`
        /// (`block_ranges_len(dims)` floats): measured once, when the texels
        /// are made.
        fn brick_block_ranges(texels: &[f32], dims: &[usize], ranges: &mut [f32]) -> Result<()>;
        /// The OpenGL mapper's vertices of a frame: per brick its slices
        /// clipped to its visible blocks, the surface triangles and points in
        /// the slabs between them (the CPU compositor's slab rule), or its
        /// ray-marched box.
        fn brick_geometry(desc: &BrickGeometryDesc) -> Result<BrickGeometryOutput>;

        /// The CPU compositor's picture of the selection's DrawList for
        /// `camera` into `rgba`: `width x height` premultiplied RGBA (4
        /// floats a pixel, rows from the top), with the transfer function
        /// of `colors` ((value, r, g, b) flattened) and `opacities` ((value,
        /// opacity) flattened), over the image the octree was built from; a
        /// selection made with points draws them, with Gaussian footprints
        /// when `gaussian_points`, else square ones; the octree's surface,
        /// when it holds one and `surface_rgba` (r, g, b, opacity) has an
        /// opacity above 0, headlight-shaded (opacity 1: the opaque pass,
        /// below 1: the batches in the slabs).
        #[allow(clippy::too_many_arguments)]
        fn composite(
            self: &SelectionHandle,
            octree: &HybridOctreeHandle,
            camera: &CameraDesc,
            bytes: &[u8],
            desc: &GridDesc,
            colors: &[f64],
            opacities: &[f64],
            gaussian_points: bool,
            surface_rgba: &[f64],
            width: usize,
            height: usize,
            rgba: &mut [f32],
        ) -> Result<()>;
    }
}

use bridge::BuildProgress;
pub use bridge::{
    BrickGeometryDesc, BrickGeometryOutput, CameraDesc, CutBoxes, DrawListOutput, FtbDesc, FtbSummary, GridDesc,
    LoadingSummary, OctreeSummary, PointsDesc, PointsSummary, RegionDesc, ScalarType, ScatteringDesc,
    ScatteringFrameDesc, SelectDesc, SelectionSummary, ShadingDesc, StoreSummary, SurfaceMode, SurfaceSummary,
    TimedFrameDesc, TimedSummary, ViewDesc,
};
use dependent::build_dependent_octree;
use ftb::ftb_display;
use geometry::{block_ranges_len, brick_block_ranges, frame_brick_geometry as brick_geometry};
use octree::build_hybrid_octree;
pub use octree::HybridOctreeHandle;
use points::generate_points;
pub use points::GeneratedPoints;
pub use render::SelectionHandle;
pub use store::StoreHandle;
use store::{build_octree_from_store, open_store};
use timed::new_frame_timer;
pub use timed::FrameTimer;
use view::view_change_degrees;
