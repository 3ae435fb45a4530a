//! The numerical-stability suite: hard volumes and views through the public
//! API, each case against an f64 reference (the full-resolution reference
//! ray caster, the same field at ordinary values, or a closed form) with
//! the bound it must meet stated beside its assert.
//!
//! RMSE is over R, G, B of premultiplied pictures in `[0, 1]`.

use hybrid_octree::camera::{Camera, Projection};
use hybrid_octree::grid::{Grid, GridShape, GridVisitor, Sample, ScalarType, TypedGrid};
use hybrid_octree::hybrid::HybridOctree;
use hybrid_octree::octree::leaf_stats::{leaf_stats, Scratch};
use hybrid_octree::octree::{BuildOptions, KernelPath, Layout, VolumeOctree};
use hybrid_octree::plan::{draw_list, DrawList, Scene};
use hybrid_octree::render::compositor::composite;
use hybrid_octree::render::image::Image;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::render::reference::{reference, ReferenceOptions};
use hybrid_octree::render::transfer::TransferFunction;
use hybrid_octree::select::{select, uniform, SelectOptions};
use hybrid_octree::surface::{Surface, SurfaceOptions};
use hybrid_octree::volume::{SampleBuf, Volume};

const PIXELS: usize = 48;

/// `dims` samples of `f(i, j, k)` stored as `scalar_type`, with `spacing`.
fn volume(
    dims: [usize; 3],
    scalar_type: ScalarType,
    spacing: [f64; 3],
    f: impl Fn(usize, usize, usize) -> f64,
) -> Volume {
    let mut values = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                values.push(f(i, j, k));
            }
        }
    }
    let mut v = Volume::new(SampleBuf::from_f64(&values, scalar_type), dims, "stability");
    v.shape.spacing = spacing;
    v
}

/// A ball of radius 6 around (8, 8, 8) over a gentle x ramp, mapped to
/// `[lo, hi]` (`t` in `[0, 1]` gives `lo (1 - t) + hi t`, no overflow).
fn ball(lo: f64, hi: f64) -> impl Fn(usize, usize, usize) -> f64 {
    move |i, j, k| {
        let inside = (i as f64 - 8.0).powi(2) + (j as f64 - 8.0).powi(2) + (k as f64 - 8.0).powi(2) < 36.0;
        let t = if inside { 0.8 } else { 0.0 } + 0.2 * i as f64 / 16.0;
        lo * (1.0 - t) + hi * t
    }
}

/// A camera around the volume's world box.
fn around(shape: &GridShape, azimuth: f64, elevation: f64, parallel: bool) -> Camera {
    let far = shape.dims.map(|d| (d - 1) as f64);
    Camera::around(shape.world([0.0; 3]), shape.world(far), azimuth, elevation, parallel).unwrap()
}

/// The octree's picture under a 64 MB budget (the CLI's selection, the
/// ramp transfer function over the data range) and the reference picture.
struct Frame {
    octree: VolumeOctree,
    list: DrawList,
    image: Image,
    truth: Image,
}

fn frame(grid: &Grid<'_>, camera: &Camera) -> Frame {
    let octree = VolumeOctree::build(grid, &BuildOptions { leaf_size: 8 }).unwrap();
    assert_eq!(octree.validate(), Ok(()));
    let (lo, hi) = octree.value_range();
    let tf = TransferFunction::ramp(lo, hi);
    let selection =
        select(&octree, &SelectOptions::new(64_000_000, 0.0), |a, b| !tf.is_transparent_over(a, b)).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: None,
        gradient_opacity: None,
        transfer_2d: None,
        region: None,
        blend: Default::default(),
    };
    let list = draw_list(&octree, grid.shape(), &selection, camera, &scene, None).unwrap();
    let image = composite(grid, &list, &tf, PIXELS, PIXELS, None).unwrap();
    let truth = reference(grid, &tf, camera, PIXELS, PIXELS, &ReferenceOptions::default()).unwrap();
    Frame { octree, list, image, truth }
}

fn rmse(a: &Image, b: &Image) -> f64 {
    compare(a, b).unwrap().rmse
}

fn slices(list: &DrawList) -> usize {
    list.bricks.iter().map(|b| b.slices.len()).sum()
}

/// A constant volume is one two-texel brick; its picture must still be the
/// reference's cube, for every scalar type. Bound: RMSE <= 0.02 (was 0.22,
/// a single slice drawn as a triangle).
#[test]
fn constant_volume_matches_the_reference() {
    for (ty, c) in [(ScalarType::F32, 0.5), (ScalarType::U8, 200.0), (ScalarType::I32, -7.0), (ScalarType::F64, 1e300)]
    {
        let v = volume([33; 3], ty, [1.0; 3], |_, _, _| c);
        let g = v.grid(None).unwrap();
        let f = frame(&g, &around(g.shape(), 30.0, 20.0, false));
        assert_eq!(f.octree.node(f.octree.root()).error(0), 0.0);
        let e = rmse(&f.image, &f.truth);
        assert!(e <= 0.02, "{ty:?} {c}: RMSE {e}");
        let covered = f.image.rgba.iter().filter(|p| p[3] > 0.5).count();
        assert!(covered > PIXELS * PIXELS / 5, "{ty:?}: the cube covers {covered} pixels");
    }
}

/// The same field at ordinary values, `[0, 1]`, is the f64 reference of a
/// field at extreme values: the transfer function follows the data range,
/// so the pictures must agree. Nodal errors are relative to the range, so
/// they must agree too.
fn assert_like_unit(lo: f64, hi: f64, ty: ScalarType, picture_bound: f64, error_bound: f64) {
    let unit = volume([17; 3], ScalarType::F64, [1.0; 3], ball(0.0, 1.0));
    let hard = volume([17; 3], ty, [1.0; 3], ball(lo, hi));
    let (gu, gh) = (unit.grid(None).unwrap(), hard.grid(None).unwrap());
    let camera = around(gu.shape(), 30.0, 20.0, false);
    let (fu, fh) = (frame(&gu, &camera), frame(&gh, &camera));
    let e = rmse(&fu.image, &fh.image);
    assert!(e <= picture_bound, "[{lo}, {hi}] {ty:?}: RMSE {e} against the unit field's picture");
    let e = rmse(&fh.truth, &fh.image);
    assert!(e <= 0.01, "[{lo}, {hi}] {ty:?}: RMSE {e} against its own reference");
    let (ru, rh) = (fu.octree.node(fu.octree.root()), fh.octree.node(fh.octree.root()));
    for p in 0..3 {
        let (a, b) = (ru.error(p) as f64, rh.error(p) as f64);
        assert!(b.is_finite() && (a - b).abs() <= error_bound, "[{lo}, {hi}] E_{p}: {b} vs {a}");
    }
}

/// f64 extremes +-1e308 (their differences overflow), the largest f64 and 0:
/// bound RMSE <= 1e-6 (the same picture) and nodal errors equal to 1e-6.
#[test]
fn f64_extremes_render_like_the_unit_field() {
    assert_like_unit(-1e308, 1e308, ScalarType::F64, 1e-6, 1e-6);
    assert_like_unit(0.0, f64::MAX, ScalarType::F64, 1e-6, 1e-6);
    assert_like_unit(-f64::MAX, f64::MAX, ScalarType::F64, 1e-6, 1e-6);
}

/// A 1e-3 range on a 1e9 offset keeps f64's ~2e-7 absolute precision, 2e-4
/// of the range: bound RMSE <= 2e-3, nodal errors within 1e-3.
#[test]
fn small_range_on_a_big_offset_renders_like_the_unit_field() {
    assert_like_unit(1e9, 1e9 + 1e-3, ScalarType::F64, 2e-3, 1e-3);
}

/// Subnormal samples (squares underflow to 0): bound RMSE <= 1e-6 and nodal
/// errors within 1e-6 (the values are exact multiples of 2^-1074 · 2^k,
/// scaled exactly).
#[test]
fn subnormal_samples_render_like_the_unit_field() {
    let tiny = f64::MIN_POSITIVE / 2f64.powi(20);
    assert_like_unit(0.0, tiny * 1024.0, ScalarType::F64, 2e-3, 2e-3);
}

/// i32 and u32 over their whole range (texels beyond 2^24 kept exactly as
/// f64): bound RMSE <= 2e-3 against the unit field (integer rounding of the
/// ramp), nodal errors within 1e-3.
#[test]
fn integer_extremes_render_like_the_unit_field() {
    assert_like_unit(i32::MIN as f64, i32::MAX as f64, ScalarType::I32, 2e-3, 1e-3);
    assert_like_unit(0.0, u32::MAX as f64, ScalarType::U32, 2e-3, 1e-3);
}

/// Spacings of 1e-6 and 1e6 draw the spacing-1 picture (bound: RMSE <= 1e-6);
/// anisotropic 1:1000 and a 1e-7 axis keep the slices bounded by the samples
/// (bound: at most 16 sqrt(3) slices per sample along the longest axis per
/// brick, never 1/spacing), and still match their reference (RMSE <= 0.02).
/// Subnormal spacings and far corners beyond f64::MAX are refused with why.
#[test]
fn spacings_scale_and_anisotropy_stays_bounded() {
    let at = |spacing: [f64; 3]| {
        let v = volume([17; 3], ScalarType::F32, spacing, ball(0.0, 1.0));
        let g = v.grid(None).unwrap();
        let f = frame(&g, &around(g.shape(), 30.0, 20.0, false));
        (f.image.clone(), f)
    };
    let (one, f1) = at([1.0; 3]);
    for s in [1e-6, 1e6, 1e-300, 1e300] {
        let (img, f) = at([s; 3]);
        let e = rmse(&one, &img);
        assert!(e <= 1e-6, "spacing {s}: RMSE {e} against spacing 1");
        assert_eq!(slices(&f.list), slices(&f1.list), "spacing {s}");
    }
    for (spacing, why) in [([1e-320; 3], "subnormal"), ([1.0, 1e308, 1.0], "beyond the largest f64")] {
        let v = volume([17; 3], ScalarType::F32, spacing, ball(0.0, 1.0));
        let e = v.grid(None).unwrap_err().to_string();
        assert!(e.contains(why), "{spacing:?}: {e}");
    }
    for spacing in [[1.0, 1.0, 1000.0], [1.0, 1.0, 1e-7], [1e-30, 1.0, 1.0], [1.0, 1e-300, 1.0]] {
        let (_, f) = at(spacing);
        let bound = f.list.bricks.len() * (16.0 * 3f64.sqrt() * 17.0).ceil() as usize;
        assert!(slices(&f.list) <= bound, "{spacing:?}: {} slices, bound {bound}", slices(&f.list));
        let e = rmse(&f.image, &f.truth);
        assert!(e <= 0.02, "{spacing:?}: RMSE {e}");
    }
}

/// The leaf kernel's buffers of every leaf of a 2x2xN needle and an NxNx2
/// slab: bounded by the brick, the same at N and 4N (was 2^L entries a leaf:
/// the build took time N^2).
struct LongestBuffer<'l>(&'l Layout);

impl GridVisitor for LongestBuffer<'_> {
    type Output = usize;
    fn visit<T: Sample>(self, g: TypedGrid<'_, T>) -> usize {
        let leaf = self.0.leaf_level();
        let d = self.0.level_dims(leaf);
        let mut scratch = Scratch::default();
        let mut longest = 0;
        for i in 0..d[0] * d[1] * d[2] {
            let (lo, hi) = self.0.node_box(leaf, [i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1])]);
            leaf_stats(&g, self.0, lo, hi, 1.0, KernelPath::Fast, &mut scratch);
            longest = longest.max(scratch.longest_buffer());
        }
        longest
    }
}

/// Work of needles and slabs, counted (not timed): the leaf kernel's largest
/// buffer is the same at N and 4N (bound: equal, at most the brick's 9^3
/// samples), node slots, surface triangles and DrawList slices grow at most
/// 4.5 times for 4 times the samples.
#[test]
fn needles_and_slabs_cost_linear_work() {
    let wave = |i: usize, j: usize, k: usize| ((i + 2 * j + 3 * k) as f64 * 0.37).sin();
    let measure = |dims: [usize; 3]| {
        let v = volume(dims, ScalarType::F32, [1.0; 3], wave);
        let g = v.grid(None).unwrap();
        let layout = Layout::new(dims, 8).unwrap();
        let longest = g.visit(LongestBuffer(&layout));
        let octree = VolumeOctree::build(&g, &BuildOptions { leaf_size: 8 }).unwrap();
        let surface = Surface::extract(&g, &octree, &SurfaceOptions::discretized(0.1)).unwrap();
        let camera = around(g.shape(), 30.0, 20.0, true);
        let s = uniform(&octree, 1, 4).unwrap();
        let scene = Scene {
            surface: None,
            surface_opacity: 1.0,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        let list = draw_list(&octree, g.shape(), &s, &camera, &scene, None).unwrap();
        (longest, layout.node_slots(), surface.polygon_count(), slices(&list))
    };
    for (small, large) in [([2, 2, 4097], [2, 2, 16385]), ([129, 129, 2], [257, 257, 2])] {
        let (a, b) = (measure(small), measure(large));
        assert_eq!(a.0, b.0, "{small:?} vs {large:?}: leaf buffers");
        assert!(b.0 <= 9 * 9 * 9);
        for (what, x, y) in [("node slots", a.1, b.1), ("triangles", a.2, b.2), ("slices", a.3, b.3)] {
            assert!(x > 0 && y as f64 <= 4.5 * x as f64, "{small:?} -> {large:?}: {what} {x} -> {y}");
        }
    }
}

/// Axis-aligned, nearly axis-aligned, grazing and diagonal views, parallel
/// and perspective, and a camera inside the volume: the full-resolution
/// octree picture against the reference, bound RMSE <= 0.02.
#[test]
fn grazing_axis_aligned_and_inside_views_match_the_reference() {
    let v = volume([17; 3], ScalarType::F32, [1.0; 3], ball(0.0, 1.0));
    let g = v.grid(None).unwrap();
    let mut cameras = Vec::new();
    for parallel in [false, true] {
        for (az, el) in [(0.0, 0.0), (90.0, 0.0), (0.0, 90.0), (45.0, 0.0), (0.0, 89.999), (0.0, 0.001), (45.0, 35.26)]
        {
            cameras.push(around(g.shape(), az, el, parallel));
        }
    }
    let inside = Projection::Perspective { view_angle_deg: 60.0 };
    cameras.push(Camera::new([8.0, 8.0, 8.0], [16.0, 9.0, 7.5], [0.0, 0.0, 1.0], inside).unwrap());
    cameras.push(Camera::new([8.5, 8.5, 8.5], [8.5, 8.5, -10.0], [0.0, 1.0, 0.0], inside).unwrap());
    for camera in cameras {
        let f = frame(&g, &camera);
        let e = rmse(&f.image, &f.truth);
        assert!(e <= 0.02, "{camera:?}: RMSE {e}");
    }
}

/// Isovalues equal to sample values, and surface vertices lying exactly on
/// slice planes (integer data, DiscMC midpoints, a parallel view along x from
/// x = -10.5 so midpoints sit at integer depths): the Hybrid Octree is valid
/// and its picture with the translucent surface matches the reference's,
/// bound RMSE <= 0.03.
#[test]
fn isovalues_on_samples_and_vertices_on_slices() {
    let v =
        volume([17; 3], ScalarType::U8, [1.0; 3], |i, j, k| ((i + j + k) % 5) as f64 + if i > 8 { 3.0 } else { 0.0 });
    let g = v.grid(None).unwrap();
    let camera =
        Camera::new([-10.5, 8.0, 8.0], [8.0, 8.0, 8.0], [0.0, 0.0, 1.0], Projection::Parallel { scale: 12.0 }).unwrap();
    for iso in [2.0, 3.0, 7.0] {
        let hybrid =
            HybridOctree::build(&g, &BuildOptions { leaf_size: 8 }, &SurfaceOptions::discretized(iso)).unwrap();
        assert_eq!(hybrid.validate(), Ok(()));
        let octree = VolumeOctree::build(&g, &BuildOptions { leaf_size: 8 }).unwrap();
        let surface = Surface::extract(&g, &octree, &SurfaceOptions::discretized(iso)).unwrap();
        assert!(surface.polygon_count() > 0);
        let tf = TransferFunction::ramp(0.0, 7.0);
        let colour = [0.9, 0.75, 0.55, 0.5];
        let scene = Scene {
            surface: Some(&surface),
            surface_opacity: 0.5,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        let s = uniform(&octree, 1, 4).unwrap();
        let list = draw_list(&octree, g.shape(), &s, &camera, &scene, None).unwrap();
        let image = composite(&g, &list, &tf, PIXELS, PIXELS, Some((&surface, colour))).unwrap();
        let options = ReferenceOptions { surface: Some((&surface, colour)), ..ReferenceOptions::default() };
        let truth = reference(&g, &tf, &camera, PIXELS, PIXELS, &options).unwrap();
        let e = rmse(&image, &truth);
        assert!(e <= 0.03, "isovalue {iso}: RMSE {e}");
    }
}

/// A single-brick DrawList at stride 1 of `v` under `tf`, seen by `camera`.
fn full_resolution(v: &Volume, tf: &TransferFunction, camera: &Camera, pixels: usize) -> (Image, Image) {
    let g = v.grid(None).unwrap();
    let octree = VolumeOctree::build(&g, &BuildOptions { leaf_size: 8 }).unwrap();
    let s = uniform(&octree, 1, 4).unwrap();
    let scene = Scene {
        surface: None,
        surface_opacity: 1.0,
        shading: None,
        gradient_opacity: None,
        transfer_2d: None,
        region: None,
        blend: Default::default(),
    };
    let list = draw_list(&octree, g.shape(), &s, camera, &scene, None).unwrap();
    let image = composite(&g, &list, tf, pixels, pixels, None).unwrap();
    let truth = reference(&g, tf, camera, pixels, pixels, &ReferenceOptions::default()).unwrap();
    (image, truth)
}

/// 4096 slices of opacity 1e-4 along a ray: the f32 picture against the
/// f64 closed form `A = 1 - (1 - 1e-4)^4096`, bound relative error <= 1e-5
/// for the opacity and the (white, premultiplied) colour.
#[test]
fn many_faint_slices_sum_like_f64() {
    let v = volume([5, 5, 4097], ScalarType::F32, [1.0; 3], |_, _, _| 0.0);
    let tf = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(0.0, 1e-4)]).unwrap();
    let camera =
        Camera::new([2.0, 2.0, 5000.0], [2.0, 2.0, 0.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 1.0 }).unwrap();
    let (image, truth) = full_resolution(&v, &tf, &camera, 4);
    let exact = 1.0 - (1.0 - 1e-4f64).powi(4096);
    for (pixels, what) in [(&image, "compositor"), (&truth, "reference")] {
        for p in &pixels.rgba {
            for c in p {
                let rel = (*c as f64 - exact).abs() / exact;
                assert!(rel <= 1e-5, "{what}: {c} vs {exact} (relative {rel})");
            }
        }
    }
}

/// Opacity 1 at the first sample: the pixel is the colour of the first
/// sample on the ray, exactly (bound 1e-6), and the reference within 4e-3
/// of it (it samples the midpoint of its first step of d0/4, 0.125 further
/// in: 0.125/32 of the colour ramp, 3.9e-3).
#[test]
fn opacity_one_at_the_first_sample() {
    let v = volume([5, 5, 33], ScalarType::F32, [1.0; 3], |_, _, k| k as f64);
    let tf = TransferFunction::new(vec![(0.0, [0.0, 0.2, 0.4]), (32.0, [1.0, 0.8, 0.6])], vec![(0.0, 1.0)]).unwrap();
    let camera =
        Camera::new([2.0, 2.0, 100.0], [2.0, 2.0, 0.0], [0.0, 1.0, 0.0], Projection::Parallel { scale: 1.0 }).unwrap();
    let (image, truth) = full_resolution(&v, &tf, &camera, 4);
    let first = tf.eval(32.0); // the top face, z = 32, is the first sample
    for (p, t) in image.rgba.iter().zip(&truth.rgba) {
        for c in 0..4 {
            assert!((p[c] - first[c]).abs() <= 1e-6, "compositor {p:?} vs {first:?}");
            assert!((t[c] - first[c]).abs() <= 4e-3, "reference {t:?} vs {first:?}");
        }
    }
}
