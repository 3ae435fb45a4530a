#include "vtkHybridOctreeSurfaceDrawer.h"

#include "vtkMatrix4x4.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include <cmath>
#include <limits>

namespace
{
const char* VertexShader = R"(//VTK::System::Dec
in vec3 vertexMC;
in vec3 normalMC;
uniform mat4 MCDC;
out vec3 positionMC;
out vec3 normal;
void main()
{
  positionMC = vertexMC;
  normal = normalMC;
  gl_Position = MCDC * vec4(vertexMC, 1.0);
}
)";

const char* FragmentShader = R"(//VTK::System::Dec
in vec3 positionMC;
in vec3 normal;
uniform vec3 eye;
uniform vec3 forward;
uniform int parallel;
uniform vec4 surfaceColor;
//VTK::Output::Dec
void main()
{
  vec3 d = parallel != 0 ? forward : normalize(positionMC - eye);
  float len = length(normal);
  float lambert = len > 0.0 ? abs(dot(normal, d)) / len : 1.0;
  vec3 rgb = clamp(surfaceColor.rgb, 0.0, 1.0) * lambert;
  gl_FragData[0] = vec4(rgb * surfaceColor.a, surfaceColor.a);
}
)";

}

vtkHybridOctreeSurfaceDrawer::vtkHybridOctreeSurfaceDrawer() = default;
vtkHybridOctreeSurfaceDrawer::~vtkHybridOctreeSurfaceDrawer() = default;

bool vtkHybridOctreeSurfaceDrawer::Upload(
  const vtkHybridOctreeBridge::SurfaceMesh& mesh, std::string& error)
{
  const std::size_t vertices = mesh.Points.size() / 3;
  const std::size_t polygons = mesh.Offsets.empty() ? 0 : mesh.Offsets.size() - 1;
  if (mesh.Normals.size() != mesh.Points.size() ||
    vertices > std::numeric_limits<unsigned int>::max())
  {
    error = "the surface's normals do not match its points";
    return false;
  }
  this->VertexData.resize(6 * vertices);
  for (std::size_t v = 0; v < vertices; ++v)
  {
    for (int k = 0; k < 3; ++k)
    {
      this->VertexData[6 * v + k] = static_cast<float>(mesh.Points[3 * v + k]);
      this->VertexData[6 * v + 3 + k] = mesh.Normals[3 * v + k];
    }
  }
  this->IndexData.resize(3 * polygons);
  for (std::size_t p = 0; p < polygons; ++p)
  {
    if (mesh.Offsets[p + 1] - mesh.Offsets[p] != 3)
    {
      error = "surface polygon " + std::to_string(p) + " is not a triangle";
      return false;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t id = mesh.Connectivity[static_cast<std::size_t>(mesh.Offsets[p]) + k];
      if (id < 0 || static_cast<std::size_t>(id) >= vertices)
      {
        error = "surface polygon " + std::to_string(p) + " names a vertex it does not have";
        return false;
      }
      this->IndexData[3 * p + k] = static_cast<unsigned int>(id);
    }
  }
  this->Triangles = polygons;
  this->Uploaded = false;
  return true;
}

bool vtkHybridOctreeSurfaceDrawer::Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
  const double eye[3], const double forward[3], bool parallel, const double rgba[4],
  std::string& error)
{
  this->Program = window->GetShaderCache()->ReadyShaderProgram(VertexShader, FragmentShader, "");
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
    this->Uploaded = false;
  }
  this->Vao->Bind();
  if (!this->Uploaded)
  {
    if (!this->Vertices->Upload(this->VertexData, vtkOpenGLBufferObject::ArrayBuffer) ||
      !this->Indices->Upload(this->IndexData, vtkOpenGLBufferObject::ElementArrayBuffer))
    {
      error = "could not load the surface into OpenGL buffers";
      this->Vao->Release();
      return false;
    }
    this->Uploaded = true;
  }
  const int stride = 6 * sizeof(float);
  if (!this->Vao->AddAttributeArray(
        this->Program, this->Vertices, "vertexMC", 0, stride, VTK_FLOAT, 3, false) ||
    !this->Vao->AddAttributeArray(
      this->Program, this->Vertices, "normalMC", 3 * sizeof(float), stride, VTK_FLOAT, 3, false))
  {
    error = "could not bind the surface's vertex arrays";
    this->Vao->Release();
    return false;
  }
  this->Indices->Bind();
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
  return true;
}

void vtkHybridOctreeSurfaceDrawer::Draw(std::size_t first, std::size_t end)
{
  if (end <= first || !this->Program)
  {
    return;
  }
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * (end - first)), GL_UNSIGNED_INT,
    reinterpret_cast<const void*>(3 * first * sizeof(unsigned int)));
}

void vtkHybridOctreeSurfaceDrawer::Unbind()
{
  if (this->Vao)
  {
    this->Vao->Release();
  }
}

void vtkHybridOctreeSurfaceDrawer::ReleaseGraphicsResources()
{
  if (this->Vertices)
  {
    this->Vertices->ReleaseGraphicsResources();
    this->Indices->ReleaseGraphicsResources();
    this->Vao->ReleaseGraphicsResources();
  }
  this->Vao = nullptr;
  this->Vertices = nullptr;
  this->Indices = nullptr;
  this->Program = nullptr;
  this->Uploaded = false;
}
