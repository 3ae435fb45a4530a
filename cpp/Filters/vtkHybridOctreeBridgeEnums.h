/**
 * @file   vtkHybridOctreeBridgeEnums.h
 * @brief  The enums shared with the Rust bridge, defined once.
 *
 * The bridge (src/ffi/mod.rs) declares these enums as C++ types: cxx checks
 * at compile time that its variants, values and integer type match these
 * definitions, and the generated header uses these types. Plain C++: no cxx
 * type, so vtkHybridOctreeBridge.h may include it.
 */
#ifndef vtkHybridOctreeBridgeEnums_h
#define vtkHybridOctreeBridgeEnums_h

#include <cstdint>

namespace hybrid_octree
{

/// Scalar types the Rust core reads (VTK_UNSIGNED_CHAR -> U8, ...; see
/// vtkHybridOctreeImageInput::ToBridgeType()).
enum class ScalarType : std::uint8_t
{
  U8 = 0,
  I8 = 1,
  U16 = 2,
  I16 = 3,
  U32 = 4,
  I32 = 5,
  F32 = 6,
  F64 = 7
};

/// Which isosurface the Hybrid Octree keeps.
enum class SurfaceMode : std::uint8_t
{
  /// Discretized Marching Cubes: vertices at edge midpoints, coplanar facets
  /// merged into faces and re-triangulated (lossless).
  Discretized = 0,
  /// Classic Marching Cubes: vertices linearly interpolated along edges.
  Interpolated = 1
};

} // namespace hybrid_octree

#endif
