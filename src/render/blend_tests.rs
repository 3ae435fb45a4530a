//! The blend modes besides Composite: analytic volumes, the compositor at
//! full budget against the reference caster, and a MIP of the angiogram
//! under a small budget that keeps every vessel.

use super::compositor::{composite, composite_textures};
use super::image::Image;
use super::intensity::Reduction;
use super::metrics::compare;
use super::reference::{reference_blend, ReferenceOptions};
use super::texture::upload;
use crate::data::grid::{Grid, GridShape, Samples, ScalarType};
use crate::datasets::{generate, Dataset};
use crate::geometry::camera::{Camera, Projection};
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::select::{select, SelectOptions};
use crate::plan::{draw_list, Blend, BlendMode, DrawList, Scene};
use crate::transfer::TransferFunction;

/// The DrawList of `octree`'s selection under `budget` bytes for `mode`
/// (the mode's transparency test), seen by `camera`.
fn list(
    octree: &VolumeOctree,
    shape: &GridShape,
    tf: &TransferFunction,
    budget: usize,
    mode: BlendMode,
    camera: &Camera,
) -> DrawList {
    let (lo, hi) = octree.value_range();
    let blend = match mode {
        // Two surfaces, at 0.3 and 0.6 of the range.
        BlendMode::Isosurface => Blend::isosurfaces(&[lo + 0.3 * (hi - lo), lo + 0.6 * (hi - lo)], [lo, hi]).unwrap(),
        _ => Blend::new(mode, [lo, hi]),
    };
    let visible = |a: f64, b: f64| blend.visible(a, b, &|a, b| !tf.is_transparent_over(a, b));
    let options = SelectOptions {
        pooled: mode.is_extremum(),
        gradient_border: mode == BlendMode::Isosurface,
        ..SelectOptions::new(budget, 0.0)
    };
    let selection = select(octree, &options, visible).unwrap();
    let scene = Scene::volume(blend);
    draw_list(octree, shape, &selection, camera, &scene, None).unwrap()
}

/// A quadratic ramp `f = z^2 / 8` (0 ..= 8 on z = 0 ..= 8; not trilinear, so
/// a full budget draws it at stride 1) seen along -z. Every compositor ray
/// takes the slices `z = 1, ..., 8` (depths `d_min <= z < d_max`: the far
/// face is the next brick's near face, none here), weight 1, and the
/// reference the midpoints `z = (i + 1/2) / 4`, weight 1/4, of the
/// piecewise-linear field between the grid values; each renderer's picture
/// is the reduction ([`Reduction`], tested on its own) of exactly those
/// samples, within 1e-6: MIP the transfer function at the ray's max exactly.
#[test]
fn a_ramp_reduces_to_its_extremes_mean_and_sum() {
    let v = |z: usize| (z * z) as f64 / 8.0;
    let data: Vec<f32> = (0..9 * 9 * 9).map(|i| v(i / 81) as f32).collect();
    let grid = Grid::scalar(Samples::F32(&data), [9, 9, 9]).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let tf =
        TransferFunction::new(vec![(0.0, [0.0, 0.0, 1.0]), (8.0, [1.0, 0.0, 0.0])], vec![(0.0, 0.01), (8.0, 0.05)])
            .unwrap();
    let camera =
        Camera::new([4.0, 4.0, 20.0], [4.0, 4.0, 0.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 3.0 }).unwrap();
    let field = |z: f64| {
        let i = (z.floor() as usize).min(7);
        v(i) + (z - i as f64) * (v(i + 1) - v(i))
    };
    let slices: Vec<(f64, f64)> = (1..=8).map(|z| (v(z), 1.0)).collect();
    let midpoints: Vec<(f64, f64)> = (0..32).map(|i| (field((i as f64 + 0.5) / 4.0), 0.25)).collect();
    let lookup = |x: f64| tf.eval(x).map(f64::from);
    for mode in [BlendMode::Mip, BlendMode::Minip, BlendMode::Average, BlendMode::Additive] {
        let l = list(&octree, &shape, &tf, 1 << 30, mode, &camera);
        assert_eq!(l.plan.passes, vec![mode.pass()]);
        assert!(l.bricks.iter().all(|b| b.brick.stride == 1), "{mode:?}: not at full resolution");
        let blend = l.plan.blend;
        let expect = |samples: &[(f64, f64)]| {
            let mut r = Reduction::new();
            for &(x, w) in samples {
                r.add(&blend, x, w, lookup);
            }
            r.resolve(&blend, true, lookup)
        };
        let image = composite(&grid, &l, &tf, 8, 8, None).unwrap();
        let truth = reference_blend(&grid, &tf, &camera, 8, 8, &ReferenceOptions::default(), &blend).unwrap();
        let (e_image, e_truth) = (expect(&slices), expect(&midpoints));
        for (p, q) in image.rgba.iter().zip(&truth.rgba) {
            for c in 0..4 {
                assert!((p[c] as f64 - e_image[c]).abs() < 1e-6, "{mode:?} compositor: {p:?} vs {e_image:?}");
                assert!((q[c] as f64 - e_truth[c]).abs() < 1e-6, "{mode:?} reference: {q:?} vs {e_truth:?}");
            }
        }
        if mode == BlendMode::Mip {
            let exact = [0.05, 0.0, 0.0, 0.05];
            assert!((0..4).all(|c| (e_image[c] - exact[c]).abs() < 1e-7), "the max, 8, on the near face: {e_image:?}");
        }
    }
}

/// At full budget (every brick at stride 1, or constant) the compositor and
/// the reference differ only by where they sample: slices every `d0`
/// against midpoints every `d0 / 4`. Shepp-Logan 33^3, perspective.
/// Measured RMSE: composite 0.0040, MIP 0.0125 (the slices miss the thin
/// ellipses' peaks by up to half a spacing; bound 0.02), MinIP 0.0004,
/// additive 0.0103 (bound 0.02), average 0.041 (bound 0.05: a ray grazing
/// the box's silhouette crosses no slice but a few midpoints, and an
/// average of any sample is opaque grey: up to 0.43 on those pixels),
/// isosurface 0.021 (a crossing is found one slice step late, `d0`, against
/// `d0 / 4`: its silhouettes shift; bound 0.03); the others' bound 0.01.
#[test]
fn full_budget_matches_the_reference_in_every_mode() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let (lo, hi) = octree.value_range();
    let tf = TransferFunction::new(
        vec![(lo, [0.2, 0.3, 1.0]), (hi, [1.0, 0.9, 0.6])],
        vec![(lo, 0.01), (lo + 0.1 * (hi - lo), 0.02), (hi, 0.3)],
    )
    .unwrap();
    let camera = Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), 30.0, 20.0, false).unwrap();
    for (mode, bound) in [
        (BlendMode::Composite, 0.01),
        (BlendMode::Mip, 0.02),
        (BlendMode::Minip, 0.01),
        (BlendMode::Average, 0.05),
        (BlendMode::Additive, 0.02),
        (BlendMode::Isosurface, 0.03),
    ] {
        let l = list(&octree, &shape, &tf, 1 << 30, mode, &camera);
        let coarse = l.bricks.iter().filter(|b| b.brick.stride > 1);
        assert!(coarse.map(|b| octree.node(b.brick.node)).all(|n| n.min == n.max), "{mode:?}: not at full resolution");
        let image = composite(&grid, &l, &tf, 64, 64, None).unwrap();
        let truth = reference_blend(&grid, &tf, &camera, 64, 64, &ReferenceOptions::default(), &l.plan.blend).unwrap();
        let m = compare(&image, &truth).unwrap();
        eprintln!("{mode:?} at full budget: {m:?}");
        assert!(m.rmse < bound, "{mode:?}: {m:?}");
        assert!(truth.rgba.iter().filter(|p| p[3] > 0.005).count() > 500, "{mode:?}: the test picture is empty");
    }
}

/// VTK's opacity per ScalarOpacityUnitDistance `U` in every mode
/// ([`BlendMode::opacity_per_reference`]): the reference caster with a
/// table per `U = 5 d0` (its `opacity_unit`) draws within 1e-3 (max over
/// the channels; the table is converted at its 65 points, exact between
/// them only for the linear rules) of the caster with the table taken to
/// `d0` by the mode's rule, and the compositor at full budget with that
/// table within the bounds of [`full_budget_matches_the_reference_in_every_mode`].
/// Another mode's rule (Composite's power for the others, none for
/// Composite) moves pixels by more than 5e-3, five times that bound (MinIP
/// the least, 0.009): the rule is what is tested.
#[test]
fn opacity_unit_distance_per_mode() {
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let (lo, hi) = octree.value_range();
    let d0 = crate::data::spacing::reference_spacing(&shape);
    let unit = 5.0 * d0;
    let colors = vec![(lo, [0.2, 0.3, 1.0]), (hi, [1.0, 0.9, 0.6])];
    // A smooth opacity, 0.02 to 0.3 over the range, at 65 points.
    let at = |i: usize| lo + (hi - lo) * i as f64 / 64.0;
    let raw: Vec<(f64, f32)> = (0..=64).map(|i| (at(i), (0.02 + 0.28 * (i as f64 / 64.0).powi(2)) as f32)).collect();
    let per_unit = TransferFunction::new(colors.clone(), raw.clone()).unwrap();
    let taken = |rule: BlendMode| {
        let points = raw.iter().map(|&(v, a)| (v, rule.opacity_per_reference(f64::from(a), d0 / unit) as f32));
        TransferFunction::new(colors.clone(), points.collect()).unwrap()
    };
    let camera = Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), 30.0, 20.0, false).unwrap();
    // The same samples, d0 / 4 apart (without a step the caster's follows its unit).
    let at_unit = ReferenceOptions { opacity_unit: Some(unit), step: Some(d0 / 4.0), ..ReferenceOptions::default() };
    for (mode, bound, wrong) in [
        (BlendMode::Composite, 0.01, BlendMode::Mip),
        (BlendMode::Mip, 0.02, BlendMode::Composite),
        (BlendMode::Minip, 0.01, BlendMode::Composite),
        (BlendMode::Average, 0.05, BlendMode::Composite),
        (BlendMode::Additive, 0.02, BlendMode::Composite),
        (BlendMode::Isosurface, 0.03, BlendMode::Composite),
    ] {
        let tf = taken(mode);
        let l = list(&octree, &shape, &tf, 1 << 30, mode, &camera);
        let blend = l.plan.blend;
        let vtk = reference_blend(&grid, &per_unit, &camera, 64, 64, &at_unit, &blend).unwrap();
        let ours = reference_blend(&grid, &tf, &camera, 64, 64, &ReferenceOptions::default(), &blend).unwrap();
        let same = compare(&ours, &vtk).unwrap();
        let image = composite(&grid, &l, &tf, 64, 64, None).unwrap();
        let drawn = compare(&image, &vtk).unwrap();
        let other =
            reference_blend(&grid, &taken(wrong), &camera, 64, 64, &ReferenceOptions::default(), &blend).unwrap();
        let moved = compare(&other, &vtk).unwrap();
        eprintln!("{mode:?} at U = 5 d0: reference {same:?}, compositor {drawn:?}, {wrong:?}'s rule {moved:?}");
        assert!(same.max_abs < 1e-3, "{mode:?}: the reference per d0 against per U: {same:?}");
        assert!(drawn.rmse < bound, "{mode:?}: the compositor against the reference per U: {drawn:?}");
        assert!(moved.max_abs > 5e-3, "{mode:?}: {wrong:?}'s rule changes the picture: {moved:?}");
        assert!(vtk.rgba.iter().filter(|p| p[3] > 0.005).count() > 500, "{mode:?}: the test picture is empty");
    }
}

/// The connected regions (4-neighbours) of the pixels whose opacity is above `threshold`.
fn regions(image: &Image, threshold: f32) -> Vec<Vec<usize>> {
    let (w, h) = (image.width, image.height);
    let mut seen = vec![false; w * h];
    let mut out = Vec::new();
    for start in 0..w * h {
        if seen[start] || image.rgba[start][3] <= threshold {
            continue;
        }
        let (mut region, mut stack) = (Vec::new(), vec![start]);
        seen[start] = true;
        while let Some(p) = stack.pop() {
            region.push(p);
            let (x, y) = (p % w, p / w);
            let next = [
                (x > 0).then(|| p - 1),
                (x + 1 < w).then(|| p + 1),
                (y > 0).then(|| p - w),
                (y + 1 < h).then(|| p + w),
            ];
            for q in next.into_iter().flatten() {
                if !seen[q] && image.rgba[q][3] > threshold {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
        out.push(region);
    }
    out
}

/// MIP of the 128^3 angiogram under a budget of a thirtieth of its full
/// resolution keeps every vessel: in each vessel (a connected region, at
/// least 8 pixels, of the full-resolution picture's pixels whose opacity,
/// a ramp over the values, is above 0.3: tissue stays below 0.12) the
/// largest opacity is at least 95 % of the full-resolution picture's. Full
/// resolution: the compositor with every brick at stride 1, on the same
/// slice lattice (the reference caster's midpoints `d0 / 4` apart differ
/// from it by up to 16 % on the thinnest vessels' peaks, at any budget:
/// that is where a slice falls, not what a coarse brick hides). The bound
/// is one-sided: peak-keeping texels may show a peak up to a stride away,
/// brighter than the full-resolution pixel there (measured up to 1 against
/// 0.79). The same bricks with plain coarse texels lose vessels (the test
/// fails without the pooling): measured worst ratio 1.0 pooled, 0.13 plain
/// (6 vessel regions).
#[test]
fn mip_under_a_small_budget_keeps_every_vessel() {
    let volume = generate(Dataset::Vessels, 128, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let shape = *grid.shape();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let (lo, hi) = octree.value_range();
    let tf = TransferFunction::new(vec![(lo, [1.0, 1.0, 1.0])], vec![(lo, 0.0), (hi, 1.0)]).unwrap();
    let camera = Camera::around(shape.world([0.0; 3]), shape.world([127.0; 3]), 20.0, 15.0, true).unwrap();
    let full_bytes = 128 * 128 * 128 * 4;
    let l = list(&octree, &shape, &tf, full_bytes / 30, BlendMode::Mip, &camera);
    assert!(l.bricks.iter().filter(|b| b.brick.stride >= 4).count() * 2 > l.bricks.len(), "the budget is not small");
    let (w, h) = (128, 128);
    let pooled = composite(&grid, &l, &tf, w, h, None).unwrap();
    let full = list(&octree, &shape, &tf, 1 << 30, BlendMode::Mip, &camera);
    let truth = composite(&grid, &full, &tf, w, h, None).unwrap();
    // Plain texels: the textures of the same bricks uploaded for a Composite list.
    let mut plain_list = l.clone();
    plain_list.plan.blend.mode = BlendMode::Composite;
    let plain = composite_textures(&upload(&grid, &plain_list).unwrap(), &l, &tf, w, h, None).unwrap();
    let vessels: Vec<Vec<usize>> = regions(&truth, 0.3).into_iter().filter(|r| r.len() >= 4).collect();
    assert!(vessels.len() >= 3, "{} vessel regions", vessels.len());
    let peak = |image: &Image, r: &[usize]| r.iter().map(|&p| image.rgba[p][3]).fold(0.0f32, f32::max);
    let (mut worst_pooled, mut worst_plain) = (f32::INFINITY, f32::INFINITY);
    for r in &vessels {
        let t = peak(&truth, r);
        eprintln!("region of {} pixels: full {t}, pooled {}, plain {}", r.len(), peak(&pooled, r), peak(&plain, r));
        worst_pooled = worst_pooled.min(peak(&pooled, r) / t);
        worst_plain = worst_plain.min(peak(&plain, r) / t);
    }
    eprintln!("{} vessel regions; worst peak ratio pooled {worst_pooled}, plain {worst_plain}", vessels.len());
    assert!(worst_pooled >= 0.95, "pooled: a vessel's peak down to {worst_pooled} of full resolution");
    assert!(worst_plain < 0.95, "plain texels keep every vessel too: the test does not discriminate");
}
