//! The Marching Cubes case table, derived from one rule per cube face so that
//! two cubes sharing a face always cut it the same way (watertight).
//!
//! ```text
//!         6 ------- 7          corner c sits at (c & 1, (c >> 1) & 1, (c >> 2) & 1)
//!        /|        /|          edge e = 4 * axis + (b0 + 2 b1): the edge along `axis`
//!       4 ------- 5 |          whose two other coordinates (in axis order) are b0, b1
//!       | 2 ------|-3
//!       |/        |/           z
//!       0 ------- 1            |  y
//!                              | /
//!                              0 ---- x
//! ```
//!
//! A corner is *inside* when its value is at or above the isovalue. On each
//! face, edges with one inside and one outside corner carry a vertex; they are
//! joined by segments lying in the face:
//!
//! - two crossing edges: one segment;
//! - four (the two inside corners diagonal, the ambiguous face): two segments,
//!   each cutting off one inside corner, so inside corners stay separated.
//!
//! The rule reads only the face's four corners, so both cubes of a face agree.
//! Each segment is directed so that `d x N_face` points to the inside corner it
//! bounds (`N_face` the face's outward normal): the polygons come out
//! counter-clockwise seen from outside, with right-hand normals pointing to
//! the values below the isovalue; the cube across the face sees the face normal
//! reversed and traverses the segment the other way, so shared edges are used
//! once in each direction. Every crossing edge lies on two faces, so the
//! segments link into closed cycles: the case's polygons, whose vertices are
//! distinct edge midpoints (no three collinear, so no zero-area triangle).

use super::exact::{cross, dot, sub};
use std::sync::OnceLock;

/// Corner offset of corner `c`.
pub fn corner(c: usize) -> [i64; 3] {
    [(c & 1) as i64, ((c >> 1) & 1) as i64, ((c >> 2) & 1) as i64]
}

/// The two corners of edge `e` (low end first) and its axis.
pub fn edge_corners(e: usize) -> (usize, usize, usize) {
    let axis = e / 4;
    let bits = e % 4;
    let others: [usize; 2] = match axis {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    };
    let low = ((bits & 1) << others[0]) | (((bits >> 1) & 1) << others[1]);
    (low, low | (1 << axis), axis)
}

/// Edge `e`'s midpoint in doubled cube coordinates (0..=2).
pub fn edge_midpoint2(e: usize) -> [i64; 3] {
    let (a, b, _) = edge_corners(e);
    let (ca, cb) = (corner(a), corner(b));
    [ca[0] + cb[0], ca[1] + cb[1], ca[2] + cb[2]]
}

/// One case: its polygons as cycles of edge ids (counter-clockwise from
/// outside), and their triangles.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Case {
    /// The cycles, each a list of edge ids.
    pub cycles: Vec<Vec<u8>>,
    /// The edges the surface crosses (the cycles' edges, each once).
    pub edges: Vec<u8>,
    /// Each cycle fan-triangulated from a start vertex chosen so that no
    /// triangle lies in a cube face: a cycle through three crossing edges of
    /// an ambiguous face would otherwise put a triangle in that face, and the
    /// cube across the face the same triangle reversed (a zero-volume fin).
    pub triangles: Vec<[u8; 3]>,
    /// Each triangle's plane normal in doubled coordinates, divided by the gcd
    /// of its components (right-hand, pointing out): the same for every cell, so
    /// face compression reads it here instead of computing it per facet.
    pub normals: Vec<[i64; 3]>,
    /// Each triangle's plane normal as an index into [`plane_normals`].
    pub planes: Vec<u8>,
    /// For edge `k` of triangle `t` (corner `k` to corner `k + 1`): the
    /// half-edge `3 t' + k'` of this case running the other way (a diagonal of
    /// a fan), or [`ON_CELL_FACE`] when the edge lies on a face of the cell and
    /// its twin is in the neighbouring cell.
    pub across: Vec<[u8; 3]>,
}

/// [`Case::across`] of an edge on a cell face.
pub const ON_CELL_FACE: u8 = u8::MAX;

/// True when the midpoints of edges `a`, `b`, `c` lie in one face of the cube.
fn on_one_face(a: u8, b: u8, c: u8) -> bool {
    let (pa, pb, pc) = (edge_midpoint2(a as usize), edge_midpoint2(b as usize), edge_midpoint2(c as usize));
    (0..3).any(|k| pa[k] == pb[k] && pb[k] == pc[k] && pa[k] != 1)
}

/// Fan triangles of `cycle` from the first start vertex that puts no triangle in a cube face.
fn triangulate(cycle: &[u8]) -> Vec<[u8; 3]> {
    let n = cycle.len();
    let fan = |s: usize| -> Vec<[u8; 3]> {
        (1..n - 1).map(|i| [cycle[s], cycle[(s + i) % n], cycle[(s + i + 1) % n]]).collect()
    };
    (0..n).map(fan).find(|tris| tris.iter().all(|t| !on_one_face(t[0], t[1], t[2]))).unwrap_or_else(|| fan(0))
}

/// The 256 cases, indexed by `sum over inside corners c of 2^c`.
pub fn cases() -> &'static [Case; 256] {
    &table().0
}

/// The distinct facet plane normals of all cases, sorted (DiscMC facets take
/// a finite set of orientations; a plane id is an index into this list).
pub fn plane_normals() -> &'static [[i64; 3]] {
    &table().1
}

/// The cases and the distinct plane normals of their facets.
type Table = (Box<[Case; 256]>, Vec<[i64; 3]>);

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut cases: Box<[Case; 256]> = Box::new(std::array::from_fn(build_case));
        let mut normals: Vec<[i64; 3]> = cases.iter().flat_map(|c| c.normals.iter().copied()).collect();
        normals.sort_unstable();
        normals.dedup();
        assert!(normals.len() <= 256, "{} facet planes do not fit a u8 id", normals.len());
        for case in cases.iter_mut() {
            case.planes = case.normals.iter().map(|n| normals.binary_search(n).unwrap_or(0) as u8).collect();
        }
        (cases, normals)
    })
}

/// `n` divided by the gcd of its components.
pub fn reduced(n: [i64; 3]) -> [i64; 3] {
    fn gcd(a: i64, b: i64) -> i64 {
        if b == 0 {
            a.abs()
        } else {
            gcd(b, a % b)
        }
    }
    let g = gcd(gcd(n[0], n[1]), n[2]).max(1);
    [n[0] / g, n[1] / g, n[2] / g]
}

fn build_case(index: usize) -> Case {
    let inside = |c: usize| index >> c & 1 == 1;
    let mut next = [u8::MAX; 12];
    for axis in 0..3 {
        for side in 0..2usize {
            let corners: Vec<usize> = (0..8).filter(|&c| (c >> axis) & 1 == side).collect();
            let mut normal = [0i64; 3];
            normal[axis] = if side == 0 { -1 } else { 1 };
            let crossing: Vec<usize> = (0..12)
                .filter(|&e| {
                    let (a, b, ax) = edge_corners(e);
                    ax != axis && (a >> axis) & 1 == side && inside(a) != inside(b)
                })
                .collect();
            let inside_corners: Vec<usize> = corners.iter().copied().filter(|&c| inside(c)).collect();
            // (segment end points, the inside corner it bounds)
            let mut segments: Vec<(usize, usize, usize)> = Vec::new();
            match crossing.len() {
                0 => {}
                2 => segments.push((crossing[0], crossing[1], inside_corners[0])),
                4 => {
                    for &c in &inside_corners {
                        let ends: Vec<usize> = crossing
                            .iter()
                            .copied()
                            .filter(|&e| {
                                let (a, b, _) = edge_corners(e);
                                a == c || b == c
                            })
                            .collect();
                        segments.push((ends[0], ends[1], c));
                    }
                }
                n => unreachable!("a face has {n} crossing edges"),
            }
            for (p, q, c) in segments {
                let (mp, mq) = (edge_midpoint2(p), edge_midpoint2(q));
                let mid = [mp[0] + mq[0], mp[1] + mq[1], mp[2] + mq[2]]; // 2 x segment midpoint, in doubled units
                let cc = corner(c);
                let to_corner = sub([4 * cc[0], 4 * cc[1], 4 * cc[2]], mid);
                let d = sub(mq, mp);
                let (from, to) = if dot(cross(d, normal), to_corner) > 0 { (p, q) } else { (q, p) };
                debug_assert_eq!(next[from], u8::MAX, "edge {from} starts two segments");
                next[from] = to as u8;
            }
        }
    }
    let mut seen = [false; 12];
    let mut cycles = Vec::new();
    for start in 0..12 {
        if next[start] == u8::MAX || seen[start] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut e = start;
        while !seen[e] {
            seen[e] = true;
            cycle.push(e as u8);
            e = next[e] as usize;
        }
        cycles.push(cycle);
    }
    let triangles: Vec<[u8; 3]> = cycles.iter().flat_map(|c| triangulate(c)).collect();
    let normals = triangles
        .iter()
        .map(|t| {
            let p = t.map(|e| edge_midpoint2(e as usize));
            reduced(cross(sub(p[1], p[0]), sub(p[2], p[0])))
        })
        .collect();
    let across = triangles
        .iter()
        .map(|t| {
            std::array::from_fn(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                triangles
                    .iter()
                    .enumerate()
                    .find_map(|(i, u)| (0..3).find(|&m| u[m] == b && u[(m + 1) % 3] == a).map(|m| (3 * i + m) as u8))
                    .unwrap_or(ON_CELL_FACE)
            })
        })
        .collect();
    let edges = cycles.iter().flatten().copied().collect();
    Case { cycles, edges, triangles, normals, planes: Vec::new(), across }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_corner_is_one_outward_triangle() {
        let case = &cases()[1];
        assert_eq!(case.cycles.len(), 1);
        let c = &case.cycles[0];
        assert_eq!(c.len(), 3);
        let p: Vec<[i64; 3]> = c.iter().map(|&e| edge_midpoint2(e as usize)).collect();
        let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        assert!(n.iter().all(|&v| v > 0), "normal {n:?} must point away from corner 0");
    }

    #[test]
    fn complements_and_counts() {
        for (i, case) in cases().iter().enumerate() {
            let used: usize = case.cycles.iter().map(|c| c.len()).sum();
            let crossing = (0..12).filter(|&e| {
                let (a, b, _) = edge_corners(e);
                (i >> a & 1) != (i >> b & 1)
            });
            assert_eq!(used, crossing.count(), "case {i}: every crossing edge is used once");
            assert!(case.cycles.iter().all(|c| c.len() >= 3), "case {i}");
            assert!(
                case.triangles.iter().all(|t| !on_one_face(t[0], t[1], t[2])),
                "case {i}: a triangle lies in a face"
            );
            let expected: usize = case.cycles.iter().map(|c| c.len() - 2).sum();
            assert_eq!(case.triangles.len(), expected, "case {i}");
        }
        assert!(cases()[0].cycles.is_empty() && cases()[255].cycles.is_empty());
    }
}
