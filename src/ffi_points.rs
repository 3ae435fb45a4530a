//! The bridge's hybrid point/volume representation (issue 8): the body
//! behind `ffi::generate_points`, for `vtkHybridOctreePoints`.

use crate::error::Result;
use crate::ffi::{grid_of, guarded, GridDesc, PointsDesc, PointsOutput};
use crate::points::{generate_hybrid, normals, write_points, PointOptions, PointSelect};
use std::time::Instant;

/// The points completing the borrowed image's stride-`factor` low resolution.
pub(crate) fn generate_points(
    bytes: &[u8],
    desc: &GridDesc,
    options: &PointsDesc,
) -> std::result::Result<PointsOutput, String> {
    guarded(|| generate(bytes, desc, options))
}

fn generate(bytes: &[u8], desc: &GridDesc, options: &PointsDesc) -> Result<PointsOutput> {
    let grid = grid_of(bytes, desc)?;
    let select = if options.use_budget {
        PointSelect::Budget(options.budget)
    } else {
        PointSelect::Threshold(options.threshold)
    };
    let point_options = PointOptions {
        factor: options.factor,
        select,
        underestimates_only: options.underestimates_only,
        max_overestimate: (options.max_overestimate >= 0.0 || options.max_overestimate.is_nan())
            .then_some(options.max_overestimate),
    };
    let started = Instant::now();
    let (set, _low) = generate_hybrid(&grid, &point_options)?;
    let generate_ms = started.elapsed().as_secs_f64() * 1e3;
    if !options.file_name.is_empty() {
        write_points(&set, std::path::Path::new(&options.file_name))?;
    }
    let n = set.points.len();
    let mut out = PointsOutput {
        ijk: Vec::with_capacity(3 * n),
        value: Vec::with_capacity(n),
        error: Vec::with_capacity(n),
        normal: Vec::with_capacity(3 * n),
        factor: set.factor,
        point_bytes: set.bytes(),
        underestimates: set.points.iter().filter(|p| p.error > 0).count(),
        generate_ms,
    };
    for p in &set.points {
        out.ijk.extend(p.ijk.map(u32::from));
        out.value.push(set.value(p) as f32);
        out.error.push(set.error(p) as f32);
        out.normal.extend(normals::direction(p.normal).map(|c| c as f32));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::{as_bytes, f32_desc};

    fn ball() -> (Vec<f32>, GridDesc) {
        let n = 21;
        let c = (n as f32 - 1.0) / 2.0;
        let data: Vec<f32> = (0..n * n * n)
            .map(|i| {
                let (x, y, z) = ((i % n) as f32 - c, ((i / n) % n) as f32 - c, (i / (n * n)) as f32 - c);
                if (x * x + y * y + z * z).sqrt() < 6.3 {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        (data, f32_desc([n; 3]))
    }

    fn options() -> PointsDesc {
        PointsDesc {
            factor: 4,
            threshold: 0.1,
            use_budget: false,
            budget: 0,
            underestimates_only: false,
            max_overestimate: -1.0,
            file_name: String::new(),
        }
    }

    #[test]
    fn points_of_a_ball_sit_on_its_edge_and_the_file_is_written() {
        let (data, desc) = ball();
        let file = std::env::temp_dir().join(format!("ho-ffi-points-{}.hop", std::process::id()));
        let o = PointsDesc { file_name: file.display().to_string(), ..options() };
        let out = generate_points(as_bytes(&data), &desc, &o).unwrap();
        let n = out.value.len();
        assert!(n > 0 && out.ijk.len() == 3 * n && out.normal.len() == 3 * n && out.error.len() == n);
        assert_eq!(out.point_bytes, 6 * n);
        assert_eq!(std::fs::metadata(&file).unwrap().len() as usize, 72 + 6 * n);
        std::fs::remove_file(&file).ok();
        // A step edge: every point's error is large and its value 0 or 1.
        assert!(out.error.iter().all(|e| e.abs() > 0.1));
        assert!(out.value.iter().all(|&v| v == 0.0 || v == 1.0));
        let budget =
            generate_points(as_bytes(&data), &desc, &PointsDesc { use_budget: true, budget: 7, ..options() }).unwrap();
        assert_eq!(budget.value.len(), 7);
    }

    #[test]
    fn bad_options_are_clear_errors() {
        let (data, desc) = ball();
        let e = generate_points(as_bytes(&data), &desc, &PointsDesc { factor: 3, ..options() }).unwrap_err();
        assert!(e.contains("factor 3"), "{e}");
        let e = generate_points(as_bytes(&data), &desc, &PointsDesc { threshold: 2.0, ..options() }).unwrap_err();
        assert!(e.contains("threshold 2"), "{e}");
        let e = generate_points(as_bytes(&data), &desc, &PointsDesc { max_overestimate: f64::NAN, ..options() })
            .unwrap_err();
        assert!(e.contains("bound"), "{e}");
        let o = PointsDesc { file_name: "/nonexistent-dir/x.hop".into(), ..options() };
        let e = generate_points(as_bytes(&data), &desc, &o).unwrap_err();
        assert!(e.contains("/nonexistent-dir/x.hop"), "{e}");
    }
}
