#include "vtkOpenGLHybridOctreeBrickDrawer.h"

#include "vtkHybridOctreeBrickFS.h"
#include "vtkHybridOctreeBrickVS.h"

#include "vtkHybridOctreeSliceGeometry.h"
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

namespace
{
/// Floats per vertex: position, normal, clip interval (near, far), kind,
/// point opacity. Kinds: 0 a slice, 1 a surface triangle, 2 a ray-marched
/// box, 3 a square point, 4 a Gaussian point. A point's six vertices all
/// hold its centre, its straight colour in the normal, their quad corner
/// (+-1, +-1) in the clip interval, and its opacity a_p.
constexpr std::size_t Stride = 10;
/// The primitive kinds, as the shaders name them (SLICE, SURFACE_TRIANGLE, ...).
enum PrimitiveKind : int
{
  Slice = 0,
  SurfaceTriangle = 1,
  RayMarchedBox = 2,
  SquarePoint = 3,
  GaussianPoint = 4,
};
/// An unbounded clip side (the shader's clip distances stay finite).
constexpr float Unbounded = 1.0e30f;

/// A triangle copy in a slab, clipped to [Near, Far).
struct Placed
{
  std::size_t Slab;
  std::uint32_t Triangle;
  float Near;
  float Far;
};
}

vtkOpenGLHybridOctreeBrickDrawer::vtkOpenGLHybridOctreeBrickDrawer() = default;
vtkOpenGLHybridOctreeBrickDrawer::~vtkOpenGLHybridOctreeBrickDrawer() = default;

void vtkOpenGLHybridOctreeBrickDrawer::Emit(
  const float position[3], const float normal[3], float near, float far, int kind, float alpha)
{
  this->VertexData.insert(this->VertexData.end(),
    { position[0], position[1], position[2], normal[0], normal[1], normal[2], near, far,
      static_cast<float>(kind), alpha });
}

void vtkOpenGLHybridOctreeBrickDrawer::EmitBox(const double bounds[6])
{
  // Corner c at x[c & 1], y[(c >> 1) & 1], z[(c >> 2) & 1]; two triangles a
  // face, wound counter-clockwise seen from inside the box: the faces a ray
  // leaves by are the front faces, so culling back faces leaves one fragment
  // per pixel.
  static const int faces[6][4] = { { 0, 2, 6, 4 }, { 1, 5, 7, 3 }, { 0, 4, 5, 1 }, { 2, 3, 7, 6 },
    { 0, 1, 3, 2 }, { 4, 6, 7, 5 } };
  const float none[3] = { 0.0f, 0.0f, 0.0f };
  for (const auto& f : faces)
  {
    for (int k : { 0, 1, 2, 0, 2, 3 })
    {
      const int c = f[k];
      const float p[3] = { static_cast<float>(bounds[c & 1]),
        static_cast<float>(bounds[2 + ((c >> 1) & 1)]),
        static_cast<float>(bounds[4 + ((c >> 2) & 1)]) };
      this->Emit(p, none, -Unbounded, Unbounded, RayMarchedBox);
    }
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::CollectPoints(const vtkHybridOctreeBridge::DrawList& list,
  std::size_t bucket, const PointData& points, const double eye[3], std::vector<SlabItem>& items)
{
  const vtkHybridOctreeBridge::PointsDrawing& d = *points.Drawing;
  const std::vector<float>& shades = *points.Shades;
  const std::size_t count = std::min(d.Position.size() / 3, shades.size() / 4);
  for (std::size_t k = list.BucketPointOffsets[bucket]; k < list.BucketPointOffsets[bucket + 1];
       ++k)
  {
    const std::uint32_t id = list.BucketPoints[k];
    if (id >= count || !(shades[4 * static_cast<std::size_t>(id) + 3] > 0.0f))
    {
      continue; // not in the set, or adds nothing
    }
    const float* p = &d.Position[3 * static_cast<std::size_t>(id)];
    double z = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      z += (p[a] - eye[a]) * list.Forward[a];
    }
    items.push_back({ z, id, true });
  }
}

void vtkOpenGLHybridOctreeBrickDrawer::EmitPoint(const PointData& points, std::uint32_t id)
{
  static const float corners[6][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, -1 }, { 1, 1 },
    { -1, 1 } };
  const int kind = points.Gaussian ? GaussianPoint : SquarePoint;
  const float* p = &points.Drawing->Position[3 * static_cast<std::size_t>(id)];
  const float* shade = &(*points.Shades)[4 * static_cast<std::size_t>(id)];
  for (const auto& c : corners)
  {
    this->Emit(p, shade, c[0], c[1], kind, shade[3]);
  }
  ++this->PointsPlaced;
}

std::size_t vtkOpenGLHybridOctreeBrickDrawer::Build(const vtkHybridOctreeBridge::DrawList& list,
  const std::vector<double>& bounds, const std::vector<char>& drawn, const double eye[3],
  const double viewUp[3], const SurfaceData& surface, const PointData& points)
{
  double right[3], up[3];
  vtkHybridOctreeSliceGeometry::ViewBasis(list.Forward, viewUp, right, up);
  for (int a = 0; a < 3; ++a)
  {
    this->PointUp[a] = static_cast<float>(up[a]);
  }
  this->PointSpacing = static_cast<float>(list.ReferenceSpacing);
  this->PointsPlaced = 0;
  const bool withPoints =
    points.Drawing && points.Shades && list.BucketOffsets.size() == list.GetNumberOfBricks() + 1;
  std::vector<SlabItem> items;
  this->VertexData.clear();
  this->Boxes.clear();
  this->RayMarched.clear();
  this->BrickFirst.assign(1, 0);
  this->Uploaded = false;
  const bool withSurface = surface.Vertices && surface.Triangles &&
    list.BatchOffsets.size() == list.GetNumberOfBricks() + 1;
  const float* sv = withSurface ? surface.Vertices->data() : nullptr;
  const std::size_t vertexCount = withSurface ? surface.Vertices->size() / 6 : 0;
  const float noNormal[3] = { 0.0f, 0.0f, 0.0f };
  const float f[3] = { static_cast<float>(list.Forward[0]), static_cast<float>(list.Forward[1]),
    static_cast<float>(list.Forward[2]) };
  const float e[3] = { static_cast<float>(eye[0]), static_cast<float>(eye[1]),
    static_cast<float>(eye[2]) };
  std::vector<float> polygon;
  std::vector<Placed> placed;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  std::size_t placedTotal = 0;
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    const double* slices = list.Slices.data() + list.SliceOffsets[i];
    const std::size_t n = list.SliceOffsets[i + 1] - list.SliceOffsets[i];
    // slab(z) = #{ k : S[k] > z }, the slices being sorted back to front.
    auto slab = [&](double z) {
      return static_cast<std::size_t>(
        std::partition_point(slices, slices + n, [z](double s) { return s > z; }) - slices);
    };
    placed.clear();
    if (withSurface)
    {
      ranges.clear();
      for (std::size_t k = list.BatchOffsets[i]; k < list.BatchOffsets[i + 1]; ++k)
      {
        ranges.emplace_back(list.BatchFirst[k], list.BatchEnd[k]);
      }
      // The union of the batches' ranges (a batch spanning slabs is listed once per slab).
      std::sort(ranges.begin(), ranges.end());
      std::uint32_t covered = 0;
      for (const auto& range : ranges)
      {
        for (std::uint32_t t = std::max(range.first, covered); t < range.second; ++t)
        {
          if (3 * static_cast<std::size_t>(t) + 2 >= surface.Triangles->size())
          {
            continue;
          }
          double zmin = HUGE_VAL, zmax = -HUGE_VAL;
          for (int c = 0; c < 3; ++c)
          {
            const unsigned int v = (*surface.Triangles)[3 * static_cast<std::size_t>(t) + c];
            const float* p = sv + 6 * std::min<std::size_t>(v, vertexCount - 1);
            const double z = (p[0] - e[0]) * static_cast<double>(f[0]) +
              (p[1] - e[1]) * static_cast<double>(f[1]) + (p[2] - e[2]) * static_cast<double>(f[2]);
            zmin = std::min(zmin, z);
            zmax = std::max(zmax, z);
          }
          const std::size_t far = slab(zmax);
          const std::size_t near = slab(zmin);
          if (far == near)
          {
            placed.push_back({ far, t, -Unbounded, Unbounded });
            continue;
          }
          for (std::size_t s = far; s <= near; ++s)
          {
            placed.push_back({ s, t, s < n ? static_cast<float>(slices[s]) : -Unbounded,
              s > 0 ? static_cast<float>(slices[s - 1]) : Unbounded });
          }
        }
        covered = std::max(covered, range.second);
      }
      std::stable_sort(placed.begin(), placed.end(),
        [](const Placed& a, const Placed& b) { return a.Slab < b.Slab; });
      placedTotal += placed.size();
    }
    this->Boxes.insert(this->Boxes.end(), &bounds[6 * i], &bounds[6 * i] + 6);
    // Brick i's point buckets, by slab: [bucket, lastBucket).
    std::size_t bucket = withPoints ? list.BucketOffsets[i] : 0;
    const std::size_t lastBucket = withPoints ? list.BucketOffsets[i + 1] : 0;
    if (placed.empty() && bucket == lastBucket)
    {
      // No triangles between its slices: the brick is ray-marched, drawn as its box.
      if (drawn[i] && n > 0)
      {
        this->EmitBox(&bounds[6 * i]);
      }
      this->BrickFirst.push_back(this->VertexData.size() / Stride);
      this->RayMarched.push_back(1);
      continue;
    }
    std::size_t next = 0;
    for (std::size_t s = 0; s <= n; ++s)
    {
      // The slab's triangles and points, far first (the CPU compositor
      // sorts a pixel's hits in a slab by depth): a triangle at its
      // centroid's depth within its clip interval, ties in list order.
      items.clear();
      for (; next < placed.size() && placed[next].Slab == s; ++next)
      {
        double z = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          const unsigned int v =
            (*surface.Triangles)[3 * static_cast<std::size_t>(placed[next].Triangle) + c];
          const float* p = sv + 6 * std::min<std::size_t>(v, vertexCount - 1);
          for (int a = 0; a < 3; ++a)
          {
            z += (p[a] - e[a]) * static_cast<double>(f[a]) / 3.0;
          }
        }
        z = std::min(std::max(z, static_cast<double>(placed[next].Near)),
          static_cast<double>(placed[next].Far));
        items.push_back({ z, static_cast<std::uint32_t>(next), false });
      }
      for (; bucket < lastBucket && list.BucketSlab[bucket] <= s; ++bucket)
      {
        this->CollectPoints(list, bucket, points, eye, items);
      }
      std::stable_sort(items.begin(), items.end(),
        [](const SlabItem& a, const SlabItem& b) { return a.Depth > b.Depth; });
      for (const SlabItem& item : items)
      {
        if (item.Point)
        {
          this->EmitPoint(points, item.Id);
          continue;
        }
        const Placed& t = placed[item.Id];
        for (int c = 0; c < 3; ++c)
        {
          const unsigned int v = (*surface.Triangles)[3 * static_cast<std::size_t>(t.Triangle) + c];
          const float* p = sv + 6 * std::min<std::size_t>(v, vertexCount - 1);
          this->Emit(p, p + 3, t.Near, t.Far, SurfaceTriangle);
        }
      }
      if (s < n && drawn[i])
      {
        polygon.clear();
        vtkHybridOctreeSliceGeometry::AppendSlicePolygon(
          &bounds[6 * i], eye, list.Forward, right, up, slices[s], polygon);
        for (std::size_t v = 0; v + 2 < polygon.size(); v += 3)
        {
          this->Emit(&polygon[v], noNormal, -Unbounded, Unbounded, Slice);
        }
      }
    }
    this->BrickFirst.push_back(this->VertexData.size() / Stride);
    this->RayMarched.push_back(0);
  }
  return placedTotal;
}

bool vtkOpenGLHybridOctreeBrickDrawer::Bind(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
  vtkTextureObject* table, vtkOpenGLHybridOctreeFloatTarget& target, int entries, double lo,
  double hi, const double eye[3], const double forward[3], bool parallel,
  const double surfaceRGBA[4], std::string& error)
{
  vtkTextureObject* depth = target.GetDepth();
  const bool shade = this->Shading.Shade;
  std::string fragment = vtkHybridOctreeBrickFS;
  if (shade)
  {
    // The shading variant: its own program; the unshaded one is unchanged.
    const std::string system = "//VTK::System::Dec";
    const std::size_t at = fragment.find(system);
    const std::string defines =
      "\n#define HO_SHADE\n#define HO_MAX_LIGHTS " + std::to_string(MaxLights) + "\n";
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
    if (!this->VertexData.empty() &&
      !this->Vertices->Upload(this->VertexData, vtkOpenGLBufferObject::ArrayBuffer))
    {
      error = "could not load the slices into an OpenGL buffer";
      this->Vao->Release();
      return false;
    }
    this->Uploaded = true;
  }
  const int stride = static_cast<int>(Stride * sizeof(float));
  if (!this->VertexData.empty() &&
    (!this->Vao->AddAttributeArray(
       this->Program, this->Vertices, "vertexMC", 0, stride, VTK_FLOAT, 3, false) ||
      !this->Vao->AddAttributeArray(this->Program, this->Vertices, "normalMC", 3 * sizeof(float),
        stride, VTK_FLOAT, 3, false) ||
      !this->Vao->AddAttributeArray(
        this->Program, this->Vertices, "clipMC", 6 * sizeof(float), stride, VTK_FLOAT, 2, false) ||
      !this->Vao->AddAttributeArray(
        this->Program, this->Vertices, "kindMC", 8 * sizeof(float), stride, VTK_FLOAT, 1, false) ||
      !this->Vao->AddAttributeArray(
        this->Program, this->Vertices, "alphaMC", 9 * sizeof(float), stride, VTK_FLOAT, 1, false)))
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
  this->Program->SetUniform3f("pointUp", this->PointUp);
  this->Program->SetUniformf("pointSpacing", this->PointSpacing);
  if (shade && !this->SetShadingUniforms(error))
  {
    return false;
  }
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

void vtkOpenGLHybridOctreeBrickDrawer::DrawBrick(const vtkHybridOctreeBridge::DrawList& list,
  std::size_t i, const double spacing[3], vtkTextureObject* texture)
{
  if (i + 1 >= this->BrickFirst.size() || !this->Program)
  {
    return;
  }
  const std::size_t first = this->BrickFirst[i];
  const std::size_t count = this->BrickFirst[i + 1] - first;
  if (count == 0)
  {
    return;
  }
  const double* b = &list.Bounds[6 * i];
  const float lo[3] = { static_cast<float>(b[0]), static_cast<float>(b[2]),
    static_cast<float>(b[4]) };
  float inverseStep[3];
  float n[3];
  float gradientStep[3];
  // Shaded: the texture carries one border texel per side.
  const std::size_t border = this->Shading.Shade ? 2 : 0;
  for (int a = 0; a < 3; ++a)
  {
    inverseStep[a] = static_cast<float>(1.0 / (list.Stride[i] * spacing[a]));
    gradientStep[a] = static_cast<float>(list.Stride[i] * spacing[a]);
    n[a] = static_cast<float>(list.Texels[3 * i + a] + border);
  }
  if (border)
  {
    this->Program->SetUniform3f("gradientStep", gradientStep);
  }
  this->Program->SetUniformi("brickTexture", texture->GetTextureUnit());
  this->Program->SetUniform3f("brickLo", lo);
  this->Program->SetUniform3f("inverseStep", inverseStep);
  this->Program->SetUniform3f("texels", n);
  // A ray-marched brick samples every max(d, SampleSpacing d0) along the
  // view (both powers of two times d0: still a shared lattice), its opacity
  // corrected for that spacing.
  const double d = list.SliceSpacing[i];
  const double along =
    this->IsRayMarched(i) ? std::max(d, this->SampleSpacing * list.ReferenceSpacing) : d;
  this->Program->SetUniformf(
    "opacityRatio", static_cast<float>(list.OpacityRatio[i] * (d > 0.0 ? along / d : 1.0)));
  const double* box = &this->Boxes[6 * i];
  const float boxLo[3] = { static_cast<float>(box[0]), static_cast<float>(box[2]),
    static_cast<float>(box[4]) };
  const float boxHi[3] = { static_cast<float>(box[1]), static_cast<float>(box[3]),
    static_cast<float>(box[5]) };
  this->Program->SetUniform3f("boxLo", boxLo);
  this->Program->SetUniform3f("boxHi", boxHi);
  this->Program->SetUniformf("sliceSpacing", static_cast<float>(along));
  this->Program->SetUniformi("jitter", along > d ? 1 : 0);
  glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(count));
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
  this->Uploaded = false;
}
