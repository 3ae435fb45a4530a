//! Frames within a time through the bridge: the warm-up's budgets, the
//! fitted model meeting a target on a simulated machine, the re-search when
//! the machine's speed moves, and bad targets and viewports refused.

use super::octree::HybridOctreeHandle;
use super::render::SelectionHandle;
use super::test_support::{as_bytes, ball_camera, build_volume_octree, f32_desc, select_desc};
use super::timed::{min_budget, FrameTimer, WARM_UP_FRAMES};
use super::{ScatteringDesc, SelectDesc, ShadingDesc, TimedFrameDesc};
use crate::plan::cost::{CostModel, CostTerms};

/// Samples per axis of [`field`].
const N: usize = 49;

/// Detail everywhere (no homogeneous node): a product of sines, x fastest.
fn field() -> Vec<f32> {
    (0..N * N * N)
        .map(|i| {
            let (x, y, z) = ((i % N) as f32, ((i / N) % N) as f32, (i / (N * N)) as f32);
            ((0.4 * x).sin() * (0.3 * y).cos() + (0.5 * z).sin()) * 0.5 + 0.5
        })
        .collect()
}

fn octree() -> Box<HybridOctreeHandle> {
    build_volume_octree(as_bytes(&field()), &f32_desc([N; 3]), 4).unwrap()
}

fn frame(target_ms: f64) -> TimedFrameDesc {
    TimedFrameDesc {
        target_ms,
        camera: ball_camera(),
        width: 256,
        height: 192,
        surface_opacity: 0.0,
        shading: ShadingDesc {
            shade: false,
            ambient: 0.1,
            diffuse: 0.7,
            specular: 0.2,
            specular_power: 10.0,
            two_sided: true,
            headlight: true,
            light_directions: Vec::new(),
            light_ambient: Vec::new(),
            light_diffuse: Vec::new(),
            light_specular: Vec::new(),
        },
        gradient_opacity_points: Vec::new(),
        jittering: false,
        sample_distance: 0.0,
        scattering: ScatteringDesc {
            blending: 0.0,
            reach: 0.0,
            anisotropy: 0.0,
            headlight_ambient: [1.0; 3],
            sample_distance: 0.0,
        },
    }
}

/// The whole volume at full resolution, f32.
fn limit() -> SelectDesc {
    select_desc(N * N * N * 4 * 2)
}

/// A machine `speed` times slower than the prior model says, paying for its uploads.
fn measured(h: &HybridOctreeHandle, s: &SelectionHandle, f: &TimedFrameDesc, uploaded: usize, speed: f64) -> f64 {
    let list = s.list(h, &f.camera, f.surface_opacity).unwrap();
    speed * CostModel::prior().predict(&CostTerms::of(&list, f.width, f.height, uploaded))
}

/// Draws `frames` frames of `f` with `timer` on the machine of `speed`; the last selection.
fn run(
    timer: &mut FrameTimer,
    h: &HybridOctreeHandle,
    f: &TimedFrameDesc,
    frames: usize,
    speed: f64,
) -> Box<SelectionHandle> {
    let mut s = timer.select_for_time(h, &limit(), f).unwrap();
    for _ in 0..frames {
        let uploaded = s.summary().unwrap().texture_bytes;
        let ms = measured(h, &s, f, uploaded, speed);
        if timer.observe_frame(&s, h, f, uploaded, ms).unwrap() {
            s = timer.select_for_time(h, &limit(), f).unwrap();
        }
    }
    s
}

#[test]
fn the_warm_up_draws_the_limit_then_shrinking_budgets() {
    let h = octree();
    let f = frame(10.0);
    let mut timer = FrameTimer::new();
    let mut bytes = Vec::new();
    for i in 0..WARM_UP_FRAMES {
        let summary = timer.summary();
        assert_eq!(summary.warm_up_left, WARM_UP_FRAMES - i);
        let s = timer.select_for_time(&h, &limit(), &f).unwrap();
        assert_eq!(timer.summary().outcome, "warm-up");
        bytes.push(s.summary().unwrap().texture_bytes);
        let ms = measured(&h, &s, &f, 0, 3.0);
        assert!(timer.observe_frame(&s, &h, &f, 0, ms).unwrap(), "every warm-up frame selects again");
    }
    assert_eq!(timer.summary().warm_up_left, 0);
    assert!(
        bytes.windows(2).all(|w| w[0] >= w[1]) && bytes[0] > bytes[WARM_UP_FRAMES - 1],
        "budgets shrink: {bytes:?}"
    );
    let full = h.select_bricks(&limit()).unwrap().summary().unwrap().texture_bytes;
    assert_eq!(bytes[0], full, "the first warm-up frame draws the limit");
    assert!(bytes[WARM_UP_FRAMES - 1] > 0, "the smallest warm-up budget draws bricks");
    // The fitted model predicts the simulated machine.
    let ratio = timer.summary().ratio;
    assert!((ratio - 1.0).abs() < 1e-9, "no correction before the first fitted frame: {ratio}");
}

#[test]
fn a_fitted_timer_meets_targets_between_the_fastest_and_the_full_frame() {
    let h = octree();
    let speed = 3.0;
    // The fastest and the full frame on the simulated machine.
    let coarsest = h.select_bricks(&select_desc(min_budget(limit().budget_bytes))).unwrap();
    let full = h.select_bricks(&limit()).unwrap();
    let f = frame(1.0);
    let (t_lo, t_hi) = (measured(&h, &coarsest, &f, 0, speed), measured(&h, &full, &f, 0, speed));
    assert!(t_hi > 1.5 * t_lo, "the field must span a range of times: {t_lo} .. {t_hi}");
    let mut errors = Vec::new();
    for target in [0.5 * t_lo, 0.5 * (t_lo + t_hi), 2.0 * t_hi] {
        let f = frame(target);
        let mut timer = FrameTimer::new();
        let s = run(&mut timer, &h, &f, WARM_UP_FRAMES + 3, speed);
        let summary = timer.summary();
        let drawn = measured(&h, &s, &f, 0, speed);
        match summary.outcome.as_str() {
            "below-fastest" => {
                assert!(target < t_lo);
                assert!(!summary.note.is_empty(), "the note says the target is below the fastest frame");
            }
            "full" => {
                assert!(target > t_hi);
                assert_eq!(s.summary().unwrap().texture_bytes, full.summary().unwrap().texture_bytes);
            }
            "met" => {
                assert!(drawn <= 1.2 * target, "met {target} ms with a frame of {drawn} ms");
                assert!(drawn >= 0.5 * target, "met {target} ms with a frame of only {drawn} ms");
            }
            other => panic!("outcome {other} after the warm-up"),
        }
        errors.push((summary.slice_factor, summary.estimated_rms_error));
    }
    // Below the fastest budget's frame the slices widen, at a larger
    // estimated error (the estimate counts the slices as drawn); between,
    // bytes buy accuracy.
    assert!(errors[0].0 > 1, "a target below the coarsest frame widens the slices: {errors:?}");
    assert!(errors[0].1 > errors[1].1, "widened slices cost accuracy: {errors:?}");
    assert!(errors[1].0 == 1 && errors[1].1 > 0.0, "a target between is met by bytes: {errors:?}");
    assert!(errors[2] == (1, 0.0), "a target above the full frame draws it: {errors:?}");
}

#[test]
fn the_timer_searches_again_when_the_machine_slows_down() {
    let h = octree();
    let f = frame(6.0e5);
    let mut timer = FrameTimer::new();
    let s = run(&mut timer, &h, &f, WARM_UP_FRAMES + 1, 2.0);
    let ms = measured(&h, &s, &f, 0, 2.0);
    assert!(!timer.observe_frame(&s, &h, &f, 0, ms).unwrap(), "frames as predicted keep the selection");
    let mut again = false;
    for _ in 0..20 {
        let ms = measured(&h, &s, &f, 0, 6.0);
        again = again || timer.observe_frame(&s, &h, &f, 0, ms).unwrap();
    }
    assert!(again, "frames three times slower than predicted select again");
    assert!(timer.summary().ratio > RESEARCHED, "the correction follows: {}", timer.summary().ratio);
}

/// The correction above which the machine has visibly slowed.
const RESEARCHED: f64 = 1.25;

#[test]
fn equal_frames_give_equal_choices() {
    let h = octree();
    let f = frame(0.0);
    let t = measured(&h, &h.select_bricks(&select_desc(N * N * N)).unwrap(), &f, 0, 2.0);
    let f = frame(t);
    let (mut a, mut b) = (FrameTimer::new(), FrameTimer::new());
    let (sa, sb) = (run(&mut a, &h, &f, 6, 2.0), run(&mut b, &h, &f, 6, 2.0));
    assert_eq!(sa.summary().unwrap().texture_bytes, sb.summary().unwrap().texture_bytes);
    assert_eq!(a.summary().budget_bytes, b.summary().budget_bytes);
    assert_eq!(a.summary().slice_factor, b.summary().slice_factor);
}

#[test]
fn bad_targets_and_viewports_are_refused() {
    let h = octree();
    let mut timer = FrameTimer::new();
    for target in [0.0, -5.0, f64::NAN, f64::INFINITY, 1.0e9] {
        let e = timer.select_for_time(&h, &limit(), &frame(target)).unwrap_err();
        assert!(e.contains("target") || e.contains("ms"), "{target}: {e}");
    }
    let e = timer.select_for_time(&h, &limit(), &TimedFrameDesc { width: 0, ..frame(10.0) }).unwrap_err();
    assert!(e.contains("viewport"), "{e}");
    let e = timer.select_for_time(&h, &select_desc(0), &frame(10.0)).unwrap_err();
    assert!(e.contains("budget"), "{e}");
    assert_eq!(timer.summary().warm_up_left, WARM_UP_FRAMES, "nothing refused counts as a frame");
}
