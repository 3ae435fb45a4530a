/**
 * @class   vtkHybridOctreeFilter
 * @brief   Builds the Volume Octree of an image and outputs the boxes of its
 *          cut at an error tolerance and the isosurface the octree keeps.
 *
 * vtkHybridOctreeFilter takes a vtkImageData with point scalars, hands the
 * scalar array (borrowed, not copied) to the Rust Hybrid Octree core, which
 * builds the Volume Octree with per-node nodal errors (The Hybrid Octree,
 * section 2.1), and outputs the cut of that octree at ErrorTolerance: the
 * first nodes from the root whose normalised nodal error E_0 is at most the
 * tolerance, or that are terminal (homogeneous nodes and leaf bricks). The
 * boxes of a cut tile the image exactly once.
 *
 * Output port 0 ("Boxes"): a vtkPolyData with, for box `b` of the cut, the 8 corner points
 * `8b .. 8b+7` (corner `c` at x[c & 1], y[(c >> 1) & 1], z[(c >> 2) & 1]) and
 * the 12 line cells `12b .. 12b+11` of its outline. Cell arrays, repeated on
 * the 12 lines of a box: "node" (id of the octree node in the level-by-level
 * numbering, as on the surface output), "level"
 * (0 = root), "nodal_error" (E_0 / data range), "min", "max" (scalar range of
 * the node, NaN left out; NaN for a box of NaN only). Field data:
 * "node_count", "terminal_count", "homogeneous_count", "levels", "leaf_size",
 * "root_size", "octree_bytes", "input_bytes", "build_ms", "value_min",
 * "value_max", "nan_samples" (NaN samples: no data), "cut_count".
 *
 * NaN samples are no data: transparent, left out of ranges and errors,
 * outside the isosurface (cells touching NaN have no facets). Infinite
 * samples and an image of NaN only ("no data") are errors.
 *
 * Output port 1 ("Surface"): the isosurface at Isovalue that the Hybrid
 * Octree keeps, extracted per terminal node (The Hybrid Octree, section 2.2).
 * SurfaceMode chooses it: Discretized (default) is the Discretized Marching
 * Cubes surface (vertices at edge midpoints) with each region of coplanar
 * facets in a node merged into one face, losslessly, and the face
 * triangulated with its own vertices (no T-junctions): far fewer triangles;
 * Interpolated is the
 * classic Marching Cubes surface with vertices interpolated along the edges
 * (the vertices vtkFlyingEdges3D produces), triangles only. Points are
 * doubles; point data "Normals" (float, 3 components, unit length, pointing
 * from values >= Isovalue towards values below it) is the active normals
 * array; polygons are triangles. Cell arrays: "node" (id of the terminal
 * octree node holding the triangle, in the level-by-level numbering), "level"
 * and "face" (the merged coplanar face the triangle belongs to: color by it
 * to see the compression).
 * Field data: "isovalue", "surface_mode" (string: "discretized" or
 * "interpolated"), "polygons" (= "triangles"), "faces" (merged coplanar
 * faces), "triangles",
 * "uncompressed_triangles" (before facets are merged), "vertices",
 * "boundary_edges" (edges of one polygon only: 0 for a closed surface),
 * "extract_ms", "compress_ms", "distance_mean", "distance_max" (sampled
 * symmetric distance between the discretized and the interpolated surface in
 * voxels, -1 when MeasureSurfaceDistance is off). An Isovalue outside the data
 * range gives an empty surface, not an error.
 *
 * The input array is chosen with SetInputArrayToProcess (default: the point
 * scalars). Supported types: (un)signed char, short, int, float, double.
 * Multi-component arrays need SetComponent().
 *
 * The built octree is cached: changing only ErrorTolerance re-cuts the cached
 * octree without rebuilding it (see GetOctreeBuildCount()). It is rebuilt when
 * the input array (object or values), the image geometry, LeafSize or
 * Component change. The surface is cached too: it is extracted again only
 * when the octree was rebuilt or Isovalue, SurfaceMode or
 * MeasureSurfaceDistance changed (see GetSurfaceExtractCount()), not when
 * only ErrorTolerance changed.
 *
 * Errors (no image, no point scalars, unsupported type, infinite samples, a 1-wide
 * axis, a non-finite Isovalue, ...) are reported with vtkErrorMacro and fail
 * the request with both outputs empty.
 *
 * Progress (vtkCommand::ProgressEvent, ParaView's progress bar): the octree
 * build reports 0 .. 0.8 as its leaf bricks are done, the surface 0.9, the
 * end 1. Abort (SetAbortExecute(1), read with CheckAbort()) is honoured
 * between chunks of leaf bricks: the build stops, nothing of it is kept, and
 * the request ends with both outputs empty, marked ABORTED, and a warning.
 * ParaView 5.11's abort button does not reach filters (its
 * pqProgressManager only emits a Qt signal nothing listens to), so there the
 * abort comes from code, e.g. a progress observer.
 */
#ifndef vtkHybridOctreeFilter_h
#define vtkHybridOctreeFilter_h

#include "HybridOctreeFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkDataArray;
class vtkImageData;
class vtkPolyData;

class HYBRIDOCTREEFILTERS_EXPORT vtkHybridOctreeFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkHybridOctreeFilter* New();
  vtkTypeMacro(vtkHybridOctreeFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Cells per axis of a leaf brick: a power of two from 2 to 256 (default 16).
   * Values in range that are not powers of two make RequestData fail.
   */
  vtkSetClampMacro(LeafSize, int, 2, 256);
  vtkGetMacro(LeafSize, int);
  ///@}

  ///@{
  /**
   * Nodal error tolerance as a fraction of the data range, 0 to 1 (default
   * 0.01). The cut stops at nodes whose E_0 is at most this value. Changing
   * it does not rebuild the octree.
   */
  vtkSetClampMacro(ErrorTolerance, double, 0.0, 1.0);
  vtkGetMacro(ErrorTolerance, double);
  ///@}

  ///@{
  /**
   * Component of a multi-component input array to build from; -1 (default)
   * means none, which only 1-component arrays accept.
   */
  vtkSetClampMacro(Component, int, -1, VTK_INT_MAX);
  vtkGetMacro(Component, int);
  ///@}

  /// Values of SurfaceMode.
  enum SurfaceModes
  {
    /// Discretized Marching Cubes, coplanar facets merged (lossless).
    SURFACE_MODE_DISCRETIZED = 0,
    /// Classic Marching Cubes with interpolated vertices.
    SURFACE_MODE_INTERPOLATED = 1
  };

  ///@{
  /**
   * Isovalue of the surface on output port 1 (default 0). A value outside the
   * data range gives an empty surface; a NaN or infinite isovalue makes RequestData fail.
   */
  vtkSetMacro(Isovalue, double);
  vtkGetMacro(Isovalue, double);
  ///@}

  ///@{
  /**
   * Which isosurface output port 1 holds: SURFACE_MODE_DISCRETIZED (0,
   * default) is the Discretized Marching Cubes surface the Hybrid Octree keeps:
   * vertices at edge midpoints, so within about half a voxel of the
   * interpolated surface, with coplanar facets merged into faces and
   * re-triangulated, which leaves far fewer triangles to draw. SURFACE_MODE_INTERPOLATED (1) is
   * the classic Marching Cubes surface: exact vertices, more triangles.
   */
  vtkSetClampMacro(SurfaceMode, int, SURFACE_MODE_DISCRETIZED, SURFACE_MODE_INTERPOLATED);
  vtkGetMacro(SurfaceMode, int);
  void SetSurfaceModeToDiscretized() { this->SetSurfaceMode(SURFACE_MODE_DISCRETIZED); }
  void SetSurfaceModeToInterpolated() { this->SetSurfaceMode(SURFACE_MODE_INTERPOLATED); }
  /// "discretized" or "interpolated".
  const char* GetSurfaceModeAsString() const;
  ///@}

  ///@{
  /**
   * Whether to measure the distance between the discretized and the
   * interpolated surface (field data "distance_mean", "distance_max", in
   * voxels; default on). Measuring extracts both surfaces, which costs extra
   * time; off, both values are -1.
   */
  vtkSetMacro(MeasureSurfaceDistance, vtkTypeBool);
  vtkGetMacro(MeasureSurfaceDistance, vtkTypeBool);
  vtkBooleanMacro(MeasureSurfaceDistance, vtkTypeBool);
  ///@}

  /**
   * Number of times this filter has built a Volume Octree. A request that
   * reuses the cached octree (for example after only ErrorTolerance changed)
   * does not increase it.
   */
  vtkGetMacro(OctreeBuildCount, vtkIdType);

  /**
   * Number of times this filter has extracted an isosurface. A request that
   * reuses the cached surface (for example after only ErrorTolerance
   * changed) does not increase it.
   */
  vtkGetMacro(SurfaceExtractCount, vtkIdType);

protected:
  vtkHybridOctreeFilter();
  ~vtkHybridOctreeFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int LeafSize = 16;
  double ErrorTolerance = 0.01;
  int Component = -1;
  double Isovalue = 0.0;
  int SurfaceMode = SURFACE_MODE_DISCRETIZED;
  vtkTypeBool MeasureSurfaceDistance = 1;
  vtkIdType OctreeBuildCount = 0;
  vtkIdType SurfaceExtractCount = 0;

private:
  vtkHybridOctreeFilter(const vtkHybridOctreeFilter&) = delete;
  void operator=(const vtkHybridOctreeFilter&) = delete;

  /// The scalar array to build from, or nullptr after reporting why not.
  vtkDataArray* GetScalars(vtkImageData* image, vtkInformationVector** inputVector);
  /// Builds the octree unless the cached one was built from the same inputs,
  /// reporting progress and honouring abort (GetAbortOutput() then true).
  bool UpdateOctree(vtkImageData* image, vtkDataArray* scalars);
  /// Extracts the surface unless the cached one has the same octree and settings.
  bool UpdateSurface(vtkDataArray* scalars);
  /// Fills `output` with the boxes of the cut at ErrorTolerance.
  bool FillBoxes(vtkPolyData* output);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
