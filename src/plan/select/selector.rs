//! A reusable selection: [`Selector`] keeps what a selection computed
//! (every node's [`cheapest`](super::mass::cheapest) forms and every brick's
//! best next step) for the next one, so that a new budget re-runs only the
//! greedy refinement's queue, not the error mass and form of each node.

use super::brick::{SelectOptions, Selection};
use super::refine::{select_impl, Caches};
use super::view::ViewImportance;
use crate::base::error::Result;
use crate::octree::VolumeOctree;
use crate::points::PointMass;

/// Selections of one octree under one visibility test (and points), each
/// equal to a fresh [`super::select`] (or [`super::select_with_points`],
/// [`super::select_in_view`]) with the same options.
///
/// What is kept depends on what changed (see `Caches`):
///
/// ```text
/// budget changed                                  -> forms and steps kept
/// tolerance changed                               -> forms kept, steps recomputed
/// region of interest or view weights changed      -> forms kept, their weighted
///                                                    masses and the steps recomputed
/// anything else (texels, region, slice, pooling,
///   a view's pixel cap)                           -> both recomputed
/// ```
///
/// The forms hold no importance (a form's weighted mass is summed under
/// the current one when asked for), so a moved region of interest or a
/// new camera re-runs the steps and the queue, not the forms; a view with
/// a pixel cap ([`ViewImportance::caps`]) decides where refinement stops,
/// so its forms are its own.
///
/// The caller keeps one `Selector` per octree, visibility test and points:
/// another transfer function (another `visible`) or another octree needs a
/// [`Selector::default`] (the kept forms would be theirs otherwise).
#[derive(Default)]
pub struct Selector {
    caches: Caches,
    /// The options the forms were made for, with a budget of 0, a
    /// tolerance of 0 and no region of interest.
    forms_for: Option<SelectOptions>,
    /// The view the forms were made for when it caps refinement (none otherwise).
    cap: Option<ViewImportance>,
    /// The options the steps were made for.
    options: Option<SelectOptions>,
    /// The view importance they were made for (none: data space).
    view: Option<ViewImportance>,
}

impl Selector {
    /// [`super::select`] of `octree` under `options` and `visible`, reusing
    /// what the last selection computed that `options` leaves valid.
    pub fn select(
        &mut self,
        octree: &VolumeOctree,
        options: &SelectOptions,
        visible: impl Fn(f64, f64) -> bool,
    ) -> Result<Selection> {
        self.select_in_view(octree, options, visible, None, None)
    }

    /// [`super::select_with_points`], reusing as [`Selector::select`] does.
    pub fn select_with_points(
        &mut self,
        octree: &VolumeOctree,
        options: &SelectOptions,
        visible: impl Fn(f64, f64) -> bool,
        points: &PointMass,
    ) -> Result<Selection> {
        self.select_in_view(octree, options, visible, Some(points), None)
    }

    /// [`super::select_in_view`] (`view`: none is the data-space selection),
    /// with `points` if given, reusing as [`Selector::select`] does, and
    /// keeping the forms from one view to the next.
    pub fn select_in_view(
        &mut self,
        octree: &VolumeOctree,
        options: &SelectOptions,
        visible: impl Fn(f64, f64) -> bool,
        points: Option<&PointMass>,
        view: Option<&ViewImportance>,
    ) -> Result<Selection> {
        let view = view.filter(|v| !v.is_empty());
        self.prepare(options, view);
        select_impl(octree, options, &visible, points, view, &self.caches)
    }

    /// Keeps the caches that `options` and `view` leave valid.
    fn prepare(&mut self, options: &SelectOptions, view: Option<&ViewImportance>) {
        let forms_for = SelectOptions { budget_bytes: 0, tolerance: 0.0, roi: None, ..*options };
        let cap = view.filter(|v| v.caps());
        let view_changed = self.view.as_ref() != view;
        match self.options {
            Some(_) if self.forms_for != Some(forms_for) || self.cap.as_ref() != cap => self.caches = Caches::default(),
            Some(last) if view_changed || last.roi != options.roi => self.caches.reweigh(view_changed),
            Some(last) if last.tolerance != options.tolerance => self.caches.forget_steps(),
            _ => {}
        }
        self.forms_for = Some(forms_for);
        self.cap = cap.cloned();
        self.options = Some(*options);
        if view_changed {
            self.view = view.cloned();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::grid::ScalarType;
    use crate::datasets::{generate, Dataset};
    use crate::octree::BuildOptions;
    use crate::plan::select::{select, select_with_points, Roi};
    use crate::points::{generate_hybrid, PointOptions, PointSelect};

    /// A deterministic stream of numbers in `[0, 1)` (a 64-bit LCG, Knuth's constants).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Random options around `base`: a budget from 2 kB to 2 MB (log-uniform),
    /// often a small change of the last one, sometimes the same options
    /// again; sometimes another tolerance, a region of interest moved,
    /// removed or added, peak-keeping texels.
    fn change(rng: &mut Lcg, last: &SelectOptions) -> SelectOptions {
        let mut o = *last;
        let r = rng.next();
        if r < 0.05 {
            return o;
        } else if r < 0.5 {
            let factor = 0.8 + 0.4 * rng.next();
            o.budget_bytes = ((o.budget_bytes as f64 * factor) as usize).max(1);
        } else if r < 0.7 {
            o.budget_bytes = (2_000.0 * 1000f64.powf(rng.next())) as usize;
        } else if r < 0.8 {
            o.tolerance = [0.0, 0.02, 0.1][(rng.next() * 3.0) as usize];
        } else if r < 0.95 {
            o.roi = (rng.next() < 0.8)
                .then(|| Roi { center: [0, 1, 2].map(|_| rng.next() * 64.0), radius: 2.0 + 10.0 * rng.next() });
        } else {
            o.pooled = !o.pooled;
        }
        o
    }

    /// Every selection of a `Selector` over a random walk of options equals
    /// a fresh one, with or without a transfer function hiding nodes.
    #[test]
    fn reselection_equals_a_fresh_selection_over_random_changes() {
        let v = generate(Dataset::SheppLogan, 65, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 4 }).unwrap();
        for (seed, threshold) in [(1u64, -1.0), (2, 0.25)] {
            let visible = |_: f64, max: f64| max > threshold;
            let mut rng = Lcg(seed);
            let mut selector = Selector::default();
            let mut options = SelectOptions::new(100_000, 0.0);
            let (mut kept, mut changed) = (0, 0);
            for i in 0..60 {
                let next = change(&mut rng, &options);
                changed += usize::from(next.budget_bytes != options.budget_bytes);
                kept += usize::from(next.roi == options.roi && next.pooled == options.pooled);
                options = next;
                let fresh = select(&o, &options, visible).unwrap();
                let again = selector.select(&o, &options, visible).unwrap();
                assert_eq!(again, fresh, "seed {seed}, change {i}: {options:?}");
            }
            // The walk exercised kept caches and new budgets.
            assert!(kept > 30 && changed > 30, "{kept} {changed}");
        }
    }

    /// With points, likewise ([`select_with_points`]), and points were taken.
    #[test]
    fn reselection_with_points_equals_a_fresh_selection() {
        let v = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let (set, _) = generate_hybrid(&grid, &PointOptions::new(2, PointSelect::Threshold(0.1))).unwrap();
        let points = crate::points::PointMass::new(&set, o.layout().leaf_size());
        let mut selector = Selector::default();
        let mut rng = Lcg(7);
        let mut took = false;
        let mut options = SelectOptions::new(20_000, 0.0);
        for i in 0..30 {
            options = change(&mut rng, &options);
            let fresh = select_with_points(&o, &options, |_, _| true, &points).unwrap();
            let again = selector.select_with_points(&o, &options, |_, _| true, &points).unwrap();
            assert_eq!(again, fresh, "change {i}: {options:?}");
            took |= fresh.point_bytes > 0;
        }
        assert!(took, "no selection took points");
    }

    /// Over a walk of budgets and cameras, each view-dependent selection of
    /// a `Selector` equals a fresh [`select_in_view`], and a data-space one
    /// after it equals a fresh [`select`] (the kept view weights go with
    /// the view).
    #[test]
    fn reselection_in_view_equals_a_fresh_selection() {
        use crate::geometry::camera::Camera;
        use crate::plan::select::{select_in_view, Medium, ViewImportance, ViewInputs, ViewSelection};
        let v = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let grid = v.grid(None).unwrap();
        let o = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 4 }).unwrap();
        let medium = Medium::new(&o, &grid, &|v: f64| 0.3 * v.clamp(0.0, 1.0), 1.0, None).unwrap();
        let shape = *grid.shape();
        let mut rng = Lcg(11);
        let mut selector = Selector::default();
        let mut options = SelectOptions::new(20_000, 0.0);
        let mut camera = Camera::around([0.0; 3], [32.0; 3], 0.0, 20.0, false).unwrap();
        for i in 0..30 {
            if rng.next() < 0.5 {
                camera = Camera::around([0.0; 3], [32.0; 3], rng.next() * 360.0, 20.0, rng.next() < 0.3).unwrap();
            } else {
                options = change(&mut rng, &options);
            }
            let mode = ViewSelection::ALL[(rng.next() * 4.0) as usize];
            let inputs = ViewInputs {
                camera: &camera,
                width: 64,
                height: 64,
                shape: &shape,
                // Now and then a pixel cap, which makes the forms the view's own.
                min_texel_pixels: if i % 7 == 3 { 2.0 } else { 0.0 },
                medium: Some(&medium),
            };
            let view = ViewImportance::new(mode, &inputs).unwrap();
            let fresh = select_in_view(&o, &options, |_, _| true, None, &view).unwrap();
            let again = selector.select_in_view(&o, &options, |_, _| true, None, Some(&view)).unwrap();
            assert_eq!(again, fresh, "step {i}: {mode:?} {options:?}");
            if i % 5 == 4 {
                assert_eq!(
                    selector.select(&o, &options, |_, _| true).unwrap(),
                    select(&o, &options, |_, _| true).unwrap()
                );
            }
        }
    }

    /// Bad options are the fresh selection's errors, and the `Selector`
    /// selects as before after one.
    #[test]
    fn bad_options_are_errors_and_leave_the_selector_usable() {
        let v = generate(Dataset::SheppLogan, 33, ScalarType::F32);
        let o = VolumeOctree::build(&v.grid(None).unwrap(), &BuildOptions { leaf_size: 4 }).unwrap();
        let mut selector = Selector::default();
        let good = SelectOptions::new(30_000, 0.0);
        let first = selector.select(&o, &good, |_, _| true).unwrap();
        for bad in [
            SelectOptions::new(0, 0.0),
            SelectOptions::new(30_000, f64::NAN),
            SelectOptions { roi: Some(Roi { center: [1.0; 3], radius: -1.0 }), ..good },
            SelectOptions { bytes_per_texel: 0, ..good },
        ] {
            let e = selector.select(&o, &bad, |_, _| true).unwrap_err().to_string();
            assert_eq!(e, select(&o, &bad, |_, _| true).unwrap_err().to_string());
            assert_eq!(selector.select(&o, &good, |_, _| true).unwrap(), first);
        }
    }
}
