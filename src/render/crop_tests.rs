//! Cropping and clipping planes: the compositor executing the planner's
//! DrawList against the reference caster with the same region, removed
//! bricks not drawn, and no region work when the scene asks for none.

use super::compositor::composite;
use super::metrics::compare;
use super::reference::{reference_blend, ReferenceOptions};
use crate::data::grid::ScalarType;
use crate::datasets::{generate, Dataset};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::crop::{flags, ClippingPlane, Cropping, KeptRegion};
use crate::plan::select::{select, SelectOptions};
use crate::plan::{draw_list, Blend, BlendMode, DrawList, Scene};
use crate::transfer::TransferFunction;

/// A translucent ramp over the whole range: every removed part shows.
fn ramp() -> TransferFunction {
    TransferFunction::new(
        vec![(0.0, [0.2, 0.4, 1.0]), (0.5, [1.0, 0.9, 0.3]), (1.0, [1.0, 0.3, 0.2])],
        vec![(0.0, 0.0), (0.2, 0.1), (1.0, 0.5)],
    )
    .unwrap()
}

/// The regions tested, over the 33^3 grid of unit spacing at the origin.
fn regions() -> Vec<(&'static str, KeptRegion)> {
    let planes = [4.0, 22.5, 6.0, 27.0, 3.5, 25.0];
    // Tighter, so that the fence's removed corners hold part of the phantom.
    let tight = [12.0, 19.5, 13.0, 20.0, 12.5, 19.0];
    // Wider, so that the inverted cross removes much of it.
    let wide = [9.0, 23.5, 10.0, 22.0, 8.5, 24.0];
    let oblique = ClippingPlane { origin: [16.0, 16.0, 16.0], normal: [1.0, -0.6, 0.4] };
    let second = ClippingPlane { origin: [0.0, 0.0, 20.0], normal: [0.0, 0.0, -1.0] };
    vec![
        ("subvolume", KeptRegion::new(Some(Cropping::subvolume(planes)), &[]).unwrap()),
        ("fence", KeptRegion::new(Some(Cropping { planes: tight, flags: flags::FENCE }), &[]).unwrap()),
        (
            "inverted cross",
            KeptRegion::new(Some(Cropping { planes: wide, flags: flags::INVERTED_CROSS }), &[]).unwrap(),
        ),
        ("two planes", KeptRegion::new(None, &[oblique, second]).unwrap()),
        ("both", KeptRegion::new(Some(Cropping::subvolume(planes)), &[oblique]).unwrap()),
    ]
}

/// The planner's list for `region` at a budget that draws every brick at
/// full resolution (stride 1).
fn list(
    octree: &VolumeOctree,
    shape: &crate::data::grid::GridShape,
    region: Option<&KeptRegion>,
    blend: Blend,
) -> DrawList {
    let tf = ramp();
    let options = SelectOptions {
        region: region.map(|r| r.to_index(shape)),
        gradient_border: blend.mode == BlendMode::Isosurface,
        ..SelectOptions::new(1 << 30, 0.0)
    };
    let selection =
        select(octree, &options, |a, b| blend.visible(a, b, &|a, b| !tf.is_transparent_over(a, b))).unwrap();
    assert!(selection.bricks.iter().all(|b| b.stride == 1));
    let camera = Camera::around([0.0; 3], [32.0; 3], 35.0, 25.0, false).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: None,
        gradient_opacity: None,
        transfer_2d: None,
        blend,
        region,
    };
    draw_list(octree, shape, &selection, &camera, &scene, None).unwrap()
}

/// Full-resolution bricks against the reference with the same region,
/// Composite and MIP: the pictures differ only by where they sample (the
/// slice lattice against the reference's midpoints), also along the cut
/// faces, so a region adds little to the difference without one. Measured
/// (64 x 64): without a region RMSE 0.0073 (Composite), 0.0141 (MIP); with
/// one 0.0058 to 0.0096 (Composite), 0.0091 and 0.0108 (MIP), while the
/// regions move the reference by 0.035 to 0.089; Additive 0.0118 without,
/// 0.0151 and 0.0104 with (moved 0.19, 0.24); Isosurface 0.0273 without,
/// 0.0241 with the subvolume (moved 0.078). Bounds: RMSE below 1.25
/// times the difference without a region + 0.001, SSIM > 0.96, and the
/// region moving the reference by more than 3 times that RMSE (it shows).
#[test]
fn cropped_and_clipped_compositor_matches_the_reference() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf = ramp();
    let (lo, hi) = octree.value_range();
    for mode in [BlendMode::Composite, BlendMode::Mip, BlendMode::Additive, BlendMode::Isosurface] {
        let blend = match mode {
            BlendMode::Isosurface => {
                Blend::isosurfaces(&[lo + 0.3 * (hi - lo), lo + 0.6 * (hi - lo)], [lo, hi]).unwrap()
            }
            _ => Blend::new(mode, [lo, hi]),
        };
        let whole = list(&octree, &shape, None, blend);
        let full = reference_blend(&grid, &tf, &whole.camera, 64, 64, &ReferenceOptions::default(), &blend).unwrap();
        let uncut = compare(&composite(&grid, &whole, &tf, 64, 64, None).unwrap(), &full).unwrap();
        eprintln!("no region, {mode:?}: {uncut:?}");
        // MIP: the regions whose effect stands well above its sampling difference.
        // Isosurface: the subvolume (with two planes a brick of one value
        // holds no crossing at stride 1 and is drawn coarser, losslessly).
        let tested = |name: &str| match mode {
            BlendMode::Composite => true,
            BlendMode::Isosurface => name == "subvolume",
            _ => matches!(name, "subvolume" | "two planes"),
        };
        for (name, region) in regions().into_iter().filter(|(name, _)| tested(name)) {
            let l = list(&octree, &shape, Some(&region), blend);
            assert_eq!(l.region, Some(region), "{name}");
            let image = composite(&grid, &l, &tf, 64, 64, None).unwrap();
            let options = ReferenceOptions { region: Some(&region), ..ReferenceOptions::default() };
            let truth = reference_blend(&grid, &tf, &l.camera, 64, 64, &options, &blend).unwrap();
            let m = compare(&image, &truth).unwrap();
            let moved = compare(&truth, &full).unwrap();
            eprintln!("{name}, {mode:?}: {m:?}, the region moves the reference {:.4}", moved.rmse);
            assert!(m.ssim > 0.96, "{name} {mode:?}: {m:?}");
            assert!(m.rmse < 1.25 * uncut.rmse + 0.001, "{name} {mode:?}: {m:?}, without a region {uncut:?}");
            assert!(moved.rmse > 3.0 * m.rmse, "{name} {mode:?}: the region must show: {moved:?} vs {m:?}");
        }
    }
}

/// A region that keeps the whole volume is not planned: no effect, no
/// region in the list, the same bricks and picture as without one; a
/// region removing part of it leaves out the bricks it removes whole.
#[test]
fn a_no_op_region_does_no_work_and_removed_bricks_are_not_drawn() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let blend = Blend::default();
    let whole = list(&octree, &shape, None, blend);
    assert!(whole.plan.effects.is_empty() && whole.region.is_none());
    let around = KeptRegion::new(
        Some(Cropping::subvolume([-1.0, 40.0, 0.0, 32.0, -5.0, 32.0])),
        &[ClippingPlane { origin: [0.0, -1.0, 0.0], normal: [0.2, 1.0, 0.0] }],
    )
    .unwrap();
    let same = list(&octree, &shape, Some(&around), blend);
    assert_eq!(same, whole);
    let half = KeptRegion::new(None, &[ClippingPlane { origin: [16.0, 0.0, 0.0], normal: [-1.0, 0.0, 0.0] }]).unwrap();
    let cut = list(&octree, &shape, Some(&half), blend);
    assert_eq!(
        (cut.plan.passes.clone(), cut.plan.effects.clone()),
        (vec!["volume".to_string()], vec!["clipping".to_string()])
    );
    assert!(cut.bricks.iter().all(|b| b.world_lo[0] <= 16.0), "a brick entirely at x > 16 is drawn");
    assert!(cut.bricks.len() < whole.bricks.len() && cut.plan.skipped_bricks > whole.plan.skipped_bricks);
    // recrop gives the planner's list again, and clears it.
    assert_eq!(crate::plan::recrop(cut.clone(), Some(&half), &shape), cut);
    let cleared = crate::plan::recrop(cut, None, &shape);
    assert!(cleared.region.is_none() && cleared.plan.effects.is_empty());
}

/// The plan's effects are one list: the per-sample effects in their order
/// (`gradient-opacity`, `shading`), then `cropping`, `clipping`; planning
/// the shading and gradient opacity again keeps the region's, cropping
/// again keeps theirs.
#[test]
fn region_effects_follow_the_per_sample_effects() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let region = &regions()[4].1;
    let lighting = crate::transfer::lighting::Lighting::headlight(Default::default());
    let ramp_g = crate::transfer::GradientOpacity::new(vec![(0.0, 0.0), (0.1, 1.0)]).unwrap();
    let options = SelectOptions {
        region: Some(region.to_index(&shape)),
        gradient_border: true,
        ..SelectOptions::new(1 << 30, 0.0)
    };
    let selection = select(&octree, &options, |_, _| true).unwrap();
    let camera = Camera::around([0.0; 3], [32.0; 3], 35.0, 25.0, false).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: Some(&lighting),
        gradient_opacity: Some(&ramp_g),
        transfer_2d: None,
        blend: Blend::default(),
        region: Some(region),
    };
    let all = draw_list(&octree, &shape, &selection, &camera, &scene, None).unwrap();
    assert_eq!(all.plan.effects, ["gradient-opacity", "shading", "cropping", "clipping"]);
    assert_eq!(all.plan.passes, ["volume-shaded"]);
    let unlit = crate::plan::replan_effects(all.clone(), None, None).unwrap();
    assert_eq!(unlit.plan.effects, ["cropping", "clipping"]);
    assert_eq!(unlit.region.as_ref(), Some(region));
    assert_eq!(crate::plan::replan_effects(unlit, Some(&lighting), Some(&ramp_g)).unwrap(), all);
    let uncut = crate::plan::recrop(all.clone(), None, &shape);
    assert_eq!(uncut.plan.effects, ["gradient-opacity", "shading"]);
    assert_eq!(crate::plan::recrop(uncut, Some(region), &shape), all);
}
