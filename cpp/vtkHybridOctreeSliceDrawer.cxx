#include "vtkHybridOctreeSliceDrawer.h"

#include "vtkHybridOctreeSliceGeometry.h"

#include "vtkMatrix4x4.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

namespace
{
const char* VertexShader = R"(//VTK::System::Dec
in vec3 vertexMC;
uniform mat4 MCDC;
out vec3 positionMC;
void main()
{
  positionMC = vertexMC;
  gl_Position = MCDC * vec4(vertexMC, 1.0);
}
)";

const char* FragmentShader = R"(//VTK::System::Dec
in vec3 positionMC;
uniform sampler3D brickTexture;
uniform sampler2D transferTable;
uniform vec3 brickLo;
uniform vec3 inverseStep;
uniform vec3 texels;
uniform vec2 tableScaleShift;
uniform float opacityRatio;
//VTK::Output::Dec
void main()
{
  vec3 u = clamp((positionMC - brickLo) * inverseStep, vec3(0.0), texels - vec3(1.0));
  float value = texture(brickTexture, (u + vec3(0.5)) / texels).r;
  vec4 c = texture(transferTable, vec2(value * tableScaleShift.x + tableScaleShift.y, 0.5));
  float a = clamp(c.a, 0.0, 1.0);
  if (a == 0.0)
  {
    discard; // blends to nothing: skip the blend
  }
  if (opacityRatio != 1.0 && a < 1.0)
  {
    a = 1.0 - exp(opacityRatio * log(1.0 - a));
  }
  gl_FragData[0] = vec4(clamp(c.rgb, 0.0, 1.0) * a, a);
}
)";
}

vtkHybridOctreeSliceDrawer::vtkHybridOctreeSliceDrawer() = default;
vtkHybridOctreeSliceDrawer::~vtkHybridOctreeSliceDrawer() = default;

void vtkHybridOctreeSliceDrawer::Build(const vtkHybridOctreeBridge::DrawList& list,
  const std::vector<double>& bounds, const std::vector<char>& drawn, const double eye[3],
  const double viewUp[3])
{
  double right[3], up[3];
  vtkHybridOctreeSliceGeometry::ViewBasis(list.Forward, viewUp, right, up);
  this->VertexData.clear();
  this->SliceFirst.assign(1, 0);
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    for (std::size_t s = list.SliceOffsets[i]; s < list.SliceOffsets[i + 1]; ++s)
    {
      if (drawn[i])
      {
        vtkHybridOctreeSliceGeometry::AppendSlicePolygon(
          &bounds[6 * i], eye, list.Forward, right, up, list.Slices[s], this->VertexData);
      }
      this->SliceFirst.push_back(this->VertexData.size() / 3);
    }
  }
  this->Uploaded = false;
}

bool vtkHybridOctreeSliceDrawer::Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
  vtkTextureObject* table, int entries, double lo, double hi, std::string& error)
{
  this->Program = window->GetShaderCache()->ReadyShaderProgram(VertexShader, FragmentShader, "");
  if (!this->Program)
  {
    error = "the slice shader did not compile";
    return false;
  }
  if (!this->Vao)
  {
    this->Vertices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->Vao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
    this->Uploaded = false;
  }
  this->Vao->Bind();
  if (!this->Uploaded)
  {
    if (!this->VertexData.empty() &&
      !this->Vertices->Upload(this->VertexData, vtkOpenGLBufferObject::ArrayBuffer))
    {
      error = "could not load the slice polygons into an OpenGL buffer";
      this->Vao->Release();
      return false;
    }
    this->Uploaded = true;
  }
  if (!this->VertexData.empty() &&
    !this->Vao->AddAttributeArray(
      this->Program, this->Vertices, "vertexMC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
  {
    error = "could not bind the slice vertices";
    this->Vao->Release();
    return false;
  }
  this->Program->SetUniformMatrix("MCDC", mcdc);
  // Table cell k holds the value lo + (hi - lo) k / (entries - 1); its centre
  // is at texture coordinate (k + 0.5) / entries.
  const double scale = (entries - 1.0) / (entries * (hi - lo));
  const float scaleShift[2] = { static_cast<float>(scale),
    static_cast<float>(0.5 / entries - lo * scale) };
  this->Program->SetUniform2f("tableScaleShift", scaleShift);
  this->Program->SetUniformi("transferTable", table->GetTextureUnit());
  return true;
}

void vtkHybridOctreeSliceDrawer::UseBrick(const vtkHybridOctreeBridge::DrawList& list,
  std::size_t i, const double spacing[3], vtkTextureObject* texture)
{
  const double* b = &list.Bounds[6 * i];
  const float lo[3] = { static_cast<float>(b[0]), static_cast<float>(b[2]),
    static_cast<float>(b[4]) };
  float inverseStep[3];
  float n[3];
  for (int a = 0; a < 3; ++a)
  {
    inverseStep[a] = static_cast<float>(1.0 / (list.Stride[i] * spacing[a]));
    n[a] = static_cast<float>(list.Texels[3 * i + a]);
  }
  this->Program->SetUniformi("brickTexture", texture->GetTextureUnit());
  this->Program->SetUniform3f("brickLo", lo);
  this->Program->SetUniform3f("inverseStep", inverseStep);
  this->Program->SetUniform3f("texels", n);
  this->Program->SetUniformf("opacityRatio", static_cast<float>(list.OpacityRatio[i]));
}

void vtkHybridOctreeSliceDrawer::DrawSlices(std::size_t from, std::size_t to)
{
  if (to <= from || to >= this->SliceFirst.size())
  {
    return;
  }
  const std::size_t first = this->SliceFirst[from];
  const std::size_t count = this->SliceFirst[to] - first;
  if (count > 0)
  {
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(count));
  }
}

void vtkHybridOctreeSliceDrawer::Unbind()
{
  if (this->Vao)
  {
    this->Vao->Release();
  }
}

void vtkHybridOctreeSliceDrawer::ReleaseGraphicsResources()
{
  if (this->Vertices)
  {
    this->Vertices->ReleaseGraphicsResources();
    this->Vao->ReleaseGraphicsResources();
  }
  this->Vertices = nullptr;
  this->Vao = nullptr;
  this->Program = nullptr;
  this->Uploaded = false;
}
