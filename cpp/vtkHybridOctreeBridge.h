/**
 * @file   vtkHybridOctreeBridge.h
 * @brief  Plain C++ view of the Rust Hybrid Octree core (private to the module).
 *
 * The VTK classes of this module call the Rust crate only through this
 * header. It holds no cxx type: vtkHybridOctreeBridge.cxx is the only file
 * that includes the cxx-generated `hybrid-octree/src/ffi.rs.h`, converts
 * between these structs and the bridge's, and turns every `rust::Error`
 * (a `std::exception`) into an error string the caller reports with
 * vtkErrorMacro.
 *
 * Volume samples cross borrowed: Build() and ExtractSurface() read the
 * caller's buffer while they run and keep no pointer to it.
 */
#ifndef vtkHybridOctreeBridge_h
#define vtkHybridOctreeBridge_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vtkHybridOctreeBridge
{

/// Scalar types the Rust core reads (VTK_UNSIGNED_CHAR -> U8, ...).
enum class ScalarType
{
  U8,
  I8,
  U16,
  I16,
  U32,
  I32,
  F32,
  F64
};

/// Layout of a borrowed image: point dims, spacing, origin of the first
/// sample, components per tuple and the chosen component (-1: none, allowed
/// only for 1-component arrays).
struct GridDescription
{
  ScalarType Type = ScalarType::F32;
  std::size_t Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  std::size_t Components = 1;
  int Component = -1;
};

/// Summary of a built Volume Octree (see OctreeSummary in src/ffi.rs).
struct OctreeSummary
{
  std::uint64_t NodeCount = 0;
  std::uint64_t TerminalCount = 0;
  std::uint64_t HomogeneousCount = 0;
  std::uint32_t Levels = 0;
  std::uint32_t LeafSize = 0;
  std::uint32_t RootSize = 0;
  std::uint64_t OctreeBytes = 0;
  std::uint64_t InputBytes = 0;
  double BuildMilliseconds = 0.0;
  double ValueMin = 0.0;
  double ValueMax = 0.0;
};

/// The boxes of an octree cut, one entry per node, in world coordinates.
/// `Bounds` holds 6 values per node in VTK order (xmin, xmax, ymin, ymax,
/// zmin, zmax); every other vector holds one value per node.
struct CutBoxes
{
  std::vector<double> Bounds;
  std::vector<std::uint32_t> NodeId; ///< id in the level-by-level numbering
  std::vector<std::uint32_t> Level;
  std::vector<float> NodalError; ///< E_0 normalised by the data range
  std::vector<double> Min;
  std::vector<double> Max;

  std::size_t GetNumberOfBoxes() const { return this->Level.size(); }
};

/// Which isosurface the Hybrid Octree keeps (see SurfaceMode in src/ffi.rs).
enum class SurfaceMode
{
  /// Discretized Marching Cubes: vertices at edge midpoints, coplanar facets
  /// merged into faces and re-triangulated (lossless).
  Discretized,
  /// Classic Marching Cubes: vertices linearly interpolated along edges.
  Interpolated
};

/// An isosurface extracted from a Volume Octree (see SurfaceOutput in
/// src/ffi.rs), world coordinates.
///
/// Sizes: `Points` and `Normals` hold 3 values per vertex; polygon `i` uses
/// `Connectivity[Offsets[i] .. Offsets[i + 1]]`, so `Offsets` holds
/// `Polygons + 1` values starting at 0; `PolygonNode`, `PolygonLevel` and
/// `PolygonFace` hold one value per polygon. Polygons are triangles: the
/// merged coplanar faces triangulated with their own vertices.
struct SurfaceMesh
{
  std::vector<double> Points;
  std::vector<float> Normals; ///< unit, from values >= isovalue towards values below
  std::vector<std::int64_t> Offsets;
  std::vector<std::int64_t> Connectivity;
  std::vector<std::uint32_t> PolygonNode;  ///< terminal node holding the polygon (level-by-level id)
  std::vector<std::uint32_t> PolygonLevel; ///< level of that node (0 = root)
  std::vector<std::uint32_t> PolygonFace;  ///< the merged coplanar face the triangle belongs to
  std::uint64_t Polygons = 0;
  std::uint64_t Faces = 0;                 ///< merged coplanar faces
  std::uint64_t Triangles = 0;             ///< triangles in the output (= Polygons)
  std::uint64_t UncompressedTriangles = 0; ///< before coplanar facets are merged
  std::uint64_t Vertices = 0;
  std::uint64_t BoundaryEdges = 0; ///< edges of one polygon only (0: closed surface)
  double ExtractMilliseconds = 0.0;
  double CompressMilliseconds = 0.0;
  double DistanceMean = -1.0; ///< DiscMC to interpolated surface, voxels; -1: not measured
  double DistanceMax = -1.0;
};

/// A Volume Octree owned on the C++ side (it owns the Rust handle).
class VolumeOctree
{
public:
  ~VolumeOctree();
  VolumeOctree(const VolumeOctree&) = delete;
  VolumeOctree& operator=(const VolumeOctree&) = delete;

  /**
   * Builds the Volume Octree of `byteCount` bytes at `bytes` laid out as
   * `grid`, with leaf bricks of `leafSize` cells per axis. Returns nullptr
   * and sets `error` to the core's message on failure.
   */
  static std::unique_ptr<VolumeOctree> Build(const void* bytes, std::size_t byteCount,
    const GridDescription& grid, unsigned int leafSize, std::string& error);

  /// Node counts, levels, memory and build time. False and `error` on failure.
  bool GetSummary(OctreeSummary& summary, std::string& error) const;

  /// The cut at normalised error tolerance `tolerance` (0..1), replacing the
  /// contents of `boxes`. False and `error` on failure.
  bool GetCutBoxes(double tolerance, CutBoxes& boxes, std::string& error) const;

  /**
   * Extracts the isosurface at `isovalue` of the image the octree was built
   * from: `bytes`, `byteCount` and `grid` must describe the same samples as
   * in Build(). `measureDistance` also measures the distance between the
   * discretized and the interpolated surface. Replaces the contents of
   * `surface`. An isovalue outside the data range gives an empty surface;
   * a non-finite isovalue or a grid that does not match the octree's returns
   * false and sets `error`.
   */
  bool ExtractSurface(const void* bytes, std::size_t byteCount, const GridDescription& grid,
    double isovalue, SurfaceMode mode, bool measureDistance, SurfaceMesh& surface,
    std::string& error) const;

private:
  struct Internals;
  explicit VolumeOctree(std::unique_ptr<Internals> internals);
  std::unique_ptr<Internals> Impl;
};

} // namespace vtkHybridOctreeBridge

#endif
