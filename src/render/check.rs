//! Checks of the renderers' inputs, with messages that say what to change:
//! picture sizes, surface colours, and DrawLists that must fit the grid they
//! are drawn over.

use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::plan::DrawList;
use crate::surface::Surface;

/// Checks a surface colour: four numbers in `[0, 1]`.
pub(crate) fn check_colour(colour: [f32; 4]) -> Result<()> {
    if colour.iter().all(|c| (0.0..=1.0).contains(c)) {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "surface colour {colour:?}: red, green, blue and opacity must each be between 0 and 1"
        )))
    }
}

/// Checks a picture size: 1 to 16384 pixels per side.
pub(crate) fn check_size(width: usize, height: usize) -> Result<()> {
    if (1..=16384).contains(&width) && (1..=16384).contains(&height) {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!("picture size {width}x{height}: use 1 to 16384 pixels per side")))
    }
}

/// Checks a DrawList's bricks against the grid: boxes inside it, texel
/// counts that match them, positive spacings, slices back to front.
pub(crate) fn check_bricks(list: &DrawList, shape: &GridShape) -> Result<()> {
    let bad = |m: String| Err(Error::InvalidArgument(format!("DrawList: {m}")));
    if !(list.reference_spacing > 0.0 && list.reference_spacing.is_finite()) {
        return bad(format!("reference spacing {} must be a positive number", list.reference_spacing));
    }
    for (i, d) in list.bricks.iter().enumerate() {
        let b = &d.brick;
        let expected = [0, 1, 2].map(|a| (b.hi[a].saturating_sub(b.lo[a])).div_ceil(b.stride.max(1)) + 1);
        if b.stride == 0 || (0..3).any(|a| b.lo[a] > b.hi[a] || b.hi[a] >= shape.dims[a]) || b.texels != expected {
            return bad(format!(
                "brick {i} (node {}) has box {:?}..{:?}, stride {} and texels {:?}: not a brick of this {:?} grid; \
                 make the DrawList from this grid's octree",
                b.node.0, b.lo, b.hi, b.stride, b.texels, shape.dims
            ));
        }
        if !(d.slice_spacing > 0.0 && d.slice_spacing.is_finite()) {
            return bad(format!("brick {i} has slice spacing {}: it must be a positive number", d.slice_spacing));
        }
        if d.slices.iter().any(|z| !z.is_finite()) || d.slices.windows(2).any(|w| w[0] < w[1]) {
            return bad(format!("brick {i}'s slices must be finite depths listed back to front (decreasing)"));
        }
    }
    Ok(())
}

/// Checks a DrawList against the grid: its bricks (see [`check_bricks`]),
/// and triangle ids of the surface (which must be given when the list draws
/// triangles).
pub(crate) fn check_list(list: &DrawList, shape: &GridShape, surface: Option<&Surface>) -> Result<()> {
    check_bricks(list, shape)?;
    let bad = |m: String| Err(Error::InvalidArgument(format!("DrawList: {m}")));
    // Batch ranges by their last id (an empty range draws nothing).
    let mut ids = list
        .opaque_triangles
        .iter()
        .copied()
        .chain(list.bricks.iter().flat_map(|b| b.batches.iter().filter_map(|t| t.triangles.clone().next_back())));
    match (ids.clone().next(), surface) {
        (None, _) => Ok(()),
        (Some(_), None) => {
            bad("it draws surface triangles but no surface was given: pass the surface the DrawList was made with"
                .into())
        }
        (Some(_), Some(s)) => match ids.find(|&t| t as usize >= s.polygon_count()) {
            Some(t) => bad(format!("triangle {t} is not one of the surface's {} polygons", s.polygon_count())),
            None => Ok(()),
        },
    }
}
