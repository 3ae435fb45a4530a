//! Face compression (the Surface Octree's terminal surface nodes, paper 1
//! section 2.2): the coplanar DiscMC facets of one terminal node merged into
//! faces, with no point of the surface moved.
//!
//! DiscMC vertices are edge midpoints, so every facet plane has one of a few
//! small integer normals (from the case table) and two facets sharing an edge
//! with the same normal are coplanar. A *region* is a set of coplanar facets
//! of the node connected through shared edges; a *face* is the region's
//! boundary loop, counter-clockwise seen from outside: the facet edges whose
//! facet across lies in another plane, in another node, or outside the volume.
//! Each loop is traced with half-edges: from the boundary edge `a -> b` of a
//! facet, the next boundary edge leaves `b`, found by rotating about `b`
//! through the region's facets:
//!
//! ```text
//! in facet t: b -> c boundary?  yes: next edge.  no: t' = facet across b -> c
//! (it holds c -> b); continue with the edge that leaves b in t'.
//! ```
//!
//! Vertices inside a region belong to no face and leave the surface. A region
//! with a hole (a loop turning clockwise) or whose loop touches itself at a
//! vertex is not a simple polygon; the facets of that plane in that node stay
//! as they are, each its own face. Faces are simple polygons, possibly
//! non-convex: [`super::earclip`] triangulates them.

use super::exact::{dot, loop_area2};
use super::extract::{NodeTriangles, NodeVertices, NO_TWIN};
use super::table::plane_normals;

/// The faces of one terminal node: loop `i` is
/// `vertices[offsets[i] .. offsets[i + 1]]`, local vertex indices into `verts`,
/// counter-clockwise seen from outside, in plane `planes[i]` (an index into
/// [`super::table::plane_normals`]).
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct NodeFaces {
    /// The node's vertices (local numbering, as marched).
    pub verts: NodeVertices,
    /// Start of each face in `vertices`, plus the end.
    pub offsets: Vec<u32>,
    /// Local vertex indices.
    pub vertices: Vec<u32>,
    /// The plane of each face.
    pub planes: Vec<u8>,
}

impl NodeFaces {
    /// Number of faces.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
    /// True when there is no face.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Face `i` (local vertex indices).
    pub fn get(&self, i: usize) -> &[u32] {
        &self.vertices[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
    fn push(&mut self, face: &[u32], plane: u8) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.vertices.extend_from_slice(face);
        self.offsets.push(self.vertices.len() as u32);
        self.planes.push(plane);
    }
    /// Every facet its own face (no merging: interpolated mode, or compression off).
    pub fn from_triangles(node: NodeTriangles) -> NodeFaces {
        let count = node.triangles.len();
        NodeFaces {
            offsets: (0..=count as u32).map(|i| 3 * i).collect(),
            vertices: node.triangles.iter().flatten().copied().collect(),
            planes: node.planes,
            verts: node.verts,
        }
    }
}

/// Half-edge `k` of facet `t` (from corner `k` to corner `k + 1`) is `3 t + k`.
fn half_edge(t: usize, k: usize) -> usize {
    3 * t + k
}

/// Merges the facets of one node into faces (see the module documentation).
/// The node must have been marched with [`super::extract::Record::across`].
pub fn merge_coplanar(node: NodeTriangles) -> NodeFaces {
    let tris = &node.triangles;
    let planes = &node.planes;
    let nv = node.verts.len();
    // The half-edge across each half-edge `a -> b` (the reverse `b -> a` in
    // the facet on the other side, from the marching) when that facet lies in
    // the same plane; NONE marks a face boundary edge (another plane, another
    // node, or the volume's face).
    const NONE: u32 = NO_TWIN;
    let twin: Vec<u32> = node
        .across
        .iter()
        .enumerate()
        .map(|(h, &r)| if r != NONE && planes[r as usize / 3] == planes[h / 3] { r } else { NONE })
        .collect();
    let points = &node.verts.midpoints;
    let mut visited = vec![false; 3 * tris.len()];
    let mut seen_in = vec![u32::MAX; nv];
    let mut loops = NodeFaces::default();
    // Planes whose faces in this node are not simple polygons.
    let mut broken: Vec<u8> = Vec::new();
    let mut face: Vec<u32> = Vec::new();
    for h0 in 0..3 * tris.len() {
        if twin[h0] != NONE || visited[h0] {
            continue;
        }
        let plane = planes[h0 / 3];
        let normal = plane_normals()[plane as usize];
        let id = loops.len() as u32;
        face.clear();
        let mut simple = true;
        let mut h = h0;
        loop {
            visited[h] = true;
            let (t, k) = (h / 3, h % 3);
            let a = tris[t][k];
            if seen_in[a as usize] == id {
                simple = false; // the loop touches itself at a
            }
            seen_in[a as usize] = id;
            face.push(a);
            // Rotate about b = the end of h through the region to the next
            // boundary edge: from the half-edge b -> c that leaves b in this
            // facet, across to c -> b, then the half-edge leaving b there.
            let mut next = half_edge(t, (k + 1) % 3);
            let mut guard = 0;
            while twin[next] != NONE && guard <= tris.len() {
                let across = twin[next] as usize;
                next = half_edge(across / 3, (across % 3 + 1) % 3);
                guard += 1;
            }
            if guard > tris.len() || face.len() > 3 * tris.len() {
                simple = false; // not a manifold fan (cannot happen for a watertight table)
                break;
            }
            h = next;
            if h == h0 {
                break;
            }
        }
        let counter_clockwise = dot(loop_area2(face.iter().map(|&v| points[v as usize])), normal) > 0;
        if !(simple && counter_clockwise) {
            broken.push(plane);
        }
        loops.push(&face, plane);
    }
    if broken.is_empty() {
        loops.verts = node.verts;
        return loops;
    }
    // Faces of intact planes, then the facets of broken planes one by one.
    broken.sort_unstable();
    broken.dedup();
    let is_broken = |n: &u8| broken.binary_search(n).is_ok();
    let mut out = NodeFaces::default();
    for i in 0..loops.len() {
        if !is_broken(&loops.planes[i]) {
            out.push(loops.get(i), loops.planes[i]);
        }
    }
    for (t, n) in tris.iter().zip(planes) {
        if is_broken(n) {
            out.push(t, *n);
        }
    }
    out.verts = node.verts;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node of facets in the plane z = 1 (doubled z = 2 is not a midpoint;
    /// use the midpoints of z-edges at z = 0: doubled (2x, 2y, 1)).
    fn grid_facets(cells: &[(usize, usize)], dims: [usize; 3]) -> NodeTriangles {
        let mut node = NodeTriangles::default();
        let id = |node: &mut NodeTriangles, x: usize, y: usize| -> u32 {
            let k = crate::surface::extract::edge_key([x, y, 0], 2, dims);
            match node.verts.keys.iter().position(|&q| q == k) {
                Some(i) => i as u32,
                None => {
                    node.verts.push([x, y, 0], 2, [0, 0, 0], [dims[0] - 1, dims[1] - 1, dims[2] - 1], dims);
                    node.verts.len() as u32 - 1
                }
            }
        };
        for &(x, y) in cells {
            let (a, b, c, d) =
                (id(&mut node, x, y), id(&mut node, x + 1, y), id(&mut node, x + 1, y + 1), id(&mut node, x, y + 1));
            node.triangles.push([a, b, c]);
            node.triangles.push([a, c, d]);
            let up = plane_normals().binary_search(&[0, 0, 1]).expect("the table has the plane z") as u8;
            node.planes.extend([up, up]);
        }
        // Twins by brute force.
        let t = &node.triangles;
        node.across = (0..3 * t.len())
            .map(|h| {
                let (a, b) = (t[h / 3][h % 3], t[h / 3][(h % 3 + 1) % 3]);
                (0..3 * t.len())
                    .find(|&r| t[r / 3][r % 3] == b && t[r / 3][(r % 3 + 1) % 3] == a)
                    .map_or(NO_TWIN, |r| r as u32)
            })
            .collect();
        node
    }

    #[test]
    fn an_l_shaped_region_is_one_non_convex_face() {
        let dims = [8, 8, 2];
        let node = grid_facets(&[(0, 0), (1, 0), (0, 1)], dims);
        let f = merge_coplanar(node.clone());
        assert_eq!(f.len(), 1);
        // Boundary of the L: 8 vertices (corners and straight ones), interior none.
        assert_eq!(f.get(0).len(), 8);
    }

    #[test]
    fn a_region_with_a_hole_keeps_its_facets() {
        let dims = [8, 8, 2];
        let ring: Vec<(usize, usize)> =
            (0..3).flat_map(|x| (0..3).map(move |y| (x, y))).filter(|&c| c != (1, 1)).collect();
        let node = grid_facets(&ring, dims);
        let f = merge_coplanar(node.clone());
        assert_eq!(f.len(), node.triangles.len());
    }

    #[test]
    fn regions_touching_at_a_vertex_keep_their_facets() {
        let dims = [8, 8, 2];
        let node = grid_facets(&[(0, 0), (1, 1)], dims);
        let f = merge_coplanar(node.clone());
        // One region per square, each loop simple: two faces of 4.
        assert_eq!(f.len(), 2);
        assert!(f.get(0).len() == 4 && f.get(1).len() == 4);
    }
}
