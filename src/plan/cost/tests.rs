//! The cost model's arithmetic, the fit on synthetic measurements, the
//! online correction, the search's monotonicity and its ends, and the
//! time-budgeted selection over a real octree. No test measures time.

use super::*;
use crate::data::grid::ScalarType;
use crate::datasets::{generate, Dataset};
use crate::geometry::camera::Camera;
use crate::octree::{BuildOptions, VolumeOctree};
use crate::plan::select::{select, SelectOptions, Selector};
use crate::plan::{draw_list, Blend, BlendMode, Scene};

fn terms(samples: f64, bricks: f64, bytes: f64) -> CostTerms {
    CostTerms {
        pixels: 65536.0,
        bricks,
        brick_pixels: 300.0 * bricks,
        samples,
        upload_bytes: bytes,
        ..CostTerms::default()
    }
}

/// A machine whose frames take exactly `truth`'s time.
fn measured(truth: &CostModel, t: CostTerms) -> Measurement {
    Measurement { terms: t, ms: truth.predict(&t) }
}

#[test]
fn the_model_is_the_sum_of_its_terms() {
    let mut c = [0.0; TERMS];
    c[0] = 2.0; // frame
    c[4] = 1e-6; // samples
    c[9] = 1e-9; // bytes
    let m = CostModel::new(c).unwrap();
    let t = CostTerms { samples: 3e6, upload_bytes: 4e6, ..CostTerms::default() };
    assert!((m.predict(&t) - (2.0 + 3.0 + 0.004)).abs() < 1e-12);
    assert_eq!(m.predict(&CostTerms::default()), 2.0, "a frame of no work costs the constant");
}

#[test]
fn negative_infinite_nan_or_all_zero_coefficients_are_refused() {
    for bad in [-1e-9, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut c = CostModel::prior().coefficients();
        c[4] = bad;
        let e = CostModel::new(c).unwrap_err().to_string();
        assert!(e.contains("samples") && e.contains("at least 0"), "{e}");
    }
    let e = CostModel::new([0.0; TERMS]).unwrap_err().to_string();
    assert!(e.contains("every coefficient is 0"), "{e}");
    let mut c = [0.0; TERMS];
    c[3] = 1e-6;
    assert!(CostModel::new(c).is_ok(), "zero coefficients beside a positive one are fine");
}

#[test]
fn the_fit_recovers_the_machine_from_varied_frames() {
    let mut c = CostModel::prior().coefficients();
    c[0] = 3.0;
    c[3] = 4e-5;
    c[4] = 3e-5;
    c[9] = 1e-6;
    let truth = CostModel::new(c).unwrap();
    let frames: Vec<Measurement> =
        [(1e5, 10.0, 1e4), (1e6, 50.0, 1e6), (4e6, 400.0, 8e6), (2e6, 900.0, 2e6), (8e6, 200.0, 3e7)]
            .iter()
            .map(|&(s, b, u)| measured(&truth, terms(s, b, u)))
            .collect();
    let fitted = fit(&CostModel::prior(), &frames).unwrap();
    for m in &frames {
        let rel = fitted.predict(&m.terms) / m.ms - 1.0;
        assert!(rel.abs() < 0.05, "predicted within 5 % of the frame it was fitted on: {rel}");
    }
    assert!(fitted.coefficients().iter().all(|c| c.is_finite() && *c >= 0.0));
    // A frame it did not see, inside the range.
    let t = terms(3e6, 300.0, 5e6);
    let rel = fitted.predict(&t) / truth.predict(&t) - 1.0;
    assert!(rel.abs() < 0.1, "{rel}");
}

#[test]
fn the_fit_ignores_unusable_frames_and_refuses_none() {
    let truth = CostModel::prior();
    let good = measured(&truth, terms(1e6, 10.0, 0.0));
    let hostile = [
        Measurement { ms: f64::NAN, ..good },
        Measurement { ms: f64::INFINITY, ..good },
        Measurement { ms: -5.0, ..good },
        Measurement { ms: 0.0, ..good },
        Measurement { terms: CostTerms { samples: f64::NAN, ..good.terms }, ..good },
        Measurement { terms: CostTerms { bricks: -1.0, ..good.terms }, ..good },
    ];
    let e = fit(&truth, &hostile).unwrap_err().to_string();
    assert!(e.contains("finite positive time"), "{e}");
    let mut frames = hostile.to_vec();
    frames.push(good);
    let fitted = fit(&truth, &frames).unwrap();
    assert!((fitted.predict(&good.terms) / good.ms - 1.0).abs() < 0.01);
    assert!(fitted.coefficients().iter().all(|c| c.is_finite() && *c >= 0.0));
}

#[test]
fn the_fit_never_makes_a_coefficient_negative() {
    // Times that fall as samples grow: least squares would give samples a
    // negative coefficient; the fit clamps it at 0.
    let frames: Vec<Measurement> = [(1e5, 100.0), (1e6, 80.0), (1e7, 20.0)]
        .iter()
        .map(|&(s, ms)| Measurement { terms: terms(s, 10.0, 0.0), ms })
        .collect();
    let fitted = fit(&CostModel::prior(), &frames).unwrap();
    assert!(fitted.coefficients().iter().all(|c| c.is_finite() && *c >= 0.0), "{:?}", fitted.coefficients());
    assert_eq!(fitted.coefficients()[4], 0.0);
}

#[test]
fn the_online_correction_follows_the_machine_and_ignores_hostile_frames() {
    let model = CostModel::prior();
    let t = terms(2e6, 100.0, 0.0);
    let m = model.predict(&t);
    let mut c = Calibration::new(model);
    for bad in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
        c.observe(&t, bad);
    }
    assert_eq!((c.ratio(), c.corrections()), (1.0, 0), "not finite or not positive: ignored");
    for _ in 0..40 {
        c.observe(&t, 1.5 * m);
    }
    assert!((c.ratio() - 1.5).abs() < 1e-3, "{}", c.ratio());
    assert!((c.predict(&t) / (1.5 * m) - 1.0).abs() < 1e-3);
    // One stalled frame moves it by at most a factor 2^alpha.
    let before = c.ratio();
    c.observe(&t, 1000.0 * m);
    assert!(c.ratio() <= before * 2f64.powf(ALPHA) * (1.0 + 1e-12));
    // Bounded either way.
    for _ in 0..1000 {
        c.observe(&t, 1e9 * m);
    }
    assert!(c.ratio() <= MAX_RATIO);
    // A prediction of 0 cannot be corrected.
    let mut z = [0.0; TERMS];
    z[7] = 1.0;
    let mut c = Calibration::new(CostModel::new(z).unwrap());
    c.observe(&CostTerms::default(), 10.0);
    assert_eq!(c.corrections(), 0);
}

#[test]
fn bad_targets_are_refused_by_name() {
    for (bad, says) in [
        (0.0, "not above 0"),
        (-5.0, "not above 0"),
        (f64::NAN, "not a number"),
        (f64::INFINITY, "above"),
        (1e9, "above"),
    ] {
        let e = check_target_ms(bad).unwrap_err().to_string();
        assert!(e.contains(says) && e.contains("give milliseconds"), "{bad}: {e}");
        assert!(TimeTarget::new(bad, 1000).is_err());
    }
    assert_eq!(check_target_ms(50.0).unwrap(), 50.0);
}

/// A synthetic frame: time `1 + budget / 1000 * 1 / factor` ms, error falling with the budget.
fn synthetic(budget: usize, factor: u32) -> Result<((usize, u32), f64, f64), crate::base::error::Error> {
    let ms = 1.0 + budget as f64 / 1000.0 / f64::from(factor);
    Ok(((budget, factor), ms, 1.0 / (1.0 + budget as f64)))
}

#[test]
fn the_search_meets_the_target_and_its_budget_grows_with_it() {
    let mut last = 0;
    for target_ms in [2.0, 5.0, 10.0, 20.0, 50.0, 100.0] {
        let t = TimeTarget::new(target_ms, 1_000_000).unwrap();
        let c = search(&t, synthetic).unwrap();
        assert_eq!(c.outcome, Outcome::Met);
        assert_eq!(c.chosen.slice_factor, 1);
        assert!(c.chosen.predicted_ms <= target_ms);
        // Within the resolution of the largest budget that fits, (target - 1) * 1000.
        let best = (target_ms - 1.0) * 1000.0;
        assert!(
            c.chosen.budget_bytes as f64 >= best / (1.0 + t.resolution) - 1.0,
            "{target_ms}: {}",
            c.chosen.budget_bytes
        );
        assert!(c.chosen.budget_bytes >= last, "monotone in the target");
        assert!(c.evaluations <= 1 + t.scan_points + t.max_steps);
        last = c.chosen.budget_bytes;
    }
}

#[test]
fn a_target_above_the_full_frame_gives_the_full_budget() {
    let t = TimeTarget::new(5000.0, 1_000_000).unwrap();
    let c = search(&t, synthetic).unwrap();
    assert_eq!((c.outcome, c.chosen.budget_bytes, c.evaluations), (Outcome::Full, 1_000_000, 1));
}

#[test]
fn a_target_below_the_fastest_frame_widens_the_slices_then_says_so() {
    // The coarsest selection (1 byte) takes 1.001 ms at factor 1; a
    // frame of constant time 10 ms cannot be helped by anything.
    let t = TimeTarget::new(0.5, 1_000_000).unwrap();
    let c = search(&t, |b, f| Ok(((b, f), 10.0, 1.0))).unwrap();
    assert_eq!(c.outcome, Outcome::BelowFastest);
    assert_eq!((c.chosen.budget_bytes, c.chosen.slice_factor), (1, t.max_slice_factor));
    // The full budget, then the strides' spacing and the widest: not the spacings between.
    assert_eq!(c.evaluations, 1 + 2 * t.scan_points);
    let note = c.note.unwrap();
    assert!(note.contains("below the fastest frame") && note.contains("10.0 ms"), "{note}");
    // Wider slices that do meet it: the first factor that fits, its budget bisected.
    let t = TimeTarget::new(30.0, 100_000).unwrap();
    let c = search(&t, |b, f| Ok(((b, f), 40.0 / f64::from(f) + b as f64 / 1e4, 0.0))).unwrap();
    assert_eq!((c.outcome, c.chosen.slice_factor), (Outcome::Met, 2));
    assert!(c.chosen.predicted_ms <= 30.0);
    // Only the widest fits: its scan, made out of turn, is the one bisected.
    let c = search(&t, |b, f| Ok(((b, f), 200.0 / f64::from(f) + b as f64 / 1e4, 0.0))).unwrap();
    assert_eq!((c.outcome, c.chosen.slice_factor), (Outcome::Met, 8));
    assert!(c.chosen.predicted_ms <= 30.0 && c.chosen.budget_bytes > 1);
    // A prediction that is not a number never fits.
    let t = TimeTarget::new(30.0, 100).unwrap();
    assert_eq!(search(&t, |b, f| Ok(((b, f), f64::NAN, 0.0))).unwrap().outcome, Outcome::BelowFastest);
}

#[test]
fn the_search_finds_the_fast_middle_when_the_coarsest_frame_is_slow() {
    // One coarse brick visible everywhere is slow; finer cuts that skip the
    // air are faster, then the time grows with the bytes.
    let time = |b: usize| if b < 1000 { 50.0 } else { 5.0 + b as f64 / 1e4 };
    let t = TimeTarget::new(20.0, 1_000_000).unwrap();
    let c = search(&t, |b, f| Ok(((b, f), time(b), 1.0 / (1.0 + b as f64)))).unwrap();
    assert_eq!(c.outcome, Outcome::Met);
    assert!(c.chosen.predicted_ms <= 20.0);
    assert!(c.chosen.budget_bytes as f64 >= 150_000.0 / (1.0 + t.resolution) - 1.0, "{}", c.chosen.budget_bytes);
}

#[test]
fn the_search_keeps_the_least_error_within_the_target() {
    // The error rises at one budget: the bisection's last fit is not taken.
    let t = TimeTarget::new(500.0, 1_000_000).unwrap();
    let c = search(&t, |b, f| {
        let e = if b > 400_000 { 0.5 } else { 1.0 / (1.0 + b as f64) };
        Ok(((b, f), b as f64 / 1000.0, e))
    })
    .unwrap();
    assert!(c.chosen.budget_bytes <= 400_000 && c.chosen.error < 0.5);
}

#[test]
fn rank_correlation_of_orders_ties_and_nan() {
    let up = [(1.0, 10.0), (2.0, 20.0), (3.0, 25.0), (4.0, 100.0)];
    assert_eq!(rank_correlation(&up), Some(1.0));
    let down: Vec<(f64, f64)> = up.iter().map(|&(x, y)| (x, -y)).collect();
    assert_eq!(rank_correlation(&down), Some(-1.0));
    assert_eq!(rank_correlation(&[(1.0, 1.0)]), None);
    assert_eq!(rank_correlation(&[(1.0, 1.0), (1.0, 2.0)]), None, "all ranks equal");
    let with_nan = [(1.0, 1.0), (f64::NAN, 5.0), (2.0, 2.0), (3.0, 3.0)];
    assert_eq!(rank_correlation(&with_nan), Some(1.0));
    // Ties at their mean rank: x = 1, 1, 2 against y = 1, 2, 3 gives 0.866.
    let r = rank_correlation(&[(1.0, 1.0), (1.0, 2.0), (2.0, 3.0)]).unwrap();
    assert!((r - 0.75f64.sqrt()).abs() < 1e-12, "{r}");
}

struct Fixture {
    octree: VolumeOctree,
    shape: crate::data::grid::GridShape,
    camera: Camera,
}

fn fixture() -> Fixture {
    let volume = generate(Dataset::SheppLogan, 65, ScalarType::F32);
    let grid = volume.grid(None).unwrap();
    let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
    let shape = *grid.shape();
    let camera = Camera::around(shape.world([0.0; 3]), shape.world([64.0; 3]), 30.0, 20.0, false).unwrap();
    Fixture { octree, shape, camera }
}

fn plan_of(
    f: &Fixture,
    s: &crate::plan::select::Selection,
) -> Result<crate::plan::DrawList, crate::base::error::Error> {
    let scene = Scene::volume(Blend::new(BlendMode::Composite, f.octree.value_range().into()));
    draw_list(&f.octree, &f.shape, s, &f.camera, &scene, None)
}

#[test]
fn terms_grow_with_the_budget_and_the_slices_widen() {
    let f = fixture();
    let visible = |_: f64, _: f64| true;
    let small = select(&f.octree, &SelectOptions::new(20_000, 0.0), visible).unwrap();
    let large = select(&f.octree, &SelectOptions::new(2_000_000, 0.0), visible).unwrap();
    let (a, b) = (plan_of(&f, &small).unwrap(), plan_of(&f, &large).unwrap());
    let (ta, tb) = (CostTerms::of(&a, 128, 128, small.texture_bytes), CostTerms::of(&b, 128, 128, large.texture_bytes));
    assert!(ta.is_valid() && tb.is_valid());
    assert!(tb.samples > ta.samples && tb.upload_bytes > ta.upload_bytes, "{ta:?} {tb:?}");
    assert_eq!(ta.pixels, 128.0 * 128.0);
    assert_eq!((ta.gradient_samples, ta.scattering_samples, ta.triangles, ta.points), (0.0, 0.0, 0.0, 0.0));
    // The samples estimate is bounded by the slices times the rectangles.
    let bound: f64 = b.bricks.iter().map(|d| d.slices.len() as f64).sum::<f64>() * 128.0 * 128.0;
    assert!(tb.samples <= bound);
    // A full-resolution frame of a 65^3 volume on 128^2 pixels: about 65 slices of the volume's footprint.
    assert!(tb.samples > 1e5 && tb.samples < 65.0 * 128.0 * 128.0 * 2.0, "{}", tb.samples);
    let wide = widen_slices(b.clone(), 4);
    let d0 = b.reference_spacing;
    assert_eq!(wide.plan.min_slice_spacing, Some(4.0 * d0));
    assert!(wide.bricks.iter().all(|d| d.slice_spacing >= 4.0 * d0 * (1.0 - 1e-12)));
    assert_eq!(wide.plan.effects, b.plan.effects, "no per-sample effect added");
    let tw = CostTerms::of(&wide, 128, 128, 0);
    assert!(tw.samples < tb.samples / 2.0, "{} vs {}", tw.samples, tb.samples);
    assert_eq!(widen_slices(b.clone(), 1), b, "factor 1 changes nothing");
}

#[test]
fn the_time_budgeted_selection_is_a_fresh_selection_at_its_budget() {
    let f = fixture();
    let visible = |_: f64, _: f64| true;
    let calibration = Calibration::new(CostModel::prior());
    let shape = FrameShape { width: 128, height: 128, uploads: true };
    let options = SelectOptions::new(4_000_000, 0.0);
    let mut selector = Selector::default();
    // The predicted times of the coarsest and the full selection bracket the targets.
    let time_at = |budget: usize| {
        let s = select(&f.octree, &SelectOptions::new(budget, 0.0), visible).unwrap();
        calibration.predict(&CostTerms::of(&plan_of(&f, &s).unwrap(), 128, 128, s.texture_bytes))
    };
    let (fast, full) = (time_at(1), time_at(4_000_000));
    assert!(fast < full, "{fast} {full}");
    let mut last_error = f64::INFINITY;
    let mut last_budget = 0;
    for k in 1..=4 {
        let target_ms = fast + (full - fast) * f64::from(k) / 5.0;
        let target = TimeTarget::new(target_ms, options.budget_bytes).unwrap();
        let c = select_for_time(
            &target,
            &mut selector,
            &f.octree,
            &options,
            visible,
            None,
            None,
            &calibration,
            shape,
            |s| plan_of(&f, s),
        )
        .unwrap();
        assert_eq!(c.outcome, Outcome::Met);
        assert!(c.chosen.predicted_ms <= target_ms);
        let fresh = select(&f.octree, &SelectOptions::new(c.chosen.budget_bytes, 0.0), visible).unwrap();
        assert_eq!(c.chosen.value.selection, fresh, "replayed equals fresh");
        assert!(c.chosen.budget_bytes >= last_budget);
        assert!(c.chosen.error <= last_error + 0.05, "the error falls as the target grows (up to its wobble)");
        last_budget = c.chosen.budget_bytes;
        last_error = c.chosen.error;
    }
    // Above the full frame: the full budget; below the fastest: the coarsest, said.
    let target = TimeTarget::new(full * 2.0, options.budget_bytes).unwrap();
    let c =
        select_for_time(&target, &mut selector, &f.octree, &options, visible, None, None, &calibration, shape, |s| {
            plan_of(&f, s)
        })
        .unwrap();
    assert_eq!((c.outcome, c.chosen.budget_bytes), (Outcome::Full, options.budget_bytes));
    assert_eq!(c.chosen.error, c.chosen.value.selection.estimated_rms_error, "at the strides: the selection's");
    let target = TimeTarget::new(1e-6, options.budget_bytes).unwrap();
    let c =
        select_for_time(&target, &mut selector, &f.octree, &options, visible, None, None, &calibration, shape, |s| {
            plan_of(&f, s)
        })
        .unwrap();
    assert_eq!(c.outcome, Outcome::BelowFastest);
    assert!(c.note.is_some());
    assert_eq!(c.chosen.value.list.plan.min_slice_spacing.is_some(), c.chosen.slice_factor > 1);
    // The error compared is the frame's as drawn: widened slices cost accuracy.
    let chosen = &c.chosen.value;
    assert_eq!(c.chosen.error, chosen.estimated_rms_error);
    assert_eq!(chosen.estimated_rms_error, super::frame_rms_error(&f.octree, &chosen.list, visible, None));
    // The full budget's fine bricks sliced 8 samples apart: a larger error than at their strides.
    let fine = plan_of(&f, &selector.select_in_view(&f.octree, &options, visible, None, None).unwrap()).unwrap();
    let at_strides = super::frame_rms_error(&f.octree, &fine, visible, None);
    let widened = super::frame_rms_error(&f.octree, &super::widen_slices(fine, 8), visible, None);
    assert!(widened > at_strides, "widened {widened} vs at the strides {at_strides}");
}
