//! The bridge's hybrid point/volume representation (paper 3): the body
//! behind `ffi::generate_points`, for `vtkHybridOctreePoints`, and the
//! points the volume mapper draws ([`PointsHandle`]).

use crate::error::{Error, Result};
use crate::ffi::{grid_of, guarded, same_image, GridDesc, PointsDesc, PointsDrawing, PointsOutput, VolumeOctreeHandle};
use crate::grid::GridShape;
use crate::points::mass::PointMass;
use crate::points::{
    generate as generate_set, generate_hybrid, normals, write_points, PointOptions, PointSelect, PointSet,
};
use std::sync::Arc;
use std::time::Instant;

/// Points kept for drawing: the set, and its per-block mass for the selection.
#[derive(Debug)]
pub struct PointsHandle {
    pub(crate) set: Arc<PointSet>,
    pub(crate) mass: PointMass,
    pub(crate) octree_id: u64,
    shape: GridShape,
}

impl VolumeOctreeHandle {
    pub(crate) fn points_for_drawing(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        options: &PointsDesc,
    ) -> std::result::Result<Box<PointsHandle>, String> {
        guarded(|| {
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let point_options = point_options(options);
            if point_options.max_overestimate.is_some() {
                return Err(Error::InvalidArgument(
                    "drawn points complete textures of the image itself: the optimized low resolution \
                     (max_overestimate >= 0) cannot be drawn; set it below 0"
                        .into(),
                ));
            }
            let set = generate_set(&grid, &point_options)?;
            if !options.file_name.is_empty() {
                write_points(&set, std::path::Path::new(&options.file_name))?;
            }
            let mass = PointMass::voxel_means(&grid, &set, self.octree.layout().leaf_size());
            Ok(Box::new(PointsHandle { set: Arc::new(set), mass, octree_id: self.id, shape: self.shape }))
        })
    }
}

impl PointsHandle {
    pub(crate) fn drawing(&self) -> std::result::Result<PointsDrawing, String> {
        guarded(|| Ok(drawing(&self.set, &self.shape)))
    }

    pub(crate) fn shades(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        colors: &[f64],
        opacities: &[f64],
    ) -> std::result::Result<Vec<f32>, String> {
        guarded(|| {
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let tf = crate::ffi_render::transfer_function(colors, opacities)?;
            let shades = crate::points::shade(&grid, &self.set, &tf)?;
            Ok(shades.iter().flat_map(|s| [s.rgb[0], s.rgb[1], s.rgb[2], s.alpha]).collect())
        })
    }
}

/// `set`'s world positions (on the grid of `shape`), values and errors.
fn drawing(set: &PointSet, shape: &GridShape) -> PointsDrawing {
    PointsDrawing {
        position: set.points.iter().flat_map(|p| shape.world(p.ijk.map(f64::from)).map(|c| c as f32)).collect(),
        value: set.points.iter().map(|p| set.value(p) as f32).collect(),
        error: set.points.iter().map(|p| set.error(p) as f32).collect(),
        factor: set.factor,
        point_bytes: set.bytes(),
    }
}

/// The generation options of `options` (a negative bound: plain subsampling).
fn point_options(options: &PointsDesc) -> PointOptions {
    let select = if options.use_budget {
        PointSelect::Budget(options.budget)
    } else {
        PointSelect::Threshold(options.threshold)
    };
    PointOptions {
        factor: options.factor,
        select,
        underestimates_only: options.underestimates_only,
        max_overestimate: (options.max_overestimate >= 0.0 || options.max_overestimate.is_nan())
            .then_some(options.max_overestimate),
    }
}

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
    let point_options = point_options(options);
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
    use crate::ffi::{as_bytes, f32_desc, select_desc};

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

    fn camera() -> crate::ffi::CameraDesc {
        crate::ffi::CameraDesc {
            position: [40.0, 30.0, 50.0],
            focal_point: [10.0; 3],
            view_up: [0.0, 1.0, 0.0],
            parallel: false,
            parallel_scale: 1.0,
            view_angle: 30.0,
        }
    }

    #[test]
    fn a_selection_with_points_buys_them_and_its_draw_list_buckets_them() {
        use crate::ffi::build_volume_octree;
        use crate::points::draw::Footprint;
        use crate::render::compositor::composite_with_points;
        use crate::transfer::TransferFunction;
        let (data, desc) = ball();
        let octree = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        let o = PointsDesc { factor: 2, underestimates_only: true, ..options() };
        let points = octree.points_for_drawing(as_bytes(&data), &desc, &o).unwrap();
        let drawing = points.drawing().unwrap();
        let n = drawing.value.len();
        assert!(n > 0 && drawing.position.len() == 3 * n && drawing.error.iter().all(|&e| e > 0.0));
        assert_eq!((drawing.factor, drawing.point_bytes), (2, 6 * n));
        // A budget between stride 2 and full resolution: some bricks stay at stride 2 and take points.
        let s = octree.select_bricks_with_points(&select_desc(14_000), &points).unwrap();
        let sum = s.summary().unwrap();
        assert!(sum.points > 0 && sum.point_bytes == 6 * sum.points, "{sum:?}");
        assert!(sum.texture_bytes + sum.point_bytes <= 14_000, "{sum:?}");
        let list = s.draw_list(&octree, &camera()).unwrap();
        assert!(list.passes.ends_with("points"), "{}", list.passes);
        let bricks = list.brick.len();
        assert_eq!(list.bucket_offsets.len(), bricks + 1);
        let buckets = *list.bucket_offsets.last().unwrap();
        assert_eq!((list.bucket_slab.len(), list.bucket_point_offsets.len()), (buckets, buckets + 1));
        assert_eq!(list.bucket_points.len(), sum.points, "every point bought is drawn once");
        for i in 0..bricks {
            let slabs = list.slice_offsets[i + 1] - list.slice_offsets[i];
            let mine = &list.bucket_slab[list.bucket_offsets[i]..list.bucket_offsets[i + 1]];
            assert!(mine.windows(2).all(|w| w[0] < w[1]) && mine.iter().all(|&k| k <= slabs));
            assert!(mine.is_empty() || list.stride[i] == 2, "points only in bricks of their stride");
        }
        // The CPU picture through the bridge draws them: the compositor's own, with the same points.
        let colors = [0.0, 0.2, 0.3, 0.4, 1.0, 1.0, 0.9, 0.8];
        let opacities = [0.0, 0.0, 1.0, 0.3];
        let tf =
            TransferFunction::new(vec![(0.0, [0.2, 0.3, 0.4]), (1.0, [1.0, 0.9, 0.8])], vec![(0.0, 0.0), (1.0, 0.3)])
                .unwrap();
        let grid = grid_of(as_bytes(&data), &desc).unwrap();
        let direct_list = s.list(&octree, &camera(), None).unwrap();
        let textures = crate::render::texture::upload(&grid, &direct_list).unwrap();
        for (gaussian, kind) in [(false, Footprint::Square), (true, Footprint::Gaussian)] {
            let bridged =
                s.composite(&octree, &camera(), as_bytes(&data), &desc, &colors, &opacities, gaussian, 48, 40);
            let shades = crate::points::shade(&grid, &points.set, &tf).unwrap();
            let drawn = Some((&*points.set, shades.as_slice(), kind));
            let direct = composite_with_points(&textures, &direct_list, &tf, 48, 40, None, drawn).unwrap();
            assert_eq!(bridged.unwrap(), direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
        }
        // The shades the mapper draws are the compositor's.
        let bridged = points.shades(as_bytes(&data), &desc, &colors, &opacities).unwrap();
        let direct = crate::points::shade(&grid, &points.set, &tf).unwrap();
        let flat: Vec<f32> = direct.iter().flat_map(|s| [s.rgb[0], s.rgb[1], s.rgb[2], s.alpha]).collect();
        assert_eq!(bridged, flat);
        assert!(direct.iter().any(|s| s.alpha > 0.0));
        let e = points.shades(as_bytes(&data), &desc, &colors[..3], &opacities).unwrap_err();
        assert!(e.contains("tuples"), "{e}");
        let without = octree.select_bricks(&select_desc(14_000)).unwrap();
        assert_eq!(without.summary().unwrap().points, 0);
        assert!(without.draw_list(&octree, &camera()).unwrap().bucket_offsets.is_empty());
    }

    #[test]
    fn points_for_drawing_refuse_what_cannot_be_drawn() {
        use crate::ffi::build_volume_octree;
        let (data, desc) = ball();
        let octree = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        let other = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        let o = PointsDesc { max_overestimate: 0.1, ..options() };
        let e = octree.points_for_drawing(as_bytes(&data), &desc, &o).map(|_| ()).unwrap_err();
        assert!(e.contains("max_overestimate"), "{e}");
        let e = octree.points_for_drawing(as_bytes(&data), &desc, &PointsDesc { factor: 5, ..options() });
        assert!(e.map(|_| ()).unwrap_err().contains("factor 5"));
        let small = f32_desc([11; 3]);
        let e = octree.points_for_drawing(as_bytes(&data[..11 * 11 * 11]), &small, &options()).map(|_| ());
        assert!(e.unwrap_err().contains("rebuild"));
        let points = other.points_for_drawing(as_bytes(&data), &desc, &options()).unwrap();
        let e = octree.select_bricks_with_points(&select_desc(14_000), &points).map(|_| ()).unwrap_err();
        assert!(e.contains("another octree"), "{e}");
    }
}
