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

use super::compress::{cross, dot, sub, Polygons};
use super::extract::midpoint2;

/// For each vertex of `sorted_keys`, whether it must stay: true when some
/// polygon turns at it. Parallel over the nodes' polygon sets.
pub fn keep_flags(polygons: &[Polygons], sorted_keys: &[u64], dims: [usize; 3]) -> Vec<bool> {
    use rayon::prelude::*;
    let turning: Vec<Vec<u32>> = polygons
        .par_iter()
        .map(|polys| {
            let mut out = Vec::new();
            for i in 0..polys.len() {
                let poly = polys.get(i);
                let n = poly.len();
                for k in 0..n {
                    let p = midpoint2(poly[(k + n - 1) % n], dims);
                    let w = midpoint2(poly[k], dims);
                    let q = midpoint2(poly[(k + 1) % n], dims);
                    let (a, b) = (sub(w, p), sub(q, w));
                    if !(cross(a, b) == [0, 0, 0] && dot(a, b) > 0) {
                        if let Ok(at) = sorted_keys.binary_search(&poly[k]) {
                            out.push(at as u32);
                        }
                    }
                }
            }
            out
        })
        .collect();
    let mut keep = vec![false; sorted_keys.len()];
    for at in turning.iter().flatten() {
        keep[*at as usize] = true;
    }
    keep
}
