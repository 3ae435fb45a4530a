//! The view-dependent selection against the picture: bytes go where the
//! viewer sees them, and the picture is closer to the full-resolution
//! reference than the data-space selection's at the same bytes.

use super::compositor::composite;
use super::metrics::compare;
use super::reference::{reference, ReferenceOptions};
use crate::data::grid::{Grid, GridShape, Samples};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::select::{
    select_in_view, uniform, Medium, SelectOptions, Selection, ViewImportance, ViewInputs, ViewSelection,
};
use crate::plan::Scene;
use crate::transfer::TransferFunction;

const N: usize = 65;

/// Detail everywhere (a 3D ripple in [0.1, 0.5]) but for a dense wall at
/// `20 <= y < 28`: the camera at -y sees the front part through nothing
/// and the back part through the wall.
fn walled() -> Vec<f32> {
    let mut v = vec![0.0f32; N * N * N];
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let f = |t: usize| (t as f32 * 0.55).sin();
                v[x + N * (y + N * z)] = if (20..28).contains(&y) { 1.0 } else { 0.3 + 0.2 * f(x) * f(y) * f(z) };
            }
        }
    }
    v
}

fn tf() -> TransferFunction {
    TransferFunction::new(
        vec![(0.0, [0.2, 0.4, 1.0]), (0.5, [1.0, 0.8, 0.3]), (1.0, [1.0, 1.0, 1.0])],
        vec![(0.1, 0.0), (0.5, 0.08), (0.9, 0.08), (1.0, 0.7)],
    )
    .unwrap()
}

struct Setup {
    values: Vec<f32>,
    shape: GridShape,
    camera: Camera,
}

impl Setup {
    fn new() -> Setup {
        let shape = GridShape { dims: [N; 3], spacing: [1.0; 3], origin: [0.0; 3] };
        let camera = Camera::around([0.0; 3], [64.0; 3], 0.0, 0.0, false).unwrap();
        Setup { values: walled(), shape, camera }
    }
}

/// The selection of `mode` under the budget of uniform stride 2, with a
/// `size x size` image.
fn selection(grid: &Grid<'_>, octree: &VolumeOctree, camera: &Camera, mode: ViewSelection, size: usize) -> Selection {
    let t = tf();
    let opacity = |v: f64| t.opacity(v) as f64;
    let medium = Medium::new(octree, grid, &opacity, 1.0, None).unwrap();
    let shape = grid.shape();
    let inputs = ViewInputs { camera, width: size, height: size, shape, min_texel_pixels: 1.0, medium: Some(&medium) };
    let view = ViewImportance::new(mode, &inputs).unwrap();
    let budget = uniform(octree, 2, 4).unwrap().texture_bytes;
    select_in_view(octree, &SelectOptions::new(budget, 0.0), |a, b| !t.is_transparent_over(a, b), None, &view).unwrap()
}

/// Texture bytes behind the wall (`y >= 28`): each brick's bytes times
/// the share of its box there.
fn behind(s: &Selection) -> f64 {
    s.bricks
        .iter()
        .map(|b| {
            let (lo, hi) = (b.lo[1] as f64, b.hi[1] as f64);
            b.bytes as f64 * ((hi - lo.max(28.0)).max(0.0) / (hi - lo))
        })
        .sum()
}

/// Visibility moves bytes from behind the wall to the front; the picture's
/// RMSE against the full-resolution reference (measured: data 0.0044,
/// visibility 0.0088, both 0.0044).
#[test]
fn visibility_spends_bytes_in_front_of_the_wall() {
    let s = Setup::new();
    let grid = Grid::new(Samples::F32(&s.values), s.shape, 1, None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let t = tf();
    let truth = reference(&grid, &t, &s.camera, 96, 96, &ReferenceOptions::default()).unwrap();
    let rmse = |sel: &Selection| {
        let scene = Scene {
            surface: None,
            surface_opacity: 0.0,
            shading: None,
            gradient_opacity: None,
            transfer_2d: None,
            blend: Default::default(),
            region: None,
        };
        let list = crate::plan::draw_list(&octree, grid.shape(), sel, &s.camera, &scene, None).unwrap();
        let image = composite(&grid, &list, &t, 96, 96, None).unwrap();
        compare(&image, &truth).unwrap().rmse
    };
    let data = selection(&grid, &octree, &s.camera, ViewSelection::Data, 96);
    let seen = selection(&grid, &octree, &s.camera, ViewSelection::Visibility, 96);
    let both = selection(&grid, &octree, &s.camera, ViewSelection::Both, 96);
    assert!(2.0 * behind(&seen) < behind(&data), "behind the wall: {} vs {}", behind(&seen), behind(&data));
    let (rd, rv, rb) = (rmse(&data), rmse(&seen), rmse(&both));
    eprintln!("RMSE data {rd:.4}, visibility {rv:.4}, both {rb:.4}");
    // Both is no worse than the data-space selection. Visibility alone is
    // (about 2x here): on data with detail everywhere its greedy cut of
    // small bricks at strides 2 and 4 in front loses to the one stride-2
    // brick the data-space selection starts from (docs/ARCHITECTURE.md).
    assert!(rb <= rd * 1.05, "data {rd}, both {rb}");
    assert!(rv < 3.0 * rd, "data {rd}, visibility {rv}");
    // Seen from behind, the same wall hides the front: bytes go the other way.
    let back = Camera::around([0.0; 3], [64.0; 3], 180.0, 0.0, false).unwrap();
    let from_back = selection(&grid, &octree, &back, ViewSelection::Visibility, 96);
    assert!(behind(&from_back) > behind(&data), "{} vs {}", behind(&from_back), behind(&data));
}

/// On a 12-pixel image no texel finer than a pixel is drawn: the
/// screen-space selection never goes below the stride whose texels cover a
/// pixel, whatever the budget, while the data-space one reaches stride 1.
#[test]
fn screen_space_stops_below_a_pixel() {
    let s = Setup::new();
    let grid = Grid::new(Samples::F32(&s.values), s.shape, 1, None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
    let t = tf();
    let shape = grid.shape();
    let inputs =
        |size| ViewInputs { camera: &s.camera, width: size, height: size, shape, min_texel_pixels: 1.0, medium: None };
    let visible = |a: f64, b: f64| !t.is_transparent_over(a, b);
    let all = SelectOptions::new(1 << 30, 0.0);
    let data = select_in_view(&octree, &all, visible, None, &ViewImportance::default()).unwrap();
    assert_eq!(data.bricks.iter().map(|b| b.stride).min(), Some(1));
    let view = ViewImportance::new(ViewSelection::Screen, &inputs(12)).unwrap();
    let small = select_in_view(&octree, &all, visible, None, &view).unwrap();
    let finest = small.bricks.iter().map(|b| b.stride).min().unwrap();
    assert!(finest >= 4, "finest stride {finest} on a 12-pixel image");
    assert!(small.texture_bytes * 8 < data.texture_bytes);
    // A large image refines to full resolution again.
    let view = ViewImportance::new(ViewSelection::Screen, &inputs(1024)).unwrap();
    let large = select_in_view(&octree, &all, visible, None, &view).unwrap();
    assert_eq!(large.bricks.iter().map(|b| b.stride).min(), Some(1));
}
