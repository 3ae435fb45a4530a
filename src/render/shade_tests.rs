//! Shaded volumes: the compositor against the reference with the same
//! gradient rule, no seams between bricks of different strides (shaded, and
//! with a gradient opacity), and no gradient work when the plan does not shade.

use super::*;
use crate::render::compositor::composite_counting_gradients;
use crate::render::texture::upload;
use crate::transfer::lighting::{Light, LightSpace, Lighting, Lights, Material};
use crate::transfer::GradientOpacity;

/// VTK's default material under a white headlight.
fn headlight() -> Lighting {
    Lighting::headlight(Material::default())
}

/// A light kit like ParaView's (key, fill, back and head lights in view
/// space; vtkLightKit's default intensities and warmths left white), black
/// ambient colours.
fn light_kit() -> Lighting {
    let light = |direction: [f64; 3], intensity: f64| Light {
        direction,
        space: LightSpace::View,
        ambient: [0.0; 3],
        diffuse: [intensity; 3],
        specular: [intensity; 3],
    };
    Lighting {
        material: Material::default(),
        lights: Lights::Directional(vec![
            light([-0.35, -0.7, -0.6], 0.75),
            light([0.8, 0.2, -0.55], 0.25),
            light([0.6, 0.1, 0.8], 0.2),
            light([0.0, 0.0, -1.0], 0.25),
        ]),
        two_sided: true,
    }
}

/// `list` made to shade with `lighting` (as the planner does).
fn shaded(mut list: DrawList, lighting: &Lighting) -> DrawList {
    list.plan.shading = true;
    list.lighting = Some(lighting.in_world(&list.camera));
    list
}

/// A shell: opaque-ish near the sphere's surface (0.5), so the gradient
/// gives it relief.
fn shell() -> TransferFunction {
    TransferFunction::new(
        vec![(0.3, [1.0, 0.9, 0.6]), (0.6, [0.3, 0.5, 1.0])],
        vec![(0.3, 0.0), (0.45, 0.05), (0.5, 0.3), (0.55, 0.05), (0.6, 0.0)],
    )
    .unwrap()
}

/// Full-resolution bricks (stride 1) against the reference, shaded with
/// the headlight and with a light kit, parallel and perspective: the same
/// gradient rule, so the pictures differ only by where they sample.
/// Measured RMSE 0.00012 to 0.00020 (max 0.0024), while shading moves the
/// reference by 0.13 to 0.15 RMSE; bound 0.002, SSIM > 0.999.
#[test]
fn shaded_full_resolution_matches_the_reference() {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = shell();
    let shape = *grid.shape();
    for lighting in [headlight(), light_kit()] {
        for (parallel, bricks) in [(true, leaf_bricks(shape.dims, 16)), (false, vec![brick(0, [0; 3], [32; 3], 1)])] {
            let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
            let list = shaded(draw_list(&shape, &camera, &bricks, SurfacePass::None), &lighting);
            let image = composite(&grid, &list, &tf, 64, 64, None).unwrap();
            let options = ReferenceOptions { lighting: Some(&lighting), ..ReferenceOptions::default() };
            let truth = reference(&grid, &tf, &camera, 64, 64, &options).unwrap();
            let unshaded = reference(&grid, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
            let m = compare(&image, &truth).unwrap();
            let shading = compare(&truth, &unshaded).unwrap();
            eprintln!(
                "shaded full resolution, parallel {parallel}, {:?}: {m:?} (shading moves {:.4})",
                lighting.lights, shading.rmse
            );
            assert!(m.rmse < 0.002 && m.ssim > 0.999, "parallel {parallel}: {m:?}");
            assert!(shading.rmse > 5.0 * m.rmse, "the shading must show: {shading:?} vs {m:?}");
        }
    }
}

/// Four bricks at strides 1, 2, 4 and 8 side by side, shaded (the unshaded
/// test `bricks_of_four_strides_show_no_seam`, a headlight from above): the
/// gradient border gives each brick's faces its neighbours' samples at its
/// own stride, so the error of every ray on or next to a shared face is at
/// most the largest error inside the bricks it touches (+ 1e-6). Measured:
/// inside 0.0008, 0.0053, 0.021, 0.096 (strides 1, 2, 4, 8), along the
/// seams at most 0.094.
#[test]
fn shaded_bricks_of_four_strides_show_no_seam() {
    let lighting = headlight();
    assert_four_strides_seamless("shaded", |list| shaded(list, &lighting), Some(&lighting), None);
}

/// The same with a gradient opacity (the same gradients, from the same
/// borders), unshaded and shaded. Measured: gradient opacity, inside
/// 0.0009, 0.0070, 0.022, 0.11, along the seams at most 0.097; with the
/// shading, inside 0.0010, 0.0060, 0.014, 0.074, seams at most 0.062.
#[test]
fn gradient_opacity_bricks_of_four_strides_show_no_seam() {
    let f = sphere_gradient_opacity();
    let with = |list: DrawList| with_gradient_opacity(list, &f);
    assert_four_strides_seamless("gradient opacity", with, None, Some(&f));
    let lighting = headlight();
    let both = |list: DrawList| with_gradient_opacity(shaded(list, &lighting), &f);
    assert_four_strides_seamless("gradient opacity, shaded", both, Some(&lighting), Some(&f));
}

/// A gradient opacity for the sphere, whose field has magnitude `1 / (sqrt(3)
/// 32)` = 0.018 per voxel away from its centre: 0.3 there, 1 at twice it.
fn sphere_gradient_opacity() -> GradientOpacity {
    GradientOpacity::new(vec![(0.0, 0.0), (0.018, 0.3), (0.036, 1.0)]).unwrap()
}

/// `list` made to apply `f` per sample (as the planner does).
fn with_gradient_opacity(mut list: DrawList, f: &GradientOpacity) -> DrawList {
    list.plan.gradient_opacity = true;
    list.gradient_opacity = Some(f.clone());
    list
}

/// The four-strides seam check (see `shaded_bricks_of_four_strides_show_no_seam`)
/// for the list `effects` makes, against the reference with `lighting` and `gradient_opacity`.
fn assert_four_strides_seamless(
    label: &str,
    effects: impl Fn(DrawList) -> DrawList,
    lighting: Option<&Lighting>,
    gradient_opacity: Option<&GradientOpacity>,
) {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = shell();
    let shape = *grid.shape();
    let camera =
        Camera::new([16.0, 16.0, 100.0], [16.0, 16.0, 16.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 16.25 })
            .unwrap();
    let bricks = [
        brick(0, [0, 0, 0], [16, 16, 32], 1),
        brick(1, [16, 0, 0], [32, 16, 32], 2),
        brick(2, [0, 16, 0], [16, 32, 32], 4),
        brick(3, [16, 16, 0], [32, 32, 32], 8),
    ];
    let list = effects(draw_list(&shape, &camera, &bricks, SurfacePass::None));
    let (w, h) = (65, 65);
    let image = composite(&grid, &list, &tf, w, h, None).unwrap();
    let options = ReferenceOptions { lighting, gradient_opacity, transfer_2d: None, ..ReferenceOptions::default() };
    let truth = reference(&grid, &tf, &camera, w, h, &options).unwrap();
    let (a, b) = (image.luminance(BACKGROUND), truth.luminance(BACKGROUND));
    let error = |px: usize, py: usize| (a[px + w * py] - b[px + w * py]).abs();
    let xside = |px: usize| (px >= 32) as usize;
    let yside = |py: usize| (py <= 32) as usize;
    let near_seam = |p: usize| (31..=33).contains(&p);
    let mut inside = [0.0f64; 4];
    let mut seam = 0.0f64;
    for py in 0..h {
        for px in 0..w {
            if !near_seam(px) && !near_seam(py) {
                let q = xside(px) + 2 * yside(py);
                inside[q] = inside[q].max(error(px, py));
            }
        }
    }
    eprintln!("{label}: largest error inside the bricks of strides 1, 2, 4, 8: {inside:?}");
    for py in 0..h {
        for px in 0..w {
            if near_seam(px) || near_seam(py) {
                let xs: &[usize] = if near_seam(px) { &[0, 1] } else { &[xside(px)] };
                let ys: &[usize] = if near_seam(py) { &[0, 1] } else { &[yside(py)] };
                let bound =
                    xs.iter().flat_map(|&x| ys.iter().map(move |&y| x + 2 * y)).map(|q| inside[q]).fold(0.0, f64::max);
                seam = seam.max(error(px, py));
                assert!(
                    error(px, py) <= bound + 1e-6,
                    "{label}: seam at pixel ({px}, {py}): {} > {bound}",
                    error(px, py)
                );
            }
        }
    }
    eprintln!("{label}: largest error along the seams {seam}");
    assert!(inside.iter().all(|&e| e < 0.2), "{label}: {inside:?}");
}

/// The unshaded path takes no gradient, a shaded one one per visible
/// sample; a planner given identity shading (ambient 1, diffuse and
/// specular 0) plans "volume" and takes none either.
#[test]
fn gradients_only_when_shading() {
    let volume = generate(Dataset::Sphere, 17, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = shell();
    let shape = *grid.shape();
    let camera = Camera::around([0.0; 3], [16.0; 3], 30.0, 20.0, false).unwrap();
    let plain = draw_list(&shape, &camera, &[brick(0, [0; 3], [16; 3], 2)], SurfacePass::None);
    let count =
        |list: &DrawList| composite_counting_gradients(&upload(&grid, list).unwrap(), list, &tf, 32, 32).unwrap();
    let (image, none) = count(&plain);
    assert_eq!(none, 0);
    let (lit, some) = count(&shaded(plain.clone(), &headlight()));
    assert!(some > 100, "{some}");
    assert_ne!(image, lit);
    // The planner, from an octree's selection.
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let selection =
        crate::plan::select::select(&octree, &crate::plan::select::SelectOptions::new(1 << 20, 0.0), |a, b| {
            !tf.is_transparent_over(a, b)
        })
        .unwrap();
    let identity = Lighting::headlight(Material { ambient: 1.0, diffuse: 0.0, specular: 0.0, specular_power: 10.0 });
    let scene = crate::plan::Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: Some(&identity),
        gradient_opacity: None,
        transfer_2d: None,
        blend: Default::default(),
        region: None,
    };
    let list = crate::plan::draw_list(&octree, &shape, &selection, &camera, &scene, None).unwrap();
    assert_eq!(list.plan.passes, vec!["volume"]);
    assert_eq!(count(&list).1, 0);
    let lighting = headlight();
    let scene = crate::plan::Scene { shading: Some(&lighting), ..scene };
    let list = crate::plan::draw_list(&octree, &shape, &selection, &camera, &scene, None).unwrap();
    assert_eq!(list.plan.passes, vec!["volume-shaded"]);
    assert!(count(&list).1 > 100);
    // Textures of an unshaded list (no border) do not fit a shaded one.
    let e = composite_counting_gradients(&upload(&grid, &plain).unwrap(), &shaded(plain.clone(), &lighting), &tf, 8, 8);
    assert!(e.unwrap_err().to_string().contains("another DrawList"));
}
