//! Two dependent fields: the CPU compositor against the reference (colour
//! from field 0, opacity from field 1), the selection's visibility by the
//! opacity field, and the planner's rule (a single field plans nothing of it).

use super::compositor::composite;
use super::dependent::{composite_dependent, reference_dependent, upload_dependent};
use super::metrics::compare;
use super::reference::{reference, ReferenceOptions};
use crate::data::grid::{Grid, GridShape, Samples};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, DependentOctree};
use crate::plan::dependent::{plan_dependent, EFFECT};
use crate::plan::select::{select, SelectOptions};
use crate::plan::{draw_list, Blend, BlendMode, DrawList, Scene};
use crate::transfer::TransferFunction;

const N: usize = 33;

/// Two interleaved fields on an `N^3` grid: field 0 a ramp along x
/// (0 to 1, the colour) with a checkerboard of 0.3 in the corner
/// `[0, 10)^3` (detail the selection refines there first), field 1 a ball of radius 12 (1 at the centre,
/// falling to 0 at its surface; the opacity), or `opacity(x, y, z)`.
fn two_fields(opacity: impl Fn(f64, f64, f64) -> f64) -> Vec<f32> {
    let mut data = Vec::with_capacity(2 * N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let [x, y, z] = [i, j, k].map(|v| v as f64);
                let checker = if i < 10 && j < 10 && k < 10 { 0.3 * ((i + j + k) % 2) as f64 } else { 0.0 };
                data.push((x / (N - 1) as f64 + checker) as f32);
                data.push(opacity(x, y, z) as f32);
            }
        }
    }
    data
}

fn ball(x: f64, y: f64, z: f64) -> f64 {
    let r = ((x - 16.0).powi(2) + (y - 16.0).powi(2) + (z - 16.0).powi(2)).sqrt();
    (1.0 - r / 12.0).max(0.0)
}

fn fields(data: &[f32]) -> (Grid<'_>, Grid<'_>) {
    let shape = GridShape { dims: [N; 3], spacing: [1.0; 3], origin: [0.0; 3] };
    (
        Grid::new(Samples::F32(data), shape, 2, Some(0)).unwrap(),
        Grid::new(Samples::F32(data), shape, 2, Some(1)).unwrap(),
    )
}

/// Colour blue to orange over field 0's [0, 1]; opacity 0 at 0 rising to
/// 0.3 at 1 (over field 1's values).
fn tf() -> TransferFunction {
    TransferFunction::new(vec![(0.0, [0.2, 0.4, 1.0]), (1.0, [1.0, 0.6, 0.1])], vec![(0.0, 0.0), (1.0, 0.3)]).unwrap()
}

/// The selection of the combined tree at `budget` bytes (8 bytes a texel:
/// two f32 fields), visible where the opacity function over the node's
/// opacity range is not 0, and its dependent DrawList.
fn planned(octree: &DependentOctree, shape: &GridShape, camera: &Camera, budget: usize, mode: BlendMode) -> DrawList {
    let tf = tf();
    let options = SelectOptions { bytes_per_texel: 8, ..SelectOptions::new(budget, 0.0) };
    let selection = select(&octree.combined, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: None,
        gradient_opacity: None,
        blend: Blend::new(mode, [0.0, 1.0]),
        region: None,
        transfer_2d: None,
    };
    let list = draw_list(&octree.combined, shape, &selection, camera, &scene, None).unwrap();
    plan_dependent(list, true)
}

/// The compositor draws colour from field 0 and opacity from field 1, as
/// the reference does: at the full budget (every brick at stride 1) and at
/// a budget of mixed strides (1, 2 and 4 in one picture), parallel and
/// perspective. Metric RMSE of RGBA in [0, 1]; measured 0.00003 to
/// 0.00007 at the full budget (one stride-1 brick) and 0.0012 to 0.0026
/// with strides 1, 2 and 4 (the coarse bricks' own error); bounds 0.0005
/// and 0.005. The dependent picture is far from the picture of field 0
/// alone (RMSE above 0.05): the opacity field shows.
#[test]
fn compositor_matches_the_reference_with_mixed_strides() {
    let data = two_fields(ball);
    let (colour, opacity) = fields(&data);
    let shape = *colour.shape();
    let octree = DependentOctree::build(&colour, &opacity, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf = tf();
    for parallel in [true, false] {
        let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
        let truth = reference_dependent(&colour, &opacity, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
        let field0 = reference(&colour, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
        let apart = compare(&truth, &field0).unwrap();
        assert!(apart.rmse > 0.05, "the opacity field must show: {apart:?}");
        let mut mixed = 0;
        for budget in [1usize << 30, 300_000, 150_000, 100_000, 60_000] {
            let list = planned(&octree, &shape, &camera, budget, BlendMode::Composite);
            assert!(list.plan.dependent && list.plan.effects == [EFFECT], "{:?}", list.plan);
            let strides: std::collections::BTreeSet<usize> = list.bricks.iter().map(|b| b.brick.stride).collect();
            mixed += usize::from(strides.len() >= 2);
            if budget == 1 << 30 {
                assert_eq!(strides.iter().copied().collect::<Vec<_>>(), [1]);
            }
            let textures = upload_dependent(&colour, &opacity, &list).unwrap();
            let texels: usize = list.bricks.iter().map(|b| b.brick.texels.iter().product::<usize>()).sum();
            assert_eq!(textures.bytes(), 2 * 4 * texels, "both fields counted");
            let image = composite_dependent(&textures, &list, &tf, 64, 64).unwrap();
            let m = compare(&image, &truth).unwrap();
            eprintln!("dependent, parallel {parallel}, budget {budget}, strides {strides:?}: {m:?}");
            let bound = if strides.len() == 1 && strides.contains(&1) { 0.0005 } else { 0.005 };
            assert!(m.rmse < bound, "parallel {parallel} budget {budget}: {m:?}");
        }
        assert!(mixed >= 1, "no budget gave mixed strides");
    }
}

/// A node transparent by its opacity field is not selected even where its
/// colour field varies (the ramp), and a node whose colour field is
/// constant is selected where its opacity field shows.
#[test]
fn visibility_is_the_opacity_fields() {
    // Opacity only in the half x >= 16; the colour ramp varies everywhere.
    let data = two_fields(|x, _, _| if x >= 16.0 { 0.5 } else { 0.0 });
    let (colour, opacity) = fields(&data);
    let octree = DependentOctree::build(&colour, &opacity, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf = tf();
    let options = SelectOptions { bytes_per_texel: 8, ..SelectOptions::new(1 << 30, 0.0) };
    let s = select(&octree.combined, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
    assert!(s.skipped > 0 && !s.bricks.is_empty());
    assert!(s.bricks.iter().all(|b| b.hi[0] >= 16), "a brick of transparent opacity was selected");
    // The colour field alone would show everywhere (its ramp is within the function's range).
    let s0 = select(&octree.colour, &SelectOptions::new(1 << 30, 0.0), |a, b| !tf.is_transparent_over(a, b)).unwrap();
    assert!(s0.bricks.iter().any(|b| b.lo[0] < 8));
    assert!(s.bricks.iter().all(|b| b.lo[0] >= 8), "{:?}", s.bricks);
    // Reverse: a constant colour field (0.5 everywhere) and a visible opacity ball.
    let mut data = two_fields(ball);
    for pair in data.chunks_exact_mut(2) {
        pair[0] = 0.5;
    }
    let (colour, opacity) = fields(&data);
    let octree = DependentOctree::build(&colour, &opacity, &BuildOptions { leaf_size: 8 }).unwrap();
    assert!(octree.colour.node(octree.colour.root()).is_homogeneous());
    let s = select(&octree.combined, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
    let centre = |b: &crate::plan::select::Brick| (0..3).all(|a| b.lo[a] <= 16 && 16 <= b.hi[a]);
    assert!(s.bricks.iter().any(centre) && s.bricks.iter().all(|b| b.stride == 1 || b.error == 0.0));
}

/// The planner runs none of it for one field (the plan, effects and
/// picture of the single-field pipeline) nor outside Composite; the
/// dependent compositor refuses a list that does not plan it.
#[test]
fn a_single_field_plans_nothing_of_it() {
    let data = two_fields(ball);
    let (colour, opacity) = fields(&data);
    let shape = *colour.shape();
    let octree = DependentOctree::build(&colour, &opacity, &BuildOptions { leaf_size: 8 }).unwrap();
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, true).unwrap();
    let list = planned(&octree, &shape, &camera, 1 << 30, BlendMode::Composite);
    let single = plan_dependent(list.clone(), false);
    assert!(!single.plan.dependent && single.plan.effects.is_empty(), "{:?}", single.plan);
    let mut by_hand = list.clone();
    by_hand.plan.dependent = false;
    by_hand.plan.effects.clear();
    assert_eq!(single, by_hand);
    let tf = tf();
    let plain = composite(&colour, &single, &tf, 32, 32, None).unwrap();
    let field0 = composite(&colour, &by_hand, &tf, 32, 32, None).unwrap();
    assert_eq!(plain.rgba, field0.rgba);
    let textures = upload_dependent(&colour, &opacity, &single).unwrap();
    let e = composite_dependent(&textures, &single, &tf, 32, 32).unwrap_err().to_string();
    assert!(e.contains("does not plan dependent"), "{e}");
    let mip = planned(&octree, &shape, &camera, 1 << 30, BlendMode::Mip);
    assert!(!mip.plan.dependent && !mip.plan.effects.iter().any(|e| e == EFFECT));
}

/// A NaN colour value is no data: transparent whatever the opacity field
/// says, in the compositor as in the reference (and the OpenGL shader). A
/// NaN ball of radius 6 at the centre lowers the centre pixel's opacity;
/// compositor against reference RMSE 0.0013, bound 0.003 (full budget: the
/// hole's edge, NaN within a cell of a NaN sample, is where slices and rays
/// sample differently).
#[test]
fn a_nan_colour_is_no_data() {
    let mut data = two_fields(ball);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let r2 = [i, j, k].iter().map(|&v| (v as f64 - 16.0).powi(2)).sum::<f64>();
                if r2 <= 36.0 {
                    data[2 * (i + N * (j + N * k))] = f32::NAN;
                }
            }
        }
    }
    let (colour, opacity) = fields(&data);
    let shape = *colour.shape();
    let octree = DependentOctree::build(&colour, &opacity, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf = tf();
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, true).unwrap();
    let list = planned(&octree, &shape, &camera, 1 << 30, BlendMode::Composite);
    let image = composite_dependent(&upload_dependent(&colour, &opacity, &list).unwrap(), &list, &tf, 64, 64).unwrap();
    let truth = reference_dependent(&colour, &opacity, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
    let m = compare(&image, &truth).unwrap();
    assert!(m.rmse < 0.003, "{m:?}");
    let whole = two_fields(ball);
    let (c, o) = fields(&whole);
    let full = reference_dependent(&c, &o, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
    let centre = 32 * 64 + 32;
    assert!(truth.rgba[centre][3] + 0.05 < full.rgba[centre][3], "{:?} vs {:?}", truth.rgba[centre], full.rgba[centre]);
}
