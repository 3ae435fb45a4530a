#include "vtkHybridOctreeBrickOccupancy.h"

#include <algorithm>
#include <cmath>
#include <limits>

void vtkHybridOctreeOpacityTable::Set(const std::vector<float>& rgba, double lo, double hi)
{
  const std::size_t n = rgba.size() / 4;
  this->NonZero.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    this->NonZero[k + 1] = this->NonZero[k] + (rgba[4 * k + 3] > 0.0f ? 1 : 0);
  }
  this->Lo = lo;
  this->Hi = hi;
}

bool vtkHybridOctreeOpacityTable::AnyVisible(double a, double b) const
{
  const std::size_t n = this->NonZero.size() - 1;
  // The empty range (+inf, -inf) of a block of NaN only, and NaN bounds: no data.
  if (n == 0 || !(a <= b))
  {
    return false;
  }
  // Opacity is linear between table cells, so it is 0 over [a, b] only when
  // every cell from floor(a) to ceil(b) (in cell units, clamped) has opacity 0.
  const double scale = (n - 1) / (this->Hi - this->Lo);
  const double ka = std::floor((a - this->Lo) * scale);
  const double kb = std::ceil((b - this->Lo) * scale);
  const double last = static_cast<double>(n - 1);
  const std::size_t first = static_cast<std::size_t>(std::min(std::max(ka, 0.0), last));
  const std::size_t end = static_cast<std::size_t>(std::min(std::max(kb, 0.0), last)) + 1;
  return end > first && this->NonZero[end] > this->NonZero[first];
}

void vtkHybridOctreeBrickOccupancy::Measure(
  const std::vector<float>& texels, const std::size_t dims[3])
{
  for (int a = 0; a < 3; ++a)
  {
    this->Dims[a] = dims[a];
    this->Blocks[a] = dims[a] > 1 ? (dims[a] - 2) / BlockCells + 1 : 1;
  }
  const std::size_t blocks = this->Blocks[0] * this->Blocks[1] * this->Blocks[2];
  this->Min.assign(blocks, std::numeric_limits<float>::infinity());
  this->Max.assign(blocks, -std::numeric_limits<float>::infinity());
  // Texel t is a corner of cells t - 1 and t; cell c lies in block c / B.
  auto blocksOf = [](std::size_t t, std::size_t dim, std::size_t out[2]) {
    std::size_t n = 0;
    if (dim == 1)
    {
      out[n++] = 0;
      return n;
    }
    if (t > 0)
    {
      out[n++] = (t - 1) / BlockCells;
    }
    if (t + 1 < dim && (n == 0 || out[0] != t / BlockCells))
    {
      out[n++] = t / BlockCells;
    }
    return n;
  };
  for (std::size_t z = 0; z < dims[2]; ++z)
  {
    std::size_t bz[2];
    const std::size_t nz = blocksOf(z, dims[2], bz);
    for (std::size_t y = 0; y < dims[1]; ++y)
    {
      std::size_t by[2];
      const std::size_t ny = blocksOf(y, dims[1], by);
      for (std::size_t x = 0; x < dims[0]; ++x)
      {
        std::size_t bx[2];
        const std::size_t nx = blocksOf(x, dims[0], bx);
        const float v = texels[x + dims[0] * (y + dims[1] * z)];
        if (std::isnan(v))
        {
          continue; // no data: left out of the range
        }
        for (std::size_t k = 0; k < nz; ++k)
        {
          for (std::size_t j = 0; j < ny; ++j)
          {
            for (std::size_t i = 0; i < nx; ++i)
            {
              const std::size_t b = bx[i] + this->Blocks[0] * (by[j] + this->Blocks[1] * bz[k]);
              this->Min[b] = std::min(this->Min[b], v);
              this->Max[b] = std::max(this->Max[b], v);
            }
          }
        }
      }
    }
  }
}

bool vtkHybridOctreeBrickOccupancy::VisibleBox(
  const vtkHybridOctreeOpacityTable& table, double lo[3], double hi[3]) const
{
  std::size_t first[3] = { this->Blocks[0], this->Blocks[1], this->Blocks[2] };
  std::size_t last[3] = { 0, 0, 0 };
  bool any = false;
  for (std::size_t z = 0; z < this->Blocks[2]; ++z)
  {
    for (std::size_t y = 0; y < this->Blocks[1]; ++y)
    {
      for (std::size_t x = 0; x < this->Blocks[0]; ++x)
      {
        const std::size_t b = x + this->Blocks[0] * (y + this->Blocks[1] * z);
        if (!table.AnyVisible(this->Min[b], this->Max[b]))
        {
          continue;
        }
        any = true;
        const std::size_t at[3] = { x, y, z };
        for (int a = 0; a < 3; ++a)
        {
          first[a] = std::min(first[a], at[a]);
          last[a] = std::max(last[a], at[a]);
        }
      }
    }
  }
  if (!any)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    const double top = this->Dims[a] > 0 ? static_cast<double>(this->Dims[a] - 1) : 0.0;
    lo[a] = static_cast<double>(first[a] * BlockCells);
    hi[a] = std::min(top, static_cast<double>((last[a] + 1) * BlockCells));
  }
  return true;
}
