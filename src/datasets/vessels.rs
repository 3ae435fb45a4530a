//! A synthetic angiogram: a branching tree of thin contrast-filled vessels in
//! a faint, smooth soft-tissue background. It is the "data with fine detail"
//! of paper 3: structures one to three voxels across on a 256^3 grid, which a
//! low resolution smears away, over a background that any resolution
//! reconstructs well.
//!
//! Coordinates are `p = 2 t - 1` in `[-1, 1]^3`. The value is
//!
//! ```text
//! f(p) = max(B(p), V(p))
//! B(p) = 0.12 clamp((1 - q) / 0.3, 0, 1),   q = (p_x / 0.9)^2 + (p_y / 0.95)^2 + (p_z / 0.9)^2
//! V(p) = max over segments s of clamp((r_s + w - d_s(p)) / w, 0, 1)
//! ```
//!
//! with `d_s(p)` the distance from `p` to segment `s`, `r_s` its radius and
//! `w = 0.004` (half a voxel at 256^3) the width of the edge ramp. So the
//! vessels are 1.0, the tissue at most 0.12 and the outside 0.
//!
//! The tree ([`tree`]): a root from `(0, -0.8, 0)` along `+y`, 0.42 long,
//! radius 0.022 (2.8 voxels at 256^3); each segment ends in two children,
//! each turned by [`BRANCH_ANGLE`] away from its parent, to either side,
//! about an axis that turns by the golden angle every generation, so the
//! branches fill 3D space, 0.8 times as long and 0.7 times as wide as their
//! parent; [`GENERATIONS`] generations, 63 segments, the finest 0.47 voxels
//! in radius at 256^3 (thinner than a voxel; on a smaller grid every vessel
//! is thinner in voxels).
//!
//! Each subtree carries its bounding box, so a sample far from a branch
//! skips all of it: the field costs a few segment distances a sample.

use crate::geometry::vec3::{add, cross, dot, normalize, scale, sub};
use std::sync::OnceLock;

/// Generations of the tree (root = 1): 2^6 - 1 = 63 segments.
pub const GENERATIONS: usize = 6;
/// Angle between a child and its parent, radians (40 degrees).
pub const BRANCH_ANGLE: f64 = 40.0 * std::f64::consts::PI / 180.0;
/// Width of the vessels' edge ramp, in `p` units.
pub const EDGE: f64 = 0.004;
/// The soft tissue's value.
pub const TISSUE: f64 = 0.12;

/// One vessel segment of the tree, with the bounding box of its subtree.
#[derive(Debug, Clone, Copy)]
pub struct Segment {
    /// Start point in `p` coordinates.
    pub a: [f64; 3],
    /// End point.
    pub b: [f64; 3],
    /// Radius.
    pub radius: f64,
    /// Box around this segment and all its descendants, padded by radius + edge.
    lo: [f64; 3],
    hi: [f64; 3],
}

/// The tree as an implicit binary heap: segment `i` has children `2i + 1` and `2i + 2`.
pub fn tree() -> &'static [Segment] {
    static TREE: OnceLock<Vec<Segment>> = OnceLock::new();
    TREE.get_or_init(build_tree)
}

fn build_tree() -> Vec<Segment> {
    let count = (1 << GENERATIONS) - 1;
    let mut segs = Vec::with_capacity(count);
    // (start, direction, length, radius) of each segment, heap order.
    let mut todo = vec![([0.0, -0.8, 0.0], [0.0, 1.0, 0.0], 0.42, 0.022)];
    for i in 0..count {
        let (a, d, len, radius) = todo[i];
        let b = add(a, scale(d, len));
        segs.push(Segment { a, b, radius, lo: [0.0; 3], hi: [0.0; 3] });
        let generation = (usize::BITS - (i + 1).leading_zeros()) as f64; // 1 for the root
        let (u, v) = perpendiculars(d);
        let phi = generation * 2.399_963_229_728_653; // the golden angle
        let axis = add(scale(u, phi.cos()), scale(v, phi.sin()));
        for side in [1.0, -1.0] {
            todo.push((b, rotate(d, axis, side * BRANCH_ANGLE), len * 0.8, radius * 0.7));
        }
    }
    // Subtree boxes, leaves first.
    for i in (0..count).rev() {
        let s = segs[i];
        let pad = s.radius + EDGE;
        let mut lo = [0.0; 3];
        let mut hi = [0.0; 3];
        for k in 0..3 {
            lo[k] = s.a[k].min(s.b[k]) - pad;
            hi[k] = s.a[k].max(s.b[k]) + pad;
        }
        for c in [2 * i + 1, 2 * i + 2] {
            if c < count {
                for k in 0..3 {
                    lo[k] = lo[k].min(segs[c].lo[k]);
                    hi[k] = hi[k].max(segs[c].hi[k]);
                }
            }
        }
        segs[i].lo = lo;
        segs[i].hi = hi;
    }
    segs
}

/// The angiogram's value at box-normalised `t`.
pub fn value(t: [f64; 3]) -> f64 {
    let p = [2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0, 2.0 * t[2] - 1.0];
    let q = (p[0] / 0.9).powi(2) + (p[1] / 0.95).powi(2) + (p[2] / 0.9).powi(2);
    let tissue = TISSUE * ((1.0 - q) / 0.3).clamp(0.0, 1.0);
    tissue.max(vessel(tree(), 0, p))
}

/// One x-row of [`value`] (`t_y`, `t_z` fixed, `t_x = i / (n - 1)` for the
/// row's `n` samples): the same values, bit for bit, at the cost of the
/// segments near the row. A segment's own box (padded by radius and edge)
/// bounds where it is not 0; the row keeps the segments whose box holds
/// its `(p_y, p_z)` and each sample evaluates those whose x-extent (in
/// samples, widened by one) holds it. `V` is a max, exact in any order,
/// and a skipped segment's term is 0 (its distance is at least its padded
/// radius there).
pub fn row(ty: f64, tz: f64, out: &mut [f64]) {
    let n = out.len();
    let (py, pz) = (2.0 * ty - 1.0, 2.0 * tz - 1.0);
    let segs = tree();
    // (first, last) sample index of each segment near the row.
    let mut near: Vec<(usize, usize, &Segment)> = Vec::new();
    let last = n.saturating_sub(1) as f64;
    for s in segs {
        let pad = s.radius + EDGE;
        let (ylo, yhi) = (s.a[1].min(s.b[1]) - pad, s.a[1].max(s.b[1]) + pad);
        let (zlo, zhi) = (s.a[2].min(s.b[2]) - pad, s.a[2].max(s.b[2]) + pad);
        if py < ylo || py > yhi || pz < zlo || pz > zhi {
            continue;
        }
        let (xlo, xhi) = (s.a[0].min(s.b[0]) - pad, s.a[0].max(s.b[0]) + pad);
        // p_x = 2 i / (n - 1) - 1: the sample indices of [xlo, xhi], one more each side.
        let first = (((xlo + 1.0) / 2.0 * last).floor() - 1.0).max(0.0);
        let end = (((xhi + 1.0) / 2.0 * last).ceil() + 1.0).min(last);
        if first <= end {
            near.push((first as usize, end as usize, s));
        }
    }
    for (i, v) in out.iter_mut().enumerate() {
        let tx = if n > 1 { i as f64 / (n - 1) as f64 } else { 0.0 };
        let p = [2.0 * tx - 1.0, py, pz];
        let q = (p[0] / 0.9).powi(2) + (p[1] / 0.95).powi(2) + (p[2] / 0.9).powi(2);
        let tissue = TISSUE * ((1.0 - q) / 0.3).clamp(0.0, 1.0);
        let mut vessel = 0.0f64;
        for &(first, end, s) in &near {
            if (first..=end).contains(&i) && vessel < 1.0 {
                let own = ((s.radius + EDGE - distance_to_segment(p, s.a, s.b)) / EDGE).clamp(0.0, 1.0);
                vessel = vessel.max(own);
            }
        }
        *v = tissue.max(vessel);
    }
}

/// `V(p)` over the subtree of segment `i`.
fn vessel(segs: &[Segment], i: usize, p: [f64; 3]) -> f64 {
    let s = &segs[i];
    if (0..3).any(|k| p[k] < s.lo[k] || p[k] > s.hi[k]) {
        return 0.0;
    }
    let own = ((s.radius + EDGE - distance_to_segment(p, s.a, s.b)) / EDGE).clamp(0.0, 1.0);
    let mut v = own;
    for c in [2 * i + 1, 2 * i + 2] {
        if v < 1.0 && c < segs.len() {
            v = v.max(vessel(segs, c, p));
        }
    }
    v
}

/// Distance from `p` to the segment `a b`.
fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let ap = sub(p, a);
    let s = (dot(ap, ab) / dot(ab, ab)).clamp(0.0, 1.0);
    let c = sub(ap, scale(ab, s));
    dot(c, c).sqrt()
}

/// Two unit vectors perpendicular to the unit `d` and to each other.
fn perpendiculars(d: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if d[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 0.0, 1.0] };
    let u = normalize(cross(d, helper));
    (u, cross(d, u))
}

/// `v` rotated by `angle` about the unit `axis` (Rodrigues' formula; `axis` is perpendicular to `v`).
fn rotate(v: [f64; 3], axis: [f64; 3], angle: f64) -> [f64; 3] {
    add(scale(v, angle.cos()), scale(cross(axis, v), angle.sin()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t_of(p: [f64; 3]) -> [f64; 3] {
        [(p[0] + 1.0) / 2.0, (p[1] + 1.0) / 2.0, (p[2] + 1.0) / 2.0]
    }

    #[test]
    fn tree_has_its_generations_and_stays_in_the_box() {
        let segs = tree();
        assert_eq!(segs.len(), 63);
        for s in segs {
            for k in 0..3 {
                assert!(s.a[k].abs() < 1.0 && s.b[k].abs() < 1.0, "{s:?}");
            }
        }
        // Children start where their parent ends, thinner.
        for i in 0..31 {
            for c in [2 * i + 1, 2 * i + 2] {
                assert_eq!(segs[c].a, segs[i].b);
                assert!((segs[c].radius - 0.7 * segs[i].radius).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn vessels_are_one_tissue_faint_outside_zero() {
        let s = tree()[5];
        let mid = scale(add(s.a, s.b), 0.5);
        assert_eq!(value(t_of(mid)), 1.0);
        // Deep in the tissue, away from every vessel: the tissue's plateau.
        let tissue = [0.0, 0.0, -0.4];
        assert_eq!(vessel(tree(), 0, tissue), 0.0);
        assert_eq!(value(t_of(tissue)), TISSUE);
        assert_eq!(value([0.0; 3]), 0.0);
        assert_eq!(value([1.0; 3]), 0.0);
    }

    #[test]
    fn a_row_is_the_values_of_its_samples() {
        for n in [2, 3, 17, 64, 255] {
            for (j, k) in [(0, 0), (n / 2, n / 3), (n / 3, n / 2), (n - 1, n / 4), (n / 5, n - 1)] {
                let (ty, tz) = (j as f64 / (n - 1) as f64, k as f64 / (n - 1) as f64);
                let mut out = vec![0.0; n];
                row(ty, tz, &mut out);
                for (i, v) in out.iter().enumerate() {
                    let want = value([i as f64 / (n - 1) as f64, ty, tz]);
                    assert_eq!(v.to_bits(), want.to_bits(), "n {n} sample ({i}, {j}, {k})");
                }
            }
        }
        // Rows through the vessels themselves: every segment's midpoint.
        let n = 300;
        for s in tree() {
            let m = scale(add(s.a, s.b), 0.5);
            let t = t_of(m);
            let (ty, tz) = (
                ((t[1] * (n - 1) as f64).round()) / (n - 1) as f64,
                ((t[2] * (n - 1) as f64).round()) / (n - 1) as f64,
            );
            let mut out = vec![0.0; n];
            row(ty, tz, &mut out);
            for (i, v) in out.iter().enumerate() {
                assert_eq!(v.to_bits(), value([i as f64 / (n - 1) as f64, ty, tz]).to_bits());
            }
        }
    }

    #[test]
    fn subtree_boxes_only_skip_what_is_zero() {
        // Brute force over every segment against the culled walk, on a lattice.
        let n = 41;
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let p = [i, j, k].map(|c| -1.0 + 2.0 * c as f64 / (n - 1) as f64);
                    let brute = tree()
                        .iter()
                        .map(|s| ((s.radius + EDGE - distance_to_segment(p, s.a, s.b)) / EDGE).clamp(0.0, 1.0))
                        .fold(0.0, f64::max);
                    assert_eq!(vessel(tree(), 0, p), brute, "{p:?}");
                }
            }
        }
    }
}
