#include "vtkHybridOctreeSliceGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace vtkHybridOctreeSliceGeometry
{
namespace
{
double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

} // namespace

void ViewBasis(const double forward[3], const double viewUp[3], double right[3], double up[3])
{
  right[0] = forward[1] * viewUp[2] - forward[2] * viewUp[1];
  right[1] = forward[2] * viewUp[0] - forward[0] * viewUp[2];
  right[2] = forward[0] * viewUp[1] - forward[1] * viewUp[0];
  const double norm = std::sqrt(Dot(right, right));
  for (int k = 0; k < 3; ++k)
  {
    right[k] = norm > 0.0 ? right[k] / norm : 0.0;
  }
  up[0] = right[1] * forward[2] - right[2] * forward[1];
  up[1] = right[2] * forward[0] - right[0] * forward[2];
  up[2] = right[0] * forward[1] - right[1] * forward[0];
}

std::size_t AppendSlicePolygon(const double bounds[6], const double eye[3], const double forward[3],
  const double right[3], const double up[3], double depth, std::vector<float>& out)
{
  double corners[8][3];
  double dist[8];
  for (int c = 0; c < 8; ++c)
  {
    corners[c][0] = bounds[(c & 1)];
    corners[c][1] = bounds[2 + ((c >> 1) & 1)];
    corners[c][2] = bounds[4 + ((c >> 2) & 1)];
    const double rel[3] = { corners[c][0] - eye[0], corners[c][1] - eye[1],
      corners[c][2] - eye[2] };
    dist[c] = Dot(rel, forward) - depth;
  }
  static const int edges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
    { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
  std::vector<std::array<double, 3>> points;
  for (int c = 0; c < 8; ++c)
  {
    if (dist[c] == 0.0)
    {
      points.push_back({ corners[c][0], corners[c][1], corners[c][2] });
    }
  }
  for (const auto& e : edges)
  {
    const double da = dist[e[0]], db = dist[e[1]];
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
    {
      const double t = da / (da - db);
      std::array<double, 3> p;
      for (int k = 0; k < 3; ++k)
      {
        p[k] = corners[e[0]][k] + t * (corners[e[1]][k] - corners[e[0]][k]);
      }
      points.push_back(p);
    }
  }
  if (points.size() < 3)
  {
    return 0;
  }
  double centre[3] = { 0.0, 0.0, 0.0 };
  for (const auto& p : points)
  {
    for (int k = 0; k < 3; ++k)
    {
      centre[k] += p[k] / static_cast<double>(points.size());
    }
  }
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double rel[3] = { points[i][0] - centre[0], points[i][1] - centre[1],
      points[i][2] - centre[2] };
    order.emplace_back(std::atan2(Dot(rel, up), Dot(rel, right)), i);
  }
  std::sort(order.begin(), order.end());
  std::size_t added = 0;
  for (std::size_t i = 1; i + 1 < order.size(); ++i)
  {
    for (std::size_t j : { order[0].second, order[i].second, order[i + 1].second })
    {
      out.push_back(static_cast<float>(points[j][0]));
      out.push_back(static_cast<float>(points[j][1]));
      out.push_back(static_cast<float>(points[j][2]));
      ++added;
    }
  }
  return added;
}
}
