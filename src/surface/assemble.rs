//! One mesh from the nodes' faces: which vertices stay, one global name per
//! vertex, and each face triangulated.
//!
//! A vertex whose grid edge lies strictly inside a node is used by that node's
//! faces only, so the node alone decides whether it stays
//! ([`super::straight`]) and names it: the nodes' inner vertices are numbered
//! node after node (a prefix sum). A vertex on a node's boundary (its edge on
//! a face of the node's box) may be used by up to four nodes: those are
//! gathered, sorted by edge key and merged (it stays if any node turns at it),
//! and numbered first, in key order. Only boundary vertices are sorted, a
//! fraction of all. Deterministic: per-node work is collected in node order,
//! the rest is a sort.

use super::earclip::EarClipper;
use super::faces::NodeFaces;
use super::straight::{vertex_flags, TURNS, USED};
use crate::error::{Error, Result};
use crate::octree::NodeId;
use rayon::prelude::*;

/// A node's faces with the flags of its vertices.
pub struct NodePart {
    /// The node.
    pub node: NodeId,
    /// Its faces.
    pub faces: NodeFaces,
    /// [`USED`] | [`TURNS`] per local vertex.
    pub flags: Vec<u8>,
}

impl NodePart {
    /// Flags the vertices of `faces`, the faces of terminal node `node`.
    /// With `merged` false every used vertex stays (facets are not merged).
    pub fn new(node: NodeId, faces: NodeFaces, merged: bool) -> NodePart {
        let mut flags = vertex_flags(&faces);
        if !merged {
            flags.iter_mut().filter(|f| **f & USED != 0).for_each(|f| *f |= TURNS);
        }
        NodePart { node, faces, flags }
    }
    fn inner_kept(&self, local: usize) -> bool {
        !self.faces.verts.on_boundary[local] && self.flags[local] & TURNS != 0
    }
}

/// The assembled mesh: vertices by edge key, triangles by node.
#[derive(Debug, Default)]
pub struct Mesh {
    /// Edge key of each vertex: the boundary vertices in key order, then each node's inner ones.
    pub keys: Vec<u64>,
    /// Three vertex indices per triangle, counter-clockwise from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The face (merged polygon) of each triangle, numbered node after node.
    pub triangle_face: Vec<u32>,
    /// The terminal node of each triangle.
    pub triangle_node: Vec<NodeId>,
    /// Per node with faces: (node, first triangle, end triangle).
    pub node_ranges: Vec<(NodeId, u32, u32)>,
    /// Number of faces.
    pub faces: usize,
}

/// Names the vertices of `parts` (in node order) and triangulates their faces.
pub fn assemble(parts: &[NodePart]) -> Result<Mesh> {
    // Boundary vertices: (key, turns) from every node, merged by key.
    let mut boundary: Vec<(u64, bool)> = parts
        .par_iter()
        .flat_map_iter(|p| {
            let v = &p.faces.verts;
            (0..v.len()).filter(|&l| v.on_boundary[l] && p.flags[l] & USED != 0).map(|l| (v.keys[l], p.flags[l] & TURNS != 0))
        })
        .collect();
    boundary.par_sort_unstable();
    // Sorted by (key, turns): the last entry of a key says whether any node turns there.
    let shared: Vec<u64> = boundary
        .iter()
        .enumerate()
        .filter(|&(i, e)| e.1 && boundary.get(i + 1).is_none_or(|n| n.0 != e.0))
        .map(|(_, e)| e.0)
        .collect();
    drop(boundary);
    // Inner vertices kept per node, numbered after the shared ones.
    let mut first_inner = Vec::with_capacity(parts.len() + 1);
    let mut next = shared.len() as u32;
    for p in parts {
        first_inner.push(next);
        next += (0..p.faces.verts.len()).filter(|&l| p.inner_kept(l)).count() as u32;
    }
    let vertex_count = next as usize;
    let mut face_base = Vec::with_capacity(parts.len());
    let mut faces = 0u32;
    for p in parts {
        face_base.push(faces);
        faces += p.faces.len() as u32;
    }

    let per_node: Vec<Result<(Vec<[u32; 3]>, Vec<u32>)>> = parts
        .par_iter()
        .zip(&first_inner)
        .zip(&face_base)
        .map_init(EarClipper::default, |clipper, ((p, &first), &face0)| {
            let v = &p.faces.verts;
            // Global index of each local vertex, u32::MAX when it leaves.
            let mut inner = first;
            let global: Vec<u32> = (0..v.len())
                .map(|l| {
                    if v.on_boundary[l] {
                        shared.binary_search(&v.keys[l]).map_or(u32::MAX, |g| g as u32)
                    } else if p.inner_kept(l) {
                        inner += 1;
                        inner - 1
                    } else {
                        u32::MAX
                    }
                })
                .collect();
            let mut triangles = Vec::with_capacity(p.faces.vertices.len());
            let mut face_of = Vec::with_capacity(p.faces.vertices.len());
            let mut kept: Vec<u32> = Vec::new();
            for f in 0..p.faces.len() {
                kept.clear();
                kept.extend(p.faces.get(f).iter().copied().filter(|&l| global[l as usize] != u32::MAX));
                let before = triangles.len();
                if !clipper.triangulate(&kept, &v.midpoints, p.faces.normals[f], &mut triangles) {
                    return Err(Error::Internal(format!(
                        "face {f} of node {:?} is not a simple polygon ({} vertices); please report this volume and isovalue",
                        p.node,
                        kept.len()
                    )));
                }
                face_of.resize(triangles.len(), face0 + f as u32);
                for t in &mut triangles[before..] {
                    *t = t.map(|l| global[l as usize]);
                }
            }
            Ok((triangles, face_of))
        })
        .collect();

    let mut mesh = Mesh { faces: faces as usize, ..Mesh::default() };
    mesh.keys.reserve(vertex_count);
    mesh.keys.extend_from_slice(&shared);
    for p in parts {
        mesh.keys.extend((0..p.faces.verts.len()).filter(|&l| p.inner_kept(l)).map(|l| p.faces.verts.keys[l]));
    }
    for (p, result) in parts.iter().zip(per_node) {
        let (triangles, face_of) = result?;
        let first = mesh.triangles.len() as u32;
        mesh.triangles.extend_from_slice(&triangles);
        mesh.triangle_face.extend_from_slice(&face_of);
        mesh.triangle_node.extend(std::iter::repeat_n(p.node, triangles.len()));
        mesh.node_ranges.push((p.node, first, mesh.triangles.len() as u32));
    }
    Ok(mesh)
}
