//! Dropping straight-through vertices without opening T-junctions.
//!
//! After merging, a polygon keeps every vertex of its facets' boundary, many
//! of them on straight runs. A vertex may leave a polygon only if it leaves
//! every polygon that uses it: then the edge on either side of it becomes one
//! longer edge in all of them, and no neighbour keeps a vertex in the middle of
//! another polygon's edge (a T-junction, which renders as a crack). The rule:
//!
//! ```text
//! drop v  <=>  in every polygon using v, (v - p) x (n - v) = 0 and (v - p) . (n - v) > 0
//! ```
//!
//! (p, n the neighbours of v in that polygon). Removing a straight vertex does
//! not change a polygon's point set.

use super::compress::{cross, dot, sub, NodeMesh};
use super::extract::midpoint2;
use rayon::prelude::*;

/// For each of `global_count` vertices, whether it must stay: true when some
/// polygon turns at it. `node_global[n][local]` is the global index of node
/// `n`'s local vertex. Parallel over nodes.
pub fn keep_flags(meshes: &[NodeMesh], node_global: &[Vec<u32>], global_count: usize, dims: [usize; 3]) -> Vec<bool> {
    let turning: Vec<Vec<u32>> = meshes
        .par_iter()
        .zip(node_global)
        .map(|(mesh, global)| {
            let points: Vec<[i64; 3]> = mesh.keys.iter().map(|&k| midpoint2(k, dims)).collect();
            let mut out = Vec::new();
            for i in 0..mesh.len() {
                let poly = mesh.get(i);
                let n = poly.len();
                for k in 0..n {
                    let p = points[poly[(k + n - 1) % n] as usize];
                    let w = points[poly[k] as usize];
                    let q = points[poly[(k + 1) % n] as usize];
                    let (a, b) = (sub(w, p), sub(q, w));
                    if !(cross(a, b) == [0, 0, 0] && dot(a, b) > 0) {
                        out.push(global[poly[k] as usize]);
                    }
                }
            }
            out
        })
        .collect();
    let mut keep = vec![false; global_count];
    for g in turning.iter().flatten() {
        keep[*g as usize] = true;
    }
    keep
}
