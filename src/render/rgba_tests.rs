//! RGBA volumes (four dependent components): the CPU compositor against the
//! reference (colour from fields 0, 1, 2 read as VTK 9.2 reads them, opacity
//! from field 3's `v'`, gradient from field 0), unshaded and shaded, u8 and float data; the
//! selection's bytes (4 a texel for u8, 16 otherwise) and visibility by
//! field 3; NaN and constant components; the planner's rule (one field
//! plans nothing of it and does none of its work).

use super::compositor::{composite, composite_counting};
use super::metrics::compare;
use super::reference::{reference, ReferenceOptions};
use super::rgba::{
    brick_texels_rgba_f32_into, brick_texels_rgba_u8_into, composite_rgba, composite_rgba_counted, reference_rgba,
    upload_rgba,
};
use super::texture::upload;
use crate::data::grid::{Grid, GridShape, Samples, ScalarType};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, RgbaOctree};
use crate::plan::dependent::{plan_fields, rgba_texel_bytes, Fields, RGBA_EFFECT};
use crate::plan::select::{select, SelectOptions};
use crate::plan::texel_format::TexelEncoding;
use crate::plan::{draw_list, Blend, BlendMode, DrawList, Scene};
use crate::transfer::direct_colour::RgbaScale;
use crate::transfer::lighting::{Lighting, Material};
use crate::transfer::TransferFunction;

const N: usize = 33;

/// The four components at grid point `(i, j, k)`, each in `[0, 1]`: red a
/// ramp along x, green along y, blue a checkerboard in the corner
/// `[0, 10)^3` (detail the selection refines there first) over 0.4, alpha a
/// ball of radius 12 (1 at the centre, 0 at its surface).
fn components(i: usize, j: usize, k: usize) -> [f64; 4] {
    let [x, y, z] = [i, j, k].map(|v| v as f64);
    let checker = if i < 10 && j < 10 && k < 10 { 0.5 * ((i + j + k) % 2) as f64 } else { 0.0 };
    let r = ((x - 16.0).powi(2) + (y - 16.0).powi(2) + (z - 16.0).powi(2)).sqrt();
    [x / 32.0, y / 32.0, 0.4 + checker, (1.0 - r / 12.0).max(0.0)]
}

/// The components as u8 (`255 c`, rounded), interleaved.
fn rgba_u8() -> Vec<u8> {
    let mut data = Vec::with_capacity(4 * N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                data.extend(components(i, j, k).map(|c| (255.0 * c).round() as u8));
            }
        }
    }
    data
}

/// The components as f32, `0.9 c + 0.05` for the colour (VTK 9.2 reads
/// floats as they are) and `2 c` for alpha (whose opacity VTK reads at
/// `v' = 2 v` over its range [0, 2]), interleaved.
fn rgba_f32() -> Vec<f32> {
    let mut data = Vec::with_capacity(4 * N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let c = components(i, j, k);
                data.extend(
                    [100.0 * c[0] - 20.0, 100.0 * c[1] - 20.0, 100.0 * c[2] - 20.0, 2.0 * c[3]].map(|v| v as f32),
                );
            }
        }
    }
    data
}

fn shape() -> GridShape {
    GridShape { dims: [N; 3], spacing: [1.0; 3], origin: [0.0; 3] }
}

fn grids<'a>(samples: Samples<'a>) -> Vec<Grid<'a>> {
    (0..4).map(|c| Grid::new(samples, shape(), 4, Some(c)).unwrap()).collect()
}

fn four<'a, 'b>(g: &'b [Grid<'a>]) -> [&'b Grid<'a>; 4] {
    [&g[0], &g[1], &g[2], &g[3]]
}

/// VTK's reading of `octree`'s data (its type the one given).
fn scale(octree: &RgbaOctree, scalar: ScalarType) -> RgbaScale {
    assert_eq!(octree.scale, RgbaScale::vtk(scalar, octree.ranges));
    octree.scale
}

/// Opacity 0 at alpha 0 rising to 0.3 at alpha's maximum `top` (the
/// colour function is not used: a loud one shows if it were).
fn opacity_tf(top: f64) -> TransferFunction {
    TransferFunction::new(vec![(0.0, [1.0, 0.0, 1.0]), (top, [0.0, 1.0, 0.0])], vec![(0.0, 0.0), (top, 0.3)]).unwrap()
}

/// The selection of the combined tree at `budget` bytes (`rgba_texel_bytes`
/// a texel), visible where the opacity function over the node's alpha range
/// is not 0, and its DrawList planned for `fields`.
#[allow(clippy::too_many_arguments)]
fn planned(
    octree: &RgbaOctree,
    scalar: ScalarType,
    tf: &TransferFunction,
    camera: &Camera,
    budget: usize,
    mode: BlendMode,
    lighting: Option<&Lighting>,
    fields: Fields,
) -> DrawList {
    let options = SelectOptions { bytes_per_texel: rgba_texel_bytes(scalar), ..SelectOptions::new(budget, 0.0) };
    let selection = select(&octree.combined, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
    let range = octree.red.value_range();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: lighting,
        gradient_opacity: None,
        blend: Blend::new(mode, [range.0, range.1]),
        region: None,
        transfer_2d: None,
    };
    let mut list = draw_list(&octree.combined, &shape(), &selection, camera, &scene, None).unwrap();
    list.texel = TexelEncoding::float32(scalar, range);
    plan_fields(list, fields)
}

/// The compositor draws the RGBA volume as the reference does (colour from
/// the components read as VTK 9.2 reads them, opacity at `v'` of component
/// 3, gradient of component 0): u8 and f32 data, unshaded and shaded
/// (headlight), parallel and perspective, at the full budget (stride 1) and
/// at budgets of mixed strides. Metric RMSE of RGBA in [0, 1]. Measured: full
/// budget u8 0.00003 to 0.00006, f32 0.0003 to 0.0014 (its alpha 2c is read
/// at `v' = 2 min(2c, 1)`: the opacity has a kink where it saturates, which
/// slices and rays sample differently), bound 0.003; mixed strides 0.0006
/// to 0.0069, bound 0.008. The RGBA picture is far from component 3 drawn
/// alone through the colour function (RMSE above 0.02; measured 0.029 to 0.1).
#[test]
fn compositor_matches_the_reference() {
    let bytes = rgba_u8();
    let floats = rgba_f32();
    let cases = [(Samples::U8(&bytes), ScalarType::U8, 255.0), (Samples::F32(&floats), ScalarType::F32, 2.0)];
    let lighting = Lighting::headlight(Material::default());
    for (samples, scalar, top) in cases {
        let g = grids(samples);
        let octree = RgbaOctree::build(four(&g), &BuildOptions { leaf_size: 8 }).unwrap();
        let rgb = scale(&octree, scalar);
        let tf = opacity_tf(top);
        for (parallel, shaded) in [(true, false), (false, false), (true, true)] {
            let light = shaded.then_some(&lighting);
            let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
            let options = ReferenceOptions { lighting: light, ..ReferenceOptions::default() };
            let truth = reference_rgba(four(&g), rgb, &tf, &camera, 64, 64, &options).unwrap();
            let alone = reference(&g[3], &tf, &camera, 64, 64, &options).unwrap();
            let apart = compare(&truth, &alone).unwrap();
            assert!(apart.rmse > 0.02, "the colour fields must show: {apart:?}");
            let mut mixed = 0;
            for budget in [1usize << 30, 100_000, 60_000] {
                let budget = budget * rgba_texel_bytes(scalar) / 4;
                let list = planned(&octree, scalar, &tf, &camera, budget, BlendMode::Composite, light, Fields::Rgba);
                let expected: Vec<&str> = if shaded { vec![RGBA_EFFECT, "shading"] } else { vec![RGBA_EFFECT] };
                assert!(list.plan.rgba && !list.plan.dependent && list.plan.effects == expected, "{:?}", list.plan);
                let strides: std::collections::BTreeSet<usize> = list.bricks.iter().map(|b| b.brick.stride).collect();
                mixed += usize::from(strides.len() >= 2);
                let textures = upload_rgba(four(&g), rgb, &list).unwrap();
                let image = composite_rgba(&textures, &list, &tf, 64, 64).unwrap();
                let m = compare(&image, &truth).unwrap();
                eprintln!(
                    "rgba {scalar:?} parallel {parallel} shaded {shaded} budget {budget} strides {strides:?}: {m:?}"
                );
                let bound = if strides.len() == 1 && strides.contains(&1) { 0.003 } else { 0.008 };
                assert!(m.rmse < bound, "{scalar:?} parallel {parallel} shaded {shaded} budget {budget}: {m:?}");
            }
            assert!(mixed >= 1, "no budget gave mixed strides");
        }
    }
}

/// The selection counts the bytes as uploaded (4 a texel for u8: RGBA8;
/// 16 for f32: RGBA32F), skips what component 3 makes transparent whatever
/// the colours, and the GPU texels are the four components in order.
#[test]
fn selection_counts_uploaded_bytes_and_alpha_visibility() {
    let bytes = rgba_u8();
    let floats = rgba_f32();
    for (samples, scalar, per_texel, top) in
        [(Samples::U8(&bytes), ScalarType::U8, 4, 255.0), (Samples::F32(&floats), ScalarType::F32, 16, 2.0)]
    {
        let g = grids(samples);
        let octree = RgbaOctree::build(four(&g), &BuildOptions { leaf_size: 8 }).unwrap();
        assert_eq!(rgba_texel_bytes(scalar), per_texel);
        let tf = opacity_tf(top);
        let options = SelectOptions { bytes_per_texel: per_texel, ..SelectOptions::new(1 << 30, 0.0) };
        let s = select(&octree.combined, &options, |a, b| !tf.is_transparent_over(a, b)).unwrap();
        let texels: usize = s.bricks.iter().map(|b| b.texels.iter().product::<usize>()).sum();
        assert_eq!(s.texture_bytes, per_texel * texels, "{scalar:?}");
        // The ball (alpha > 0) is within 12 of the centre: the corner bricks are skipped, colours or not.
        assert!(s.skipped > 0);
        assert!(s.bricks.iter().all(|b| (0..3).all(|a| b.hi[a] >= 4 && b.lo[a] <= 28)), "{:?}", s.bricks);
        // A budget of a quarter of that selects within it.
        let quarter = SelectOptions { bytes_per_texel: per_texel, ..SelectOptions::new(s.texture_bytes / 4, 0.0) };
        let q = select(&octree.combined, &quarter, |a, b| !tf.is_transparent_over(a, b)).unwrap();
        assert!(q.texture_bytes <= s.texture_bytes / 4, "{} > {}", q.texture_bytes, s.texture_bytes / 4);
        // Texels: four channels, component order.
        let b = &s.bricks[0];
        let count: usize = b.texels.iter().product();
        let mut out = vec![0.0f32; 4 * count];
        brick_texels_rgba_f32_into(four(&g), b, false, &mut out).unwrap();
        let [i, j, k] = b.lo;
        assert_eq!(
            out[..4].iter().map(|&v| f64::from(v)).collect::<Vec<_>>(),
            (0..4).map(|c| g[c].value(i, j, k)).collect::<Vec<_>>()
        );
        assert!(brick_texels_rgba_f32_into(four(&g), b, false, &mut out[..count]).is_err());
        let mut eight = vec![0u8; 4 * count];
        match scalar {
            ScalarType::U8 => {
                brick_texels_rgba_u8_into(four(&g), b, false, &mut eight).unwrap();
                assert!(eight.iter().zip(&out).all(|(&e, &f)| f32::from(e) == f));
            }
            _ => {
                let e = brick_texels_rgba_u8_into(four(&g), b, false, &mut eight).unwrap_err().to_string();
                assert!(e.contains("unsigned char"), "{e}");
            }
        }
    }
}

/// A NaN in any component is no data (transparent) in the compositor as in
/// the reference; constant colour components are read as VTK 9.2 reads them.
/// Measured RMSE of the NaN picture 0.0004, bound 0.004.
#[test]
fn nan_and_constant_components() {
    let mut floats = rgba_f32();
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let r2 = [i, j, k].iter().map(|&v| (v as f64 - 16.0).powi(2)).sum::<f64>();
                if r2 <= 25.0 {
                    floats[4 * (i + N * (j + N * k)) + 1] = f32::NAN; // green
                }
            }
        }
    }
    let g = grids(Samples::F32(&floats));
    let octree = RgbaOctree::build(four(&g), &BuildOptions { leaf_size: 8 }).unwrap();
    let rgb = scale(&octree, ScalarType::F32);
    let tf = opacity_tf(2.0);
    let camera = Camera::around([0.0; 3], [32.0; 3], 0.0, 0.0, true).unwrap();
    let truth = reference_rgba(four(&g), rgb, &tf, &camera, 48, 48, &ReferenceOptions::default()).unwrap();
    let list = planned(&octree, ScalarType::F32, &tf, &camera, 1 << 30, BlendMode::Composite, None, Fields::Rgba);
    let image = composite_rgba(&upload_rgba(four(&g), rgb, &list).unwrap(), &list, &tf, 48, 48).unwrap();
    let m = compare(&image, &truth).unwrap();
    eprintln!("rgba with a NaN green ball: {m:?}");
    assert!(m.rmse < 0.004, "{m:?}");
    let clean = rgba_f32();
    let gc = grids(Samples::F32(&clean));
    let whole = reference_rgba(four(&gc), rgb, &tf, &camera, 48, 48, &ReferenceOptions::default()).unwrap();
    let centre = |im: &super::image::Image| im.rgba[24 + 48 * 24][3];
    assert!(centre(&truth) < centre(&whole) - 0.05, "{} vs {}", centre(&truth), centre(&whole));
    assert!(centre(&image) < centre(&whole) - 0.05, "{} vs {}", centre(&image), centre(&whole));

    // Constant colour components, read as VTK 9.2 reads them: a float red
    // of 0.25 is 0.25 (floats as they are); a double red of 7.5 is 0 (wide
    // types scaled to their range, a constant one to 0 at its value); a u8
    // blue of 100 is 100 / 255. Premultiplied: the channel is the factor
    // times the opacity.
    let premultiplied = |pic: &super::image::Image, channel: usize, factor: f32| {
        pic.rgba.iter().any(|p| p[3] > 0.1) && pic.rgba.iter().all(|p| (p[channel] - factor * p[3]).abs() < 1e-5)
    };
    let mut constant = clean.clone();
    constant.chunks_exact_mut(4).for_each(|q| q[0] = 0.25);
    let gk = grids(Samples::F32(&constant));
    let tk = RgbaOctree::build(four(&gk), &BuildOptions { leaf_size: 8 }).unwrap();
    assert_eq!(tk.ranges[0], (0.25, 0.25));
    let options = ReferenceOptions::default();
    let pic = reference_rgba(four(&gk), scale(&tk, ScalarType::F32), &tf, &camera, 48, 48, &options).unwrap();
    assert!(premultiplied(&pic, 0, 0.25), "float red 0.25");
    let doubles: Vec<f64> =
        clean.iter().enumerate().map(|(i, &v)| if i % 4 == 0 { 7.5 } else { f64::from(v) }).collect();
    let gd = grids(Samples::F64(&doubles));
    let td = RgbaOctree::build(four(&gd), &BuildOptions { leaf_size: 8 }).unwrap();
    let pic = reference_rgba(four(&gd), scale(&td, ScalarType::F64), &tf, &camera, 48, 48, &options).unwrap();
    assert!(premultiplied(&pic, 0, 0.0), "double red constant: 0");
    let mut bytes = rgba_u8();
    bytes.chunks_exact_mut(4).for_each(|q| q[2] = 100);
    let gb = grids(Samples::U8(&bytes));
    let tb = RgbaOctree::build(four(&gb), &BuildOptions { leaf_size: 8 }).unwrap();
    let pic =
        reference_rgba(four(&gb), scale(&tb, ScalarType::U8), &opacity_tf(255.0), &camera, 48, 48, &options).unwrap();
    assert!(premultiplied(&pic, 2, 100.0 / 255.0), "u8 blue 100");
}

/// The planner runs none of it for one field (the plan, effects and picture
/// of the single-field pipeline, and no colour read from colour fields) nor
/// outside Composite; the RGBA compositor refuses a list that does not plan it.
#[test]
fn a_single_field_plans_nothing_of_it() {
    let bytes = rgba_u8();
    let g = grids(Samples::U8(&bytes));
    let octree = RgbaOctree::build(four(&g), &BuildOptions { leaf_size: 8 }).unwrap();
    let rgb = scale(&octree, ScalarType::U8);
    let tf = opacity_tf(255.0);
    let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, true).unwrap();
    let list = planned(&octree, ScalarType::U8, &tf, &camera, 1 << 30, BlendMode::Composite, None, Fields::Rgba);
    let single = plan_fields(list.clone(), Fields::One);
    assert!(!single.plan.rgba && !single.plan.dependent && single.plan.effects.is_empty(), "{:?}", single.plan);
    let mut by_hand = list.clone();
    by_hand.plan.rgba = false;
    by_hand.plan.effects.clear();
    assert_eq!(single, by_hand);
    let (plain, counts) = composite_counting(&upload(&g[3], &single).unwrap(), &single, &tf, 32, 32).unwrap();
    assert_eq!(counts.direct_colours, 0, "a single field reads no colour field");
    assert_eq!(plain.rgba, composite(&g[3], &by_hand, &tf, 32, 32, None).unwrap().rgba);
    let textures = upload_rgba(four(&g), rgb, &list).unwrap();
    let (_, counts) = composite_rgba_counted(&textures, &list, &tf, 32, 32).unwrap();
    assert!(counts.direct_colours > 0 && counts.gradients == 0, "{counts:?}");
    let e = composite_rgba(&textures, &single, &tf, 32, 32).unwrap_err().to_string();
    assert!(e.contains("does not plan an RGBA"), "{e}");
    let two = plan_fields(list.clone(), Fields::Two);
    assert!(!two.plan.rgba && two.plan.dependent);
    let mip = planned(&octree, ScalarType::U8, &tf, &camera, 1 << 30, BlendMode::Mip, None, Fields::Rgba);
    assert!(!mip.plan.rgba && !mip.plan.effects.iter().any(|e| e == RGBA_EFFECT));
}
