//! Face compression (the Surface Octree's planar terminal nodes, paper 1
//! section 2.2): coplanar DiscMC facets of one terminal node merged into
//! convex polygons, with no point of the surface moved.
//!
//! DiscMC vertices are edge midpoints, so in doubled index coordinates every
//! vertex is an integer point and every facet plane is `n . x = d` with a
//! small integer normal `n` (divided by the gcd of its components) and integer
//! `d`: coplanarity is tested exactly.
//!
//! Region growing, per node and plane: a polygon starts as one triangle and
//! takes a neighbouring triangle of the same plane across one of its edges
//! `u -> v` (the triangle holds `v -> u`) when the union stays convex:
//!
//! ```text
//! third vertex c new:        ... u v ...  ->  ... u c v ...
//! c == prev(u) (a notch):    ... c u v ... ->  ... c v ...
//! c == next(v) (a notch):    ... u v c ... ->  ... u c ...
//! c elsewhere on the polygon: refused (it would enclose a hole)
//! ```
//!
//! and the turn `((w - p) x (n - w)) . normal` stays >= 0 at every vertex whose
//! neighbours changed (collinear vertices stay, for now; see
//! [`super::collinear`]). A locally convex polygon grown from a convex one by
//! triangles outside it is convex, so renderers may fan-triangulate it; the
//! union of its triangles is exactly the polygon, so the merged surface covers
//! the same point set as the facets.

use super::extract::{midpoint2, NodeTriangles};

/// Polygons of a node: `vertices[offsets[i] .. offsets[i + 1]]` index the
/// node's vertex keys `keys` (local numbering); counter-clockwise from outside.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct NodeMesh {
    /// The node's vertex edge keys, unique.
    pub keys: Vec<u64>,
    /// Start of each polygon in `vertices`, plus the end.
    pub offsets: Vec<u32>,
    /// Local vertex indices (into `keys`).
    pub vertices: Vec<u32>,
}

impl NodeMesh {
    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
    /// True when there is no polygon.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Polygon `i` (local vertex indices).
    pub fn get(&self, i: usize) -> &[u32] {
        &self.vertices[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
    fn push(&mut self, polygon: &[u32]) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.vertices.extend_from_slice(polygon);
        self.offsets.push(self.vertices.len() as u32);
    }
    /// The triangles as they are (no merging).
    pub fn from_triangles(node: &NodeTriangles) -> NodeMesh {
        NodeMesh {
            keys: node.keys.clone(),
            offsets: (0..=node.triangles.len() as u32).map(|i| 3 * i).collect(),
            vertices: node.triangles.iter().flatten().copied().collect(),
        }
    }
}

pub(crate) fn sub(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn cross(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
pub(crate) fn dot(a: [i64; 3], b: [i64; 3]) -> i64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// The turn at `w` (from `p`, to `n`) against `normal`: > 0 convex, 0 straight
/// (or a spike, told apart by [`straight`]), < 0 reflex.
pub(crate) fn turn(p: [i64; 3], w: [i64; 3], n: [i64; 3], normal: [i64; 3]) -> i64 {
    dot(cross(sub(w, p), sub(n, w)), normal)
}

/// True when `p -> w -> n` continues straight on (not a 180-degree spike).
fn straight(p: [i64; 3], w: [i64; 3], n: [i64; 3]) -> bool {
    dot(sub(w, p), sub(n, w)) > 0
}

/// Merges the triangles of one node into convex coplanar polygons.
pub fn compress(node: &NodeTriangles, dims: [usize; 3]) -> NodeMesh {
    let keys = node.keys.clone();
    let tris = &node.triangles;
    let points: Vec<[i64; 3]> = keys.iter().map(|&k| midpoint2(k, dims)).collect();
    // The plane n . x = d of each facet: n from the case table, d from one vertex.
    let planes: Vec<[i64; 4]> = tris
        .iter()
        .zip(&node.normals)
        .map(|(t, n)| [n[0], n[1], n[2], dot(*n, points[t[0] as usize])])
        .collect();
    // Outgoing directed edges per vertex (compressed rows): (to, triangle).
    let mut start = vec![0u32; keys.len() + 1];
    for t in tris {
        for &v in t {
            start[v as usize + 1] += 1;
        }
    }
    for v in 0..keys.len() {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut outgoing = vec![(0u32, 0u32); 3 * tris.len()];
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            let from = t[k] as usize;
            outgoing[fill[from] as usize] = (t[(k + 1) % 3], i as u32);
            fill[from] += 1;
        }
    }
    let across = |from: u32, to: u32| -> Option<usize> {
        let row = &outgoing[start[from as usize] as usize..start[from as usize + 1] as usize];
        row.iter().find(|e| e.0 == to).map(|e| e.1 as usize)
    };
    // Seeds in plane order, then triangle order (deterministic).
    let mut order: Vec<u32> = (0..tris.len() as u32).collect();
    order.sort_by_key(|&i| (planes[i as usize], i));
    let mut used = vec![false; tris.len()];
    // The growing polygon as a ring of local vertices: next/prev links (a
    // vertex is on the polygon at most once), so an insertion or a removal is
    // O(1). `edges` holds the polygon edges still to try, by their first vertex.
    let mut on_polygon = vec![false; keys.len()];
    let mut next = vec![u32::MAX; keys.len()];
    let mut prev = vec![u32::MAX; keys.len()];
    let mut edges: Vec<u32> = Vec::new();
    let mut out = NodeMesh::default();
    let mut polygon: Vec<u32> = Vec::new();
    for &seed in &order {
        let seed = seed as usize;
        if used[seed] {
            continue;
        }
        used[seed] = true;
        let key = planes[seed];
        let normal = [key[0], key[1], key[2]];
        let t = tris[seed];
        let mut ring = Ring { next: &mut next, prev: &mut prev, on: &mut on_polygon, len: 3, first: t[0] };
        for k in 0..3 {
            ring.link(t[k], t[(k + 1) % 3]);
            ring.on[t[k] as usize] = true;
        }
        edges.clear();
        edges.extend_from_slice(&[t[2], t[1], t[0]]);
        while let Some(u) = edges.pop() {
            if !ring.on[u as usize] {
                continue; // removed since it was pushed
            }
            let v = ring.next[u as usize];
            let Some(t) = across(v, u).filter(|&t| !used[t] && planes[t] == key) else {
                continue;
            };
            let tri = tris[t];
            let k = tri.iter().position(|&x| x == v).unwrap_or(0);
            let c = tri[(k + 2) % 3];
            if let Some(touched) = ring.try_add(u, v, c, normal, &points) {
                used[t] = true;
                // Edges whose ends changed neighbours: try them (again).
                edges.extend(touched.into_iter().flatten());
            }
        }
        polygon.clear();
        let mut v = ring.first;
        for _ in 0..ring.len {
            polygon.push(v);
            v = ring.next[v as usize];
        }
        for &v in &polygon {
            on_polygon[v as usize] = false;
        }
        out.push(&polygon);
    }
    out.keys = keys;
    out
}

/// A polygon as a ring of linked vertices.
struct Ring<'a> {
    next: &'a mut [u32],
    prev: &'a mut [u32],
    on: &'a mut [bool],
    len: usize,
    /// Some vertex on the ring (where the output walk starts).
    first: u32,
}

impl Ring<'_> {
    fn link(&mut self, a: u32, b: u32) {
        self.next[a as usize] = b;
        self.prev[b as usize] = a;
    }

    /// Adds the triangle `(v, u, c)` across the ring edge `u -> v` when the
    /// result stays convex (checked at the vertices whose neighbours change;
    /// the others keep their turns). Returns the first vertices of the edges to
    /// try again, or `None` when refused.
    fn try_add(&mut self, u: u32, v: u32, c: u32, normal: [i64; 3], points: &[[i64; 3]]) -> Option<[Option<u32>; 4]> {
        let prev_u = self.prev[u as usize];
        let next_v = self.next[v as usize];
        let p = |x: u32| points[x as usize];
        let ok = |a: u32, w: u32, b: u32| {
            let t = turn(p(a), p(w), p(b), normal);
            t > 0 || (t == 0 && straight(p(a), p(w), p(b)))
        };
        if self.len == 3 && c == prev_u && c == next_v {
            return None;
        }
        if c == prev_u {
            // The notch at u is filled: ... c u v ... -> ... c v ...
            let prev_c = self.prev[c as usize];
            if self.len <= 3 || !(ok(prev_c, c, v) && ok(c, v, next_v)) {
                return None;
            }
            self.remove(u);
            self.link(c, v);
            Some([Some(prev_c), Some(c), Some(v), None])
        } else if c == next_v {
            // The notch at v is filled: ... u v c ... -> ... u c ...
            let next_c = self.next[c as usize];
            if self.len <= 3 || !(ok(prev_u, u, c) && ok(u, c, next_c)) {
                return None;
            }
            self.remove(v);
            self.link(u, c);
            Some([Some(prev_u), Some(u), Some(c), None])
        } else if self.on[c as usize] {
            None
        } else {
            if !(ok(prev_u, u, c) && ok(u, c, v) && ok(c, v, next_v)) {
                return None;
            }
            self.link(u, c);
            self.link(c, v);
            self.on[c as usize] = true;
            self.len += 1;
            Some([Some(prev_u), Some(u), Some(c), Some(v)])
        }
    }

    fn remove(&mut self, x: u32) {
        self.on[x as usize] = false;
        self.len -= 1;
        if self.first == x {
            self.first = self.next[x as usize];
        }
    }
}
