//! Gradient opacity: the compositor against the reference with the same
//! gradient rule, and the planner's rules: no gradient when the function is
//! constant (a constant other than 1 scales every opacity), one gradient per
//! sample for gradient opacity and shading together.

use super::*;
use crate::render::compositor::composite_counting_gradients;
use crate::render::texture::upload;
use crate::transfer::lighting::{Lighting, Material};
use crate::transfer::GradientOpacity;

/// The Shepp-Logan phantom's boundaries: homogeneous regions (gradient 0)
/// fade to 0.05 of their opacity, boundaries (steps of 0.1 to 1 over a
/// voxel, magnitudes up to ~0.5 per world unit) keep theirs.
fn boundaries() -> GradientOpacity {
    GradientOpacity::new(vec![(0.0, 0.05), (0.04, 1.0)]).unwrap()
}

/// Opacity on the brain and the inner structures (0.2 to 0.6), the skull less.
fn phantom_tf() -> TransferFunction {
    TransferFunction::new(
        vec![(0.1, [0.9, 0.8, 0.6]), (0.4, [0.4, 0.7, 1.0]), (1.0, [1.0, 1.0, 1.0])],
        vec![(0.1, 0.0), (0.2, 0.2), (0.6, 0.4), (1.0, 0.1)],
    )
    .unwrap()
}

/// The planner's list for `scene`'s effects from an octree's selection.
fn planned(
    grid: &Grid<'_>,
    octree: &VolumeOctree,
    camera: &Camera,
    tf: &TransferFunction,
    shading: Option<&Lighting>,
    gradient_opacity: Option<&GradientOpacity>,
) -> DrawList {
    let options = crate::plan::select::SelectOptions {
        gradient_border: crate::plan::needs_gradients(shading, gradient_opacity, false, Default::default()),
        ..crate::plan::select::SelectOptions::new(1 << 20, 0.0)
    };
    let selection = crate::plan::select::select(octree, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
    let scene = crate::plan::Scene {
        surface: None,
        surface_opacity: 1.0,
        shading,
        gradient_opacity,
        transfer_2d: None,
        blend: Default::default(),
        region: None,
    };
    crate::plan::draw_list(octree, grid.shape(), &selection, camera, &scene, None).unwrap()
}

/// A Gaussian blob on a 33^3 grid, `f = exp(-r^2 / (2 8^2))`: its gradient
/// magnitude `r f / 64` is 0 at the centre, largest (0.076 per voxel) at
/// `r = 8` and falls off outside, so a gradient opacity carves a shell.
fn blob() -> Vec<f32> {
    let n = 33;
    (0..n * n * n)
        .map(|i| {
            let [x, y, z] = [i % n, (i / n) % n, i / (n * n)].map(|v| v as f64 - 16.0);
            (-(x * x + y * y + z * z) / 128.0).exp() as f32
        })
        .collect()
}

/// Full-resolution bricks (stride 1) against the reference, with a
/// gradient opacity (0 at 0, 1 at the blob's steepest), unshaded and
/// shaded, parallel and perspective: the same gradient rule, so the
/// pictures differ only by where they sample. Measured RMSE 0.00015 to
/// 0.00031 (max 0.0024), while the gradient opacity moves the reference by
/// 0.017 to 0.030; bound 0.002, SSIM > 0.999.
#[test]
fn gradient_opacity_full_resolution_matches_the_reference() {
    let data = blob();
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [33; 3]).unwrap();
    let tf = TransferFunction::new(
        vec![(0.0, [0.3, 0.5, 1.0]), (1.0, [1.0, 0.8, 0.4])],
        vec![(0.0, 0.0), (0.2, 0.05), (1.0, 0.2)],
    )
    .unwrap();
    let shape = *grid.shape();
    let f = GradientOpacity::new(vec![(0.0, 0.0), (0.076, 1.0)]).unwrap();
    let lighting = Lighting::headlight(Material::default());
    for shading in [None, Some(&lighting)] {
        for (parallel, bricks) in [(true, leaf_bricks(shape.dims, 16)), (false, vec![brick(0, [0; 3], [32; 3], 1)])] {
            let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
            let mut list = draw_list(&shape, &camera, &bricks, SurfacePass::None);
            list.plan.gradient_opacity = true;
            list.gradient_opacity = Some(f.clone());
            list.plan.shading = shading.is_some();
            list.lighting = shading.map(|l| l.in_world(&camera));
            let image = composite(&grid, &list, &tf, 64, 64, None).unwrap();
            let with = ReferenceOptions {
                lighting: shading,
                gradient_opacity: Some(&f),
                transfer_2d: None,
                ..ReferenceOptions::default()
            };
            let truth = reference(&grid, &tf, &camera, 64, 64, &with).unwrap();
            let without = ReferenceOptions { lighting: shading, ..ReferenceOptions::default() };
            let plain = reference(&grid, &tf, &camera, 64, 64, &without).unwrap();
            let m = compare(&image, &truth).unwrap();
            let effect = compare(&truth, &plain).unwrap();
            eprintln!(
                "gradient opacity, shaded {}, parallel {parallel}: {m:?} (the gradient opacity moves {:.4})",
                shading.is_some(),
                effect.rmse
            );
            assert!(m.rmse < 0.002 && m.ssim > 0.999, "parallel {parallel}: {m:?}");
            assert!(effect.rmse > 10.0 * m.rmse, "the gradient opacity must show: {effect:?} vs {m:?}");
        }
    }
}

/// The planner takes no gradient for a gradient opacity that is 1 at every
/// magnitude (the list, textures and picture of no gradient opacity), none
/// for a constant 0.5 (every opacity halved: the picture of the transfer
/// function with halved opacities), and one per visible sample for one that
/// varies, the same count with shading too (one gradient for both).
#[test]
fn gradients_only_when_the_gradient_opacity_varies() {
    let volume = generate(Dataset::SheppLogan, 17, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf = phantom_tf();
    let camera = Camera::around([0.0; 3], [16.0; 3], 30.0, 20.0, false).unwrap();
    let count = |list: &DrawList| {
        let textures = upload(&grid, list).unwrap();
        let (image, gradients) = composite_counting_gradients(&textures, list, &tf, 32, 32).unwrap();
        (image, gradients, textures.bytes())
    };
    let plain = planned(&grid, &octree, &camera, &tf, None, None);
    let (plain_image, none, plain_bytes) = count(&plain);
    assert_eq!(none, 0);

    let one = GradientOpacity::new(vec![(0.0, 1.0), (5.0, 1.0)]).unwrap();
    let list = planned(&grid, &octree, &camera, &tf, None, Some(&one));
    assert_eq!(list, plain, "a gradient opacity of 1 is no effect");
    assert!(list.plan.effects.is_empty() && !list.plan.gradients());

    let half = GradientOpacity::new(vec![(0.0, 0.5), (5.0, 0.5)]).unwrap();
    let list = planned(&grid, &octree, &camera, &tf, None, Some(&half));
    assert_eq!((list.plan.effects.clone(), list.plan.opacity_scale), (vec!["opacity-scale".to_string()], 0.5));
    assert!(!list.plan.gradients() && list.gradient_opacity.is_none());
    let (image, gradients, bytes) = count(&list);
    assert_eq!((gradients, bytes), (0, plain_bytes), "no gradient, no border");
    let halved_tf =
        TransferFunction::new(tf.colors().to_vec(), tf.opacities().iter().map(|&(v, a)| (v, a * 0.5)).collect())
            .unwrap();
    let halved = composite_counting_gradients(&upload(&grid, &plain).unwrap(), &plain, &halved_tf, 32, 32).unwrap().0;
    let m = compare(&image, &halved).unwrap();
    assert!(m.max_abs < 1e-5, "a constant 0.5 halves every opacity: {m:?}");
    assert!(compare(&image, &plain_image).unwrap().rmse > 0.005);

    let f = boundaries();
    let list = planned(&grid, &octree, &camera, &tf, None, Some(&f));
    assert_eq!(list.plan.effects, vec!["gradient-opacity"]);
    assert_eq!(list.plan.passes, vec!["volume"]);
    assert!(list.plan.gradients() && list.gradient_opacity.is_some());
    let (_, varying, bytes) = count(&list);
    assert!(varying > 100 && bytes > plain_bytes, "gradients {varying}, bordered bytes {bytes} vs {plain_bytes}");

    // Shading changes no opacity: the same samples, one gradient each for both effects.
    let lighting = Lighting::headlight(Material::default());
    let both = planned(&grid, &octree, &camera, &tf, Some(&lighting), Some(&f));
    assert_eq!(both.plan.effects, vec!["gradient-opacity", "shading"]);
    assert_eq!(both.plan.passes, vec!["volume-shaded"]);
    assert_eq!(count(&both).1, varying, "one gradient per sample for both effects");
}

/// The gradient opacity multiplies each sample's opacity before the
/// slice-spacing correction, so a brick's picture does not depend on its
/// stride. A constant field (opacity `a = 0.1` a reference spacing) drawn
/// at stride 2, every slice `2 d0` apart (ratio 2), under a factor
/// `c = 0.5`: each slice is `1 - (1 - c a)^2`. With `m` slices on the ray
/// (from the picture without the factor, `1 - A = (1 - a)^(2m)`), the pixel
/// is `1 - (1 - c a)^(2m)`, through the plan's constant (no gradient) and
/// through a function equal to `c` at every magnitude the field has
/// (gradients taken), within 1e-5. VTK's ray caster multiplies after its
/// corrected table, `c (1 - (1 - a)^2)` a slice here, which depends on the
/// sample distance (docs/VTK.md): more than 1e-3 away. The reference at
/// `l = 0.05` steps over the 16 units of z: `1 - (1 - c a)^16` too.
#[test]
fn gradient_opacity_scales_the_opacity_before_the_correction() {
    use crate::geometry::camera::Projection;
    let n = 17;
    let data = vec![0.5f32; n * n * n];
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [n; 3]).unwrap();
    let shape = *grid.shape();
    let (a, c) = (0.1f64, 0.5f64);
    let tf = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(0.0, a as f32)]).unwrap();
    let camera =
        Camera::new([8.0, 8.0, 40.0], [8.0, 8.0, 8.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 4.0 }).unwrap();
    let plain = draw_list(&shape, &camera, &[brick(0, [0; 3], [16; 3], 2)], SurfacePass::None);
    let centre = |image: &Image| f64::from(image.rgba[4 * 8 + 4][3]);
    let alpha = |list: &DrawList| centre(&composite(&grid, list, &tf, 8, 8, None).unwrap());
    let m = (1.0 - alpha(&plain)).ln() / (2.0 * (1.0 - a).ln());
    assert!((m - m.round()).abs() < 1e-3 && m.round() >= 4.0, "slices on the ray: {m}");
    let m = m.round();
    let expected = 1.0 - (1.0 - c * a).powf(2.0 * m);
    let vtk = 1.0 - (1.0 - c * (1.0 - (1.0 - a).powi(2))).powf(m);
    assert!((expected - vtk).abs() > 1e-3, "{expected} vs {vtk}");

    let mut scaled = plain.clone();
    scaled.plan.opacity_scale = c;
    let function = GradientOpacity::new(vec![(0.0, c as f32), (1e6, c as f32), (2e6, 0.25)]).unwrap();
    let mut varying = plain.clone();
    varying.plan.gradient_opacity = true;
    varying.gradient_opacity = Some(function.clone());
    for (name, list) in [("constant", &scaled), ("function", &varying)] {
        let got = alpha(list);
        assert!((got - expected).abs() < 1e-5, "{name}: {got} vs {expected} (after the correction {vtk})");
    }

    let options =
        ReferenceOptions { step: Some(0.05), gradient_opacity: Some(&function), ..ReferenceOptions::default() };
    let truth = centre(&reference(&grid, &tf, &camera, 8, 8, &options).unwrap());
    let exact = 1.0 - (1.0 - c * a).powf(16.0);
    assert!((truth - exact).abs() < 1e-5, "reference {truth} vs {exact}");
}
