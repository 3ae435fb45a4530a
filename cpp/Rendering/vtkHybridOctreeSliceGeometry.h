/**
 * @file   vtkHybridOctreeSliceGeometry.h
 * @brief  View-aligned slice polygons clipped to a brick's box (private to the module).
 *
 * The Hybrid Octree, section 3: each brick is drawn as the polygons of the
 * view-aligned planes through it, back to front. The plane of view depth z
 * is {x : (x - eye) . forward = z}; its polygon inside the box is the convex
 * hull of the points where the plane meets the box's 12 edges, ordered by
 * angle around their centroid in the (right, up) basis of the view and
 * emitted as a triangle fan.
 */
#ifndef vtkHybridOctreeSliceGeometry_h
#define vtkHybridOctreeSliceGeometry_h

#include <cstddef>
#include <vector>

namespace vtkHybridOctreeSliceGeometry
{
/// Unit `right = forward x viewUp` and `up = right x forward`.
void ViewBasis(const double forward[3], const double viewUp[3], double right[3], double up[3]);

/**
 * Appends the polygon of the plane {x : (x - eye) . forward = depth} inside
 * the box `bounds` (VTK order: xmin, xmax, ymin, ymax, zmin, zmax) to `out`
 * as triangles, 3 floats per vertex; returns the vertices appended (0 when
 * the plane misses the box or touches it in fewer than 3 points).
 */
std::size_t AppendSlicePolygon(const double bounds[6], const double eye[3], const double forward[3],
  const double right[3], const double up[3], double depth, std::vector<float>& out);
}

#endif
