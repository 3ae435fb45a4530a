//! Dropping straight-through vertices without opening T-junctions.
//!
//! A face keeps every vertex of its facets' boundary, many of them on
//! straight runs. A vertex may leave a face only if it leaves every face that
//! uses it: then the edge on either side of it becomes one longer edge in all
//! of them, and no neighbour keeps a vertex in the middle of another face's
//! edge (a T-junction, which renders as a crack). The rule:
//!
//! ```text
//! drop v  <=>  in every face using v, (v - p) x (n - v) = 0 and (v - p) . (n - v) > 0
//! ```
//!
//! (p, n the neighbours of v in that face). Removing a straight vertex does
//! not change a face's point set. Vertices used by no face (inside a merged
//! region) leave too. Faces of one node decide for the vertices inside the
//! node; vertices on the node's boundary are decided over all nodes
//! ([`super::assemble`]).

use super::exact::straight;
use super::faces::NodeFaces;

/// Flag: some face of the node uses the vertex.
pub const USED: u8 = 1;
/// Flag: some face of the node turns at the vertex (it must stay).
pub const TURNS: u8 = 2;

/// [`USED`] | [`TURNS`] flags of each local vertex of a node's faces.
pub fn vertex_flags(faces: &NodeFaces) -> Vec<u8> {
    let points = &faces.verts.midpoints;
    let mut flags = vec![0u8; faces.verts.len()];
    for i in 0..faces.len() {
        let face = faces.get(i);
        let n = face.len();
        for k in 0..n {
            let p = points[face[(k + n - 1) % n] as usize];
            let w = points[face[k] as usize];
            let q = points[face[(k + 1) % n] as usize];
            let turns = n == 3 || !straight(p, w, q);
            flags[face[k] as usize] |= USED | if turns { TURNS } else { 0 };
        }
    }
    flags
}
