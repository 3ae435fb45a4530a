//! The 2D transfer function: the compositor against the reference with the
//! same gradient rule (full resolution, and bricks of four strides side by
//! side: no seam), the selection's visibility test over every gradient, and
//! the planner's rules (Composite only, one gradient per sample shared with
//! the shading, the 1D gradient opacity left out, no work without it).

use super::*;
use crate::plan::select::{select, SelectOptions};
use crate::plan::{needs_gradients, BlendMode, Scene};
use crate::render::compositor::composite_counting_gradients;
use crate::render::texture::upload;
use crate::transfer::lighting::{Lighting, Material};
use crate::transfer::{GradientOpacity, TransferFunction2D};

/// A `width x height` table from `f(x, y)`, `x` and `y` the texel centres in `[0, 1]`.
fn table(width: usize, height: usize, f: impl Fn(f64, f64) -> [f32; 4]) -> Vec<[f32; 4]> {
    (0..height)
        .flat_map(|j| (0..width).map(move |i| (i, j)))
        .map(|(i, j)| f((i as f64 + 0.5) / width as f64, (j as f64 + 0.5) / height as f64))
        .collect()
}

/// Colour by value (x) and gradient (y), opacity growing with both: the
/// boundaries of a field show, its flat parts fade.
fn boundaries(range: [f64; 2], gradient_max: f64) -> TransferFunction2D {
    let rgba = table(32, 24, |x, y| {
        let a = 0.25 * y * (x * 1.5).min(1.0);
        [x as f32, y as f32, (1.0 - x) as f32, a as f32]
    });
    TransferFunction2D::new(32, 24, rgba, range, gradient_max).unwrap()
}

/// The 1D function the tests pass besides (not read under a 2D function).
fn unused_tf() -> TransferFunction {
    TransferFunction::new(vec![(0.0, [1.0, 0.0, 0.0])], vec![(0.0, 1.0)]).unwrap()
}

/// A Gaussian blob on a 33^3 grid, `f = exp(-r^2 / (2 8^2))`: gradient 0 at
/// the centre, largest (0.076 per voxel) at `r = 8`.
fn blob() -> Vec<f32> {
    let n = 33;
    (0..n * n * n)
        .map(|i| {
            let [x, y, z] = [i % n, (i / n) % n, i / (n * n)].map(|v| v as f64 - 16.0);
            (-(x * x + y * y + z * z) / 128.0).exp() as f32
        })
        .collect()
}

fn with_transfer_2d(mut list: DrawList, t: &TransferFunction2D, lighting: Option<&Lighting>) -> DrawList {
    list.plan.transfer_2d = true;
    list.transfer_2d = Some(t.clone());
    list.plan.shading = lighting.is_some();
    list.lighting = lighting.map(|l| l.in_world(&list.camera));
    list
}

/// Full-resolution bricks (stride 1) against the reference, both classified
/// by the same table, unshaded and shaded, parallel and perspective: the
/// pictures differ only by where they sample. Bound RMSE 0.002, SSIM >
/// 0.999; the table must move the picture at least 10x that far from the
/// same table read at gradient 0 (gradient_max huge: only row 0 is read).
#[test]
fn transfer_2d_full_resolution_matches_the_reference() {
    let data = blob();
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [33; 3]).unwrap();
    let shape = *grid.shape();
    let t = boundaries([0.0, 1.0], 0.08);
    let flat = boundaries([0.0, 1.0], 1e9);
    let tf = unused_tf();
    let lighting = Lighting::headlight(Material::default());
    for shading in [None, Some(&lighting)] {
        for (parallel, bricks) in [(true, leaf_bricks(shape.dims, 16)), (false, vec![brick(0, [0; 3], [32; 3], 1)])] {
            let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
            let list = with_transfer_2d(draw_list(&shape, &camera, &bricks, SurfacePass::None), &t, shading);
            let image = composite(&grid, &list, &tf, 64, 64, None).unwrap();
            let options =
                |t| ReferenceOptions { lighting: shading, transfer_2d: Some(t), ..ReferenceOptions::default() };
            let truth = reference(&grid, &tf, &camera, 64, 64, &options(&t)).unwrap();
            let at_zero = reference(&grid, &tf, &camera, 64, 64, &options(&flat)).unwrap();
            let m = compare(&image, &truth).unwrap();
            let effect = compare(&truth, &at_zero).unwrap();
            eprintln!(
                "2D transfer function, shaded {}, parallel {parallel}: {m:?} (the gradient axis moves {:.4})",
                shading.is_some(),
                effect.rmse
            );
            assert!(m.rmse < 0.002 && m.ssim > 0.999, "parallel {parallel}: {m:?}");
            assert!(effect.rmse > 10.0 * m.rmse, "the gradient axis must show: {effect:?} vs {m:?}");
        }
    }
}

/// Four bricks at strides 1, 2, 4 and 8 side by side under the 2D table
/// (the gradient taken one texel away in each, so the error grows with the
/// stride): every ray on or next to a shared face errs at most as much as
/// the largest error inside the bricks it touches (plus 1e-6), and every
/// error is below 0.1.
#[test]
fn transfer_2d_bricks_of_four_strides_show_no_seam() {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let (lo, hi) = octree.value_range();
    let t = boundaries([lo, hi], 0.25 * (hi - lo));
    let camera =
        Camera::new([16.0, 16.0, 100.0], [16.0, 16.0, 16.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 16.25 })
            .unwrap();
    let bricks = [
        brick(0, [0, 0, 0], [16, 16, 32], 1),
        brick(1, [16, 0, 0], [32, 16, 32], 2),
        brick(2, [0, 16, 0], [16, 32, 32], 4),
        brick(3, [16, 16, 0], [32, 32, 32], 8),
    ];
    let list = with_transfer_2d(draw_list(&shape, &camera, &bricks, SurfacePass::None), &t, None);
    let (w, h) = (65, 65);
    let tf = unused_tf();
    let image = composite(&grid, &list, &tf, w, h, None).unwrap();
    let with = ReferenceOptions { transfer_2d: Some(&t), ..ReferenceOptions::default() };
    let truth = reference(&grid, &tf, &camera, w, h, &with).unwrap();
    let (a, b) = (image.luminance(BACKGROUND), truth.luminance(BACKGROUND));
    assert!(b.iter().any(|&v| v > 0.05), "the table must show something");
    let error = |px: usize, py: usize| (a[px + w * py] - b[px + w * py]).abs();
    let xside = |px: usize| (px >= 32) as usize;
    let yside = |py: usize| (py <= 32) as usize;
    let near_seam = |p: usize| (31..=33).contains(&p);
    let mut inside = [0.0f64; 4];
    for py in 0..h {
        for px in 0..w {
            if !near_seam(px) && !near_seam(py) {
                let q = xside(px) + 2 * yside(py);
                inside[q] = inside[q].max(error(px, py));
            }
        }
    }
    eprintln!("2D transfer function: largest error inside the bricks of strides 1, 2, 4, 8: {inside:?}");
    assert!(inside.iter().all(|&e| e < 0.1), "{inside:?}");
    for py in 0..h {
        for px in 0..w {
            if near_seam(px) || near_seam(py) {
                let xs: &[usize] = if near_seam(px) { &[0, 1] } else { &[xside(px)] };
                let ys: &[usize] = if near_seam(py) { &[0, 1] } else { &[yside(py)] };
                let bound =
                    xs.iter().flat_map(|&x| ys.iter().map(move |&y| x + 2 * y)).map(|q| inside[q]).fold(0.0, f64::max);
                assert!(error(px, py) <= bound + 1e-6, "seam at pixel ({px}, {py}): {} > {bound}", error(px, py));
            }
        }
    }
}

/// The scene of a 2D function, shading, gradient opacity and blend mode.
fn scene<'a>(
    t: Option<&'a TransferFunction2D>,
    shading: Option<&'a Lighting>,
    gradient_opacity: Option<&'a GradientOpacity>,
    mode: BlendMode,
) -> Scene<'a> {
    Scene {
        surface: None,
        surface_opacity: 1.0,
        shading,
        gradient_opacity,
        transfer_2d: t,
        blend: crate::plan::Blend::new(mode, [0.0, 1.0]),
        region: None,
    }
}

/// The visibility test: a node whose values read only texels of alpha 0 in
/// every row is skipped; one that a high-gradient row alone makes visible is
/// kept (the test takes every gradient, `[0, infinity)`); a table 0
/// everywhere selects nothing. On the blob at full budget.
#[test]
fn transfer_2d_visibility_skips_only_nodes_transparent_at_every_gradient() {
    let data = blob();
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [33; 3]).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    // Alpha only for values in [0.5, 0.6] (columns 16..=18 of 32) and only in the top quarter of the rows.
    let band = |rows: std::ops::Range<usize>| {
        let rgba = (0..32 * 32)
            .map(|k| {
                let (i, j) = (k % 32, k / 32);
                [1.0, 1.0, 1.0, if (16..=18).contains(&i) && rows.contains(&j) { 0.5 } else { 0.0 }]
            })
            .collect();
        TransferFunction2D::new(32, 32, rgba, [0.0, 1.0], 0.08).unwrap()
    };
    let high = band(24..32);
    let options = SelectOptions { gradient_border: true, ..SelectOptions::new(1 << 24, 0.0) };
    let selection = select(&octree, &options, |a, b| !high.is_transparent_over(a, b)).unwrap();
    assert!(
        !selection.bricks.is_empty() && selection.skipped > 0,
        "{} bricks, {} skipped",
        selection.bricks.len(),
        selection.skipped
    );
    for b in &selection.bricks {
        let node = octree.node(b.node);
        let (min, max) = (node.min, node.max);
        assert!(high.max_opacity(min, max, 0.0, f64::INFINITY) > 0.0, "a kept node is transparent: [{min}, {max}]");
    }
    // A node holding 0.55 is kept although only the high-gradient rows show it.
    assert!(selection.bricks.iter().any(|b| {
        let node = octree.node(b.node);
        node.min <= 0.55 && 0.55 <= node.max
    }));
    // The same columns in the low rows: the same nodes (the test does not bound the gradient).
    let low = band(0..8);
    let same = select(&octree, &options, |a, b| !low.is_transparent_over(a, b)).unwrap();
    assert_eq!(same.bricks, selection.bricks);
    let zero = band(0..0);
    let none = select(&octree, &options, |a, b| !zero.is_transparent_over(a, b)).unwrap();
    assert!(none.bricks.is_empty());
    // The kept nodes draw the shell: a picture that is not empty.
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, true).unwrap();
    let list = crate::plan::draw_list(
        &octree,
        grid.shape(),
        &selection,
        &camera,
        &scene(Some(&high), None, None, BlendMode::Composite),
        None,
    )
    .unwrap();
    let image = composite(&grid, &list, &unused_tf(), 48, 48, None).unwrap();
    assert!(image.rgba.iter().any(|p| p[3] > 0.05), "the high-gradient shell must show");
}

/// The planner: `transfer-2d` (first, gradients, bordered textures, the
/// table in the list) under Composite only; with shading one gradient per
/// sample for both; the 1D gradient opacity left out under it (VTK's TF_2D);
/// a scene without it does none of its work (no effect, no table, no
/// gradient, no border: the plain list and picture).
#[test]
fn transfer_2d_is_planned_for_composite_and_costs_nothing_without_it() {
    let volume = generate(Dataset::SheppLogan, 17, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let camera = Camera::around([0.0; 3], [16.0; 3], 30.0, 20.0, false).unwrap();
    let t = boundaries([0.0, 1.0], 0.5);
    let tf = TransferFunction::new(vec![(0.0, [0.8, 0.7, 0.6])], vec![(0.1, 0.0), (0.2, 0.2), (1.0, 0.1)]).unwrap();
    let go = GradientOpacity::new(vec![(0.0, 0.0), (0.1, 1.0)]).unwrap();
    let lighting = Lighting::headlight(Material::default());
    let planned_on = |select_for: &Scene<'_>, s: &Scene<'_>| {
        let options = SelectOptions {
            gradient_border: needs_gradients(
                select_for.shading,
                select_for.gradient_opacity,
                select_for.transfer_2d.is_some(),
                select_for.blend.mode,
            ),
            ..SelectOptions::new(1 << 20, 0.0)
        };
        let visible = |a: f64, b: f64| match select_for.transfer_2d {
            Some(t) if select_for.blend.mode == BlendMode::Composite => !t.is_transparent_over(a, b),
            _ => !tf.is_transparent_over(a, b),
        };
        let selection = select(&octree, &options, visible).unwrap();
        crate::plan::draw_list(&octree, grid.shape(), &selection, &camera, s, None).unwrap()
    };
    let planned = |s: &Scene<'_>| planned_on(s, s);
    let count = |list: &DrawList| {
        let textures = upload(&grid, list).unwrap();
        let (image, gradients) = composite_counting_gradients(&textures, list, &tf, 32, 32).unwrap();
        (image, gradients, textures.bytes())
    };

    let plain = planned(&scene(None, None, None, BlendMode::Composite));
    assert!(!plain.plan.transfer_2d && plain.transfer_2d.is_none() && plain.plan.effects.is_empty());
    assert!(!needs_gradients(None, None, false, BlendMode::Composite));
    let (plain_image, none, plain_bytes) = count(&plain);
    assert_eq!(none, 0, "a 1D scene takes no gradient");

    let l = planned(&scene(Some(&t), None, None, BlendMode::Composite));
    assert_eq!(l.plan.effects, vec!["transfer-2d"]);
    assert_eq!(l.plan.passes, vec!["volume"]);
    assert!(l.plan.gradients() && l.plan.bordered() && l.transfer_2d.as_ref() == Some(&t));
    let (image, gradients, bytes) = count(&l);
    assert!(gradients > 100 && bytes > plain_bytes, "gradients {gradients}, bordered bytes {bytes} vs {plain_bytes}");
    assert!(compare(&image, &plain_image).unwrap().rmse > 0.01, "the table classifies, not the 1D function");

    let shaded = planned(&scene(Some(&t), Some(&lighting), None, BlendMode::Composite));
    assert_eq!(shaded.plan.effects, vec!["transfer-2d", "shading"]);
    assert_eq!(shaded.plan.passes, vec!["volume-shaded"]);
    assert_eq!(count(&shaded).1, gradients, "one gradient per sample for both");

    let with_go = planned(&scene(Some(&t), None, Some(&go), BlendMode::Composite));
    assert_eq!(with_go.plan.effects, vec!["transfer-2d"], "the 1D gradient opacity is not applied");
    assert!(with_go.gradient_opacity.is_none() && !with_go.plan.gradient_opacity);
    assert_eq!(count(&with_go).0.rgba, image.rgba);

    // Planned again on the same selection: the same as planned with the scene's table.
    let with_t = scene(Some(&t), None, None, BlendMode::Composite);
    let without = planned_on(&with_t, &scene(None, None, None, BlendMode::Composite));
    assert_eq!(crate::plan::replan_transfer_2d(without.clone(), Some(&t)), l);
    assert_eq!(crate::plan::replan_transfer_2d(l.clone(), None), without);

    for mode in [BlendMode::Mip, BlendMode::Additive] {
        let m = planned(&scene(Some(&t), None, None, mode));
        assert!(!m.plan.transfer_2d && m.transfer_2d.is_none() && m.plan.effects.is_empty(), "{mode:?}");
        assert!(!needs_gradients(None, None, true, mode));
    }
}
