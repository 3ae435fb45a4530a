//! Placing a vertex: its point and its normal, from the grid edge it lies on.
//!
//! Points are in index space (`world = origin + spacing * point`):
//!
//! ```text
//! Discretized:   p = midpoint of the edge = a + (b - a) / 2
//! Interpolated:  p = a + (b - a) * (iso - f(a)) / (f(b) - f(a))
//! ```
//!
//! Normals are unit vectors in world space pointing from the inside (values
//! at or above the isovalue) out: `-grad f / |grad f|`, with `grad f` the
//! central-difference gradient (one-sided on the volume's faces) interpolated
//! along the edge like the point; where the gradient vanishes, the area-weighted
//! normal of the polygons around the point ([`finish_normals`]).

use super::extract::edge_of_key;
use super::mesh::{Surface, SurfaceMode};
use crate::data::grid::{Sample, TypedGrid};
use rayon::prelude::*;

/// Places vertices of one grid at one isovalue.
pub struct Placer<'a, 'g, T: Sample> {
    /// The grid.
    pub grid: &'a TypedGrid<'g, T>,
    /// The isovalue.
    pub isovalue: f64,
    /// Midpoints or interpolated points.
    pub mode: SurfaceMode,
}

impl<T: Sample> Placer<'_, '_, T> {
    /// The point and the raw index-space normal `-grad f` (not normalised) of
    /// the vertex on the edge from `a` along `axis`.
    pub fn place(&self, a: [usize; 3], axis: usize) -> ([f64; 3], [f64; 3]) {
        let mut point = a.map(|v| v as f64);
        let t = match self.mode {
            SurfaceMode::Discretized => 0.5,
            SurfaceMode::Interpolated => crossing(self.grid, a, axis, self.isovalue),
        };
        point[axis] += t;
        let mut b = a;
        b[axis] += 1;
        let (ga, gb) = (gradient(self.grid, a), gradient(self.grid, b));
        (point, [0, 1, 2].map(|k| -(ga[k] + (gb[k] - ga[k]) * t)))
    }
    /// [`Self::place`] of the vertex on edge `key`.
    pub fn place_key(&self, key: u64) -> ([f64; 3], [f64; 3]) {
        let (a, axis) = edge_of_key(key, self.grid.dims);
        self.place(a, axis)
    }
}

/// Where along the edge from `a` along `axis` the isovalue is crossed:
/// `t = (iso - f(a)) / (f(b) - f(a))`. One end is >= iso and the other < iso,
/// so `f(b) != f(a)`.
fn crossing<T: Sample>(g: &TypedGrid<'_, T>, a: [usize; 3], axis: usize, iso: f64) -> f64 {
    let mut b = a;
    b[axis] += 1;
    let (fa, fb) = (g.at(a[0], a[1], a[2]), g.at(b[0], b[1], b[2]));
    (iso - fa) / (fb - fa)
}

/// The interpolated crossing on edge `key`: `a + (b - a) * (iso - f(a)) / (f(b) - f(a))`.
pub fn interpolated_point<T: Sample>(g: &TypedGrid<'_, T>, key: u64, iso: f64) -> [f64; 3] {
    let (a, axis) = edge_of_key(key, g.dims);
    let mut p = a.map(|v| v as f64);
    p[axis] += crossing(g, a, axis, iso);
    p
}

/// Central-difference gradient at point `p` (one-sided on the faces and
/// beside a NaN neighbour, 0 with NaN on both sides), index units. `p`
/// itself is finite: it is a corner of a cell that touches no NaN.
fn gradient<T: Sample>(g: &TypedGrid<'_, T>, p: [usize; 3]) -> [f64; 3] {
    let at = |q: [usize; 3]| g.at(q[0], q[1], q[2]);
    let mut out = [0.0; 3];
    for (a, o) in out.iter_mut().enumerate() {
        let (mut lo, mut hi) = (p, p);
        lo[a] = p[a].saturating_sub(1);
        hi[a] = (p[a] + 1).min(g.dims[a] - 1);
        if at(lo).is_nan() {
            lo = p;
        }
        if at(hi).is_nan() {
            hi = p;
        }
        let span = (hi[a] - lo[a]) as f64;
        *o = if span > 0.0 { (at(hi) - at(lo)) / span } else { 0.0 };
    }
    out
}

/// World-space unit normals from the raw index-space normals `raw` of the
/// points of `s`: where a gradient vanishes, the area-weighted normal of the
/// polygons around the point instead; then the inverse-transpose of
/// `diag(spacing)` (a division by the spacing) and normalisation.
pub fn finish_normals(s: &Surface, mut raw: Vec<[f64; 3]>, spacing: [f64; 3]) -> Vec<[f32; 3]> {
    let flat: Vec<usize> = (0..raw.len()).filter(|&i| raw[i].iter().all(|&v| v == 0.0)).collect();
    if !flat.is_empty() {
        let mut acc = vec![[0.0f64; 3]; raw.len()];
        for i in 0..s.polygon_count() {
            let poly = s.polygon(i);
            let n = super::polygon::polygon_normal(s, poly);
            for &v in poly {
                for k in 0..3 {
                    acc[v as usize][k] += n[k];
                }
            }
        }
        for i in flat {
            raw[i] = acc[i];
        }
    }
    raw.par_iter()
        .map(|n| {
            let n = [n[0] / spacing[0], n[1] / spacing[1], n[2] / spacing[2]];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if len > 0.0 {
                [(n[0] / len) as f32, (n[1] / len) as f32, (n[2] / len) as f32]
            } else {
                [0.0, 0.0, 1.0]
            }
        })
        .collect()
}
