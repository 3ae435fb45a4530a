//! Triangulating a face: ear clipping of a simple planar polygon, exact in
//! doubled index coordinates.
//!
//! A vertex `w` with neighbours `p`, `n` is an *ear* when it turns strictly
//! counter-clockwise, `((w - p) x (n - w)) . normal > 0`, and no other vertex
//! of the polygon lies in the closed triangle `(p, w, n)`; then the diagonal
//! `p n` lies inside the polygon (an edge crossing the triangle would have to
//! cross `p w` or `w n`, or bring a vertex inside), and cutting the ear off
//! leaves a simple polygon with one vertex less. Every simple polygon with more
//! than three vertices, not all on one line, has such an ear, so the loop ends
//! with `n - 2` triangles, none of zero area, using only the polygon's own
//! vertices (no T-junction: straight vertices a neighbour needs stay corners).
//! Only vertices that do not turn strictly (reflex or straight) can lie in an
//! ear's triangle, so only they are tested.

use super::exact::{in_closed_triangle, turn};

/// The ear clipper, with its buffers reused from face to face.
#[derive(Debug, Default)]
pub struct EarClipper {
    next: Vec<usize>,
    prev: Vec<usize>,
    convex: Vec<bool>,
    /// Vertices that did not turn strictly at the start. Clipping an ear only
    /// shrinks the angles at its two neighbours, so a convex vertex never
    /// becomes reflex or straight again: no vertex joins the list. A clipped
    /// tip was convex and stays marked so, so `convex` alone filters both.
    others: Vec<usize>,
}

impl EarClipper {
    /// Appends the triangles of the simple polygon `face` (indices into
    /// `points`, counter-clockwise about `normal`) to `out`. Returns false, with
    /// `out` as it was, if no ear is left before the end (the polygon was not
    /// simple).
    pub fn triangulate(
        &mut self,
        face: &[u32],
        points: &[[i64; 3]],
        normal: [i64; 3],
        out: &mut Vec<[u32; 3]>,
    ) -> bool {
        let n = face.len();
        if n < 3 {
            return n == 0;
        }
        if n == 3 {
            out.push([face[0], face[1], face[2]]);
            return true;
        }
        let before = out.len();
        let p = |i: usize| points[face[i] as usize];
        let EarClipper { next, prev, convex, others } = self;
        next.clear();
        next.extend((1..=n).map(|i| i % n));
        prev.clear();
        prev.extend((0..n).map(|i| (i + n - 1) % n));
        let turns = |prev: &[usize], next: &[usize], i: usize| turn(p(prev[i]), p(i), p(next[i]), normal) > 0;
        convex.clear();
        convex.extend((0..n).map(|i| turns(prev, next, i)));
        others.clear();
        others.extend((0..n).filter(|&i| !convex[i]));
        if others.is_empty() {
            // Strictly convex: every fan triangle from vertex 0 is an ear.
            out.extend((1..n - 1).map(|k| [face[0], face[k], face[k + 1]]));
            return true;
        }
        let mut left = n;
        let mut i = 0;
        let mut tried = 0;
        while left > 3 {
            if tried > left {
                out.truncate(before);
                return false;
            }
            let (a, c) = (prev[i], next[i]);
            let ear = convex[i] && {
                // No non-convex vertex of the rest in the closed triangle (a, i, c).
                let (pa, pi, pc) = (p(a), p(i), p(c));
                let lo = [0, 1, 2].map(|k| pa[k].min(pi[k]).min(pc[k]));
                let hi = [0, 1, 2].map(|k| pa[k].max(pi[k]).max(pc[k]));
                !others.iter().any(|&j| {
                    let q = p(j);
                    j != a
                        && j != c
                        && !convex[j]
                        && (0..3).all(|k| lo[k] <= q[k] && q[k] <= hi[k])
                        && in_closed_triangle(q, pa, pi, pc, normal)
                })
            };
            if ear {
                out.push([face[a], face[i], face[c]]);
                next[a] = c;
                prev[c] = a;
                convex[a] = turns(prev, next, a);
                convex[c] = turns(prev, next, c);
                left -= 1;
                tried = 0;
                i = a; // a's turn changed; c's too, reached next
            } else {
                i = c;
                tried += 1;
            }
        }
        let a = prev[i];
        out.push([face[a], face[i], face[next[i]]]);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::exact::{cross, dot, sub};

    fn area2(tris: &[[u32; 3]], pts: &[[i64; 3]], normal: [i64; 3]) -> i64 {
        tris.iter()
            .map(|t| {
                let a = dot(
                    cross(sub(pts[t[1] as usize], pts[t[0] as usize]), sub(pts[t[2] as usize], pts[t[0] as usize])),
                    normal,
                );
                assert!(a > 0, "zero-area or flipped triangle {t:?}");
                a
            })
            .sum()
    }

    #[test]
    fn comb_with_straight_vertices() {
        // A comb: non-convex, with straight vertices on the base.
        let pts: Vec<[i64; 3]> = vec![
            [0, 0, 0],
            [2, 0, 0],
            [4, 0, 0],
            [6, 0, 0],
            [6, 4, 0],
            [5, 4, 0],
            [4, 1, 0],
            [3, 4, 0],
            [2, 1, 0],
            [1, 4, 0],
            [0, 4, 0],
        ];
        let face: Vec<u32> = (0..pts.len() as u32).collect();
        let mut out = Vec::new();
        assert!(EarClipper::default().triangulate(&face, &pts, [0, 0, 1], &mut out));
        assert_eq!(out.len(), pts.len() - 2);
        // Shoelace area of the comb (doubled): every triangle positive, sum equal.
        let shoelace: i64 = (0..pts.len()).map(|i| cross(pts[i], pts[(i + 1) % pts.len()])[2]).sum();
        assert_eq!(area2(&out, &pts, [0, 0, 1]), shoelace);
    }

    #[test]
    fn triangle_with_a_vertex_on_every_side() {
        let pts: Vec<[i64; 3]> = vec![[0, 0, 0], [2, 0, 0], [4, 0, 0], [2, 2, 0], [0, 4, 0], [0, 2, 0]];
        let face: Vec<u32> = (0..6).collect();
        let mut out = Vec::new();
        assert!(EarClipper::default().triangulate(&face, &pts, [0, 0, 1], &mut out));
        assert_eq!(out.len(), 4);
        assert_eq!(area2(&out, &pts, [0, 0, 1]), 16);
    }

    #[test]
    fn a_clockwise_loop_is_refused_and_nothing_is_written() {
        let pts: Vec<[i64; 3]> = vec![[0, 0, 0], [0, 2, 0], [2, 2, 0], [2, 0, 0]];
        let mut out = vec![[7, 7, 7]];
        assert!(!EarClipper::default().triangulate(&[0, 1, 2, 3], &pts, [0, 0, 1], &mut out));
        assert_eq!(out, vec![[7, 7, 7]]);
    }
}
