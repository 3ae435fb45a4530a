//! Compositing order: bricks back to front (and front to back) for a camera.
//!
//! The bricks of a selection are nodes of the Volume Octree, so their order
//! comes from a traversal of the tree (paper 1, section 4.1, after the
//! classic back-to-front octree traversal): starting at the root, a selected
//! node is emitted; any other node is entered, and its children that hold
//! selected nodes are visited far child first. Children are ranked by how
//! many of the three split planes of their parent have the eye on the
//! child's side:
//!
//! ```text
//! split plane along a:   x_a = w_a,   w_a = world(lo_a + 2^(L-k-1))   (the children's shared face)
//! eye side along a:      perspective  high if eye_a > w_a,   low if eye_a < w_a,   none if eye_a = w_a
//!                        parallel     high if f_a < 0,       low if f_a > 0,       none if f_a = 0
//! rank(child)        =   #{ a : the child lies on the eye side of the split plane along a }
//! back to front      =   children by (rank, child index),   rank 0 (far child) first, 3 (eye child) last
//! front to back      =   the exact reverse of back to front
//! ```
//!
//! (`f` is the unit view direction, `eye` the camera position, the child
//! index is `dx + 2 dy + 4 dz`.) Why it is a visibility order: two siblings
//! differing on the axes `D` are separated by the split planes along `D`; the
//! one that can hide the other is on the eye side of all of them, so its rank
//! is larger by `|D|`. When the eye is on one's side along some axis and the
//! other's along another, or on a plane itself, neither can hide the other
//! and any order is valid: ties go to the child index, so the result is
//! deterministic. Whole subtrees are separated by their ancestors' split
//! planes, so the recursion extends the order to all bricks. The perspective
//! rule uses the eye position only, so it holds with the camera inside the
//! volume.
//!
//! The split plane is the face the children share, `lo + 2^(L-k-1)` in index
//! space, not the midpoint of the parent's box: boxes are clipped to the grid
//! (`[lo, min(lo + 2^(L-k), n - 1)]`), and the midpoint of a clipped box is
//! not where its children meet. A child is on the high side along `a` when
//! its coordinate is odd, which is where its box centre lies too.
//!
//! [`is_back_to_front`] is the brute-force check the tests hold the order to.

use crate::data::grid::GridShape;
use crate::geometry::camera::Camera;
use crate::octree::{NodeId, VolumeOctree};
use std::collections::{HashMap, HashSet};

/// On which side of an axis-aligned plane the eye lies, per projection.
#[derive(Debug, Clone, Copy)]
enum Eye {
    /// Perspective: the camera position.
    Point([f64; 3]),
    /// Parallel: the unit view direction `f`; the eye is at infinity towards `-f`.
    Direction([f64; 3]),
}

impl Eye {
    fn new(camera: &Camera) -> Eye {
        if camera.is_perspective() {
            Eye::Point(camera.position)
        } else {
            Eye::Direction(camera.forward())
        }
    }

    /// `Some(true)`: the eye is strictly on the high side of the plane
    /// `x_axis = w`, `Some(false)`: strictly on the low side, `None`: on the
    /// plane (perspective) or looking along it (parallel, `f_axis = 0`).
    fn high_side(&self, axis: usize, w: f64) -> Option<bool> {
        let (a, b) = match *self {
            Eye::Point(e) => (e[axis], w),
            // Towards -f: high when f_axis < 0.
            Eye::Direction(f) => (0.0, f[axis]),
        };
        match a.partial_cmp(&b) {
            Some(std::cmp::Ordering::Greater) => Some(true),
            Some(std::cmp::Ordering::Less) => Some(false),
            _ => None,
        }
    }
}

/// Indices into `selected` in compositing order for `camera`: back to front
/// when `back_to_front`, else front to back (its exact reverse). See the
/// module documentation for the traversal and the ranking of children.
///
/// `selected` is normally a cut of the tree (the bricks of a
/// [`crate::plan::select::Selection`]). Every index is emitted exactly once in any
/// case: a node listed twice gives its indices in increasing order (back to
/// front), and a selected node that is an ancestor of another selected node
/// comes before its descendants (back to front). `shape` maps index space to
/// world space (`origin + spacing * index`), where the eye is compared with
/// the split planes. Panics on a node id not from `octree` (a caller bug).
pub fn brick_order(
    camera: &Camera,
    octree: &VolumeOctree,
    shape: &GridShape,
    selected: &[NodeId],
    back_to_front: bool,
) -> Vec<usize> {
    let layout = octree.layout();
    // Selected nodes (with every index they appear at) and the strict
    // ancestors of selected nodes, the only nodes the traversal enters.
    let mut chosen: HashMap<NodeId, Vec<usize>> = HashMap::with_capacity(selected.len());
    let mut inner: HashSet<NodeId> = HashSet::new();
    for (i, &id) in selected.iter().enumerate() {
        chosen.entry(id).or_default().push(i);
        let (mut level, mut c) = layout.locate(id);
        while level > 0 {
            level -= 1;
            c = c.map(|v| v / 2);
            if !inner.insert(layout.id(level, c)) {
                break; // this ancestor and its own ancestors are in already
            }
        }
    }
    let walk = Walk { eye: Eye::new(camera), octree, shape, chosen: &chosen, inner: &inner };
    let mut order = Vec::with_capacity(selected.len());
    if !selected.is_empty() {
        walk.visit(0, [0; 3], &mut order);
    }
    debug_assert_eq!(order.len(), selected.len());
    if !back_to_front {
        order.reverse();
    }
    order
}

/// The back-to-front traversal's fixed inputs.
struct Walk<'a> {
    eye: Eye,
    octree: &'a VolumeOctree,
    shape: &'a GridShape,
    chosen: &'a HashMap<NodeId, Vec<usize>>,
    inner: &'a HashSet<NodeId>,
}

impl Walk<'_> {
    /// Emits the selected nodes of the subtree of node `c` at `level`, back to front.
    fn visit(&self, level: usize, c: [usize; 3], out: &mut Vec<usize>) {
        let layout = self.octree.layout();
        let id = layout.id(level, c);
        if let Some(indices) = self.chosen.get(&id) {
            out.extend_from_slice(indices);
        }
        if !self.inner.contains(&id) {
            return;
        }
        // Split planes: the children's shared faces w_a = world(lo_a + 2^(L-k-1)).
        let (lo, _) = layout.node_box(level, c);
        let half = layout.node_size(level + 1);
        let split = self.shape.world(lo.map(|v| (v + half) as f64));
        let eye_high: [Option<bool>; 3] = [0, 1, 2].map(|a| self.eye.high_side(a, split[a]));
        // rank = #{a : child on the eye side along a}; layout.children yields
        // increasing child index, and the sort is stable: ties by child index.
        let mut children: Vec<(usize, [usize; 3])> = layout
            .children(level, c)
            .filter(|&(l, cc)| {
                let cid = layout.id(l, cc);
                self.chosen.contains_key(&cid) || self.inner.contains(&cid)
            })
            .map(|(_, cc)| {
                let rank = (0..3).filter(|&a| eye_high[a] == Some(cc[a] % 2 == 1)).count();
                (rank, cc)
            })
            .collect();
        children.sort_by_key(|&(rank, _)| rank);
        for (_, cc) in children {
            self.visit(level + 1, cc, out);
        }
    }
}

/// True when `order` is a valid back-to-front order of the axis-aligned
/// world boxes `boxes_world` (`(lo, hi)` each) for `camera`: a brute-force
/// check of every pair, for the tests.
///
/// `order` must be a permutation of the box indices, and no two boxes may
/// overlap (interiors intersecting: touching faces, edges or corners are
/// fine); otherwise the answer is false. For boxes `A` drawn before `B`, `A`
/// must not be able to hide `B`. Boxes are separated along the axes `S`
/// where their intervals do not overlap (`A.hi_a <= B.lo_a` or
/// `B.hi_a <= A.lo_a`), and `A` can hide `B` only if the eye is strictly on
/// `A`'s side of every separating plane along every axis of `S`:
///
/// ```text
/// A below B along a:  perspective eye_a < A.hi_a,   parallel f_a > 0
/// A above B along a:  perspective eye_a > A.lo_a,   parallel f_a < 0
/// ```
///
/// (if the eye is on `B`'s side of, or on, some separating plane, a ray from
/// the eye through `A` never reaches `B`). Whether the boxes overlap on the
/// screen is not tested, which makes the check stricter than needed: an
/// octree order still passes it, since along the axes where the octree
/// separates the two subtrees the eye is then on `A`'s side of the split
/// plane too.
pub fn is_back_to_front(camera: &Camera, boxes_world: &[([f64; 3], [f64; 3])], order: &[usize]) -> bool {
    let n = boxes_world.len();
    if order.len() != n {
        return false;
    }
    let mut seen = vec![false; n];
    for &i in order {
        if i >= n || std::mem::replace(&mut seen[i], true) {
            return false;
        }
    }
    let eye = Eye::new(camera);
    for (p, &i) in order.iter().enumerate() {
        for &j in &order[p + 1..] {
            match can_hide(&eye, boxes_world[i], boxes_world[j]) {
                None | Some(true) => return false,
                Some(false) => {}
            }
        }
    }
    true
}

/// Whether box `a` can hide box `b` from `eye` (see [`is_back_to_front`]);
/// `None` when the boxes overlap.
fn can_hide(eye: &Eye, a: ([f64; 3], [f64; 3]), b: ([f64; 3], [f64; 3])) -> Option<bool> {
    let mut separated = false;
    let mut hides = true;
    for axis in 0..3 {
        // The eye must be strictly on a's side of every plane between a and b.
        let a_side = if a.1[axis] <= b.0[axis] {
            match eye {
                Eye::Point(e) => e[axis] < a.1[axis],
                Eye::Direction(f) => f[axis] > 0.0,
            }
        } else if b.1[axis] <= a.0[axis] {
            match eye {
                Eye::Point(e) => e[axis] > a.0[axis],
                Eye::Direction(f) => f[axis] < 0.0,
            }
        } else {
            continue;
        };
        separated = true;
        hides &= a_side;
    }
    separated.then_some(hides)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, generate_dims, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, SelectOptions};

    struct Fixture {
        octree: VolumeOctree,
        shape: GridShape,
    }

    fn fixture(size: usize) -> Fixture {
        let volume = generate(Dataset::SheppLogan, size, ScalarType::F32);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        Fixture { octree, shape: *grid.shape() }
    }

    /// The selection at `budget` with bricks of at most 8 cells (larger ones
    /// would hold a 33 or 65 grid in one or eight bricks).
    fn selection(f: &Fixture, budget: usize) -> Vec<NodeId> {
        let options = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(budget, 0.0) };
        let s = select(&f.octree, &options, |_, _| true).unwrap();
        s.bricks.iter().map(|b| b.node).collect()
    }

    fn boxes(f: &Fixture, ids: &[NodeId]) -> Vec<([f64; 3], [f64; 3])> {
        ids.iter()
            .map(|&id| {
                let n = f.octree.node(id);
                (f.shape.world(n.lo.map(|v| v as f64)), f.shape.world(n.hi.map(|v| v as f64)))
            })
            .collect()
    }

    fn cam(position: [f64; 3], focal: [f64; 3], parallel: bool) -> Camera {
        crate::geometry::camera::test_camera(position, focal, parallel.then_some(40.0))
    }

    /// Cameras around a volume centred at `c`: along +-x, +-y, +-z, the 8
    /// diagonals, views with one zero component, both projections.
    fn cameras_around(c: [f64; 3], r: f64) -> Vec<Camera> {
        let mut dirs: Vec<[f64; 3]> = Vec::new();
        for a in 0..3 {
            for s in [-1.0, 1.0] {
                let mut d = [0.0; 3];
                d[a] = s;
                dirs.push(d);
            }
        }
        for o in 0..8 {
            dirs.push([0, 1, 2].map(|a| if o >> a & 1 == 1 { 1.0 } else { -1.0 }));
        }
        dirs.extend([[1.0, 1.0, 0.0], [0.0, -1.0, 2.0], [-3.0, 0.0, 1.0], [1.0, -0.2, 0.7], [-0.3, 0.9, -0.1]]);
        let mut cams = Vec::new();
        for d in dirs {
            let pos = [0, 1, 2].map(|a| c[a] + 3.0 * r * d[a]);
            cams.push(cam(pos, c, false));
            cams.push(cam(pos, c, true));
        }
        cams
    }

    fn check(f: &Fixture, ids: &[NodeId], camera: &Camera) {
        let b = boxes(f, ids);
        let btf = brick_order(camera, &f.octree, &f.shape, ids, true);
        let ftb = brick_order(camera, &f.octree, &f.shape, ids, false);
        assert!(is_back_to_front(camera, &b, &btf), "not back to front for {camera:?}");
        assert_eq!(btf, brick_order(camera, &f.octree, &f.shape, ids, true), "not deterministic");
        let mut rev = ftb.clone();
        rev.reverse();
        assert_eq!(rev, btf, "front to back is not the reverse of back to front");
    }

    fn level_mix(f: &Fixture, ids: &[NodeId]) -> usize {
        let levels: HashSet<usize> = ids.iter().map(|&id| f.octree.node(id).level).collect();
        levels.len()
    }

    #[test]
    fn outside_cameras_at_several_budgets() {
        let f = fixture(65);
        let c = [32.0; 3];
        let mut mixed = false;
        for budget in [5_000, 50_000, 150_000, 600_000, 50_000_000] {
            let ids = selection(&f, budget);
            mixed |= level_mix(&f, &ids) > 1;
            for camera in cameras_around(c, 32.0) {
                check(&f, &ids, &camera);
            }
        }
        assert!(mixed, "no budget gave bricks of mixed sizes");
        // The default largest brick (32 cells): one root brick, then 8.
        for budget in [600_000, 2_000_000] {
            let ids: Vec<NodeId> = select(&f.octree, &SelectOptions::new(budget, 0.0), |_, _| true)
                .unwrap()
                .bricks
                .iter()
                .map(|b| b.node)
                .collect();
            for camera in cameras_around(c, 32.0) {
                check(&f, &ids, &camera);
            }
        }
    }

    #[test]
    fn perspective_cameras_inside_the_volume() {
        let f = fixture(65);
        let ids = selection(&f, 600_000);
        assert!(level_mix(&f, &ids) > 1);
        let b = boxes(&f, &ids);
        // Generic points, points on split planes (32, 16, 8...), on brick
        // corners, on the grid's boundary.
        let positions = [
            [13.3, 20.1, 7.7],
            [32.0, 32.0, 32.0],
            [32.0, 17.5, 40.25],
            [8.0, 16.0, 48.0],
            [0.0, 0.0, 0.0],
            [64.0, 1.0, 63.0],
            [50.5, 50.5, 3.0],
        ];
        let targets = [[60.0, 61.0, 62.0], [0.0, 3.0, 1.0], [32.0, 0.0, 32.0], [10.0, 64.0, 50.0]];
        for p in positions {
            for t in targets {
                let camera = cam(p, t, false);
                check(&f, &ids, &camera);
                // The front-to-back order is not back to front here: a nearer
                // brick would come first.
                let ftb = brick_order(&camera, &f.octree, &f.shape, &ids, false);
                assert!(!is_back_to_front(&camera, &b, &ftb));
            }
        }
    }

    #[test]
    fn axis_views_order_siblings_by_x_and_zero_components_by_child_index() {
        // Parallel view along +x: the eye is on the low side of every x plane
        // and on no side of the y and z planes.
        let f = fixture(33);
        let ids = selection(&f, 10_000_000);
        assert!(ids.len() == 64 && ids.iter().all(|&id| f.octree.node(id).is_leaf), "all 64 leaves expected");
        let camera = cam([-100.0, 16.0, 16.0], [16.0, 16.0, 16.0], true);
        assert_eq!(camera.forward(), [1.0, 0.0, 0.0]);
        let btf = brick_order(&camera, &f.octree, &f.shape, &ids, true);
        check(&f, &ids, &camera);
        let layout = f.octree.layout();
        // Siblings: the 4 with odd x (far) first, then the 4 with even x,
        // each four by child index (= by node id).
        let mut by_parent: HashMap<[usize; 3], Vec<(usize, [usize; 3])>> = HashMap::new();
        for &i in &btf {
            let (_, c) = layout.locate(ids[i]);
            by_parent.entry(c.map(|v| v / 2)).or_default().push((i, c));
        }
        assert_eq!(by_parent.len(), 8);
        for kids in by_parent.values() {
            assert_eq!(kids.len(), 8);
            assert!(kids[..4].iter().all(|k| k.1[0] % 2 == 1) && kids[4..].iter().all(|k| k.1[0] % 2 == 0));
            for half in [&kids[..4], &kids[4..]] {
                assert!(half.windows(2).all(|w| ids[w[0].0] < ids[w[1].0]), "ties not by child index");
            }
        }
    }

    #[test]
    fn the_eight_children_of_the_root_in_rank_order() {
        let f = fixture(33);
        let layout = f.octree.layout();
        let ids: Vec<NodeId> = layout.children(0, [0; 3]).map(|(l, c)| layout.id(l, c)).collect();
        assert_eq!(ids.len(), 8);
        // Looking towards +x+y+z: the eye is on the low side of every plane;
        // rank = number of low axes. Far child 7 first, eye child 0 last.
        let camera = cam([-50.0, -60.0, -70.0], [16.0; 3], true);
        let btf = brick_order(&camera, &f.octree, &f.shape, &ids, true);
        assert_eq!(btf, vec![7, 3, 5, 6, 1, 2, 4, 0]);
        let camera = cam([-50.0, -60.0, -70.0], [16.0; 3], false);
        assert_eq!(brick_order(&camera, &f.octree, &f.shape, &ids, true), vec![7, 3, 5, 6, 1, 2, 4, 0]);
        // Looking towards -x+y, along the z planes: x high is the eye side,
        // z ties: rank = [x high] + [y low].
        let camera = cam([100.0, -100.0, 16.0], [16.0; 3], true);
        let btf = brick_order(&camera, &f.octree, &f.shape, &ids, true);
        assert_eq!(btf, vec![2, 6, 0, 3, 4, 7, 1, 5]);
        // The camera on the root's x split plane, inside: x ties.
        let camera = cam([16.0, 4.0, 4.0], [16.0, 30.0, 31.0], false);
        let btf = brick_order(&camera, &f.octree, &f.shape, &ids, true);
        assert_eq!(btf, vec![6, 7, 2, 3, 4, 5, 0, 1]);
        assert!(is_back_to_front(&camera, &boxes(&f, &ids), &btf));
    }

    #[test]
    fn clipped_boxes_split_on_the_shared_face_not_the_midpoint() {
        // 41 x 33 x 20 samples: the root spans 64 cells, clipped to [0, 40] in
        // x; its children meet at x = 32, not at the box midpoint x = 20.
        let volume = generate_dims(Dataset::SheppLogan, [41, 33, 20], ScalarType::F32);
        let grid = volume.grid(None).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
        // Anisotropic spacing and an offset origin: the planes are compared in world space.
        let shape = GridShape { dims: grid.dims(), spacing: [0.5, 1.0, 2.0], origin: [-3.0, 1.0, 5.0] };
        let f = Fixture { octree, shape };
        for budget in [30_000, 200_000, 10_000_000] {
            let ids = selection(&f, budget);
            let world = |p: [f64; 3]| shape.world(p);
            for p in [[25.0, 10.0, 5.0], [33.0, 20.0, 18.0], [32.0, 16.0, 8.0], [5.0, 30.0, 1.0]] {
                for t in [[0.0, 0.0, 0.0], [40.0, 32.0, 19.0], [40.0, 0.0, 10.0]] {
                    check(&f, &ids, &cam(world(p), world(t), false));
                }
            }
            for camera in cameras_around(world([20.0, 16.0, 9.5]), 40.0) {
                check(&f, &ids, &camera);
            }
        }
    }

    #[test]
    fn the_checker_refuses_wrong_orders() {
        let a = ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
        let b = ([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
        let diagonal = ([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]);
        // Looking along +x: b (higher x) is farther, so it goes first.
        let camera = cam([-10.0, 0.5, 0.5], [5.0, 0.5, 0.5], false);
        assert!(is_back_to_front(&camera, &[a, b], &[1, 0]));
        assert!(!is_back_to_front(&camera, &[a, b], &[0, 1]));
        // Parallel, same.
        let camera = cam([-10.0, 0.5, 0.5], [5.0, 0.5, 0.5], true);
        assert!(is_back_to_front(&camera, &[a, b], &[1, 0]));
        assert!(!is_back_to_front(&camera, &[a, b], &[0, 1]));
        // Looking along +y: a and b side by side, either order.
        let camera = cam([1.0, -10.0, 0.5], [1.0, 5.0, 0.5], true);
        assert!(is_back_to_front(&camera, &[a, b], &[0, 1]) && is_back_to_front(&camera, &[a, b], &[1, 0]));
        // Eye between the diagonal boxes' x and y planes' sides: neither hides the other.
        let camera = cam([5.0, -5.0, 0.5], [0.0, 0.0, 0.5], false);
        assert!(is_back_to_front(&camera, &[a, diagonal], &[0, 1]));
        assert!(is_back_to_front(&camera, &[a, diagonal], &[1, 0]));
        // Overlap, repeats, missing indices.
        let overlapping = ([0.5, 0.5, 0.5], [1.5, 1.5, 1.5]);
        assert!(!is_back_to_front(&camera, &[a, overlapping], &[0, 1]));
        assert!(!is_back_to_front(&camera, &[a, b], &[0, 0]));
        assert!(!is_back_to_front(&camera, &[a, b], &[0]));
        assert!(!is_back_to_front(&camera, &[a, b], &[0, 2]));
    }

    #[test]
    fn duplicates_nested_nodes_and_empty_selections() {
        let f = fixture(33);
        let camera = cam([-40.0, 5.0, 70.0], [16.0; 3], false);
        assert!(brick_order(&camera, &f.octree, &f.shape, &[], true).is_empty());
        let root = f.octree.root();
        let kids = f.octree.children(root);
        let ids = vec![kids[3], root, kids[3], kids[0]];
        let btf = brick_order(&camera, &f.octree, &f.shape, &ids, true);
        let mut sorted = btf.clone();
        sorted.sort();
        assert_eq!(sorted, vec![0, 1, 2, 3]);
        assert_eq!(btf[0], 1, "the ancestor first");
        let p = btf.iter().position(|&i| i == 0).unwrap();
        assert_eq!(btf[p + 1], 2, "duplicates together, by index");
    }
}
