#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeBridge.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkHybridOctreeVolumeMapper);

namespace
{
using namespace vtkHybridOctreeBridge;

const char* VertexShader = R"(//VTK::System::Dec
in vec3 vertexWC;
uniform mat4 WCDC;
out vec3 positionWC;
void main()
{
  positionWC = vertexWC;
  gl_Position = WCDC * vec4(vertexWC, 1.0);
}
)";

const char* FragmentShader = R"(//VTK::System::Dec
in vec3 positionWC;
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
  vec3 u = clamp((positionWC - brickLo) * inverseStep, vec3(0.0), texels - vec3(1.0));
  float value = texture(brickTexture, (u + vec3(0.5)) / texels).r;
  vec4 c = texture(transferTable, vec2(value * tableScaleShift.x + tableScaleShift.y, 0.5));
  float a = clamp(c.a, 0.0, 1.0);
  if (a < 1.0)
  {
    a = 1.0 - exp(opacityRatio * log(1.0 - a));
  }
  gl_FragData[0] = vec4(clamp(c.rgb, 0.0, 1.0) * a, a);
}
)";

bool ToBridgeType(int vtkType, ScalarType& type)
{
  switch (vtkType)
  {
    case VTK_UNSIGNED_CHAR:
      type = ScalarType::U8;
      return true;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      type = ScalarType::I8;
      return true;
    case VTK_UNSIGNED_SHORT:
      type = ScalarType::U16;
      return true;
    case VTK_SHORT:
      type = ScalarType::I16;
      return true;
    case VTK_UNSIGNED_INT:
      type = ScalarType::U32;
      return true;
    case VTK_INT:
      type = ScalarType::I32;
      return true;
    case VTK_FLOAT:
      type = ScalarType::F32;
      return true;
    case VTK_DOUBLE:
      type = ScalarType::F64;
      return true;
    default:
      return false;
  }
}

std::size_t ByteCount(vtkDataArray* scalars)
{
  return static_cast<std::size_t>(scalars->GetNumberOfTuples()) *
    static_cast<std::size_t>(scalars->GetNumberOfComponents()) *
    static_cast<std::size_t>(scalars->GetDataTypeSize());
}

const void* Bytes(vtkDataArray* scalars)
{
  return ByteCount(scalars) > 0 ? scalars->GetVoidPointer(0) : nullptr;
}

bool SameGrid(const GridDescription& a, const GridDescription& b)
{
  for (int i = 0; i < 3; ++i)
  {
    if (a.Dims[i] != b.Dims[i] || a.Spacing[i] != b.Spacing[i] || a.Origin[i] != b.Origin[i])
    {
      return false;
    }
  }
  return a.Type == b.Type && a.Components == b.Components && a.Component == b.Component;
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The polygon of the plane {x : (x - eye) . forward = depth} inside the box
/// `bounds` (VTK order), as a triangle fan appended to `out` (3 floats per
/// vertex); returns the vertices appended.
std::size_t SlicePolygon(const double bounds[6], const double eye[3], const double forward[3],
  const double right[3], const double up[3], double depth, std::vector<float>& out)
{
  double corners[8][3];
  double dist[8];
  for (int c = 0; c < 8; ++c)
  {
    corners[c][0] = bounds[(c & 1)];
    corners[c][1] = bounds[2 + ((c >> 1) & 1)];
    corners[c][2] = bounds[4 + ((c >> 2) & 1)];
    const double rel[3] = { corners[c][0] - eye[0], corners[c][1] - eye[1],
      corners[c][2] - eye[2] };
    dist[c] = Dot(rel, forward) - depth;
  }
  static const int edges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
    { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
  std::vector<std::array<double, 3>> points;
  for (int c = 0; c < 8; ++c)
  {
    if (dist[c] == 0.0)
    {
      points.push_back({ corners[c][0], corners[c][1], corners[c][2] });
    }
  }
  for (const auto& e : edges)
  {
    const double da = dist[e[0]], db = dist[e[1]];
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
    {
      const double t = da / (da - db);
      std::array<double, 3> p;
      for (int k = 0; k < 3; ++k)
      {
        p[k] = corners[e[0]][k] + t * (corners[e[1]][k] - corners[e[0]][k]);
      }
      points.push_back(p);
    }
  }
  if (points.size() < 3)
  {
    return 0;
  }
  double centre[3] = { 0.0, 0.0, 0.0 };
  for (const auto& p : points)
  {
    for (int k = 0; k < 3; ++k)
    {
      centre[k] += p[k] / static_cast<double>(points.size());
    }
  }
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double rel[3] = { points[i][0] - centre[0], points[i][1] - centre[1],
      points[i][2] - centre[2] };
    order.emplace_back(std::atan2(Dot(rel, up), Dot(rel, right)), i);
  }
  std::sort(order.begin(), order.end());
  std::size_t added = 0;
  for (std::size_t i = 1; i + 1 < order.size(); ++i)
  {
    for (std::size_t j : { order[0].second, order[i].second, order[i + 1].second })
    {
      out.push_back(static_cast<float>(points[j][0]));
      out.push_back(static_cast<float>(points[j][1]));
      out.push_back(static_cast<float>(points[j][2]));
      ++added;
    }
  }
  return added;
}
} // namespace

struct vtkHybridOctreeVolumeMapper::vtkInternals
{
  // Octree cache.
  std::unique_ptr<VolumeOctree> Octree;
  vtkDataArray* Array = nullptr;
  vtkMTimeType ArrayMTime = 0;
  GridDescription Grid;
  int LeafSize = 0;
  unsigned long OctreeGeneration = 0;

  // Selection cache.
  std::unique_ptr<Selection> Selected;
  unsigned long SelectedGeneration = 0;
  std::size_t SelectedBudget = 0;
  double SelectedTolerance = -1.0;
  std::vector<double> SelectedOpacity;

  // Transfer function table, the points the CPU compositor gets.
  std::vector<double> ColorPoints;
  std::vector<double> OpacityPoints;
  std::vector<float> Table;
  double RangeLo = 0.0;
  double RangeHi = 1.0;

  // GL resources.
  std::map<std::pair<std::uint32_t, std::size_t>, vtkSmartPointer<vtkTextureObject>> Textures;
  unsigned long TexturesGeneration = 0;
  vtkSmartPointer<vtkTextureObject> TableTexture;
  vtkSmartPointer<vtkOpenGLBufferObject> Vertices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> Vao;

  vtkDataArray* Scalars = nullptr;
};

vtkHybridOctreeVolumeMapper::vtkHybridOctreeVolumeMapper()
  : Internals(new vtkInternals)
{
}

vtkHybridOctreeVolumeMapper::~vtkHybridOctreeVolumeMapper() = default;

int vtkHybridOctreeVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  // Accept any data set so that a non-image input is a clear error, not a pipeline failure.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  // Optional, so that Render() with no input reports its own error.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

bool vtkHybridOctreeVolumeMapper::Prepare(vtkRenderer* vtkNotUsed(ren), vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  if (this->GetNumberOfInputConnections(0) == 0)
  {
    vtkErrorMacro("no input: connect a vtkImageData with point scalars");
    return false;
  }
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkDataSet* data = this->GetDataSetInput();
  if (!data)
  {
    vtkErrorMacro("no input: connect a vtkImageData with point scalars");
    return false;
  }
  vtkImageData* image = vtkImageData::SafeDownCast(data);
  if (!image)
  {
    vtkErrorMacro("the input is a " << data->GetClassName()
                                    << ", not a vtkImageData: the mapper draws images only");
    return false;
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars || image->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("the input image is empty or has no point scalars");
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components > 1 && this->Component < 0)
  {
    vtkErrorMacro("the point scalars have " << components
                                            << " components: choose one with SetComponent()");
    return false;
  }
  if (this->Component >= components)
  {
    vtkErrorMacro("component " << this->Component << " does not exist: the point scalars have "
                               << components << " components");
    return false;
  }
  GridDescription grid;
  if (!ToBridgeType(scalars->GetDataType(), grid.Type))
  {
    vtkErrorMacro("scalar type " << scalars->GetDataTypeAsString() << " is not supported");
    return false;
  }
  const int* extent = image->GetExtent();
  const double* spacing = image->GetSpacing();
  const double* origin = image->GetOrigin();
  for (int axis = 0; axis < 3; ++axis)
  {
    const int cells = extent[2 * axis + 1] - extent[2 * axis];
    grid.Dims[axis] = cells >= 0 ? static_cast<std::size_t>(cells) + 1 : 0;
    grid.Spacing[axis] = spacing[axis];
    grid.Origin[axis] = origin[axis] + extent[2 * axis] * spacing[axis];
  }
  grid.Components = static_cast<std::size_t>(components);
  grid.Component = components > 1 ? this->Component : -1;
  if (this->BudgetMB <= 0.0)
  {
    vtkErrorMacro("the texture budget is 0 MB: set BudgetMB > 0");
    return false;
  }

  std::string error;
  if (!in.Octree || in.Array != scalars || in.ArrayMTime != scalars->GetMTime() ||
    !SameGrid(in.Grid, grid) || in.LeafSize != this->LeafSize)
  {
    in.Octree.reset();
    in.Selected.reset();
    in.Octree = VolumeOctree::Build(Bytes(scalars), ByteCount(scalars), grid,
      static_cast<unsigned int>(this->LeafSize), error);
    if (!in.Octree)
    {
      vtkErrorMacro(<< error);
      return false;
    }
    in.Array = scalars;
    in.ArrayMTime = scalars->GetMTime();
    in.Grid = grid;
    in.LeafSize = this->LeafSize;
    ++in.OctreeGeneration;
  }
  in.Scalars = scalars;

  vtkVolumeProperty* property = vol ? vol->GetProperty() : nullptr;
  if (!property)
  {
    vtkErrorMacro("the volume has no vtkVolumeProperty");
    return false;
  }
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);

  // The transfer function table over the scalars' range.
  double range[2];
  scalars->GetRange(range, grid.Component < 0 ? 0 : grid.Component);
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  const int n = this->TableSize;
  std::vector<double> rgb(3 * static_cast<std::size_t>(n));
  std::vector<double> alpha(static_cast<std::size_t>(n));
  color->GetTable(range[0], range[1], n, rgb.data());
  opacity->GetTable(range[0], range[1], n, alpha.data());
  in.RangeLo = range[0];
  in.RangeHi = range[1];
  in.Table.assign(4 * static_cast<std::size_t>(n), 0.0f);
  in.ColorPoints.clear();
  in.OpacityPoints.clear();
  for (int k = 0; k < n; ++k)
  {
    const double v = range[0] + (range[1] - range[0]) * k / (n - 1);
    const double a = std::min(1.0, std::max(0.0, alpha[k]));
    for (int c = 0; c < 3; ++c)
    {
      in.Table[4 * k + c] = static_cast<float>(rgb[3 * k + c]);
    }
    in.Table[4 * k + 3] = static_cast<float>(a);
    in.ColorPoints.insert(in.ColorPoints.end(),
      { v, static_cast<double>(in.Table[4 * k]), static_cast<double>(in.Table[4 * k + 1]),
        static_cast<double>(in.Table[4 * k + 2]) });
    in.OpacityPoints.insert(in.OpacityPoints.end(), { v, static_cast<double>(in.Table[4 * k + 3]) });
  }

  // The selection.
  SelectDescription select;
  select.BudgetBytes = static_cast<std::size_t>(this->BudgetMB * 1.0e6);
  select.Tolerance = this->ErrorTolerance;
  select.OpacityPoints = vtkHybridOctreeBridge::OpacityPoints(opacity);
  if (!in.Selected || in.SelectedGeneration != in.OctreeGeneration ||
    in.SelectedBudget != select.BudgetBytes || in.SelectedTolerance != select.Tolerance ||
    in.SelectedOpacity != select.OpacityPoints)
  {
    in.Selected = in.Octree->Select(select, error);
    if (!in.Selected)
    {
      vtkErrorMacro(<< error);
      return false;
    }
    in.SelectedGeneration = in.OctreeGeneration;
    in.SelectedBudget = select.BudgetBytes;
    in.SelectedTolerance = select.Tolerance;
    in.SelectedOpacity = select.OpacityPoints;
  }
  return true;
}

void vtkHybridOctreeVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  this->LastRenderOK = false;
  this->LastBricks = 0;
  this->LastSlices = 0;
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* window =
    ren ? vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()) : nullptr;
  vtkOpenGLCamera* camera = ren ? vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera()) : nullptr;
  if (!window || !camera)
  {
    vtkErrorMacro("an OpenGL render window and camera are required");
    return;
  }
  if (!this->Prepare(ren, vol))
  {
    return;
  }
  std::string error;
  const CameraDescription cam = DescribeCamera(camera);
  DrawList list;
  if (!in.Selected->GetDrawList(*in.Octree, cam, list, error))
  {
    vtkErrorMacro(<< error);
    return;
  }

  // Slice polygons, on the CPU.
  double right[3], up[3];
  {
    const double* f = list.Forward;
    const double* vu = cam.ViewUp;
    right[0] = f[1] * vu[2] - f[2] * vu[1];
    right[1] = f[2] * vu[0] - f[0] * vu[2];
    right[2] = f[0] * vu[1] - f[1] * vu[0];
    const double norm = std::sqrt(Dot(right, right));
    for (double& r : right)
    {
      r /= norm;
    }
    up[0] = right[1] * f[2] - right[2] * f[1];
    up[1] = right[2] * f[0] - right[0] * f[2];
    up[2] = right[0] * f[1] - right[1] * f[0];
  }
  const std::size_t bricks = list.GetNumberOfBricks();
  std::vector<float> vertices;
  std::vector<std::size_t> first(bricks + 1, 0);
  for (std::size_t i = 0; i < bricks; ++i)
  {
    for (std::size_t s = list.SliceOffsets[i]; s < list.SliceOffsets[i + 1]; ++s)
    {
      SlicePolygon(&list.Bounds[6 * i], cam.Position, list.Forward, right, up, list.Slices[s],
        vertices);
    }
    first[i + 1] = vertices.size() / 3;
    this->LastSlices += static_cast<vtkTypeInt64>(list.SliceOffsets[i + 1] - list.SliceOffsets[i]);
  }

  // Textures: keep those the selection still draws, upload the new ones.
  if (in.TexturesGeneration != in.OctreeGeneration)
  {
    for (auto& t : in.Textures)
    {
      t.second->ReleaseGraphicsResources(window);
    }
    in.Textures.clear();
    in.TexturesGeneration = in.OctreeGeneration;
  }
  std::map<std::pair<std::uint32_t, std::size_t>, vtkSmartPointer<vtkTextureObject>> used;
  std::vector<vtkTextureObject*> textures(bricks, nullptr);
  std::vector<float> texels;
  for (std::size_t i = 0; i < bricks; ++i)
  {
    const auto key = std::make_pair(list.NodeId[i], list.Stride[i]);
    auto found = in.Textures.find(key);
    vtkSmartPointer<vtkTextureObject> texture;
    if (found != in.Textures.end())
    {
      texture = found->second;
    }
    else
    {
      if (!in.Selected->GetBrickTexels(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            list.Brick[i], texels, error))
      {
        vtkErrorMacro(<< error);
        return;
      }
      texture = vtkSmartPointer<vtkTextureObject>::New();
      texture->SetContext(window);
      texture->SetWrapS(vtkTextureObject::ClampToEdge);
      texture->SetWrapT(vtkTextureObject::ClampToEdge);
      texture->SetWrapR(vtkTextureObject::ClampToEdge);
      texture->SetMinificationFilter(vtkTextureObject::Linear);
      texture->SetMagnificationFilter(vtkTextureObject::Linear);
      if (!texture->Create3DFromRaw(static_cast<unsigned int>(list.Texels[3 * i]),
            static_cast<unsigned int>(list.Texels[3 * i + 1]),
            static_cast<unsigned int>(list.Texels[3 * i + 2]), 1, VTK_FLOAT, texels.data()))
      {
        vtkErrorMacro("could not create the 3D texture of brick " << i);
        return;
      }
    }
    used[key] = texture;
    textures[i] = texture;
  }
  for (auto& t : in.Textures)
  {
    if (!used.count(t.first))
    {
      t.second->ReleaseGraphicsResources(window);
    }
  }
  in.Textures.swap(used);
  this->LastTextureBytes = 0;
  for (std::size_t i = 0; i < bricks; ++i)
  {
    this->LastTextureBytes += static_cast<vtkTypeInt64>(4 * list.Texels[3 * i] *
      list.Texels[3 * i + 1] * list.Texels[3 * i + 2]);
  }

  // The transfer function table.
  if (!in.TableTexture)
  {
    in.TableTexture = vtkSmartPointer<vtkTextureObject>::New();
  }
  in.TableTexture->SetContext(window);
  in.TableTexture->SetWrapS(vtkTextureObject::ClampToEdge);
  in.TableTexture->SetWrapT(vtkTextureObject::ClampToEdge);
  in.TableTexture->SetMinificationFilter(vtkTextureObject::Linear);
  in.TableTexture->SetMagnificationFilter(vtkTextureObject::Linear);
  in.TableTexture->Create2DFromRaw(
    static_cast<unsigned int>(this->TableSize), 1, 4, VTK_FLOAT, in.Table.data());

  if (vertices.empty())
  {
    this->LastBricks = static_cast<int>(bricks);
    this->LastRenderOK = true;
    return;
  }

  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(VertexShader, FragmentShader, "");
  if (!program)
  {
    vtkErrorMacro("could not compile the slice shader");
    return;
  }
  if (!in.Vertices)
  {
    in.Vertices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    in.Vao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
  }
  in.Vertices->Upload(vertices, vtkOpenGLBufferObject::ArrayBuffer);
  in.Vao->Bind();
  if (!in.Vao->AddAttributeArray(
        program, in.Vertices, "vertexWC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
  {
    vtkErrorMacro("could not bind the slice vertices");
    in.Vao->Release();
    return;
  }

  vtkMatrix4x4* wcvc;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  vtkMatrix3x3* normals;
  camera->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  program->SetUniformMatrix("WCDC", wcdc);
  const double scale = (this->TableSize - 1.0) / (this->TableSize * (in.RangeHi - in.RangeLo));
  const float scaleShift[2] = { static_cast<float>(scale),
    static_cast<float>(0.5 / this->TableSize - in.RangeLo * scale) };
  program->SetUniform2f("tableScaleShift", scaleShift);

  vtkOpenGLState* state = window->GetState();
  {
    vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    vtkOpenGLState::ScopedglActiveTexture activeTexture(state);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglDisable(GL_CULL_FACE);

    in.TableTexture->Activate();
    program->SetUniformi("transferTable", in.TableTexture->GetTextureUnit());
    for (std::size_t i = 0; i < bricks; ++i)
    {
      const GLsizei count = static_cast<GLsizei>(first[i + 1] - first[i]);
      if (count == 0)
      {
        continue;
      }
      const double* b = &list.Bounds[6 * i];
      const float lo[3] = { static_cast<float>(b[0]), static_cast<float>(b[2]),
        static_cast<float>(b[4]) };
      float inverseStep[3];
      float n[3];
      for (int a = 0; a < 3; ++a)
      {
        inverseStep[a] = static_cast<float>(1.0 / (list.Stride[i] * in.Grid.Spacing[a]));
        n[a] = static_cast<float>(list.Texels[3 * i + a]);
      }
      textures[i]->Activate();
      program->SetUniformi("brickTexture", textures[i]->GetTextureUnit());
      program->SetUniform3f("brickLo", lo);
      program->SetUniform3f("inverseStep", inverseStep);
      program->SetUniform3f("texels", n);
      program->SetUniformf("opacityRatio", static_cast<float>(list.OpacityRatio[i]));
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first[i]), count);
      textures[i]->Deactivate();
    }
    in.TableTexture->Deactivate();
  }
  in.Vao->Release();
  this->LastBricks = static_cast<int>(bricks);
  this->LastRenderOK = true;
}

bool vtkHybridOctreeVolumeMapper::CompositeOnCPU(
  vtkRenderer* ren, vtkVolume* vol, int width, int height, vtkFloatArray* rgba)
{
  vtkInternals& in = *this->Internals;
  if (!ren || !ren->GetActiveCamera() || !rgba || width <= 0 || height <= 0)
  {
    vtkErrorMacro("CompositeOnCPU needs a renderer with a camera, a size and an output array");
    return false;
  }
  if (!this->Prepare(ren, vol))
  {
    return false;
  }
  std::vector<float> out;
  std::string error;
  if (!in.Selected->Composite(*in.Octree, DescribeCamera(ren->GetActiveCamera()), Bytes(in.Scalars),
        ByteCount(in.Scalars), in.Grid, in.ColorPoints, in.OpacityPoints,
        static_cast<std::size_t>(width), static_cast<std::size_t>(height), out, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  std::copy(out.begin(), out.end(), rgba->GetPointer(0));
  return true;
}

void vtkHybridOctreeVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  for (auto& t : in.Textures)
  {
    t.second->ReleaseGraphicsResources(window);
  }
  in.Textures.clear();
  if (in.TableTexture)
  {
    in.TableTexture->ReleaseGraphicsResources(window);
  }
  if (in.Vertices)
  {
    in.Vertices->ReleaseGraphicsResources();
  }
  if (in.Vao)
  {
    in.Vao->ReleaseGraphicsResources();
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkHybridOctreeVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BudgetMB: " << this->BudgetMB << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "TableSize: " << this->TableSize << "\n";
  os << indent << "LastBricks: " << this->LastBricks << "\n";
  os << indent << "LastTextureBytes: " << this->LastTextureBytes << "\n";
  os << indent << "LastSlices: " << this->LastSlices << "\n";
  os << indent << "LastRenderOK: " << this->LastRenderOK << "\n";
}
