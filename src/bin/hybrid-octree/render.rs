//! `render`: one frame of the Hybrid Octree under a texture budget, written
//! as a PNG, with what it cost (bricks, bytes, step times, the plan) and,
//! with `--reference`, how far it is from the full-resolution ray caster.

use crate::extension::require_extension;
use crate::field::Field;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use crate::scene::{
    dress, dress_field, frame_of, load, reference_image, select_options, visible, Frame, Loaded, SceneArgs,
};
use clap::Args;
use hybrid_octree::grid::Grid;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::select::{select_in_view, Selection, ViewSelection};
use hybrid_octree::store::Store;
use hybrid_octree::Result;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// Texture budget in megabytes (10^6 bytes).
    #[arg(long, default_value_t = 64.0, allow_negative_numbers = true)]
    budget_mb: f64,
    /// Error tolerance Eu: nodes stop refining at e_p <= Eu / Imp (fraction of the data range).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    tolerance: f64,
    /// The PNG to write.
    #[arg(long)]
    output: PathBuf,
    /// Also ray-cast the full-resolution reference, report RMSE/PSNR/SSIM and write it here.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
    /// Read an OME-Zarr store's volume whole into memory instead of drawing it from disk brick by brick.
    #[arg(long)]
    in_memory: bool,
    /// Frame-time target, ms: the texture budget (at most --budget-mb) and,
    /// when bytes alone cannot, the slice spacing of the least estimated
    /// error whose frame (upload and compositing) the cost model, calibrated
    /// on warm-up frames, predicts within it.
    #[arg(long, allow_negative_numbers = true)]
    target_ms: Option<f64>,
    /// Warm-up frames that calibrate the cost model for --target-ms (at least 2).
    #[arg(long, default_value_t = 3)]
    warmup_frames: usize,
}

/// What `render` reports.
#[derive(Debug, Serialize)]
struct RenderReport {
    output: String,
    width: usize,
    height: usize,
    budget_bytes: usize,
    /// Texture bytes as uploaded, at the texel format's width.
    texture_bytes: usize,
    /// What the selection weighed nodes by (`--view-selection`).
    view_selection: hybrid_octree::select::ViewSelection,
    /// The texel format (`--texel-format` resolved for the data), its
    /// decoding `bias + scale t` and quantization error (data units).
    texel: hybrid_octree::plan::texel_format::TexelEncoding,
    /// The hard memory limit (`--budget-mb`); `budget_bytes` is what the
    /// selection was given (with `--target-ms`, what the search chose).
    max_budget_bytes: usize,
    /// `--target-ms`.
    target_ms: Option<f64>,
    /// The frame's measured time: upload and compositing, ms.
    ms: f64,
    /// The cost model's prediction of `ms` (with `--target-ms`).
    predicted_ms: Option<f64>,
    /// How the choice relates to the target: met, full (the whole budget
    /// fits), below-fastest (even the coarsest selection is predicted over it).
    time_outcome: Option<&'static str>,
    /// The slices' least spacing in multiples of the reference spacing d0 (1: the strides').
    slice_factor: Option<u32>,
    /// The warm-up frames' coarsest selection, measured, ms.
    fastest_ms: Option<f64>,
    /// Warm-up frames that calibrated the cost model.
    warmup_frames: Option<usize>,
    /// Candidates the search evaluated.
    evaluations: Option<usize>,
    bricks: usize,
    /// The selection's estimated error (`select::estimated_error`): the
    /// largest nodal error of the visible bricks, a fraction of the data
    /// range; 0 when they all draw the full-resolution field. The volume
    /// mapper's `GetLastEstimatedError()` is the same number.
    estimated_error: f64,
    /// The selection's estimated root-mean-square error of the visible
    /// samples (`select::estimated_rms_error`), a fraction of the data range.
    estimated_rms_error: f64,
    passes: Vec<String>,
    /// What each volume sample does besides its classification, then what
    /// removes samples (the plan's effects: `transfer-2d`, `gradient-opacity` or
    /// `opacity-scale`, `shading`, `cropping`, `clipping`), then `jittering`; empty: nothing.
    effects: Vec<String>,
    /// The cropping and clipping planes that act on the volume (world coordinates).
    region: Option<hybrid_octree::plan::crop::KeptRegion>,
    /// The shading the frame used, lights in world space (the plan says `volume-shaded`).
    lighting: Option<hybrid_octree::transfer::lighting::Lighting>,
    /// The blend mode and its ranges (the plan's).
    blend: hybrid_octree::plan::Blend,
    skipped_bricks: usize,
    warning: Option<String>,
    /// The selection, its view importance included, ms.
    select_ms: f64,
    slab_polygons_ms: f64,
    drawlist_ms: f64,
    upload_ms: f64,
    composite_ms: f64,
    rmse: Option<f64>,
    psnr: Option<f64>,
    ssim: Option<f64>,
    reference_ms: Option<f64>,
}

/// Renders and reports.
pub fn run(args: &RenderArgs) -> Result<()> {
    require_extension(&args.output, "--output", &[".png"], "PNG pictures")?;
    if let Some(path) = &args.reference {
        require_extension(path, "--reference", &[".png"], "PNG pictures")?;
    }
    let budget_bytes = crate::bench::render::budget_bytes(args.budget_mb)?;
    if let Some(t) = args.target_ms {
        check_target(t)?;
    }
    let report = with_threads(args.input.threads, || match args.input.store()? {
        Some(store) if !args.in_memory => from_store(args, &store, budget_bytes),
        Some(store) => in_memory(args, budget_bytes, Some(&store)),
        None => in_memory(args, budget_bytes, None),
    })?;
    if let (false, Some(w)) = (args.json, &report.warning) {
        eprintln!("warning: {w}");
    }
    print_report(&report, args.json, print_text)
}

/// The frame of a volume read into memory: the input's, or the open
/// `store`'s read whole (with its stored octree if it has one).
fn in_memory(args: &RenderArgs, budget_bytes: usize, store: Option<&Store>) -> Result<RenderReport> {
    let (volume, stored) = match store {
        Some(store) => (store.read_volume()?, store.octree()?),
        None => (args.input.load()?, None),
    };
    let grid = args.input.grid(&volume)?;
    let scene = match stored {
        Some(octree) => dress(&grid, octree, &args.scene)?,
        None => load(&grid, &args.scene)?,
    };
    let options = select_options(&scene, &args.scene, budget_bytes, args.tolerance);
    let started = Instant::now();
    let mode = args.scene.view.view_selection;
    let medium = match mode {
        ViewSelection::Visibility | ViewSelection::Both => crate::view::medium(&grid, &scene, &args.scene)?,
        _ => None,
    };
    let view = crate::view::importance(&grid, &args.scene, &scene.camera, mode, medium.as_ref())?;
    let (selection, f, timed, select_ms) = select_and_draw(args, Field::Grid(&grid), &scene, options, &view, started)?;
    f.image.to_png(&args.output)?;
    let reference = match &args.reference {
        Some(path) => Some(reference(&grid, &scene, args, &f, path)?),
        None => None,
    };
    let warning = timed_warning(selection.warning.clone(), timed.as_ref());
    Ok(report(args, budget_bytes, &scene, &selection, &f, (select_ms, mode), reference, warning, timed.as_ref()))
}

/// The frame of an OME-Zarr store drawn from disk: its octree (stored, or
/// for a store written elsewhere built by one streaming pass over its full
/// resolution) selects, each brick is read from the level of its stride
/// (subsampled from the full resolution when the store lacks that level). The visibility estimate needs every sample, so a store
/// weighs by screen space alone (said in the warning); the reference, if
/// asked for, reads the whole volume.
fn from_store(args: &RenderArgs, store: &Store, budget_bytes: usize) -> Result<RenderReport> {
    if !store.has_octree() {
        store.check_streamable()?;
        let [nx, ny, nz] = store.shape.dims;
        eprintln!(
            "warning: '{}' holds no Volume Octree: it is built first by one pass over its {nx} x {ny} x {nz} \
             samples ({} chunks); `hybrid-octree convert` stores it once",
            store.label(),
            store.spatial_chunks()
        );
    }
    let octree = store.volume_octree(args.scene.leaf_size)?;
    let field = Field::Store(store);
    let scene = dress_field(field, octree, &args.scene)?;
    let options = select_options(&scene, &args.scene, budget_bytes, args.tolerance);
    let started = Instant::now();
    let (mode, note) = match args.scene.view.view_selection {
        ViewSelection::Visibility | ViewSelection::Both => (
            ViewSelection::Screen,
            Some(format!(
                "view selection '{}' weighs nodes by the opacity in front of them, estimated from every sample: \
                 a volume drawn from disk is weighed by screen space alone",
                args.scene.view.view_selection.name()
            )),
        ),
        m => (m, None),
    };
    let view = crate::view::importance_in(&store.shape, &args.scene, &scene.camera, mode, None)?;
    let (selection, f, timed, select_ms) = select_and_draw(args, field, &scene, options, &view, started)?;
    f.image.to_png(&args.output)?;
    let reference = match &args.reference {
        Some(path) => {
            let volume = store.read_volume()?;
            let grid = volume.grid(None)?;
            Some(reference(&grid, &scene, args, &f, path)?)
        }
        None => None,
    };
    let warning = join(timed_warning(selection.warning.clone(), timed.as_ref()), note);
    Ok(report(args, budget_bytes, &scene, &selection, &f, (select_ms, mode), reference, warning, timed.as_ref()))
}

/// The frame's selection and picture: within `--target-ms` when given
/// ([`timed`]), else under the budget of `options`; with what the report
/// needs of the time search, and the select time counted from `started`.
fn select_and_draw(
    args: &RenderArgs,
    field: Field<'_>,
    scene: &Loaded,
    options: hybrid_octree::select::SelectOptions,
    view: &hybrid_octree::select::ViewImportance,
    started: Instant,
) -> Result<(Selection, Frame, Option<TimedReport>, f64)> {
    if let Some(target) = args.target_ms {
        return timed(args, field, scene, options, view, target);
    }
    let selection = select_in_view(&scene.octree, &options, visible(scene, args.scene.isovalue), None, view)?;
    let select_ms = started.elapsed().as_secs_f64() * 1e3;
    let f = frame_of(field, scene, &selection, &args.scene, None)?;
    Ok((selection, f, None, select_ms))
}

/// The selection's warning, or with `--target-ms` the search's note in its
/// place: the time chose the budget, so the selection's advice to raise it
/// for the tolerance does not apply.
fn timed_warning(selection: Option<String>, timed: Option<&TimedReport>) -> Option<String> {
    match timed {
        Some(t) => t.note.clone(),
        None => selection,
    }
}

/// Two warnings as one.
fn join(a: Option<String>, b: Option<String>) -> Option<String> {
    match (a, b) {
        (Some(a), Some(b)) => Some(format!("{a}; {b}")),
        (a, b) => a.or(b),
    }
}

/// `--target-ms`: in range, or the one-line error of the cost model's check, naming the flag.
fn check_target(ms: f64) -> Result<f64> {
    hybrid_octree::plan::cost::check_target_ms(ms)
        .map_err(|e| hybrid_octree::Error::InvalidArgument(format!("--target-ms: {e}")))
}

/// What the time search chose, for the report.
struct TimedReport {
    target_ms: f64,
    predicted_ms: f64,
    outcome: &'static str,
    slice_factor: u32,
    budget_bytes: usize,
    fastest_ms: Option<f64>,
    warmup_frames: usize,
    evaluations: usize,
    note: Option<String>,
}

/// The frame within `target` ms (`crate::timed`): calibrated on the
/// warm-up frames, searched, drawn. Its select time is the search's.
fn timed(
    args: &RenderArgs,
    field: Field<'_>,
    scene: &Loaded,
    options: hybrid_octree::select::SelectOptions,
    view: &hybrid_octree::select::ViewImportance,
    target: f64,
) -> Result<(Selection, Frame, Option<TimedReport>, f64)> {
    let mut timer = crate::timed::Timer::new(field, scene, &args.scene, options, Some(view));
    timer.calibrate(args.warmup_frames)?;
    let t = timer.frame(target)?;
    let report = TimedReport {
        target_ms: t.target_ms,
        predicted_ms: t.predicted_ms,
        outcome: t.outcome.name(),
        slice_factor: t.slice_factor,
        budget_bytes: t.budget_bytes,
        fastest_ms: timer.fastest_ms,
        warmup_frames: timer.warmup_frames,
        evaluations: t.evaluations,
        note: t.note,
    };
    Ok((t.selection, t.frame, Some(report), t.search_ms))
}

/// The reference picture written to `path` and the frame's distance to it:
/// (RMSE, PSNR, SSIM, reference ms).
fn reference(
    grid: &Grid<'_>,
    scene: &Loaded,
    args: &RenderArgs,
    f: &Frame,
    path: &Path,
) -> Result<(f64, f64, f64, f64)> {
    let started = Instant::now();
    let r = reference_image(grid, scene, &args.scene)?;
    let ms = started.elapsed().as_secs_f64() * 1e3;
    r.to_png(path)?;
    let m = compare(&f.image, &r)?;
    Ok((m.rmse, m.psnr, m.ssim, ms))
}

/// The report of one frame.
#[allow(clippy::too_many_arguments)]
fn report(
    args: &RenderArgs,
    budget_bytes: usize,
    scene: &Loaded,
    selection: &Selection,
    f: &Frame,
    (select_ms, view_selection): (f64, ViewSelection),
    reference: Option<(f64, f64, f64, f64)>,
    warning: Option<String>,
    timed: Option<&TimedReport>,
) -> RenderReport {
    RenderReport {
        output: args.output.display().to_string(),
        width: args.scene.width,
        height: args.scene.height,
        budget_bytes: timed.map_or(budget_bytes, |t| t.budget_bytes),
        max_budget_bytes: budget_bytes,
        target_ms: timed.map(|t| t.target_ms),
        ms: crate::timed::frame_ms(f),
        predicted_ms: timed.map(|t| t.predicted_ms),
        time_outcome: timed.map(|t| t.outcome),
        slice_factor: timed.map(|t| t.slice_factor),
        fastest_ms: timed.and_then(|t| t.fastest_ms),
        warmup_frames: timed.map(|t| t.warmup_frames),
        evaluations: timed.map(|t| t.evaluations),
        texture_bytes: selection.texture_bytes,
        view_selection,
        texel: scene.texel,
        bricks: selection.bricks.len(),
        estimated_error: selection.estimated_error,
        estimated_rms_error: selection.estimated_rms_error,
        passes: f.list.plan.passes.clone(),
        effects: f.list.plan.effects.clone(),
        region: f.list.region,
        lighting: f.list.lighting.clone(),
        blend: f.list.plan.blend,
        skipped_bricks: f.list.plan.skipped_bricks,
        warning,
        select_ms,
        slab_polygons_ms: f.slab_polygons_ms,
        drawlist_ms: f.drawlist_ms,
        upload_ms: f.upload_ms,
        composite_ms: f.composite_ms,
        rmse: reference.map(|r| r.0),
        psnr: reference.map(|r| r.1),
        ssim: reference.map(|r| r.2),
        reference_ms: reference.map(|r| r.3),
    }
}

fn print_text(r: &RenderReport) {
    println!("wrote {} ({}x{})", r.output, r.width, r.height);
    println!("plan:            {} ({} transparent or removed nodes skipped)", r.passes.join(" -> "), r.skipped_bricks);
    if !r.effects.is_empty() {
        println!("volume effects:  {}", r.effects.join(", "));
    }
    println!(
        "bricks:          {} using {:.2} MB of {} texels of a {:.2} MB budget, estimated error {:.4} (RMS {:.5})",
        r.bricks,
        r.texture_bytes as f64 / 1e6,
        r.texel.format.name(),
        r.budget_bytes as f64 / 1e6,
        r.estimated_error,
        r.estimated_rms_error
    );
    println!("view selection:  {}", r.view_selection.name());
    if let (Some(target), Some(predicted)) = (r.target_ms, r.predicted_ms) {
        println!(
            "frame time:      target {target:.1} ms, predicted {predicted:.1} ms, measured {:.1} ms ({}; budget {:.2} MB of {:.2} MB{})",
            r.ms,
            r.time_outcome.unwrap_or("-"),
            r.budget_bytes as f64 / 1e6,
            r.max_budget_bytes as f64 / 1e6,
            match r.slice_factor {
                Some(m) if m > 1 => format!(", slices {m} times wider"),
                _ => String::new(),
            }
        );
    }
    println!(
        "times:           select {:.1} ms, SlabPolygons {:.1} ms, DrawList {:.1} ms, upload {:.1} ms, composite {:.1} ms",
        r.select_ms, r.slab_polygons_ms, r.drawlist_ms, r.upload_ms, r.composite_ms
    );
    if let (Some(rmse), Some(psnr), Some(ssim)) = (r.rmse, r.psnr, r.ssim) {
        println!(
            "vs reference:    RMSE {rmse:.4}, PSNR {psnr:.2} dB, SSIM {ssim:.4} (reference {:.0} ms)",
            r.reference_ms.unwrap_or(0.0)
        );
    }
}
