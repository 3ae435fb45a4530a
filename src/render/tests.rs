//! Tests across the module: the compositor executing hand-made DrawLists
//! against the reference ray caster.

use super::compositor::composite;
use super::image::{Image, BACKGROUND};
use super::metrics::compare;
use super::reference::{reference, ReferenceOptions};
use crate::data::grid::{Grid, GridShape, ScalarType};
use crate::datasets::{generate, Dataset};
use crate::geometry::camera::{Camera, Projection};
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::select::Brick;
use crate::plan::{Batch, BrickDraw, DrawList, Plan, SurfacePass};
use crate::surface::{Surface, SurfaceOptions};
use crate::transfer::TransferFunction;

/// A brick over the index box `[lo, hi]` sampled every `stride` cells.
fn brick(node: u32, lo: [usize; 3], hi: [usize; 3], stride: usize) -> Brick {
    crate::plan::select::test_brick(node, lo, hi, stride)
}

/// Slice depths `k d` (integer k) with `near <= k d < far`, `near` and `far`
/// the box's smallest and largest view depth, back to front (largest first);
/// the convention of [`crate::plan::slab::slice_depths`].
fn slice_depths(camera: &Camera, lo: [f64; 3], hi: [f64; 3], d: f64) -> Vec<f64> {
    let depths: Vec<f64> =
        (0..8).map(|c| camera.depth([0, 1, 2].map(|a| if c >> a & 1 == 0 { lo[a] } else { hi[a] }))).collect();
    let near = depths.iter().copied().fold(f64::INFINITY, f64::min);
    let far = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let ks = (near / d).floor() as i64 - 1..=(far / d).ceil() as i64 + 1;
    ks.rev().map(|k| k as f64 * d).filter(|&z| near <= z && z < far).collect()
}

/// A DrawList of `bricks`, slices every `stride` reference spacings, sorted
/// back to front by the depth of their centres (a valid order for bricks of
/// one size under a parallel projection, or for one brick).
fn draw_list(shape: &GridShape, camera: &Camera, bricks: &[Brick], surface: SurfacePass) -> DrawList {
    let d0 = crate::data::spacing::reference_spacing(shape);
    let mut draws: Vec<BrickDraw> = bricks
        .iter()
        .map(|&brick| {
            let world_lo = shape.world(brick.lo.map(|v| v as f64));
            let world_hi = shape.world(brick.hi.map(|v| v as f64));
            let slice_spacing = brick.stride as f64 * d0;
            let slices = slice_depths(camera, world_lo, world_hi, slice_spacing);
            BrickDraw { brick, world_lo, world_hi, slice_spacing, slices, batches: Vec::new(), points: Vec::new() }
        })
        .collect();
    let centre = |d: &BrickDraw| camera.depth([0, 1, 2].map(|a| 0.5 * (d.world_lo[a] + d.world_hi[a])));
    draws.sort_by(|a, b| centre(b).total_cmp(&centre(a)));
    let plan = Plan {
        volume: true,
        surface,
        shading: false,
        gradient_opacity: false,
        transfer_2d: false,
        opacity_scale: 1.0,
        skipped_bricks: 0,
        blend: Default::default(),
        passes: Vec::new(),
        dependent: false,
        rgba: false,
        effects: Vec::new(),
        jitter: false,
        scattering: false,
        sample_distance: None,
        min_slice_spacing: None,
    };
    DrawList {
        plan,
        camera: *camera,
        bricks: draws,
        opaque_triangles: Vec::new(),
        reference_spacing: d0,
        lighting: None,
        region: None,
        gradient_opacity: None,
        transfer_2d: None,
        scattering: None,
        texel: Default::default(),
    }
}

/// Leaf bricks of `size` cells tiling the grid, at stride 1.
fn leaf_bricks(dims: [usize; 3], size: usize) -> Vec<Brick> {
    let mut out = Vec::new();
    for z in (0..dims[2] - 1).step_by(size) {
        for y in (0..dims[1] - 1).step_by(size) {
            for x in (0..dims[0] - 1).step_by(size) {
                let lo = [x, y, z];
                let hi = [0, 1, 2].map(|a| (lo[a] + size).min(dims[a] - 1));
                out.push(brick(out.len() as u32, lo, hi, 1));
            }
        }
    }
    out
}

/// For the sphere field (0.3 at the centre, 0.5 on the sphere, 0.8 in the
/// box's corners): a fog, densest at the centre, gone beyond the sphere, so
/// that the box's own edges do not make the silhouette (where slices and
/// rays differ most: a ray grazing a corner crosses no slice or one).
fn fog() -> TransferFunction {
    TransferFunction::new(
        vec![(0.3, [1.0, 0.9, 0.6]), (0.6, [0.3, 0.5, 1.0])],
        vec![(0.3, 0.15), (0.5, 0.04), (0.6, 0.0)],
    )
    .unwrap()
}

/// (d) Full-resolution leaf bricks (stride 1), slices every voxel: the
/// compositor differs from the reference (samples every 1/4 voxel along the
/// ray) only by where it samples. Measured RMSE 0.0040 (parallel, 8 bricks)
/// and 0.0060 (perspective, 1 brick; the slices stay one voxel apart in depth
/// while the off-axis rays cross them up to 1/cos(21°) = 7 % further apart);
/// the bound is 0.012, SSIM above 0.99.
#[test]
fn full_resolution_bricks_match_the_reference() {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = fog();
    let shape = *grid.shape();
    for (parallel, bricks) in [(true, leaf_bricks(shape.dims, 16)), (false, vec![brick(0, [0; 3], [32; 3], 1)])] {
        let camera = Camera::around([0.0; 3], [32.0; 3], 30.0, 20.0, parallel).unwrap();
        let list = draw_list(&shape, &camera, &bricks, SurfacePass::None);
        let image = composite(&grid, &list, &tf, 64, 64, None).unwrap();
        let truth = reference(&grid, &tf, &camera, 64, 64, &ReferenceOptions::default()).unwrap();
        let m = compare(&image, &truth).unwrap();
        eprintln!("full resolution, parallel {parallel}: {m:?}");
        assert!(m.rmse < 0.012 && m.ssim > 0.99, "parallel {parallel}: {m:?}");
        assert!(truth.rgba.iter().filter(|p| p[3] > 0.1).count() > 500, "the test picture is empty");
    }
}

/// (e) Four bricks at strides 1, 2, 4 and 8 side by side (the four xy
/// quadrants of a 33^3 sphere field, seen from above, one pixel ray every
/// half voxel so some rays run exactly along the shared faces): no seam. The
/// error of every ray on or next to a shared face is at most the largest
/// error inside the bricks it touches (bound: that maximum, plus 1e-6);
/// every error is below 0.05 (measured 0.030, in the stride-8 brick).
#[test]
fn bricks_of_four_strides_show_no_seam() {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = fog();
    let shape = *grid.shape();
    // Pixel (px, py) looks down -z at world (px / 2, 32 - py / 2).
    let camera =
        Camera::new([16.0, 16.0, 100.0], [16.0, 16.0, 16.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 16.25 })
            .unwrap();
    let bricks = [
        brick(0, [0, 0, 0], [16, 16, 32], 1),
        brick(1, [16, 0, 0], [32, 16, 32], 2),
        brick(2, [0, 16, 0], [16, 32, 32], 4),
        brick(3, [16, 16, 0], [32, 32, 32], 8),
    ];
    let list = draw_list(&shape, &camera, &bricks, SurfacePass::None);
    let (w, h) = (65, 65);
    let image = composite(&grid, &list, &tf, w, h, None).unwrap();
    let truth = reference(&grid, &tf, &camera, w, h, &ReferenceOptions::default()).unwrap();
    let (a, b) = (image.luminance(BACKGROUND), truth.luminance(BACKGROUND));
    let error = |px: usize, py: usize| (a[px + w * py] - b[px + w * py]).abs();
    // Side of the seam of a pixel column (x = px / 2) or row (y = 32 - py / 2): 1 when x or y >= 16.
    let xside = |px: usize| (px >= 32) as usize;
    let yside = |py: usize| (py <= 32) as usize;
    let quadrant = |px: usize, py: usize| xside(px) + 2 * yside(py);
    let near_seam = |p: usize| (31..=33).contains(&p);
    let mut inside = [0.0f64; 4];
    for py in 0..h {
        for px in 0..w {
            if !near_seam(px) && !near_seam(py) {
                let q = quadrant(px, py);
                inside[q] = inside[q].max(error(px, py));
            }
        }
    }
    eprintln!("largest error inside the bricks of strides 1, 2, 4, 8: {inside:?}");
    assert!(inside[0] < inside[1] && inside[1] < inside[2] && inside[2] < inside[3], "{inside:?}");
    assert!(inside.iter().all(|&e| e < 0.1), "{inside:?}");
    for py in 0..h {
        for px in 0..w {
            if near_seam(px) || near_seam(py) {
                // The bricks the ray may touch: both sides of each seam it is near.
                let xs: &[usize] = if near_seam(px) { &[0, 1] } else { &[xside(px)] };
                let ys: &[usize] = if near_seam(py) { &[0, 1] } else { &[yside(py)] };
                let bound =
                    xs.iter().flat_map(|&x| ys.iter().map(move |&y| x + 2 * y)).map(|q| inside[q]).fold(0.0, f64::max);
                assert!(error(px, py) <= bound + 1e-6, "seam at pixel ({px}, {py}): {} > {bound}", error(px, py));
            }
        }
    }
}

/// The picture is the same on one thread and on two.
#[test]
fn pictures_do_not_depend_on_the_thread_count() {
    let volume = generate(Dataset::MarschnerLobb, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = TransferFunction::ramp(0.0, 1.0);
    let camera = Camera::around([0.0; 3], [32.0; 3], 40.0, 30.0, false).unwrap();
    let list = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [32; 3], 2)], SurfacePass::None);
    let run = |threads: usize| -> (Image, Image) {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            (
                composite(&grid, &list, &tf, 48, 40, None).unwrap(),
                reference(&grid, &tf, &camera, 48, 40, &ReferenceOptions::default()).unwrap(),
            )
        })
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.0, two.0);
    assert_eq!(one.1, two.1);
}

fn sphere_surface() -> (crate::data::volume::Volume, Surface) {
    let volume = generate(Dataset::Sphere, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let surface = Surface::extract(&grid, &octree, &SurfaceOptions::interpolated(0.5)).unwrap();
    (volume, surface)
}

/// An opaque isosurface: drawn first, the volume in front of it blended
/// over it. Against the reference (the same surface, rays stopped at it):
/// measured RMSE 0.0034, bound 0.01.
#[test]
fn opaque_surface_matches_the_reference() {
    let (volume, surface) = sphere_surface();
    let grid = volume.grid(None).unwrap();
    // Faint volume outside the sphere (values above 0.5), transparent inside.
    let tf = TransferFunction::new(vec![(0.5, [0.2, 0.4, 1.0])], vec![(0.5, 0.0), (0.8, 0.05)]).unwrap();
    let camera = Camera::around([0.0; 3], [32.0; 3], 20.0, 30.0, true).unwrap();
    let mut list = draw_list(grid.shape(), &camera, &leaf_bricks(grid.dims(), 16), SurfacePass::Opaque);
    list.opaque_triangles = (0..surface.polygon_count() as u32).collect();
    let colour = [1.0, 0.8, 0.5, 1.0];
    let image = composite(&grid, &list, &tf, 64, 64, Some((&surface, colour))).unwrap();
    let options = ReferenceOptions {
        step: None,
        surface: Some((&surface, colour)),
        lighting: None,
        gradient_opacity: None,
        transfer_2d: None,
        region: None,
        opacity_unit: None,
        scattering: None,
    };
    let truth = reference(&grid, &tf, &camera, 64, 64, &options).unwrap();
    let m = compare(&image, &truth).unwrap();
    eprintln!("opaque surface: {m:?}");
    assert!(m.rmse < 0.01, "{m:?}");
    // The centre pixel sees the sphere: opaque, orange, lit head-on.
    let centre = image.rgba[32 + 64 * 32];
    assert_eq!(centre[3], 1.0);
    assert!(centre[0] > 0.8 && centre[2] < centre[1], "{centre:?}");
    // Without the surface the list cannot be drawn.
    assert!(composite(&grid, &list, &tf, 8, 8, None).unwrap_err().to_string().contains("no surface"));
}

/// A translucent plane between the slices of one brick: blended after the
/// slices behind it and before those in front, exactly (1e-6); a clip range
/// that excludes it drops it. The reference agrees within RMSE 0.02
/// (measured 0.0145: both see 8 voxels of fog, but the slicer puts 4 of
/// them in front of the plane at z = 4.5 where the ray caster has 3.5).
#[test]
fn translucent_batches_are_blended_inside_their_slab() {
    let data = vec![0.5f32; 9 * 9 * 9];
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [9, 9, 9]).unwrap();
    let tf = TransferFunction::new(vec![(0.0, [1.0, 1.0, 1.0])], vec![(0.0, 0.1)]).unwrap();
    let camera =
        Camera::new([4.0, 4.0, 100.0], [4.0, 4.0, 4.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 3.0 }).unwrap();
    let plane = super::triangles::tests::surface_of(&[
        [[-1.0, -1.0, 4.5], [9.0, -1.0, 4.5], [9.0, 9.0, 4.5]],
        [[-1.0, -1.0, 4.5], [9.0, 9.0, 4.5], [-1.0, 9.0, 4.5]],
    ]);
    let mut list = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [8; 3], 1)], SurfacePass::Translucent);
    // Slices at depths 99 (z = 1) down to 92 (z = 8); the plane (depth 95.5)
    // is in slab #{slices > 95.5} = 4: after the slices 99..=96, before 95.
    let slices = &list.bricks[0].slices;
    assert_eq!((slices.len(), slices[0], slices[3], slices[4]), (8, 99.0, 96.0, 95.0));
    list.bricks[0].batches = vec![Batch { slab: 4, triangles: 0..2, clip: None }];
    let colour = [0.0, 0.0, 1.0, 0.5];
    let image = composite(&grid, &list, &tf, 6, 6, Some((&plane, colour))).unwrap();
    let mut acc = [0.0; 4];
    for _ in 0..4 {
        acc = super::blend::over(acc, [1.0; 3], 0.1);
    }
    acc = super::blend::over(acc, [0.0, 0.0, 1.0], 0.5);
    for _ in 0..4 {
        acc = super::blend::over(acc, [1.0; 3], 0.1);
    }
    for p in &image.rgba {
        for k in 0..4 {
            assert!((p[k] as f64 - acc[k]).abs() < 1e-6, "{p:?} vs {acc:?}");
        }
    }
    let options = ReferenceOptions {
        step: None,
        surface: Some((&plane, colour)),
        lighting: None,
        gradient_opacity: None,
        transfer_2d: None,
        region: None,
        opacity_unit: None,
        scattering: None,
    };
    let truth = reference(&grid, &tf, &camera, 6, 6, &options).unwrap();
    let m = compare(&image, &truth).unwrap();
    eprintln!("translucent plane: {m:?}");
    assert!(m.rmse < 0.02, "{m:?}");
    // The last slab comes after every slice.
    list.bricks[0].batches[0].slab = 8;
    let last = composite(&grid, &list, &tf, 6, 6, Some((&plane, colour))).unwrap();
    let front = super::blend::over([1.0 - 0.9f64.powi(8); 4], [0.0, 0.0, 1.0], 0.5);
    assert!((last.rgba[0][2] as f64 - front[2]).abs() < 1e-6 && (last.rgba[0][0] as f64 - front[0]).abs() < 1e-6);
    // Clipped away: only the volume.
    list.bricks[0].batches[0].clip = Some((90.0, 95.0));
    let clipped = composite(&grid, &list, &tf, 6, 6, Some((&plane, colour))).unwrap();
    let volume_only = 1.0 - 0.9f64.powi(8);
    assert!((clipped.rgba[0][3] as f64 - volume_only).abs() < 1e-6 && clipped.rgba[0][2] == clipped.rgba[0][0]);
}

/// Bricks stacked along the view, their shared face seen head-on at a
/// slice depth: the slice on the face is listed by one brick only (the one
/// whose near face it is) and drawn once, from above and from below; two
/// bricks composite exactly like one (1e-6), 8 slices for 8 voxels.
#[test]
fn a_face_seen_head_on_is_sampled_once() {
    let data = vec![0.5f32; 5 * 5 * 9];
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [5, 5, 9]).unwrap();
    let tf = TransferFunction::new(vec![(0.0, [1.0, 1.0, 1.0])], vec![(0.0, 0.1)]).unwrap();
    for eye_z in [100.0, -100.0] {
        let camera =
            Camera::new([2.0, 2.0, eye_z], [2.0, 2.0, 4.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 2.0 })
                .unwrap();
        let one = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [4, 4, 8], 1)], SurfacePass::None);
        let two = [brick(0, [0; 3], [4, 4, 4], 1), brick(1, [0, 0, 4], [4, 4, 8], 1)];
        let two = draw_list(grid.shape(), &camera, &two, SurfacePass::None);
        assert_eq!(two.bricks.iter().map(|b| b.slices.len()).sum::<usize>(), 8);
        let (a, b) =
            (composite(&grid, &one, &tf, 5, 5, None).unwrap(), composite(&grid, &two, &tf, 5, 5, None).unwrap());
        for (p, q) in a.rgba.iter().zip(&b.rgba) {
            assert!((p[3] - q[3]).abs() < 1e-6 && (p[3] as f64 - (1.0 - 0.9f64.powi(8))).abs() < 1e-6, "{p:?} {q:?}");
        }
    }
}

/// DrawLists that do not fit the grid are refused with a reason.
#[test]
fn foreign_draw_lists_are_refused() {
    let data = vec![0.5f32; 5 * 5 * 5];
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [5, 5, 5]).unwrap();
    let tf = TransferFunction::ramp(0.0, 1.0);
    let camera = Camera::around([0.0; 3], [4.0; 3], 0.0, 0.0, true).unwrap();
    let list = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [8; 3], 2)], SurfacePass::None);
    let e = composite(&grid, &list, &tf, 4, 4, None).unwrap_err().to_string();
    assert!(e.contains("not a brick of this"), "{e}");
    let mut list = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [4; 3], 2)], SurfacePass::None);
    list.bricks[0].slices.reverse();
    assert!(composite(&grid, &list, &tf, 4, 4, None).unwrap_err().to_string().contains("back to front"));
}

/// The whole pipeline (selection, DrawList from [`crate::plan::draw_list`],
/// compositor) against the reference on the 65^3 phantom, volume alone and
/// with its isosurface opaque and translucent. At full resolution (every
/// brick at stride 1) the compositor is within RMSE 0.01 of the reference
/// (measured 0.0036 volume, 0.0040 opaque, 0.0036 translucent); a budget of
/// 1/8 of the full-resolution texture stays within 0.05 (measured 0.011).
#[test]
fn the_pipeline_tracks_the_reference() {
    use crate::plan::select::{select, uniform, SelectOptions};
    use crate::plan::Scene;
    let volume = generate(Dataset::SheppLogan, 65, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let surface = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(0.5)).unwrap();
    let tf = TransferFunction::ramp(0.0, 1.0);
    let camera = Camera::around([0.0; 3], [64.0; 3], 30.0, 20.0, false).unwrap();
    let full = uniform(&octree, 1, 4).unwrap();
    let options = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(full.texture_bytes / 4, 0.0) };
    let coarse =
        select(&octree, &options, |min, max| !tf.is_transparent_over(min, max) || (min < 0.5 && 0.5 <= max)).unwrap();
    let colour = [0.9, 0.75, 0.55];
    for (name, selection, opacity, bound) in [
        ("full, volume", &full, 0.0, 0.01),
        ("full, opaque surface", &full, 1.0, 0.01),
        ("full, translucent surface", &full, 0.4, 0.01),
        ("1/4 budget, translucent surface", &coarse, 0.4, 0.05),
    ] {
        let scene = Scene {
            surface: Some(&surface),
            surface_opacity: opacity,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        // Translucent: the selection's SlabPolygons made once, apart from the view.
        let polygons = (opacity > 0.0 && opacity < 1.0)
            .then(|| crate::plan::slab::SlabPolygons::new(&octree, &surface, grid.shape(), selection));
        let list =
            crate::plan::draw_list(&octree, grid.shape(), selection, &camera, &scene, polygons.as_ref()).unwrap();
        let with = (opacity > 0.0).then_some((&surface, [colour[0], colour[1], colour[2], opacity as f32]));
        let image = composite(&grid, &list, &tf, 96, 96, with).unwrap();
        let options = ReferenceOptions {
            step: None,
            surface: with,
            lighting: None,
            gradient_opacity: None,
            transfer_2d: None,
            region: None,
            opacity_unit: None,
            scattering: None,
        };
        let truth = reference(&grid, &tf, &camera, 96, 96, &options).unwrap();
        let m = compare(&image, &truth).unwrap();
        let strides: Vec<usize> =
            (0..4).map(|s| list.bricks.iter().filter(|b| b.brick.stride == 1 << s).count()).collect();
        eprintln!("{name}: {} bricks (strides 1, 2, 4, 8: {strides:?}), {m:?}", list.bricks.len());
        assert!(m.rmse < bound, "{name}: {m:?}");
    }
}

/// Early ray termination: a dense fog (opacity 0.7 per slice, 8 slices) stops
/// after 6 slices, at `1 - 0.3^6 >= OPAQUE`; the picture is within
/// `1 - OPAQUE` of the whole sum `1 - 0.3^8`, in every channel. The opaque
/// surface behind is then dropped too, within the same bound.
#[test]
fn rays_stop_once_opaque_within_the_bound() {
    use super::compositor::OPAQUE;
    let data = vec![0.5f32; 9 * 9 * 9];
    let grid = Grid::scalar(crate::data::grid::Samples::F32(&data), [9, 9, 9]).unwrap();
    let tf = TransferFunction::new(vec![(0.0, [1.0, 0.5, 0.25])], vec![(0.0, 0.7)]).unwrap();
    let camera =
        Camera::new([4.0, 4.0, 100.0], [4.0, 4.0, 4.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 3.0 }).unwrap();
    let list = draw_list(grid.shape(), &camera, &[brick(0, [0; 3], [8; 3], 1)], SurfacePass::None);
    let image = composite(&grid, &list, &tf, 6, 6, None).unwrap();
    let (stopped, whole) = (1.0 - 0.3f64.powi(6), 1.0 - 0.3f64.powi(8));
    assert!(stopped >= OPAQUE && 1.0 - 0.3f64.powi(5) < OPAQUE);
    for p in &image.rgba {
        assert!((p[3] as f64 - stopped).abs() < 1e-6, "{p:?}");
        for (k, c) in [1.0, 0.5, 0.25, 1.0].iter().enumerate() {
            assert!((p[k] as f64 - c * whole).abs() <= 1.0 - OPAQUE, "{p:?}");
        }
    }
}

#[path = "shade_tests.rs"]
mod shade_tests;

#[path = "gradient_opacity_tests.rs"]
mod gradient_opacity_tests;

#[path = "transfer2d_tests.rs"]
mod transfer2d_tests;

#[path = "scattering_tests.rs"]
mod scattering_tests;

#[path = "texel_format_tests.rs"]
mod texel_format_tests;

/// A plan that names an effect none of whose inputs is set takes the
/// general loop (every effect's branch) and draws exactly what the plain
/// loop of a plan without effects draws.
#[test]
fn the_plain_loop_draws_what_the_general_loop_draws() {
    let volume = generate(Dataset::MarschnerLobb, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let tf = TransferFunction::ramp(0.0, 1.0);
    let camera = Camera::around([0.0; 3], [32.0; 3], 40.0, 30.0, false).unwrap();
    let bricks = [brick(0, [0, 0, 0], [16, 32, 32], 1), brick(1, [16, 0, 0], [32, 32, 32], 2)];
    let plain = draw_list(grid.shape(), &camera, &bricks, SurfacePass::None);
    assert!(plain.plan.effects.is_empty());
    let mut general = plain.clone();
    general.plan.effects.push("no-op".into());
    let a = composite(&grid, &plain, &tf, 48, 40, None).unwrap();
    let b = composite(&grid, &general, &tf, 48, 40, None).unwrap();
    assert!(a.rgba.iter().any(|p| p[3] > 0.1), "the volume is drawn");
    assert_eq!(a, b);
}
