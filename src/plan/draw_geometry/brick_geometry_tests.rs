//! Tests of [`super::brick_geometry`]: hand cases of the vertex stream, the
//! placement against a brute-force slab overlap, and the agreement with the
//! CPU compositor's batches on the slab of every point of every triangle.
#![allow(clippy::single_range_in_vec_init)]

use super::*;
use crate::geometry::camera::Camera;
use crate::plan::slab::{assign_batches, slab_interval, slab_of, slice_depths, Batch, PolygonBatch};
use proptest::prelude::*;

fn cam(position: [f64; 3], focal: [f64; 3], parallel: bool) -> Camera {
    crate::geometry::camera::test_camera(position, focal, parallel.then_some(20.0))
}

fn view_of(camera: &Camera) -> GeometryView {
    GeometryView { eye: camera.position, forward: camera.forward(), view_up: camera.view_up }
}

/// A vertex of the stream.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    near: f32,
    far: f32,
    kind: i32,
    alpha: f32,
}

/// Brick `brick`'s vertices, each checked to name that brick.
fn vertices(g: &BrickGeometry, brick: usize) -> Vec<Vertex> {
    g.vertices[FLOATS_PER_VERTEX * g.brick_first[brick]..FLOATS_PER_VERTEX * g.brick_first[brick + 1]]
        .chunks_exact(FLOATS_PER_VERTEX)
        .inspect(|v| assert_eq!(v[10], brick as f32, "a vertex of brick {brick} names brick {}", v[10]))
        .map(|v| Vertex {
            position: [v[0], v[1], v[2]],
            normal: [v[3], v[4], v[5]],
            near: v[6],
            far: v[7],
            kind: v[8] as i32,
            alpha: v[9],
        })
        .collect()
}

/// A surface of triangles given by their corners (normals all +z).
fn surface_of(tris: &[[[f32; 3]; 3]]) -> (Vec<f32>, Vec<u32>) {
    let vertices = tris.iter().flatten().flat_map(|p| [p[0], p[1], p[2], 0.0, 0.0, 1.0]).collect();
    (vertices, (0..3 * tris.len() as u32).collect())
}

/// Looking along +z from z = -10 (depth = z + 10), a 1 x 1 x 8 brick sliced every 1: slices 17 .. 10.
fn along_z() -> (Camera, Vec<f64>, [f64; 6]) {
    let camera = cam([0.5, 0.5, -10.0], [0.5, 0.5, 0.0], false);
    let slices = slice_depths(&camera, [0.0; 3], [1.0, 1.0, 8.0], 1.0);
    (camera, slices, [0.0, 1.0, 0.0, 1.0, 0.0, 8.0])
}

fn flat(z: f32) -> [[f32; 3]; 3] {
    [[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]]
}

#[test]
fn slabs_slices_and_clip_intervals_by_hand() {
    let (camera, slices, bounds) = along_z();
    assert_eq!(slices, (10..18).rev().map(f64::from).collect::<Vec<_>>());
    // Triangle 0 in slab 3 (depth 14.5: slices 17, 16, 15 behind it);
    // triangle 1 from depth 12.5 to 13.5: slabs 4 and 5, clipped;
    // triangle 2 behind everything (slab 0), triangle 3 in front (slab 8).
    let tris = [flat(4.5), [[0.0, 0.0, 2.5], [1.0, 0.0, 3.5], [0.0, 1.0, 3.0]], flat(9.0), flat(-1.0)];
    let (v, t) = surface_of(&tris);
    let surface = SurfaceVertices { vertices: &v, triangles: &t };
    let brick = BrickSlabs { slices: &slices, bounds, drawn: true, batches: vec![0..4], buckets: Vec::new() };
    let g = brick_geometry(&view_of(&camera), &[brick], Some(&surface), None).unwrap();
    assert_eq!(g.triangles_placed, 5);
    assert_eq!(g.brick_first, vec![0, g.vertices.len() / FLOATS_PER_VERTEX]);
    assert_eq!(g.ray_marched, vec![false]);
    let v = vertices(&g, 0);
    let (slice, tri) = (PrimitiveKind::Slice as i32, PrimitiveKind::SurfaceTriangle as i32);
    // Each slice is the 1 x 1 square: 2 fan triangles.
    assert_eq!(v.iter().filter(|x| x.kind == slice).count(), 8 * 6);
    // Walk the stream: the slice depths in order, the triangles between them.
    let depth = |p: [f32; 3]| camera.depth(p.map(f64::from));
    let mut seen = Vec::new();
    for chunk in v.chunks(3) {
        let d = depth(chunk[0].position);
        if chunk[0].kind == slice {
            assert!(chunk.iter().all(|x| x.near == -UNBOUNDED && x.far == UNBOUNDED && x.normal == [0.0; 3]));
            if seen.last() != Some(&("slice", d)) {
                seen.push(("slice", d));
            }
        } else {
            assert_eq!(chunk[0].kind, tri);
            assert_eq!(chunk[0].normal, [0.0, 0.0, 1.0]);
            seen.push(("triangle", d));
        }
    }
    let order: Vec<(&str, f64)> = vec![
        ("triangle", 19.0),
        ("slice", 17.0),
        ("slice", 16.0),
        ("slice", 15.0),
        ("triangle", 14.5),
        ("slice", 14.0),
        ("slice", 13.0),
        ("triangle", 12.5), // triangle 1 in slab 5 ([12, 13)), after slice 13
        ("slice", 12.0),
        ("slice", 11.0),
        ("slice", 10.0),
        ("triangle", 9.0),
    ];
    // Triangle 1 is also in slab 4 ([13, 14)), between slices 14 and 13.
    let mut expected = order.clone();
    expected.insert(6, ("triangle", 12.5));
    assert_eq!(seen, expected);
    // Clip intervals: unclipped ones unbounded, triangle 1's the slabs'.
    let clips: Vec<(f32, f32)> = v.iter().filter(|x| x.kind == tri).map(|x| (x.near, x.far)).step_by(3).collect();
    assert_eq!(
        clips,
        vec![(-UNBOUNDED, UNBOUNDED), (-UNBOUNDED, UNBOUNDED), (13.0, 14.0), (12.0, 13.0), (-UNBOUNDED, UNBOUNDED)]
    );
}

#[test]
fn a_slab_is_drawn_far_first_triangles_by_clamped_centroid_points_by_depth() {
    let (camera, slices, bounds) = along_z();
    // All in slab 3 ([14, 15)): triangles at depths 14.2 and 14.8, a
    // triangle spanning 13.5 .. 14.6 (its copy in slab 3 at its centroid
    // 14.0 clamped... to [14, 15): 14.0), and points at 14.5 and 14.9.
    let tris = [flat(4.2), flat(4.8), [[0.0, 0.0, 3.5], [1.0, 0.0, 4.6], [0.0, 1.0, 3.9]]];
    let (v, t) = surface_of(&tris);
    let surface = SurfaceVertices { vertices: &v, triangles: &t };
    let positions = [0.5f32, 0.5, 4.5, 0.5, 0.5, 4.9, 0.5, 0.5, 4.7];
    // Point 2 adds nothing: not drawn.
    let shades = [0.1f32, 0.2, 0.3, 0.5, 0.4, 0.5, 0.6, 0.25, 1.0, 1.0, 1.0, 0.0];
    let points = PointVertices { positions: &positions, shades: &shades, gaussian: true };
    let ids = [0u32, 1, 2, 7]; // 7: not in the set
    let brick =
        BrickSlabs { slices: &slices, bounds, drawn: true, batches: vec![2..3, 0..2, 1..3], buckets: vec![(3, &ids)] };
    let g = brick_geometry(&view_of(&camera), &[brick], Some(&surface), Some(&points)).unwrap();
    assert_eq!((g.triangles_placed, g.points_placed), (4, 2));
    let v = vertices(&g, 0);
    let slab3: Vec<Vertex> = v.iter().copied().skip_while(|x| x.kind == 0).take_while(|x| x.kind != 0).collect();
    let kinds: Vec<i32> = slab3.iter().map(|x| x.kind).collect();
    let g_point = PrimitiveKind::GaussianPoint as i32;
    let tri = PrimitiveKind::SurfaceTriangle as i32;
    // Far first: point 1 (14.9), triangle 1 (14.8), point 0 (14.5), triangle 0 (14.2), triangle 2's copy (14.0).
    let expected: Vec<i32> = [(g_point, 6), (tri, 3), (g_point, 6), (tri, 3), (tri, 3)]
        .iter()
        .flat_map(|&(k, n)| std::iter::repeat_n(k, n))
        .collect();
    assert_eq!(kinds, expected);
    // A point's six vertices: its centre, colour in the normal, corners, opacity.
    let p1 = &slab3[..6];
    assert!(p1.iter().all(|x| x.position == [0.5, 0.5, 4.9] && x.normal == [0.4, 0.5, 0.6] && x.alpha == 0.25));
    let corners: Vec<(f32, f32)> = p1.iter().map(|x| (x.near, x.far)).collect();
    assert_eq!(corners, vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]);
    assert_eq!(slab3[6].position[2], 4.8);
    assert_eq!(slab3[15].position[2], 4.2);
    assert_eq!((slab3[18].near, slab3[18].far), (14.0, 15.0), "triangle 2's copy in slab 3");
    // The point quad's up: the view's up, perpendicular to forward (view up +x here).
    assert_eq!(g.point_up, [1.0, 0.0, 0.0]);
}

#[test]
fn bricks_without_triangles_or_points_are_ray_marched_boxes() {
    let (camera, slices, bounds) = along_z();
    let (v, t) = surface_of(&[flat(4.5)]);
    let surface = SurfaceVertices { vertices: &v, triangles: &t };
    let empty: &[f64] = &[];
    let bricks = [
        BrickSlabs { slices: &slices, bounds, drawn: true, batches: Vec::new(), buckets: Vec::new() },
        BrickSlabs { slices: &slices, bounds, drawn: false, batches: Vec::new(), buckets: Vec::new() },
        BrickSlabs { slices: empty, bounds, drawn: true, batches: Vec::new(), buckets: Vec::new() },
        BrickSlabs { slices: &slices, bounds, drawn: false, batches: vec![0..1], buckets: Vec::new() },
        BrickSlabs { slices: &slices, bounds, drawn: true, batches: vec![0..1], buckets: Vec::new() },
    ];
    let g = brick_geometry(&view_of(&camera), &bricks, Some(&surface), None).unwrap();
    assert_eq!(g.ray_marched, vec![true, true, true, false, false]);
    // A drawn ray-marched brick: 12 triangles; not drawn or without slices: nothing.
    // A brick with triangles not drawn: its triangles only; drawn: with its 8 slices.
    assert_eq!(g.brick_first, vec![0, 36, 36, 36, 39, 39 + 3 + 8 * 6]);
    let v = vertices(&g, 0);
    assert!(v.iter().all(|x| x.kind == PrimitiveKind::RayMarchedBox as i32 && x.near == -UNBOUNDED));
    // Every face seen from inside is counter-clockwise: its normal (right-handed) points inwards.
    let centre = [0.5, 0.5, 4.0];
    for t in v.chunks(3) {
        let p = t.iter().map(|x| x.position.map(f64::from)).collect::<Vec<_>>();
        let n = crate::geometry::vec3::cross(
            crate::geometry::vec3::sub(p[1], p[0]),
            crate::geometry::vec3::sub(p[2], p[0]),
        );
        assert!(crate::geometry::vec3::dot(n, crate::geometry::vec3::sub(centre, p[0])) > 0.0);
    }
    // Without a surface the batches are not read: every brick ray-marched.
    let g = brick_geometry(&view_of(&camera), &bricks, None, None).unwrap();
    assert_eq!(g.ray_marched, vec![true; 5]);
    assert_eq!(g.triangles_placed, 0);
}

#[test]
fn bad_triangles_are_errors() {
    let (camera, slices, bounds) = along_z();
    let (v, t) = surface_of(&[flat(4.5)]);
    let brick = |batches| BrickSlabs { slices: &slices, bounds, drawn: true, batches, buckets: Vec::new() };
    let surface = SurfaceVertices { vertices: &v, triangles: &t };
    let e = brick_geometry(&view_of(&camera), &[brick(vec![0..2])], Some(&surface), None).unwrap_err();
    assert!(e.to_string().contains("names surface triangle 1, the surface has 1"), "{e}");
    let short = SurfaceVertices { vertices: &v[..12], triangles: &t };
    let e = brick_geometry(&view_of(&camera), &[brick(vec![0..1])], Some(&short), None).unwrap_err();
    assert!(e.to_string().contains("names vertex 2, the surface has 2"), "{e}");
}

/// Brick `brick`'s triangle copies in stream order: (slab, near, far), the
/// slab by the copy's place in the stream, the number of slices drawn before
/// it (a slice identified by its vertices' depth, nearest of `slices`).
fn copies_in_stream(g: &BrickGeometry, brick: usize, view: &GeometryView, slices: &[f64]) -> Vec<(usize, f32, f32)> {
    let depth = |p: [f32; 3]| (0..3).map(|a| (p[a] as f64 - view.eye[a]) * view.forward[a]).sum::<f64>();
    let mut slab = 0;
    let mut out = Vec::new();
    for t in vertices(g, brick).chunks(3) {
        if t[0].kind == PrimitiveKind::Slice as i32 {
            let d = depth(t[0].position);
            let k = (0..slices.len()).min_by(|&a, &b| (slices[a] - d).abs().total_cmp(&(slices[b] - d).abs())).unwrap();
            assert!(k + 1 >= slab, "slices back to front");
            slab = k + 1;
        } else {
            assert_eq!(t[0].kind, PrimitiveKind::SurfaceTriangle as i32);
            out.push((slab, t[0].near, t[0].far));
        }
    }
    out
}

/// The brute-force placement: slab `s` gets a copy of a triangle whose depth
/// range `[z_min, z_max]` meets `[S[s], S[s-1])`, unclipped when it is the only one.
fn brute_force_slabs(slices: &[f64], z: [f64; 3]) -> Vec<(usize, bool)> {
    let (lo, hi) =
        (z.iter().copied().fold(f64::INFINITY, f64::min), z.iter().copied().fold(f64::NEG_INFINITY, f64::max));
    let hit: Vec<usize> = (0..=slices.len())
        .filter(|&s| {
            let (near, far) = slab_interval(slices, s);
            lo < far && hi >= near
        })
        .collect();
    let clipped = hit.len() > 1;
    hit.into_iter().map(|s| (s, clipped)).collect()
}

/// A small random generator for the tests.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn random_triangles(r: &mut Lcg, count: usize, lo: f64, hi: f64) -> Vec<[[f32; 3]; 3]> {
    (0..count)
        .map(|i| {
            let c = [0, 1, 2].map(|_| lo + (hi - lo) * r.next());
            let size = if i % 4 == 0 { 6.0 } else { 0.8 };
            [0, 1, 2].map(|_| [0, 1, 2].map(|a| (c[a] + size * (r.next() - 0.5)) as f32))
        })
        .collect()
}

#[test]
fn placement_matches_a_brute_force_slab_overlap() {
    let mut r = Lcg(5);
    let tris = random_triangles(&mut r, 200, 0.0, 16.0);
    let (v, t) = surface_of(&tris);
    let surface = SurfaceVertices { vertices: &v, triangles: &t };
    for (p, parallel) in [([-20.0, 3.0, 40.0], false), ([30.0, 25.0, -9.0], true), ([8.0, -30.0, 8.0], false)] {
        let camera = cam(p, [8.0; 3], parallel);
        let view = view_of(&camera);
        let slices = slice_depths(&camera, [0.0; 3], [16.0; 3], 1.3);
        // One triangle a brick: its copies are the brick's placed triangles;
        // drawn in a box a little larger than the slices', so that every
        // slice has its polygon, which tells the slab of what follows it.
        let bounds = [-1.0, 17.0, -1.0, 17.0, -1.0, 17.0];
        let bricks: Vec<BrickSlabs> = (0..tris.len() as u32)
            .map(|i| BrickSlabs { slices: &slices, bounds, drawn: true, batches: vec![i..i + 1], buckets: Vec::new() })
            .collect();
        let g = brick_geometry(&view, &bricks, Some(&surface), None).unwrap();
        let f = view.forward.map(|x| x as f32);
        let e = view.eye.map(|x| x as f32);
        for (i, tri) in tris.iter().enumerate() {
            // The depths as the GL placement computes them.
            let z = tri.map(|p| (0..3).map(|a| (p[a] - e[a]) as f64 * f[a] as f64).sum::<f64>());
            let expected = brute_force_slabs(&slices, z);
            let copies: Vec<(usize, bool)> = copies_in_stream(&g, i, &view, &slices)
                .into_iter()
                .map(|(slab, near, far)| {
                    let clipped = (near, far) != (-UNBOUNDED, UNBOUNDED);
                    if clipped {
                        // Clipped to the slab it is drawn in.
                        let (n, f) = slab_interval(&slices, slab);
                        let bound = |v: f64| if v.is_infinite() { v.signum() as f32 * UNBOUNDED } else { v as f32 };
                        assert_eq!((near, far), (bound(n), bound(f)), "triangle {i}");
                    }
                    (slab, clipped)
                })
                .collect();
            assert_eq!(copies, expected, "triangle {i} at depths {z:?}");
        }
    }
}

/// The CPU compositor's slab for a hit of triangle `t` at depth `z`: the
/// slab of the batch holding `t` whose clip range holds `z` (exactly one).
fn cpu_slab(batches: &[Batch], t: u32, z: f64) -> usize {
    let hits: Vec<usize> = batches
        .iter()
        .filter(|b| b.triangles.contains(&t) && b.clip.is_none_or(|(near, far)| near <= z && z < far))
        .map(|b| b.slab)
        .collect();
    assert_eq!(hits.len(), 1, "triangle {t} at depth {z}: {batches:?}");
    hits[0]
}

/// The OpenGL slab of a fragment of triangle `t` at depth `z`: the slab
/// (by place in the stream) of the copy whose clip interval keeps it (clip
/// distances `z - near >= 0`, `far - z >= 0`).
fn gl_slab(g: &BrickGeometry, view: &GeometryView, slices: &[f64], t: usize, z: f64) -> Vec<usize> {
    copies_in_stream(g, t, view, slices)
        .into_iter()
        .filter(|&(_, near, far)| near as f64 <= z && z <= far as f64)
        .map(|(slab, _, _)| slab)
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The OpenGL placement and the CPU compositor's batches put every point
    /// of every triangle (away from the slice planes, where float rounding
    /// may pick either side) into the same slab: `slab(z)` of its depth.
    #[test]
    fn gl_placement_and_the_cpu_compositor_agree_on_the_slab(
        seed in any::<u64>(),
        azimuth in 0.0f64..360.0,
        elevation in -80.0f64..80.0,
        parallel in any::<bool>(),
        spacing in prop::sample::select(vec![0.5, 1.0, 1.7, 4.0]),
        group in 1usize..6,
    ) {
        let mut r = Lcg(seed);
        let tris = random_triangles(&mut r, 40, 1.0, 15.0);
        let (v, t) = surface_of(&tris);
        let surface = SurfaceVertices { vertices: &v, triangles: &t };
        let camera = Camera::around([0.0; 3], [16.0; 3], azimuth, elevation, parallel).unwrap();
        let slices = slice_depths(&camera, [0.0; 3], [16.0; 3], spacing);
        // The CPU side: batches of `group` triangles with their tight f64 boxes.
        let world: Vec<[[f64; 3]; 3]> = tris.iter().map(|t| t.map(|p| p.map(f64::from))).collect();
        let polygon_batches: Vec<PolygonBatch> = (0..tris.len())
            .step_by(group)
            .map(|first| {
                let end = (first + group).min(tris.len());
                let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for p in world[first..end].iter().flatten() {
                    for a in 0..3 {
                        lo[a] = lo[a].min(p[a]);
                        hi[a] = hi[a].max(p[a]);
                    }
                }
                PolygonBatch { triangles: first as u32..end as u32, lo, hi }
            })
            .collect();
        let batches = assign_batches(&camera, &slices, &polygon_batches);
        // The GL side: one brick a triangle (its stream is that triangle's
        // copies and the slices), in a box a little larger than the slices'.
        let bounds = [-1.0, 17.0, -1.0, 17.0, -1.0, 17.0];
        let bricks: Vec<BrickSlabs> = (0..tris.len() as u32)
            .map(|i| BrickSlabs { slices: &slices, bounds, drawn: true, batches: vec![i..i + 1], buckets: Vec::new() })
            .collect();
        let view = view_of(&camera);
        let g = brick_geometry(&view, &bricks, Some(&surface), None).unwrap();
        let tolerance = 1e-4 * spacing;
        for (i, tri) in world.iter().enumerate() {
            for k in 0..12 {
                let (mut u, mut w) = (r.next(), r.next());
                if u + w > 1.0 {
                    (u, w) = (1.0 - u, 1.0 - w);
                }
                if k == 0 {
                    (u, w) = (1.0 / 3.0, 1.0 / 3.0);
                }
                let p = [0, 1, 2].map(|a| tri[0][a] + u * (tri[1][a] - tri[0][a]) + w * (tri[2][a] - tri[0][a]));
                let z = camera.depth(p);
                if slices.iter().any(|&s| (s - z).abs() < tolerance) {
                    continue;
                }
                let expected = slab_of(&slices, z);
                prop_assert_eq!(cpu_slab(&batches, i as u32, z), expected, "CPU, triangle {} depth {}", i, z);
                prop_assert_eq!(gl_slab(&g, &view, &slices, i, z), vec![expected], "GL, triangle {} depth {}", i, z);
            }
        }
    }
}

#[test]
fn a_real_draw_list_with_a_surface() {
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::{BuildOptions, VolumeOctree};
    use crate::plan::select::{select, SelectOptions};
    use crate::plan::{draw_list, Scene};
    use crate::surface::{Surface, SurfaceOptions};
    let volume = generate(Dataset::SheppLogan, 33, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let surface = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(0.5)).unwrap();
    let shape = grid.shape();
    let options = SelectOptions { max_brick_log2: 3, ..SelectOptions::new(200_000, 0.0) };
    let selection = select(&octree, &options, |_, _| true).unwrap();
    let camera = Camera::around(shape.world([0.0; 3]), shape.world([32.0; 3]), 30.0, 20.0, false).unwrap();
    let scene = Scene {
        surface: Some(&surface),
        surface_opacity: 0.4,
        shading: None,
        gradient_opacity: None,
        transfer_2d: None,
        blend: Default::default(),
        region: None,
    };
    let list = draw_list(&octree, shape, &selection, &camera, &scene, None).unwrap();
    // The surface as the mapper uploads it: world positions, triangles (the DrawList's ids).
    let mut v = Vec::new();
    for p in &surface.points {
        let w = shape.world(*p);
        v.extend([w[0] as f32, w[1] as f32, w[2] as f32, 0.0, 0.0, 1.0]);
    }
    let t: Vec<u32> = (0..surface.polygon_count()).flat_map(|i| surface.polygon(i).to_vec()).collect();
    assert_eq!(t.len(), 3 * surface.polygon_count(), "a triangle mesh");
    let s = SurfaceVertices { vertices: &v, triangles: &t };
    let bricks = list_bricks(&list);
    let g = brick_geometry(&view_of(&camera), &bricks, Some(&s), None).unwrap();
    assert_eq!(g.brick_first.len(), list.bricks.len() + 1);
    assert!(g.brick_first.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(*g.brick_first.last().unwrap() * FLOATS_PER_VERTEX, g.vertices.len());
    // Every triangle placed at least once; bricks with batches are sliced, the rest ray-marched.
    let mut placed = vec![false; surface.polygon_count()];
    for (i, b) in list.bricks.iter().enumerate() {
        assert_eq!(g.ray_marched[i], b.batches.is_empty(), "brick {i}");
        for batch in &b.batches {
            for k in batch.triangles.clone() {
                placed[k as usize] = true;
            }
        }
        if !g.ray_marched[i] {
            let slices = vertices(&g, i).iter().filter(|x| x.kind == PrimitiveKind::Slice as i32).count();
            assert!(slices >= 3 * b.slices.len(), "brick {i}: every slice a polygon");
        }
    }
    assert!(placed.iter().all(|&p| p));
    assert!(g.triangles_placed >= surface.polygon_count());
    // Deterministic.
    assert_eq!(brick_geometry(&view_of(&camera), &bricks, Some(&s), None).unwrap(), g);
}
