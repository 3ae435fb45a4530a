//! The hybrid point/volume representation (paper 3) through the bridge: the
//! points `vtkHybridOctreePoints` outputs ([`generate_points`]), and the
//! points integrated into the Hybrid Octree for the volume mapper to draw.

use super::grid::{grid_of, same_image};
use super::guard::{check_len, guarded, Bridged};
use super::octree::HybridOctreeHandle;
use super::transfer::transfer_function;
use super::{GridDesc, PointsDesc, PointsSummary};
use crate::error::{Error, Result};
use crate::hybrid::HybridPoints;
use crate::points::mass::PointMass;
use crate::points::{
    generate as generate_set, generate_hybrid, normals, write_points, PointOptions, PointSelect, PointSet,
};
use std::sync::Arc;
use std::time::Instant;

/// Points made by `generate_points`, kept until the host has read them.
#[derive(Debug)]
pub struct GeneratedPoints {
    set: PointSet,
    generate_ms: f64,
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

/// What `set` holds, for the host.
fn points_summary(set: &PointSet, generate_ms: f64) -> PointsSummary {
    PointsSummary {
        points: set.points.len(),
        factor: set.factor,
        point_bytes: set.bytes(),
        underestimates: set.points.iter().filter(|p| p.error > 0).count(),
        generate_ms,
    }
}

/// Writes `set` to `file_name` unless it is empty.
fn write_if_named(set: &PointSet, file_name: &str) -> Result<()> {
    if file_name.is_empty() {
        Ok(())
    } else {
        write_points(set, std::path::Path::new(file_name))
    }
}

/// The points completing the borrowed image's stride-`factor` low resolution.
pub(crate) fn generate_points(bytes: &[u8], desc: &GridDesc, options: &PointsDesc) -> Bridged<Box<GeneratedPoints>> {
    guarded(|| {
        let grid = grid_of(bytes, desc)?;
        let started = Instant::now();
        let (set, _low) = generate_hybrid(&grid, &point_options(options))?;
        let generate_ms = started.elapsed().as_secs_f64() * 1e3;
        write_if_named(&set, &options.file_name)?;
        Ok(Box::new(GeneratedPoints { set, generate_ms }))
    })
}

impl GeneratedPoints {
    pub(crate) fn summary(&self) -> Bridged<PointsSummary> {
        guarded(|| Ok(points_summary(&self.set, self.generate_ms)))
    }

    pub(crate) fn fill(
        &self,
        ijk: &mut [u32],
        value: &mut [f32],
        error: &mut [f32],
        normal: &mut [f32],
    ) -> Bridged<()> {
        guarded(|| {
            let set = &self.set;
            let n = set.points.len();
            check_len("point indices", ijk, 3 * n)?;
            check_len("point values", value, n)?;
            check_len("point errors", error, n)?;
            check_len("point normals", normal, 3 * n)?;
            for (i, p) in set.points.iter().enumerate() {
                ijk[3 * i..3 * i + 3].copy_from_slice(&p.ijk.map(u32::from));
                value[i] = set.value(p) as f32;
                error[i] = set.error(p) as f32;
                normal[3 * i..3 * i + 3].copy_from_slice(&normals::direction(p.normal).map(|c| c as f32));
            }
            Ok(())
        })
    }
}

impl HybridOctreeHandle {
    pub(crate) fn integrate_points(
        &mut self,
        bytes: &[u8],
        desc: &GridDesc,
        options: &PointsDesc,
    ) -> Bridged<PointsSummary> {
        guarded(|| {
            self.hybrid.points = None;
            // The kept selection's steps were those of the octree without (or with other) points.
            self.selector = Default::default();
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
            write_if_named(&set, &options.file_name)?;
            let mass = PointMass::voxel_means(&grid, &set, self.volume().layout().leaf_size());
            let summary = points_summary(&set, -1.0);
            self.hybrid.points = Some(HybridPoints { set: Arc::new(set), mass });
            Ok(summary)
        })
    }

    pub(crate) fn remove_points(&mut self) -> Bridged<()> {
        guarded(|| {
            self.hybrid.points = None;
            // The kept selection's steps were those of the octree without (or with other) points.
            self.selector = Default::default();
            Ok(())
        })
    }

    /// The points held, or the error naming what to do first.
    fn points(&self) -> Result<&PointSet> {
        match &self.hybrid.points {
            Some(p) => Ok(&p.set),
            None => Err(Error::InvalidArgument("the Hybrid Octree holds no points: integrate them first".into())),
        }
    }

    pub(crate) fn points_drawing(&self, position: &mut [f32], value: &mut [f32], error: &mut [f32]) -> Bridged<()> {
        guarded(|| {
            let set = self.points()?;
            let n = set.points.len();
            check_len("point positions", position, 3 * n)?;
            check_len("point values", value, n)?;
            check_len("point errors", error, n)?;
            for (i, p) in set.points.iter().enumerate() {
                let world = self.shape.world(p.ijk.map(f64::from));
                position[3 * i..3 * i + 3].copy_from_slice(&world.map(|c| c as f32));
                value[i] = set.value(p) as f32;
                error[i] = set.error(p) as f32;
            }
            Ok(())
        })
    }

    pub(crate) fn point_shades(
        &self,
        bytes: &[u8],
        desc: &GridDesc,
        colors: &[f64],
        opacities: &[f64],
        shades: &mut [f32],
    ) -> Bridged<()> {
        guarded(|| {
            let set = self.points()?;
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let tf = transfer_function(colors, opacities)?;
            check_len("point shades", shades, 4 * set.points.len())?;
            for (s, to) in crate::points::shade(&grid, set, &tf)?.iter().zip(shades.chunks_exact_mut(4)) {
                to.copy_from_slice(&[s.rgb[0], s.rgb[1], s.rgb[2], s.alpha]);
            }
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{as_bytes, build_volume_octree, f32_desc, select_desc};
    use super::super::CameraDesc;
    use super::*;

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

    /// Generated points read out: indices, values, errors, normals and the summary.
    struct Read {
        ijk: Vec<u32>,
        value: Vec<f32>,
        error: Vec<f32>,
        normal: Vec<f32>,
        summary: PointsSummary,
    }

    fn generate(data: &[f32], desc: &GridDesc, options: &PointsDesc) -> std::result::Result<Read, String> {
        let made = generate_points(as_bytes(data), desc, options)?;
        let summary = made.summary()?;
        let n = summary.points;
        let mut r =
            Read { ijk: vec![0; 3 * n], value: vec![0.0; n], error: vec![0.0; n], normal: vec![0.0; 3 * n], summary };
        made.fill(&mut r.ijk, &mut r.value, &mut r.error, &mut r.normal)?;
        Ok(r)
    }

    #[test]
    fn points_of_a_ball_sit_on_its_edge_and_the_file_is_written() {
        let (data, desc) = ball();
        let file = std::env::temp_dir().join(format!("ho-ffi-points-{}.hop", std::process::id()));
        let o = PointsDesc { file_name: file.display().to_string(), ..options() };
        let out = generate(&data, &desc, &o).unwrap();
        let n = out.value.len();
        assert!(n > 0 && out.summary.points == n);
        assert_eq!(out.summary.point_bytes, 6 * n);
        assert_eq!(std::fs::metadata(&file).unwrap().len() as usize, 72 + 6 * n);
        std::fs::remove_file(&file).ok();
        // A step edge: every point's error is large and its value 0 or 1.
        assert!(out.error.iter().all(|e| e.abs() > 0.1));
        assert!(out.value.iter().all(|&v| v == 0.0 || v == 1.0));
        assert!(out.normal.chunks(3).all(|n| (n.iter().map(|c| c * c).sum::<f32>() - 1.0).abs() < 1e-3));
        let budget = generate(&data, &desc, &PointsDesc { use_budget: true, budget: 7, ..options() }).unwrap();
        assert_eq!(budget.value.len(), 7);
        let made = generate_points(as_bytes(&data), &desc, &options()).unwrap();
        let mut short = vec![0; 3];
        let e = made.fill(&mut short, &mut [], &mut [], &mut []).unwrap_err();
        assert!(e.contains("point indices"), "{e}");
    }

    #[test]
    fn bad_options_are_clear_errors() {
        let (data, desc) = ball();
        let err = |o: PointsDesc| generate(&data, &desc, &o).err().unwrap();
        assert!(err(PointsDesc { factor: 3, ..options() }).contains("factor 3"));
        assert!(err(PointsDesc { threshold: 2.0, ..options() }).contains("threshold 2"));
        assert!(err(PointsDesc { max_overestimate: f64::NAN, ..options() }).contains("bound"));
        let e = err(PointsDesc { file_name: "/nonexistent-dir/x.hop".into(), ..options() });
        assert!(e.contains("/nonexistent-dir/x.hop"), "{e}");
    }

    fn camera() -> CameraDesc {
        CameraDesc {
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
        use crate::points::Footprint;
        use crate::render::compositor::composite_with_points;
        use crate::transfer::TransferFunction;
        let (data, desc) = ball();
        let mut octree = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        let without = octree.select_bricks(&select_desc(14_000)).unwrap();
        let o = PointsDesc { factor: 2, underestimates_only: true, ..options() };
        let made = octree.integrate_points(as_bytes(&data), &desc, &o).unwrap();
        let n = made.points;
        let (mut position, mut value, mut error) = (vec![0.0; 3 * n], vec![0.0; n], vec![0.0; n]);
        octree.points_drawing(&mut position, &mut value, &mut error).unwrap();
        assert!(n > 0 && error.iter().all(|&e| e > 0.0));
        assert_eq!((made.factor, made.point_bytes), (2, 6 * n));
        let set = Arc::clone(&octree.hybrid.points.as_ref().unwrap().set);
        // A budget between stride 2 and full resolution: some bricks stay at stride 2 and take points.
        let s = octree.select_bricks(&select_desc(14_000)).unwrap();
        let sum = s.summary().unwrap();
        assert!(sum.points > 0 && sum.point_bytes == 6 * sum.points, "{sum:?}");
        assert!(sum.texture_bytes + sum.point_bytes <= 14_000, "{sum:?}");
        let list = s.draw_list(&octree, &camera(), 0.0).unwrap();
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
        let direct_list = s.list(&octree, &camera(), 0.0).unwrap();
        let textures = crate::render::texture::upload(&grid, &direct_list).unwrap();
        let shades = crate::points::shade(&grid, &set, &tf).unwrap();
        for (gaussian, kind) in [(false, Footprint::Square), (true, Footprint::Gaussian)] {
            let mut bridged = vec![0.0; 4 * 48 * 40];
            let no_surface = [0.0; 4];
            s.composite(
                &octree,
                &camera(),
                as_bytes(&data),
                &desc,
                &colors,
                &opacities,
                gaussian,
                &no_surface,
                48,
                40,
                &mut bridged,
            )
            .unwrap();
            let drawn = Some((&*set, shades.as_slice(), kind));
            let direct = composite_with_points(&textures, &direct_list, &tf, 48, 40, None, drawn).unwrap();
            assert_eq!(bridged, direct.rgba.iter().flatten().copied().collect::<Vec<f32>>());
        }
        // The shades the mapper draws are the compositor's.
        let mut bridged = vec![0.0; 4 * n];
        octree.point_shades(as_bytes(&data), &desc, &colors, &opacities, &mut bridged).unwrap();
        let flat: Vec<f32> = shades.iter().flat_map(|s| [s.rgb[0], s.rgb[1], s.rgb[2], s.alpha]).collect();
        assert_eq!(bridged, flat);
        assert!(shades.iter().any(|s| s.alpha > 0.0));
        let e = octree.point_shades(as_bytes(&data), &desc, &colors[..3], &opacities, &mut bridged).unwrap_err();
        assert!(e.contains("tuples"), "{e}");
        // A selection made before the points were integrated has none.
        assert_eq!(without.summary().unwrap().points, 0);
        assert!(without.draw_list(&octree, &camera(), 0.0).unwrap().bucket_offsets.is_empty());
        // Removed points are bought no more.
        octree.remove_points().unwrap();
        assert_eq!(octree.select_bricks(&select_desc(14_000)).unwrap().summary().unwrap().points, 0);
        let e = octree.points_drawing(&mut position, &mut value, &mut error).unwrap_err();
        assert!(e.contains("holds no points"), "{e}");
    }

    #[test]
    fn integrated_points_refuse_what_cannot_be_drawn() {
        let (data, desc) = ball();
        let mut octree = build_volume_octree(as_bytes(&data), &desc, 4).unwrap();
        let o = PointsDesc { max_overestimate: 0.1, ..options() };
        let e = octree.integrate_points(as_bytes(&data), &desc, &o).unwrap_err();
        assert!(e.contains("max_overestimate"), "{e}");
        let e = octree.integrate_points(as_bytes(&data), &desc, &PointsDesc { factor: 5, ..options() }).unwrap_err();
        assert!(e.contains("factor 5"));
        let small = f32_desc([11; 3]);
        let e = octree.integrate_points(as_bytes(&data[..11 * 11 * 11]), &small, &options()).unwrap_err();
        assert!(e.contains("rebuild"));
        assert!(octree.hybrid.points.is_none(), "a failed integration leaves no points");
    }
}
