/**
 * @file   vtkOpenGLHybridOctreeFloatTarget.h
 * @brief  The float framebuffer the bricks are composited in (private to the module).
 *
 * Back-to-front slicing adds one premultiplied `c a'` per slice; with the
 * window's 8-bit colour each addition is rounded to 1/255, so the many tiny
 * opacities of a translucent transfer function (0.002 a slice, 256 slices)
 * are lost or inflated: on the 256^3 phantom the 8-bit picture was 0.017
 * RMSE from the full-resolution reference. The mapper therefore composites
 * into a 32-bit float RGBA texture of the viewport's size and blends that
 * once, premultiplied, over the window (`(ONE, ONE_MINUS_SRC_ALPHA)`).
 *
 * Opaque geometry already drawn (VTK's opaque actors, the mapper's opaque
 * surface) still hides the volume: its depth is blitted into a depth texture
 * first (a blit also resolves a multisampled window); the brick shader
 * drops fragments and ray samples behind it.
 *
 * An interactive frame may composite at a coarser image sample distance s
 * (vtkGPUVolumeRayCastMapper's ImageSampleDistance): the target is then
 * ceil(w / s) x ceil(h / s) texels, 1 / s^2 of the fragments, and is
 * blended over the viewport with linear filtering. The depth texture stays
 * viewport-sized: the shaders read it at their fragment's position times
 * GetDepthScale().
 *
 * The blend modes besides Composite reduce each ray in the target instead
 * (the brick shader's HO_REDUCE: a maximum, a minimum or sums) and End()
 * resolves each texel through the transfer function before it is blended
 * (vtkHybridOctreeResolveFS.glsl).
 */
#ifndef vtkOpenGLHybridOctreeFloatTarget_h
#define vtkOpenGLHybridOctreeFloatTarget_h

#include "vtkSmartPointer.h"

#include <memory>
#include <string>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class vtkMatrix4x4;

class vtkOpenGLHybridOctreeFloatTarget
{
public:
  /// How End() resolves a reduction (blend modes besides Composite).
  struct Resolve
  {
    int ReduceMode = 0;                ///< 1 maximum, 2 minimum, 3 average, 4 additive intensity
    vtkTextureObject* Table = nullptr; ///< the transfer function table
    int TableEntries = 1;
    double TableRange[2] = { 0.0, 1.0 };    ///< the values of its first and last cells
    vtkMatrix4x4* MCDC = nullptr;           ///< model to clip (VTK's transposed layout)
    double VolumeLo[3] = { 0.0, 0.0, 0.0 }; ///< the volume's box, model coordinates
    double VolumeHi[3] = { 0.0, 0.0, 0.0 };
  };

  vtkOpenGLHybridOctreeFloatTarget();
  ~vtkOpenGLHybridOctreeFloatTarget();

  /**
   * Copies the depth of `ren`'s viewport, then binds the float target with
   * a viewport of the viewport's size divided by `imageSampleDistance` (>= 1,
   * rounded up), cleared to 0 and drawn only within `region` (xmin, xmax,
   * ymin, ymax in normalized device coordinates: what is drawn covers no
   * more) by the scissor test. `clear`: the value cleared to (transparent
   * black by default; a reduction's identity). False and `error` when OpenGL
   * refuses (the window's bindings are then unchanged).
   */
  bool Begin(vtkRenderer* ren, vtkOpenGLRenderWindow* window, double imageSampleDistance,
    const double region[4], std::string& error, const float clear[4] = nullptr);

  /// Restores the window's framebuffer, viewport and scissor and blends the
  /// target's region over the window, resolved first by `resolve` when given.
  void End(vtkOpenGLRenderWindow* window, const Resolve* resolve = nullptr);

  /// The opaque depth copied by Begin(), viewport-sized (valid until End()).
  vtkTextureObject* GetDepth() { return this->Depth; }
  /// The target's size in texels (its viewport while bound).
  const int* GetSize() const { return this->Size; }
  /// Depth texels per target texel along x and y (1 at full resolution).
  const float* GetDepthScale() const { return this->DepthScale; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkOpenGLHybridOctreeFloatTarget(const vtkOpenGLHybridOctreeFloatTarget&) = delete;
  vtkOpenGLHybridOctreeFloatTarget& operator=(const vtkOpenGLHybridOctreeFloatTarget&) = delete;

  /// Draws the target over the window's viewport, blended premultiplied.
  void Composite(vtkOpenGLRenderWindow* window, const Resolve* resolve);

  /// The resolve program's uniforms for `resolve`.
  void SetResolveUniforms(const Resolve& resolve);

  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  vtkSmartPointer<vtkTextureObject> Color;
  vtkSmartPointer<vtkTextureObject> Depth;
  /// Holds Depth as its depth attachment, the blit's destination.
  vtkSmartPointer<vtkOpenGLFramebufferObject> DepthFramebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  std::unique_ptr<vtkOpenGLQuadHelper> ResolveQuad;
  int Size[2] = { 0, 0 };
  int DepthSize[2] = { 0, 0 };
  float DepthScale[2] = { 1.0f, 1.0f };
  int DepthFormat = -1; ///< the depth format of the texture, the window's
  int Viewport[4] = { 0, 0, 0, 0 };
  int Scissor[4] = { 0, 0, 0, 0 };
  bool ScissorTest = false; ///< the window's scissor test before Begin()
  /// The region's texels: x in [Region[0], Region[1]), y in [Region[2], Region[3]).
  int Region[4] = { 0, 0, 0, 0 };
};

#endif
