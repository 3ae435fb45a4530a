//! The Surface Octree and the Hybrid Octree through the public API: watertight
//! DiscMC, lossless face compression, the interpolated mode, and the hard
//! cases of the Surface Octree. Every Hybrid Octree built here is validated.

use hybrid_octree::grid::{Grid, GridShape, Samples};
use hybrid_octree::hybrid::HybridOctree;
use hybrid_octree::octree::{BuildOptions, VolumeOctree};
use hybrid_octree::surface::{check, distance, Surface, SurfaceMode, SurfaceOptions};
use proptest::prelude::*;

fn hybrid(grid: &Grid<'_>, leaf: usize, options: SurfaceOptions) -> HybridOctree {
    let h = HybridOctree::build(grid, &BuildOptions { leaf_size: leaf }, &options).expect("build");
    h.validate().expect("validate");
    h
}

/// The surface of a Hybrid Octree built with one.
fn surface(h: &HybridOctree) -> &Surface {
    h.surface.as_ref().expect("built with a surface")
}

fn uncompressed(iso: f64) -> SurfaceOptions {
    SurfaceOptions { compress: false, ..SurfaceOptions::discretized(iso) }
}

/// Distance to the centre of a grid of `n^3`, as f32.
fn ball(n: usize, spacing_free: bool) -> Vec<f32> {
    let c = (n as f32 - 1.0) / 2.0;
    let mut v = Vec::with_capacity(n * n * n);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let (dx, dy, dz) = (x as f32 - c, y as f32 - c, z as f32 - c);
                let r = if spacing_free {
                    (dx * dx + dy * dy + dz * dz).sqrt()
                } else {
                    (dx * dx + 2.0 * dy * dy + dz * dz).sqrt()
                };
                v.push(-r); // inside (>= iso) is near the centre
            }
        }
    }
    v
}

/// Every edge used twice, in opposite directions: a closed, consistently oriented surface.
fn assert_closed(s: &Surface) {
    let e = check::edge_use(s);
    assert_eq!((e.boundary, e.nonmanifold), (0, 0), "{e:?}");
    assert_eq!(s.stats.boundary_edges, 0);
}

fn assert_same_point_set(a: &Surface, b: &Surface) {
    let (aa, ab) = (check::area(a), check::area(b));
    assert!((aa - ab).abs() <= 1e-9 * aa.max(1.0), "areas {aa} vs {ab}");
    let (va, vb) = (check::volume(a), check::volume(b));
    assert!((va - vb).abs() <= 1e-9 * va.abs().max(1.0), "volumes {va} vs {vb}");
}

#[test]
fn closed_sphere_is_watertight_in_both_modes() {
    let n = 41;
    let data = ball(n, true);
    let grid = Grid::scalar(Samples::F32(&data), [n; 3]).unwrap();
    for options in [SurfaceOptions::discretized(-12.3), uncompressed(-12.3), SurfaceOptions::interpolated(-12.3)] {
        let h = hybrid(&grid, 8, options);
        assert!(surface(&h).polygon_count() > 100);
        assert_closed(surface(&h));
        // The enclosed volume is close to the ball's (4/3 pi r^3), and positive.
        let v = check::volume(surface(&h));
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 12.3f64.powi(3);
        assert!((v - exact).abs() < 0.05 * exact, "{:?}: volume {v} vs {exact}", options.mode);
    }
}

#[test]
fn compression_is_lossless_and_saves_polygons() {
    let n = 49;
    let data = ball(n, false);
    let grid = Grid::scalar(Samples::F32(&data), [n; 3]).unwrap();
    let merged = hybrid(&grid, 16, SurfaceOptions::discretized(-15.5));
    let plain = hybrid(&grid, 16, uncompressed(-15.5));
    assert_same_point_set(surface(&merged), surface(&plain));
    assert_closed(surface(&merged));
    assert_eq!(surface(&merged).stats.uncompressed_triangles, surface(&plain).polygon_count());
    assert!(surface(&merged).stats.triangles < surface(&plain).polygon_count());
    assert!(surface(&merged).polygon_count() * 2 < surface(&plain).polygon_count());
    // Sampling: points of every facet lie in a merged polygon of the same node.
    for (node, first, end) in &surface(&plain).node_ranges {
        let range = merged.polygons_of(*node);
        for f in *first as usize..*end as usize {
            let tri: Vec<[f64; 3]> =
                surface(&plain).polygon(f).iter().map(|&v| surface(&plain).points[v as usize]).collect();
            for (wa, wb, wc) in [(1.0, 1.0, 1.0), (4.0, 1.0, 1.0), (1.0, 4.0, 1.0), (1.0, 1.0, 4.0), (1.0, 0.0, 0.0)] {
                let w = wa + wb + wc;
                let q = [0, 1, 2].map(|k| (wa * tri[0][k] + wb * tri[1][k] + wc * tri[2][k]) / w);
                assert!(
                    range.clone().any(|p| inside_convex(surface(&merged), p, q)),
                    "facet {f} point {q:?} is in no merged polygon of node {node:?}"
                );
            }
        }
    }
}

/// `q` lies in convex polygon `p` (on its plane, inside or on its edges).
fn inside_convex(s: &Surface, p: usize, q: [f64; 3]) -> bool {
    let poly: Vec<[f64; 3]> = s.polygon(p).iter().map(|&v| s.points[v as usize]).collect();
    let n = check::polygon_normal(s, s.polygon(p));
    let d = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross =
        |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    if dot(n, d(q, poly[0])).abs() > 1e-9 {
        return false;
    }
    (0..poly.len()).all(|k| dot(cross(d(poly[(k + 1) % poly.len()], poly[k]), d(q, poly[k])), n) >= -1e-9)
}

#[test]
fn a_plane_with_a_bump_merges_around_the_hole() {
    // f = z, inside z >= 3: the plane z = 2.5, with one sample of the plane
    // z = 2 lifted inside, which bulges the surface around it: the plane's
    // region in that node has a hole, so its facets stay (a face must be a
    // simple polygon), while the other nodes' planes merge.
    let dims = [12, 12, 6];
    let mut data: Vec<f64> = (0..12 * 12 * 6).map(|i| (i / (12 * 12)) as f64).collect();
    data[5 + 12 * (5 + 12 * 2)] = 3.0;
    let grid = Grid::scalar(Samples::F64(&data), dims).unwrap();
    let merged = hybrid(&grid, 8, SurfaceOptions::discretized(3.0));
    let plain = hybrid(&grid, 8, uncompressed(3.0));
    assert_same_point_set(surface(&merged), surface(&plain));
    let (m, p) = (surface(&merged), surface(&plain));
    assert_eq!(check::edge_use(m).nonmanifold, 0);
    assert_eq!(check::edge_use(m).boundary, m.stats.boundary_edges);
    assert!(m.stats.faces < m.stats.triangles && m.stats.triangles < p.stats.triangles, "{:?}", m.stats);
    // The node holding the bump keeps the plane's facets: more faces there
    // than in a flat node of the same size.
    let faces_in = |s: &Surface, node| -> usize {
        let r = merged.polygons_of(node);
        let mut f: Vec<u32> = s.polygon_face[r].to_vec();
        f.dedup();
        f.len()
    };
    let counts: Vec<usize> = m.node_ranges.iter().map(|r| faces_in(m, r.0)).collect();
    assert!(counts.iter().max() > counts.iter().min(), "{counts:?}");
}

#[test]
fn isovalue_equal_to_a_plane_of_samples() {
    // f = z: the isovalue 3 equals every sample of the plane z = 3 (inside: >= 3).
    let dims = [9, 7, 8];
    let data: Vec<f64> = (0..9 * 7 * 8).map(|i| (i / (9 * 7)) as f64).collect();
    let grid = Grid::scalar(Samples::F64(&data), dims).unwrap();
    for options in [SurfaceOptions::discretized(3.0), SurfaceOptions::interpolated(3.0)] {
        let h = hybrid(&grid, 4, options);
        let s = surface(&h);
        // DiscMC: the plane z = 2.5; interpolated: exactly through the samples, z = 3.
        let z = if options.mode == SurfaceMode::Discretized { 2.5 } else { 3.0 };
        assert!(s.points.iter().all(|p| p[2] == z), "{:?}", options.mode);
        assert!((check::area(s) - 8.0 * 6.0).abs() < 1e-9);
        // An open plane: it leaves the volume on four sides.
        assert_eq!(s.stats.boundary_edges, check::edge_use(s).boundary);
        assert!(s.stats.boundary_edges > 0);
        assert_eq!(check::edge_use(s).nonmanifold, 0);
        if options.mode == SurfaceMode::Discretized {
            // The whole plane inside one 8-cell-per-axis... at least: far fewer polygons than facets.
            assert!(s.polygon_count() * 4 <= s.stats.uncompressed_triangles, "{:?}", s.stats);
        }
    }
}

#[test]
fn isovalue_outside_the_range_gives_an_empty_surface_and_nan_an_error() {
    let data = ball(9, true);
    let grid = Grid::scalar(Samples::F32(&data), [9; 3]).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    for iso in [1.0, 1e-300, -100.0, f64::from(f32::MAX)] {
        let s = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(iso)).unwrap();
        assert_eq!(s.polygon_count(), 0, "iso {iso}");
    }
    // At the minimum everything is inside: no surface. At the maximum (the centre
    // sample, 0) only that sample is inside: the octahedron around it.
    let s = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(octree.value_range().0)).unwrap();
    assert_eq!(s.polygon_count(), 0);
    let s = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(0.0)).unwrap();
    assert_eq!(s.polygon_count(), 8);
    let e = Surface::extract(&grid, &octree, &SurfaceOptions::discretized(f64::NAN)).unwrap_err();
    assert!(e.to_string().contains("isovalue NaN must be a finite number"), "{e}");
}

#[test]
fn one_voxel_features_are_closed() {
    // A single voxel, and a one-voxel-thin sheet, in a 10 x 11 x 12 (non power of two) grid.
    let dims = [10, 11, 12];
    let mut voxel = vec![0u8; 10 * 11 * 12];
    voxel[5 + 10 * (5 + 11 * 6)] = 200;
    let mut sheet = vec![0u8; 10 * 11 * 12];
    for z in 0..12 {
        for y in 0..11 {
            sheet[4 + 10 * (y + 11 * z)] = 200;
        }
    }
    for (name, data) in [("voxel", &voxel), ("sheet", &sheet)] {
        let grid = Grid::scalar(Samples::U8(data), dims).unwrap();
        for options in [SurfaceOptions::discretized(100.0), uncompressed(100.0), SurfaceOptions::interpolated(100.0)] {
            let h = hybrid(&grid, 4, options);
            let e = check::edge_use(surface(&h));
            assert_eq!(e.nonmanifold, 0, "{name}");
            assert_eq!(e.boundary, surface(&h).stats.boundary_edges, "{name}");
            if name == "voxel" {
                assert_eq!(e.boundary, 0);
                assert!(check::volume(surface(&h)) > 0.0);
            }
        }
        let merged = hybrid(&grid, 4, SurfaceOptions::discretized(100.0));
        let plain = hybrid(&grid, 4, uncompressed(100.0));
        assert_same_point_set(surface(&merged), surface(&plain));
    }
    // The voxel's DiscMC surface is the octahedron through its six edge midpoints: 8 facets, 8 polygons.
    let grid = Grid::scalar(Samples::U8(&voxel), dims).unwrap();
    let h = hybrid(&grid, 4, SurfaceOptions::discretized(100.0));
    assert_eq!((surface(&h).polygon_count(), surface(&h).points.len()), (8, 6));
    assert!((check::volume(surface(&h)) - 4.0 / 3.0 * 0.125).abs() < 1e-12);
}

#[test]
fn anisotropic_spacing_gives_world_normals() {
    let n = 17;
    let data = ball(n, true);
    let shape = GridShape { dims: [n; 3], spacing: [1.0, 1.0, 4.0], origin: [0.0; 3] };
    let grid = Grid::new(Samples::F32(&data), shape, 1, None).unwrap();
    let h = hybrid(&grid, 8, SurfaceOptions::interpolated(-5.0));
    // The top of the sphere (largest z) has a normal close to +z in world space too.
    let top = (0..surface(&h).points.len())
        .max_by(|&a, &b| surface(&h).points[a][2].total_cmp(&surface(&h).points[b][2]))
        .unwrap();
    let nz = surface(&h).normals[top][2];
    assert!(nz > 0.9, "normal {:?}", surface(&h).normals[top]);
    for nrm in &surface(&h).normals {
        let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-5);
    }
}

#[test]
fn every_scalar_type_gives_the_same_surface() {
    let dims = [13, 12, 11];
    let base: Vec<u8> = (0..13 * 12 * 11).map(|i| ((i * 7 + i / 13 * 3 + i / 156 * 5) % 60) as u8).collect();
    let f: Vec<f64> = base.iter().map(|&v| v as f64).collect();
    let reference = hybrid(&Grid::scalar(Samples::F64(&f), dims).unwrap(), 4, SurfaceOptions::discretized(29.5));
    macro_rules! check_type {
        ($variant:ident, $t:ty) => {{
            let v: Vec<$t> = base.iter().map(|&x| x as $t).collect();
            let h = hybrid(&Grid::scalar(Samples::$variant(&v), dims).unwrap(), 4, SurfaceOptions::discretized(29.5));
            assert_eq!(surface(&h).connectivity, surface(&reference).connectivity, stringify!($t));
            assert_eq!(surface(&h).points, surface(&reference).points, stringify!($t));
        }};
    }
    check_type!(U8, u8);
    check_type!(I8, i8);
    check_type!(U16, u16);
    check_type!(I16, i16);
    check_type!(U32, u32);
    check_type!(I32, i32);
    check_type!(F32, f32);
}

#[test]
fn same_surface_on_one_and_many_threads() {
    let n = 37;
    let data = ball(n, false);
    let grid = Grid::scalar(Samples::F32(&data), [n; 3]).unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| hybrid(&grid, 4, SurfaceOptions::discretized(-11.2)).surface.expect("a surface"))
    };
    let one = run(1);
    for threads in [2, 5] {
        let many = run(threads);
        assert_eq!((&many.points, &many.connectivity, &many.normals), (&one.points, &one.connectivity, &one.normals));
        assert_eq!(many.polygon_node, one.polygon_node);
    }
}

#[test]
fn discretized_lies_within_half_a_voxel_of_interpolated() {
    let n = 33;
    let data = ball(n, false);
    let grid = Grid::scalar(Samples::F32(&data), [n; 3]).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions::default()).unwrap();
    let d = distance::discretized_to_interpolated(&grid, &octree, -9.7).unwrap();
    // Corresponding vertices sit on the same edge, at most half an edge apart.
    assert!(d.max > 0.0 && d.max <= 0.5 + 1e-12, "{d:?}");
    assert!(d.mean > 0.0 && d.mean < d.max);
    assert!(d.samples > 1000);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// Random binary volumes exercise every ambiguous face: the surface is always
    /// consistently oriented with no edge used more than twice, boundary edges
    /// are exactly the edges on the volume's faces, and compression keeps the
    /// point set.
    #[test]
    fn random_volumes_stay_watertight(dims in prop::array::uniform3(2usize..12), seed in any::<u64>(), leaf in 1u32..4) {
        let n = dims[0] * dims[1] * dims[2];
        let mut state = seed | 1;
        let data: Vec<i16> = (0..n).map(|_| {
            state ^= state << 13; state ^= state >> 7; state ^= state << 17;
            (state % 3) as i16
        }).collect();
        let grid = Grid::scalar(Samples::I16(&data), dims).unwrap();
        let merged = hybrid(&grid, 1 << leaf, SurfaceOptions::discretized(1.0));
        let plain = hybrid(&grid, 1 << leaf, uncompressed(1.0));
        let interp = hybrid(&grid, 1 << leaf, SurfaceOptions::interpolated(1.0));
        for s in [surface(&merged), surface(&plain), surface(&interp)] {
            let e = check::edge_use(s);
            prop_assert_eq!(e.nonmanifold, 0);
            prop_assert_eq!(e.boundary, s.stats.boundary_edges);
        }
        assert_same_point_set(surface(&merged), surface(&plain));
        prop_assert_eq!(surface(&plain).polygon_count(), surface(&interp).polygon_count());
    }
}
