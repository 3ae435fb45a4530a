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
use super::table::plane_normals;
use crate::base::error::{Error, Result};
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
    /// Point and raw normal of each inner vertex that stays, in local order.
    pub inner: Vec<([f64; 3], [f64; 3])>,
}

impl NodePart {
    /// Flags the vertices of `faces`, the faces of terminal node `node`,
    /// and places the inner ones that stay with `place` (edge start, axis).
    /// With `merged` false every used vertex stays (facets are not merged).
    pub fn new(
        node: NodeId,
        faces: NodeFaces,
        merged: bool,
        place: impl Fn([usize; 3], usize) -> ([f64; 3], [f64; 3]),
    ) -> NodePart {
        let mut flags = vertex_flags(&faces);
        if !merged {
            flags.iter_mut().filter(|f| **f & USED != 0).for_each(|f| *f |= TURNS);
        }
        let mut part = NodePart { node, faces, flags, inner: Vec::new() };
        let v = &part.faces.verts;
        part.inner = (0..v.len())
            .filter(|&l| part.inner_kept(l))
            .map(|l| {
                // The edge midpoint in doubled coordinates: the odd coordinate is the axis.
                let m = v.midpoints[l];
                let axis = (0..3).find(|&k| m[k] & 1 == 1).unwrap_or(0);
                place(m.map(|c| (c / 2) as usize), axis)
            })
            .collect();
        part
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
    /// Number of vertices on node boundaries (the first ones of `keys`).
    pub shared: usize,
}

/// Names the vertices of `parts` (in node order) and triangulates their faces.
pub fn assemble(parts: &[NodePart]) -> Result<Mesh> {
    let (boundary, shared_of, shared) = shared_vertices(parts);
    let global = global_names(parts, &boundary, &shared_of, shared.len() as u32);
    drop((boundary, shared_of));
    let (face_base, faces) = face_bases(parts);
    let counts = triangle_counts(parts, &global);
    let total: usize = counts.iter().sum();
    let mut mesh = Mesh {
        faces: faces as usize,
        triangles: vec![[0; 3]; total],
        triangle_face: vec![0; total],
        ..Mesh::default()
    };
    triangulate(parts, &global, &face_base, &counts, &mut mesh)?;
    name_vertices(parts, &counts, shared, &mut mesh);
    Ok(mesh)
}

/// A boundary vertex of a node: its edge key, whether the node turns there,
/// the node's position in `parts` and the vertex's local index.
type BoundaryVertex = (u64, bool, u32, u32);

/// The boundary vertices of every node sorted by key, the shared name each
/// gets (`u32::MAX`: the vertex leaves), and the keys of the shared vertices
/// in key order. A key's run says whether any node turns there: it
/// stays if one does.
fn shared_vertices(parts: &[NodePart]) -> (Vec<BoundaryVertex>, Vec<u32>, Vec<u64>) {
    let mut boundary: Vec<BoundaryVertex> = parts
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, p)| {
            let v = &p.faces.verts;
            (0..v.len())
                .filter(|&l| v.on_boundary[l] && p.flags[l] & USED != 0)
                .map(move |l| (v.keys[l], p.flags[l] & TURNS != 0, i as u32, l as u32))
        })
        .collect();
    boundary.par_sort_unstable();
    let mut shared: Vec<u64> = Vec::new();
    let mut shared_of: Vec<u32> = vec![u32::MAX; boundary.len()];
    let mut run = 0;
    while run < boundary.len() {
        let key = boundary[run].0;
        let mut end = run;
        while end < boundary.len() && boundary[end].0 == key {
            end += 1;
        }
        // Sorted by (key, turns, ..): the run's last entry turns if any does.
        if boundary[end - 1].1 {
            shared_of[run..end].fill(shared.len() as u32);
            shared.push(key);
        }
        run = end;
    }
    (boundary, shared_of, shared)
}

/// The global name of each node's local vertices (`u32::MAX`: the vertex
/// leaves): the shared ones from [`shared_vertices`], then the inner ones kept
/// per node (placed in [`NodePart::new`]), numbered node after node from
/// `shared`, the number of shared vertices (a prefix sum).
fn global_names(parts: &[NodePart], boundary: &[BoundaryVertex], shared_of: &[u32], shared: u32) -> Vec<Vec<u32>> {
    let mut first_inner = Vec::with_capacity(parts.len());
    let mut next = shared;
    for count in parts.iter().map(|p| p.inner.len() as u32) {
        first_inner.push(next);
        next += count;
    }
    let mut global: Vec<Vec<u32>> = parts
        .par_iter()
        .zip(&first_inner)
        .map(|(p, &first)| {
            let mut inner = first;
            (0..p.faces.verts.len())
                .map(|l| {
                    if p.inner_kept(l) {
                        inner += 1;
                        inner - 1
                    } else {
                        u32::MAX
                    }
                })
                .collect()
        })
        .collect();
    for (e, &g) in boundary.iter().zip(shared_of) {
        global[e.2 as usize][e.3 as usize] = g;
    }
    global
}

/// The number of each node's first face (faces are numbered node after
/// node), and the number of faces.
fn face_bases(parts: &[NodePart]) -> (Vec<u32>, u32) {
    let mut face_base = Vec::with_capacity(parts.len());
    let mut faces = 0u32;
    for p in parts {
        face_base.push(faces);
        faces += p.faces.len() as u32;
    }
    (face_base, faces)
}

/// Triangles per node: a face of `k` kept vertices gives `k - 2`.
fn triangle_counts(parts: &[NodePart], global: &[Vec<u32>]) -> Vec<usize> {
    parts
        .par_iter()
        .zip(global)
        .map(|(p, global)| {
            (0..p.faces.len())
                .map(|f| p.faces.get(f).iter().filter(|&&l| global[l as usize] != u32::MAX).count().saturating_sub(2))
                .sum()
        })
        .collect()
}

/// Ear-clips every face's kept vertices into `mesh.triangles` (global names)
/// and `mesh.triangle_face`, each node filling its own slice of `counts[i]`
/// triangles, in parallel.
///
/// # Errors
///
/// [`Error::Internal`] when a face is not a simple polygon.
fn triangulate(
    parts: &[NodePart],
    global: &[Vec<u32>],
    face_base: &[u32],
    counts: &[usize],
    mesh: &mut Mesh,
) -> Result<()> {
    let mut slices = Vec::with_capacity(parts.len());
    let (mut rest_t, mut rest_f) = (&mut mesh.triangles[..], &mut mesh.triangle_face[..]);
    for &count in counts {
        let (t, tail_t) = rest_t.split_at_mut(count);
        let (f, tail_f) = rest_f.split_at_mut(count);
        slices.push((t, f));
        (rest_t, rest_f) = (tail_t, tail_f);
    }
    slices
        .into_par_iter()
        .zip(parts)
        .zip(global)
        .zip(face_base)
        .map_init(
            || (EarClipper::default(), Vec::new(), Vec::new()),
            |(clipper, kept, triangles), ((((out, face_out), p), global), &face0)| {
                triangles.clear();
                let mut at = 0;
                for f in 0..p.faces.len() {
                    kept.clear();
                    kept.extend(p.faces.get(f).iter().copied().filter(|&l| global[l as usize] != u32::MAX));
                    if !clipper.triangulate(kept, &p.faces.verts.midpoints, plane_normals()[p.faces.planes[f] as usize], triangles) {
                        return Err(Error::Internal(format!(
                            "face {f} of node {:?} is not a simple polygon ({} vertices); please report this volume and isovalue",
                            p.node,
                            kept.len()
                        )));
                    }
                    for t in triangles.drain(..) {
                        out[at] = t.map(|l| global[l as usize]);
                        face_out[at] = face0 + f as u32;
                        at += 1;
                    }
                }
                Ok(())
            },
        )
        .collect::<Result<()>>()
}

/// The mesh's vertex keys (the `shared` ones, then each node's inner ones
/// kept), the node of each triangle and each node's triangle range.
fn name_vertices(parts: &[NodePart], counts: &[usize], shared: Vec<u64>, mesh: &mut Mesh) {
    mesh.shared = shared.len();
    mesh.keys = shared;
    mesh.keys.par_extend(
        parts
            .par_iter()
            .flat_map_iter(|p| (0..p.faces.verts.len()).filter(|&l| p.inner_kept(l)).map(|l| p.faces.verts.keys[l])),
    );
    mesh.triangle_node.par_extend(parts.par_iter().zip(counts).flat_map_iter(|(p, &n)| std::iter::repeat_n(p.node, n)));
    let mut first = 0u32;
    for (p, &n) in parts.iter().zip(counts) {
        let end = first + n as u32;
        mesh.node_ranges.push((p.node, first, end));
        first = end;
    }
}
