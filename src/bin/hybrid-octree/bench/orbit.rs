//! `bench orbit`: what a view-dependent selection costs while the camera
//! moves. For each view selection, an orbit of `--frames` cameras
//! `--step` degrees apart in azimuth under a texture budget (the bytes of
//! uniform stride `--stride`). A frame re-selects only when the camera
//! moved more than `--view-change` degrees from the camera of the last
//! selection (`select::view_change_degrees`); textures stay resident from
//! one selection to the next, so a frame uploads the bricks (node, level)
//! its selection has and the last one had not. Per view selection: the
//! re-selections, the selection's ms per view change (visibility estimate
//! included), the uploaded bytes per frame (mean, and as a share of the
//! budget), and the last frame's picture: its compositing ms and RMSE
//! against the full-resolution reference of that view.

use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use crate::scene::{frame, load, reference_image, select_options, visible, SceneArgs};
use clap::Args;
use hybrid_octree::camera::Camera;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::select::{uniform, view_change_degrees, Selection, Selector, ViewSelection};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::collections::HashSet;
use std::time::Instant;

/// Arguments of `bench orbit`.
#[derive(Args, Debug)]
pub struct BenchOrbitArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// The budget: the bytes of uniform downsampling at this stride.
    #[arg(long, default_value_t = 4)]
    stride: usize,
    /// Frames of the orbit.
    #[arg(long, default_value_t = 36)]
    frames: usize,
    /// Azimuth step between frames, degrees (from --azimuth).
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    step: f64,
    /// A frame re-selects when the camera moved more than this many
    /// degrees from the camera of the last selection (0: every frame).
    #[arg(long, default_value_t = 5.0, allow_negative_numbers = true)]
    view_change: f64,
    /// The view selections measured.
    #[arg(long, value_delimiter = ',', default_value = "data,screen,visibility,both", value_parser = crate::view::view_selection)]
    view_selections: Vec<ViewSelection>,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One view selection's orbit.
#[derive(Debug, Serialize)]
struct Row {
    view: &'static str,
    frames: usize,
    /// Frames that re-selected (the first one included).
    reselections: usize,
    budget_bytes: usize,
    /// Texture bytes of the last selection.
    texture_bytes: usize,
    /// Selection ms per re-selection (view importance included), mean.
    select_ms: f64,
    /// Selection ms per frame (0 for frames that kept theirs), mean.
    select_ms_per_frame: f64,
    /// Bytes uploaded per frame after the first, mean.
    uploaded_bytes_per_frame: f64,
    /// The same as a fraction of the budget.
    uploaded_share: f64,
    /// The last frame's DrawList plus compositing, ms.
    frame_ms: f64,
    /// The last frame's RMSE against the full-resolution reference of its view.
    rmse: f64,
}

/// Runs the benchmark.
pub fn run(args: &BenchOrbitArgs) -> Result<()> {
    if args.frames == 0 || !args.step.is_finite() || !(args.view_change >= 0.0 && args.view_change.is_finite()) {
        return Err(Error::InvalidArgument(
            "bench orbit needs --frames >= 1, a finite --step and a --view-change of at least 0 degrees".into(),
        ));
    }
    let rows = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let mut scene = load(&grid, &args.scene)?;
        let budget = uniform(&scene.octree, args.stride, scene.texel.bytes())?.texture_bytes;
        let medium = crate::view::medium(&grid, &scene, &args.scene)?;
        let shape = grid.shape();
        let centre = shape.world(shape.dims.map(|d| (d - 1) as f64 / 2.0));
        let (lo, hi) = (shape.world([0.0; 3]), shape.world(shape.dims.map(|d| (d - 1) as f64)));
        let cameras: Vec<Camera> = (0..args.frames)
            .map(|i| {
                let azimuth = args.scene.azimuth + args.step * i as f64;
                Camera::around(lo, hi, azimuth, args.scene.elevation, args.scene.parallel)
            })
            .collect::<Result<_>>()?;
        let options = select_options(&scene, &args.scene, budget, 0.0);
        // Every row's last frame is drawn from the last camera: one reference.
        scene.camera = *cameras.last().unwrap_or(&scene.camera);
        let truth = reference_image(&grid, &scene, &args.scene)?;
        let mut rows = Vec::new();
        for &view in &args.view_selections {
            let mut selector = Selector::default();
            let (mut last, mut selected_at): (Option<Selection>, Option<Camera>) = (None, None);
            let (mut reselections, mut select_ms, mut uploaded) = (0usize, 0.0f64, 0usize);
            for (i, camera) in cameras.iter().enumerate() {
                let moved =
                    selected_at.as_ref().is_none_or(|c| view_change_degrees(c, camera, centre) > args.view_change);
                if !moved {
                    continue;
                }
                let started = Instant::now();
                let weights = crate::view::importance(&grid, &args.scene, camera, view, medium.as_ref())?;
                let s = selector.select_in_view(
                    &scene.octree,
                    &options,
                    visible(&scene, args.scene.isovalue),
                    None,
                    Some(&weights),
                )?;
                select_ms += started.elapsed().as_secs_f64() * 1e3;
                reselections += 1;
                if i > 0 {
                    uploaded += new_bytes(last.as_ref(), &s);
                }
                last = Some(s);
                selected_at = Some(*camera);
            }
            let Some(last) = last else { continue };
            let f = frame(&grid, &scene, &last, &args.scene, None)?;
            let moves = (args.frames - 1).max(1) as f64;
            rows.push(Row {
                view: view.name(),
                frames: args.frames,
                reselections,
                budget_bytes: budget,
                texture_bytes: last.texture_bytes,
                select_ms: select_ms / reselections as f64,
                select_ms_per_frame: select_ms / args.frames as f64,
                uploaded_bytes_per_frame: uploaded as f64 / moves,
                uploaded_share: uploaded as f64 / moves / budget as f64,
                frame_ms: f.drawlist_ms + f.composite_ms,
                rmse: compare(&f.image, &truth)?.rmse,
            });
        }
        Ok(rows)
    })?;
    print_report(&rows, args.json, |rows| print_table(rows))
}

/// Bytes of the bricks of `now` that `before` did not hold (by node and level).
fn new_bytes(before: Option<&Selection>, now: &Selection) -> usize {
    let resident: HashSet<_> = before.map(|b| b.bricks.iter().map(|b| (b.node, b.p)).collect()).unwrap_or_default();
    now.bricks.iter().filter(|b| !resident.contains(&(b.node, b.p))).map(|b| b.bytes).sum()
}

fn print_table(rows: &[Row]) {
    println!(
        "{:>10} {:>6} {:>8} {:>11} {:>11} {:>10} {:>10} {:>13} {:>8} {:>9} {:>8}",
        "view",
        "frames",
        "reselect",
        "budget B",
        "texture B",
        "select ms",
        "ms/frame",
        "upload B/frm",
        "upload%",
        "frame ms",
        "RMSE"
    );
    for r in rows {
        println!(
            "{:>10} {:>6} {:>8} {:>11} {:>11} {:>10.2} {:>10.2} {:>13.0} {:>7.1}% {:>9.1} {:>8.5}",
            r.view,
            r.frames,
            r.reselections,
            r.budget_bytes,
            r.texture_bytes,
            r.select_ms,
            r.select_ms_per_frame,
            r.uploaded_bytes_per_frame,
            100.0 * r.uploaded_share,
            r.frame_ms,
            r.rmse
        );
    }
}
