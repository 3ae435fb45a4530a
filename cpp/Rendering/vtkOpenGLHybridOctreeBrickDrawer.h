/**
 * @file   vtkOpenGLHybridOctreeBrickDrawer.h
 * @brief  The bricks' slices, and the translucent surface in their slabs, drawn with OpenGL
 *         (private to the module).
 *
 * The Hybrid Octree, sections 3 and 4.1: a brick of level p is drawn as slices
 * every d = stride * d0 along the view, its texture sampled trilinearly at
 *
 *     u_a = clamp((x_a - lo_a) / (stride * spacing_a), 0, texels_a - 1)   (texels)
 *
 * the value looked up in the transfer-function table and the opacity
 * corrected for the slice spacing, `a' = 1 - (1 - a)^(d / d0)`, blended
 * premultiplied back to front: `C = (c a', a') + (1 - a') C`. Exactly the CPU
 * compositor's sampling of the same DrawList.
 *
 * A translucent surface is drawn inside the slabs between the slices. With
 * the brick's slices at depths S[0] > S[1] > ... > S[n-1] (back to front),
 * slab s = { z : S[s] <= z < S[s-1] } (slab 0 unbounded behind, slab n in
 * front), z = (x - eye) . forward. The DrawList names each brick's surface
 * triangles (its batches); each triangle goes, per view, into the slabs its
 * depth range [z_min, z_max] covers, slab(z) = #{ k : S[k] > z }: unclipped
 * when that is one slab, else once per slab, clipped to it with
 *
 *     gl_ClipDistance[0] = z - near,  gl_ClipDistance[1] = far - z.
 *
 * Per triangle rather than per batch: a batch (a terminal surface node) spans
 * as many slabs as its brick is deep, a triangle one or two. Each brick is
 * one draw call of one program, in the order slab 0's triangles, slice 0,
 * slab 1's triangles, slice 1, ..., slab n's triangles (OpenGL keeps primitive
 * order within a draw). Surface fragments are shaded as in the CPU
 * compositor: headlight Lambert `rgb = colour |n . d|`, blended `(rgb a, a)`.
 *
 * Points of the hybrid representation (paper 3 section 4, "slices of points
 * are drawn interleaved with each pair of volumetric planes") are drawn in
 * the slab the DrawList buckets them into, with the slab's triangles, far
 * first (points at their depth, triangles at their centroid's); a brick
 * holding points is drawn as slices. Each point is a quad of
 * whole pixels around its projected centre c (window coordinates), its size
 * s = the projection of d0 (pixels), as the CPU compositor splats it
 * (crate::points::footprint):
 *
 *     square:   S = ceil(s) pixels across, from round(c - S/2), coverage s^2 / S^2
 *     Gaussian: sigma = max(s/2, 0.5), pixels within r = ceil(3 sigma) of floor(c),
 *               coverage exp(-|x - c|^2 / 2 sigma^2) s^2 / sum (the sum over those pixels)
 *
 * and its colour c_p and opacity a_p, what it adds over the textures
 * averaged over its voxel (crate::points::shade, computed in Rust per
 * transfer function, the CPU compositor's own):
 *
 *     a_p = (A_t - A_v) / (1 - A_v),   c_p = (C_t - C_v) / (A_t - A_v)
 *
 * drawn `(c_p a_p w, a_p w)` with coverage w; points adding nothing are not drawn.
 */
#ifndef vtkOpenGLHybridOctreeBrickDrawer_h
#define vtkOpenGLHybridOctreeBrickDrawer_h

#include "vtkHybridOctreeBridge.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

class vtkOpenGLHybridOctreeFloatTarget;
class vtkMatrix4x4;
class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;

class vtkOpenGLHybridOctreeBrickDrawer
{
public:
  /// The translucent surface's vertices: 6 floats each (position, normal),
  /// and triangle t's vertex ids at 3t .. 3t + 3.
  struct SurfaceData
  {
    const std::vector<float>* Vertices = nullptr;
    const std::vector<unsigned int>* Triangles = nullptr;
  };

  vtkOpenGLHybridOctreeBrickDrawer();
  ~vtkOpenGLHybridOctreeBrickDrawer();

  /// The points the list's buckets name, what each adds (4 floats a
  /// point: straight colour, opacity a_p; Points::GetShades()) and their footprint.
  struct PointData
  {
    const vtkHybridOctreeBridge::PointsDrawing* Drawing = nullptr;
    const std::vector<float>* Shades = nullptr;
    bool Gaussian = false;
  };

  /**
   * The vertices of every brick of `list` for a camera at `eye` with
   * `viewUp` (model coordinates), on the CPU: brick i's slices clipped to
   * `bounds[6i .. 6i+6]` (inside its box; none where `drawn[i]` is 0), and,
   * when `surface` is given and the list has batches, the brick's surface
   * triangles in their slabs, and when `points` are given and the list has
   * buckets, its points in their slabs. Returns the surface triangles placed
   * (copies in several slabs counted each time).
   */
  std::size_t Build(const vtkHybridOctreeBridge::DrawList& list, const std::vector<double>& bounds,
    const std::vector<char>& drawn, const double eye[3], const double viewUp[3],
    const SurfaceData& surface, const PointData& points);

  /// Points placed by the last Build().
  std::size_t GetPointsPlaced() const { return this->PointsPlaced; }

  /**
   * Makes the program current: `mcdc` the model-to-clip matrix, `table` the
   * transfer-function table (RGBA over [lo, hi] in `entries` cells),
   * `target` the bound float target (its size, and its copy of the opaque
   * geometry's depth: fragments and ray samples behind it are dropped),
   * `eye`, `forward`, `parallel` the camera in model coordinates,
   * `surfaceRGBA` the surface's colour and opacity. Uploads the vertices of
   * the last Build() on the first call after it. False and `error` on failure.
   */
  bool Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc, vtkTextureObject* table,
    vtkOpenGLHybridOctreeFloatTarget& target, int entries, double lo, double hi,
    const double eye[3], const double forward[3], bool parallel, const double surfaceRGBA[4],
    std::string& error);

  /// The volume's shading, light directions in model coordinates (see
  /// ShadingDescription); Shade off: the unshaded program, no gradient.
  /// Shaded bricks' textures carry one border texel per side. Call before Bind().
  void SetShading(const vtkHybridOctreeBridge::ShadingDescription& shading)
  {
    this->Shading = shading;
  }

  /// The most lights the shaded program takes.
  static constexpr int MaxLights = 8;

  /// Ray-marched bricks sample every max(d, factor d0) along the view (d
  /// their slice spacing; `factor` a power of two, 1 by default: the slice lattice).
  void SetSampleSpacing(int factor) { this->SampleSpacing = factor > 1 ? factor : 1; }

  /// Makes the program and vertices of the last Bind() current again
  /// (after another program drew).
  void Rebind(vtkOpenGLRenderWindow* window);

  /// Draws brick i of the built list, sampling `texture`.
  void DrawBrick(const vtkHybridOctreeBridge::DrawList& list, std::size_t i,
    const double spacing[3], vtkTextureObject* texture);

  /// Whether brick i is drawn as its ray-marched box (else as slices).
  bool IsRayMarched(std::size_t i) const
  {
    return i < this->RayMarched.size() && this->RayMarched[i];
  }

  /// Unbinds the vertex arrays.
  void Unbind();

  /// Frees the buffers (the context is going away).
  void ReleaseGraphicsResources();

private:
  /// The shaded program's material and light uniforms.
  bool SetShadingUniforms(std::string& error);

  vtkOpenGLHybridOctreeBrickDrawer(const vtkOpenGLHybridOctreeBrickDrawer&) = delete;
  vtkOpenGLHybridOctreeBrickDrawer& operator=(const vtkOpenGLHybridOctreeBrickDrawer&) = delete;

  /// Appends the 12 triangles of a box (flag 2: a ray-marched brick).
  void EmitBox(const double bounds[6]);

  /// Appends one vertex: position, normal, clip interval, kind, point opacity.
  void Emit(const float position[3], const float normal[3], float near, float far, int kind,
    float alpha = 0.0f);

  /// A triangle copy (index into the brick's placed triangles) or a point
  /// (point id) of a slab, at its view depth.
  struct SlabItem
  {
    double Depth;
    std::uint32_t Id;
    bool Point;
  };
  /// Appends the points of `list`'s bucket `bucket` that add something to `items`.
  void CollectPoints(const vtkHybridOctreeBridge::DrawList& list, std::size_t bucket,
    const PointData& points, const double eye[3], std::vector<SlabItem>& items);
  /// Appends point `id`'s quad (two triangles).
  void EmitPoint(const PointData& points, std::uint32_t id);

  std::vector<float> VertexData;
  /// Brick i's vertices: BrickFirst[i] .. BrickFirst[i + 1].
  std::vector<std::size_t> BrickFirst;
  /// Per brick: drawn as its ray-marched box.
  std::vector<char> RayMarched;
  /// Brick i's drawn box (its visible blocks): Boxes[6i .. 6i+6].
  std::vector<double> Boxes;
  /// The view's up (model coordinates, perpendicular to forward) and d0: a point's size.
  float PointUp[3] = { 0.0f, 1.0f, 0.0f };
  float PointSpacing = 1.0f;
  std::size_t PointsPlaced = 0;
  int SampleSpacing = 1;
  vtkHybridOctreeBridge::ShadingDescription Shading;
  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;
  vtkShaderProgram* Program = nullptr;
  bool Uploaded = false;
};

#endif
