#include "vtkOpenGLHybridOctreeFloatTarget.h"

#include "vtkHybridOctreeCompositeFS.h"
#include "vtkHybridOctreeResolveFS.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>

namespace
{
/// The target's premultiplied RGBA, as is (blended by the fixed function).
}

vtkOpenGLHybridOctreeFloatTarget::vtkOpenGLHybridOctreeFloatTarget() = default;
vtkOpenGLHybridOctreeFloatTarget::~vtkOpenGLHybridOctreeFloatTarget() = default;

bool vtkOpenGLHybridOctreeFloatTarget::Begin(vtkRenderer* ren, vtkOpenGLRenderWindow* window,
  double imageSampleDistance, const double region[4], std::string& error, const float clear[4])
{
  int width = 0, height = 0, x = 0, y = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  if (width <= 0 || height <= 0)
  {
    error = "the renderer's viewport is empty";
    return false;
  }
  const double s = imageSampleDistance > 1.0 ? imageSampleDistance : 1.0;
  const int targetWidth = std::max(1, static_cast<int>(std::ceil(width / s)));
  const int targetHeight = std::max(1, static_cast<int>(std::ceil(height / s)));
  if (!this->Framebuffer || this->Color->GetContext() != window)
  {
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->Framebuffer->SetContext(window);
    this->Color = vtkSmartPointer<vtkTextureObject>::New();
    this->Color->SetContext(window);
    this->Depth = vtkSmartPointer<vtkTextureObject>::New();
    this->Depth->SetContext(window);
    this->DepthFramebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->DepthFramebuffer->SetContext(window);
    this->Quad.reset();
    this->ResolveQuad.reset();
    this->Size[0] = this->Size[1] = 0;
    this->DepthSize[0] = this->DepthSize[1] = 0;
  }
  // A depth blit needs the same depth format on both sides: the window's.
  GLint bits = 0, type = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  const int format = type == GL_FLOAT ? vtkTextureObject::Float32
    : bits <= 16                      ? vtkTextureObject::Fixed16
    : bits <= 24                      ? vtkTextureObject::Fixed24
                                      : vtkTextureObject::Fixed32;
  if (this->Size[0] != targetWidth || this->Size[1] != targetHeight)
  {
    // Blended over the viewport texel for pixel at full resolution, filtered when coarser.
    const int filter = s > 1.0 ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
    this->Color->SetMinificationFilter(filter);
    this->Color->SetMagnificationFilter(filter);
    this->Color->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Color->SetWrapT(vtkTextureObject::ClampToEdge);
    if (!this->Color->Allocate2D(targetWidth, targetHeight, 4, VTK_FLOAT))
    {
      error = "OpenGL could not allocate a float colour texture of " + std::to_string(targetWidth) +
        "x" + std::to_string(targetHeight);
      return false;
    }
    this->Size[0] = targetWidth;
    this->Size[1] = targetHeight;
  }
  if (this->DepthSize[0] != width || this->DepthSize[1] != height || this->DepthFormat != format)
  {
    this->Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    if (!this->Depth->AllocateDepth(width, height, format))
    {
      error = "OpenGL could not allocate a depth texture of the viewport's size";
      return false;
    }
    this->DepthSize[0] = width;
    this->DepthSize[1] = height;
    this->DepthFormat = format;
  }
  this->DepthScale[0] = static_cast<float>(width) / targetWidth;
  this->DepthScale[1] = static_cast<float>(height) / targetHeight;
  // The depth of what is drawn so far, blitted from the bound (read)
  // framebuffer: a blit also resolves a multisampled one (a copy would not).
  vtkOpenGLState* state = window->GetState();
  while (glGetError() != GL_NO_ERROR)
  {
  }
  state->PushFramebufferBindings();
  this->DepthFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->DepthFramebuffer->AddDepthAttachment(this->Depth);
  glBlitFramebuffer(
    x, y, x + width, y + height, 0, 0, width, height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  state->PopFramebufferBindings();
  if (glGetError() != GL_NO_ERROR)
  {
    error = "OpenGL could not read the window's depth buffer into a texture of its format (" +
      std::to_string(bits) + "-bit)";
    return false;
  }

  state->PushFramebufferBindings();
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, this->Color);
  this->Framebuffer->ActivateDrawBuffer(0);
  if (this->Framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
  {
    state->PopFramebufferBindings();
    error = "OpenGL refused the float framebuffer";
    return false;
  }
  state->vtkglGetIntegerv(GL_VIEWPORT, this->Viewport);
  state->vtkglGetIntegerv(GL_SCISSOR_BOX, this->Scissor);
  this->ScissorTest = state->GetEnumState(GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, targetWidth, targetHeight);
  // The region's texels; cleared and drawn with two more around them (End()
  // blends one more, which its linear filter reads with the next).
  for (int a = 0; a < 2; ++a)
  {
    const int n = a == 0 ? targetWidth : targetHeight;
    const double lo = std::max(-1.0, std::min(1.0, region[2 * a]));
    const double hi = std::max(lo, std::min(1.0, region[2 * a + 1]));
    this->Region[2 * a] = static_cast<int>(std::floor((lo + 1.0) * 0.5 * n));
    this->Region[2 * a + 1] = static_cast<int>(std::ceil((hi + 1.0) * 0.5 * n));
  }
  const int cleared[4] = { std::max(0, this->Region[0] - 2),
    std::min(targetWidth, this->Region[1] + 2), std::max(0, this->Region[2] - 2),
    std::min(targetHeight, this->Region[3] + 2) };
  state->vtkglEnable(GL_SCISSOR_TEST);
  state->vtkglScissor(cleared[0], cleared[2], cleared[1] - cleared[0], cleared[3] - cleared[2]);
  vtkOpenGLState::ScopedglClearColor clearColor(state);
  if (clear)
  {
    state->vtkglClearColor(clear[0], clear[1], clear[2], clear[3]);
  }
  else
  {
    state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  }
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  return true;
}

void vtkOpenGLHybridOctreeFloatTarget::End(vtkOpenGLRenderWindow* window, const Resolve* resolve)
{
  vtkOpenGLState* state = window->GetState();
  state->PopFramebufferBindings();
  state->vtkglViewport(this->Viewport[0], this->Viewport[1], this->Viewport[2], this->Viewport[3]);
  // Blended over the window pixels of the region and one texel around it
  // (texel t covers pixels [t s, (t + 1) s)), within the scissor box it had.
  int lo[2], hi[2];
  for (int a = 0; a < 2; ++a)
  {
    const double scale = this->DepthScale[a];
    lo[a] = std::max(this->Scissor[a],
      this->Viewport[a] + static_cast<int>(std::floor((this->Region[2 * a] - 1) * scale)));
    hi[a] = std::min(this->Scissor[a] + this->Scissor[a + 2],
      this->Viewport[a] + static_cast<int>(std::ceil((this->Region[2 * a + 1] + 1) * scale)));
    hi[a] = std::max(hi[a], lo[a]);
  }
  state->vtkglScissor(lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1]);
  this->Composite(window, resolve);
  state->vtkglScissor(this->Scissor[0], this->Scissor[1], this->Scissor[2], this->Scissor[3]);
  if (!this->ScissorTest)
  {
    state->vtkglDisable(GL_SCISSOR_TEST);
  }
}

void vtkOpenGLHybridOctreeFloatTarget::Composite(
  vtkOpenGLRenderWindow* window, const Resolve* resolve)
{
  vtkOpenGLState* state = window->GetState();
  std::unique_ptr<vtkOpenGLQuadHelper>& quad = resolve ? this->ResolveQuad : this->Quad;
  if (!quad)
  {
    quad.reset(new vtkOpenGLQuadHelper(
      window, nullptr, resolve ? vtkHybridOctreeResolveFS : vtkHybridOctreeCompositeFS, ""));
  }
  if (!quad->Program)
  {
    return;
  }
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  this->Color->Activate();
  quad->Program->SetUniformi("composited", this->Color->GetTextureUnit());
  if (resolve)
  {
    resolve->Table->Activate();
    this->Depth->Activate();
    this->SetResolveUniforms(*resolve);
  }
  quad->Render();
  if (resolve)
  {
    this->Depth->Deactivate();
    resolve->Table->Deactivate();
  }
  this->Color->Deactivate();
}

void vtkOpenGLHybridOctreeFloatTarget::SetResolveUniforms(const Resolve& resolve)
{
  vtkShaderProgram* program = this->ResolveQuad->Program;
  program->SetUniformi("transferTable", resolve.Table->GetTextureUnit());
  program->SetUniformi("opaqueDepth", this->Depth->GetTextureUnit());
  program->SetUniformi("reduceMode", resolve.ReduceMode);
  // Table cell k holds the value lo + (hi - lo) k / (entries - 1), its centre at (k + 0.5) /
  // entries.
  const double lo = resolve.TableRange[0];
  const double hi = resolve.TableRange[1];
  const double n = resolve.TableEntries;
  const double scale = hi > lo ? (n - 1.0) / (n * (hi - lo)) : 0.0;
  const float scaleShift[2] = { static_cast<float>(scale),
    static_cast<float>(0.5 / n - lo * scale) };
  program->SetUniform2f("tableScaleShift", scaleShift);
  const float size[2] = { static_cast<float>(this->Size[0]), static_cast<float>(this->Size[1]) };
  program->SetUniform2f("targetSize", size);
  program->SetUniform2f("depthScale", this->DepthScale);
  const float depthSize[2] = { static_cast<float>(this->DepthSize[0]),
    static_cast<float>(this->DepthSize[1]) };
  program->SetUniform2f("depthSize", depthSize);
  vtkNew<vtkMatrix4x4> dcmc;
  vtkMatrix4x4::Invert(resolve.MCDC, dcmc);
  program->SetUniformMatrix("DCMC", dcmc);
  const float lo3[3] = { static_cast<float>(resolve.VolumeLo[0]),
    static_cast<float>(resolve.VolumeLo[1]), static_cast<float>(resolve.VolumeLo[2]) };
  const float hi3[3] = { static_cast<float>(resolve.VolumeHi[0]),
    static_cast<float>(resolve.VolumeHi[1]), static_cast<float>(resolve.VolumeHi[2]) };
  program->SetUniform3f("volumeLo", lo3);
  program->SetUniform3f("volumeHi", hi3);
}

void vtkOpenGLHybridOctreeFloatTarget::ReleaseGraphicsResources(vtkWindow* window)
{
  for (std::unique_ptr<vtkOpenGLQuadHelper>* quad : { &this->Quad, &this->ResolveQuad })
  {
    if (*quad)
    {
      (*quad)->ReleaseGraphicsResources(window);
      quad->reset();
    }
  }
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
    this->Color->ReleaseGraphicsResources(window);
    this->Depth->ReleaseGraphicsResources(window);
    this->DepthFramebuffer->ReleaseGraphicsResources(window);
  }
  this->Framebuffer = nullptr;
  this->Color = nullptr;
  this->Depth = nullptr;
  this->DepthFramebuffer = nullptr;
  this->Size[0] = this->Size[1] = 0;
  this->DepthSize[0] = this->DepthSize[1] = 0;
}
