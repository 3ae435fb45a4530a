//! The `hybrid-octree` command line tool, run as a process.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

const KEYS: [&str; 16] = [
    "dims",
    "scalar_type",
    "node_count",
    "terminal_count",
    "homogeneous_count",
    "nodes_per_level",
    "levels",
    "leaf_size",
    "root_size",
    "octree_bytes",
    "input_bytes",
    "build_ms",
    "value_min",
    "value_max",
    "tolerance",
    "cut_count",
];

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hybrid-octree")).args(args).output().expect("the CLI starts")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn temp(name: &str) -> PathBuf {
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("hybrid-octree-cli-{}-{n}-{name}", std::process::id()))
}

/// Runs `command --json args...`, which must succeed, and parses its one JSON object.
fn json_of(command: &str, args: &[&str]) -> Value {
    let mut all = vec![command, "--json"];
    all.extend_from_slice(args);
    let out = run(&all);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("one JSON object on stdout")
}

fn build_json(args: &[&str]) -> Value {
    json_of("build", args)
}

/// The command failed with status 2, a one-line `error:` message containing
/// `needle`, and no panic.
fn assert_clean_failure(out: &Output, needle: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(err.contains(needle), "expected '{needle}' in: {err}");
    assert!(!err.contains("panicked") && !err.contains("RUST_BACKTRACE"), "{err}");
}

#[test]
fn info_describes_a_dataset() {
    let out = run(&["info", "--dataset", "sphere", "--size", "12", "--type", "u16"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("12 x 12 x 12 (1728 points)"), "{text}");
    assert!(text.contains("type:        u16") && text.contains("bytes:       3456"), "{text}");
    assert!(text.contains("value range:"), "{text}");
}

#[test]
fn build_prints_a_text_report() {
    let out = run(&["build", "--dataset", "shepp-logan", "--size", "33", "--leaf-size", "8"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("nodes per level:   [1, 8, 64]"), "{text}");
    assert!(text.contains("root size:         32 cells"), "{text}");
}

#[test]
fn build_json_has_every_key_and_consistent_values() {
    let j = build_json(&["--dataset", "shepp-logan", "--size", "41", "--type", "u8", "--leaf-size", "8"]);
    for key in KEYS {
        assert!(j.get(key).is_some(), "missing key {key} in {j}");
    }
    assert_eq!(j["dims"], serde_json::json!([41, 41, 41]));
    assert_eq!(j["scalar_type"], "u8");
    assert_eq!(j["input_bytes"], 41 * 41 * 41);
    assert_eq!(j["leaf_size"], 8);
    assert_eq!(j["root_size"], 64);
    assert_eq!((j["value_min"].as_f64(), j["value_max"].as_f64()), (Some(0.0), Some(255.0)));
    let node_count = j["node_count"].as_u64().unwrap();
    let per_level: u64 = j["nodes_per_level"].as_array().unwrap().iter().map(|v| v.as_u64().unwrap()).sum();
    assert_eq!(per_level, node_count);
    assert_eq!(j["nodes_per_level"].as_array().unwrap().len() as u64, j["levels"].as_u64().unwrap());
    assert!(node_count >= j["terminal_count"].as_u64().unwrap());
    assert!(j["terminal_count"].as_u64().unwrap() >= j["homogeneous_count"].as_u64().unwrap());
    let cut = j["cut_count"].as_u64().unwrap();
    assert!(cut >= 1 && cut <= j["terminal_count"].as_u64().unwrap());
    assert!(j["octree_bytes"].as_u64().unwrap() > 0 && j["build_ms"].as_f64().unwrap() >= 0.0);
    assert_eq!(j["tolerance"].as_f64(), Some(0.01));
}

#[test]
fn thread_count_does_not_change_the_result() {
    let args = ["--dataset", "marschner-lobb", "--size", "49", "--leaf-size", "4"];
    let mut one = build_json(&[&args[..], &["--threads", "1"]].concat());
    let mut two = build_json(&[&args[..], &["--threads", "2"]].concat());
    one.as_object_mut().unwrap().remove("build_ms");
    two.as_object_mut().unwrap().remove("build_ms");
    assert_eq!(one, two);
}

/// `generate --dims X,Y,Z` writes a box of those samples (`build` reads
/// them back); a flat axis, both --size and --dims, or a box larger than
/// the memory is refused before a file is written.
#[test]
fn generate_dims_writes_a_box() {
    let path = temp("box.vti");
    let file = path.to_str().unwrap();
    let out = run(&["generate", "--dataset", "vessels", "--dims", "12,10,6", "--type", "u8", "--output", file]);
    assert!(out.status.success(), "{}", stderr(&out));
    let built = build_json(&["--file", file, "--leaf-size", "4"]);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(built["dims"], serde_json::json!([12, 10, 6]), "{built}");
    assert_eq!(built["scalar_type"], "u8");
    assert_clean_failure(
        &run(&["generate", "--dataset", "vessels", "--dims", "12,1,6", "--output", file]),
        "at least 2 samples per axis",
    );
    assert_clean_failure(
        &run(&["generate", "--dataset", "vessels", "--size", "8", "--dims", "8,8,8", "--output", file]),
        "cannot be used with",
    );
    assert_clean_failure(
        &run(&["generate", "--dataset", "vessels", "--dims", "100000,100000,100000", "--type", "u8", "--output", file]),
        "use a smaller --size (or --dims)",
    );
    assert!(!path.exists(), "a refused run writes no file");
}

#[test]
fn generated_vti_builds_like_the_dataset() {
    let path = temp("phantom.vti");
    let file = path.to_str().unwrap();
    let out = run(&["generate", "--dataset", "shepp-logan", "--size", "37", "--type", "i16", "--output", file]);
    assert!(out.status.success(), "{}", stderr(&out));
    let from_file = build_json(&["--file", file, "--leaf-size", "8"]);
    std::fs::remove_file(&path).unwrap();
    let from_dataset = build_json(&["--dataset", "shepp-logan", "--size", "37", "--type", "i16", "--leaf-size", "8"]);
    for key in [
        "dims",
        "scalar_type",
        "node_count",
        "terminal_count",
        "homogeneous_count",
        "nodes_per_level",
        "cut_count",
        "value_min",
        "value_max",
    ] {
        assert_eq!(from_file[key], from_dataset[key], "{key}");
    }
}

#[test]
fn unknown_dataset_lists_the_names() {
    let out = run(&["build", "--dataset", "teapot", "--size", "9"]);
    assert_clean_failure(&out, "shepp-logan, marschner-lobb, sphere, ramp, constant, vessels");
}

#[test]
fn missing_file_is_reported() {
    let path = temp("nowhere.vti");
    let out = run(&["build", "--file", path.to_str().unwrap()]);
    assert_clean_failure(&out, "does not exist");
}

#[test]
fn raw_size_mismatch_gives_both_sizes() {
    let path = temp("short.raw");
    std::fs::write(&path, vec![0u8; 100]).unwrap();
    let out = run(&["info", "--file", path.to_str().unwrap(), "--dims", "5,5,5", "--type", "u8"]);
    std::fs::remove_file(&path).unwrap();
    assert_clean_failure(&out, "has 100 bytes");
    assert!(stderr(&out).contains("need 125 bytes"));
}

#[test]
fn multi_component_needs_a_component() {
    let path = temp("rgb.raw");
    std::fs::write(&path, vec![7u8; 4 * 4 * 4 * 3]).unwrap();
    let file = path.to_str().unwrap();
    let base = ["build", "--file", file, "--dims", "4,4,4", "--type", "u8", "--components", "3", "--leaf-size", "2"];
    let out = run(&base);
    assert_clean_failure(&out, "--component");
    let ok = run(&[&base[..], &["--component", "1", "--json"]].concat());
    std::fs::remove_file(&path).unwrap();
    assert!(ok.status.success(), "{}", stderr(&ok));
}

/// NaN is no data: `info` and `build` (text and JSON) count it, `surface`
/// reports the open edges along it; an infinity is refused with its position.
#[test]
fn nan_samples_are_counted_and_infinity_is_refused() {
    let path = temp("nan.raw");
    let file = path.to_str().unwrap().to_string();
    let write = |values: &[f32]| {
        std::fs::write(&path, values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>()).unwrap()
    };
    let mut values: Vec<f32> = (0..9 * 9 * 9)
        .map(|i| {
            -(((i % 9) as f32 - 4.0).powi(2) + ((i / 9 % 9) as f32 - 4.0).powi(2) + ((i / 81) as f32 - 4.0).powi(2))
                .sqrt()
        })
        .collect();
    values[13] = f32::NAN;
    for z in 0..9 {
        for y in 0..9 {
            values[7 + 9 * (y + 9 * z)] = f32::NAN;
        }
    }
    write(&values);
    let base = ["--file", &file, "--dims", "9,9,9", "--type", "f32"];
    let info = run(&[&["info"], &base[..]].concat());
    assert!(info.status.success(), "{}", stderr(&info));
    assert!(stdout(&info).contains("NaN samples: 82"), "{}", stdout(&info));
    let text = run(&[&["build", "--leaf-size", "2"], &base[..]].concat());
    assert!(text.status.success(), "{}", stderr(&text));
    assert!(stdout(&text).contains("NaN samples:       82"), "{}", stdout(&text));
    let json = run(&[&["build", "--leaf-size", "2", "--json"], &base[..]].concat());
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(report["nan_samples"], 82);
    let surface = run(&[&["surface", "--isovalue", "-3.5", "--leaf-size", "2", "--json"], &base[..]].concat());
    assert!(surface.status.success(), "{}", stderr(&surface));
    let report: serde_json::Value = serde_json::from_slice(&surface.stdout).unwrap();
    assert!(report["nan_boundary_edges"].as_u64().unwrap() > 0, "{report}");
    assert_eq!(report["nonmanifold_edges"], 0);
    // Every view selection renders the holes, with and without an isosurface to hide behind.
    let png = temp("nan-view.png");
    for view in ["data", "screen", "visibility", "both"] {
        for iso in [&["--isovalue", "-3.5"][..], &[][..]] {
            let args = [&["render", "--view-selection", view, "--width", "16", "--height", "16", "--json"][..], iso];
            let out = run(&[&args.concat(), &base[..], &["--output", png.to_str().unwrap()][..]].concat());
            assert!(out.status.success(), "{view}: {}", stderr(&out));
            let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_eq!(report["view_selection"], view.to_string()[..1].to_uppercase() + &view[1..], "{report}");
        }
    }
    let bad =
        run(&[&["render", "--min-texel-pixels", "-1", "--output", png.to_str().unwrap()][..], &base[..]].concat());
    assert_clean_failure(&bad, "smallest texel -1");
    std::fs::remove_file(&png).ok();
    values[13] = f32::INFINITY;
    write(&values);
    let out = run(&[&["build"], &base[..]].concat());
    std::fs::remove_file(&path).unwrap();
    assert_clean_failure(&out, "1 infinite sample(s)");
    assert!(stderr(&out).contains("i=4, j=1, k=0"), "{}", stderr(&out));
}

#[test]
fn bench_prints_a_row_per_combination_and_the_ratio() {
    let out = run(&[
        "bench",
        "build",
        "--sizes",
        "17,33",
        "--types",
        "u8",
        "--threads",
        "1",
        "--leaf-sizes",
        "8",
        "--kernels",
        "fast,general",
        "--repeats",
        "1",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let rows = text.lines().filter(|l| l.trim_start().starts_with("shepp-logan ") && !l.contains("ns/voxel")).count();
    assert_eq!(rows, 4, "{text}");
    for kernel in ["fast", "general"] {
        let ratio = format!("shepp-logan u8, 1 thread(s), leaf 8, {kernel} kernel: ns/voxel size 33 / size 17 = ");
        assert!(text.contains(&ratio), "{text}");
    }
}

#[test]
fn bench_surface_prints_every_mode_with_ratios_to_interpolated() {
    let out = run(&[
        "bench",
        "surface",
        "--cases",
        "sphere:0.5,marschner-lobb:0.3",
        "--size",
        "33",
        "--threads",
        "1",
        "--repeats",
        "1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).expect("a JSON array");
    let rows = rows.as_array().expect("rows");
    assert_eq!(rows.len(), 6, "two cases, three modes each");
    for case in rows.chunks(3) {
        let (interp, plain, disc) = (&case[0], &case[1], &case[2]);
        assert_eq!(
            (interp["mode"].as_str(), plain["mode"].as_str(), disc["mode"].as_str()),
            (Some("interpolated"), Some("discmc-unmerged"), Some("discmc"))
        );
        assert_eq!(interp["time_vs_interpolated"], 1.0);
        assert_eq!(plain["triangles"], interp["triangles"], "same facets, other vertices");
        assert!(disc["triangles"].as_u64() < plain["triangles"].as_u64(), "{disc}");
        assert!(disc["faces"].as_u64() < disc["triangles"].as_u64(), "{disc}");
        assert!(disc["triangles_vs_uncompressed"].as_f64().unwrap() < 1.0);
    }
    let bad = run(&["bench", "surface", "--cases", "sphere"]);
    assert_clean_failure(&bad, "DATASET:ISOVALUE");
    let bad = run(&["bench", "surface", "--modes", "fast"]);
    assert_clean_failure(&bad, "unknown mode 'fast'");
}

fn surface_json(args: &[&str]) -> Value {
    json_of("surface", args)
}

#[test]
fn surface_reports_both_modes_and_what_compression_saves() {
    let common = ["--dataset", "sphere", "--size", "33", "--isovalue", "0.5", "--distance"];
    let disc = surface_json(&common);
    let plain = surface_json(&[&common[..], &["--no-compress"]].concat());
    let interp = surface_json(&[&common[..], &["--mode", "interpolated"]].concat());
    for r in [&disc, &plain, &interp] {
        for key in [
            "polygons",
            "faces",
            "triangles",
            "uncompressed_triangles",
            "vertices",
            "boundary_edges",
            "extract_ms",
            "compress_ms",
        ] {
            assert!(r.get(key).is_some(), "missing {key} in {r}");
        }
        assert_eq!(r["boundary_edges"], 0, "a closed sphere: {r}");
        assert_eq!(r["nonmanifold_edges"], 0, "{r}");
        let max = r["distance_max"].as_f64().unwrap();
        assert!(max > 0.0 && max <= 0.5, "{r}");
    }
    assert_eq!(disc["mode"], "discretized");
    assert_eq!(interp["mode"], "interpolated");
    // Compression keeps the surface (area, volume) and saves polygons.
    assert_eq!(disc["uncompressed_triangles"], plain["triangles"]);
    assert!(disc["polygons"].as_u64() < plain["polygons"].as_u64());
    // Faces: merged facets, fewer than the triangles that draw them; unmerged, one per facet.
    assert!(disc["faces"].as_u64() < disc["triangles"].as_u64(), "{disc}");
    assert_eq!(plain["faces"], plain["triangles"]);
    assert_eq!(interp["faces"], interp["triangles"]);
    let rel = |a: &Value, b: &Value, k: &str| {
        (a[k].as_f64().unwrap() - b[k].as_f64().unwrap()).abs() / b[k].as_f64().unwrap().abs()
    };
    assert!(rel(&disc, &plain, "area") < 1e-9 && rel(&disc, &plain, "volume") < 1e-9);
    // Same topology: interpolated triangles are the DiscMC facets, moved.
    assert_eq!(interp["triangles"], plain["triangles"]);
}

#[test]
fn surface_writes_a_vtk_file_and_refuses_bad_options() {
    let path = temp("surface.vtk");
    let out = run(&[
        "surface",
        "--dataset",
        "sphere",
        "--size",
        "17",
        "--isovalue",
        "0.5",
        "--output",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("# vtk DataFile") && text.contains("POLYGONS") && text.contains("NORMALS"));
    std::fs::remove_file(&path).ok();
    assert_clean_failure(
        &run(&["surface", "--dataset", "sphere", "--size", "9", "--isovalue", "0.5", "--mode", "smooth"]),
        "unknown surface mode 'smooth'",
    );
    assert_clean_failure(
        &run(&["surface", "--dataset", "sphere", "--size", "9", "--isovalue", "NaN"]),
        "must be a finite number",
    );
    // Outside the data range: an empty surface, not an error.
    let empty = surface_json(&["--dataset", "sphere", "--size", "9", "--isovalue", "7"]);
    assert_eq!(empty["polygons"], 0);
}

#[test]
fn render_writes_a_png_and_reports_the_plan_bytes_and_error() {
    let dir = std::env::temp_dir().join(format!("ho-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (png, reference) = (dir.join("frame.png"), dir.join("reference.png"));
    let r = json_of(
        "render",
        &[
            "--dataset",
            "shepp-logan",
            "--size",
            "33",
            "--width",
            "64",
            "--height",
            "48",
            "--budget-mb",
            "0.05",
            "--isovalue",
            "0.5",
            "--output",
            png.to_str().unwrap(),
            "--reference",
            reference.to_str().unwrap(),
        ],
    );
    for path in [&png, &reference] {
        let bytes = std::fs::read(path).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{path:?} is not a PNG");
    }
    assert_eq!(r["passes"], serde_json::json!(["surface-opaque", "volume"]));
    assert!(r["texture_bytes"].as_u64().unwrap() <= 50_000, "{r}");
    assert!(r["bricks"].as_u64().unwrap() >= 1);
    let ssim = r["ssim"].as_f64().unwrap();
    assert!(ssim > 0.5 && ssim <= 1.0, "{r}");
    assert!(r["rmse"].as_f64().unwrap() < 0.2, "{r}");
    // Bad input: a zero budget and a camera looking from nowhere are clear errors.
    let out =
        run(&["render", "--dataset", "sphere", "--size", "9", "--budget-mb", "0", "--output", png.to_str().unwrap()]);
    assert_clean_failure(&out, "budget");
    let out = run(&["render", "--dataset", "sphere", "--size", "9", "--width", "0", "--output", png.to_str().unwrap()]);
    assert_clean_failure(&out, "image size");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bench_render_compares_octree_and_uniform_at_equal_bytes() {
    let dir = std::env::temp_dir().join(format!("ho-bench-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plot = dir.join("plot.png");
    let out = run(&[
        "bench",
        "render",
        "--dataset",
        "marschner-lobb",
        "--size",
        "33",
        "--width",
        "48",
        "--height",
        "48",
        "--strides",
        "2,4",
        "--tolerances",
        "0.1",
        "--leaf-size",
        "8",
        "--plot",
        plot.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(
        rows.len(),
        17,
        "2 uniform + 2 x 4 octree (data, screen, visibility, both) at their bytes + 2 x 3 VTK smart mapper rows + 1 \
         tolerance row"
    );
    let views: Vec<&str> = rows[1..5].iter().map(|r| r["view"].as_str().unwrap()).collect();
    assert_eq!(views, ["data", "screen", "visibility", "both"]);
    assert!(rows[1..5].iter().all(|r| r["budget_bytes"] == rows[0]["texture_bytes"]));
    for r in rows.iter().filter(|r| !r["method"].as_str().unwrap().starts_with("vtk-smart")) {
        for key in [
            "method",
            "tolerance",
            "budget_bytes",
            "texture_bytes",
            "bricks",
            "select_ms",
            "drawlist_ms",
            "composite_ms",
            "rmse",
            "psnr",
            "ssim",
        ] {
            assert!(r.get(key).is_some(), "missing {key} in {r}");
        }
        assert!(r["texture_bytes"].as_u64() <= r["budget_bytes"].as_u64(), "{r}");
    }
    assert_eq!(rows[0]["method"], "uniform");
    assert_eq!(rows[1]["method"], "octree");
    assert_eq!(rows[1]["budget_bytes"], rows[0]["texture_bytes"], "octree gets the uniform row's bytes");
    assert_eq!(&std::fs::read(&plot).unwrap()[..4], b"\x89PNG");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bench orbit`: one row per view selection, re-selecting only past the
/// view change (every frame at 0 degrees), uploading a share of the budget
/// per frame; bad arguments are clear errors.
#[test]
fn bench_orbit_reselects_past_the_view_change_and_counts_uploads() {
    let orbit = |change: &str| {
        run(&[
            "bench",
            "orbit",
            "--dataset",
            "shepp-logan",
            "--size",
            "33",
            "--width",
            "32",
            "--height",
            "32",
            "--frames",
            "6",
            "--step",
            "3",
            "--view-change",
            change,
            "--leaf-size",
            "4",
            "--json",
        ])
    };
    let out = orbit("5");
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let rows = rows.as_array().unwrap();
    let views: Vec<&str> = rows.iter().map(|r| r["view"].as_str().unwrap()).collect();
    assert_eq!(views, ["data", "screen", "visibility", "both"]);
    for r in rows {
        // 3 degrees a frame past 5 degrees: frames 0, 2 and 4.
        assert_eq!(r["reselections"], 3, "{r}");
        assert!(r["texture_bytes"].as_u64() <= r["budget_bytes"].as_u64(), "{r}");
        let share = r["uploaded_share"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&share), "{r}");
        assert!(r["rmse"].as_f64().unwrap() < 0.2, "{r}");
    }
    // The data-space selection does not depend on the view: nothing to upload.
    assert_eq!(rows[0]["uploaded_bytes_per_frame"], 0.0);
    let out = orbit("0");
    let rows: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert!(rows.as_array().unwrap().iter().all(|r| r["reselections"] == 6));
    assert_clean_failure(&orbit("-1"), "view-change");
    let out = run(&["render", "--dataset", "sphere", "--size", "9", "--view-selection", "pixels", "--output", "x.png"]);
    assert_clean_failure(&out, "data, screen, visibility or both");
}

/// `bench render` on 8-bit data: every texture counts 1 byte a texel; the
/// `vtk-smart` rows upload what VTK's GPU mapper asks for under the uniform
/// row's bytes (`r = 1 - (1 - B / size) / 3` per axis, more than `B`), the
/// `vtk-smart@bytes` rows at most `B`, each with a finite RMSE; the
/// `octree@vtk-smart` rows get the bytes of the `vtk-smart` row as budget.
#[test]
fn bench_render_has_vtk_smart_mapper_rows_at_the_uniform_bytes() {
    let size = 33usize;
    let out = run(&[
        "bench",
        "render",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--type",
        "u8",
        "--width",
        "40",
        "--height",
        "40",
        "--strides",
        "2,4",
        "--tolerances",
        "0.1",
        "--leaf-size",
        "8",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let rows = rows.as_array().unwrap();
    let of = |m: &str| rows.iter().filter(|r| r["method"] == m).collect::<Vec<_>>();
    let uniform = of("uniform");
    assert_eq!(uniform.len(), 2);
    for r in rows.iter().filter(|r| r["method"] != "vtk-smart" && r["method"] != "vtk-smart@bytes") {
        assert_eq!(r["texel_format"], "unorm8", "{r}");
    }
    // Uniform stride s over the 32-cell root: (32 / s + 1)^3 texels of 1 byte.
    assert_eq!(uniform[0]["texture_bytes"], 17 * 17 * 17);
    assert_eq!(uniform[1]["texture_bytes"], 9 * 9 * 9);
    let volume_bytes = (size * size * size) as f64;
    for (method, rows) in [("vtk-smart", of("vtk-smart")), ("vtk-smart@bytes", of("vtk-smart@bytes"))] {
        assert_eq!(rows.len(), 2, "{method}");
        for (r, u) in rows.iter().zip(&uniform) {
            let budget = u["texture_bytes"].as_u64().unwrap();
            assert_eq!(r["budget_bytes"], budget, "{r}");
            assert_eq!(r["stride"], u["stride"], "{r}");
            assert_eq!(r["texel_format"], "unorm8");
            let factor = r["magnification"].as_f64().unwrap();
            let dims: Vec<u64> = r["resampled_dims"].as_array().unwrap().iter().map(|d| d.as_u64().unwrap()).collect();
            let n = ((size - 1) as f64 * factor).floor() as u64 + 1;
            assert_eq!(dims, vec![n; 3], "{r}: vtkImageResample keeps floor((n - 1) r) + 1 samples");
            let bytes = r["texture_bytes"].as_u64().unwrap();
            assert_eq!(bytes, n * n * n, "{r}: 1 byte a sample");
            if method == "vtk-smart" {
                let vtk = 1.0 - (1.0 - budget as f64 / volume_bytes) / 3.0;
                assert!((factor - vtk).abs() < 1e-12, "{r}: VTK's GetReductionRatio is {vtk}");
                assert!(bytes > budget, "{r}: VTK's per-axis ratio uploads more than the limit");
            } else {
                assert!(bytes <= budget && bytes as f64 > 0.5 * budget as f64, "{r}");
            }
            let rmse = r["rmse"].as_f64().unwrap();
            assert!(rmse.is_finite() && rmse > 0.0 && rmse < 0.5, "{r}");
        }
    }
    // The octree under the bytes VTK uploads.
    let octree_at_vtk = of("octree@vtk-smart");
    assert_eq!(octree_at_vtk.len(), 2);
    for (o, v) in octree_at_vtk.iter().zip(of("vtk-smart")) {
        assert_eq!(o["budget_bytes"], v["texture_bytes"], "{o}");
        assert!(o["texture_bytes"].as_u64() <= o["budget_bytes"].as_u64(), "{o}");
        assert_eq!(o["texel_format"], "unorm8");
        assert!(o["rmse"].as_f64().unwrap().is_finite());
    }
    // The text table prints the ratios at each budget.
    let out = run(&[
        "bench",
        "render",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--type",
        "u8",
        "--width",
        "24",
        "--height",
        "24",
        "--strides",
        "4",
        "--tolerances",
        "0.1",
        "--leaf-size",
        "8",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("octree RMSE / vtk-smart RMSE = "), "{text}");
    assert!(text.contains("/ vtk-smart@bytes RMSE = "), "{text}");
    assert!(text.contains("(what VTK uploads under a "), "{text}");
}

#[test]
fn ftb_runs_the_papers_four_views_with_identical_depth() {
    let prefix = temp("ftb-phantom");
    let out = run(&[
        "ftb",
        "--dataset",
        "shepp-logan",
        "--size",
        "48",
        "--isovalue",
        "0.5",
        "--image-size",
        "64",
        "--repeats",
        "1",
        "--output",
        prefix.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Vec<Value> =
        stdout(&out).lines().map(|l| serde_json::from_str(l).expect("one JSON object a line")).collect();
    assert_eq!(rows.len(), 4, "the paper's four VPNs");
    let vpns: Vec<Value> = rows.iter().map(|r| r["vpn"].clone()).collect();
    assert_eq!(vpns[3], serde_json::json!([0.0, -1.0, 0.0]));
    for r in &rows {
        for key in ["vpn", "btf_ms", "ftb_ms", "reduction_pct", "depth_identical", "btf", "ftb", "bitmap_bytes"] {
            assert!(r.get(key).is_some(), "key {key} missing in {r}");
        }
        assert_eq!(r["depth_identical"], true);
        assert!(r["ftb"]["faces"].as_u64().unwrap() < r["btf"]["faces"].as_u64().unwrap());
        assert!(r["bitmap_bytes"].as_u64().unwrap() <= 1 << (2 * r["resolution"].as_u64().unwrap()));
        for png in ["depth_png", "shaded_png"] {
            let path = r[png].as_str().unwrap();
            let bytes = std::fs::read(path).expect("the PNG is written");
            assert_eq!(&bytes[1..4], b"PNG");
        }
    }
}

#[test]
fn ftb_one_view_and_a_label() {
    let out = run(&[
        "ftb",
        "--dataset",
        "sphere",
        "--size",
        "20",
        "--label",
        "1",
        "--vpn",
        "1,-1,1",
        "--image-size",
        "32",
        "--repeats",
        "1",
        "--output",
        temp("ftb-label").to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(stdout(&out).lines().count(), 1);
}

#[test]
fn ftb_refuses_a_zero_vpn_and_a_missing_isovalue() {
    let out = run(&["ftb", "--dataset", "sphere", "--size", "8", "--isovalue", "0.5", "--vpn", "0,0,0"]);
    assert_clean_failure(&out, "(0, 0, 0)");
    let out = run(&["ftb", "--dataset", "sphere", "--size", "8"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("--isovalue") || stderr(&out).contains("--label"), "{}", stderr(&out));
}

/// `points` on a 33^3 volume at threshold 0.1, written to `file` and drawn
/// at 48x48 as `prefix-*.png`, with `options` (dataset, factor, ...); its JSON.
fn points_json(options: &[&str], file: &std::path::Path, prefix: &str) -> Value {
    let common = ["--size", "33", "--threshold", "0.1", "--width", "48", "--height", "48", "--render", prefix];
    let mut args: Vec<&str> = options.to_vec();
    args.extend(common);
    args.extend(["--output", file.to_str().unwrap()]);
    json_of("points", &args)
}

#[test]
fn points_writes_a_file_that_reads_back_and_draws_the_difference_pictures() {
    let file = temp("points.hop");
    let prefix = temp("points");
    let prefix = prefix.to_str().unwrap();
    let r = points_json(&["--dataset", "shepp-logan", "--factor", "2"], &file, prefix);
    let points = r["points"].as_u64().unwrap();
    assert!(points > 0, "{r}");
    // 6 bytes a point on a 33^3 grid, plus the 72-byte header in the file.
    assert_eq!(r["point_bytes"].as_u64().unwrap(), 6 * points);
    assert_eq!(r["file_bytes"].as_u64().unwrap(), 6 * points + 72);
    assert_eq!(r["total_bytes"].as_u64().unwrap(), r["texture_bytes"].as_u64().unwrap() + 6 * points);
    // Both pictures are measured (what points buy is tested in tests/hybrid_points.rs).
    assert!(r["hybrid_rmse"].as_f64().unwrap() > 0.0 && r["lowres_rmse"].as_f64().unwrap() > 0.0, "{r}");
    assert_eq!(r["passes"], serde_json::json!(["volume", "points"]));
    for name in ["lowres", "hybrid", "reference", "lowres-diff", "hybrid-diff"] {
        let png = format!("{prefix}-{name}.png");
        assert!(std::fs::metadata(&png).map(|m| m.len() > 100).unwrap_or(false), "{png}");
        std::fs::remove_file(png).ok();
    }
    assert!(r["subsampled_rmse"].is_null(), "plain subsampling is the low resolution itself: {r}");
    // The optimized low resolution: plain subsampling alone is drawn too, for comparison.
    let r = points_json(&["--dataset", "vessels", "--factor", "4", "--max-overestimate", "0.1"], &file, prefix);
    assert!(r["subsampled_rmse"].as_f64().unwrap() > 0.0, "{r}");
    for name in ["lowres", "hybrid", "reference", "lowres-diff", "hybrid-diff", "subsampled", "subsampled-diff"] {
        let png = format!("{prefix}-{name}.png");
        assert!(std::fs::metadata(&png).map(|m| m.len() > 100).unwrap_or(false), "{png}");
        std::fs::remove_file(png).ok();
    }
    std::fs::remove_file(&file).ok();
    // Bad options are clear errors.
    let out =
        run(&["points", "--dataset", "sphere", "--size", "17", "--factor", "3", "--budget", "5", "--output", "x.hop"]);
    assert_clean_failure(&out, "factor 3");
    let out = run(&["points", "--dataset", "sphere", "--size", "17", "--output", "x.hop"]);
    assert_clean_failure(&out, "--threshold");
}

/// `bench effects` on a small phantom at the full budget: a row per effect,
/// the plain frame first with ratio 1, every ratio finite, every picture
/// close to the reference caster drawing the same effect, the plan naming
/// each effect (and the plain frame none), shading's gradient border in the
/// bytes, the peak RSS and the plot.
#[test]
fn bench_effects_measures_each_effect_against_the_plain_frame() {
    let dir = std::env::temp_dir().join(format!("ho-bench-effects-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plot = dir.join("effects.png");
    let out = run(&[
        "bench",
        "effects",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--leaf-size",
        "8",
        "--width",
        "40",
        "--height",
        "40",
        "--frames",
        "1",
        "--plot",
        plot.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(report["full_budget"], true, "{report}");
    let rows = report["rows"].as_array().unwrap();
    let row = |name: &str| rows.iter().find(|r| r["effect"] == name).unwrap_or_else(|| panic!("no row {name}"));
    let passes = |name: &str| -> Vec<String> {
        row(name)["passes"].as_array().unwrap().iter().map(|p| p.as_str().unwrap().to_string()).collect()
    };
    let names = [
        "plain",
        "shade",
        "shade+specular",
        "mip",
        "minip",
        "average",
        "additive",
        "translucent-iso",
        "shade+translucent-iso",
        "gradient-opacity",
        "shade+gradient-opacity",
        "isosurface",
        "shade+isosurface",
        "cropping",
        "clipping",
        "scattering",
        "scattering-full-reach",
    ];
    assert_eq!(rows.len(), names.len(), "{report}");
    assert_eq!(rows[0]["effect"], "plain");
    assert_eq!(rows[0]["frame_ratio"].as_f64(), Some(1.0));
    for r in rows {
        for key in ["frame_ratio", "composite_ratio"] {
            let v = r[key].as_f64().unwrap();
            assert!(v.is_finite() && v > 0.0, "{key} of {r}");
        }
        // At the full budget only the samples' places differ from the
        // reference (the average's silhouette rays: up to 0.05, see
        // render::blend_tests).
        let rmse = r["rmse"].as_f64().unwrap();
        assert!(rmse < 0.05, "RMSE {rmse} of {r}");
        assert_eq!(r["estimated_error"].as_f64(), Some(0.0), "full budget: {r}");
    }
    assert_eq!(passes("plain"), ["volume"]);
    assert_eq!(passes("shade"), ["volume-shaded"]);
    assert_eq!(passes("shade+specular"), ["volume-shaded"]);
    for mode in ["mip", "minip", "average", "additive"] {
        assert_eq!(passes(mode), [format!("volume-{mode}")]);
    }
    assert_eq!(passes("translucent-iso"), ["surface-in-slabs", "volume"]);
    assert_eq!(passes("shade+translucent-iso"), ["surface-in-slabs", "volume-shaded"]);
    let effects = |name: &str| row(name)["effects"].clone();
    assert_eq!(effects("plain"), serde_json::json!([]), "{report}");
    assert_eq!(effects("shade"), serde_json::json!(["shading"]), "{report}");
    assert_eq!(
        (passes("gradient-opacity"), effects("gradient-opacity")),
        (vec!["volume".to_string()], serde_json::json!(["gradient-opacity"]))
    );
    assert_eq!(effects("shade+gradient-opacity"), serde_json::json!(["gradient-opacity", "shading"]));
    assert_eq!(passes("isosurface"), ["volume-isosurface"]);
    assert_eq!(passes("shade+isosurface"), ["volume-isosurface-shaded"]);
    assert_eq!(
        (passes("cropping"), effects("cropping")),
        (vec!["volume".to_string()], serde_json::json!(["cropping"]))
    );
    assert_eq!(
        (passes("clipping"), effects("clipping")),
        (vec!["volume".to_string()], serde_json::json!(["clipping"]))
    );
    for name in ["scattering", "scattering-full-reach"] {
        assert_eq!(
            (passes(name), effects(name)),
            (vec!["volume-shaded".to_string()], serde_json::json!(["shading", "volume-scattering"])),
            "{report}"
        );
    }
    let bytes = |name: &str| row(name)["texture_bytes"].as_u64().unwrap();
    for cut in ["cropping", "clipping"] {
        assert!(bytes(cut) < bytes("plain"), "{cut}: the removed bricks get no texture: {report}");
    }
    assert!(bytes("shade") > bytes("plain"), "the gradient border costs bytes: {report}");
    assert_eq!(bytes("mip"), bytes("plain"), "{report}");
    assert!(report["peak_rss_bytes"].as_u64().is_some_and(|b| b > 1 << 20), "{report}");
    assert_eq!(&std::fs::read(&plot).unwrap()[..4], b"\x89PNG");
    // A subset by name (plain always first), and an unknown name refused.
    let out = run(&[
        "bench",
        "effects",
        "--dataset",
        "sphere",
        "--size",
        "9",
        "--width",
        "8",
        "--height",
        "8",
        "--frames",
        "1",
        "--effects",
        "mip",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let effects: Vec<&str> = report["rows"].as_array().unwrap().iter().map(|r| r["effect"].as_str().unwrap()).collect();
    assert_eq!(effects, ["plain", "mip"]);
    let bad = run(&["bench", "effects", "--dataset", "sphere", "--size", "9", "--effects", "glow"]);
    assert_clean_failure(&bad, "unknown effect 'glow'");
    let bad = run(&["bench", "effects", "--dataset", "sphere", "--size", "9", "--shade"]);
    assert_clean_failure(&bad, "--shade");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bench_render_points_rows_carry_bytes_and_error() {
    let out = run(&[
        "bench",
        "render",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--width",
        "32",
        "--height",
        "32",
        "--strides",
        "2,4",
        "--tolerances",
        "0.1",
        "--leaf-size",
        "8",
        "--points",
        "--point-thresholds",
        "0.1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let points: Vec<&Value> = rows.as_array().unwrap().iter().filter(|r| r["method"] == "points").collect();
    assert_eq!(points.len(), 3, "one threshold row per stride and one equal-bytes row");
    for r in points {
        for key in ["texture_bytes", "point_bytes", "total_bytes", "points", "ms", "rmse", "ssim"] {
            assert!(r.get(key).is_some(), "missing {key} in {r}");
        }
        let t = r["texture_bytes"].as_u64().unwrap() + r["point_bytes"].as_u64().unwrap();
        assert_eq!(r["total_bytes"].as_u64().unwrap(), t);
    }
}

/// Runs the CLI with `HYBRID_OCTREE_MAX_MEMORY` set to `cap`.
fn run_capped(cap: &str, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hybrid-octree"))
        .args(args)
        .env("HYBRID_OCTREE_MAX_MEMORY", cap)
        .output()
        .expect("the CLI starts")
}

#[test]
fn raw_files_are_checked_against_memory_before_reading() {
    // A sparse 256 MiB file: its layout is right, its size (read straight into the volume) too much for a 64 MiB cap.
    let path = temp("big.raw");
    std::fs::File::create(&path).unwrap().set_len(256 << 20).unwrap();
    let file = path.to_str().unwrap();
    let out = run_capped("64M", &["info", "--file", file, "--dims", "1024,512,512", "--type", "u8"]);
    std::fs::remove_file(&path).unwrap();
    assert_clean_failure(&out, "needs 256.0 MiB of memory");
    assert!(stderr(&out).contains("1024x512x512 u8") && stderr(&out).contains("HYBRID_OCTREE_MAX_MEMORY"));
}

#[test]
fn a_named_pipe_is_refused_not_waited_on() {
    let fifo = temp("pipe.vti");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let out = run(&["info", "--file", fifo.to_str().unwrap()]);
    std::fs::remove_file(&fifo).unwrap();
    assert_clean_failure(&out, "named pipe (FIFO), not a regular file");
}

#[test]
fn writers_refuse_extensions_they_do_not_write_before_working() {
    let dir = temp("ext");
    std::fs::create_dir_all(&dir).unwrap();
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let input = ["--dataset", "sphere", "--size", "9"];
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["generate".into(), "--output".into(), at("x.vtk")], ".vti"),
        (vec!["generate".into(), "--output".into(), at("x.nii")], ".vti"),
        (vec!["render".into(), "--output".into(), at("x.jpg")], ".png"),
        (vec!["render".into(), "--output".into(), at("x.png"), "--reference".into(), at("r.bmp")], ".png"),
        (vec!["surface".into(), "--isovalue".into(), "0.5".into(), "--output".into(), at("s.obj")], ".vtk"),
        (vec!["points".into(), "--threshold".into(), "0.1".into(), "--output".into(), at("p.png")], ".hop"),
        (vec!["bench".into(), "render".into(), "--plot".into(), at("plot.svg")], ".png"),
    ];
    for (args, supported) in cases {
        let mut all: Vec<&str> = args.iter().map(String::as_str).collect();
        if all[0] != "generate" {
            all.extend(input);
        } else {
            all.extend(["--dataset", "sphere", "--size", "9"]);
        }
        let out = run(&all);
        assert_clean_failure(&out, supported);
        assert!(stderr(&out).contains("writes"), "{all:?}: {}", stderr(&out));
    }
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(left.is_empty(), "files written: {left:?}");
}

#[test]
fn terminal_escapes_in_a_file_name_are_not_printed() {
    let out = run(&["info", "--file", "no-such-\x1b[2J.vti"]);
    assert_clean_failure(&out, "no-such-\\u{1b}[2J.vti");
    assert!(!stderr(&out).contains('\x1b'));
}

/// Sizes are checked from the arguments before anything is generated: a
/// size whose bytes overflow, or need more memory than there is, is refused
/// with the bytes it needs, in every command taking `--size` or `--sizes`.
#[test]
fn huge_sizes_are_refused_up_front_with_the_bytes_needed() {
    for size in ["4294967296", "18446744073709551615"] {
        assert_clean_failure(&run(&["info", "--dataset", "sphere", "--size", size]), "use a smaller --size");
        assert_clean_failure(&run(&["build", "--dataset", "sphere", "--size", size]), "use a smaller --size");
    }
    let cap = [("HYBRID_OCTREE_MAX_MEMORY", "64M")];
    let capped = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_hybrid-octree")).args(args).envs(cap).output().expect("the CLI starts")
    };
    // 100000^3 f32: 4e15 bytes (the generator writes them in place).
    let out = capped(&["render", "--dataset", "sphere", "--size", "100000", "--output", "never.png"]);
    assert_clean_failure(&out, "needs 3.6 PiB");
    // 300^3 f64 = 216 MB is above the 64 MiB cap; 3000^3 far above.
    let out = capped(&["generate", "--dataset", "sphere", "--size", "300", "--type", "f64", "--output", "never.vti"]);
    assert_clean_failure(&out, "needs 206.0 MiB");
    assert_clean_failure(&capped(&["generate", "--dataset", "ramp", "--size", "3000", "--output", "x.vti"]), "GiB");
    assert_clean_failure(&capped(&["bench", "build", "--sizes", "16,100000", "--repeats", "1"]), "PiB");
    assert_clean_failure(&run(&["bench", "build", "--sizes", "9", "--kernels", "fastest"]), "use fast or general");
    assert_clean_failure(&capped(&["bench", "surface", "--size", "100000", "--repeats", "1"]), "PiB");
    assert!(!std::path::Path::new("never.vti").exists() && !std::path::Path::new("never.png").exists());
}

/// Thread counts beyond the cap are refused before a pool is started, in
/// single values and in bench lists.
#[test]
fn absurd_thread_counts_are_refused() {
    let huge = "100000000";
    assert_clean_failure(&run(&["build", "--dataset", "sphere", "--size", "9", "--threads", huge]), "at most 1024");
    assert_clean_failure(
        &run(&["generate", "--dataset", "sphere", "--size", "9", "--threads", huge, "--output", "t.vti"]),
        "at most 1024",
    );
    assert!(!std::path::Path::new("t.vti").exists(), "a refused generate writes no file");
    assert_clean_failure(&run(&["bench", "build", "--sizes", "9", "--threads", &format!("1,{huge}")]), "at most 1024");
    assert_clean_failure(&run(&["bench", "surface", "--size", "9", "--threads", &format!("2,{huge}")]), "at most 1024");
    assert_clean_failure(&run(&["build", "--dataset", "sphere", "--size", "9", "--threads", "0"]), "at least 1");
    assert!(run(&["build", "--dataset", "sphere", "--size", "9", "--threads", "1024"]).status.success());
}

/// Negative numbers are values, not flags, in every subcommand: isovalues
/// (CT Hounsfield units), ROI centres, camera angles; values out of range
/// are refused by the command with its reason, not by the parser.
#[test]
fn negative_numbers_are_accepted_as_values_everywhere() {
    let png = temp("neg.png");
    let png = png.to_str().unwrap();
    let hu = ["--dataset", "shepp-logan", "--size", "17", "--type", "i16"];
    let view = ["--width", "24", "--height", "24", "--azimuth", "-30", "--elevation", "-15", "--roi", "-2,-2,-2,40"];
    let mut render = vec!["render"];
    render.extend(hu);
    render.extend(view);
    render.extend(["--isovalue", "-500", "--output", png]);
    let out = run(&render);
    assert!(out.status.success(), "{}", stderr(&out));
    let mut surface = vec!["surface"];
    surface.extend(hu);
    surface.extend(["--isovalue", "-500"]);
    assert!(run(&surface).status.success());
    let ftb_prefix = png.replace(".png", "-ftb");
    let mut ftb = vec!["ftb"];
    ftb.extend(hu);
    ftb.extend(["--isovalue", "-500", "--output", &ftb_prefix]);
    assert!(run(&ftb).status.success());
    let mut bench = vec!["bench", "render"];
    bench.extend(hu);
    bench.extend(view);
    bench.extend(["--isovalue", "-500", "--strides", "4", "--tolerances", "0.1"]);
    let out = run(&bench);
    assert!(out.status.success(), "{}", stderr(&out));
    // Refused by the commands' own checks (status 2, their reason), not as unknown arguments.
    let base = ["--dataset", "sphere", "--size", "9"];
    let hop = png.replace(".png", ".hop");
    let refused: [(&[&str], &str); 5] = [
        (&["build", "--tolerance", "-0.1"], "must be a finite number >= 0"),
        (&["render", "--tolerance", "-1", "--output", png], "must be a number >= 0"),
        (&["render", "--budget-mb", "-1", "--output", png], "positive number of megabytes"),
        (&["render", "--surface-opacity", "-0.5", "--output", png], "between 0 and 1"),
        (&["points", "--threshold", "-0.1", "--output", &hop], "in [0, 1]"),
    ];
    for (args, reason) in refused {
        let mut all = vec![args[0]];
        all.extend(base);
        all.extend(&args[1..]);
        assert_clean_failure(&run(&all), reason);
    }
    let _ = std::fs::remove_file(png);
}

/// `render --blend` names its pass and carries the mode in the JSON plan;
/// an unknown mode is a clean error naming the five.
#[test]
fn render_blend_modes_name_their_pass() {
    let png = temp("blend.png");
    for (mode, pass) in [
        ("composite", "volume"),
        ("mip", "volume-mip"),
        ("minip", "volume-minip"),
        ("average", "volume-average"),
        ("additive", "volume-additive"),
    ] {
        let args = ["--dataset", "vessels", "--size", "17", "--width", "16", "--height", "16", "--blend", mode];
        let json = json_of("render", &[&args[..], &["--output", png.to_str().unwrap()]].concat());
        assert_eq!(json["passes"], serde_json::json!([pass]), "{json}");
        assert_eq!(json["blend"]["mode"], mode, "{json}");
    }
    let out =
        run(&["render", "--dataset", "sphere", "--size", "9", "--blend", "max", "--output", png.to_str().unwrap()]);
    assert_clean_failure(&out, "give one of composite, mip, minip, average, additive, isosurface, slice");
    let _ = std::fs::remove_file(png);
}

/// `render --crop` and `--clip` say what acts in the JSON plan (`effects`,
/// `region`), leave removed bricks out, and match the reference caster
/// under the same region; a box or plane removing nothing is dropped; bad
/// values are clean errors naming the problem.
#[test]
fn render_crop_and_clip_report_their_effects() {
    let png = temp("crop.png");
    let reference = temp("crop-reference.png");
    let base = ["--dataset", "sphere", "--size", "33", "--width", "48", "--height", "48", "--leaf-size", "8"];
    let render = |extra: &[&str]| {
        let args = [&base[..], extra, &["--output", png.to_str().unwrap(), "--reference", reference.to_str().unwrap()]];
        json_of("render", &args.concat())
    };
    let plain = render(&[]);
    assert_eq!(plain["effects"], serde_json::json!([]), "{plain}");
    assert!(plain["region"].is_null(), "{plain}");
    let cut = render(&["--crop", "0,20,-5,40,0,32", "--clip", "16,16,16,0,-1,-1", "--clip", "-1,0,0,1,0,0"]);
    assert_eq!(cut["effects"], serde_json::json!(["cropping", "clipping"]), "{cut}");
    assert_eq!(cut["region"]["cropping"]["planes"], serde_json::json!([0.0, 20.0, -5.0, 40.0, 0.0, 32.0]), "{cut}");
    // The plane with the whole volume on its kept side is dropped.
    assert_eq!(cut["region"]["clipping_planes"].as_array().unwrap().len(), 1, "{cut}");
    assert!(cut["skipped_bricks"].as_u64() > plain["skipped_bricks"].as_u64(), "{cut}");
    assert!(cut["texture_bytes"].as_u64() < plain["texture_bytes"].as_u64(), "{cut}");
    assert!(cut["rmse"].as_f64().unwrap() < 0.02, "{cut}");
    let whole = render(&["--crop", "-1,40,0,32,0,32", "--clip", "0,0,0,1,1,1"]);
    assert_eq!(whole["effects"], serde_json::json!([]), "{whole}");
    assert_eq!(whole["texture_bytes"], plain["texture_bytes"], "{whole}");
    for (flag, value, reason) in [
        ("--crop", "0,1,0,1,0", "has 5 numbers"),
        ("--crop", "0,NaN,0,1,0,1", "finite"),
        ("--crop", "0,1,5,1,0,1", "y min 5 is above its max 1"),
        ("--clip", "0,0,0,0,0,0", "normal of length > 0"),
        ("--clip", "0,0,0,1,0", "has 5 numbers"),
    ] {
        let out = run(&[&["render"][..], &base[..], &[flag, value, "--output", png.to_str().unwrap()]].concat());
        assert_clean_failure(&out, reason);
    }
    let _ = std::fs::remove_file(png);
    let _ = std::fs::remove_file(reference);
}

/// `render --gradient-opacity` reports its effect in the JSON plan (one that
/// varies: `gradient-opacity`, with `--shade` before `shading`; a constant
/// other than 1: `opacity-scale`; 1 everywhere: none, the picture of no
/// gradient opacity), stays within the reference, and bad points are clean
/// errors naming the problem.
#[test]
fn render_gradient_opacity_names_its_effect() {
    let png = temp("gradient-opacity.png");
    let reference = temp("gradient-opacity-reference.png");
    let (out, truth) = (png.to_str().unwrap(), reference.to_str().unwrap());
    let base = ["--dataset", "sphere", "--size", "17", "--width", "24", "--height", "24", "--output", out];
    let json = |extra: &[&str]| json_of("render", &[&base[..], extra].concat());
    let plain = json(&[]);
    assert_eq!(plain["effects"], serde_json::json!([]), "{plain}");
    let plain_png = std::fs::read(&png).unwrap();
    let one = json(&["--gradient-opacity", "0,1,5,1"]);
    assert_eq!(one["effects"], serde_json::json!([]), "{one}");
    assert_eq!(std::fs::read(&png).unwrap(), plain_png, "1 everywhere draws the plain picture");
    let half = json(&["--gradient-opacity", "0,0.5"]);
    assert_eq!(half["effects"], serde_json::json!(["opacity-scale"]), "{half}");
    let varying = json(&["--gradient-opacity", "0,0,0.05,1", "--shade", "--reference", truth]);
    assert_eq!(varying["effects"], serde_json::json!(["gradient-opacity", "shading"]), "{varying}");
    assert_eq!(varying["passes"], serde_json::json!(["volume-shaded"]), "{varying}");
    assert!(varying["rmse"].as_f64().unwrap() < 0.05, "{varying}");
    for (points, reason) in [
        ("0,1,2", "give pairs G,A"),
        ("0,x", "'x' is not a number"),
        ("0,1.5", "[0, 1]"),
        ("1,0.5,0,0.5", "increasing magnitude order"),
    ] {
        assert_clean_failure(&run(&[&["render"][..], &base[..], &["--gradient-opacity", points]].concat()), reason);
    }
    let _ = std::fs::remove_file(png);
    let _ = std::fs::remove_file(reference);
}

/// `render --transfer-2d FILE` (JSON): the plan names `transfer-2d`, the
/// picture differs from the 1D ramp's and stays within RMSE 0.05 of the
/// reference with the same table (both read it: the check can fail), and
/// hostile files are refused with the reason before anything is drawn.
#[test]
fn render_transfer_2d_reads_a_json_table() {
    let png = temp("transfer-2d.png");
    let reference = temp("transfer-2d-reference.png");
    let table = temp("transfer-2d.json");
    let (out, truth) = (png.to_str().unwrap(), reference.to_str().unwrap());
    let base = ["--dataset", "sphere", "--size", "17", "--width", "24", "--height", "24", "--output", out];
    let json = |extra: &[&str]| json_of("render", &[&base[..], extra].concat());
    let plain = json(&[]);
    assert_eq!(plain["effects"], serde_json::json!([]), "{plain}");
    let plain_png = std::fs::read(&png).unwrap();
    // 8 x 4: opacity rising with the value (x) and the gradient (y).
    let rgba: Vec<String> = (0..4)
        .flat_map(|j| (0..8).map(move |i| (i, j)))
        .map(|(i, j)| {
            format!("{},{},0.5,{}", i as f64 / 7.0, j as f64 / 3.0, 0.04 * i as f64 * (j as f64 + 1.0) / 28.0)
        })
        .collect();
    std::fs::write(&table, format!("{{\"width\": 8, \"height\": 4, \"rgba\": [{}]}}", rgba.join(","))).unwrap();
    let path = table.to_str().unwrap();
    let two_d = json(&["--transfer-2d", path, "--shade", "--reference", truth]);
    assert_eq!(two_d["effects"], serde_json::json!(["transfer-2d", "shading"]), "{two_d}");
    assert_eq!(two_d["passes"], serde_json::json!(["volume-shaded"]), "{two_d}");
    assert!(two_d["rmse"].as_f64().unwrap() < 0.05, "{two_d}");
    assert_ne!(std::fs::read(&png).unwrap(), plain_png, "the table classifies");
    let mip = json(&["--transfer-2d", path, "--blend", "mip"]);
    assert_eq!(mip["effects"], serde_json::json!([]), "Composite only: {mip}");
    let bad = temp("transfer-2d-bad.json");
    for (content, reason) in [
        ("{\"width\": 2, \"height\": 1, \"rgba\": [0,0,0,0]}", "4 rgba numbers for a 2 x 1 table"),
        ("{\"width\": 0, \"height\": 1, \"rgba\": []}", "1 to 4096"),
        ("{\"width\": 100000, \"height\": 100000, \"rgba\": []}", "1 to 4096"),
        ("{\"width\": 1, \"height\": 1, \"rgba\": [0,0,0,2]}", "[0, 1]"),
        ("{\"width\": 1, \"height\": 1, \"rgba\": [0,0,0,1], \"gradient_max\": -1}", "gradient magnitude"),
        ("{\"width\": 1, \"height\": 1, \"rgba\": [0,0,0,1], \"scalar_range\": [1, 0]}", "scalar range"),
        ("{\"width\": 1, \"height\": 1}", "not a 2D transfer function"),
        ("[1, 2, 3]", "not a 2D transfer function"),
        ("{\"width\": 1, \"height\": 1, \"rgba\": [0,0,0,1], \"colour\": 3}", "unknown field"),
    ] {
        std::fs::write(&bad, content).unwrap();
        assert_clean_failure(
            &run(&[&["render"][..], &base[..], &["--transfer-2d", bad.to_str().unwrap()]].concat()),
            reason,
        );
    }
    let missing = temp("transfer-2d-missing.json");
    assert_clean_failure(
        &run(&[&["render"][..], &base[..], &["--transfer-2d", missing.to_str().unwrap()]].concat()),
        "cannot read it",
    );
    for f in [png, reference, table, bad] {
        let _ = std::fs::remove_file(f);
    }
}

/// `render --blend slice` draws the plane of `--slice-origin`,
/// `--slice-normal`: its pass in the JSON plan, the plane in the blend,
/// within the reference caster on the same plane (RMSE below 0.01 at the
/// full budget: the bricks give the plane's points the reference's values),
/// less texture than Composite (only the nodes the plane cuts); bad values
/// are clean errors naming the problem.
#[test]
fn render_slice_draws_the_plane() {
    let png = temp("slice.png");
    let reference = temp("slice-reference.png");
    let (out, truth) = (png.to_str().unwrap(), reference.to_str().unwrap());
    let base = ["--dataset", "shepp-logan", "--size", "33", "--width", "32", "--height", "32", "--leaf-size", "4"];
    let json = |extra: &[&str]| json_of("render", &[&base[..], extra, &["--output", out]].concat());
    let plain = json(&[]);
    let slice = json(&[
        "--blend",
        "slice",
        "--slice-origin",
        "16,15,17",
        "--slice-normal",
        "0.4,-0.5,0.75",
        "--reference",
        truth,
    ]);
    assert_eq!(slice["passes"], serde_json::json!(["volume-slice"]), "{slice}");
    assert_eq!(slice["blend"]["slice"]["normal"], serde_json::json!([0.4, -0.5, 0.75]), "{slice}");
    assert!(slice["rmse"].as_f64().unwrap() < 0.01, "{slice}");
    assert!(slice["texture_bytes"].as_u64() < plain["texture_bytes"].as_u64(), "{slice} vs {plain}");
    let shaded = json(&["--blend", "slice", "--slice-normal", "0,0,1", "--shade"]);
    assert_eq!(shaded["passes"], serde_json::json!(["volume-slice-shaded"]), "{shaded}");
    assert_eq!(shaded["blend"]["slice"]["origin"], serde_json::json!([16.0, 16.0, 16.0]), "the volume's centre");
    for (extra, reason) in [
        (&["--blend", "slice"][..], "--slice-normal"),
        (&["--blend", "slice", "--slice-normal", "0,0,0"][..], "non-zero"),
        (&["--blend", "slice", "--slice-normal", "0,nan,1"][..], "finite"),
        (&["--blend", "slice", "--slice-normal", "0,1"][..], "has 2 numbers"),
        (&["--blend", "slice", "--slice-normal", "1,0,0", "--slice-origin", "a,b,c"][..], "not X,Y,Z"),
        (&["--slice-normal", "1,0,0"][..], "are for --blend slice"),
    ] {
        assert_clean_failure(&run(&[&["render"][..], &base[..], extra, &["--output", out]].concat()), reason);
    }
    let _ = std::fs::remove_file(png);
    let _ = std::fs::remove_file(reference);
}

/// `bench scale` writes each size and type to a file, reads it back and
/// reports every step with its time per voxel and peak memory; its files
/// are removed afterwards.
#[test]
fn bench_scale_reports_every_step_of_every_size() {
    let dir = temp("scale");
    std::fs::create_dir_all(&dir).unwrap();
    let out = run(&[
        "bench",
        "scale",
        "--sizes",
        "9,12",
        "--type",
        "u8,u16",
        "--width",
        "24",
        "--height",
        "24",
        "--dir",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).expect("a JSON array");
    let rows = rows.as_array().unwrap();
    let steps = ["generate", "read", "build", "select", "first frame"];
    assert_eq!(rows.len(), 2 * 2 * steps.len());
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r["step"], steps[i % steps.len()], "{r}");
        let size = [9, 12][i / (2 * steps.len())];
        let ty = ["u8", "u16"][i / steps.len() % 2];
        assert_eq!((r["size"].as_u64(), r["scalar_type"].as_str()), (Some(size), Some(ty)), "{r}");
        assert_eq!(r["volume_bytes"].as_u64(), Some(size * size * size * if ty == "u8" { 1 } else { 2 }));
        let (ms, ns) = (r["ms"].as_f64().unwrap(), r["ns_per_voxel"].as_f64().unwrap());
        assert!(ms >= 0.0 && (ns - ms * 1e6 / (size * size * size) as f64).abs() <= 1e-9 * ns.max(1.0), "{r}");
        if cfg!(target_os = "linux") {
            let peak = r["peak_rss_bytes"].as_u64().unwrap();
            assert!(peak > 1 << 20, "{r}");
            let ratio = r["peak_rss_ratio"].as_f64().unwrap();
            assert!((ratio - peak as f64 / r["volume_bytes"].as_f64().unwrap()).abs() < 1e-9 * ratio, "{r}");
        }
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "the benchmark's files are removed");
    std::fs::remove_dir(&dir).unwrap();
    assert_clean_failure(&run(&["bench", "scale", "--sizes", "9", "--type", "u12"]), "u12");
}

/// `bench select`: per budget, the fresh selection, a `Selector`'s first,
/// its re-selections after budgets of +-10 % and after the region of
/// interest moved, with their budgets and bricks; a bad budget is a clean
/// error.
#[test]
fn bench_select_reports_fresh_and_kept_selections() {
    let out = run(&[
        "bench",
        "select",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--budgets-mb",
        "0.02,0.1",
        "--repeats",
        "1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows: Value = serde_json::from_str(&stdout(&out)).expect("a JSON array");
    let rows = rows.as_array().unwrap();
    let operations = [
        "select",
        "selector first",
        "reselect budget +10%",
        "reselect budget -10%",
        "select roi",
        "reselect roi moved",
    ];
    assert_eq!(rows.len(), 2 * operations.len());
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r["operation"], operations[i % operations.len()], "{r}");
        let budget = [20_000.0, 100_000.0][i / operations.len()];
        let factor = match i % operations.len() {
            2 => 1.1,
            3 => 0.9,
            _ => 1.0,
        };
        assert_eq!(r["budget_bytes"].as_u64(), Some((budget * factor) as u64), "{r}");
        assert!(r["bricks"].as_u64().unwrap() >= 1 && r["ms"].as_f64().unwrap() >= 0.0, "{r}");
        assert!(r["texture_bytes"].as_u64().unwrap() <= (budget * factor) as u64, "{r}");
    }
    // The fresh selection and the Selector's first are the same.
    assert_eq!(rows[0]["bricks"], rows[1]["bricks"]);
    assert_clean_failure(
        &run(&["bench", "select", "--dataset", "sphere", "--size", "9", "--budgets-mb", "0"]),
        "budget",
    );
}

/// `render --jitter`: the plan's effects end with `jittering` (absent
/// without the flag, and under Slice), the picture differs from the
/// lattice's, and against the reference it is no worse than the lattice's
/// within 5 % on a coarse selection (the render tests' bound; the library
/// test measures the rings, render::jitter_tests).
#[test]
fn render_jitter_is_reported_and_changes_only_the_sampling() {
    let dir = std::env::temp_dir().join(format!("ho-jitter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (png, reference) = (dir.join("frame.png"), dir.join("reference.png"));
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "--dataset",
            "sphere",
            "--size",
            "33",
            "--width",
            "64",
            "--height",
            "64",
            "--budget-mb",
            "0.01",
            "--output",
            png.to_str().unwrap(),
            "--reference",
            reference.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(str::to_string).collect::<Vec<_>>()
    };
    let render = |extra: &[&'static str]| {
        let a = args(extra);
        let r = json_of("render", &a.iter().map(String::as_str).collect::<Vec<_>>());
        (r.clone(), std::fs::read(&png).unwrap())
    };
    let (plain, plain_png) = render(&[]);
    let (jittered, jittered_png) = render(&["--jitter"]);
    assert_eq!(plain["effects"], serde_json::json!([]), "{plain}");
    assert_eq!(jittered["effects"], serde_json::json!(["jittering"]), "{jittered}");
    assert_ne!(plain_png, jittered_png);
    let (a, b) = (plain["rmse"].as_f64().unwrap(), jittered["rmse"].as_f64().unwrap());
    assert!(b <= 1.05 * a, "jittered RMSE {b} vs {a}");
    let (sliced, _) = render(&["--jitter", "--blend", "slice", "--slice-normal", "0,0,1"]);
    assert!(!sliced["effects"].as_array().unwrap().iter().any(|e| e == "jittering"), "{sliced}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The scattering arguments are checked whether or not scattering runs:
/// a reach or an anisotropy out of range is refused at blending 0 too,
/// with the value and its range named; a good one at blending 0 renders.
#[test]
fn render_refuses_bad_scattering_arguments_even_unused() {
    let png = temp("scatter-args.png");
    let out = png.to_str().unwrap();
    let base = ["--dataset", "sphere", "--size", "9", "--width", "8", "--height", "8", "--shade", "--output", out];
    for (extra, reason) in [
        (&["--scatter-reach", "-1"][..], "reach -1: give a number from 0 to 1"),
        (&["--scatter-anisotropy", "2"][..], "anisotropy 2: give a number from -1 to 1"),
        (&["--scatter-blending", "nan"][..], "blending NaN"),
        (&["--scatter-reach", "inf", "--scatter-blending", "1"][..], "reach inf"),
    ] {
        assert_clean_failure(&run(&[&["render"][..], &base[..], extra].concat()), reason);
    }
    let ok = run(&[&["render"][..], &base[..], &["--scatter-reach", "0.5"]].concat());
    assert!(ok.status.success(), "{}", stderr(&ok));
    let _ = std::fs::remove_file(png);
}

/// `convert` writes an OME-Zarr store that every `--file` command reads;
/// `render` draws it from disk the picture it draws in memory, and refuses
/// what needs every sample with what to do.
#[test]
fn convert_writes_a_store_that_renders_from_disk_as_in_memory() {
    let store = temp("phantom.ome.zarr");
    let s = store.to_str().unwrap();
    let c = json_of(
        "convert",
        &["--dataset", "shepp-logan", "--size", "40", "--type", "u16", "--leaf-size", "8", "--output", s],
    );
    assert_eq!(c["dims"], serde_json::json!([40, 40, 40]));
    assert_eq!(c["levels"], 7, "strides 1 .. 64 for a 64-cell root");
    assert!(c["store_bytes"].as_u64().unwrap() > 0);
    // The stored volume is the generated one.
    let from_store = build_json(&["--file", s, "--leaf-size", "8"]);
    let generated = build_json(&["--dataset", "shepp-logan", "--size", "40", "--type", "u16", "--leaf-size", "8"]);
    for key in ["node_count", "value_min", "value_max", "cut_count"] {
        assert_eq!(from_store[key], generated[key], "{key}");
    }
    let (disk, memory) = (temp("disk.png"), temp("memory.png"));
    let common = [
        "--file",
        s,
        "--budget-mb",
        "0.05",
        "--view-selection",
        "screen",
        "--width",
        "96",
        "--height",
        "96",
        "--shade",
    ];
    let r = json_of("render", &[&common[..], &["--output", disk.to_str().unwrap()]].concat());
    json_of("render", &[&common[..], &["--in-memory", "--output", memory.to_str().unwrap()]].concat());
    assert!(std::fs::read(&disk).unwrap() == std::fs::read(&memory).unwrap(), "disk and memory pictures differ");
    assert!(r["bricks"].as_u64().unwrap() > 1 && r["estimated_error"].as_f64().unwrap() > 0.0, "{r}");
    assert_eq!(r["passes"], serde_json::json!(["volume-shaded"]));
    // The default view selection falls back to screen space, and says so.
    let both = json_of("render", &["--file", s, "--budget-mb", "0.05", "--output", disk.to_str().unwrap()]);
    assert_eq!(both["view_selection"], "Screen");
    assert!(both["warning"].as_str().unwrap().contains("weighed by screen space alone"), "{both}");
    // What needs every sample is refused, with what to do.
    let iso = run(&["render", "--file", s, "--isovalue", "100", "--output", disk.to_str().unwrap()]);
    assert_clean_failure(&iso, "--in-memory");
    let mip =
        run(&["render", "--file", s, "--blend", "mip", "--budget-mb", "0.02", "--output", disk.to_str().unwrap()]);
    assert_clean_failure(&mip, "peak");
    // Nothing is overwritten; the output must be a .zarr folder.
    let again = run(&["convert", "--dataset", "sphere", "--size", "8", "--output", s]);
    assert_clean_failure(&again, "already exists");
    let not_zarr = run(&["convert", "--dataset", "sphere", "--size", "8", "--output", disk.to_str().unwrap()]);
    assert_clean_failure(&not_zarr, ".ome.zarr");
    for p in [&disk, &memory] {
        let _ = std::fs::remove_file(p);
    }
    let _ = std::fs::remove_dir_all(&store);
}

/// A store written elsewhere (NGFF 0.4, Zarr v2, time and channel axes,
/// uncompressed chunks) opens: its first time point and channel, its
/// spacing and origin from the coordinate transformations.
#[test]
fn a_foreign_ngff_0_4_store_opens() {
    let store = temp("foreign.zarr");
    let dims = [6usize, 5, 4]; // x, y, z
    std::fs::create_dir_all(store.join("0")).unwrap();
    std::fs::write(store.join(".zgroup"), r#"{"zarr_format": 2}"#).unwrap();
    let attrs = serde_json::json!({"multiscales": [{
        "version": "0.4",
        "axes": [{"name": "t", "type": "time"}, {"name": "c", "type": "channel"},
                 {"name": "z", "type": "space"}, {"name": "y", "type": "space"}, {"name": "x", "type": "space"}],
        "datasets": [{"path": "0", "coordinateTransformations": [
            {"type": "scale", "scale": [1.0, 1.0, 3.0, 2.0, 0.5]},
            {"type": "translation", "translation": [0.0, 0.0, 7.0, 8.0, 9.0]}]}]
    }]});
    std::fs::write(store.join(".zattrs"), attrs.to_string()).unwrap();
    let zarray = serde_json::json!({"zarr_format": 2, "shape": [2, 2, dims[2], dims[1], dims[0]],
        "chunks": [1, 1, dims[2], dims[1], dims[0]], "dtype": "<u2", "compressor": null, "fill_value": 0,
        "order": "C", "filters": null, "dimension_separator": "/"});
    std::fs::write(store.join("0/.zarray"), zarray.to_string()).unwrap();
    let n = dims[0] * dims[1] * dims[2];
    for (t, c, offset) in [(0, 0, 0u16), (0, 1, 1000), (1, 0, 2000), (1, 1, 3000)] {
        let bytes: Vec<u8> = (0..n as u16).flat_map(|v| (v + offset).to_le_bytes()).collect();
        let dir = store.join(format!("0/{t}/{c}/0/0"));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("0"), bytes).unwrap();
    }
    let out = run(&["info", "--file", store.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("6 x 5 x 4"), "{text}");
    assert!(text.contains("[0.5, 2.0, 3.0]") && text.contains("[9.0, 8.0, 7.0]"), "{text}");
    assert!(text.contains("value range: 0 .. 119"), "index 0 of t and c: {text}");
    assert!(stderr(&out).contains("index 0 of each is read"), "{}", stderr(&out));
    // Drawn from disk (its octree built by one streaming pass over level 0),
    // the picture read whole draws.
    let (disk, memory) = (temp("foreign-disk.png"), temp("foreign-memory.png"));
    let common =
        ["render", "--file", store.to_str().unwrap(), "--view-selection", "screen", "--width", "64", "--height", "48"];
    let budget = ["--budget-mb", "0.0005", "--leaf-size", "2"];
    for (extra, png) in [(&[][..], &disk), (&["--in-memory"][..], &memory)] {
        let out = run(&[&common[..], &budget[..], extra, &["--output", png.to_str().unwrap()]].concat());
        assert!(out.status.success(), "{}", stderr(&out));
    }
    assert!(std::fs::read(&disk).unwrap() == std::fs::read(&memory).unwrap(), "disk and memory pictures differ");
    for p in [&disk, &memory] {
        let _ = std::fs::remove_file(p);
    }
    let _ = std::fs::remove_dir_all(&store);
}

#[test]
fn render_meets_a_frame_time_target_and_shows_the_price() {
    let dir = std::env::temp_dir().join(format!("ho-render-time-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (png, reference) = (dir.join("frame.png"), dir.join("reference.png"));
    let (png, reference) = (png.to_str().unwrap(), reference.to_str().unwrap());
    let scene = ["--dataset", "shepp-logan", "--size", "33", "--width", "48", "--height", "48", "--output", png];
    let mut args = scene.to_vec();
    args.extend(["--target-ms", "30", "--budget-mb", "0.2", "--reference", reference]);
    let r = json_of("render", &args);
    for key in ["target_ms", "ms", "predicted_ms", "rmse", "estimated_error", "budget_bytes", "max_budget_bytes"] {
        assert!(r[key].is_number(), "{key} in {r}");
    }
    assert_eq!(r["target_ms"].as_f64(), Some(30.0));
    assert!(["met", "full", "below-fastest"].contains(&r["time_outcome"].as_str().unwrap()), "{r}");
    assert!(r["budget_bytes"].as_u64() <= r["max_budget_bytes"].as_u64(), "the memory limit holds: {r}");
    assert_eq!(r["max_budget_bytes"].as_u64(), Some(200_000));
    assert!(r["warmup_frames"].as_u64().unwrap() >= 2);
    // The text form says the target, the prediction and the measurement.
    let mut text = vec!["render"];
    text.extend(&args);
    let out = run(&text);
    assert!(out.status.success(), "{}", stderr(&out));
    let s = stdout(&out);
    assert!(s.contains("frame time:") && s.contains("target 30.0 ms") && s.contains("predicted"), "{s}");
    // A target no frame can meet: the coarsest selection, said in the warning.
    let mut args = scene.to_vec();
    args.extend(["--target-ms", "0.000001"]);
    let r = json_of("render", &args);
    assert_eq!(r["time_outcome"], "below-fastest", "{r}");
    assert!(r["warning"].as_str().unwrap().contains("below the fastest frame"), "{r}");
    // Bad targets: one line naming the problem and the fix, status 2.
    for (bad, says) in [("0", "not above 0"), ("-3", "not above 0"), ("NaN", "not a number"), ("1e12", "above")] {
        let mut args = vec!["render"];
        args.extend(scene);
        args.extend(["--target-ms", bad]);
        let out = run(&args);
        assert_clean_failure(&out, says);
        assert!(stderr(&out).contains("--target-ms") && stderr(&out).contains("give milliseconds"));
        assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bench_render_rows_per_frame_time_target() {
    let plot = temp("targets.png");
    let args = [
        "render",
        "--dataset",
        "shepp-logan",
        "--size",
        "33",
        "--width",
        "40",
        "--height",
        "40",
        "--budget-mb",
        "0.2",
        "--targets-ms",
        "5,20,80",
        "--frames",
        "2",
        "--plot",
        plot.to_str().unwrap(),
    ];
    let r = {
        let mut all = vec!["bench"];
        all.extend_from_slice(&args[..]);
        all.push("--json");
        let out = run(&all);
        assert!(out.status.success(), "{}", stderr(&out));
        serde_json::from_str::<Value>(&stdout(&out)).expect("one JSON object")
    };
    let rows = r["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for (row, target) in rows.iter().zip([5.0, 20.0, 80.0]) {
        assert_eq!(row["target_ms"].as_f64(), Some(target));
        for key in ["ms", "p90_ms", "predicted_ms", "rmse", "estimated_error", "budget_bytes"] {
            assert!(row[key].is_number(), "{key} in {row}");
        }
        assert_eq!(row["frames"].as_u64(), Some(2));
        assert!(row["budget_bytes"].as_u64().unwrap() <= 200_000);
    }
    assert!(r["fastest_ms"].is_number() && r["coefficients"].is_array(), "{r}");
    assert!(r.get("rank_correlation").is_some(), "{r}");
    assert_eq!(&std::fs::read(&plot).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    std::fs::remove_file(&plot).unwrap();
    // A bad target among them is refused by value before anything runs.
    let out = run(&["bench", "render", "--dataset", "sphere", "--size", "9", "--targets-ms", "20,-1"]);
    assert_clean_failure(&out, "--targets-ms");
    let out = run(&["bench", "render", "--dataset", "sphere", "--size", "9", "--targets-ms", "inf"]);
    assert_clean_failure(&out, "above");
}
