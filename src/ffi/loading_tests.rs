//! A store's bricks loaded in the background through the bridge: the
//! stand-ins drawn until they are read are the same nodes coarser, with the
//! in-memory texels of that stride; once read, every brick is the
//! in-memory brick bit for bit.

use super::loading::{STAND_IN_LEVELS, UPLOAD_SHARE};
use super::store::{build_octree_from_store, open_store};
use super::store_tests::{field, in_memory_twin, Tmp};
use super::test_support::{ball_camera, build_volume_octree, select_desc};
use super::{GridDesc, ScalarType};
use crate::data::grid::ScalarType as Type;
use crate::datasets::{generate, Dataset};
use crate::octree::{BuildOptions, VolumeOctree};
use crate::render::texture::{brick_texels_f32_bordered_into, brick_texels_f32_into};
use crate::store::{write_store, WriteOptions};
use std::time::{Duration, Instant};

/// The 64^3 f32 phantom's samples, their description and a store of them
/// with leaves of 16 (what `convert` writes): budgets of a few hundred kB
/// select dozens of bricks at several strides.
fn phantom(name: &str) -> (Vec<u8>, GridDesc, Tmp) {
    let v = generate(Dataset::SheppLogan, 64, Type::F32);
    let desc = GridDesc {
        scalar_type: ScalarType::F32,
        dims: v.shape.dims,
        spacing: v.shape.spacing,
        origin: v.shape.origin,
        components: 1,
        component: -1,
    };
    let tmp = Tmp::new(name);
    let grid = v.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 16 }).unwrap();
    write_store(&tmp.0, &grid, &octree, &WriteOptions::default(), &mut |_, _| {}).unwrap();
    (v.samples.as_bytes().to_vec(), desc, tmp)
}

/// The values' bits: texels compared exactly, NaN included.
fn bits(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn stand_ins_are_drawn_until_the_bricks_are_read() {
    let (data, desc, tmp) = phantom("loading");
    let store = open_store(tmp.0.to_str().unwrap()).unwrap();
    let octree = build_octree_from_store(&store, 16).unwrap();
    let in_memory = build_volume_octree(&data, &desc, 16).unwrap();
    let grid = super::grid::grid_of(&data, &desc).unwrap();
    // (A bordered data-space selection of this phantom is one brick at every
    // budget tried; the mapper's test draws bordered stand-ins, shaded.)
    for (bordered, budget, texel_format) in [(false, 500_000, 0), (false, 2_000_000, 4)] {
        // The phantom's low values transparent, as in the mapper's tests.
        let opacity_points = vec![0.0, 0.0, 0.15, 0.0, 0.3, 0.08, 1.0, 0.5];
        let options =
            super::SelectDesc { gradient_border: bordered, opacity_points, texel_format, ..select_desc(budget) };
        let (s, m) = (octree.select_bricks(&options).unwrap(), in_memory.select_bricks(&options).unwrap());
        let selected = s.selection.bricks.clone();
        let loads = |b: &crate::plan::select::Brick| b.p > 0;
        let expected = selected.iter().filter(|b| loads(b)).count();
        assert!(expected > 1, "bricks to load: {expected} of {}", selected.len());

        // The first frame: every brick to load is drawn by its stand-in.
        let first = s.plan_loading(&octree, &store, &[], &[], usize::MAX).unwrap();
        assert_eq!((first.stand_ins, first.loaded), (expected, 0));
        let list = s.draw_list(&octree, &ball_camera(), 0.0).unwrap();
        let drawn: Vec<_> = (0..).map_while(|i| s.selected_brick(i).ok()).collect();
        let inside = |b: &crate::plan::select::Brick, d: &crate::plan::select::Brick| {
            (0..3).all(|a| d.lo[a] <= b.lo[a] && b.hi[a] <= d.hi[a])
        };
        // Each selected brick lies in one drawn brick: itself while it
        // neither loads nor is at p = 0, else a stand-in (merged up the
        // octree) no coarser than its own.
        for (i, b) in selected.iter().enumerate() {
            let holders: Vec<_> = drawn.iter().filter(|d| inside(b, d)).collect();
            assert_eq!(holders.len(), 1, "brick {i} in {} drawn bricks", holders.len());
            let d = holders[0];
            if loads(b) || b.p == 0 {
                assert!(d.stride <= b.stride << b.p.min(STAND_IN_LEVELS), "brick {i}: {d:?}");
            } else {
                assert_eq!(d, b, "brick {i}");
            }
        }
        assert!(drawn.len() < expected, "{} drawn for {expected} loading: the stand-ins merge", drawn.len());
        for (i, d) in drawn.iter().enumerate() {
            for e in &drawn[i + 1..] {
                assert!((0..3).any(|a| d.hi[a] <= e.lo[a] || e.hi[a] <= d.lo[a]), "{d:?} overlaps {e:?}");
            }
        }
        let mut drawn_bytes = 0;
        for (i, d) in drawn.iter().enumerate() {
            drawn_bytes += d.bytes;
            if let Some(at) = list.brick.iter().position(|&j| j == i) {
                assert_eq!(list.stride[at], d.stride, "the DrawList draws the stand-in");
            }
            // Its texels: the in-memory texels of the stand-in's stride.
            let border = usize::from(bordered);
            let count = d.texels.iter().map(|n| n + 2 * border).product::<usize>();
            let (mut got, mut want) = (vec![0f32; count], vec![0f32; count]);
            s.brick_texels_from_store(&octree, &store, i, bordered, &mut got, &mut []).unwrap();
            if bordered {
                brick_texels_f32_bordered_into(&grid, d, &mut want).unwrap();
            } else {
                brick_texels_f32_into(&grid, d, &mut want).unwrap();
            }
            assert_eq!(bits(&got), bits(&want), "drawn brick {i}");
        }
        assert!(drawn_bytes < s.selection.texture_bytes, "stand-ins take fewer bytes");

        // Later frames: each uploads at most 1/UPLOAD_SHARE of the
        // selection's bytes of read bricks (drawn as themselves, resident
        // from then on), the others stand in one more frame.
        let start = Instant::now();
        let cap = s.selection.texture_bytes / UPLOAD_SHARE;
        let mut resident: Vec<(u32, usize)> = Vec::new();
        let mut frames = 0;
        loop {
            let (nodes, strides): (Vec<u32>, Vec<usize>) = resident.iter().copied().unzip();
            let summary = s.plan_loading(&octree, &store, &nodes, &strides, usize::MAX).unwrap();
            frames += 1;
            let drawn: Vec<_> = (0..).map_while(|i| s.selected_brick(i).ok()).collect();
            let uploads: Vec<_> = drawn
                .iter()
                .filter(|d| d.p > 0 && selected.contains(d) && !resident.contains(&(d.node.0, d.stride)))
                .collect();
            let bytes = uploads.iter().map(|d| d.bytes).sum::<usize>();
            assert!(bytes <= cap || uploads.len() == 1, "frame {frames} uploads {bytes} bytes, over {cap}");
            assert_eq!(summary.loaded, uploads.len(), "frame {frames}: the bricks it uploads");
            resident.extend(uploads.iter().map(|d| (d.node.0, d.stride)));
            if summary.stand_ins == 0 {
                break;
            }
            assert!(start.elapsed() < Duration::from_secs(20), "still loading after 20 s: {summary:?}");
            std::thread::sleep(Duration::from_millis(2));
        }
        let loading_bytes: usize = selected.iter().filter(|b| loads(b)).map(|b| b.bytes).sum();
        assert!(frames * cap >= loading_bytes && frames > 1, "{frames} frames for {loading_bytes} bytes");
        assert_eq!(resident.len(), expected, "every brick to load uploaded once");
        // Read again without resident textures, every brick is ready.
        let later = loop {
            let summary = s.plan_loading(&octree, &store, &[], &[], usize::MAX).unwrap();
            if summary.queued == 0 {
                break summary;
            }
            assert!(start.elapsed() < Duration::from_secs(20), "still loading after 20 s: {summary:?}");
            std::thread::sleep(Duration::from_millis(2));
        };
        assert_eq!(later.stand_ins + later.loaded, expected);
        assert!(later.waiting_bytes > 0 && later.bytes_read > 0);
        s.draw_selected();
        for (i, b) in selected.iter().enumerate() {
            assert_eq!(&s.selected_brick(i).unwrap(), b);
            let count = b.texels.iter().map(|n| n + 2 * usize::from(bordered)).product::<usize>();
            let (mut got, mut want) = (vec![0f32; count], vec![0f32; count]);
            s.brick_texels_from_store(&octree, &store, i, bordered, &mut got, &mut []).unwrap();
            if bordered {
                m.brick_texels_bordered(&data, &desc, i, &mut want).unwrap();
            } else {
                m.brick_texels(&data, &desc, i, &mut want).unwrap();
            }
            assert_eq!(bits(&got), bits(&want), "brick {i}");
        }

        // Resident textures are not loaded again; draw_selected drops the stand-ins.
        let nodes: Vec<u32> = selected.iter().map(|b| b.node.0).collect();
        let strides: Vec<usize> = selected.iter().map(|b| b.stride).collect();
        let resident = s.plan_loading(&octree, &store, &nodes, &strides, usize::MAX).unwrap();
        assert_eq!((resident.stand_ins, resident.loaded, resident.queued, resident.waiting_bytes), (0, 0, 0, 0));
        assert!(s.plan_loading(&octree, &store, &[], &[], usize::MAX).unwrap().stand_ins > 0);
        s.draw_selected();
        assert!(selected.iter().enumerate().all(|(i, b)| &s.selected_brick(i).unwrap() == b));
        // Nothing asked for: the reader lets every brick go (the next selection starts afresh).
        s.plan_loading(&octree, &store, &nodes, &strides, usize::MAX).unwrap();
        s.draw_selected();
    }
}

#[test]
fn maximum_intensity_reads_its_bricks_itself() {
    let (data, desc, tmp) = phantom("loading-mip");
    let store = open_store(tmp.0.to_str().unwrap()).unwrap();
    let octree = build_octree_from_store(&store, 16).unwrap();
    let in_memory = build_volume_octree(&data, &desc, 16).unwrap();
    // At a budget where every brick is at full resolution, as a store's MIP needs.
    let options = super::SelectDesc { blend_mode: 1, ..select_desc(1 << 30) };
    let (s, m) = (octree.select_bricks(&options).unwrap(), in_memory.select_bricks(&options).unwrap());
    let summary = s.plan_loading(&octree, &store, &[], &[], usize::MAX).unwrap();
    assert_eq!((summary.stand_ins, summary.queued), (0, 0), "no stand-in: it would need peaks");
    for (i, b) in s.selection.bricks.iter().enumerate() {
        assert_eq!(&s.selected_brick(i).unwrap(), b);
        let count = b.texels.iter().product::<usize>();
        let (mut got, mut want) = (vec![0f32; count], vec![0f32; count]);
        s.brick_texels_from_store(&octree, &store, i, false, &mut got, &mut []).unwrap();
        m.brick_texels(&data, &desc, i, &mut want).unwrap();
        assert_eq!(bits(&got), bits(&want), "brick {i}");
    }
}

#[test]
fn loading_is_refused_for_another_octree_or_mismatched_textures() {
    let (_data, _desc, tmp) = field("loading-refused");
    let store = open_store(tmp.0.to_str().unwrap()).unwrap();
    let octree = build_octree_from_store(&store, 8).unwrap();
    let s = octree.select_bricks(&select_desc(6000)).unwrap();
    let e = s.plan_loading(&octree, &store, &[1, 2], &[1], 1 << 20).unwrap_err();
    assert!(e.contains("resident textures' strides"), "{e}");
    let twin = in_memory_twin();
    let e = s.plan_loading(&twin, &store, &[], &[], 1 << 20).unwrap_err();
    assert!(e.contains("another octree"), "{e}");
}
