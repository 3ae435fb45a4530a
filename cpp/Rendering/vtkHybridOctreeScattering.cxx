#include "vtkHybridOctreeScattering.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"

#include <vector>

using namespace vtkHybridOctreeBridge;

ScatteringDescription vtkHybridOctreeScattering::Describe(double blending, double reach,
  vtkVolumeProperty* property, const ShadingDescription& shading, double sampleDistance)
{
  ScatteringDescription d;
  // VTK scatters only with a light on (VolumetricScatteringBlending > 0 and totalNumberOfLights >
  // 0).
  d.Blending = shading.LightsOn > 0 ? blending : 0.0;
  d.Reach = reach;
  d.Anisotropy = property ? property->GetScatteringAnisotropy() : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    d.HeadlightAmbient[k] = shading.LightAmbient.size() >= 3 ? shading.LightAmbient[k] : 1.0;
  }
  d.SampleDistance = sampleDistance > 0.0 ? sampleDistance : 0.0;
  return d;
}

bool vtkHybridOctreeScattering::Activate(vtkOpenGLRenderWindow* window, const Selection& selection,
  const void* bytes, std::size_t byteCount, const GridDescription& grid, vtkMTimeType dataTime,
  std::string& error)
{
  if (!selection.GetScatteringFrame(this->Frame, error))
  {
    return false;
  }
  const std::size_t* n = this->Frame.ShadowDims;
  if (!this->Texture)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
  }
  const bool fresh = this->Texture->GetContext() == window && this->Texture->GetHandle() != 0 &&
    this->Uploaded.GetMTime() > dataTime &&
    this->Texture->GetWidth() == static_cast<unsigned int>(n[0]) &&
    this->Texture->GetHeight() == static_cast<unsigned int>(n[1]) &&
    this->Texture->GetDepth() == static_cast<unsigned int>(n[2]);
  if (!fresh)
  {
    std::vector<float> texels(n[0] * n[1] * n[2]);
    if (!selection.GetShadowVolume(bytes, byteCount, grid, texels.data(), texels.size(), error))
    {
      return false;
    }
    this->Texture->SetContext(window);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapR(vtkTextureObject::ClampToEdge);
    this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!this->Texture->Create3DFromRaw(static_cast<unsigned int>(n[0]),
          static_cast<unsigned int>(n[1]), static_cast<unsigned int>(n[2]), 1, VTK_FLOAT,
          texels.data()))
    {
      error = "OpenGL could not create the shadow volume's texture (" + std::to_string(n[0]) +
        " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) + ")";
      return false;
    }
    this->Uploaded.Modified();
  }
  this->Texture->Activate();
  return true;
}

void vtkHybridOctreeScattering::SetUniforms(vtkShaderProgram* program) const
{
  const ScatteringFrame& f = this->Frame;
  auto vec3 = [](const double v[3]) {
    return std::vector<float>{ static_cast<float>(v[0]), static_cast<float>(v[1]),
      static_cast<float>(v[2]) };
  };
  program->SetUniformi("shadowVolume", this->Texture->GetTextureUnit());
  program->SetUniform3f("scatterCorner", vec3(f.TextureCorner).data());
  program->SetUniform3f("scatterSize", vec3(f.TextureSize).data());
  program->SetUniform3f("shadowScale", vec3(f.ShadowScale).data());
  program->SetUniform3f("shadowShift", vec3(f.ShadowShift).data());
  program->SetUniform3f("headlightAmbient", vec3(f.HeadlightAmbient).data());
  program->SetUniformf("scatterBlending", static_cast<float>(f.Blending));
  program->SetUniformf("scatterAnisotropy", static_cast<float>(f.Anisotropy));
  program->SetUniformf("gradientScale", static_cast<float>(f.GradientScale));
  program->SetUniformf("scatterExtent", static_cast<float>(f.Extent));
  program->SetUniformf("sampleDistance", static_cast<float>(f.Distance));
  program->SetUniformf("toVtk", static_cast<float>(f.ToVtk));
  program->SetUniformi("maxShadowSteps", static_cast<int>(f.MaxSteps));
}

void vtkHybridOctreeScattering::Deactivate() const
{
  if (this->Texture && this->Texture->GetContext())
  {
    this->Texture->Deactivate();
  }
}

void vtkHybridOctreeScattering::ReleaseGraphicsResources()
{
  if (this->Texture && this->Texture->GetContext())
  {
    this->Texture->ReleaseGraphicsResources(this->Texture->GetContext());
  }
  this->Texture = nullptr;
}
