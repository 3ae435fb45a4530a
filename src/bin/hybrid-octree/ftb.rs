//! `ftb`: display the binary octree of an isovalue (or a label) front to
//! back with blocking quadtrees and back to front (Meagher), compare the two
//! depth images, write the FTB depth and shaded images, and print the
//! paper's table II counters and times per view.

use crate::input::InputArgs;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::ftb::{
    back_to_front as btf, front_to_back as ftb, shade, BinaryOctree, Counters, DepthImage, Display, Inside, View,
    ViewCase,
};
use hybrid_octree::render::image::Image;
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::time::Instant;

/// The paper's four views of the skull (table II).
const PAPER_VPNS: [[f64; 3]; 4] = [[1.0, -2.0, 1.0], [-1.0, -2.0, 1.0], [1.0, -1.0, 0.0], [0.0, -1.0, 0.0]];

/// Arguments of `ftb`.
#[derive(Args, Debug)]
pub struct FtbArgs {
    #[command(flatten)]
    input: InputArgs,
    /// Inside the object: value at or above this isovalue.
    #[arg(long, allow_negative_numbers = true, conflicts_with = "label", required_unless_present = "label")]
    isovalue: Option<f64>,
    /// Inside the object: value equal to this label (label volumes).
    #[arg(long, allow_negative_numbers = true)]
    label: Option<f64>,
    /// View plane normal X,Y,Z (towards the viewer); without it the paper's four views.
    #[arg(long, value_parser = vpn, allow_hyphen_values = true)]
    vpn: Option<[f64; 3]>,
    /// Image side in pixels.
    #[arg(long, default_value_t = 512)]
    image_size: usize,
    /// Timed runs of each display; the median is reported.
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Image file prefix: writes PREFIX-depth-<vpn>.png and PREFIX-shaded-<vpn>.png.
    #[arg(long, default_value = "hybrid-octree-ftb")]
    output: String,
    /// Print one JSON object per view on stdout instead of the table.
    #[arg(long)]
    json: bool,
}

fn vpn(s: &str) -> std::result::Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected X,Y,Z, got '{s}'"));
    }
    let mut out = [0.0; 3];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p.parse().map_err(|_| format!("'{p}' is not a number in '{s}'"))?;
    }
    Ok(out)
}

/// One view's row. Key names are a contract with the scripts that read them: keep them.
#[derive(Debug, Serialize)]
struct FtbRow {
    input: String,
    vpn: [f64; 3],
    view_case: ViewCase,
    resolution: u32,
    white_octants: usize,
    black_octants: usize,
    gray_octants: usize,
    octree_build_ms: f64,
    btf_ms: f64,
    ftb_ms: f64,
    /// `100 (btf_ms - ftb_ms) / btf_ms`.
    reduction_pct: f64,
    depth_identical: bool,
    painted_pixels: usize,
    bitmap_bytes: usize,
    btf: Counters,
    ftb: Counters,
    depth_png: String,
    shaded_png: String,
}

/// Builds the octree and displays it along each view.
pub fn run(args: &FtbArgs) -> Result<()> {
    let inside = checked_inside(args)?;
    let vpns: Vec<[f64; 3]> = args.vpn.map_or_else(|| PAPER_VPNS.to_vec(), |v| vec![v]);
    let views = vpns.iter().map(|&v| View::new(v)).collect::<Result<Vec<_>>>()?;
    let volume = args.input.load()?;
    let grid = args.input.grid(&volume)?;
    let started = Instant::now();
    let octree = with_threads(args.input.threads, || BinaryOctree::from_grid(&grid, inside))?;
    let build_ms = started.elapsed().as_secs_f64() * 1e3;
    if !args.json {
        print_header(args, &octree, build_ms);
    }
    for view in &views {
        let row = display_view(args, &octree, view, build_ms)?;
        if args.json {
            let line = serde_json::to_string(&row).map_err(|e| Error::Internal(format!("JSON output: {e}")))?;
            println!("{line}");
        } else {
            print_row(&row);
        }
        if !row.depth_identical {
            return Err(Error::Internal(format!(
                "the FTB and BTF depth images differ for vpn {:?}: please report it",
                view.vpn
            )));
        }
    }
    Ok(())
}

/// The arguments' checks: image size, repeats, and what is inside (an
/// isovalue or a label, exactly one).
fn checked_inside(args: &FtbArgs) -> Result<Inside> {
    if args.image_size < 8 || args.image_size > 8192 {
        return Err(Error::InvalidArgument(format!(
            "--image-size {} is out of range: use 8 to 8192 pixels",
            args.image_size
        )));
    }
    if args.repeats == 0 {
        return Err(Error::InvalidArgument("--repeats must be at least 1".into()));
    }
    match (args.isovalue, args.label) {
        (Some(v), None) => Ok(Inside::AtOrAbove(v)),
        (None, Some(l)) => Ok(Inside::Label(l)),
        _ => Err(Error::InvalidArgument("give --isovalue V or --label L".into())),
    }
}

/// One view: back to front and front to back (the median of the repeats),
/// both pictures written, the row of counters.
fn display_view(args: &FtbArgs, octree: &BinaryOctree, view: &View, build_ms: f64) -> Result<FtbRow> {
    let mut bytes = 0;
    let (b, f) = median_runs(
        args.repeats,
        args.image_size,
        |image| btf::display_into(octree, view, image),
        |image| {
            let (d, by) = ftb::display_into(octree, view, image);
            bytes = by;
            d
        },
    );
    let tag = vpn_tag(view.vpn);
    let depth_png = format!("{}-depth-{tag}.png", args.output);
    let shaded_png = format!("{}-shaded-{tag}.png", args.output);
    depth_picture(&f).to_png(&depth_png)?;
    shade::shade(&f.image, view).to_png(&shaded_png)?;
    let counts = octree.counts();
    Ok(FtbRow {
        input: args.input.describe(),
        vpn: view.vpn,
        view_case: view.case(),
        resolution: octree.n,
        white_octants: counts.white,
        black_octants: counts.black,
        gray_octants: counts.gray,
        octree_build_ms: build_ms,
        btf_ms: b.ms,
        ftb_ms: f.ms,
        reduction_pct: 100.0 * (b.ms - f.ms) / b.ms,
        depth_identical: f.image.identical(&b.image),
        painted_pixels: f.image.painted(),
        bitmap_bytes: bytes,
        btf: b.counters,
        ftb: f.counters,
        depth_png,
        shaded_png,
    })
}

/// The table's title line: the octree, then the column names.
fn print_header(args: &FtbArgs, octree: &BinaryOctree, build_ms: f64) {
    let counts = octree.counts();
    println!(
        "{}: binary octree n = {} ({}^3), {} W, {} B, {} G octants, built in {:.1} ms",
        args.input.describe(),
        octree.n,
        octree.side(),
        counts.white,
        counts.black,
        counts.gray,
        build_ms
    );
    println!(
        "{:<14} {:>5} {:>10} {:>10} {:>9} {:>11} {:>11} {:>9} {:>9} {:>8} {:>11} {:>11} {:>10} {:>6}",
        "vpn",
        "case",
        "BTF ms",
        "FTB ms",
        "reduct %",
        "BTF faces",
        "FTB faces",
        "FTB B vis",
        "FTB W vis",
        "FTB G",
        "BTF pixels",
        "FTB pixels",
        "bitmap B",
        "same"
    );
}

/// One view's line of the table.
fn print_row(row: &FtbRow) {
    println!(
        "{:<14} {:>5} {:>10.2} {:>10.2} {:>9.1} {:>11} {:>11} {:>9} {:>9} {:>8} {:>11} {:>11} {:>10} {:>6}",
        vpn_tag(row.vpn),
        format!("{:?}", row.view_case),
        row.btf_ms,
        row.ftb_ms,
        row.reduction_pct,
        row.btf.faces,
        row.ftb.faces,
        row.ftb.black_visited,
        row.ftb.white_visited,
        row.ftb.gray_visited,
        row.btf.pixels,
        row.ftb.pixels,
        row.bitmap_bytes,
        if row.depth_identical { "yes" } else { "NO" }
    );
}

fn median_runs(
    repeats: usize,
    size: usize,
    mut baseline: impl FnMut(DepthImage) -> Display,
    mut display: impl FnMut(DepthImage) -> Display,
) -> (Display, Display) {
    let (mut base, mut test) = (baseline(DepthImage::new(size)), display(DepthImage::new(size)));
    let (mut base_ms, mut test_ms) = (vec![base.ms], vec![test.ms]);
    for _ in 1..repeats {
        base = baseline(base.image);
        base_ms.push(base.ms);
        test = display(test.image);
        test_ms.push(test.ms);
    }
    let median = |ms: &mut Vec<f64>| {
        ms.sort_by(f64::total_cmp);
        ms[ms.len() / 2]
    };
    base.ms = median(&mut base_ms);
    test.ms = median(&mut test_ms);
    (base, test)
}

/// `1,-2,1` for file names and the table.
fn vpn_tag(v: [f64; 3]) -> String {
    v.iter().map(|c| format!("{c}")).collect::<Vec<_>>().join(",")
}

/// The depth image as grey: near white, far dark, unpainted transparent.
fn depth_picture(d: &Display) -> Image {
    let (lo, range) = d.image.depth_span();
    let mut out = Image::new(d.image.size, d.image.size);
    for (px, &z) in out.rgba.iter_mut().zip(&d.image.depth) {
        if z.is_finite() {
            let g = (1.0 - 0.85 * (z - lo) / range) as f32;
            *px = [g, g, g, 1.0];
        }
    }
    out
}
