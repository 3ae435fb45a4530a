/**
 * @file   vtkHybridOctreeFloatTarget.h
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
 */
#ifndef vtkHybridOctreeFloatTarget_h
#define vtkHybridOctreeFloatTarget_h

#include "vtkSmartPointer.h"

#include <memory>
#include <string>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class vtkHybridOctreeFloatTarget
{
public:
  vtkHybridOctreeFloatTarget();
  ~vtkHybridOctreeFloatTarget();

  /**
   * Copies the depth of `ren`'s viewport, then binds the float target
   * (cleared to 0) with a viewport of the same size. False and `error` when
   * OpenGL refuses (the window's bindings are then unchanged).
   */
  bool Begin(vtkRenderer* ren, vtkOpenGLRenderWindow* window, std::string& error);

  /// Restores the window's framebuffer and viewport and blends the target over it.
  void End(vtkOpenGLRenderWindow* window);

  /// The opaque depth copied by Begin(), viewport-sized (valid until End()).
  vtkTextureObject* GetDepth() { return this->Depth; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkHybridOctreeFloatTarget(const vtkHybridOctreeFloatTarget&) = delete;
  vtkHybridOctreeFloatTarget& operator=(const vtkHybridOctreeFloatTarget&) = delete;

  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  vtkSmartPointer<vtkTextureObject> Color;
  vtkSmartPointer<vtkTextureObject> Depth;
  /// Holds Depth as its depth attachment, the blit's destination.
  vtkSmartPointer<vtkOpenGLFramebufferObject> DepthFramebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  int Size[2] = { 0, 0 };
  int DepthFormat = -1; ///< the depth format of the texture, the window's
  int Viewport[4] = { 0, 0, 0, 0 };
  int Scissor[4] = { 0, 0, 0, 0 };
};

#endif
