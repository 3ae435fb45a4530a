//! The OpenGL mapper's geometry half of the bridge: a brick's block value
//! ranges, measured from its texels when they are made, and every frame the
//! vertices of the DrawList's bricks ([`crate::plan::draw_geometry`]), so that
//! `vtkOpenGLHybridOctreeBrickDrawer` only uploads and draws.
//!
//! The frame's inputs are the host's own copies, borrowed: the DrawList it
//! holds, the transfer function's table, each brick's block ranges, the
//! surface triangles and points it uploaded. Per brick, its drawn box is the
//! box of its visible blocks under the table
//! ([`crate::plan::draw_geometry::occupancy`]); nothing where none is visible.

use super::guard::{check_len, guarded, Bridged};
use super::{BrickGeometryDesc, BrickGeometryOutput};
use crate::base::error::{Error, Result};
use crate::plan::draw_geometry::occupancy::{measure, ranges_len, visible_bounds, visible_box, OpacityTable};
use crate::plan::draw_geometry::{
    brick_geometry, slice_plane_geometry, BrickSlabs, GeometryView, PointVertices, SurfaceVertices, MAX_BRICKS,
};
use std::ops::Range;

/// The texels per axis of a brick, checked: 3 values whose product fits memory.
fn brick_dims(dims: &[usize]) -> Result<[usize; 3]> {
    let dims: [usize; 3] = dims
        .try_into()
        .map_err(|_| Error::InvalidArgument(format!("{} texel counts for a brick: give 3 (x, y, z)", dims.len())))?;
    dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d)).ok_or_else(|| {
        Error::InvalidArgument(format!("a {}x{}x{} brick has more texels than memory holds", dims[0], dims[1], dims[2]))
    })?;
    Ok(dims)
}

/// Floats of the block ranges of a brick of `dims` texels (3 values).
pub(crate) fn block_ranges_len(dims: &[usize]) -> Bridged<usize> {
    guarded(|| Ok(ranges_len(brick_dims(dims)?)))
}

/// The block ranges of a brick's `texels` (`dims` per axis, x fastest) into
/// the caller's `ranges` ([`block_ranges_len`] floats).
pub(crate) fn brick_block_ranges(texels: &[f32], dims: &[usize], ranges: &mut [f32]) -> Bridged<()> {
    guarded(|| {
        let measured = measure(texels, brick_dims(dims)?)?;
        check_len("block ranges", ranges, measured.len())?;
        ranges.copy_from_slice(&measured);
        Ok(())
    })
}

/// The ranges `offsets[i] .. offsets[i + 1]` of a flattened per-brick list
/// of `bricks` bricks over `items` items, checked.
fn runs(name: &str, offsets: &[usize], bricks: usize, items: usize) -> Result<Vec<Range<usize>>> {
    let bad = |why: String| Err(Error::InvalidArgument(format!("the DrawList's {name}: {why}")));
    if offsets.len() != bricks + 1 {
        return bad(format!("{} offsets for {bricks} bricks, {} expected", offsets.len(), bricks + 1));
    }
    if offsets[0] != 0 || offsets.windows(2).any(|w| w[0] > w[1]) || offsets[bricks] > items {
        return bad(format!("offsets that do not run from 0 up to at most {items}"));
    }
    Ok(offsets.windows(2).map(|w| w[0]..w[1]).collect())
}

/// The vertices of the DrawList `desc` describes (see the module documentation).
pub(crate) fn frame_brick_geometry(desc: &BrickGeometryDesc<'_>) -> Bridged<BrickGeometryOutput> {
    guarded(|| {
        let bricks = desc.stride.len();
        if bricks > MAX_BRICKS {
            return Err(Error::InvalidArgument(format!(
                "{bricks} bricks to draw, at most {MAX_BRICKS} a frame: give a smaller texture budget"
            )));
        }
        check_len("brick bounds", desc.bounds, 6 * bricks)?;
        check_len("brick texel counts", desc.texels, 3 * bricks)?;
        check_len("brick block ranges", desc.block_ranges, bricks)?;
        if !desc.table.len().is_multiple_of(4) {
            return Err(Error::InvalidArgument(format!(
                "{} transfer function table values: 4 (r, g, b, opacity) a cell",
                desc.table.len()
            )));
        }
        let slices = runs("slices", desc.slice_offsets, bricks, desc.slices.len())?;
        // Triangles with the surface and the list's batches, points with the points and its buckets.
        let batches = match desc.with_surface && desc.batch_offsets.len() == bricks + 1 {
            true => {
                if desc.batch_first.len() != desc.batch_end.len() {
                    return Err(Error::InvalidArgument("the DrawList's batches: as many ends as firsts".into()));
                }
                Some(runs("batches", desc.batch_offsets, bricks, desc.batch_first.len())?)
            }
            false => None,
        };
        let buckets = match desc.with_points && desc.bucket_offsets.len() == bricks + 1 {
            true => {
                check_len("bucket slabs", desc.bucket_slab, desc.bucket_point_offsets.len().saturating_sub(1))?;
                let points =
                    runs("bucket points", desc.bucket_point_offsets, desc.bucket_slab.len(), desc.bucket_points.len())?;
                Some((runs("buckets", desc.bucket_offsets, bricks, desc.bucket_slab.len())?, points))
            }
            false => None,
        };
        let table = OpacityTable::new(desc.table, desc.table_lo, desc.table_hi);
        let mut out = BrickGeometryOutput {
            vertices: Vec::new(),
            brick_first: Vec::new(),
            ray_marched: Vec::with_capacity(bricks),
            drawn: Vec::with_capacity(bricks),
            boxes: Vec::with_capacity(6 * bricks),
            point_up: [0.0; 3],
            triangles_placed: 0,
            points_placed: 0,
        };
        let mut input = Vec::with_capacity(bricks);
        for i in 0..bricks {
            let dims = [desc.texels[3 * i], desc.texels[3 * i + 1], desc.texels[3 * i + 2]];
            let world: [f64; 6] = desc.bounds[6 * i..6 * i + 6].try_into().expect("length checked");
            let step = desc.spacing.map(|s| desc.stride[i] as f64 * s);
            let visible = visible_box(desc.block_ranges[i], dims, &table)
                .map_err(|e| Error::InvalidArgument(format!("brick {i}: {e}")))?;
            let bounds = visible.map_or([0.0; 6], |v| visible_bounds(&world, step, &v));
            out.drawn.push(u8::from(visible.is_some()));
            out.boxes.extend(bounds);
            input.push(BrickSlabs {
                slices: &desc.slices[slices[i].clone()],
                bounds,
                drawn: visible.is_some(),
                batches: batches
                    .as_ref()
                    .map_or(Vec::new(), |b| b[i].clone().map(|k| desc.batch_first[k]..desc.batch_end[k]).collect()),
                buckets: buckets.as_ref().map_or(Vec::new(), |(b, points)| {
                    b[i].clone().map(|k| (desc.bucket_slab[k], &desc.bucket_points[points[k].clone()])).collect()
                }),
            });
        }
        let view = GeometryView { eye: desc.eye, forward: desc.forward, view_up: desc.view_up };
        let surface = batches
            .is_some()
            .then_some(SurfaceVertices { vertices: desc.surface_vertices, triangles: desc.surface_triangles });
        let points = buckets.is_some().then_some(PointVertices {
            positions: desc.point_positions,
            shades: desc.point_shades,
            gaussian: desc.gaussian_points,
        });
        let g = match super::slice::geometry_plane(desc.slice_plane)? {
            Some(plane) => slice_plane_geometry(&plane, &input),
            None => brick_geometry(&view, &input, surface.as_ref(), points.as_ref())?,
        };
        out.vertices = g.vertices;
        out.brick_first = g.brick_first;
        out.ray_marched = g.ray_marched.into_iter().map(u8::from).collect();
        out.point_up = g.point_up;
        out.triangles_placed = g.triangles_placed;
        out.points_placed = g.points_placed;
        Ok(out)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::draw_geometry::FLOATS_PER_VERTEX;

    /// A one-brick list: a 1 x 1 x 8 box seen along +z from z = -10, slices
    /// 17 .. 10 (depth = z + 10), 2 x 2 x 9 texels of stride 1.
    struct Frame {
        slices: Vec<f64>,
        table: Vec<f32>,
        ranges: Vec<f32>,
        vertices: Vec<f32>,
        triangles: Vec<u32>,
    }

    fn frame(visible_value: f32) -> Frame {
        let dims = [2, 2, 9];
        // Value 1 in texels of z >= 6 only (blocks of cells 4..7: z 4..=8).
        let texels: Vec<f32> = (0..36).map(|i| if i / 4 >= 6 { visible_value } else { 0.0 }).collect();
        let mut ranges = vec![0.0; block_ranges_len(&dims).unwrap()];
        brick_block_ranges(&texels, &dims, &mut ranges).unwrap();
        Frame {
            slices: (10..18).rev().map(f64::from).collect(),
            // Opacity 0 at value 0, 1 at value 1 (2 cells over [0, 1]).
            table: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            ranges,
            vertices: [[0.0f32, 0.0, 4.5], [1.0, 0.0, 4.5], [0.0, 1.0, 4.5]]
                .iter()
                .flat_map(|p| [p[0], p[1], p[2], 0.0, 0.0, 1.0])
                .collect(),
            triangles: vec![0, 1, 2],
        }
    }

    fn desc<'a>(f: &'a Frame, ranges: &'a [&'a [f32]]) -> BrickGeometryDesc<'a> {
        BrickGeometryDesc {
            eye: [0.5, 0.5, -10.0],
            forward: [0.0, 0.0, 1.0],
            view_up: [0.0, 1.0, 0.0],
            spacing: [1.0; 3],
            bounds: &[0.0, 1.0, 0.0, 1.0, 0.0, 8.0],
            texels: &[2, 2, 9],
            stride: &[1],
            slice_offsets: &[0, 8],
            slices: &f.slices,
            batch_offsets: &[0, 1],
            batch_first: &[0],
            batch_end: &[1],
            bucket_offsets: &[],
            bucket_slab: &[],
            bucket_point_offsets: &[],
            bucket_points: &[],
            table: &f.table,
            table_lo: 0.0,
            table_hi: 1.0,
            block_ranges: ranges,
            with_surface: true,
            surface_vertices: &f.vertices,
            surface_triangles: &f.triangles,
            with_points: false,
            point_positions: &[],
            point_shades: &[],
            gaussian_points: false,
            slice_plane: &[],
        }
    }

    #[test]
    fn the_frame_geometry_clips_slices_to_the_visible_blocks() {
        let f = frame(1.0);
        let ranges = [&f.ranges[..]];
        let out = frame_brick_geometry(&desc(&f, &ranges)).unwrap();
        // Visible: z from texel 4 (block 1) to 8.
        assert_eq!(out.drawn, vec![1]);
        assert_eq!(out.boxes, vec![0.0, 1.0, 0.0, 1.0, 4.0, 8.0]);
        assert_eq!(out.ray_marched, vec![0]);
        assert_eq!(out.triangles_placed, 1);
        // Slices of depth 14 .. 17 cut the visible box (z 4 .. 7): 4 squares and the triangle.
        assert_eq!(out.brick_first, vec![0, 3 + 4 * 6]);
        assert_eq!(out.vertices.len(), FLOATS_PER_VERTEX * (3 + 4 * 6));
        // Nothing visible: no slices, the triangle still drawn.
        let f = frame(0.0);
        let ranges = [&f.ranges[..]];
        let out = frame_brick_geometry(&desc(&f, &ranges)).unwrap();
        assert_eq!((out.drawn.clone(), out.boxes.clone()), (vec![0], vec![0.0; 6]));
        assert_eq!(out.brick_first, vec![0, 3]);
        // Without the surface: ray-marched (nothing drawn: no visible block).
        let d = BrickGeometryDesc { with_surface: false, ..desc(&f, &ranges) };
        let out = frame_brick_geometry(&d).unwrap();
        assert_eq!((out.ray_marched, out.brick_first), (vec![1], vec![0, 0]));
    }

    #[test]
    fn mismatched_inputs_are_clear_errors() {
        let f = frame(1.0);
        let ranges = [&f.ranges[..]];
        let check = |d: BrickGeometryDesc<'_>, what: &str| {
            let e = frame_brick_geometry(&d).unwrap_err();
            assert!(e.contains(what), "{e} (expected {what})");
        };
        check(BrickGeometryDesc { bounds: &[0.0; 5], ..desc(&f, &ranges) }, "brick bounds holds 5 values, 6 expected");
        check(BrickGeometryDesc { block_ranges: &[], ..desc(&f, &ranges) }, "brick block ranges holds 0 values");
        check(BrickGeometryDesc { slice_offsets: &[0, 9], ..desc(&f, &ranges) }, "the DrawList's slices");
        check(BrickGeometryDesc { slice_offsets: &[0], ..desc(&f, &ranges) }, "1 offsets for 1 bricks, 2 expected");
        check(BrickGeometryDesc { table: &[0.0; 5], ..desc(&f, &ranges) }, "5 transfer function table values");
        check(BrickGeometryDesc { batch_end: &[], ..desc(&f, &ranges) }, "as many ends as firsts");
        check(BrickGeometryDesc { batch_end: &[2], ..desc(&f, &ranges) }, "names surface triangle 1");
        let short = [&f.ranges[..1]];
        check(desc(&f, &short), "brick 0: 1 block range values");
        let mut out = vec![0.0; 3];
        let e = brick_block_ranges(&[0.0; 36], &[2, 2, 9], &mut out).unwrap_err();
        assert!(e.contains("block ranges holds 3 values, 4 expected"), "{e}");
        let e = brick_block_ranges(&[0.0; 35], &[2, 2, 9], &mut out).unwrap_err();
        assert!(e.contains("35 texels for a 2x2x9 brick"), "{e}");
        assert!(block_ranges_len(&[usize::MAX, 2, 1]).unwrap_err().contains("more texels than memory holds"));
        assert!(block_ranges_len(&[2, 2]).unwrap_err().contains("2 texel counts for a brick"));
    }
}
