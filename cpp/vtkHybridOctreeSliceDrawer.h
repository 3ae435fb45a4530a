/**
 * @file   vtkHybridOctreeSliceDrawer.h
 * @brief  The bricks' view-aligned slices drawn with OpenGL (private to the module).
 *
 * The Hybrid Octree, section 3: a brick of level p is drawn as slices every
 * d = stride * d0 along the view, its texture sampled trilinearly at
 *
 *     u_a = clamp((x_a - lo_a) / (stride * spacing_a), 0, texels_a - 1)   (texels)
 *
 * the value looked up in the transfer-function table and the opacity
 * corrected for the slice spacing, `a' = 1 - (1 - a)^(d / d0)`, blended
 * premultiplied back to front: `C = (c a', a') + (1 - a') C`.
 * Exactly the CPU compositor's sampling of the same DrawList.
 */
#ifndef vtkHybridOctreeSliceDrawer_h
#define vtkHybridOctreeSliceDrawer_h

#include "vtkHybridOctreeBridge.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <string>
#include <vector>

class vtkMatrix4x4;
class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;

class vtkHybridOctreeSliceDrawer
{
public:
  vtkHybridOctreeSliceDrawer();
  ~vtkHybridOctreeSliceDrawer();

  /// The slice polygons of every brick of `list` for a camera at `eye` with
  /// `viewUp` (model coordinates), on the CPU: brick i's slices clipped to
  /// `bounds[6i .. 6i+6]` (inside its box), none where `drawn[i]` is 0.
  void Build(const vtkHybridOctreeBridge::DrawList& list, const std::vector<double>& bounds,
    const std::vector<char>& drawn, const double eye[3], const double viewUp[3]);

  /**
   * Makes the slice program current: `mcdc` the model-to-clip matrix,
   * `table` the transfer-function table (RGBA over [lo, hi] in `entries`
   * cells). Uploads the polygons of the last Build() on the first call after
   * it. False and `error` on failure.
   */
  bool Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc, vtkTextureObject* table,
    int entries, double lo, double hi, std::string& error);

  /// Sets brick `i` of the built list as the one drawn, sampling `texture`.
  void UseBrick(const vtkHybridOctreeBridge::DrawList& list, std::size_t i,
    const double spacing[3], vtkTextureObject* texture);

  /// Draws slices `from .. to` (indices into the list's Slices) of the brick in use.
  void DrawSlices(std::size_t from, std::size_t to);

  /// Unbinds the vertex arrays.
  void Unbind();

  /// Frees the buffers (the context is going away).
  void ReleaseGraphicsResources();

private:
  vtkHybridOctreeSliceDrawer(const vtkHybridOctreeSliceDrawer&) = delete;
  vtkHybridOctreeSliceDrawer& operator=(const vtkHybridOctreeSliceDrawer&) = delete;

  std::vector<float> VertexData;
  /// Slice s's vertices: SliceFirst[s] .. SliceFirst[s + 1].
  std::vector<std::size_t> SliceFirst;
  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;
  vtkShaderProgram* Program = nullptr;
  bool Uploaded = false;
};

#endif
