/**
 * @file   vtkHybridOctreeSurfaceDrawer.h
 * @brief  The Hybrid Octree's isosurface drawn with OpenGL (private to the module).
 *
 * The Hybrid Octree, section 3.3: an opaque surface is drawn before the
 * volume, with depth test and write, so that the volume behind it is hidden
 * (a translucent one is drawn in the slabs by vtkHybridOctreeBrickDrawer,
 * from this drawer's vertex and index data).
 *
 * Shading is the CPU compositor's headlight Lambert, `rgb = colour |n . d|`
 * with `n` the interpolated vertex normal and `d` the viewing ray's
 * direction.
 *
 * Triangle `t` of the DrawList (a polygon id of the surface mesh) is drawn as
 * indices `3t .. 3t + 3` of the element buffer.
 */
#ifndef vtkHybridOctreeSurfaceDrawer_h
#define vtkHybridOctreeSurfaceDrawer_h

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

class vtkHybridOctreeSurfaceDrawer
{
public:
  vtkHybridOctreeSurfaceDrawer();
  ~vtkHybridOctreeSurfaceDrawer();

  /// Loads `mesh` (triangles only) into buffers; false and `error` otherwise.
  bool Upload(const vtkHybridOctreeBridge::SurfaceMesh& mesh, std::string& error);

  /// Triangles loaded.
  std::size_t GetNumberOfTriangles() const { return this->Triangles; }
  /// The loaded vertices, 6 floats each (position, normal).
  const std::vector<float>& GetVertexData() const { return this->VertexData; }
  /// The loaded triangles' vertex ids, 3 a triangle.
  const std::vector<unsigned int>& GetIndexData() const { return this->IndexData; }

  /**
   * Makes the surface program current for a frame: `mcdc` the model-to-clip
   * matrix, `eye`, `forward` and `parallel` the DrawList's camera (model
   * coordinates), `rgba` colour and opacity. False and `error` when the
   * program does not compile.
   */
  bool Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc, const double eye[3],
    const double forward[3], bool parallel, const double rgba[4], std::string& error);

  /// Draws triangles `first .. end`. The program must be bound.
  void Draw(std::size_t first, std::size_t end);

  /// Unbinds the vertex arrays.
  void Unbind();

  /// Frees the buffers (the context is going away).
  void ReleaseGraphicsResources();

private:
  vtkHybridOctreeSurfaceDrawer(const vtkHybridOctreeSurfaceDrawer&) = delete;
  vtkHybridOctreeSurfaceDrawer& operator=(const vtkHybridOctreeSurfaceDrawer&) = delete;

  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLBufferObject> Indices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;
  vtkShaderProgram* Program = nullptr;
  std::vector<float> VertexData;
  std::vector<unsigned int> IndexData;
  bool Uploaded = false;
  std::size_t Triangles = 0;
};

#endif
