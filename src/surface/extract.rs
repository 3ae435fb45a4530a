//! Marching the cells of one terminal node: the DiscMC / MC triangles of the
//! node, with vertices named by the grid edge they lie on.
//!
//! A vertex is identified by its grid edge: `key = 3 * (x + nx * (y + ny * z)) + axis`
//! for the edge from point `(x, y, z)` along `axis`. Cubes sharing an edge
//! name its vertex the same way, so vertices are shared without a search, and
//! the same key gives the DiscMC midpoint or the interpolated point.
//!
//! Only nodes whose `[min, max]` brackets the isovalue (`min < iso <= max`:
//! some sample inside, some outside) have cells to visit.
//!
//! NaN is no data, outside the isosurface: a cell with a NaN corner gets no
//! facet, so the surface is open along the no-data region (see
//! [`super::check::nan_boundary_edges`]).

use super::table::{cases, edge_corners, ON_CELL_FACE};
use crate::data::grid::{Sample, TypedGrid};

/// The edge key of the edge from point `p` along `axis` in a grid of `dims`.
#[inline]
pub fn edge_key(p: [usize; 3], axis: usize, dims: [usize; 3]) -> u64 {
    3 * (p[0] + dims[0] * (p[1] + dims[1] * p[2])) as u64 + axis as u64
}

/// The low end point and the axis of edge `key`.
#[inline]
pub fn edge_of_key(key: u64, dims: [usize; 3]) -> ([usize; 3], usize) {
    let axis = (key % 3) as usize;
    let p = (key / 3) as usize;
    ([p % dims[0], (p / dims[0]) % dims[1], p / (dims[0] * dims[1])], axis)
}

/// The edge midpoint of `key` in doubled index coordinates (exact integers).
#[inline]
pub fn midpoint2(key: u64, dims: [usize; 3]) -> [i64; 3] {
    let (p, axis) = edge_of_key(key, dims);
    let mut m = [2 * p[0] as i64, 2 * p[1] as i64, 2 * p[2] as i64];
    m[axis] += 1;
    m
}

/// The vertices of one node, numbered locally in first-seen order.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct NodeVertices {
    /// Edge key of each vertex.
    pub keys: Vec<u64>,
    /// Its edge midpoint in doubled index coordinates ([`midpoint2`]).
    pub midpoints: Vec<[i64; 3]>,
    /// Whether its edge lies on a face of the node's box (other nodes may use it).
    pub on_boundary: Vec<bool>,
}

impl NodeVertices {
    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.keys.len()
    }
    /// True when there is none.
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }
    /// Adds the vertex on the edge from `p` along `axis` of the node `[lo, hi]`.
    pub fn push(&mut self, p: [usize; 3], axis: usize, lo: [usize; 3], hi: [usize; 3], dims: [usize; 3]) {
        let mut m = [2 * p[0] as i64, 2 * p[1] as i64, 2 * p[2] as i64];
        m[axis] += 1;
        self.keys.push(edge_key(p, axis, dims));
        self.midpoints.push(m);
        self.on_boundary.push((0..3).any(|b| b != axis && (p[b] == lo[b] || p[b] == hi[b])));
    }
}

/// Triangles of one node, counter-clockwise seen from outside (below the
/// isovalue).
#[derive(Debug, Default, Clone)]
pub struct NodeTriangles {
    /// The node's vertices.
    pub verts: NodeVertices,
    /// Local vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's plane: an index into [`super::table::plane_normals`].
    pub planes: Vec<u8>,
    /// Linear index `x + nx * (y + ny * z)` of the cell each triangle came
    /// from (only when [`Record::cells`]).
    pub cells: Vec<u64>,
    /// For half-edge `3 t + k` (corner `k` to corner `k + 1` of triangle
    /// `t`): the half-edge running the other way in the facet across, or
    /// [`NO_TWIN`] where the surface leaves the node or the volume (only when
    /// [`Record::across`]).
    pub across: Vec<u32>,
}

impl NodeTriangles {
    /// Triangle `i` as edge keys.
    pub fn keys_of(&self, i: usize) -> [u64; 3] {
        self.triangles[i].map(|v| self.verts.keys[v as usize])
    }
}

/// [`NodeTriangles::across`] of an edge with no facet across in the node.
pub const NO_TWIN: u32 = u32::MAX;

/// What [`march`] records besides the triangles.
#[derive(Debug, Clone, Copy, Default)]
pub struct Record {
    /// Each triangle's cell.
    pub cells: bool,
    /// Each half-edge's twin.
    pub across: bool,
}

/// Nodes with at most this many edges number their vertices through a dense
/// table (a reused buffer); larger homogeneous nodes use a hash map.
const DENSE_EDGES: usize = 3 * 33 * 33 * 33;

/// Reusable numbering buffer of [`march`] (one per worker).
#[derive(Debug, Default)]
pub struct EdgeIndex {
    dense: Vec<u32>,
    /// The slots of `dense` the current node set (freed when it is done).
    touched: Vec<u32>,
    /// Per local vertex, the half-edges leaving it along a cell face (at most
    /// one per cell around its grid edge, so four).
    face_out: Vec<[u32; 4]>,
}

/// Marches the cells `[lo, hi)` (point box `[lo, hi]`) at `isovalue`,
/// recording what `record` asks for.
///
/// Twins: an edge inside a cell (a fan diagonal) has its twin in the same
/// cell, from the case table; an edge on a cell face has it in the cell across
/// that face, found among the (at most four) face half-edges leaving its end
/// vertex.
pub fn march<T: Sample>(
    g: &TypedGrid<'_, T>,
    lo: [usize; 3],
    hi: [usize; 3],
    isovalue: f64,
    index: &mut EdgeIndex,
    record: Record,
) -> NodeTriangles {
    let table = cases();
    let dims = g.dims;
    let mut out = NodeTriangles::default();
    // Local edge slot of the edge from point p along axis: 3 * (local point) + axis.
    let w = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    let slots = 3 * w[0] * w[1] * w[2];
    let dense = slots <= DENSE_EDGES;
    if dense && index.dense.len() < slots {
        index.dense.resize(slots, u32::MAX); // all free between nodes: each node frees its own
    }
    let mut sparse: std::collections::HashMap<u64, u32> = std::collections::HashMap::new();
    // Inside flags (value >= isovalue) of two point slices, z and z + 1: each
    // sample is read and compared once, not once per cell that shares it.
    let plane = w[0] * w[1];
    // With them, per point: NaN (no data).
    let mut inside = vec![false; 2 * plane];
    let mut nan = vec![false; 2 * plane];
    let fill = |slice: &mut [bool], nan: &mut [bool], z: usize| {
        for y in 0..w[1] {
            for x in 0..w[0] {
                let v = g.at(lo[0] + x, lo[1] + y, z);
                slice[x + w[0] * y] = v >= isovalue;
                nan[x + w[0] * y] = v.is_nan();
            }
        }
    };
    fill(&mut inside[..plane], &mut nan[..plane], lo[2]);
    let mut ids = [0u32; 12];
    for z in lo[2]..hi[2] {
        let (below, above) = inside.split_at_mut(plane);
        let (nan_below, nan_above) = nan.split_at_mut(plane);
        if z > lo[2] {
            below.copy_from_slice(above);
            nan_below.copy_from_slice(nan_above);
        }
        fill(above, nan_above, z + 1);
        let (nan_below, nan_above) = (&*nan_below, &*nan_above);
        for y in lo[1]..hi[1] {
            // The four point rows around the cells of this row: (y, z), (y + 1, z), (y, z + 1), (y + 1, z + 1).
            let r = [
                &below[w[0] * (y - lo[1])..w[0] * (y - lo[1] + 1)],
                &below[w[0] * (y - lo[1] + 1)..w[0] * (y - lo[1] + 2)],
                &above[w[0] * (y - lo[1])..w[0] * (y - lo[1] + 1)],
                &above[w[0] * (y - lo[1] + 1)..w[0] * (y - lo[1] + 2)],
            ];
            // Corners c = dx + 2 dy + 4 dz: the even bits come from point x, the odd ones from x + 1.
            let corners_at = |i: usize| {
                usize::from(r[0][i]) | usize::from(r[1][i]) << 2 | usize::from(r[2][i]) << 4 | usize::from(r[3][i]) << 6
            };
            // A NaN among the four points at x (rows y and y + 1 of slices z and z + 1).
            let (r0, r1) = (w[0] * (y - lo[1]), w[0] * (y - lo[1] + 1));
            let nan_at = |i: usize| nan_below[r0 + i] || nan_below[r1 + i] || nan_above[r0 + i] || nan_above[r1 + i];
            let mut right = corners_at(0);
            let mut nan_right = nan_at(0);
            for x in lo[0]..hi[0] {
                let (left, nan_left) = (right, nan_right);
                right = corners_at(x - lo[0] + 1);
                nan_right = nan_at(x - lo[0] + 1);
                let case = left | right << 1;
                if case == 0 || case == 255 || nan_left || nan_right {
                    continue;
                }
                let entry = &table[case];
                // The node-local id of each crossed edge's vertex, created on first sight.
                for &e in &entry.edges {
                    let (a, _, axis) = edge_corners(e as usize);
                    let p = [x + (a & 1), y + ((a >> 1) & 1), z + ((a >> 2) & 1)];
                    let next = out.verts.len() as u32;
                    let id = if dense {
                        let slot = 3 * ((p[0] - lo[0]) + w[0] * ((p[1] - lo[1]) + w[1] * (p[2] - lo[2]))) + axis;
                        let s = &mut index.dense[slot];
                        if *s == u32::MAX {
                            *s = next;
                            index.touched.push(slot as u32);
                        }
                        *s
                    } else {
                        *sparse.entry(edge_key(p, axis, dims)).or_insert(next)
                    };
                    if id == next {
                        out.verts.push(p, axis, lo, hi, dims);
                    }
                    ids[e as usize] = id;
                }
                if record.across {
                    index.face_out.resize(out.verts.len(), [NO_TWIN; 4]);
                }
                let cell = (x + dims[0] * (y + dims[1] * z)) as u64;
                let base = 3 * out.triangles.len() as u32;
                for (i, (t, &plane)) in entry.triangles.iter().zip(&entry.planes).enumerate() {
                    let tri = t.map(|e| ids[e as usize]);
                    if record.across {
                        for (k, &code) in entry.across[i].iter().enumerate() {
                            let h = base + 3 * i as u32 + k as u32;
                            if code == ON_CELL_FACE {
                                out.across.push(NO_TWIN);
                                if let Some(free) = index.face_out[tri[k] as usize].iter_mut().find(|s| **s == NO_TWIN)
                                {
                                    *free = h;
                                }
                            } else {
                                out.across.push(base + code as u32);
                            }
                        }
                    }
                    out.triangles.push(tri);
                    out.planes.push(plane);
                    if record.cells {
                        out.cells.push(cell);
                    }
                }
            }
        }
    }
    for &slot in &index.touched {
        index.dense[slot as usize] = u32::MAX;
    }
    index.touched.clear();
    if record.across {
        match_face_twins(&mut out, &mut index.face_out);
    }
    out
}

/// Pairs the half-edges on cell faces: `a -> b` with the `b -> a` among the
/// face half-edges leaving `b`. Clears `face_out` for the next node.
fn match_face_twins(out: &mut NodeTriangles, face_out: &mut Vec<[u32; 4]>) {
    let end = |h: u32| out.triangles[h as usize / 3][(h as usize % 3 + 1) % 3];
    for a in 0..face_out.len() {
        for s in 0..4 {
            let h = face_out[a][s];
            if h == NO_TWIN || out.across[h as usize] != NO_TWIN {
                continue;
            }
            let b = end(h) as usize;
            if let Some(&r) = face_out[b].iter().find(|&&r| r != NO_TWIN && end(r) as usize == a) {
                out.across[h as usize] = r;
                out.across[r as usize] = h;
            }
        }
    }
    face_out.clear();
}
