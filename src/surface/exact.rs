//! Exact geometry of DiscMC vertices: in doubled index coordinates every edge
//! midpoint is an integer point, so orientation and containment tests are
//! integer arithmetic with no rounding.

/// `a - b`.
pub fn sub(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a x b`.
pub fn cross(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a . b`.
pub fn dot(a: [i64; 3], b: [i64; 3]) -> i64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The turn at `w` (coming from `p`, going to `n`) seen against `normal`:
/// `((w - p) x (n - w)) . normal`; > 0 convex (counter-clockwise), 0 straight
/// on or straight back, < 0 reflex.
pub fn turn(p: [i64; 3], w: [i64; 3], n: [i64; 3], normal: [i64; 3]) -> i64 {
    dot(cross(sub(w, p), sub(n, w)), normal)
}

/// True when `p -> w -> n` goes straight on: `(w - p) x (n - w) = 0` and
/// `(w - p) . (n - w) > 0` (not a 180-degree spike).
pub fn straight(p: [i64; 3], w: [i64; 3], n: [i64; 3]) -> bool {
    let (a, b) = (sub(w, p), sub(n, w));
    cross(a, b) == [0, 0, 0] && dot(a, b) > 0
}

/// True when `x`, coplanar with the counter-clockwise (about `normal`)
/// triangle `(a, b, c)`, lies inside it or on its boundary.
pub fn in_closed_triangle(x: [i64; 3], a: [i64; 3], b: [i64; 3], c: [i64; 3], normal: [i64; 3]) -> bool {
    let side = |p: [i64; 3], q: [i64; 3]| dot(cross(sub(q, p), sub(x, p)), normal) >= 0;
    side(a, b) && side(b, c) && side(c, a)
}

/// Twice the area vector of the closed loop `points` (the sum of `p_i x p_{i+1}`):
/// positive along `normal` for a counter-clockwise loop.
pub fn loop_area2(points: impl Iterator<Item = [i64; 3]> + Clone) -> [i64; 3] {
    let first = points.clone().next();
    let mut acc = [0i64; 3];
    let mut prev = None;
    for p in points.chain(first) {
        if let Some(q) = prev {
            let c = cross(q, p);
            acc = [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]];
        }
        prev = Some(p);
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_and_containment() {
        let z = [0, 0, 1];
        assert!(turn([0, 0, 0], [2, 0, 0], [2, 2, 0], z) > 0);
        assert!(turn([0, 0, 0], [2, 0, 0], [2, -2, 0], z) < 0);
        assert_eq!(turn([0, 0, 0], [2, 0, 0], [4, 0, 0], z), 0);
        assert!(straight([0, 0, 0], [2, 0, 0], [4, 0, 0]));
        assert!(!straight([0, 0, 0], [2, 0, 0], [0, 0, 0]));
        let (a, b, c) = ([0, 0, 0], [4, 0, 0], [0, 4, 0]);
        assert!(in_closed_triangle([1, 1, 0], a, b, c, z));
        assert!(in_closed_triangle([2, 2, 0], a, b, c, z), "on the hypotenuse");
        assert!(in_closed_triangle(a, a, b, c, z));
        assert!(!in_closed_triangle([3, 3, 0], a, b, c, z));
        assert_eq!(loop_area2([a, b, c].into_iter()), [0, 0, 16]);
        assert_eq!(loop_area2([a, c, b].into_iter()), [0, 0, -16]);
    }
}
