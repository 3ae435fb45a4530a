//! Points in the DrawList (paper 3, section 4): each point is bucketed into
//! the slab of the brick that holds it, between the two slices that bracket
//! its view depth. The compositor draws it there with its footprint
//! ([`crate::points::footprint`]) and the opacity it adds over the volume
//! ([`crate::points::opacity`]).
//!
//! A point at grid sample `x` belongs to the brick whose cell box holds cell
//! `min(x, dims - 2)` (bricks tile the cells, so exactly one does); points in
//! no selected brick lie where the transfer function made the whole node
//! transparent and are not drawn. Points complete T_f, the volume sampled
//! every `f` samples: they are drawn only in bricks of stride `f` (a finer
//! brick already shows their detail, a coarser one misses more than they
//! hold) that took their points in the selection
//! ([`crate::plan::select::select_with_points`], or
//! [`crate::plan::select::take_all_points`] for every such brick), so the points
//! drawn are the points paid for. Its slab is [`crate::plan::slab::slab_of`] of
//! its view depth.

use super::draw_list::{DrawList, PointBucket};
use super::slab::slab_of;
use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::points::PointSet;
use rayon::prelude::*;

/// Buckets `set`'s points into `list`'s bricks and slabs (see the module
/// documentation) and adds the `points` pass to the plan when any point is drawn.
///
/// # Errors
///
/// [`Error::InvalidArgument`] when the points were made for a grid of other
/// dimensions than `shape`'s.
pub fn add_points(list: &mut DrawList, shape: &GridShape, set: &PointSet) -> Result<()> {
    if set.dims != shape.dims {
        return Err(Error::InvalidArgument(format!(
            "the points were made for a {:?} grid, not this {:?} one: generate them from this grid",
            set.dims, shape.dims
        )));
    }
    let owner = BrickMap::new(list, shape.dims);
    let draws = |b: usize| {
        let brick = &list.bricks[b].brick;
        brick.stride == set.factor && brick.point_count > 0
    };
    // Per point: (brick position, slab), in grid order, in parallel.
    let placed: Vec<Option<(usize, usize)>> = set
        .points
        .par_iter()
        .map(|p| {
            let ijk = p.ijk.map(usize::from);
            let b = owner.brick(ijk)?;
            if !draws(b) {
                return None;
            }
            let depth = list.camera.depth(shape.world(ijk.map(|c| c as f64)));
            Some((b, slab_of(&list.bricks[b].slices, depth)))
        })
        .collect();
    for draw in &mut list.bricks {
        draw.points.clear();
    }
    let mut per_brick: Vec<Vec<(usize, u32)>> = vec![Vec::new(); list.bricks.len()];
    for (i, place) in placed.iter().enumerate() {
        if let Some((b, slab)) = *place {
            per_brick[b].push((slab, i as u32));
        }
    }
    let mut any = false;
    for (draw, mut points) in list.bricks.iter_mut().zip(per_brick) {
        points.sort_unstable();
        for (slab, i) in points {
            match draw.points.last_mut() {
                Some(bucket) if bucket.slab == slab => bucket.points.push(i),
                _ => draw.points.push(PointBucket { slab, points: vec![i] }),
            }
            any = true;
        }
    }
    list.plan.passes.retain(|p| p != "points");
    if any {
        list.plan.passes.push("points".to_string());
    }
    Ok(())
}

/// Which brick holds each cell, on a lattice of `g` cells: `g` is the
/// largest power of two not above any brick's extent, so every brick's
/// corner (a multiple of its node size) is on the lattice.
struct BrickMap {
    g: usize,
    dims: [usize; 3],
    owner: Vec<u32>,
}

impl BrickMap {
    fn new(list: &DrawList, grid_dims: [usize; 3]) -> BrickMap {
        let smallest = list.bricks.iter().flat_map(|d| (0..3).map(move |a| d.brick.hi[a] - d.brick.lo[a])).min();
        let g = smallest.unwrap_or(1).max(1);
        let g = 1usize << g.ilog2();
        let dims = grid_dims.map(|n| (n - 1).div_ceil(g));
        let mut owner = vec![u32::MAX; dims[0] * dims[1] * dims[2]];
        for (b, d) in list.bricks.iter().enumerate() {
            let lo = d.brick.lo.map(|c| c / g);
            let hi = [0, 1, 2].map(|a| d.brick.hi[a].div_ceil(g).min(dims[a]));
            for k in lo[2]..hi[2] {
                for j in lo[1]..hi[1] {
                    for i in lo[0]..hi[0] {
                        owner[i + dims[0] * (j + dims[1] * k)] = b as u32;
                    }
                }
            }
        }
        BrickMap { g, dims, owner }
    }

    /// The brick position holding sample `ijk`'s cell, if any.
    fn brick(&self, ijk: [usize; 3]) -> Option<usize> {
        let c = [0, 1, 2].map(|a| (ijk[a] / self.g).min(self.dims[a] - 1));
        let b = self.owner[c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])];
        (b != u32::MAX).then_some(b as usize)
    }
}
