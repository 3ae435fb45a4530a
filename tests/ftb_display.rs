//! Front-to-back display with blocking quadtrees against Meagher's
//! back-to-front display (paper 2): for every object and view of the test
//! set the FTB depth image equals the BTF one bit for bit, FTB never
//! scan-converts more faces, and an axis view equals a direct ray cast
//! through the voxels.

use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::ftb::{back_to_front as btf, front_to_back as ftb, BinaryOctree, Inside, View, ViewCase};
use hybrid_octree::grid::ScalarType;

/// The paper's VPNs, the axis views, two-axis views and seeded random views.
fn views() -> Vec<[f64; 3]> {
    let mut v = vec![
        [1.0, -1.0, 1.0],
        [1.0, -2.0, 1.0],
        [-1.0, -2.0, 1.0],
        [1.0, -1.0, 0.0],
        [0.0, -1.0, 0.0],
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [0.0, 2.0, -1.0],
        [-3.0, 0.0, 1.0],
        [1.0, 1e-9, 1.0], // grazing: one face nearly edge-on
    ];
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..30 {
        v.push([next(), next(), next()]);
    }
    v
}

/// Voxel soup: each voxel black with probability 1/2 (seeded), the worst case for blocking.
fn soup(dims: [usize; 3]) -> Vec<bool> {
    let mut state = 12345u64;
    (0..dims[0] * dims[1] * dims[2])
        .map(|_| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) & 1 == 1
        })
        .collect()
}

fn objects() -> Vec<(String, BinaryOctree)> {
    let mut out = Vec::new();
    let phantom = generate(Dataset::SheppLogan, 48, ScalarType::F32);
    let grid = phantom.grid(None).unwrap();
    out.push(("phantom skull".to_string(), BinaryOctree::from_grid(&grid, Inside::AtOrAbove(0.5)).unwrap()));
    out.push(("phantom inside".to_string(), BinaryOctree::from_grid(&grid, Inside::AtOrAbove(0.15)).unwrap()));
    let sphere = generate(Dataset::Sphere, 37, ScalarType::F32);
    let grid = sphere.grid(None).unwrap();
    let (lo, hi) = (0..37 * 37 * 37).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
        let v = grid.value(i % 37, (i / 37) % 37, i / (37 * 37));
        (lo.min(v), hi.max(v))
    });
    let iso = 0.5 * (lo + hi);
    out.push(("sphere 37^3".to_string(), BinaryOctree::from_grid(&grid, Inside::AtOrAbove(iso)).unwrap()));
    out.push(("soup 13x20x9".to_string(), BinaryOctree::from_voxels([13, 20, 9], &soup([13, 20, 9]))));
    out.push(("all black 8^3".to_string(), BinaryOctree::from_voxels([8, 8, 8], &[true; 512])));
    out.push(("all white 8^3".to_string(), BinaryOctree::from_voxels([8, 8, 8], &[false; 512])));
    let mut one = vec![false; 5 * 6 * 7];
    one[3 + 5 * (2 + 6 * 4)] = true;
    out.push(("one voxel".to_string(), BinaryOctree::from_voxels([5, 6, 7], &one)));
    out
}

#[test]
fn ftb_depth_equals_btf_depth_for_every_object_and_view() {
    for (name, octree) in objects() {
        octree.validate().unwrap();
        for vpn in views() {
            let view = View::new(vpn).unwrap();
            let b = btf::display(&octree, &view, 96);
            let (f, bytes) = ftb::display(&octree, &view, 96);
            assert!(f.image.identical(&b.image), "{name}, vpn {vpn:?}: FTB and BTF depth images differ");
            assert!(
                f.counters.faces <= b.counters.faces,
                "{name}, vpn {vpn:?}: FTB scan-converted {} faces, BTF {}",
                f.counters.faces,
                b.counters.faces
            );
            assert!(bytes <= 1 << (2 * octree.n), "{name}: {bytes} bitmap bytes above 4^n");
            let black = octree.counts().black;
            if black > 0 {
                assert!(b.image.painted() > 0, "{name}, vpn {vpn:?}: nothing drawn");
            } else {
                assert_eq!(f.image.painted(), 0, "{name}: an empty object draws nothing");
            }
        }
    }
}

#[test]
fn blocking_saves_work_on_a_closed_object() {
    let phantom = generate(Dataset::SheppLogan, 64, ScalarType::F32);
    let octree = BinaryOctree::from_grid(&phantom.grid(None).unwrap(), Inside::AtOrAbove(0.15)).unwrap();
    for vpn in [[1.0, -1.0, 1.0], [0.0, -1.0, 0.0]] {
        let view = View::new(vpn).unwrap();
        let b = btf::display(&octree, &view, 128);
        let (f, _) = ftb::display(&octree, &view, 128);
        assert!(f.counters.faces * 2 < b.counters.faces, "vpn {vpn:?}: {} vs {}", f.counters.faces, b.counters.faces);
        assert!(f.counters.black_visited < b.counters.black_visited, "vpn {vpn:?}: blocked subtrees skipped");
        assert!(f.counters.pixels < b.counters.pixels);
    }
}

#[test]
fn an_axis_view_equals_a_ray_cast_through_the_voxels() {
    // VPN +Z: the depth at a pixel is -(top of the highest black voxel in its column - N/2).
    let dims = [13, 20, 9];
    let inside = soup(dims);
    let octree = BinaryOctree::from_voxels(dims, &inside);
    let view = View::new([0.0, 0.0, 1.0]).unwrap();
    assert_eq!(view.case(), ViewCase::Z);
    let size = 101;
    let (f, _) = ftb::display(&octree, &view, size);
    let side = octree.side() as f64;
    let half = side / 2.0;
    let scale = 0.98 * size as f64 / (side * 3f64.sqrt());
    let c = size as f64 / 2.0;
    let mut checked = 0;
    for py in 0..size {
        for px in 0..size {
            // Pixel centre back to the octree space: x along right (+X), y along up (+Y, image rows go down).
            let x = half + (px as f64 + 0.5 - c) / scale * view.right[0] + (c - py as f64 - 0.5) / scale * view.up[0];
            let y = half + (px as f64 + 0.5 - c) / scale * view.right[1] + (c - py as f64 - 0.5) / scale * view.up[1];
            if (x - x.round()).abs() < 1e-3 || (y - y.round()).abs() < 1e-3 {
                continue; // on a voxel boundary: either side is right
            }
            let i = px + size * py;
            let column = (x >= 0.0 && y >= 0.0 && x < dims[0] as f64 && y < dims[1] as f64)
                .then(|| (x.floor() as usize, y.floor() as usize));
            let top =
                column.and_then(|(vx, vy)| (0..dims[2]).rev().find(|&k| inside[vx + dims[0] * (vy + dims[1] * k)]));
            match top {
                Some(k) => {
                    let expected = -((k + 1) as f64 - half);
                    assert!(
                        (f.image.depth[i] - expected).abs() < 1e-9,
                        "pixel {px},{py}: {} vs {expected}",
                        f.image.depth[i]
                    );
                    assert_eq!(f.image.face[i], 3, "a +Z face");
                }
                None => assert_eq!(f.image.face[i], 0, "pixel {px},{py} painted over an empty column"),
            }
            checked += 1;
        }
    }
    assert!(checked > size * size / 2);
}

#[test]
fn a_zero_vpn_is_a_clear_error() {
    let e = View::new([0.0, 0.0, 0.0]).unwrap_err().to_string();
    assert!(e.contains("no direction"), "{e}");
}
