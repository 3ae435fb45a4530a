//! Points in the DrawList (paper 3, section 4): each point is bucketed into
//! the slab of the brick that holds it, between the two slices that bracket
//! its view depth, and drawn there as a square or Gaussian footprint.
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
//!
//! Opacity (section 3.3: "the error value indicates how much the opacity
//! should be scaled so that, when combined with the volumetric data, the
//! correct opacity is presented"): over one sample's depth the volume gives
//! `a_v = alpha(f - e)` and the original `a_t = alpha(f)`, so the point adds
//!
//! ```text
//! a_p = max(0, (a_t - a_v) / (1 - a_v))      so that 1 - (1 - a_v)(1 - a_p) = a_t
//! ```
//!
//! (points only add: where the low resolution overestimates they add nothing,
//! section 4.1), in the colour of `f`. Footprint (section 4): the point
//! covers one sample spacing `d0`, `s = d0 / pixel` pixels across at its
//! depth. A square is drawn `S = ceil(s)` pixels wide with its opacity scaled
//! by `s^2 / S^2` ("point sizes are always rounded up ... and their opacity is
//! adjusted downward proportional to the increase in area"); a Gaussian
//! splat with `sigma = s / 2` over a `ceil(3 sigma)` radius, its weights
//! scaled to sum to `s^2` pixels of full coverage.

use super::set::PointSet;
use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
use crate::geometry::camera::{Camera, Projection};
use crate::geometry::vec3::{dot, sub};
use crate::plan::{DrawList, PointBucket};
use rayon::prelude::*;

/// The footprint a point is drawn with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Footprint {
    /// A square of whole pixels (an OpenGL point).
    Square,
    /// A Gaussian splat.
    Gaussian,
}

impl std::str::FromStr for Footprint {
    type Err = Error;
    fn from_str(s: &str) -> Result<Footprint> {
        match s {
            "square" => Ok(Footprint::Square),
            "gaussian" => Ok(Footprint::Gaussian),
            _ => Err(Error::InvalidArgument(format!("unknown point footprint '{s}': use square or gaussian"))),
        }
    }
}

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
            Some((b, crate::plan::slab::slab_of(&list.bricks[b].slices, depth)))
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

/// Where a point lands on a `width x height` picture: its centre in pixel
/// coordinates (pixel `(x, y)` covers `[x, x + 1) x [y, y + 1)`), and its
/// footprint size `s` in pixels; `None` behind a perspective camera.
pub fn project(camera: &Camera, width: usize, height: usize, p: [f64; 3], d0: f64) -> Option<([f64; 2], f64)> {
    let (right, up, forward) = camera.basis();
    let r = sub(p, camera.position);
    let h = height as f64;
    // Half the view height in world units at the point's depth.
    let half = match camera.projection {
        Projection::Parallel { scale } => scale,
        Projection::Perspective { view_angle_deg } => {
            let z = dot(r, forward);
            if z <= 0.0 {
                return None;
            }
            z * (view_angle_deg.to_radians() / 2.0).tan()
        }
    };
    let (u, v) = (dot(r, right) / half, dot(r, up) / half);
    let centre = [(u * h + width as f64) / 2.0, (h - v * h) / 2.0];
    Some((centre, d0 * h / (2.0 * half)))
}

/// The pixels a footprint of size `s` centred at `centre` covers, each with
/// its coverage weight (see the module documentation), clipped to the picture.
pub fn footprint(
    kind: Footprint,
    centre: [f64; 2],
    s: f64,
    width: usize,
    height: usize,
    mut pixel: impl FnMut(usize, usize, f64),
) {
    let mut emit = |x: i64, y: i64, w: f64| {
        if x >= 0 && y >= 0 && (x as usize) < width && (y as usize) < height && w > 0.0 {
            pixel(x as usize, y as usize, w);
        }
    };
    match kind {
        Footprint::Square => {
            let side = s.ceil().max(1.0);
            let w = (s * s / (side * side)).min(1.0);
            // The side x side pixels whose centres are nearest the point's centre.
            let x0 = (centre[0] - side / 2.0).round() as i64;
            let y0 = (centre[1] - side / 2.0).round() as i64;
            for y in y0..y0 + side as i64 {
                for x in x0..x0 + side as i64 {
                    emit(x, y, w);
                }
            }
        }
        Footprint::Gaussian => {
            let sigma = (s / 2.0).max(0.5);
            let radius = (3.0 * sigma).ceil() as i64;
            let (cx, cy) = (centre[0].floor() as i64, centre[1].floor() as i64);
            let weight = |x: i64, y: i64| {
                let (dx, dy) = (x as f64 + 0.5 - centre[0], y as f64 + 0.5 - centre[1]);
                (-(dx * dx + dy * dy) / (2.0 * sigma * sigma)).exp()
            };
            let mut sum = 0.0;
            for y in cy - radius..=cy + radius {
                for x in cx - radius..=cx + radius {
                    sum += weight(x, y);
                }
            }
            let scale = s * s / sum;
            for y in cy - radius..=cy + radius {
                for x in cx - radius..=cx + radius {
                    emit(x, y, (weight(x, y) * scale).min(1.0));
                }
            }
        }
    }
}

/// The straight colour of a point of opacity `a_p = (a_t - a_v) / (1 - a_v)`
/// over a volume sample `(c_v, a_v)` such that together they show the
/// original `(c_t, a_t)` premultiplied, `a_v c_v + (1 - a_v) a_p c_p = a_t c_t`:
///
/// ```text
/// c_p = (a_t c_t - a_v c_v) / (a_t - a_v)      clamped to [0, 1]
/// ```
///
/// (paper 3 section 4.1 draws `c_t`, which leaves the combined colour "the
/// average of the correct color and the color of the volume data"; this
/// removes that error wherever the clamp does not bind). Needs `a_t > a_v`.
pub fn point_colour(c_t: [f64; 3], a_t: f64, c_v: [f64; 3], a_v: f64) -> [f64; 3] {
    std::array::from_fn(|k| ((a_t * c_t[k] - a_v * c_v[k]) / (a_t - a_v)).clamp(0.0, 1.0))
}

/// `a_p = max(0, (a_t - a_v) / (1 - a_v))`: the opacity a point adds over a
/// volume of opacity `a_v` so that together they show `a_t`.
pub fn point_opacity(a_t: f64, a_v: f64) -> f64 {
    if a_t <= a_v || a_v >= 1.0 {
        0.0
    } else {
        (a_t - a_v) / (1.0 - a_v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_and_volume_together_give_the_original_opacity() {
        for (a_t, a_v) in [(0.5, 0.2), (0.9, 0.0), (0.3, 0.3), (1.0, 0.5), (1e-9, 0.0)] {
            let a_p = point_opacity(a_t, a_v);
            assert!((1.0 - (1.0 - a_v) * (1.0 - a_p) - a_t).abs() < 1e-12, "{a_t} {a_v}");
        }
        assert_eq!(point_opacity(0.2, 0.5), 0.0, "points never make the volume more transparent");
        assert_eq!(point_opacity(0.9, 1.0), 0.0);
    }

    #[test]
    fn point_and_volume_together_give_the_original_colour() {
        for (c_t, a_t, c_v, a_v) in [(0.8, 0.5, 0.6, 0.2), (0.3, 0.9, 0.5, 0.1), (1.0, 0.4, 0.0, 0.0)] {
            let a_p = point_opacity(a_t, a_v);
            let c_p = point_colour([c_t; 3], a_t, [c_v; 3], a_v)[0];
            // Premultiplied: the volume sample, then the point over it (front to back: under).
            let shown = a_v * c_v + (1.0 - a_v) * a_p * c_p;
            assert!((shown - a_t * c_t).abs() < 1e-12, "{c_t} {a_t} {c_v} {a_v}: {shown}");
        }
        // Where the exact colour is out of range, the clamp keeps it a colour.
        assert_eq!(point_colour([1.0; 3], 0.3, [0.0; 3], 0.29)[0], 1.0);
    }

    #[test]
    fn footprints_cover_the_point_area_once_rounded_up() {
        for kind in [Footprint::Square, Footprint::Gaussian] {
            for s in [0.4, 1.0, 1.7, 3.2] {
                // Total coverage is the point's area s^2 (pixels), whatever the rounding.
                let mut total = 0.0;
                let mut max: f64 = 0.0;
                footprint(kind, [20.3, 17.8], s, 64, 64, |_, _, w| {
                    total += w;
                    max = max.max(w);
                });
                assert!(
                    (total - s * s).abs() < 1e-9 * s * s + if kind == Footprint::Gaussian { 1e-3 } else { 0.0 },
                    "{kind:?} s {s}: {total}"
                );
                assert!(max <= 1.0);
            }
        }
        // Clipped at the picture's edge: nothing outside.
        let mut n = 0;
        footprint(Footprint::Square, [0.0, 0.0], 4.0, 8, 8, |x, y, _| {
            assert!(x < 8 && y < 8);
            n += 1;
        });
        assert_eq!(n, 4);
    }

    #[test]
    fn projection_matches_the_camera_rays() {
        for parallel in [true, false] {
            let c = Camera::around([0.0; 3], [10.0; 3], 30.0, 20.0, parallel).unwrap();
            for (x, y) in [(3usize, 5usize), (40, 17), (63, 63)] {
                let ray = c.ray(x, y, 64, 48);
                let p = [0, 1, 2].map(|a| ray.origin[a] + 7.5 * ray.direction[a]);
                let (centre, s) = project(&c, 64, 48, p, 1.0).unwrap();
                assert!((centre[0] - (x as f64 + 0.5)).abs() < 1e-9 && (centre[1] - (y as f64 + 0.5)).abs() < 1e-9);
                assert!(s > 0.0);
            }
        }
    }
}
