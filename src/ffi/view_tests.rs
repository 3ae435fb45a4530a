//! The bridge's view-dependent selection (`ffi::view`): what each
//! ViewSelection selects through the handle, what it leaves out, bad values.

use super::test_support::{as_bytes, build_volume_octree, data_view, f32_desc, select_desc};
use super::{view_change_degrees, CameraDesc, HybridOctreeHandle, SelectDesc, SelectionHandle, ViewDesc};

/// Samples per axis of [`walled`].
const N: usize = 64;

/// An opaque wall (value 1) over x < 48, z >= 32, in front of a camera at
/// +z; elsewhere a ripple of values in [0.1, 0.5] (x fastest).
fn walled() -> Vec<f32> {
    (0..N * N * N)
        .map(|i| {
            let (x, y, z) = (i % N, (i / N) % N, i / (N * N));
            let (xf, yf, zf) = (x as f64, y as f64, z as f64);
            let ripple = 0.3 + 0.2 * (0.9 * xf).sin() * (0.7 * yf).cos() * (0.8 * zf + 0.3 * xf).sin();
            if x < 48 && z >= 32 {
                1.0
            } else {
                ripple as f32
            }
        })
        .collect()
}

/// Looking along -z from in front of the wall, the whole grid in view.
fn front_camera() -> CameraDesc {
    CameraDesc {
        position: [31.5, 31.5, 221.5],
        focal_point: [31.5, 31.5, 31.5],
        view_up: [0.0, 1.0, 0.0],
        parallel: false,
        parallel_scale: 1.0,
        view_angle: 30.0,
    }
}

/// `mode` for [`front_camera`] on a 256 x 256 viewport.
fn view(mode: i32) -> ViewDesc {
    ViewDesc { view_selection: mode, camera: front_camera(), viewport: [256, 256], ..data_view() }
}

/// The wall opaque (opacity 1 from 0.9), the ripple faint but visible.
fn desc(budget: usize, mode: i32) -> SelectDesc {
    SelectDesc {
        opacity_points: vec![0.0, 0.0, 0.1, 0.0, 0.5, 0.08, 0.9, 1.0, 1.0, 1.0],
        view: view(mode),
        ..select_desc(budget)
    }
}

/// `desc` selected from `h` (built on `d`), its medium prepared first.
fn select(h: &HybridOctreeHandle, d: &[f32], desc: &SelectDesc) -> Result<Box<SelectionHandle>, String> {
    h.prepare_view(as_bytes(d), &f32_desc([N; 3]), desc)?;
    h.select_bricks(desc)
}

/// Texture bytes of bricks entirely behind the wall (x <= 32, z <= 32).
fn bytes_behind(s: &SelectionHandle) -> usize {
    s.selection.bricks.iter().filter(|b| b.hi[0] <= 32 && b.hi[2] <= 32).map(|b| b.bytes).sum()
}

/// Visibility spends fewer bytes behind the opaque wall than Data at the
/// same budget; both keep within it, and each names what it ran.
#[test]
fn visibility_spends_less_behind_an_opaque_wall() {
    let d = walled();
    let h = build_volume_octree(as_bytes(&d), &f32_desc([N; 3]), 4).unwrap();
    let budget = 250_000;
    let data = select(&h, &d, &desc(budget, 0)).unwrap();
    let hidden = select(&h, &d, &desc(budget, 2)).unwrap();
    let (sd, sv) = (data.summary().unwrap(), hidden.summary().unwrap());
    assert_eq!((sd.view_selection.as_str(), sv.view_selection.as_str()), ("data", "visibility"));
    assert!(sd.texture_bytes <= budget && sv.texture_bytes <= budget);
    let (behind_data, behind_hidden) = (bytes_behind(&data), bytes_behind(&hidden));
    println!("behind the wall: visibility {behind_hidden} B, data {behind_data} B");
    assert!(behind_hidden * 4 < behind_data, "behind the wall: visibility {behind_hidden} B, data {behind_data} B");
    // Without the image's medium, a visibility selection says what to call.
    let fresh = build_volume_octree(as_bytes(&d), &f32_desc([N; 3]), 4).unwrap();
    let e = fresh.select_bricks(&desc(budget, 2)).map(|_| ()).unwrap_err();
    assert!(e.contains("prepare_view"), "{e}");
}

/// Seen from far away the grid covers few pixels: screen space stops
/// refining below a pixel and leaves most of the budget unspent; Data spends it.
#[test]
fn screen_space_stops_below_a_pixel() {
    let d = walled();
    let h = build_volume_octree(as_bytes(&d), &f32_desc([N; 3]), 4).unwrap();
    let far = || CameraDesc { position: [31.5, 31.5, 4000.0], ..front_camera() };
    let budget = 200_000;
    let with = |mode: i32| SelectDesc {
        view: ViewDesc { camera: far(), viewport: [64, 64], ..view(mode) },
        ..desc(budget, 0)
    };
    let data = h.select_bricks(&with(0)).unwrap().summary().unwrap();
    let screen = h.select_bricks(&with(1)).unwrap().summary().unwrap();
    assert_eq!(screen.view_selection, "screen");
    println!("seen from far away: screen {} B, data {} B", screen.texture_bytes, data.texture_bytes);
    assert!(
        screen.texture_bytes * 4 < data.texture_bytes,
        "screen {} B, data {} B",
        screen.texture_bytes,
        data.texture_bytes
    );
}

/// Visibility does not apply to maximum intensity, nor where a cropping
/// region removes samples: Both runs as Screen, Visibility as Data.
#[test]
fn visibility_is_left_out_where_it_does_not_apply() {
    let d = walled();
    let h = build_volume_octree(as_bytes(&d), &f32_desc([N; 3]), 4).unwrap();
    let mip = |mode: i32| SelectDesc { blend_mode: 1, ..desc(60_000, mode) };
    assert_eq!(select(&h, &d, &mip(3)).unwrap().summary().unwrap().view_selection, "screen");
    assert_eq!(select(&h, &d, &mip(2)).unwrap().summary().unwrap().view_selection, "data");
    let mut cropped = desc(60_000, 3);
    cropped.region.cropping = true;
    cropped.region.cropping_planes = [0.0, 63.0, 0.0, 63.0, 0.0, 40.0];
    cropped.region.cropping_flags = 1 << 13;
    assert_eq!(select(&h, &d, &cropped).unwrap().summary().unwrap().view_selection, "screen");
    // A region that keeps the whole grid removes nothing: visibility applies.
    cropped.region.cropping_planes = [-1.0, 64.0, -1.0, 64.0, -1.0, 64.0];
    assert_eq!(select(&h, &d, &cropped).unwrap().summary().unwrap().view_selection, "both");
    assert_eq!(select(&h, &d, &desc(60_000, 3)).unwrap().summary().unwrap().view_selection, "both");
}

/// Bad view values are errors naming the value and what to give.
#[test]
fn bad_view_values_are_refused() {
    let d = walled();
    let h = build_volume_octree(as_bytes(&d), &f32_desc([N; 3]), 4).unwrap();
    let err = |v: ViewDesc| select(&h, &d, &SelectDesc { view: v, ..desc(60_000, 0) }).map(|_| ()).unwrap_err();
    assert!(err(view(4)).contains("view selection 4"));
    assert!(err(view(-1)).contains("view selection -1"));
    assert!(err(ViewDesc { viewport: [0, 10], ..view(3) }).contains("viewport 0x10"));
    assert!(err(ViewDesc { min_texel_pixels: f64::NAN, ..view(3) }).contains("smallest texel NaN"));
    assert!(err(ViewDesc { min_texel_pixels: -1.0, ..view(1) }).contains("smallest texel -1"));
    let nan_camera = CameraDesc { position: [f64::NAN, 0.0, 0.0], ..front_camera() };
    assert!(err(ViewDesc { camera: nan_camera, ..view(3) }).contains("finite"));
    assert!(err(ViewDesc { surface_opacity: 2.0, ..view(2) }).contains("surface opacity 2"));
    assert!(err(ViewDesc { opacity_unit_distance: 0.0, ..view(2) }).contains("unit distance 0"));
    // Checked in Data too: a bad setting is not hidden until the mode changes.
    assert!(err(ViewDesc { min_texel_pixels: -1.0, ..view(0) }).contains("smallest texel -1"));
}

/// The view change of a turn about the centre is its angle; a bad camera
/// or centre is an error.
#[test]
fn view_change_is_the_turn_in_degrees() {
    let a = front_camera();
    let t = 10f64.to_radians();
    let b = CameraDesc { position: [31.5 + 190.0 * t.sin(), 31.5, 31.5 + 190.0 * t.cos()], ..front_camera() };
    let centre = [31.5, 31.5, 31.5];
    assert!((view_change_degrees(&a, &b, &centre).unwrap() - 10.0).abs() < 1e-9);
    assert!(view_change_degrees(&a, &a, &centre).unwrap().abs() < 1e-9);
    assert!(view_change_degrees(&a, &b, &[0.0, f64::NAN, 0.0]).unwrap_err().contains("finite centre"));
    assert!(view_change_degrees(&a, &b, &[0.0]).unwrap_err().contains("finite centre"));
    let bad = CameraDesc { focal_point: a.position, ..a };
    assert!(view_change_degrees(&a, &bad, &centre).unwrap_err().contains("camera"));
}
