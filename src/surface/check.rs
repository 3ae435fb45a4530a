//! Measuring a surface: how its edges are shared (watertightness), its area
//! and the volume it encloses.
//!
//! On a closed surface every edge is used by exactly two polygons, once in
//! each direction. An edge used once lies where the surface leaves the volume
//! (a boundary edge); more than twice, or twice in the same direction, is a
//! defect. NaN is no data (see [`crate::data::grid`]): cells with a NaN corner have
//! no facets, so the surface is also open along them. A surface is watertight
//! when its only edges used once are [`boundary_edges`] plus
//! [`nan_boundary_edges`].

use super::extract::midpoint2;
use super::mesh::Surface;
use super::polygon::fan_cross;
pub use super::polygon::polygon_normal;
use crate::data::grid::Grid;
use crate::geometry::vec3::cross;

/// How the edges of a surface are used.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EdgeUse {
    /// Undirected edges.
    pub edges: usize,
    /// Used by one polygon.
    pub boundary: usize,
    /// Used by more than two polygons, or twice in the same direction.
    pub nonmanifold: usize,
}

/// Counts the edges of `s` by use.
pub fn edge_use(s: &Surface) -> EdgeUse {
    // (min, max, +1 for min->max / -1 for max->min)
    let mut edges: Vec<(u32, u32, i8)> = Vec::with_capacity(s.connectivity.len());
    for i in 0..s.polygon_count() {
        let p = s.polygon(i);
        for k in 0..p.len() {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            edges.push(if a < b { (a, b, 1) } else { (b, a, -1) });
        }
    }
    edges.sort_unstable();
    let mut out = EdgeUse::default();
    let mut i = 0;
    while i < edges.len() {
        let mut j = i;
        while j < edges.len() && (edges[j].0, edges[j].1) == (edges[i].0, edges[i].1) {
            j += 1;
        }
        out.edges += 1;
        match j - i {
            1 => out.boundary += 1,
            2 if edges[i].2 != edges[i + 1].2 => {}
            _ => out.nonmanifold += 1,
        }
        i = j;
    }
    out
}

/// Polygon edges lying on a face of the volume (`x = 0`, `x = nx - 1`, ...):
/// no cell lies beyond such a face, so exactly one polygon uses the edge.
/// Tested on the vertices' edge midpoints (exact, and the same in both modes:
/// an interpolated vertex may sit on a sample, but its grid edge does not
/// move). A surface segment joins two different edges of one cube face, and
/// two edges of a face share a volume face plane only when the cube face lies
/// in it. Counted in parallel; [`edge_use`] is the slower, independent check
/// the tests compare it with.
pub fn boundary_edges(s: &Surface, dims: [usize; 3]) -> usize {
    use rayon::prelude::*;
    // Bit 2a (2a + 1) set: the vertex's edge midpoint lies on the low (high) face of axis a.
    let faces: Vec<u8> = s
        .keys
        .par_iter()
        .map(|&k| {
            let m = midpoint2(k, dims);
            (0..3).fold(0u8, |bits, a| {
                let top = 2 * (dims[a] as i64 - 1);
                bits | (u8::from(m[a] == 0) << (2 * a)) | (u8::from(m[a] == top) << (2 * a + 1))
            })
        })
        .collect();
    (0..s.polygon_count())
        .into_par_iter()
        .map(|i| {
            let p = s.polygon(i);
            (0..p.len()).filter(|&k| faces[p[k] as usize] & faces[p[(k + 1) % p.len()] as usize] != 0).count()
        })
        .sum()
}

/// Polygon edges along the no-data region: edges lying in a face of the grid
/// whose cell on the other side has a NaN corner (the polygon's own cell has
/// none, so the edge has no twin there). An edge lies in the grid plane
/// `x_a = c` when both its vertices' edge midpoints do (`m[a] = 2c` in
/// doubled coordinates; interior segments of a cell never do); the face is
/// the square of that plane holding the edge's midpoint `(m1 + m2) / 2`.
/// Faces on the volume's boundary have no cell across (see [`boundary_edges`]).
pub fn nan_boundary_edges(s: &Surface, grid: &Grid<'_>) -> usize {
    let dims = grid.dims();
    nan_boundary_edges_with(s, dims, |p| grid.value(p[0], p[1], p[2]).is_nan())
}

/// [`nan_boundary_edges`] with the NaN test of one sample given.
pub(crate) fn nan_boundary_edges_with(
    s: &Surface,
    dims: [usize; 3],
    is_nan: impl Fn([usize; 3]) -> bool + Sync,
) -> usize {
    use rayon::prelude::*;
    let cell_touches_nan = |c: [usize; 3]| (0..8).any(|k| is_nan([0, 1, 2].map(|a| c[a] + ((k >> a) & 1))));
    let along_nan = |m1: [i64; 3], m2: [i64; 3]| {
        let Some(a) = (0..3).find(|&a| m1[a] == m2[a] && m1[a] % 2 == 0) else {
            return false;
        };
        let plane = m1[a] / 2;
        // The other axes: the cell row holding the midpoint, floor((m1 + m2) / 4).
        let mut cell = [0i64; 3];
        for b in (0..3).filter(|&b| b != a) {
            cell[b] = ((m1[b] + m2[b]) / 4).min(dims[b] as i64 - 2);
        }
        [plane - 1, plane].into_iter().filter(|&c| c >= 0 && c <= dims[a] as i64 - 2).any(|c| {
            cell[a] = c;
            cell_touches_nan(cell.map(|v| v as usize))
        })
    };
    (0..s.polygon_count())
        .into_par_iter()
        .map(|i| {
            let p = s.polygon(i);
            (0..p.len())
                .filter(|&k| {
                    let (u, v) = (p[k] as usize, p[(k + 1) % p.len()] as usize);
                    along_nan(midpoint2(s.keys[u], dims), midpoint2(s.keys[v], dims))
                })
                .count()
        })
        .sum()
}

/// Sum of `f(p0, pk, pk+1)` over the fan triangles of every polygon.
fn fan_sum(s: &Surface, f: impl Fn([f64; 3], [f64; 3], [f64; 3]) -> f64) -> f64 {
    (0..s.polygon_count())
        .map(|i| {
            let p = s.polygon(i);
            let o = s.points[p[0] as usize];
            (1..p.len() - 1).map(|k| f(o, s.points[p[k] as usize], s.points[p[k + 1] as usize])).sum::<f64>()
        })
        .sum()
}

/// Surface area in index units (fan triangulation from the first vertex;
/// the polygons this crate makes are triangles).
pub fn area(s: &Surface) -> f64 {
    fan_sum(s, |o, a, b| {
        let c = fan_cross(o, a, b);
        0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    })
}

/// Signed volume enclosed, in cubic index units (divergence theorem:
/// `sum of p0 . (p1 x p2) / 6` over fan triangles). Normals point from the
/// inside (values at or above the isovalue) out, so a closed surface around an
/// inside region encloses a positive volume.
pub fn volume(s: &Surface) -> f64 {
    fan_sum(s, |o, a, b| {
        let c = cross(a, b);
        (o[0] * c[0] + o[1] * c[1] + o[2] * c[2]) / 6.0
    })
}
