//! Texture-budget selection through the public API, property-tested: the
//! cut covers the grid exactly once, never exceeds the budget, and is
//! deterministic; the DrawList orders every selected brick once.

use hybrid_octree::camera::Camera;
use hybrid_octree::grid::{Grid, Samples};
use hybrid_octree::octree::{BuildOptions, VolumeOctree};
use hybrid_octree::plan::{draw_list, Scene};
use hybrid_octree::select::{select, Roi, SelectOptions};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    #[test]
    fn cut_tiles_once_within_budget_deterministically(
        dims in prop::array::uniform3(2usize..24),
        seed in any::<u64>(),
        budget in 1usize..200_000,
        tolerance in 0.0f64..0.5,
        roi in proptest::option::of((prop::array::uniform3(0.0f64..24.0), 0.5f64..10.0)),
        brick in 1u32..6,
    ) {
        let n = dims[0] * dims[1] * dims[2];
        let mut state = seed | 1;
        let data: Vec<f32> = (0..n).map(|i| {
            state ^= state << 13; state ^= state >> 7; state ^= state << 17;
            // Smooth ramp plus sparse spikes: some nodes constant, some not.
            (i % dims[0]) as f32 + if state % 7 == 0 { (state % 100) as f32 } else { 0.0 }
        }).collect();
        let grid = Grid::scalar(Samples::F32(&data), dims).unwrap();
        let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let options = SelectOptions {
            roi: roi.map(|(center, radius)| Roi { center, radius }),
            max_brick_log2: brick,
            ..SelectOptions::new(budget, tolerance)
        };
        let s = select(&octree, &options, |_, _| true).unwrap();
        let again = select(&octree, &options, |_, _| true).unwrap();
        prop_assert_eq!(&s, &again);
        // Within the budget, unless even the coarsest brick does not fit (then one brick and a warning).
        if s.texture_bytes > budget {
            prop_assert_eq!(s.bricks.len(), 1);
            prop_assert!(s.warning.is_some());
        }
        prop_assert_eq!(s.texture_bytes, s.bricks.iter().map(|b| b.bytes).sum::<usize>());
        // Every cell in exactly one brick.
        let c = [dims[0] - 1, dims[1] - 1, dims[2] - 1];
        let mut count = vec![0u8; c[0] * c[1] * c[2]];
        for b in &s.bricks {
            prop_assert_eq!(b.texels, [0, 1, 2].map(|a| (b.hi[a] - b.lo[a]).div_ceil(b.stride) + 1));
            for z in b.lo[2]..b.hi[2] { for y in b.lo[1]..b.hi[1] { for x in b.lo[0]..b.hi[0] {
                count[x + c[0] * (y + c[1] * z)] += 1;
            }}}
        }
        prop_assert!(count.iter().all(|&k| k == 1));
        // The DrawList holds every brick once, back to front.
        let shape = grid.shape();
        let camera = Camera::around(shape.world([0.0; 3]), shape.world(dims.map(|d| (d - 1) as f64)), 40.0, 25.0, false).unwrap();
        let list = draw_list(&octree, shape, &s, &camera, &Scene { surface: None, surface_opacity: 1.0, shading: None, gradient_opacity: None, transfer_2d: None, region: None , blend: Default::default() }, None).unwrap();
        let mut nodes: Vec<_> = list.bricks.iter().map(|b| b.brick.node).collect();
        nodes.sort_unstable();
        prop_assert_eq!(nodes, s.bricks.iter().map(|b| b.node).collect::<Vec<_>>());
    }
}
