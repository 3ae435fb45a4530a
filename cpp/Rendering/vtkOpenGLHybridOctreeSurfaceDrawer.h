/**
 * @file   vtkOpenGLHybridOctreeSurfaceDrawer.h
 * @brief  The Hybrid Octree's isosurface drawn with OpenGL (private to the module).
 *
 * The Hybrid Octree, section 3.3: an opaque surface is drawn before the
 * volume, with depth test and write, so that the volume behind it is hidden
 * (a translucent one is drawn in the slabs by vtkOpenGLHybridOctreeBrickDrawer,
 * from this drawer's vertex and index data).
 *
 * While the camera moves, a translucent surface is drawn by this drawer into
 * the float target brick by brick, without slabs (the bricks ray-marched
 * back to front, see vtkHybridOctreeVolumeMapper), tested against the
 * target's copy of the opaque depth. A brick's triangles go either before
 * its volume or after it, each triangle by the side of it the eye is on:
 * the volume between a triangle and the eye lies on that side, so the
 * triangle goes before the brick's volume (behind it) when that side is the
 * more opaque one (the inside, values above the isovalue, into which the
 * vertex normals -grad f do not point, or the outside), else after it.
 * Exact for a brick whose eye-side volume is all on one side of its
 * triangles; the slabs put each triangle between the right slices again in
 * the next still frame.
 *
 * Shading is the CPU compositor's headlight Lambert, `rgb = colour |n . d|`
 * with `n` the interpolated vertex normal and `d` the viewing ray's
 * direction.
 *
 * Triangle `t` of the DrawList (a polygon id of the surface mesh) is drawn as
 * indices `3t .. 3t + 3` of the element buffer.
 */
#ifndef vtkOpenGLHybridOctreeSurfaceDrawer_h
#define vtkOpenGLHybridOctreeSurfaceDrawer_h

#include "vtkHybridOctreeBridge.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

class vtkOpenGLHybridOctreeFloatTarget;
class vtkMatrix4x4;
class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;

class vtkOpenGLHybridOctreeSurfaceDrawer
{
public:
  vtkOpenGLHybridOctreeSurfaceDrawer();
  ~vtkOpenGLHybridOctreeSurfaceDrawer();

  /// Loads the surface `octree` holds into buffers (the core writes the
  /// triangles into them); false and `error` otherwise.
  bool Upload(const vtkHybridOctreeBridge::HybridOctree& octree, std::string& error);

  /// Triangles loaded.
  std::size_t GetNumberOfTriangles() const { return this->Triangles; }
  /// The loaded vertices, 6 floats each (position, normal).
  const std::vector<float>& GetVertexData() const { return this->VertexData; }
  /// The loaded triangles' vertex ids, 3 a triangle.
  const std::vector<unsigned int>& GetIndexData() const { return this->IndexData; }

  /**
   * Makes the surface program current for a frame: `mcdc` the model-to-clip
   * matrix, `eye`, `forward` and `parallel` the DrawList's camera (model
   * coordinates), `rgba` colour and opacity; with `target` (bound, its depth
   * texture active), fragments behind its copy of the opaque depth are
   * dropped. False and `error` when the program does not compile.
   */
  bool Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc, const double eye[3],
    const double forward[3], bool parallel, const double rgba[4], std::string& error,
    vtkOpenGLHybridOctreeFloatTarget* target = nullptr);

  /// Makes the program and buffers of the last Bind() current again (after another program drew).
  void Rebind(vtkOpenGLRenderWindow* window);

  /**
   * Orders the triangles of `list`'s bricks for drawing them brick by
   * brick: brick i's (the union of its batches) split into those before
   * its volume and those after it (see the file documentation), for a camera
   * at `eye` looking along `forward` (model coordinates; `parallel`: every
   * ray along `forward`), the inside (values above the isovalue) the more
   * opaque side when `insideOpaque`. Loaded on the next Bind() with a target.
   */
  void OrderByBrick(const vtkHybridOctreeBridge::DrawList& list, const double eye[3],
    const double forward[3], bool parallel, bool insideOpaque);

  /// The triangles of OrderByBrick() drawn between the volume of brick
  /// i - 1 and that of brick i (i = 0: before the first; i = the number of
  /// bricks: after the last), as Draw()'s range [first, end).
  std::pair<std::size_t, std::size_t> GetTrianglesBefore(std::size_t i) const;

  /// Draws triangles `first .. end` (OrderByBrick()'s with a target). The program must be bound.
  void Draw(std::size_t first, std::size_t end);

  /// Unbinds the vertex arrays.
  void Unbind();

  /// Frees the buffers (the context is going away).
  void ReleaseGraphicsResources();

private:
  vtkOpenGLHybridOctreeSurfaceDrawer(const vtkOpenGLHybridOctreeSurfaceDrawer&) = delete;
  vtkOpenGLHybridOctreeSurfaceDrawer& operator=(const vtkOpenGLHybridOctreeSurfaceDrawer&) = delete;

  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLBufferObject> Indices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;
  /// The order of OrderByBrick(): brick i's triangles before its volume are
  /// BrickOrder[BrickParts[2i] .. BrickParts[2i+1]), after it up to BrickParts[2i+2].
  std::vector<unsigned int> BrickOrder;
  std::vector<std::size_t> BrickParts;
  bool BrickOrderUploaded = false;
  vtkSmartPointer<vtkOpenGLBufferObject> BrickIndices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> BrickVao;
  vtkOpenGLVertexArrayObject* Bound = nullptr;
  vtkShaderProgram* Program = nullptr;
  std::vector<float> VertexData;
  std::vector<unsigned int> IndexData;
  bool Uploaded = false;
  std::size_t Triangles = 0;
};

#endif
