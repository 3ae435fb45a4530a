//! Visibility importance: an upper bound of the transmittance in front of
//! each node, estimated front to back before the selection.
//!
//! The estimate works on the nodes of one coarse level `c` of the Volume
//! Octree (at most 32 per axis, never finer than the leaf bricks), from
//! their value ranges alone:
//!
//! ```text
//! alpha_min(n) = min over [min(n), max(n)] of the opacity transfer function   (a layer d0 thick)
//! tau(n)       = -ln(1 - alpha_min(n)) / d0                                   (optical depth per world unit)
//! tau'(n)      = min of tau over n and its 26 neighbours                      (erosion)
//! T(n)         = exp(-sum_i tau'(n_i) h) * (1 - a_s)^[the ray crosses the isosurface]
//! ```
//!
//! The sum runs over samples `h` apart on the ray from the centre of `n`
//! to the eye (along `-forward` under a parallel projection), from where
//! the ray leaves `n` to where it leaves the grid. Every sample of a node is
//! at least `alpha_min` opaque, so `tau` never overstates the absorption;
//! the erosion makes the centre's ray stand for every ray from the node,
//! which passes within one node of it. The ray crosses an isosurface of
//! opacity `a_s` when it meets one eroded node entirely above the isovalue
//! and one entirely below it: the field between them takes the isovalue.
//!
//! Volumes with NaN holes get `T = 1` everywhere: a hole is transparent and
//! breaks a surface, and the octree does not say where its holes are.
//!
//! A node of level `k <= c` takes the largest `T` of the coarse nodes it
//! holds (a max pyramid); a finer node takes its coarse node's.

use crate::base::error::{Error, Result};
use crate::data::grid::GridShape;
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

/// The per-node transmittance bound of one view (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmittance {
    /// The coarse level `c`.
    coarse: usize,
    /// `pyramid[k]`: the largest `T` over each node of level `k <= c`, x fastest.
    pyramid: Vec<Vec<f32>>,
    /// Nodes per axis at each level `k <= c`.
    dims: Vec<[usize; 3]>,
}

/// The eroded coarse nodes the rays march through.
struct Medium {
    dims: [usize; 3],
    /// `tau'` per node, per world unit.
    tau: Vec<f64>,
    /// Entirely above (bit 0) or below (bit 1) the isovalue, eroded.
    side: Vec<u8>,
    /// Index units per coarse node.
    node_size: f64,
}

impl Medium {
    fn at(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }
}

impl Transmittance {
    /// The bound for `camera` over `octree` (of a grid of `shape`).
    /// `min_opacity(min, max)` is the smallest opacity of a layer `d0`
    /// world units thick over the values `[min, max]`; `occluder` an
    /// isosurface drawn with the volume; `has_nan` that the grid has holes.
    pub fn estimate(
        octree: &VolumeOctree,
        shape: &GridShape,
        camera: &Camera,
        min_opacity: &(dyn Fn(f64, f64) -> f64 + Sync),
        d0: f64,
        occluder: Option<Occluder>,
        has_nan: bool,
    ) -> Result<Transmittance> {
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
        let coarse = layout.leaf_level().min(MAX_COARSE_LOG2);
        let dims = layout.level_dims(coarse);
        let medium = medium(octree, coarse, min_opacity, d0, if has_nan { None } else { occluder });
        let count = dims[0] * dims[1] * dims[2];
        let opaque_surface = occluder.map_or(0.0, |o| o.opacity);
        let mut t = vec![1.0f32; count];
        if !has_nan {
            t.par_chunks_mut(dims[0]).enumerate().for_each(|(row, out)| {
                let (y, z) = (row % dims[1], row / dims[1]);
                for (x, v) in out.iter_mut().enumerate() {
                    *v = march(&medium, shape, camera, [x, y, z], opaque_surface) as f32;
                }
            });
        }
        let mut pyramid = vec![t];
        let mut level_dims = vec![dims];
        for k in (0..coarse).rev() {
            let (fine, fd) = (&pyramid[0], level_dims[0]);
            let d = layout.level_dims(k);
            let mut up = vec![0.0f32; d[0] * d[1] * d[2]];
            for (i, v) in up.iter_mut().enumerate() {
                let c = [i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1])];
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
        Ok(Transmittance { coarse, pyramid, dims: level_dims })
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

/// `tau'` and the eroded sides of the coarse nodes.
fn medium(
    octree: &VolumeOctree,
    coarse: usize,
    min_opacity: &dyn Fn(f64, f64) -> f64,
    d0: f64,
    occluder: Option<Occluder>,
) -> Medium {
    let layout = octree.layout();
    let dims = layout.level_dims(coarse);
    let count = dims[0] * dims[1] * dims[2];
    let mut tau = Vec::with_capacity(count);
    let mut side = Vec::with_capacity(count);
    for i in 0..count {
        let c = [i % dims[0], (i / dims[0]) % dims[1], i / (dims[0] * dims[1])];
        let n = octree.node(layout.id(coarse, c));
        // A node of NaN only has the empty range (+inf, -inf): no data, transparent.
        let empty = !(n.min <= n.max);
        let alpha = if empty { 0.0 } else { min_opacity(n.min, n.max).clamp(0.0, 1.0) };
        tau.push(-(1.0 - alpha.min(1.0 - 1e-12)).ln() / d0);
        side.push(match occluder {
            Some(o) if !empty && n.min > o.isovalue => 1,
            Some(o) if !empty && n.max < o.isovalue => 2,
            _ => 0,
        });
    }
    let mut m = Medium { dims, tau, side, node_size: layout.node_size(coarse) as f64 };
    for axis in 0..3 {
        erode(&mut m, axis);
    }
    m
}

/// One axis of the 3x3x3 erosion: the min of `tau` and the AND of the
/// sides over each node and its two neighbours along `axis`.
fn erode(m: &mut Medium, axis: usize) {
    let (tau, side) = (m.tau.clone(), m.side.clone());
    let d = m.dims;
    for i in 0..tau.len() {
        let c = [i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1])];
        for step in [-1isize, 1] {
            let v = c[axis] as isize + step;
            if v < 0 || v >= d[axis] as isize {
                continue;
            }
            let mut n = c;
            n[axis] = v as usize;
            let j = m.at(n);
            m.tau[i] = m.tau[i].min(tau[j]);
            m.side[i] &= side[j];
        }
    }
}

/// `T` of the coarse node `c`: the march from its centre to the eye.
fn march(m: &Medium, shape: &GridShape, camera: &Camera, c: [usize; 3], surface_opacity: f64) -> f64 {
    let s = m.node_size;
    // Index-space centre, clamped to the grid (the last nodes are clipped).
    let centre = [0, 1, 2].map(|a| ((c[a] as f64 + 0.5) * s).min((shape.dims[a] - 1) as f64));
    let start = shape.world(centre);
    let to_eye = match camera.projection {
        Projection::Perspective { .. } => sub(camera.position, start),
        Projection::Parallel { .. } => camera.basis().2.map(|v| -v),
    };
    let length = norm(to_eye);
    if !(length > 0.0) {
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
    let crossed = if sides == 3 { 1.0 - surface_opacity } else { 1.0 };
    (-depth).exp() * crossed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::{Grid, Samples};
    use crate::octree::BuildOptions;

    /// A 65^3 grid: value 1 in the slab `y < 16` (a wall in front of a
    /// camera at -y), 0 elsewhere.
    fn wall() -> (Vec<f32>, GridShape) {
        let n = 65;
        let mut v = vec![0.0f32; n * n * n];
        for z in 0..n {
            for y in 0..16 {
                for x in 0..n {
                    v[x + n * (y + n * z)] = 1.0;
                }
            }
        }
        (v, GridShape { dims: [n; 3], spacing: [1.0; 3], origin: [0.0; 3] })
    }

    fn octree(v: &[f32], shape: &GridShape) -> VolumeOctree {
        let grid = Grid::new(Samples::F32(v), *shape, 1, None).unwrap();
        VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap()
    }

    fn front_camera(parallel: bool) -> Camera {
        Camera::around([0.0; 3], [64.0; 3], 0.0, 0.0, parallel).unwrap()
    }

    /// An opaque wall in front hides what is behind it and nothing in
    /// front; the estimate never goes below the exact transmittance
    /// through the wall, and without the wall everything is visible.
    #[test]
    fn a_wall_hides_what_is_behind_it() {
        let (v, shape) = wall();
        let o = octree(&v, &shape);
        let coarse = o.layout().leaf_level().min(MAX_COARSE_LOG2);
        for parallel in [true, false] {
            let camera = front_camera(parallel);
            // Opacity 0.5 per unit for value 1, 0 for value 0.
            let floor = |min: f64, _max: f64| 0.5 * min;
            let t = Transmittance::estimate(&o, &shape, &camera, &floor, 1.0, None, false).unwrap();
            let at_y = |y: usize| t.at(coarse, [8, y / 4, 8]);
            // In front of the wall, and in its first nodes, nothing hides.
            assert_eq!(at_y(0), 1.0);
            // Far behind: the whole wall (16 units at tau = ln 2) in front, at most.
            let exact = 0.5f64.powi(16);
            // The erosion keeps the wall's inner 8 units: 2^-8 at most.
            assert!(at_y(60) >= exact && at_y(60) <= 0.5f64.powi(8) * 1.01, "{} vs {exact}", at_y(60));
            // Without the wall's opacity, everything shows.
            let none = Transmittance::estimate(&o, &shape, &camera, &|_, _| 0.0, 1.0, None, false).unwrap();
            assert!((0..16).all(|y| none.at(coarse, [8, y, 8]) == 1.0));
            // Holes: no estimate.
            let holes = Transmittance::estimate(&o, &shape, &camera, &floor, 1.0, None, true).unwrap();
            assert_eq!(holes.at(coarse, [8, 15, 8]), 1.0);
            // The root holds the largest.
            assert_eq!(t.at(0, [0; 3]), 1.0);
        }
    }

    /// An opaque isosurface between the wall and the rest hides the rest
    /// even when the volume itself is transparent; a translucent one lets
    /// its share through, and the side of the camera stays visible.
    #[test]
    fn an_isosurface_hides_what_is_behind_it() {
        let (v, shape) = wall();
        let o = octree(&v, &shape);
        let coarse = o.layout().leaf_level().min(MAX_COARSE_LOG2);
        let camera = front_camera(false);
        let clear = |_: f64, _: f64| 0.0;
        for opacity in [1.0, 0.4] {
            let iso = Some(Occluder { isovalue: 0.5, opacity });
            let t = Transmittance::estimate(&o, &shape, &camera, &clear, 1.0, iso, false).unwrap();
            assert_eq!(t.at(coarse, [8, 0, 8]), 1.0);
            assert!((t.at(coarse, [8, 14, 8]) - (1.0 - opacity)).abs() < 1e-6, "{}", t.at(coarse, [8, 14, 8]));
        }
        // Seen from behind (+y), the wall's far side is hidden and the rest not.
        let back = Camera::around([0.0; 3], [64.0; 3], 180.0, 0.0, false).unwrap();
        let iso = Some(Occluder { isovalue: 0.5, opacity: 1.0 });
        let t = Transmittance::estimate(&o, &shape, &back, &clear, 1.0, iso, false).unwrap();
        assert_eq!(t.at(coarse, [8, 14, 8]), 1.0);
        assert_eq!(t.at(coarse, [8, 0, 8]), 0.0);
    }

    #[test]
    fn bad_arguments_are_errors() {
        let (v, shape) = wall();
        let o = octree(&v, &shape);
        let camera = front_camera(true);
        let f = |_: f64, _: f64| 0.0;
        assert!(Transmittance::estimate(&o, &shape, &camera, &f, 0.0, None, false).is_err());
        assert!(Transmittance::estimate(&o, &shape, &camera, &f, f64::NAN, None, false).is_err());
        let bad = Some(Occluder { isovalue: f64::NAN, opacity: 1.0 });
        assert!(Transmittance::estimate(&o, &shape, &camera, &f, 1.0, bad, false).is_err());
        let bad = Some(Occluder { isovalue: 0.5, opacity: 2.0 });
        assert!(Transmittance::estimate(&o, &shape, &camera, &f, 1.0, bad, false).is_err());
    }
}
