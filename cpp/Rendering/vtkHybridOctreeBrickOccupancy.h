/**
 * @file   vtkHybridOctreeBrickOccupancy.h
 * @brief  Which part of a brick the transfer function leaves visible (private to the module).
 *
 * A slice fragment whose value maps to opacity 0 adds nothing, but a
 * software rasteriser pays for it all the same. Each resident brick keeps,
 * per block of 4x4x4 texel cells, the range [min, max] of its texels
 * (measured once, at upload). Trilinear interpolation inside a cell stays
 * within its corners' range, so a block is invisible when the transfer
 * function's opacity is 0 over its whole range; the brick's slices are then
 * clipped to the box of its visible blocks, and a brick with none is not
 * drawn. The picture is unchanged (only transparent samples go).
 */
#ifndef vtkHybridOctreeBrickOccupancy_h
#define vtkHybridOctreeBrickOccupancy_h

#include <cstddef>
#include <vector>

/// The zero-opacity test of a transfer-function table of `n` cells over
/// [lo, hi] (cell k at lo + (hi - lo) k / (n - 1), linear between cells,
/// clamped at the ends, as the shader samples it).
class vtkHybridOctreeOpacityTable
{
public:
  /// `rgba`: the table, 4 floats a cell.
  void Set(const std::vector<float>& rgba, double lo, double hi);
  /// True when some value in [a, b] has opacity above 0.
  bool AnyVisible(double a, double b) const;

private:
  /// NonZero[k]: cells with opacity > 0 among the first k.
  std::vector<std::size_t> NonZero;
  double Lo = 0.0;
  double Hi = 1.0;
};

class vtkHybridOctreeBrickOccupancy
{
public:
  /// Cells per block edge.
  static constexpr std::size_t BlockCells = 4;

  /// Measures the block ranges of `texels` (x fastest), `dims` texels per axis.
  void Measure(const std::vector<float>& texels, const std::size_t dims[3]);

  /**
   * The box of the visible blocks under `table`, in texel coordinates
   * [lo[a], hi[a]] per axis; false (and nothing to draw) when no block is
   * visible.
   */
  bool VisibleBox(const vtkHybridOctreeOpacityTable& table, double lo[3], double hi[3]) const;

private:
  std::size_t Dims[3] = { 0, 0, 0 };
  std::size_t Blocks[3] = { 0, 0, 0 };
  std::vector<float> Min;
  std::vector<float> Max;
};

#endif
