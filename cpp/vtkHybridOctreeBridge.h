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
 * Volume samples cross borrowed: Build() reads the caller's buffer while it
 * runs and keeps no pointer to it.
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
  std::vector<std::uint32_t> Level;
  std::vector<float> NodalError; ///< E_0 normalised by the data range
  std::vector<double> Min;
  std::vector<double> Max;

  std::size_t GetNumberOfBoxes() const { return this->Level.size(); }
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

private:
  struct Internals;
  explicit VolumeOctree(std::unique_ptr<Internals> internals);
  std::unique_ptr<Internals> Impl;
};

} // namespace vtkHybridOctreeBridge

#endif
