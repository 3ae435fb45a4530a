#include "vtkOpenGLHybridOctreeSurfaceDrawer.h"

#include "vtkHybridOctreeSurfaceFS.h"
#include "vtkHybridOctreeSurfaceVS.h"

#include "vtkMatrix4x4.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLHybridOctreeFloatTarget.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace
{

}

vtkOpenGLHybridOctreeSurfaceDrawer::vtkOpenGLHybridOctreeSurfaceDrawer() = default;
vtkOpenGLHybridOctreeSurfaceDrawer::~vtkOpenGLHybridOctreeSurfaceDrawer() = default;

bool vtkOpenGLHybridOctreeSurfaceDrawer::Upload(
  const vtkHybridOctreeBridge::HybridOctree& octree, std::string& error)
{
  if (!octree.GetSurfaceTriangles(this->VertexData, this->IndexData, error))
  {
    return false;
  }
  this->Triangles = this->IndexData.size() / 3;
  this->Uploaded = false;
  return true;
}

bool vtkOpenGLHybridOctreeSurfaceDrawer::Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
  const double eye[3], const double forward[3], bool parallel, const double rgba[4],
  std::string& error, vtkOpenGLHybridOctreeFloatTarget* target)
{
  this->Program = window->GetShaderCache()->ReadyShaderProgram(
    vtkHybridOctreeSurfaceVS, vtkHybridOctreeSurfaceFS, "");
  if (!this->Program)
  {
    error = "the surface shader did not compile";
    return false;
  }
  if (!this->Vao)
  {
    this->Vertices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->Indices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->Vao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
    this->BrickIndices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->BrickVao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
    this->Uploaded = false;
    this->BrickOrderUploaded = false;
  }
  // The brick order (a target: drawn brick by brick) or the surface's own;
  // the element buffer bound last is the bound vertex array's.
  this->Bound = target ? this->BrickVao.GetPointer() : this->Vao.GetPointer();
  vtkOpenGLBufferObject* indices =
    target ? this->BrickIndices.GetPointer() : this->Indices.GetPointer();
  this->Bound->Bind();
  if (!this->Uploaded)
  {
    if (!this->Vertices->Upload(this->VertexData, vtkOpenGLBufferObject::ArrayBuffer) ||
      !this->Indices->Upload(this->IndexData, vtkOpenGLBufferObject::ElementArrayBuffer))
    {
      error = "could not load the surface into OpenGL buffers";
      this->Bound->Release();
      return false;
    }
    this->Uploaded = true;
  }
  if (target && !this->BrickOrderUploaded)
  {
    if (!this->BrickOrder.empty() &&
      !this->BrickIndices->Upload(this->BrickOrder, vtkOpenGLBufferObject::ElementArrayBuffer))
    {
      error = "could not load the surface's brick order into an OpenGL buffer";
      this->Bound->Release();
      return false;
    }
    this->BrickOrderUploaded = true;
  }
  const int stride = 6 * sizeof(float);
  if (!this->Bound->AddAttributeArray(
        this->Program, this->Vertices, "vertexMC", 0, stride, VTK_FLOAT, 3, false) ||
    !this->Bound->AddAttributeArray(
      this->Program, this->Vertices, "normalMC", 3 * sizeof(float), stride, VTK_FLOAT, 3, false))
  {
    error = "could not bind the surface's vertex arrays";
    this->Bound->Release();
    return false;
  }
  indices->Bind();
  const float e[3] = { static_cast<float>(eye[0]), static_cast<float>(eye[1]),
    static_cast<float>(eye[2]) };
  const float f[3] = { static_cast<float>(forward[0]), static_cast<float>(forward[1]),
    static_cast<float>(forward[2]) };
  const float c[4] = { static_cast<float>(rgba[0]), static_cast<float>(rgba[1]),
    static_cast<float>(rgba[2]), static_cast<float>(rgba[3]) };
  this->Program->SetUniformMatrix("MCDC", mcdc);
  this->Program->SetUniform3f("eye", e);
  this->Program->SetUniform3f("forward", f);
  this->Program->SetUniformi("parallel", parallel ? 1 : 0);
  this->Program->SetUniform4f("surfaceColor", c);
  this->Program->SetUniformi("testOpaqueDepth", target ? 1 : 0);
  if (target)
  {
    this->Program->SetUniformi("opaqueDepth", target->GetDepth()->GetTextureUnit());
    this->Program->SetUniform2f("depthScale", target->GetDepthScale());
  }
  return true;
}

void vtkOpenGLHybridOctreeSurfaceDrawer::Rebind(vtkOpenGLRenderWindow* window)
{
  if (this->Program && this->Bound)
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Program);
    this->Bound->Bind();
  }
}

void vtkOpenGLHybridOctreeSurfaceDrawer::OrderByBrick(const vtkHybridOctreeBridge::DrawList& list,
  const double eye[3], const double forward[3], bool parallel, bool insideOpaque)
{
  const std::size_t bricks = list.GetNumberOfBricks();
  const std::size_t vertexCount = this->VertexData.size() / 6;
  this->BrickOrder.clear();
  this->BrickParts.assign(1, 0);
  this->BrickOrderUploaded = false;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  std::vector<unsigned int> after;
  for (std::size_t i = 0; i < bricks && list.BatchOffsets.size() == bricks + 1; ++i)
  {
    // A batch spanning several slabs is listed once per slab: the union.
    ranges.clear();
    for (std::size_t k = list.BatchOffsets[i]; k < list.BatchOffsets[i + 1]; ++k)
    {
      ranges.emplace_back(list.BatchFirst[k], list.BatchEnd[k]);
    }
    std::sort(ranges.begin(), ranges.end());
    after.clear();
    std::uint32_t covered = 0;
    for (const auto& range : ranges)
    {
      for (std::uint32_t t = std::max(range.first, covered);
           t < range.second && 3 * static_cast<std::size_t>(t) + 2 < this->IndexData.size(); ++t)
      {
        // n: the vertex normals' sum (towards lower values, the outside);
        // the eye is outside when n points towards it.
        double n[3] = { 0.0, 0.0, 0.0 }, c[3] = { 0.0, 0.0, 0.0 };
        for (int v = 0; v < 3; ++v)
        {
          const float* p = &this->VertexData[6 *
            std::min<std::size_t>(
              this->IndexData[3 * static_cast<std::size_t>(t) + v], vertexCount - 1)];
          for (int a = 0; a < 3; ++a)
          {
            c[a] += p[a] / 3.0;
            n[a] += p[3 + a];
          }
        }
        double towardsEye = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          towardsEye += n[a] * (parallel ? -forward[a] : eye[a] - c[a]);
        }
        const bool eyeInside = towardsEye < 0.0;
        std::vector<unsigned int>& part = eyeInside == insideOpaque ? this->BrickOrder : after;
        part.insert(part.end(), &this->IndexData[3 * static_cast<std::size_t>(t)],
          &this->IndexData[3 * static_cast<std::size_t>(t)] + 3);
      }
      covered = std::max(covered, range.second);
    }
    this->BrickParts.push_back(this->BrickOrder.size() / 3);
    this->BrickOrder.insert(this->BrickOrder.end(), after.begin(), after.end());
    this->BrickParts.push_back(this->BrickOrder.size() / 3);
  }
}

std::pair<std::size_t, std::size_t> vtkOpenGLHybridOctreeSurfaceDrawer::GetTrianglesBefore(
  std::size_t i) const
{
  // Brick i - 1's triangles after its volume, then brick i's before its own.
  const std::size_t n = this->BrickParts.size() / 2;
  if (this->BrickParts.size() != 2 * n + 1 || i > n)
  {
    return { 0, 0 };
  }
  return { this->BrickParts[i > 0 ? 2 * i - 1 : 0], this->BrickParts[i < n ? 2 * i + 1 : 2 * n] };
}

void vtkOpenGLHybridOctreeSurfaceDrawer::Draw(std::size_t first, std::size_t end)
{
  if (end <= first || !this->Program)
  {
    return;
  }
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * (end - first)), GL_UNSIGNED_INT,
    reinterpret_cast<const void*>(3 * first * sizeof(unsigned int)));
}

void vtkOpenGLHybridOctreeSurfaceDrawer::Unbind()
{
  if (this->Bound)
  {
    this->Bound->Release();
  }
}

void vtkOpenGLHybridOctreeSurfaceDrawer::ReleaseGraphicsResources()
{
  if (this->Vertices)
  {
    this->Vertices->ReleaseGraphicsResources();
    this->Indices->ReleaseGraphicsResources();
    this->Vao->ReleaseGraphicsResources();
  }
  if (this->BrickIndices)
  {
    this->BrickIndices->ReleaseGraphicsResources();
    this->BrickVao->ReleaseGraphicsResources();
  }
  this->Vao = nullptr;
  this->Vertices = nullptr;
  this->Indices = nullptr;
  this->BrickVao = nullptr;
  this->BrickIndices = nullptr;
  this->Bound = nullptr;
  this->BrickOrderUploaded = false;
  this->Program = nullptr;
  this->Uploaded = false;
}
