//! The rendering bridge against the library called directly: selections,
//! DrawLists, texels and the CPU picture are the CLI's.

use super::grid::grid_of;
use super::octree::HybridOctreeHandle;
use super::render::{camera, SelectionHandle};
use super::test_support::{build_volume_octree, select_desc};
use super::{CameraDesc, GridDesc, ScalarType, SelectDesc, SurfaceMode};
use crate::grid::{Grid, Samples};
use crate::plan;
use crate::plan::select::{select, Roi, SelectOptions};
use crate::plan::Scene;
use crate::transfer::TransferFunction;

const N: usize = 21;

/// Brick `i`'s texels through the bridge, into a buffer of its texel count.
fn texels(s: &SelectionHandle, bytes: &[u8], desc: &GridDesc, i: usize) -> Result<Vec<f32>, String> {
    let count = s.selection.bricks.get(i).map_or(1, |b| b.texels.iter().product());
    let mut out = vec![0.0; count];
    s.brick_texels(bytes, desc, i, &mut out).map(|()| out)
}

/// A ball: values 1 - r/10 around (10, 9, 11), spacing (1, 1.5, 0.5), origin (-3, 2, 5).
fn data() -> Vec<f32> {
    (0..N * N * N)
        .map(|i| {
            let (x, y, z) = ((i % N) as f32 - 10.0, ((i / N) % N) as f32 - 9.0, (i / (N * N)) as f32 - 11.0);
            1.0 - (x * x + y * y + z * z).sqrt() / 10.0
        })
        .collect()
}

fn bytes(data: &[f32]) -> &[u8] {
    // SAFETY: f32 has no padding; the byte view covers exactly the slice's storage.
    unsafe { std::slice::from_raw_parts(data.as_ptr() as *const u8, std::mem::size_of_val(data)) }
}

fn desc() -> GridDesc {
    GridDesc {
        scalar_type: ScalarType::F32,
        dims: [N; 3],
        spacing: [1.0, 1.5, 0.5],
        origin: [-3.0, 2.0, 5.0],
        components: 1,
        component: -1,
    }
}

fn options(budget_bytes: usize) -> SelectDesc {
    select_desc(budget_bytes)
}

fn cameras() -> Vec<CameraDesc> {
    vec![
        CameraDesc {
            position: [7.0, 17.0, -40.0],
            focal_point: [7.0, 17.0, 10.0],
            view_up: [0.0, 1.0, 0.0],
            parallel: true,
            parallel_scale: 20.0,
            view_angle: 30.0,
        },
        CameraDesc {
            position: [60.0, 70.0, 60.0],
            focal_point: [7.0, 17.0, 10.0],
            view_up: [0.0, 0.0, 1.0],
            parallel: false,
            parallel_scale: 1.0,
            view_angle: 30.0,
        },
    ]
}

#[test]
fn selects_within_the_budget_and_reports_it() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h.select_bricks(&options(12_000)).unwrap();
    let sum = s.summary().unwrap();
    assert!(sum.bricks >= 1 && sum.texture_bytes <= 12_000 && sum.budget_bytes == 12_000, "{sum:?}");
    assert_eq!(sum.bricks, s.selection.bricks.len());
    assert!(sum.warning.contains("above the tolerance 0"), "{sum:?}");
    let loose = h.select_bricks(&SelectDesc { tolerance: 0.1, ..options(12_000) }).unwrap().summary().unwrap();
    assert!(loose.warning.is_empty() && loose.estimated_error <= 0.1, "{loose:?}");
    // The same selection as select() called directly.
    let direct = select(h.volume(), &SelectOptions::new(12_000, 0.0), |_, _| true).unwrap();
    assert_eq!(s.selection, direct);
    // Too small a budget: the coarsest selection and a warning.
    let tiny = h.select_bricks(&options(8)).unwrap().summary().unwrap();
    assert!(!tiny.warning.is_empty() && tiny.texture_bytes > 8, "{tiny:?}");
}

/// A handle keeps its selection's forms for the next request: budgets,
/// tolerances, regions of interest and transfer functions in turn, each
/// selection equal to that of a new handle (which keeps nothing).
#[test]
fn kept_selections_equal_new_ones() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let roi = |budget: usize, c: f64| SelectDesc {
        has_roi: true,
        roi_center: [c, 14.0, 10.0],
        roi_radius: 3.0,
        ..options(budget)
    };
    let requests = [
        options(12_000),
        options(13_000),
        options(9_000),
        SelectDesc { tolerance: 0.05, ..options(9_000) },
        roi(9_000, 4.0),
        roi(9_000, 8.0),
        roi(20_000, 8.0),
        SelectDesc { opacity_points: vec![0.0, 0.0, 0.5, 0.0, 0.6, 1.0, 1.0, 1.0], ..options(20_000) },
        SelectDesc { opacity_points: vec![0.0, 0.0, 0.5, 0.0, 0.6, 1.0, 1.0, 1.0], ..options(6_000) },
        options(6_000),
    ];
    for (i, request) in requests.iter().enumerate() {
        let kept = h.select_bricks(request).unwrap();
        let new = build_volume_octree(bytes(&d), &desc(), 4).unwrap().select_bricks(request).unwrap();
        assert_eq!(kept.selection, new.selection, "request {i}");
    }
}

#[test]
fn bad_options_are_clear_errors() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let err = |o: SelectDesc| h.select_bricks(&o).map(|_| ()).unwrap_err();
    assert!(err(options(0)).contains("budget is 0 bytes"));
    assert!(err(SelectDesc { tolerance: f64::NAN, ..options(1000) }).contains("error tolerance NaN"));
    let roi = |c: [f64; 3], r: f64| SelectDesc { has_roi: true, roi_center: c, roi_radius: r, ..options(1000) };
    assert!(err(roi([1.0; 3], 0.0)).contains("region of interest"));
    assert!(err(roi([f64::NAN, 1.0, 1.0], 2.0)).contains("region of interest"));
    let odd = SelectDesc { opacity_points: vec![0.0, 1.0, 2.0], ..options(1000) };
    assert!(err(odd).contains("(value, opacity) pairs"));
    let above_one = SelectDesc { opacity_points: vec![0.0, 2.0], ..options(1000) };
    assert!(err(above_one).contains("opacity"));
    assert!(err(SelectDesc { has_isovalue: true, isovalue: f64::INFINITY, ..options(1000) }).contains("isovalue"));
}

#[test]
fn roi_is_given_in_world_coordinates() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    // World (2, 5, 6) is index ((2 + 3) / 1, (5 - 2) / 1.5, (6 - 5) / 0.5) = (5, 2, 2); radius 3 / 0.5 = 6.
    let o = SelectDesc { has_roi: true, roi_center: [2.0, 5.0, 6.0], roi_radius: 3.0, ..options(30_000) };
    let s = h.select_bricks(&o).unwrap();
    let roi = Some(Roi { center: [5.0, 2.0, 2.0], radius: 6.0 });
    let direct = select(h.volume(), &SelectOptions { roi, ..SelectOptions::new(30_000, 0.0) }, |_, _| true).unwrap();
    assert_eq!(s.selection, direct);
    assert_ne!(s.selection, select(h.volume(), &SelectOptions::new(30_000, 0.0), |_, _| true).unwrap());
}

#[test]
fn transparent_nodes_are_skipped_as_the_cli_does() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    // Opaque only above 0.5 (the ball's core).
    let points = vec![-1.0, 0.0, 0.5, 0.0, 1.0, 1.0];
    let s = h.select_bricks(&SelectDesc { opacity_points: points, ..options(20_000) }).unwrap();
    let tf = TransferFunction::new(vec![(0.0, [1.0; 3])], vec![(-1.0, 0.0), (0.5, 0.0), (1.0, 1.0)]).unwrap();
    let direct = select(h.volume(), &SelectOptions::new(20_000, 0.0), |a, b| !tf.is_transparent_over(a, b)).unwrap();
    assert!(direct.skipped > 0);
    assert_eq!(s.selection, direct);
    // With an isosurface at 0.2 the nodes holding it show too.
    let with_iso = SelectDesc {
        opacity_points: vec![-1.0, 0.0, 0.5, 0.0, 1.0, 1.0],
        has_isovalue: true,
        isovalue: 0.2,
        ..options(20_000)
    };
    let s = h.select_bricks(&with_iso).unwrap();
    assert!(s.selection.skipped < direct.skipped, "{} {}", s.selection.skipped, direct.skipped);
}

#[test]
fn draw_list_through_the_bridge_is_plan_draw_list() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h
        .select_bricks(&SelectDesc { has_roi: true, roi_center: [0.0, 5.0, 6.0], roi_radius: 1.0, ..options(30_000) })
        .unwrap();
    for c in cameras() {
        let out = s.draw_list(&h, &c, 0.0).unwrap();
        let scene = Scene::volume(bridge_blend(&h));
        let direct = plan::draw_list(h.volume(), &h.shape, &s.selection, &camera(&c).unwrap(), &scene, None).unwrap();
        assert_eq!(direct, s.list(&h, &c, 0.0).unwrap());
        let n = direct.bricks.len();
        assert!(n > 1 && n == s.selection.bricks.len(), "{n} bricks");
        assert_eq!(out.passes, "volume");
        assert_eq!(out.reference_spacing, 0.5);
        assert_eq!(out.forward, direct.camera.forward());
        assert_eq!(
            (out.brick.len(), out.bounds.len(), out.texels.len(), out.slice_offsets.len()),
            (n, 6 * n, 3 * n, n + 1)
        );
        for (i, b) in direct.bricks.iter().enumerate() {
            assert_eq!(s.selection.bricks[out.brick[i]], b.brick);
            assert_eq!(out.node_id[i], b.brick.node.0);
            let (lo, hi) = (b.world_lo, b.world_hi);
            assert_eq!(out.bounds[6 * i..6 * i + 6], [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]);
            assert_eq!(out.texels[3 * i..3 * i + 3], b.brick.texels);
            assert_eq!((out.stride[i], out.slice_spacing[i]), (b.brick.stride, b.slice_spacing));
            assert_eq!(out.opacity_ratio[i], b.slice_spacing / 0.5);
            assert_eq!(out.slices[out.slice_offsets[i]..out.slice_offsets[i + 1]], b.slices[..]);
        }
    }
}

#[test]
fn draw_list_errors() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let other = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h.select_bricks(&options(12_000)).unwrap();
    let c = &cameras()[0];
    assert!(s.draw_list(&other, c, 0.0).unwrap_err().contains("another octree"));
    let at_focus = CameraDesc { position: c.focal_point, ..cameras().remove(0) };
    assert!(s.draw_list(&h, &at_focus, 0.0).unwrap_err().contains("camera"));
    let zero_scale = CameraDesc { parallel_scale: 0.0, ..cameras().remove(0) };
    assert!(s.draw_list(&h, &zero_scale, 0.0).unwrap_err().contains("parallel scale"));
}

/// f64 values beyond the f32 range cannot be GPU texels: refused with
/// what to do, not handed over as infinities.
#[test]
fn texels_beyond_f32_are_refused() {
    let d: Vec<f64> = data().iter().map(|&v| v as f64 * 1e308).collect();
    // SAFETY: f64 has no padding; the byte view covers exactly the slice's storage.
    let b = unsafe { std::slice::from_raw_parts(d.as_ptr() as *const u8, std::mem::size_of_val(&d[..])) };
    let desc = GridDesc { scalar_type: ScalarType::F64, ..desc() };
    let h = build_volume_octree(b, &desc, 4).unwrap();
    let s = h.select_bricks(&options(1_000_000)).unwrap();
    let e = (0..s.selection.bricks.len()).find_map(|i| texels(&s, b, &desc, i).err()).unwrap();
    assert!(e.to_string().contains("32-bit float") && e.to_string().contains("CompositeOnCPU"), "{e}");
}

/// A 1e-3 range on a 1e9 offset is noise in 32-bit float: refused with
/// what to do; the same range near 0, and f32 data, are drawn.
#[test]
fn texels_that_f32_cannot_resolve_are_refused() {
    let texels = |offset: f64, scalar_type: ScalarType| {
        let d: Vec<f64> = data().iter().map(|&v| offset + v as f64 * 1e-3).collect();
        let desc = GridDesc { scalar_type, ..desc() };
        let bytes: Vec<u8> = match scalar_type {
            ScalarType::F64 => d.iter().flat_map(|v| v.to_ne_bytes()).collect(),
            _ => d.iter().flat_map(|&v| (v as f32).to_ne_bytes()).collect(),
        };
        let h = build_volume_octree(&bytes, &desc, 4).unwrap();
        let s = h.select_bricks(&options(1_000_000)).unwrap();
        texels(&s, &bytes, &desc, 0).map(drop)
    };
    let e = texels(1e9, ScalarType::F64).unwrap_err().to_string();
    assert!(e.contains("32-bit float") && e.contains("subtract the offset"), "{e}");
    assert!(texels(0.0, ScalarType::F64).is_ok());
    assert!(texels(1e3, ScalarType::F32).is_ok());
}

#[test]
fn brick_texels_are_the_image_at_the_texel_positions() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h.select_bricks(&options(12_000)).unwrap();
    let grid = grid_of(bytes(&d), &desc()).unwrap();
    assert!(s.selection.bricks.iter().any(|b| b.stride > 1));
    for (i, b) in s.selection.bricks.iter().enumerate() {
        let t = texels(&s, bytes(&d), &desc(), i).unwrap();
        assert_eq!(t.len(), b.texels.iter().product::<usize>());
        let mut expected = Vec::new();
        for z in b.texel_positions(2) {
            for y in b.texel_positions(1) {
                for x in b.texel_positions(0) {
                    expected.push(grid.value(x, y, z) as f32);
                }
            }
        }
        assert_eq!(t, expected, "brick {i}");
    }
    let n = s.selection.bricks.len();
    assert!(texels(&s, bytes(&d), &desc(), n).unwrap_err().contains("does not exist"));
    let moved = GridDesc { origin: [0.0; 3], ..desc() };
    assert!(texels(&s, bytes(&d), &moved, 0).unwrap_err().contains("image changed"));
    // An infinity written after the build: the brick that reads it says so,
    // the others still load. A NaN is no data: its texel is NaN.
    let roi = SelectDesc { has_roi: true, roi_center: [0.0, 5.0, 6.0], roi_radius: 1.0, ..options(30_000) };
    let s = h.select_bricks(&roi).unwrap();
    assert!(s.selection.bricks.len() > 1);
    let b = &s.selection.bricks[0];
    let mut changed = d.clone();
    changed[b.lo[0] + N * (b.lo[1] + N * b.lo[2])] = f32::NAN;
    assert!(texels(&s, bytes(&changed), &desc(), 0).unwrap()[0].is_nan());
    changed[b.lo[0] + N * (b.lo[1] + N * b.lo[2])] = f32::INFINITY;
    let e = texels(&s, bytes(&changed), &desc(), 0).unwrap_err();
    assert!(e.contains("infinite value (texel 0)"), "{e}");
    let far = s.selection.bricks.iter().position(|o| (0..3).any(|a| o.lo[a] > b.lo[a] || o.hi[a] < b.lo[a]));
    let far = far.expect("a brick away from the NaN");
    assert!(texels(&s, bytes(&changed), &desc(), far).is_ok());
}

#[test]
fn f64_texels_are_rounded_to_f32() {
    // 0.1 steps: not exact in f32, resolved by it (differences far above 2^-24).
    let d: Vec<f64> = (0..27).map(|i| 1.0 + i as f64 * 0.1).collect();
    // SAFETY: f64 has no padding; the byte view covers exactly the vector's storage.
    let b = unsafe { std::slice::from_raw_parts(d.as_ptr() as *const u8, d.len() * 8) };
    let desc = GridDesc { scalar_type: ScalarType::F64, dims: [3; 3], spacing: [1.0; 3], origin: [0.0; 3], ..desc() };
    let h = build_volume_octree(b, &desc, 2).unwrap();
    let s = h.select_bricks(&options(20_000)).unwrap();
    let grid = Grid::scalar(Samples::F64(&d), [3; 3]).unwrap();
    let all: Vec<f32> = (0..s.selection.bricks.len()).flat_map(|i| texels(&s, b, &desc, i).unwrap()).collect();
    let b0 = &s.selection.bricks[0];
    let first: Vec<f32> = b0.texel_positions(0).map(|x| grid.value(x, b0.lo[1], b0.lo[2]) as f32).collect();
    assert_eq!(&all[..first.len()], &first[..]);
    assert!(first.iter().zip(b0.texel_positions(0)).any(|(&t, x)| t as f64 != grid.value(x, b0.lo[1], b0.lo[2])));
}

/// The mesh a bridge caller reads: the surface's world points, 3 a vertex.
fn mesh_points(h: &HybridOctreeHandle, vertices: usize, polygons: usize, connectivity: usize) -> Vec<f64> {
    let mut points = vec![0.0; 3 * vertices];
    let (mut normals, mut offsets, mut conn) = (vec![0.0; 3 * vertices], vec![0; polygons + 1], vec![0; connectivity]);
    let (mut node, mut level, mut face) = (vec![0; polygons], vec![0; polygons], vec![0; polygons]);
    h.surface_mesh(&mut points, &mut normals, &mut offsets, &mut conn, &mut node, &mut level, &mut face).unwrap();
    points
}

#[test]
fn draw_list_with_a_surface_is_plan_draw_list() {
    let d = data();
    let mut h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let roi = SelectDesc { has_roi: true, roi_center: [0.0, 5.0, 6.0], roi_radius: 1.0, ..options(30_000) };
    let s = h.select_bricks(&roi).unwrap();
    let summary = h.integrate_surface(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized, false).unwrap();
    let surface = h.hybrid.surface.clone().unwrap();
    let polygons = surface.polygon_count();
    assert!(polygons > 0 && summary.polygons == polygons && summary.distance_mean == -1.0);
    let points = mesh_points(&h, summary.vertices, summary.polygons, summary.connectivity);
    let world: Vec<f64> = surface.points.iter().flat_map(|p| h.shape.world(*p)).collect();
    assert_eq!(points, world);
    for c in cameras() {
        let camera = camera(&c).unwrap();
        for (opacity, passes) in [(0.4, "surface-in-slabs,volume"), (1.0, "surface-opaque,volume"), (0.0, "volume")] {
            let scene = Scene {
                surface: Some(&surface),
                surface_opacity: opacity,
                shading: None,
                gradient_opacity: None,
                transfer_2d: None,
                blend: bridge_blend(&h),
                region: None,
            };
            let direct = plan::draw_list(h.volume(), &h.shape, &s.selection, &camera, &scene, None).unwrap();
            assert_eq!(s.list(&h, &c, opacity).unwrap(), direct);
            let out = s.draw_list(&h, &c, opacity).unwrap();
            assert_eq!(out.passes, passes);
            assert_eq!(out.opaque_triangles, direct.opaque_triangles.len());
            assert_eq!(out.batch_offsets.len(), direct.bricks.len() + 1);
            let mut seen = vec![false; polygons];
            for (i, b) in direct.bricks.iter().enumerate() {
                let range = out.batch_offsets[i]..out.batch_offsets[i + 1];
                assert_eq!(range.len(), b.batches.len());
                for (k, batch) in range.zip(&b.batches) {
                    assert_eq!(out.batch_slab[k], batch.slab);
                    assert_eq!(out.batch_first[k]..out.batch_end[k], batch.triangles);
                    let clip = batch.clip.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
                    assert_eq!(out.batch_clip[2 * k..2 * k + 2], [clip.0, clip.1]);
                    batch.triangles.clone().for_each(|t| seen[t as usize] = true);
                }
            }
            assert_eq!(seen.iter().all(|&v| v), opacity > 0.0 && opacity < 1.0, "opacity {opacity}");
            if opacity == 1.0 {
                assert_eq!(out.opaque_triangles, polygons);
            }
        }
        // Hidden is the volume alone, as without a surface.
        let volume = Scene::volume(bridge_blend(&h));
        let direct = plan::draw_list(h.volume(), &h.shape, &s.selection, &camera, &volume, None).unwrap();
        assert_eq!(s.list(&h, &c, 0.0).unwrap(), direct);
    }
    // Kept SlabPolygons are made again for another surface.
    h.integrate_surface(bytes(&d), &desc(), 0.3, SurfaceMode::Discretized, false).unwrap();
    let other = h.hybrid.surface.clone().unwrap();
    let c = &cameras()[1];
    let scene = Scene {
        surface: Some(&other),
        surface_opacity: 0.4,
        shading: None,
        gradient_opacity: None,
        transfer_2d: None,
        blend: bridge_blend(&h),
        region: None,
    };
    let direct = plan::draw_list(h.volume(), &h.shape, &s.selection, &camera(c).unwrap(), &scene, None).unwrap();
    assert_eq!(s.list(&h, c, 0.4).unwrap(), direct);
    // Without a surface any opacity draws the volume alone.
    h.remove_surface().unwrap();
    assert_eq!(s.draw_list(&h, c, 0.4).unwrap().passes, "volume");
}

#[test]
fn draw_list_with_a_surface_errors() {
    let d = data();
    let mut h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h.select_bricks(&options(12_000)).unwrap();
    h.integrate_surface(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized, false).unwrap();
    let c = &cameras()[0];
    for bad in [f64::NAN, 1.5, -0.1] {
        assert!(s.draw_list(&h, c, bad).unwrap_err().contains("surface opacity"));
    }
    let e = h.integrate_surface(bytes(&d), &desc(), f64::NAN, SurfaceMode::Discretized, false).unwrap_err();
    assert!(e.contains("isovalue"), "{e}");
    assert!(h.hybrid.surface.is_none(), "a failed integration leaves no surface");
    let (mut v, mut i) = (vec![0.0; 6], vec![0; 3]);
    assert!(h.surface_triangles(&mut v, &mut i).unwrap_err().contains("holds no surface"));
    let moved = GridDesc { origin: [0.0; 3], ..desc() };
    let e = h.integrate_surface(bytes(&d), &moved, 0.5, SurfaceMode::Discretized, false).unwrap_err();
    assert!(e.contains("image changed"), "{e}");
}

#[test]
fn surface_triangles_are_the_mesh_as_the_gpu_draws_it() {
    let d = data();
    let mut h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let sum = h.integrate_surface(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized, false).unwrap();
    let (mut vertices, mut indices) = (vec![0.0; 6 * sum.vertices], vec![0; 3 * sum.polygons]);
    h.surface_triangles(&mut vertices, &mut indices).unwrap();
    let surface = h.hybrid.surface.as_ref().unwrap();
    assert_eq!(indices, surface.connectivity);
    for (v, (p, n)) in vertices.chunks(6).zip(surface.points.iter().zip(&surface.normals)) {
        assert_eq!(v[..3], h.shape.world(*p).map(|c| c as f32));
        assert_eq!(v[3..], n[..]);
    }
    let e = h.surface_triangles(&mut vertices[1..], &mut indices).unwrap_err();
    assert!(e.contains("surface vertices"), "{e}");
}

#[test]
fn composite_through_the_bridge_is_the_cpu_compositor() {
    use crate::render::compositor::composite;
    let d = data();
    let mut h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let s = h.select_bricks(&options(30_000)).unwrap();
    h.integrate_surface(bytes(&d), &desc(), 0.5, SurfaceMode::Discretized, false).unwrap();
    let surface = h.hybrid.surface.clone().unwrap();
    let colors = [0.0, 0.2, 0.3, 0.4, 1.0, 1.0, 0.9, 0.8];
    let opacities = [0.0, 0.0, 0.3, 0.05, 1.0, 0.2];
    let tf = TransferFunction::new(
        vec![(0.0, [0.2, 0.3, 0.4]), (1.0, [1.0, 0.9, 0.8])],
        vec![(0.0, 0.0), (0.3, 0.05), (1.0, 0.2)],
    )
    .unwrap();
    let grid = grid_of(bytes(&d), &desc()).unwrap();
    let picture = |c: &CameraDesc, rgba: &[f64], w: usize, h_: usize| {
        let mut out = vec![0.0; 4 * w * h_];
        s.composite(&h, c, bytes(&d), &desc(), &colors, &opacities, false, rgba, w, h_, &mut out).map(|()| out)
    };
    for c in cameras() {
        let volume = picture(&c, &[1.0, 1.0, 1.0, 0.0], 40, 30).unwrap();
        let direct = composite(&grid, &s.list(&h, &c, 0.0).unwrap(), &tf, 40, 30, None).unwrap();
        assert_eq!(volume, direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
        assert!(volume.iter().any(|&v| v > 0.0), "the ball shows");
        for opacity in [0.4, 1.0] {
            let rgba = [0.9, 0.5, 0.1, opacity];
            let with = picture(&c, &rgba, 40, 30).unwrap();
            let list = s.list(&h, &c, opacity).unwrap();
            let drawn = Some((&surface, rgba.map(|v| v as f32)));
            let direct = composite(&grid, &list, &tf, 40, 30, drawn).unwrap();
            assert_eq!(with, direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
            assert_ne!(with, volume, "the surface shows at opacity {opacity}");
        }
    }
    let c = &cameras()[0];
    assert!(picture(c, &[1.0; 3], 8, 8).unwrap_err().contains("surface colour"));
    let mut out = vec![0.0; 4 * 64];
    let e = s.composite(&h, c, bytes(&d), &desc(), &colors[..3], &opacities, false, &[0.0; 4], 8, 8, &mut out);
    assert!(e.unwrap_err().contains("tuples"));
    let e = s.composite(&h, c, bytes(&d), &desc(), &colors, &opacities, false, &[0.0; 4], 8, 8, &mut out[1..]);
    assert!(e.unwrap_err().contains("the picture"));
}

/// A blend mode through the bridge: the plan names it, a coarse MIP brick's
/// texels keep the peak of the samples they stand for, MinIP's the low, and
/// a translucent surface is not planned under it; unknown modes and a bad
/// average range are refused.
#[test]
fn blend_modes_through_the_bridge() {
    let d = data();
    let h = build_volume_octree(bytes(&d), &desc(), 4).unwrap();
    let c = &cameras()[0];
    for (mode, pass, largest) in [(1, "volume-mip", true), (2, "volume-minip", false)] {
        let s = h.select_bricks(&SelectDesc { blend_mode: mode, ..options(6_000) }).unwrap();
        assert_eq!(s.draw_list(&h, c, 0.0).unwrap().passes, pass);
        let coarse = (0..s.selection.bricks.len()).find(|&i| s.selection.bricks[i].stride > 1).expect("a coarse brick");
        let b = s.selection.bricks[coarse];
        let t = texels(&s, bytes(&d), &desc(), coarse).unwrap();
        // The extreme of the samples of the brick's box against the extreme texel.
        let mut extreme = if largest { f32::MIN } else { f32::MAX };
        for z in b.lo[2]..=b.hi[2] {
            for y in b.lo[1]..=b.hi[1] {
                for x in b.lo[0]..=b.hi[0] {
                    let v = d[x + N * (y + N * z)];
                    extreme = if largest { extreme.max(v) } else { extreme.min(v) };
                }
            }
        }
        let got = t.iter().copied().fold(if largest { f32::MIN } else { f32::MAX }, |a, v| {
            if largest {
                a.max(v)
            } else {
                a.min(v)
            }
        });
        assert_eq!(got, extreme, "mode {mode}: brick {coarse} stride {}", b.stride);
    }
    for (mode, pass) in [(0, "volume"), (3, "volume-average"), (4, "volume-additive")] {
        let s = h.select_bricks(&SelectDesc { blend_mode: mode, ..options(30_000) }).unwrap();
        assert_eq!(s.draw_list(&h, c, 0.0).unwrap().passes, pass);
    }
    let e = h.select_bricks(&SelectDesc { blend_mode: 7, ..options(30_000) }).map(|_| ()).unwrap_err();
    assert!(e.contains("blend mode 7") && e.contains("6 (slice)"), "{e}");
    // Slice: its plane checked, then its pass.
    let e = h.select_bricks(&SelectDesc { blend_mode: 6, ..options(30_000) }).map(|_| ()).unwrap_err();
    assert!(e.contains("non-zero") && e.contains("SetSliceFunction"), "{e}");
    let plane = SelectDesc { blend_mode: 6, slice_plane: [4.0, 4.0, 4.0, 0.3, 0.2, 1.0], ..options(30_000) };
    let s = h.select_bricks(&plane).unwrap();
    let list = s.draw_list(&h, c, 0.0).unwrap();
    assert_eq!((list.passes.as_str(), list.slice_plane.len()), ("volume-slice", 6));
    let e = h.select_bricks(&SelectDesc { blend_mode: 5, ..options(30_000) }).map(|_| ()).unwrap_err();
    assert!(e.contains("0 isosurface values"), "{e}");
    let iso = SelectDesc { blend_mode: 5, isosurface_values: vec![0.5], ..options(30_000) };
    let s = h.select_bricks(&iso).unwrap();
    assert_eq!(s.draw_list(&h, c, 0.0).unwrap().passes, "volume-isosurface");
    assert!(s.list(&h, c, 0.0).unwrap().plan.bordered(), "textures with the border the step back reads");
    let e = h.select_bricks(&SelectDesc { average_range: [1.0, 0.0], ..options(30_000) }).map(|_| ()).unwrap_err();
    assert!(e.contains("average intensity range"), "{e}");
}

/// The blend of the bridge's selections: Composite over the octree's value range.
fn bridge_blend(h: &HybridOctreeHandle) -> crate::plan::Blend {
    let (lo, hi) = h.volume().value_range();
    crate::plan::Blend::new(crate::plan::BlendMode::Composite, [lo, hi])
}
