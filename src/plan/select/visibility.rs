//! Visibility importance: an estimate of the transmittance in front of
//! each node, made front to back before the selection.
//!
//! The estimate works on the nodes of one coarse level `c` of the Volume
//! Octree (at most 32 per axis, never finer than the leaf bricks). Once per
//! transfer function, the [`Medium`]: each coarse node's mean opacity over
//! its samples (every `q`-th per axis, `q = max(1, size / 4)`; NaN is no
//! data, transparent) and which side of an isosurface it lies on:
//!
//! ```text
//! alpha(n) = mean over the node's samples of alpha(v)       (a layer d0 thick)
//! tau(n)   = -ln(1 - alpha(n)) / d0                         (optical depth per world unit)
//! side(n)  = above (min > iso) or below (max < iso), without NaN; eroded over the 26 neighbours
//! ```
//!
//! Once per view, the [`Transmittance`]: from the centre of each coarse
//! node a ray to the eye (along `-forward` under a parallel projection),
//! sampled `h` apart from where it leaves the node to where it leaves the
//! grid:
//!
//! ```text
//! T(n) = exp(-sum_i tau(n_i) h) * (1 - a_s)^[the ray crosses the isosurface]
//! ```
//!
//! `tau` of the mean opacity never exceeds the mean of `tau` (`-ln(1 - x)`
//! is convex), so a node seen through a mixed region is never taken as
//! more hidden than the region's average ray says; the estimate follows the
//! camera from one view to the next. The ray crosses an isosurface of
//! opacity `a_s` when it meets one eroded node entirely above the isovalue
//! and one entirely below it: the field between them takes the isovalue,
//! on every ray from the node (the erosion covers the rays' offsets from
//! the centre's).
//!
//! A node of level `k <= c` takes the largest `T` of the coarse nodes it
//! holds (a max pyramid); a finer node takes its coarse node's.

use crate::base::error::{Error, Result};
use crate::data::grid::{Grid, GridShape};
use crate::geometry::camera::{Camera, Projection};
use crate::geometry::vec3::{norm, sub};
use crate::octree::VolumeOctree;
use rayon::prelude::*;

/// The finest coarse level: `2^5 = 32` nodes per axis at most.
const MAX_COARSE_LOG2: usize = 5;

/// Optical depth past which nothing shows (`e^-30`): the march stops.
const OPAQUE_DEPTH: f64 = 30.0;

/// An isosurface drawn with the volume: what hides the volume behind it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Occluder {
    /// The isovalue (data units).
    pub isovalue: f64,
    /// Its opacity `a_s` in `[0, 1]` (1: opaque).
    pub opacity: f64,
}

/// The coarse nodes the rays march through, for one transfer function
/// (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Medium {
    /// The coarse level `c` and its nodes per axis.
    coarse: usize,
    dims: [usize; 3],
    /// `tau` per node, per world unit.
    tau: Vec<f64>,
    /// Entirely above (bit 0) or below (bit 1) the isovalue, eroded.
    side: Vec<u8>,
    /// Index units per coarse node.
    node_size: f64,
    /// The isosurface's opacity (0 without one).
    surface_opacity: f64,
}

/// The per-node transmittance of one view (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmittance {
    /// The coarse level `c`.
    coarse: usize,
    /// `pyramid[k]`: the largest `T` over each node of level `k <= c`, x fastest.
    pyramid: Vec<Vec<f32>>,
    /// Nodes per axis at each level `k <= c`.
    dims: Vec<[usize; 3]>,
}

impl Medium {
    /// The medium of `grid` (the octree's) under `opacity(v)`, the opacity
    /// of a layer `d0` world units thick at value `v`, with `occluder` an
    /// isosurface drawn with the volume.
    pub fn new(
        octree: &VolumeOctree,
        grid: &Grid<'_>,
        opacity: &(dyn Fn(f64) -> f64 + Sync),
        d0: f64,
        occluder: Option<Occluder>,
    ) -> Result<Medium> {
        if !(d0 > 0.0 && d0.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "visibility estimate: opacity unit distance {d0}: give a positive number of world units"
            )));
        }
        if let Some(o) = occluder {
            if !o.isovalue.is_finite() || !(0.0..=1.0).contains(&o.opacity) {
                return Err(Error::InvalidArgument(format!(
                    "visibility estimate: isosurface {} of opacity {}: give a finite value and an opacity in [0, 1]",
                    o.isovalue, o.opacity
                )));
            }
        }
        let layout = octree.layout();
        if grid.dims() != layout.dims {
            return Err(Error::InvalidArgument(format!(
                "visibility estimate: grid of {:?} samples for an octree of {:?}: give the grid the octree was built on",
                grid.dims(),
                layout.dims
            )));
        }
        let coarse = layout.leaf_level().min(MAX_COARSE_LOG2);
        let dims = layout.level_dims(coarse);
        let count = dims[0] * dims[1] * dims[2];
        let per_node: Vec<(f64, u8)> = (0..count)
            .into_par_iter()
            .map(|i| {
                let c = coords(i, dims);
                let n = octree.node(layout.id(coarse, c));
                let (alpha, nan) = mean_opacity(grid, n.lo, n.hi, opacity);
                let side = match occluder {
                    Some(o) if !nan && n.min > o.isovalue => 1,
                    Some(o) if !nan && n.max < o.isovalue => 2,
                    _ => 0,
                };
                (-(1.0 - alpha.clamp(0.0, 1.0 - 1e-12)).ln() / d0, side)
            })
            .collect();
        let mut m = Medium {
            coarse,
            dims,
            tau: per_node.iter().map(|p| p.0).collect(),
            side: per_node.iter().map(|p| p.1).collect(),
            node_size: layout.node_size(coarse) as f64,
            surface_opacity: occluder.map_or(0.0, |o| o.opacity),
        };
        for axis in 0..3 {
            erode_sides(&mut m, axis);
        }
        Ok(m)
    }

    fn at(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }
}

/// The coordinates of node `i` of a level with `d` nodes per axis, x fastest.
fn coords(i: usize, d: [usize; 3]) -> [usize; 3] {
    [i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1])]
}

/// The mean opacity of the samples of the box `[lo, hi]`, every `q`-th per
/// axis (`q = max(1, size / 4)`), NaN counted as transparent; and whether
/// a NaN was met.
fn mean_opacity(grid: &Grid<'_>, lo: [usize; 3], hi: [usize; 3], opacity: &dyn Fn(f64) -> f64) -> (f64, bool) {
    let q = ((hi[0] - lo[0]).max(hi[1] - lo[1]).max(hi[2] - lo[2]) / 4).max(1);
    let (mut sum, mut count, mut nan) = (0.0f64, 0usize, false);
    for k in (lo[2]..=hi[2]).step_by(q) {
        for j in (lo[1]..=hi[1]).step_by(q) {
            for i in (lo[0]..=hi[0]).step_by(q) {
                let v = grid.value(i, j, k);
                if v.is_nan() {
                    nan = true;
                } else {
                    sum += opacity(v);
                }
                count += 1;
            }
        }
    }
    (if count > 0 { sum / count as f64 } else { 0.0 }, nan)
}

impl Transmittance {
    /// The transmittance of every node seen by `camera` through `medium`
    /// (of the octree of a grid of `shape`).
    pub fn estimate(medium: &Medium, shape: &GridShape, camera: &Camera) -> Transmittance {
        let dims = medium.dims;
        let mut t = vec![1.0f32; dims[0] * dims[1] * dims[2]];
        t.par_chunks_mut(dims[0]).enumerate().for_each(|(row, out)| {
            let (y, z) = (row % dims[1], row / dims[1]);
            for (x, v) in out.iter_mut().enumerate() {
                *v = march(medium, shape, camera, [x, y, z]) as f32;
            }
        });
        let mut pyramid = vec![t];
        let mut level_dims = vec![dims];
        for _ in 0..medium.coarse {
            let (fine, fd) = (&pyramid[0], level_dims[0]);
            let d = fd.map(|n| n.div_ceil(2));
            let mut up = vec![0.0f32; d[0] * d[1] * d[2]];
            for (i, v) in up.iter_mut().enumerate() {
                let c = coords(i, d);
                for child in 0..8 {
                    let f = [0, 1, 2].map(|a| 2 * c[a] + (child >> a & 1));
                    if f.iter().zip(&fd).all(|(x, n)| x < n) {
                        *v = v.max(fine[f[0] + fd[0] * (f[1] + fd[1] * f[2])]);
                    }
                }
            }
            pyramid.insert(0, up);
            level_dims.insert(0, d);
        }
        Transmittance { coarse: medium.coarse, pyramid, dims: level_dims }
    }

    /// `T` of the node at `level` with `coords` (module documentation).
    pub fn at(&self, level: usize, coords: [usize; 3]) -> f64 {
        let (k, c) = if level <= self.coarse {
            (level, coords)
        } else {
            let shift = level - self.coarse;
            (self.coarse, coords.map(|v| v >> shift))
        };
        let d = self.dims[k];
        let c = [0, 1, 2].map(|a| c[a].min(d[a] - 1));
        self.pyramid[k][c[0] + d[0] * (c[1] + d[1] * c[2])] as f64
    }
}

/// One axis of the 3x3x3 erosion of the sides: the AND over each node and
/// its two neighbours along `axis`.
fn erode_sides(m: &mut Medium, axis: usize) {
    let side = m.side.clone();
    let d = m.dims;
    for i in 0..side.len() {
        let c = coords(i, d);
        for step in [-1isize, 1] {
            let v = c[axis] as isize + step;
            if v < 0 || v >= d[axis] as isize {
                continue;
            }
            let mut n = c;
            n[axis] = v as usize;
            m.side[i] &= side[m.at(n)];
        }
    }
}

/// `T` of the coarse node `c`: the march from its centre to the eye.
fn march(m: &Medium, shape: &GridShape, camera: &Camera, c: [usize; 3]) -> f64 {
    let s = m.node_size;
    // Index-space centre, clamped to the grid (the last nodes are clipped).
    let centre = [0, 1, 2].map(|a| ((c[a] as f64 + 0.5) * s).min((shape.dims[a] - 1) as f64));
    let start = shape.world(centre);
    let to_eye = match camera.projection {
        Projection::Perspective { .. } => sub(camera.position, start),
        Projection::Parallel { .. } => camera.basis().2.map(|v| -v),
    };
    let length = norm(to_eye);
    if length.is_nan() || length <= 0.0 {
        return 1.0;
    }
    let dir = to_eye.map(|v| v / length);
    let eye = match camera.projection {
        Projection::Perspective { .. } => length,
        Projection::Parallel { .. } => f64::INFINITY,
    };
    // In index units per world unit along the ray, per axis.
    let per_axis = [0, 1, 2].map(|a| dir[a] / shape.spacing[a]);
    let cell = [0, 1, 2].map(|a| s * shape.spacing[a]);
    let h = 0.5 * cell.iter().copied().fold(f64::INFINITY, f64::min);
    let mut t = 0.5 * norm(cell);
    let (mut depth, mut sides) = (0.0f64, 0u8);
    while t < eye {
        let idx = [0, 1, 2].map(|a| centre[a] + per_axis[a] * t);
        if (0..3).any(|a| idx[a] < 0.0 || idx[a] > (shape.dims[a] - 1) as f64) {
            break;
        }
        let node = [0, 1, 2].map(|a| ((idx[a] / s) as usize).min(m.dims[a] - 1));
        let j = m.at(node);
        depth += m.tau[j] * h;
        sides |= m.side[j];
        if depth > OPAQUE_DEPTH {
            return 0.0;
        }
        t += h;
    }
    let crossed = if sides == 3 { 1.0 - m.surface_opacity } else { 1.0 };
    (-depth).exp() * crossed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::Samples;
    use crate::octree::BuildOptions;

    /// A 65^3 grid: value 1 in the slab `y < 16` (a wall in front of a
    /// camera at -y), 0 elsewhere; NaN in the column `x, z < 4` if asked.
    fn wall(holes: bool) -> (Vec<f32>, GridShape) {
        let n = 65;
        let mut v = vec![0.0f32; n * n * n];
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    v[x + n * (y + n * z)] = if holes && x < 4 && z < 4 {
                        f32::NAN
                    } else if y < 16 {
                        1.0
                    } else {
                        0.0
                    };
                }
            }
        }
        (v, GridShape { dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3] })
    }

    fn front_camera(parallel: bool) -> Camera {
        Camera::around([0.0; 3], [64.0; 3], 0.0, 0.0, parallel).unwrap()
    }

    /// The transmittance of coarse node `c` seen by `camera` through the
    /// wall under `opacity`, with `occluder`; and the coarse level.
    fn estimate(
        holes: bool,
        camera: &Camera,
        opacity: &(dyn Fn(f64) -> f64 + Sync),
        occluder: Option<Occluder>,
    ) -> (Transmittance, usize) {
        let (v, shape) = wall(holes);
        let grid = Grid::new(Samples::F32(&v), shape, 1, None).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let m = Medium::new(&o, &grid, opacity, 1.0, occluder).unwrap();
        (Transmittance::estimate(&m, &shape, camera), m.coarse)
    }

    /// A wall in front hides what is behind it and nothing in front of
    /// it, in parallel and perspective; the estimate is within a factor of
    /// the exact transmittance through the wall (its nodes' mean opacity
    /// over the 16 units), and without the wall everything is visible.
    #[test]
    fn a_wall_hides_what_is_behind_it() {
        for parallel in [true, false] {
            let camera = front_camera(parallel);
            // Opacity 0.5 per unit for value 1, 0 for value 0.
            let (t, coarse) = estimate(false, &camera, &|v| 0.5 * v, None);
            let at_y = |y: usize| t.at(coarse, [8, y / 4, 8]);
            assert_eq!(at_y(0), 1.0);
            let exact = 0.5f64.powi(16);
            assert!(at_y(60) > exact / 4.0 && at_y(60) < exact * 4.0, "{} vs {exact}", at_y(60));
            // The root holds the largest.
            assert_eq!(t.at(0, [0; 3]), 1.0);
            let (none, _) = estimate(false, &camera, &|_| 0.0, None);
            assert!((0..16).all(|y| none.at(coarse, [8, y, 8]) == 1.0));
        }
    }

    /// An opaque isosurface between the camera and the rest hides the rest
    /// even when the volume itself is transparent; a translucent one lets
    /// its share through; the side of the camera stays visible; and a
    /// column of NaN breaks the surface where it runs.
    #[test]
    fn an_isosurface_hides_what_is_behind_it() {
        let camera = front_camera(false);
        let clear = |_: f64| 0.0;
        for opacity in [1.0, 0.4] {
            let iso = Some(Occluder { isovalue: 0.5, opacity });
            let (t, coarse) = estimate(false, &camera, &clear, iso);
            assert_eq!(t.at(coarse, [8, 0, 8]), 1.0);
            assert!((t.at(coarse, [8, 14, 8]) - (1.0 - opacity)).abs() < 1e-6, "{}", t.at(coarse, [8, 14, 8]));
        }
        // Seen from behind (+y), the wall's far side is hidden and the rest not.
        let back = Camera::around([0.0; 3], [64.0; 3], 180.0, 0.0, false).unwrap();
        let iso = Some(Occluder { isovalue: 0.5, opacity: 1.0 });
        let (t, coarse) = estimate(false, &back, &clear, iso);
        assert_eq!(t.at(coarse, [8, 14, 8]), 1.0);
        assert_eq!(t.at(coarse, [8, 0, 8]), 0.0);
        // Holes at x, z < 4: the nodes there and their neighbours take no side.
        let parallel = front_camera(true);
        let (t, coarse) = estimate(true, &parallel, &clear, iso);
        assert_eq!(t.at(coarse, [0, 14, 0]), 1.0);
        assert_eq!(t.at(coarse, [8, 14, 8]), 0.0);
    }

    /// Detail behind the wall counts in the estimated RMS error as much as
    /// the wall lets through: a coarse selection's estimate behind an
    /// opaque wall is below its estimate with nothing in front, and the
    /// selection in view reports the estimate behind its transmittance.
    #[test]
    fn the_rms_estimate_sees_what_the_wall_lets_through() {
        use crate::plan::select::{seen_rms_error, select, select_in_view, Seen, SelectOptions, ViewImportance};
        let (mut v, shape) = wall(false);
        let n = 65;
        for z in 0..n {
            for y in 16..n {
                for x in 0..n {
                    v[x + n * (y + n * z)] = 0.3 * (0.5 + 0.5 * ((x as f32) * 0.9).sin() * ((z as f32) * 0.7).cos());
                }
            }
        }
        let grid = Grid::new(Samples::F32(&v), shape, 1, None).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let opacity = |v: f64| if v > 0.5 { 1.0 } else { 0.05 * v };
        let m = Medium::new(&o, &grid, &opacity, 1.0, None).unwrap();
        let t = Transmittance::estimate(&m, &shape, &front_camera(true));
        let options = SelectOptions::new(40_000, 0.0);
        let s = select(&o, &options, |_, _| true).unwrap();
        let behind = |b: &crate::plan::select::Brick| {
            let n = o.node(b.node);
            t.at(n.level, n.coords)
        };
        let seen = seen_rms_error(&o, s.bricks.iter().map(|b| Seen::at_stride(b, behind(b))), |_, _| true);
        assert!(s.estimated_rms_error > 0.0);
        assert!(seen < 0.5 * s.estimated_rms_error, "behind the wall {seen} vs in the open {}", s.estimated_rms_error);
        let view = ViewImportance { screen: None, visibility: Some(t.clone()) };
        let in_view = select_in_view(&o, &options, |_, _| true, None, &view).unwrap();
        let expected = seen_rms_error(&o, in_view.bricks.iter().map(|b| Seen::at_stride(b, behind(b))), |_, _| true);
        assert_eq!(in_view.estimated_rms_error, expected);
    }

    #[test]
    fn bad_arguments_are_errors() {
        let (v, shape) = wall(false);
        let grid = Grid::new(Samples::F32(&v), shape, 1, None).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let f = |_: f64| 0.0;
        assert!(Medium::new(&o, &grid, &f, 0.0, None).is_err());
        assert!(Medium::new(&o, &grid, &f, f64::NAN, None).is_err());
        let bad = Some(Occluder { isovalue: f64::NAN, opacity: 1.0 });
        assert!(Medium::new(&o, &grid, &f, 1.0, bad).is_err());
        let bad = Some(Occluder { isovalue: 0.5, opacity: 2.0 });
        assert!(Medium::new(&o, &grid, &f, 1.0, bad).is_err());
        let small = vec![0.0f32; 27];
        let other = Grid::new(Samples::F32(&small), GridShape { dims: [3; 3], ..shape }, 1, None).unwrap();
        assert!(Medium::new(&o, &other, &f, 1.0, None).unwrap_err().to_string().contains("octree"));
    }
}
