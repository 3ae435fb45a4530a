//! The Slice blend mode: the compositor executing the planner's DrawList
//! against the reference caster on the same plane, the selection leaving
//! out the nodes the plane misses, bad planes refused, and no slice work
//! in a scene that does not ask for it.

use super::compositor::composite;
use super::metrics::compare;
use super::reference::{reference_blend, ReferenceOptions};
use crate::data::grid::{GridShape, ScalarType};
use crate::datasets::{generate, Dataset};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::select::{select, SelectOptions, Selection};
use crate::plan::{draw_list, Blend, BlendMode, DrawList, Scene, SlicePlane};
use crate::transfer::lighting::{Lighting, Material};
use crate::transfer::TransferFunction;

/// Colour and opacity over the whole range, opaque at the top: a slice
/// shows every value it crosses (its opacity is not corrected).
fn tf() -> TransferFunction {
    TransferFunction::new(
        vec![(0.0, [0.2, 0.4, 1.0]), (0.5, [1.0, 0.9, 0.3]), (1.0, [1.0, 0.3, 0.2])],
        vec![(0.0, 0.0), (0.15, 0.3), (1.0, 1.0)],
    )
    .unwrap()
}

/// An oblique plane through the 33^3 grid's centre.
fn oblique() -> SlicePlane {
    SlicePlane::new([16.0, 15.0, 17.0], [0.4, -0.5, 0.75]).unwrap()
}

fn selection(octree: &VolumeOctree, shape: &GridShape, blend: &Blend, budget: usize, border: bool) -> Selection {
    let tf = tf();
    let options = SelectOptions {
        slice: blend.slice.map(|p| p.to_index(shape)),
        gradient_border: border,
        ..SelectOptions::new(budget, 0.0)
    };
    select(octree, &options, |a, b| blend.visible(a, b, &|a, b| !tf.is_transparent_over(a, b))).unwrap()
}

fn list(octree: &VolumeOctree, shape: &GridShape, s: &Selection, blend: Blend, shading: Option<&Lighting>) -> DrawList {
    let camera = Camera::around([0.0; 3], [32.0; 3], 35.0, 25.0, false).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading,
        gradient_opacity: None,
        blend,
        region: None,
        transfer_2d: None,
    };
    draw_list(octree, shape, s, &camera, &scene, None).unwrap()
}

/// At the full budget (the full-resolution field: stride 1, and stride 4
/// for constant nodes) the bricks give the plane's point the reference's
/// trilinear value: unshaded RMSE below 1e-5 (measured 5e-9); shaded below
/// 0.02 (measured 0.0127: a constant stride-4 brick takes its gradient one
/// texel, 4 samples, away, the reference one sample away, so the normals
/// near its faces differ). At budgets that mix strides 1 to 8 (15 kB
/// unshaded, 65 kB shaded with the gradient border), RMSE below 0.03
/// (measured 0.0155 unshaded, 0.0199 shaded), while the slice's picture is
/// 0.049 (0.035 shaded) from a transparent one; unshaded, the strides' error
/// stays below half of that.
#[test]
fn slice_compositor_matches_the_reference() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let (lo, hi) = octree.value_range();
    let blend = Blend::slice(oblique(), [lo, hi]).unwrap();
    let headlight = Lighting::headlight(Material::default());
    for shading in [None, Some(&headlight)] {
        let border = shading.is_some();
        let budgets = if border { [(1usize << 30, 0.02), (65_000, 0.03)] } else { [(1 << 30, 1e-5), (15_000, 0.03)] };
        for (budget, bound) in budgets {
            let s = selection(&octree, &shape, &blend, budget, border);
            let strides: std::collections::BTreeSet<usize> = s.bricks.iter().map(|b| b.stride).collect();
            let l = list(&octree, &shape, &s, blend, shading);
            let shaded = if border { "volume-slice-shaded" } else { "volume-slice" };
            assert_eq!(l.plan.passes, vec![shaded.to_string()]);
            let image = composite(&grid, &l, &tf(), 64, 64, None).unwrap();
            let options = ReferenceOptions { lighting: shading, ..ReferenceOptions::default() };
            let truth = reference_blend(&grid, &tf(), &l.camera, 64, 64, &options, &blend).unwrap();
            let m = compare(&image, &truth).unwrap();
            let empty = crate::render::image::Image { width: 64, height: 64, rgba: vec![[0.0; 4]; 64 * 64] };
            let shown = compare(&truth, &empty).unwrap();
            eprintln!(
                "budget {budget} ({} bytes), strides {strides:?}, shaded {border}: {m:?}, empty {:.4}",
                s.texture_bytes, shown.rmse
            );
            if budget < 1 << 20 {
                assert!(strides.len() >= 2 && strides.iter().any(|&s| s > 1), "mixed strides: {strides:?}");
            } else {
                assert_eq!(s.estimated_error, 0.0, "the full-resolution field");
            }
            assert!(m.rmse < bound, "budget {budget}, shaded {border}: {m:?}");
            assert!(shown.rmse > 0.03, "the slice must show: {shown:?}");
            assert!(border || m.rmse < shown.rmse / 2.0, "unshaded, strides show little: {m:?} vs {shown:?}");
        }
    }
}

/// Every selected node's box meets the plane; the nodes it misses are left
/// out (skipped), so a slice spends far less texture than Composite; a
/// plane beside the volume selects nothing and the plan has no volume pass.
#[test]
fn the_selection_spends_texture_on_the_nodes_the_plane_cuts_only() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let (lo, hi) = octree.value_range();
    let plane = oblique();
    let slice = selection(&octree, &shape, &Blend::slice(plane, [lo, hi]).unwrap(), 1 << 30, false);
    let composite = selection(&octree, &shape, &Blend::new(BlendMode::Composite, [lo, hi]), 1 << 30, false);
    assert!(!slice.bricks.is_empty());
    for b in &slice.bricks {
        let (bl, bh) = (shape.world(b.lo.map(|v| v as f64)), shape.world(b.hi.map(|v| v as f64)));
        assert!(plane.cuts_box(bl, bh), "{b:?} is not on the plane");
    }
    let missed = composite
        .bricks
        .iter()
        .filter(|b| !plane.cuts_box(shape.world(b.lo.map(|v| v as f64)), shape.world(b.hi.map(|v| v as f64))));
    assert!(missed.count() > 0, "some visible node is off the plane");
    assert!(slice.skipped > composite.skipped, "{} vs {}", slice.skipped, composite.skipped);
    assert!(
        2 * slice.texture_bytes < composite.texture_bytes,
        "{} vs {}",
        slice.texture_bytes,
        composite.texture_bytes
    );
    // A plane beside the volume: nothing selected, nothing drawn.
    let beside = Blend::slice(SlicePlane::new([40.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap(), [lo, hi]).unwrap();
    let none = selection(&octree, &shape, &beside, 1 << 30, false);
    assert!(none.bricks.is_empty());
    let l = list(&octree, &shape, &none, beside, None);
    assert!(!l.plan.volume && l.plan.passes.is_empty(), "{:?}", l.plan);
}

/// Bad planes are refused where they enter: the blend, and the selection's options.
#[test]
fn bad_planes_are_refused() {
    let bad = SlicePlane { origin: [0.0; 3], normal: [0.0; 3] };
    assert!(Blend::slice(bad, [0.0, 1.0]).unwrap_err().to_string().contains("non-zero"));
    let nan = SlicePlane { origin: [f64::NAN, 0.0, 0.0], normal: [0.0, 0.0, 1.0] };
    assert!(Blend::slice(nan, [0.0, 1.0]).unwrap_err().to_string().contains("finite"));
    let volume = generate(Dataset::Sphere, 9, ScalarType::F32);
    let octree = VolumeOctree::build(&volume.grid(None).unwrap(), &BuildOptions { leaf_size: 4 }).unwrap();
    let options = SelectOptions { slice: Some(bad), ..SelectOptions::new(1 << 20, 0.0) };
    assert!(select(&octree, &options, |_, _| true).unwrap_err().to_string().contains("non-zero"));
    // Slice without a plane (not made by Blend::slice) shows nothing.
    assert!(!Blend::new(BlendMode::Slice, [0.0, 1.0]).visible(0.0, 1.0, &|_, _| true));
}

/// A scene without the Slice mode does none of its work: no slice pass, and
/// a selection without a plane is the Composite selection.
#[test]
fn no_slice_work_without_the_mode() {
    let volume = generate(Dataset::SheppLogan, 17, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let (lo, hi) = octree.value_range();
    let blend = Blend::new(BlendMode::Composite, [lo, hi]);
    let s = selection(&octree, &shape, &blend, 1 << 30, false);
    let l = list(&octree, &shape, &s, blend, None);
    assert!(l.plan.blend.slice.is_none());
    assert!(l.plan.passes.iter().all(|p| !p.contains("slice")), "{:?}", l.plan.passes);
}
