//! Properties of the Volume Octree on random and hand-made volumes, through
//! the public API. Every tree built here is validated.

use hybrid_octree::grid::{Grid, GridShape, Samples};
use hybrid_octree::octree::{brute_force, BuildOptions, NodeId, VolumeOctree};
use proptest::prelude::*;

fn build(grid: &Grid<'_>, leaf_size: usize) -> VolumeOctree {
    let octree = VolumeOctree::build(grid, &BuildOptions { leaf_size }).expect("build");
    octree.validate().expect("validate");
    octree
}

fn all_ids(octree: &VolumeOctree) -> Vec<NodeId> {
    (0..octree.layout().node_slots() as u32).map(NodeId).collect()
}

/// Random dims in 2..=max per axis, random f32 values (some plateaus of equal values).
fn volume(max: usize) -> impl Strategy<Value = ([usize; 3], Vec<f32>)> {
    (2..=max, 2..=max, 2..=max).prop_flat_map(|(x, y, z)| {
        let n = x * y * z;
        (Just([x, y, z]), prop::collection::vec(prop_oneof![Just(0.0f32), Just(1.0f32), -100.0f32..100.0], n))
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    /// validate() holds, errors never increase with p, and the fast nodal
    /// errors equal the brute-force definition exactly, in every node slot.
    #[test]
    fn fast_errors_equal_brute_force((dims, data) in volume(19), leaf_log2 in 1u32..4) {
        let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
        let octree = build(&grid, 1 << leaf_log2);
        for id in all_ids(&octree) {
            let node = octree.node(id);
            prop_assert!(node.errors.windows(2).all(|w| w[1] <= w[0]));
            prop_assert_eq!(node.errors.to_vec(), brute_force::nodal_errors(&grid, &octree, id), "node {:?}", id);
        }
    }

    /// Any trilinear field a + bx + cy + dz + exy + fyz + gxz + hxyz has all
    /// errors 0 when the grid needs no padding (2^m + 1 samples per axis).
    /// The squared errors summed up the tree equal the definition, node by
    /// node (to f32 rounding and summation order).
    #[test]
    fn squared_errors_equal_brute_force((dims, data) in volume(19), leaf_log2 in 1u32..4) {
        let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
        let octree = build(&grid, 1 << leaf_log2);
        for id in all_ids(&octree) {
            let node = octree.node(id);
            let brute = brute_force::squared_errors(&grid, &octree, id);
            prop_assert_eq!(node.squared_errors.len(), brute.len());
            for (p, (&fast, &slow)) in node.squared_errors.iter().zip(&brute).enumerate() {
                prop_assert!((fast as f64 - slow).abs() <= 1e-5 * slow + 1e-9, "node {:?} p {}: {} vs {}", id, p, fast, slow);
            }
        }
    }

    #[test]
    fn trilinear_field_has_zero_errors(m in 1u32..5, c in prop::array::uniform8(-4i32..4)) {
        let n = (1usize << m) + 1;
        let mut data = Vec::with_capacity(n * n * n);
        for z in 0..n { for y in 0..n { for x in 0..n {
            let (x, y, z) = (x as f64, y as f64, z as f64);
            let c = c.map(f64::from);
            data.push(c[0] + c[1]*x + c[2]*y + c[3]*z + c[4]*x*y + c[5]*y*z + c[6]*x*z + c[7]*x*y*z);
        }}}
        let grid = Grid::scalar(Samples::F64(&data), [n; 3]).unwrap();
        let octree = build(&grid, 2);
        prop_assert!(octree.node(octree.root()).is_homogeneous());
        prop_assert_eq!(octree.stats().node_count, 1);
        prop_assert!(octree.errors_all_zero());
    }

    /// The cut at any tolerance tiles the grid exactly once and respects the tolerance.
    #[test]
    fn cut_tiles_the_grid((dims, data) in volume(23), tol in 0.0f64..1.0) {
        let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
        let octree = build(&grid, 4);
        let cut = octree.cut(tol).unwrap();
        let mut cells = 0usize;
        for id in &cut {
            let n = octree.node(*id);
            prop_assert!(n.is_terminal() || f64::from(n.error(0)) <= tol);
            cells += (0..3).map(|a| n.hi[a] - n.lo[a]).product::<usize>();
        }
        prop_assert_eq!(cells, (0..3).map(|a| dims[a] - 1).product::<usize>());
    }
}

trait AllZero {
    fn errors_all_zero(&self) -> bool;
}
impl AllZero for VolumeOctree {
    fn errors_all_zero(&self) -> bool {
        all_ids(self).into_iter().all(|id| self.node(id).errors.iter().all(|&e| e == 0.0))
    }
}

#[test]
fn constant_field_is_one_terminal_node() {
    for dims in [[2, 2, 2], [17, 17, 17], [40, 7, 90]] {
        let data = vec![42u16; dims[0] * dims[1] * dims[2]];
        let grid = Grid::scalar(Samples::U16(&data), dims).unwrap();
        let octree = build(&grid, 4);
        let s = octree.stats();
        assert_eq!((s.node_count, s.terminal_count, s.homogeneous_count), (1, 1, 1), "{dims:?}");
        assert_eq!(s.value_range, (42.0, 42.0));
        assert_eq!(octree.cut(0.0).unwrap(), vec![octree.root()]);
    }
}

#[test]
fn every_scalar_type_gives_the_same_tree() {
    let dims = [21, 18, 13];
    let n = dims[0] * dims[1] * dims[2];
    let base: Vec<u8> = (0..n).map(|i| ((i * 37 + i / 7 * 11) % 100) as u8).collect();
    let f64s: Vec<f64> = base.iter().map(|&v| v as f64).collect();
    let reference = build(&Grid::scalar(Samples::F64(&f64s), dims).unwrap(), 4);
    macro_rules! check {
        ($variant:ident, $t:ty) => {{
            let v: Vec<$t> = base.iter().map(|&x| x as $t).collect();
            let o = build(&Grid::scalar(Samples::$variant(&v), dims).unwrap(), 4);
            assert_eq!(o.stats().node_count, reference.stats().node_count, stringify!($t));
            for id in all_ids(&o) {
                assert_eq!(o.node(id).errors, reference.node(id).errors, stringify!($t));
            }
        }};
    }
    check!(U8, u8);
    check!(I8, i8);
    check!(U16, u16);
    check!(I16, i16);
    check!(U32, u32);
    check!(I32, i32);
    check!(F32, f32);
}

#[test]
fn multi_component_reads_only_the_chosen_component() {
    let dims = [9, 9, 9];
    let n = 729;
    let mut interleaved = Vec::with_capacity(n * 2);
    let mut second = Vec::with_capacity(n);
    for i in 0..n {
        interleaved.push(f32::NAN); // an unused component may hold anything
        let v = ((i * 13) % 17) as f32;
        interleaved.push(v);
        second.push(v);
    }
    let shape = GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] };
    let a = build(&Grid::new(Samples::F32(&interleaved), shape, 2, Some(1)).unwrap(), 4);
    let b = build(&Grid::scalar(Samples::F32(&second), dims).unwrap(), 4);
    assert_eq!(a, b);
}

#[test]
fn bit_identical_on_one_and_many_threads() {
    let dims = [67, 50, 45];
    let data: Vec<f32> = (0..dims[0] * dims[1] * dims[2])
        .map(|i| ((i as f32 * 0.618).sin() * 100.0 + (i % 97) as f32).round())
        .collect();
    let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| build(&grid, 8))
    };
    let one = run(1);
    for threads in [2, 3, 8] {
        let many = run(threads);
        assert_eq!(many, one, "{threads} threads");
    }
}

#[test]
fn cancelled_build_returns_nothing() {
    let dims = [65, 65, 65];
    let data = vec![1.0f32; 65 * 65 * 65];
    let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
    let mut calls = 0;
    let r = VolumeOctree::build_with_progress(&grid, &BuildOptions { leaf_size: 2 }, &mut |f| {
        calls += 1;
        assert!((0.0..=1.0).contains(&f));
        false
    });
    assert_eq!(r.unwrap_err(), hybrid_octree::Error::Cancelled);
    assert_eq!(calls, 1);
}

#[test]
fn extreme_values_stay_finite_and_bounded() {
    let dims = [17, 17, 17];
    let n = 17 * 17 * 17;
    let data: Vec<f64> = (0..n).map(|i| if i % 3 == 0 { f64::MAX / 4.0 } else { -f64::MAX / 4.0 }).collect();
    let grid = Grid::scalar(Samples::F64(&data), dims).unwrap();
    let octree = build(&grid, 4);
    assert!(octree.node(octree.root()).error(0) <= 1.0);
    let tiny: Vec<f64> = (0..n).map(|i| 1.0 + (i % 2) as f64 * f64::EPSILON).collect();
    let octree = build(&Grid::scalar(Samples::F64(&tiny), dims).unwrap(), 4);
    assert!(octree.node(octree.root()).error(0) > 0.0);
}

#[test]
fn memory_is_small_against_the_input() {
    // 129^3 f32 (8.6 MB): the octree must stay far below 5 % of the input.
    let dims = [129; 3];
    let data: Vec<f32> = (0..129usize.pow(3)).map(|i| ((i * 7919) % 1000) as f32).collect();
    let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
    let octree = build(&grid, 16);
    let ratio = octree.octree_bytes() as f64 / grid.input_bytes() as f64;
    assert!(ratio < 0.05, "octree is {:.2} % of the input", ratio * 100.0);
}
