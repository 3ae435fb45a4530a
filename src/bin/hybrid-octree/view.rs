//! The view importance of a scene (`--view-selection`): what the selection
//! of `render` and `bench render` weighs nodes by besides their errors.

use crate::scene::{Loaded, SceneArgs};
use clap::Args;
use hybrid_octree::camera::Camera;
use hybrid_octree::grid::Grid;
use hybrid_octree::plan::BlendMode;
use hybrid_octree::select::{Medium, Occluder, ViewImportance, ViewInputs, ViewSelection};
use hybrid_octree::Result;

/// The view-dependent selection's options.
#[derive(Args, Debug, Clone)]
pub struct ViewArgs {
    /// What the selection weighs nodes by besides their errors: data (the
    /// nodal errors and the region of interest alone), screen (and the
    /// pixels a sample covers, no refinement below --min-texel-pixels,
    /// nothing outside the view), visibility (and the transmittance in
    /// front of each node: little for what the volume or an opaque
    /// isosurface hides), or both.
    #[arg(long, default_value = "both", value_parser = view_selection)]
    pub view_selection: ViewSelection,
    /// Screen-space selection: refinement stops where a texel would cover
    /// fewer pixels than this. The default, 0, never stops: coarse texels
    /// are samples of the data, not averages, and a one-voxel vessel that a
    /// stride of 2 skips is missing from the picture however small its
    /// pixels (docs/BENCHMARKS.md).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub min_texel_pixels: f64,
}

/// `--view-selection` and `--view-selections`: data, screen, visibility or both.
pub fn view_selection(s: &str) -> std::result::Result<ViewSelection, String> {
    s.parse::<ViewSelection>().map_err(|e| e.to_string())
}

/// The medium the visibility estimate marches through, once per scene:
/// the scalar opacity times the smallest gradient opacity under Composite,
/// with the isosurface drawn with the volume; none (nothing hides
/// anything) under a 2D transfer function and the other blend modes, where
/// every sample counts whatever lies in front of it, unless an isosurface
/// is drawn.
pub fn medium(grid: &Grid<'_>, scene: &Loaded, args: &SceneArgs) -> Result<Option<Medium>> {
    let composite = composites(scene);
    let gradient = args.gradient_opacity.as_ref().map_or(1.0, |g| g.min_opacity() as f64);
    let opacity = move |v: f64| if composite { scene.tf.opacity(v) as f64 * gradient } else { 0.0 };
    let occluder = match (&scene.surface, args.isovalue) {
        (Some(_), Some(isovalue)) => Some(Occluder { isovalue, opacity: args.surface_opacity }),
        _ => None,
    };
    if !composite && occluder.is_none() {
        return Ok(None);
    }
    let d0 = hybrid_octree::spacing::reference_spacing(grid.shape());
    Medium::new(&scene.octree, grid, &opacity, d0, occluder).map(Some)
}

/// Composite blending through the scalar opacity (no 2D transfer function).
fn composites(scene: &Loaded) -> bool {
    scene.blend.mode == BlendMode::Composite && scene.transfer_2d.is_none()
}

/// The view importance of `mode` for `scene` seen by `camera`, through
/// `medium` ([`medium`]).
pub fn importance(
    grid: &Grid<'_>,
    args: &SceneArgs,
    camera: &Camera,
    mode: ViewSelection,
    medium: Option<&Medium>,
) -> Result<ViewImportance> {
    importance_in(grid.shape(), args, camera, mode, medium)
}

/// [`importance`] of a volume of `shape` (in memory or on disk).
pub fn importance_in(
    shape: &hybrid_octree::grid::GridShape,
    args: &SceneArgs,
    camera: &Camera,
    mode: ViewSelection,
    medium: Option<&Medium>,
) -> Result<ViewImportance> {
    let inputs = ViewInputs {
        camera,
        width: args.width,
        height: args.height,
        shape,
        min_texel_pixels: args.view.min_texel_pixels,
        medium,
    };
    ViewImportance::new(mode, &inputs)
}
