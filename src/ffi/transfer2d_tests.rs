//! The bridge's 2D transfer function: the selection reads it (nodes
//! transparent at every gradient skipped, the border counted), its
//! DrawLists classify by it (effect and axes in the output), bad tables are
//! refused with the reason, and a selection without one does none of it.

use super::test_support::{as_bytes, build_volume_octree, select_desc};
use super::{CameraDesc, GridDesc, ScalarType, SelectDesc};

const N: usize = 33;

/// A cone `1 - r / 20` about a point inside, on an anisotropic grid (mean spacing 1).
fn data() -> Vec<f32> {
    (0..N * N * N)
        .map(|i| {
            let (x, y, z) = ((i % N) as f32 - 16.0, ((i / N) % N) as f32 - 14.0, (i / (N * N)) as f32 - 18.0);
            1.0 - (x * x + y * y + z * z).sqrt() / 20.0
        })
        .collect()
}

fn desc() -> GridDesc {
    GridDesc {
        scalar_type: ScalarType::F32,
        dims: [N; 3],
        spacing: [1.0, 1.5, 0.5],
        origin: [-3.0, 2.0, 5.0],
        components: 1,
        component: -1,
    }
}

fn camera() -> CameraDesc {
    CameraDesc {
        position: [60.0, -40.0, 80.0],
        focal_point: [13.0, 23.0, 13.0],
        view_up: [0.0, 0.0, 1.0],
        parallel: false,
        parallel_scale: 1.0,
        view_angle: 30.0,
    }
}

/// A VTK-style table: alpha 0.3 for values in the upper half of the range
/// (columns 8..16 of 16), every gradient row.
fn upper_half() -> Vec<f32> {
    (0..16 * 8).flat_map(|k| if k % 16 >= 8 { [1.0, 0.5, 0.2, 0.3] } else { [0.0; 4] }).collect()
}

#[test]
fn the_selection_and_its_draw_lists_read_the_table() {
    let d = data();
    let h = build_volume_octree(as_bytes(&d), &desc(), 4).unwrap();
    let camera = camera();
    // A budget below the root at full resolution: the selection splits it.
    let plain = h.select_bricks(&select_desc(100_000)).unwrap();
    let plain_list = plain.draw_list(&h, &camera, 1.0).unwrap();
    assert_eq!(plain_list.effects, "");
    assert_eq!(plain_list.transfer_2d_axes, [0.0; 3]);
    let with = SelectDesc {
        transfer_2d_size: [16, 8],
        transfer_2d_rgba: upper_half(),
        transfer_2d_range: [0.0, 1.0],
        ..select_desc(100_000)
    };
    let s = h.select_bricks(&with).unwrap();
    let summary = s.summary().unwrap();
    assert!(summary.skipped > 0, "nodes below half the range are transparent at every gradient");
    assert_eq!(plain.summary().unwrap().skipped, 0);
    // Every brick kept reads a texel of alpha > 0 at some gradient.
    let t = super::transfer2d::vtk_transfer_2d(&with, &h.shape).unwrap().unwrap();
    for b in &s.selection.bricks {
        let n = h.volume().node(b.node);
        assert!(!t.is_transparent_over(n.min, n.max), "[{}, {}]", n.min, n.max);
        assert!(b.bytes == 4 * b.texels.iter().map(|n| n + 2).product::<usize>(), "bordered for the gradient");
    }
    let list = s.draw_list(&h, &camera, 1.0).unwrap();
    assert_eq!(list.effects, "transfer-2d");
    assert!(list.gradients);
    // VTK's axes: the range given, a quarter of it per mean spacing (1).
    assert_eq!(list.transfer_2d_axes, [0.0, 1.0, 0.25]);
    // Under MIP the 1D function classifies: no effect.
    let mip = h.select_bricks(&SelectDesc { blend_mode: 1, ..with }).unwrap();
    assert_eq!(mip.draw_list(&h, &camera, 1.0).unwrap().effects, "");
}

#[test]
fn bad_tables_are_refused_with_the_reason() {
    let d = data();
    let h = build_volume_octree(as_bytes(&d), &desc(), 4).unwrap();
    let err = |size: [usize; 2], rgba: Vec<f32>, range: [f64; 2]| {
        let d = SelectDesc {
            transfer_2d_size: size,
            transfer_2d_rgba: rgba,
            transfer_2d_range: range,
            ..select_desc(1 << 20)
        };
        h.select_bricks(&d).map(|_| ()).unwrap_err().to_string()
    };
    assert!(err([1 << 20, 1 << 20], vec![], [0.0, 1.0]).contains("1 to 4096"));
    assert!(err([0, 3], vec![], [0.0, 1.0]).contains("1 to 4096"));
    assert!(err([2, 2], vec![0.0; 15], [0.0, 1.0]).contains("15 values for a 2 x 2 image"));
    assert!(err([1, 1], vec![0.0, 0.0, f32::NAN, 0.0], [0.0, 1.0]).contains("texel (0, 0)"));
    assert!(err([1, 1], vec![0.0; 4], [f64::NAN, 1.0]).contains("scalar range"));
}
