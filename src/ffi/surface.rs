//! Surface data integration (paper 1, step 2): the isosurface the Hybrid
//! Octree holds, extracted from the image it was built from, and handed to
//! the host as a mesh ([`HybridOctreeHandle::surface_mesh`], for a
//! vtkPolyData) or as GPU triangles ([`HybridOctreeHandle::surface_triangles`]).

use super::grid::{grid_of, same_image};
use super::guard::{check_len, guarded, Bridged};
use super::octree::{next_id, HybridOctreeHandle};
use super::{GridDesc, SurfaceMode, SurfaceSummary};
use crate::error::{Error, Result};
use crate::surface::{distance, Surface, SurfaceOptions};

/// The extraction options of the bridge's surface mode.
fn surface_options(mode: SurfaceMode, isovalue: f64) -> Result<SurfaceOptions> {
    match mode {
        SurfaceMode::Discretized => Ok(SurfaceOptions::discretized(isovalue)),
        SurfaceMode::Interpolated => Ok(SurfaceOptions::interpolated(isovalue)),
        _ => Err(Error::InvalidArgument("unknown surface mode code from C++".into())),
    }
}

/// A node id or level as the `int` of a VTK cell array.
fn fits_int(v: u32) -> Result<i32> {
    i32::try_from(v).map_err(|_| {
        Error::InvalidArgument(
            "the octree has more than 2^31 nodes, whose ids do not fit the int cell array 'node'; use a larger \
             LeafSize"
                .into(),
        )
    })
}

impl HybridOctreeHandle {
    pub(crate) fn integrate_surface(
        &mut self,
        bytes: &[u8],
        desc: &GridDesc,
        isovalue: f64,
        mode: SurfaceMode,
        measure_distance: bool,
    ) -> Bridged<SurfaceSummary> {
        guarded(|| {
            self.hybrid.surface = None;
            self.surface_id = 0;
            let grid = grid_of(bytes, desc)?;
            same_image(&self.shape, &grid)?;
            let surface = Surface::extract(&grid, self.volume(), &surface_options(mode, isovalue)?)?;
            let (distance_mean, distance_max) = if measure_distance {
                let d = distance::discretized_to_interpolated(&grid, self.volume(), isovalue)?;
                (d.mean, d.max)
            } else {
                (-1.0, -1.0)
            };
            let summary = surface_summary(&surface, distance_mean, distance_max);
            self.hybrid.surface = Some(surface);
            self.surface_id = next_id();
            Ok(summary)
        })
    }

    pub(crate) fn remove_surface(&mut self) -> Bridged<()> {
        guarded(|| {
            self.hybrid.surface = None;
            self.surface_id = 0;
            Ok(())
        })
    }

    /// The surface held, or the error naming what to do first.
    pub(crate) fn surface(&self) -> Result<&Surface> {
        self.hybrid
            .surface
            .as_ref()
            .ok_or_else(|| Error::InvalidArgument("the Hybrid Octree holds no surface: integrate one first".into()))
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn surface_mesh(
        &self,
        points: &mut [f64],
        normals: &mut [f32],
        offsets: &mut [i64],
        connectivity: &mut [i64],
        polygon_node: &mut [i32],
        polygon_level: &mut [i32],
        polygon_face: &mut [i64],
    ) -> Bridged<()> {
        guarded(|| {
            let s = self.surface()?;
            let (vertices, polygons) = (s.points.len(), s.polygon_count());
            check_len("points", points, 3 * vertices)?;
            check_len("normals", normals, 3 * vertices)?;
            check_len("offsets", offsets, polygons + 1)?;
            check_len("connectivity", connectivity, s.connectivity.len())?;
            check_len("polygon nodes", polygon_node, polygons)?;
            check_len("polygon levels", polygon_level, polygons)?;
            check_len("polygon faces", polygon_face, polygons)?;
            for (node, to) in s.polygon_node.iter().zip(polygon_node.iter_mut()) {
                *to = fits_int(node.0)?;
            }
            for (node, to) in s.polygon_node.iter().zip(polygon_level.iter_mut()) {
                *to = fits_int(self.volume().node(*node).level as u32)?;
            }
            for (p, to) in s.points.iter().zip(points.chunks_exact_mut(3)) {
                to.copy_from_slice(&self.shape.world(*p));
            }
            for (n, to) in s.normals.iter().zip(normals.chunks_exact_mut(3)) {
                to.copy_from_slice(n);
            }
            offsets[0] = 0; // an empty surface may keep no offsets at all
            for (&o, to) in s.offsets.iter().zip(offsets.iter_mut()) {
                *to = o as i64;
            }
            for (&c, to) in s.connectivity.iter().zip(connectivity.iter_mut()) {
                *to = c as i64;
            }
            for (&f, to) in s.polygon_face.iter().zip(polygon_face.iter_mut()) {
                *to = i64::from(f);
            }
            Ok(())
        })
    }

    pub(crate) fn surface_triangles(&self, vertices: &mut [f32], indices: &mut [u32]) -> Bridged<()> {
        guarded(|| {
            let s = self.surface()?;
            check_len("surface vertices", vertices, 6 * s.points.len())?;
            check_len("surface triangle indices", indices, 3 * s.polygon_count())?;
            for i in 0..s.polygon_count() {
                let polygon = s.polygon(i);
                if polygon.len() != 3 {
                    return Err(Error::Internal(format!("surface polygon {i} is not a triangle")));
                }
                indices[3 * i..3 * i + 3].copy_from_slice(polygon);
            }
            for ((p, n), to) in s.points.iter().zip(&s.normals).zip(vertices.chunks_exact_mut(6)) {
                let world = self.shape.world(*p);
                to[..3].copy_from_slice(&world.map(|c| c as f32));
                to[3..].copy_from_slice(n);
            }
            Ok(())
        })
    }
}

/// `surface`'s sizes and statistics for the host.
fn surface_summary(surface: &Surface, distance_mean: f64, distance_max: f64) -> SurfaceSummary {
    let st = &surface.stats;
    SurfaceSummary {
        vertices: surface.points.len(),
        polygons: surface.polygon_count(),
        connectivity: surface.connectivity.len(),
        faces: st.faces as u64,
        triangles: st.triangles as u64,
        uncompressed_triangles: st.uncompressed_triangles as u64,
        boundary_edges: st.boundary_edges as u64,
        extract_ms: st.extract_ms,
        compress_ms: st.compress_ms,
        distance_mean,
        distance_max,
    }
}
