/**
 * @class   vtkHybridOctreeFilter
 * @brief   Builds the Volume Octree of an image and outputs the boxes of its
 *          cut at an error tolerance.
 *
 * vtkHybridOctreeFilter takes a vtkImageData with point scalars, hands the
 * scalar array (borrowed, not copied) to the Rust Hybrid Octree core, which
 * builds the Volume Octree with per-node nodal errors (The Hybrid Octree,
 * section 2.1), and outputs the cut of that octree at ErrorTolerance: the
 * first nodes from the root whose normalised nodal error E_0 is at most the
 * tolerance, or that are terminal (homogeneous nodes and leaf bricks). The
 * boxes of a cut tile the image exactly once.
 *
 * Output: a vtkPolyData with, for box `b` of the cut, the 8 corner points
 * `8b .. 8b+7` (corner `c` at x[c & 1], y[(c >> 1) & 1], z[(c >> 2) & 1]) and
 * the 12 line cells `12b .. 12b+11` of its outline. Cell arrays, repeated on
 * the 12 lines of a box: "node" (index of the box in the cut), "level"
 * (0 = root), "nodal_error" (E_0 / data range), "min", "max" (scalar range of
 * the node). Field data: "node_count", "terminal_count", "homogeneous_count",
 * "levels", "leaf_size", "root_size", "octree_bytes", "input_bytes",
 * "build_ms", "value_min", "value_max", "cut_count".
 *
 * The input array is chosen with SetInputArrayToProcess (default: the point
 * scalars). Supported types: (un)signed char, short, int, float, double.
 * Multi-component arrays need SetComponent().
 *
 * The built octree is cached: changing only ErrorTolerance re-cuts the cached
 * octree without rebuilding it (see GetOctreeBuildCount()). It is rebuilt when
 * the input array (object or values), the image geometry, LeafSize or
 * Component change.
 *
 * Errors (no image, no point scalars, unsupported type, NaN samples, a 1-wide
 * axis, ...) are reported with vtkErrorMacro and fail the request with an
 * empty output.
 */
#ifndef vtkHybridOctreeFilter_h
#define vtkHybridOctreeFilter_h

#include "HybridOctreeFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class vtkDataArray;
class vtkImageData;

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

  /**
   * Number of times this filter has built a Volume Octree. A request that
   * reuses the cached octree (for example after only ErrorTolerance changed)
   * does not increase it.
   */
  vtkGetMacro(OctreeBuildCount, vtkIdType);

protected:
  vtkHybridOctreeFilter();
  ~vtkHybridOctreeFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int LeafSize = 16;
  double ErrorTolerance = 0.01;
  int Component = -1;
  vtkIdType OctreeBuildCount = 0;

private:
  vtkHybridOctreeFilter(const vtkHybridOctreeFilter&) = delete;
  void operator=(const vtkHybridOctreeFilter&) = delete;

  /// The scalar array to build from, or nullptr after reporting why not.
  vtkDataArray* GetScalars(vtkImageData* image, vtkInformationVector** inputVector);
  /// Builds the octree unless the cached one was built from the same inputs.
  bool UpdateOctree(vtkImageData* image, vtkDataArray* scalars);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
