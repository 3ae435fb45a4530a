#include "vtkOpenGLHybridOctreeBrickDrawer.h"
#include "vtkHybridOctreeScattering.h"

#include "vtkHybridOctreeBrickFS.h"
#include "vtkHybridOctreeBrickVS.h"

#include "vtkOpenGLHybridOctreeFloatTarget.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace
{
/// Floats per vertex (BrickGeometry::Vertices): position, normal, clip
/// interval (near, far), kind, point opacity, brick index.
constexpr std::size_t Stride = 11;
/// RGBA texels a brick in the frame's brick table (the vertex shader's
/// t0 .. t6): brickLo, opacity ratio; inverseStep, sample spacing; texels,
/// jitter; slotOffset, jitterScale; boxLo; boxHi; gradientStep.
constexpr std::size_t TexelsPerBrick = 7;
}

vtkOpenGLHybridOctreeBrickDrawer::vtkOpenGLHybridOctreeBrickDrawer() = default;
vtkOpenGLHybridOctreeBrickDrawer::~vtkOpenGLHybridOctreeBrickDrawer() = default;

void vtkOpenGLHybridOctreeBrickDrawer::SetGeometry(
  vtkHybridOctreeBridge::BrickGeometry&& geometry, double pointSpacing)
{
  this->Geometry = std::move(geometry);
  this->PointSpacing = static_cast<float>(pointSpacing);
  this->Uploaded = false;
}

bool vtkOpenGLHybridOctreeBrickDrawer::Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
  vtkTextureObject* table, vtkOpenGLHybridOctreeFloatTarget& target, int entries, double lo,
  double hi, const double eye[3], const double forward[3], bool parallel,
  const double surfaceRGBA[4], std::string& error)
{
  vtkTextureObject* depth = target.GetDepth();
  const bool shade = this->Shading.Shade && this->ReduceMode == 0;
  const bool crop = this->Region.Cropping;
  const bool clip = !this->Region.ClippingPlanes.empty();
  std::string fragment = vtkHybridOctreeBrickFS;
  const bool isosurface = !this->Isosurfaces.empty() && this->ReduceMode == 0;
  const std::string defines = this->VariantDefines();
  if (!defines.empty())
  {
    // A variant: its own program; the plain one is unchanged.
    const std::string system = "//VTK::System::Dec";
    const std::size_t at = fragment.find(system);
    fragment.insert(at == std::string::npos ? 0 : at + system.size(), defines);
  }
  vtkShaderProgram* previous = this->Program;
  this->Program =
    window->GetShaderCache()->ReadyShaderProgram(vtkHybridOctreeBrickVS, fragment.c_str(), "");
  if (!this->Program)
  {
    error = "the brick shader did not compile";
    return false;
  }
  if (this->Vao && previous && previous != this->Program)
  {
    // The shaded and unshaded programs alternate: attributes bound anew.
    this->Vao->ShaderProgramChanged();
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
    if (this->Geometry.VertexFloats > 0 &&
      !this->Vertices->Upload(
        this->Geometry.Vertices, this->Geometry.VertexFloats, vtkOpenGLBufferObject::ArrayBuffer))
    {
      error = "could not load the slices into an OpenGL buffer";
      this->Vao->Release();
      return false;
    }
    this->Uploaded = true;
    // The buffer holds them now: the frame's copy in memory goes (a frame
    // of 100,000 bricks makes ~250 MB of vertices).
    this->Geometry.Storage.reset();
    this->Geometry.Vertices = nullptr;
  }
  const int stride = static_cast<int>(Stride * sizeof(float));
  // The attributes a program reads (the reducing one reads no normal).
  struct Attribute
  {
    const char* Name;
    int Offset;
    int Components;
  };
  const Attribute attributes[] = { { "vertexMC", 0, 3 }, { "normalMC", 3, 3 }, { "clipMC", 6, 2 },
    { "kindMC", 8, 1 }, { "alphaMC", 9, 1 }, { "brickMC", 10, 1 } };
  bool bound = true;
  for (const Attribute& a : attributes)
  {
    if (this->Geometry.VertexFloats > 0 && this->Program->IsAttributeUsed(a.Name))
    {
      bound = bound &&
        this->Vao->AddAttributeArray(this->Program, this->Vertices, a.Name,
          a.Offset * static_cast<int>(sizeof(float)), stride, VTK_FLOAT, a.Components, false);
    }
  }
  if (!bound)
  {
    error = "could not bind the brick vertices";
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
  const float texelDecode[2] = { static_cast<float>(this->TexelDecode[0]),
    static_cast<float>(this->TexelDecode[1]) };
  this->Program->SetUniform2f("texelDecode", texelDecode);
  if (this->Dependent && this->ReduceMode == 0)
  {
    // The colour column over the colour field's range (the table's alpha is over [lo, hi]).
    const double c = (entries - 1.0) / (entries * (this->ColourRange[1] - this->ColourRange[0]));
    const float colourScaleShift[2] = { static_cast<float>(c),
      static_cast<float>(0.5 / entries - this->ColourRange[0] * c) };
    this->Program->SetUniform2f("colourScaleShift", colourScaleShift);
  }
  if (this->Rgba && this->ReduceMode == 0)
  {
    const float rgbScale[3] = { static_cast<float>(this->RgbaReading[0]),
      static_cast<float>(this->RgbaReading[1]), static_cast<float>(this->RgbaReading[2]) };
    const float rgbBias[3] = { static_cast<float>(this->RgbaReading[3]),
      static_cast<float>(this->RgbaReading[4]), static_cast<float>(this->RgbaReading[5]) };
    this->Program->SetUniform3f("rgbScale", rgbScale);
    this->Program->SetUniform3f("rgbBias", rgbBias);
    const float alphaDecode[2] = { static_cast<float>(this->RgbaReading[6]),
      static_cast<float>(this->RgbaReading[7]) };
    this->Program->SetUniform2f("alphaDecode", alphaDecode);
  }
  this->Program->SetUniformi("transferTable", table->GetTextureUnit());
  this->Program->SetUniformi("opaqueDepth", depth->GetTextureUnit());
  // Clip to model coordinates: the inverse of MCDC (VTK's matrices are transposed).
  vtkNew<vtkMatrix4x4> dcmc;
  vtkMatrix4x4::Invert(mcdc, dcmc);
  this->Program->SetUniformMatrix("DCMC", dcmc);
  const float size[2] = { static_cast<float>(target.GetSize()[0]),
    static_cast<float>(target.GetSize()[1]) };
  this->Program->SetUniform2f("viewportSize", size);
  this->Program->SetUniform2f("depthScale", target.GetDepthScale());
  // The near plane's view depth: the centre of the near clip face, unprojected.
  double ndc[4] = { 0.0, 0.0, -1.0, 1.0 };
  // VTK keeps its key matrices transposed for OpenGL: p_r = sum_j dcmc[j][r] ndc_j.
  double near[4];
  for (int r = 0; r < 4; ++r)
  {
    near[r] = dcmc->GetElement(0, r) * ndc[0] + dcmc->GetElement(1, r) * ndc[1] +
      dcmc->GetElement(2, r) * ndc[2] + dcmc->GetElement(3, r) * ndc[3];
  }
  const float nearDepth = static_cast<float>((near[0] / near[3] - eye[0]) * forward[0] +
    (near[1] / near[3] - eye[1]) * forward[1] + (near[2] / near[3] - eye[2]) * forward[2]);
  this->Program->SetUniformf("nearDepth", nearDepth);
  const float e[3] = { static_cast<float>(eye[0]), static_cast<float>(eye[1]),
    static_cast<float>(eye[2]) };
  const float f[3] = { static_cast<float>(forward[0]), static_cast<float>(forward[1]),
    static_cast<float>(forward[2]) };
  const float c[4] = { static_cast<float>(surfaceRGBA[0]), static_cast<float>(surfaceRGBA[1]),
    static_cast<float>(surfaceRGBA[2]), static_cast<float>(surfaceRGBA[3]) };
  this->Program->SetUniform3f("eye", e);
  this->Program->SetUniform3f("forward", f);
  this->Program->SetUniformi("parallel", parallel ? 1 : 0);
  this->Program->SetUniform4f("surfaceColor", c);
  this->Program->SetUniform3f("pointUp", this->Geometry.PointUp);
  this->Program->SetUniformf("pointSpacing", this->PointSpacing);
  if (this->ReduceMode != 0)
  {
    this->Program->SetUniformi("reduceMode", this->ReduceMode);
    const float valueRange[2] = { static_cast<float>(this->ValueRange[0]),
      static_cast<float>(this->ValueRange[1]) };
    // Clamped to float's range: VTK's default average range is the doubles'.
    const float averageRange[2] = { static_cast<float>(std::max(this->AverageRange[0], -3.0e38)),
      static_cast<float>(std::min(this->AverageRange[1], 3.0e38)) };
    this->Program->SetUniform2f("scalarRange", valueRange);
    this->Program->SetUniform2f("averageRange", averageRange);
  }
  if (isosurface)
  {
    float values[MaxIsosurfaces] = {};
    const int count =
      static_cast<int>(std::min<std::size_t>(this->Isosurfaces.size(), MaxIsosurfaces));
    for (int i = 0; i < count; ++i)
    {
      values[i] = static_cast<float>(this->Isosurfaces[i]);
    }
    this->Program->SetUniformi("isosurfaceCount", count);
    this->Program->SetUniform1fv("isosurfaceValues", MaxIsosurfaces, values);
  }
  this->Program->SetUniformf("opacityScale", static_cast<float>(this->OpacityScale));
  if (shade && !this->SetShadingUniforms(error))
  {
    return false;
  }
  if (shade && this->Scattering)
  {
    this->Scattering->SetUniforms(this->Program);
  }
  if (!this->GradientOpacityTable.empty() && !this->SetGradientOpacityUniforms(window, error))
  {
    return false;
  }
  if (this->Transfer2DTable && this->ReduceMode == 0)
  {
    // x = (v - lo) / (hi - lo) (a range of 0 spans 1e-6, as VTK's), y = min(|g| / g_max, 1).
    const double* t = this->Transfer2DAxes;
    const double span = t[1] > t[0] ? t[1] - t[0] : 1.0e-6;
    const float axes[3] = { static_cast<float>(t[0]), static_cast<float>(1.0 / span),
      static_cast<float>(t[2] > 0.0 ? 1.0 / t[2] : 0.0) };
    this->Transfer2DTable->Activate();
    this->Program->SetUniformi("transfer2DTable", this->Transfer2DTable->GetTextureUnit());
    this->Program->SetUniform3f("transfer2DAxes", axes);
  }
  return (!crop && !clip) || this->SetRegionUniforms(error);
}

std::string vtkOpenGLHybridOctreeBrickDrawer::VariantDefines() const
{
  // The region removes samples in every variant (a removed sample is no sample).
  std::string defines;
  if (this->Region.Cropping)
  {
    defines += "\n#define HO_CROP\n";
  }
  if (!this->Region.ClippingPlanes.empty())
  {
    defines += "\n#define HO_CLIP\n#define HO_MAX_CLIP " + std::to_string(MaxClippingPlanes) + "\n";
  }
  if (this->ReduceMode != 0)
  {
    // A reduced ray: only the samples' values, no per-sample effect.
    return defines + "\n#define HO_REDUCE\n";
  }
  if (this->Dependent)
  {
    defines += "\n#define HO_DEPENDENT2\n";
  }
  if (this->Rgba)
  {
    defines += "\n#define HO_RGBA\n";
  }
  if (this->Gradients || this->Shading.Shade || !this->GradientOpacityTable.empty())
  {
    defines += "\n#define HO_GRADIENTS\n";
  }
  if (this->Shading.Shade)
  {
    defines += "#define HO_SHADE\n#define HO_MAX_LIGHTS " + std::to_string(MaxLights) + "\n";
  }
  if (this->Shading.Shade && this->Scattering)
  {
    defines += "#define HO_SCATTERING\n";
  }
  if (!this->GradientOpacityTable.empty())
  {
    defines += "#define HO_GRADIENT_OPACITY\n";
  }
  if (this->Transfer2DTable)
  {
    defines += "#define HO_TRANSFER_2D\n";
  }
  if (!this->Isosurfaces.empty())
  {
    defines += "\n#define HO_ISOSURFACE\n#define HO_MAX_ISOSURFACES " +
      std::to_string(MaxIsosurfaces) + "\n";
  }
  if (this->Slice)
  {
    defines += "\n#define HO_SLICE\n";
  }
  return defines;
}

void vtkOpenGLHybridOctreeBrickDrawer::SetOpacityEffects(
  bool gradients, const std::vector<float>& table, double end, double scale)
{
  this->Gradients = gradients;
  this->OpacityScale = scale;
  if (table != this->GradientOpacityTable || end != this->GradientOpacityEnd)
  {
    this->GradientOpacityTable = table;
    this->GradientOpacityEnd = end;
    this->GradientOpacityUploaded = false;
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::SetTransfer2D(vtkTextureObject* table, const double axes[3])
{
  this->Transfer2DTable = table;
  for (int k = 0; k < 3; ++k)
  {
    this->Transfer2DAxes[k] = axes[k];
  }
}

bool vtkOpenGLHybridOctreeBrickDrawer::SetGradientOpacityUniforms(
  vtkOpenGLRenderWindow* window, std::string& error)
{
  const std::size_t n = this->GradientOpacityTable.size();
  if (n < 2 || !(this->GradientOpacityEnd > 0.0))
  {
    error = "the gradient opacity table needs 2 or more cells over a positive magnitude range";
    return false;
  }
  if (!this->GradientOpacityTexture)
  {
    this->GradientOpacityTexture = vtkSmartPointer<vtkTextureObject>::New();
    this->GradientOpacityUploaded = false;
  }
  vtkTextureObject* texture = this->GradientOpacityTexture;
  if (!this->GradientOpacityUploaded || texture->GetContext() != window)
  {
    texture->SetContext(window);
    texture->SetWrapS(vtkTextureObject::ClampToEdge);
    texture->SetWrapT(vtkTextureObject::ClampToEdge);
    texture->SetMinificationFilter(vtkTextureObject::Linear);
    texture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!texture->Create2DFromRaw(static_cast<unsigned int>(n), 1, 1, VTK_FLOAT,
          const_cast<float*>(this->GradientOpacityTable.data())))
    {
      error = "OpenGL could not create the gradient opacity table texture";
      return false;
    }
    this->GradientOpacityUploaded = true;
  }
  texture->Activate();
  // Cell k (centre at texture coordinate (k + 0.5) / n) holds magnitude k end / (n - 1).
  const double scale = (n - 1.0) / (n * this->GradientOpacityEnd);
  const float scaleShift[2] = { static_cast<float>(scale), static_cast<float>(0.5 / n) };
  this->Program->SetUniform2f("gradientOpacityScaleShift", scaleShift);
  this->Program->SetUniformi("gradientOpacityTable", texture->GetTextureUnit());
  return true;
}

bool vtkOpenGLHybridOctreeBrickDrawer::SetRegionUniforms(std::string& error)
{
  const vtkHybridOctreeBridge::RegionDescription& r = this->Region;
  if (r.Cropping)
  {
    const float lo[3] = { static_cast<float>(r.CroppingPlanes[0]),
      static_cast<float>(r.CroppingPlanes[2]), static_cast<float>(r.CroppingPlanes[4]) };
    const float hi[3] = { static_cast<float>(r.CroppingPlanes[1]),
      static_cast<float>(r.CroppingPlanes[3]), static_cast<float>(r.CroppingPlanes[5]) };
    this->Program->SetUniform3f("croppingLo", lo);
    this->Program->SetUniform3f("croppingHi", hi);
    this->Program->SetUniformi("croppingFlags", static_cast<int>(r.CroppingFlags));
  }
  const std::size_t count = r.ClippingPlanes.size() / 6;
  if (count == 0)
  {
    return true;
  }
  if (count > static_cast<std::size_t>(MaxClippingPlanes) || r.ClippingPlanes.size() != 6 * count)
  {
    error = "clipping takes 1 to " + std::to_string(MaxClippingPlanes) + " planes, " +
      std::to_string(r.ClippingPlanes.size()) + " values given: remove some planes";
    return false;
  }
  std::vector<float> origins(3 * MaxClippingPlanes, 0.0f), normals(3 * MaxClippingPlanes, 0.0f);
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      origins[3 * i + a] = static_cast<float>(r.ClippingPlanes[6 * i + a]);
      normals[3 * i + a] = static_cast<float>(r.ClippingPlanes[6 * i + 3 + a]);
    }
  }
  using Vec3 = const float(*)[3];
  this->Program->SetUniformi("clipCount", static_cast<int>(count));
  this->Program->SetUniform3fv(
    "clipOrigin", MaxClippingPlanes, reinterpret_cast<Vec3>(origins.data()));
  this->Program->SetUniform3fv(
    "clipNormal", MaxClippingPlanes, reinterpret_cast<Vec3>(normals.data()));
  return true;
}

bool vtkOpenGLHybridOctreeBrickDrawer::SetShadingUniforms(std::string& error)
{
  const vtkHybridOctreeBridge::ShadingDescription& s = this->Shading;
  const std::size_t count = s.LightDirections.size() / 3;
  if (count == 0 || count > static_cast<std::size_t>(MaxLights) ||
    s.LightDiffuse.size() != 3 * count || s.LightSpecular.size() != 3 * count ||
    s.LightAmbient.size() != 3 * count)
  {
    error = "shading takes 1 to " + std::to_string(MaxLights) + " lights, " +
      std::to_string(count) + " given: switch some lights off";
    return false;
  }
  const float material[4] = { static_cast<float>(s.Ambient), static_cast<float>(s.Diffuse),
    static_cast<float>(s.Specular), static_cast<float>(s.SpecularPower) };
  this->Program->SetUniform4f("material", material);
  this->Program->SetUniformi("twoSided", s.TwoSided ? 1 : 0);
  this->Program->SetUniformi("headlight", s.Headlight ? 1 : 0);
  this->Program->SetUniformi("lightCount", static_cast<int>(count));
  std::vector<float> directions(3 * MaxLights, 0.0f), ambient(3 * MaxLights, 0.0f),
    diffuse(3 * MaxLights, 0.0f), specular(3 * MaxLights, 0.0f);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* d = &s.LightDirections[3 * i];
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; ++a)
    {
      directions[3 * i + a] = static_cast<float>(length > 0.0 ? d[a] / length : 0.0);
      ambient[3 * i + a] = static_cast<float>(s.LightAmbient[3 * i + a]);
      diffuse[3 * i + a] = static_cast<float>(s.LightDiffuse[3 * i + a]);
      specular[3 * i + a] = static_cast<float>(s.LightSpecular[3 * i + a]);
    }
  }
  using Vec3 = const float(*)[3];
  this->Program->SetUniform3fv(
    "lightDirection", MaxLights, reinterpret_cast<Vec3>(directions.data()));
  this->Program->SetUniform3fv("lightAmbient", MaxLights, reinterpret_cast<Vec3>(ambient.data()));
  this->Program->SetUniform3fv("lightDiffuse", MaxLights, reinterpret_cast<Vec3>(diffuse.data()));
  this->Program->SetUniform3fv("lightSpecular", MaxLights, reinterpret_cast<Vec3>(specular.data()));
  return true;
}

bool vtkOpenGLHybridOctreeBrickDrawer::SetBricks(vtkOpenGLRenderWindow* window,
  const vtkHybridOctreeBridge::DrawList& list, const double spacing[3],
  const std::vector<const vtkOpenGLHybridOctreeBrickPages::Slot*>& slots, std::string& error)
{
  const std::size_t bricks = list.GetNumberOfBricks();
  if (slots.size() != bricks || this->Geometry.Boxes.size() < 6 * bricks)
  {
    error = "the brick table needs a slot and a box for each of the " + std::to_string(bricks) +
      " bricks";
    return false;
  }
  // Gradients (shading, gradient opacity) or Isosurface: the texture carries one border texel per
  // side.
  const std::size_t border = (this->Gradients || this->Shading.Shade ||
                               !this->GradientOpacityTable.empty() || !this->Isosurfaces.empty())
    ? 2
    : 0;
  this->BrickParameters.assign(TexelsPerBrick * 4 * bricks, 0.0f);
  for (std::size_t i = 0; i < bricks; ++i)
  {
    float* t = &this->BrickParameters[TexelsPerBrick * 4 * i];
    const double* b = &list.Bounds[6 * i];
    const double* box = &this->Geometry.Boxes[6 * i];
    // A ray-marched brick of a frame that widens its spacing (SampleSpacing
    // m > 1) samples every max(d, m d0) along the view (both powers of two
    // times d0, or of the list's refined spacing: still a shared lattice), its
    // opacity corrected for that spacing; d otherwise.
    const double d = list.SliceSpacing[i];
    const double along = this->SampleSpacingOf(list, i);
    for (int a = 0; a < 3; ++a)
    {
      const double step = list.Stride[i] * spacing[a];
      t[a] = static_cast<float>(b[2 * a]);                                // brickLo
      t[4 + a] = static_cast<float>(1.0 / step);                          // inverseStep
      t[8 + a] = static_cast<float>(list.Texels[3 * i + a] + border);     // texels
      t[12 + a] = static_cast<float>(slots[i] ? slots[i]->Offset[a] : 0); // slotOffset
      t[16 + a] = static_cast<float>(box[2 * a]);                         // boxLo
      t[20 + a] = static_cast<float>(box[2 * a + 1]);                     // boxHi
      t[24 + a] = static_cast<float>(step);                               // gradientStep
    }
    t[3] = static_cast<float>(list.OpacityRatio[i] * (d > 0.0 ? along / d : 1.0));
    t[7] = static_cast<float>(along);
    // Jittered: the list asks, or an interactive frame widens the spacing.
    t[11] = this->Jitter || along > d ? 1.0f : 0.0f;
    t[15] = static_cast<float>(along > 0.0 ? this->JitterPeriod / along : 1.0);
  }
  // The table holds as many bricks as the driver's texture buffers take
  // (at least 65536 texels); a longer frame loads it in windows.
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  this->TableCapacity =
    std::max<std::size_t>(static_cast<std::size_t>(maxTexels) / TexelsPerBrick, 1);
  this->TableFirst = 0;
  this->TableCount = 0;
  this->Draws = 0;
  if (!this->BrickTable)
  {
    this->BrickTableBuffer = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->BrickTable = vtkSmartPointer<vtkTextureObject>::New();
  }
  this->BrickTable->SetContext(window);
  return true;
}

bool vtkOpenGLHybridOctreeBrickDrawer::LoadBrickTable(std::size_t first, std::string& error)
{
  const std::size_t bricks = this->BrickParameters.size() / (4 * TexelsPerBrick);
  const std::size_t count = std::min(this->TableCapacity, bricks - first);
  const float* data = this->BrickParameters.data() + 4 * TexelsPerBrick * first;
  if (!this->BrickTableBuffer->Upload(
        data, 4 * TexelsPerBrick * count, vtkOpenGLBufferObject::TextureBuffer) ||
    !this->BrickTable->CreateTextureBuffer(
      static_cast<unsigned int>(TexelsPerBrick * count), 4, VTK_FLOAT, this->BrickTableBuffer))
  {
    error = "OpenGL could not load the table of " + std::to_string(count) + " bricks";
    return false;
  }
  this->TableFirst = first;
  this->TableCount = count;
  // Bound until Unbind(): the runs drawn from this window read it.
  this->BrickTable->Activate();
  this->Program->SetUniformi("brickTable", this->BrickTable->GetTextureUnit());
  this->Program->SetUniformi("brickBase", static_cast<int>(first));
  return true;
}

bool vtkOpenGLHybridOctreeBrickDrawer::DrawBricks(std::size_t first, std::size_t last,
  const vtkOpenGLHybridOctreeBrickPages::Slot& slot, std::string& error)
{
  const std::vector<std::size_t>& brickFirst = this->Geometry.BrickFirst;
  if (!this->Program || !this->BrickTable || last + 1 > brickFirst.size() || first >= last)
  {
    return true;
  }
  vtkTextureObject* page = vtkOpenGLHybridOctreeBrickPages::GetTexture(slot);
  const unsigned int* pageTexels = vtkOpenGLHybridOctreeBrickPages::GetPageTexels(slot);
  const float pageSize[3] = { static_cast<float>(pageTexels[0]), static_cast<float>(pageTexels[1]),
    static_cast<float>(pageTexels[2]) };
  this->Program->SetUniformi("brickTexture", page->GetTextureUnit());
  this->Program->SetUniform3f("pageTexels", pageSize);
  while (first < last)
  {
    if (first < this->TableFirst || first >= this->TableFirst + this->TableCount)
    {
      if (!this->LoadBrickTable(first, error))
      {
        return false;
      }
    }
    const std::size_t end = std::min(last, this->TableFirst + this->TableCount);
    const std::size_t from = brickFirst[first];
    const std::size_t count = brickFirst[end] - from;
    if (count > 0)
    {
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(from), static_cast<GLsizei>(count));
      ++this->Draws;
    }
    first = end;
  }
  return true;
}

double vtkOpenGLHybridOctreeBrickDrawer::SampleSpacingOf(
  const vtkHybridOctreeBridge::DrawList& list, std::size_t i) const
{
  const double d = list.SliceSpacing[i];
  return this->IsRayMarched(i) && this->SampleSpacing > 1
    ? std::max(d, this->SampleSpacing * list.ReferenceSpacing)
    : d;
}

void vtkOpenGLHybridOctreeBrickDrawer::SetJitter(
  bool on, const vtkHybridOctreeBridge::DrawList& list)
{
  this->Jitter = on;
  this->JitterPeriod = 0.0;
  for (std::size_t i = 0; i < list.SliceSpacing.size(); ++i)
  {
    this->JitterPeriod = std::max(this->JitterPeriod, this->SampleSpacingOf(list, i));
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::Rebind(vtkOpenGLRenderWindow* window)
{
  if (this->Program && this->Vao)
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Program);
    this->Vao->Bind();
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::Unbind()
{
  if (this->Vao)
  {
    this->Vao->Release();
  }
  if (this->BrickTable && this->BrickTable->GetContext())
  {
    this->BrickTable->Deactivate();
  }
  if (this->GradientOpacityTexture && this->GradientOpacityTexture->GetContext())
  {
    this->GradientOpacityTexture->Deactivate();
  }
  if (this->Transfer2DTable && this->Transfer2DTable->GetContext())
  {
    this->Transfer2DTable->Deactivate();
  }
  if (this->Scattering)
  {
    this->Scattering->Deactivate();
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::ReleaseGraphicsResources()
{
  if (this->Vertices)
  {
    this->Vertices->ReleaseGraphicsResources();
    this->Vao->ReleaseGraphicsResources();
  }
  this->Vertices = nullptr;
  this->Vao = nullptr;
  this->Program = nullptr;
  if (this->BrickTable && this->BrickTable->GetContext())
  {
    this->BrickTable->ReleaseGraphicsResources(this->BrickTable->GetContext());
  }
  if (this->BrickTableBuffer)
  {
    this->BrickTableBuffer->ReleaseGraphicsResources();
  }
  this->BrickTable = nullptr;
  this->BrickTableBuffer = nullptr;
  this->TableFirst = 0;
  this->TableCount = 0;
  this->Uploaded = false;
  // Their vertices went with the buffer: nothing is drawn before SetGeometry().
  this->Geometry = vtkHybridOctreeBridge::BrickGeometry();
  if (this->GradientOpacityTexture && this->GradientOpacityTexture->GetContext())
  {
    this->GradientOpacityTexture->ReleaseGraphicsResources(
      this->GradientOpacityTexture->GetContext());
  }
  this->GradientOpacityTexture = nullptr;
  this->GradientOpacityUploaded = false;
}
