/**
 * @file   TestHybridOctreeBridge.cxx
 * @brief  The render half of the bridge, as vtkHybridOctreeVolumeMapper will
 *         call it: select bricks of a vtkImageData within a budget, get the
 *         DrawList for a vtkCamera, read each brick's texels.
 *
 * Scenarios: `draw_list` (budget kept, bricks back to front for a camera
 * along +z and a diagonal one, slices inside their brick), `texels` (every
 * brick's texels are the image at the texel positions), `surface` (a kept
 * isosurface: translucent batches cover every triangle, opaque pass first,
 * hidden: volume only), `transparent` (a
 * vtkPiecewiseFunction that is 0 everywhere: no brick), `errors` (budget 0,
 * NaN tolerance, bad ROI, camera at its focal point, brick out of range,
 * another octree's selection: clear messages, no crash), `points` (the
 * hybrid representation's points kept for drawing: positions, shades, a
 * selection that buys them within the budget, their buckets in the
 * DrawList, and the errors), `geometry` (the OpenGL mapper's vertices of a
 * DrawList: each brick's block ranges from its texels, the boxes of its
 * visible blocks under an opaque and a transparent table, one ray-marched
 * box a brick without a surface, and mismatched inputs: clear errors),
 * `shading`, `region` (cropping and a clipping plane in the selection:
 * fewer bricks, more skipped, the DrawList's Effects and Region say what
 * acts; a region around the whole image acts not at all; a plane of 5
 * numbers is refused with a message).
 */
#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeCameraInput.h"

#include "HybridOctreeTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

namespace
{
namespace B = vtkHybridOctreeBridge;

/// The wavelet on extent [0, 24] x [0, 20] x [0, 16] (float), its octree and grid.
struct Fixture
{
  vtkNew<vtkRTAnalyticSource> Source;
  vtkImageData* Image = nullptr;
  vtkFloatArray* Values = nullptr;
  B::GridDescription Grid;
  std::unique_ptr<B::HybridOctree> Octree;

  Fixture()
  {
    this->Source->SetWholeExtent(0, 24, 0, 20, 0, 16);
    this->Source->Update();
    this->Image = this->Source->GetOutput();
    this->Values = vtkFloatArray::SafeDownCast(this->Image->GetPointData()->GetScalars());
    int dims[3];
    this->Image->GetDimensions(dims);
    this->Grid.Type = B::ScalarType::F32;
    for (int a = 0; a < 3; ++a)
    {
      this->Grid.Dims[a] = static_cast<std::size_t>(dims[a]);
      this->Grid.Spacing[a] = this->Image->GetSpacing()[a];
      this->Grid.Origin[a] = this->Image->GetOrigin()[a];
    }
    std::string error;
    this->Octree = B::HybridOctree::Build(this->Bytes(), this->ByteCount(), this->Grid, 8, error);
    if (!this->Octree)
    {
      std::cerr << "build failed: " << error << "\n";
    }
  }

  const void* Bytes() const { return this->Values->GetVoidPointer(0); }
  std::size_t ByteCount() const
  {
    return static_cast<std::size_t>(this->Values->GetDataSize()) * sizeof(float);
  }
  float At(std::size_t i, std::size_t j, std::size_t k) const
  {
    return this->Values->GetValue(
      static_cast<vtkIdType>(i + this->Grid.Dims[0] * (j + this->Grid.Dims[1] * k)));
  }
};

/// A vtkCamera looking at the image centre from `direction` (unit not needed), far away.
void Aim(vtkCamera* camera, const double centre[3], const double direction[3], bool parallel)
{
  camera->SetFocalPoint(centre[0], centre[1], centre[2]);
  camera->SetPosition(
    centre[0] - 80 * direction[0], centre[1] - 80 * direction[1], centre[2] - 80 * direction[2]);
  // Up across the view: +y when looking mostly along z, else +z.
  const double n = std::sqrt(
    direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  if (std::abs(direction[2]) > 0.9 * n)
  {
    camera->SetViewUp(0.0, 1.0, 0.0);
  }
  else
  {
    camera->SetViewUp(0.0, 0.0, 1.0);
  }
  camera->SetParallelProjection(parallel ? 1 : 0);
  camera->SetParallelScale(20.0);
  camera->SetViewAngle(30.0);
}

double Depth(const B::CameraDescription& c, const double forward[3], const double p[3])
{
  double d = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    d += (p[a] - c.Position[a]) * forward[a];
  }
  return d;
}

/// The largest stride sliced at its own spacing (src/spacing.rs): the largest
/// power of two c with c d0 <= (thinnest side) / 16, d0 = 1 here.
std::size_t MaxSliceStride(const B::GridDescription& grid)
{
  double thinnest = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    thinnest = std::min(thinnest, static_cast<double>(grid.Dims[a] - 1) * grid.Spacing[a]);
  }
  std::size_t c = 1;
  while (2.0 * static_cast<double>(c) <= thinnest / 16.0)
  {
    c *= 2;
  }
  return c;
}

/// Checks one DrawList: sizes, passes, the forward axis, slices inside their
/// brick and back to front, and of two face-adjacent bricks the one beyond
/// the shared face (seen from the eye) drawn first.
void CheckDrawList(Checker& check, const B::DrawList& list, const B::CameraDescription& camera,
  std::uint64_t bricks, std::size_t maxSliceStride, const std::string& name)
{
  const std::size_t n = list.GetNumberOfBricks();
  check.Check(n == bricks, name + ": one entry per selected brick");
  check.Check(list.Passes == "volume", name + ": passes '" + list.Passes + "' should be 'volume'");
  check.Check(list.ReferenceSpacing == 1.0, name + ": reference spacing 1");
  check.Check(list.Bounds.size() == 6 * n && list.Texels.size() == 3 * n &&
      list.SliceOffsets.size() == n + 1 && list.SliceOffsets.back() == list.Slices.size(),
    name + ": flattened sizes");
  double view[3], norm = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    view[a] = camera.FocalPoint[a] - camera.Position[a];
    norm += view[a] * view[a];
  }
  for (int a = 0; a < 3; ++a)
  {
    check.Check(std::abs(view[a] / std::sqrt(norm) - list.Forward[a]) < 1e-12,
      name + ": forward is the unit view direction");
  }
  std::size_t adjacent = 0; // face-adjacent pairs whose order was checked
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* b = &list.Bounds[6 * i];
    check.Check(
      std::abs(list.OpacityRatio[i] - list.SliceSpacing[i] / list.ReferenceSpacing) < 1e-12,
      name + ": opacity ratio d/d0");
    check.Check(list.SliceSpacing[i] ==
        static_cast<double>(std::min<std::size_t>(list.Stride[i], maxSliceStride)),
      name + ": slice spacing = min(stride, c) * d0");
    double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin;
    for (int c = 0; c < 8; ++c)
    {
      const double corner[3] = { b[(c & 1) ? 1 : 0], b[(c & 2) ? 3 : 2], b[(c & 4) ? 5 : 4] };
      const double d = Depth(camera, list.Forward, corner);
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
    const std::size_t s0 = list.SliceOffsets[i], s1 = list.SliceOffsets[i + 1];
    check.Check(s1 > s0, name + ": every brick has slices");
    for (std::size_t s = s0; s < s1; ++s)
    {
      check.Check(list.Slices[s] >= dmin - 1e-9 && list.Slices[s] <= dmax + 1e-9,
        name + ": slice " + std::to_string(s) + " inside brick " + std::to_string(i));
      check.Check(s == s0 || list.Slices[s] < list.Slices[s - 1], name + ": slices back to front");
    }
    // Face-adjacent bricks: the one on the far side of the shared face from the eye comes first.
    for (std::size_t j = i + 1; j < n; ++j)
    {
      const double* c = &list.Bounds[6 * j];
      for (int a = 0; a < 3; ++a)
      {
        bool overlap = true;
        for (int o = 0; o < 3; ++o)
        {
          if (o != a && std::min(b[2 * o + 1], c[2 * o + 1]) - std::max(b[2 * o], c[2 * o]) <= 0.0)
          {
            overlap = false;
          }
        }
        if (!overlap)
        {
          continue;
        }
        // j drawn after i must be on the eye's side of the shared face (parallel:
        // the side the view comes from; a face along the view orders nothing).
        adjacent += c[2 * a] == b[2 * a + 1] || c[2 * a + 1] == b[2 * a];
        if (c[2 * a] == b[2 * a + 1]) // j above i along a
        {
          check.Check(camera.Parallel ? list.Forward[a] <= 1e-12 : camera.Position[a] >= c[2 * a],
            name + ": brick " + std::to_string(j) + " (above " + std::to_string(i) +
              ") drawn later but farther");
        }
        else if (c[2 * a + 1] == b[2 * a]) // j below i along a
        {
          check.Check(camera.Parallel ? list.Forward[a] >= -1e-12 : camera.Position[a] <= b[2 * a],
            name + ": brick " + std::to_string(j) + " (below " + std::to_string(i) +
              ") drawn later but farther");
        }
      }
    }
  }
  check.Check(adjacent > 0, name + ": some face-adjacent bricks to order");
}

std::vector<double> Ramp(double lo, double hi)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(lo, 0.0);
  opacity->AddPoint(hi, 0.8);
  return B::OpacityPoints(opacity);
}

int DrawLists()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  double range[2];
  f.Values->GetRange(range);
  B::SelectDescription options;
  options.BudgetBytes = 20000;
  options.Tolerance = 0.0;
  options.OpacityPoints = Ramp(range[0], range[1]);
  check.Check(options.OpacityPoints.size() == 4, "two opacity nodes, clamped: two pairs");
  options.HasRoi = true;
  options.RoiCenter[0] = 3.0;
  options.RoiCenter[1] = 3.0;
  options.RoiCenter[2] = 3.0;
  options.RoiRadius = 2.0;
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  if (!check.Check(selection != nullptr, "select: " + error))
  {
    return EXIT_FAILURE;
  }
  B::SelectionSummary summary;
  check.Check(selection->GetSummary(summary, error), "summary: " + error);
  std::cout << "bricks " << summary.Bricks << ", " << summary.TextureBytes << " of "
            << summary.BudgetBytes << " bytes, estimated error " << summary.EstimatedError
            << ", warning '" << summary.Warning << "'\n";
  check.Check(
    summary.TextureBytes <= 20000 && summary.BudgetBytes == 20000, "bytes within the budget");
  check.Check(summary.Bricks > 1, "more than one brick");

  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double alongZ[3] = { 0.0, 0.0, 1.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  const double back[3] = { -0.3, -1.0, -0.7 };
  struct View
  {
    const double* Direction;
    bool Parallel;
    const char* Name;
  };
  for (const View& v : { View{ alongZ, true, "+z parallel" }, View{ diagonal, false, "diagonal" },
         View{ back, false, "back diagonal" } })
  {
    vtkNew<vtkCamera> camera;
    Aim(camera, centre, v.Direction, v.Parallel);
    const B::CameraDescription desc = vtkHybridOctreeCameraInput::DescribeCamera(camera);
    check.Check(desc.Parallel == v.Parallel && desc.ViewAngle == 30.0 && desc.ParallelScale == 20.0,
      std::string(v.Name) + ": DescribeCamera");
    B::DrawList list;
    if (check.Check(selection->GetDrawList(*f.Octree, desc, 0.0, list, error),
          std::string(v.Name) + ": draw list: " + error))
    {
      CheckDrawList(check, list, desc, summary.Bricks, MaxSliceStride(f.Grid), v.Name);
    }
  }
  return check.Result();
}

int Texels()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  if (!check.Check(selection != nullptr, "select: " + error))
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, diagonal, false);
  B::DrawList list;
  if (!check.Check(selection->GetDrawList(*f.Octree,
                     vtkHybridOctreeCameraInput::DescribeCamera(camera), 0.0, list, error),
        "draw list: " + error))
  {
    return EXIT_FAILURE;
  }
  bool strided = false;
  std::vector<float> texels;
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    const std::size_t* n = &list.Texels[3 * i];
    texels.assign(n[0] * n[1] * n[2], -1.0f);
    if (!check.Check(selection->GetBrickTexels(f.Bytes(), f.ByteCount(), f.Grid, list.Brick[i],
                       texels.data(), texels.size(), error),
          "texels: " + error))
    {
      continue;
    }
    const std::size_t stride = list.Stride[i];
    strided = strided || stride > 1;
    check.Check(texels.size() == n[0] * n[1] * n[2], "texel count = product of the dims");
    std::size_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = static_cast<std::size_t>(
        std::lround((list.Bounds[6 * i + 2 * a] - f.Grid.Origin[a]) / f.Grid.Spacing[a]));
      hi[a] = static_cast<std::size_t>(
        std::lround((list.Bounds[6 * i + 2 * a + 1] - f.Grid.Origin[a]) / f.Grid.Spacing[a]));
    }
    std::size_t wrong = 0;
    for (std::size_t k = 0; k < n[2]; ++k)
    {
      for (std::size_t j = 0; j < n[1]; ++j)
      {
        for (std::size_t t = 0; t < n[0]; ++t)
        {
          const float expected = f.At(std::min(lo[0] + t * stride, hi[0]),
            std::min(lo[1] + j * stride, hi[1]), std::min(lo[2] + k * stride, hi[2]));
          wrong += texels[t + n[0] * (j + n[1] * k)] != expected;
        }
      }
    }
    check.Check(wrong == 0,
      "brick " + std::to_string(i) + ": " + std::to_string(wrong) +
        " texels differ from the image at the texel positions");
  }
  check.Check(strided, "some brick is downsampled (stride > 1)");
  return check.Result();
}

/// Shading through the bridge: the border bytes counted only when asked
/// for, the plan "volume-shaded" once SetShading() is given a lighting that
/// changes colours, the bordered texels the image at clamp(lo + (i - 1)
/// stride, 0, dims - 1), bad shading refused with a message.
int Shading()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  options.GradientBorder = true;
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  B::SelectionSummary summary;
  if (!check.Check(selection && selection->GetSummary(summary, error), "select: " + error))
  {
    return EXIT_FAILURE;
  }
  check.Check(summary.TextureBytes <= options.BudgetBytes, "within the budget, borders counted");
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, diagonal, false);
  const B::CameraDescription cam = vtkHybridOctreeCameraInput::DescribeCamera(camera);
  B::ShadingDescription shading;
  shading.Shade = true;
  shading.LightDirections = { 0.0, 0.0, -1.0 };
  shading.LightAmbient = { 1.0, 1.0, 1.0 };
  shading.LightDiffuse = { 1.0, 1.0, 1.0 };
  shading.LightSpecular = { 1.0, 1.0, 1.0 };
  B::DrawList list;
  check.Check(selection->SetShading(shading, error), "set shading: " + error);
  if (!check.Check(selection->GetDrawList(*f.Octree, cam, 0.0, list, error), "list: " + error))
  {
    return EXIT_FAILURE;
  }
  check.Check(list.Passes == "volume-shaded", "shaded passes: " + list.Passes);
  std::size_t wrong = 0;
  std::vector<float> texels;
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    const std::size_t n[3] = { list.Texels[3 * i] + 2, list.Texels[3 * i + 1] + 2,
      list.Texels[3 * i + 2] + 2 };
    texels.assign(n[0] * n[1] * n[2], -1.0f);
    if (!check.Check(selection->GetBrickTexelsBordered(f.Bytes(), f.ByteCount(), f.Grid,
                       list.Brick[i], texels.data(), texels.size(), error),
          "bordered texels: " + error))
    {
      continue;
    }
    const long stride = static_cast<long>(list.Stride[i]);
    long lo[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::lround((list.Bounds[6 * i + 2 * a] - f.Grid.Origin[a]) / f.Grid.Spacing[a]);
    }
    auto at = [&](int a, std::size_t t) {
      const long p = lo[a] + (static_cast<long>(t) - 1) * stride;
      return static_cast<std::size_t>(
        std::min(std::max(p, 0L), static_cast<long>(f.Grid.Dims[a]) - 1));
    };
    for (std::size_t k = 0; k < n[2]; ++k)
    {
      for (std::size_t j = 0; j < n[1]; ++j)
      {
        for (std::size_t t = 0; t < n[0]; ++t)
        {
          wrong += texels[t + n[0] * (j + n[1] * k)] != f.At(at(0, t), at(1, j), at(2, k));
        }
      }
    }
  }
  check.Check(wrong == 0, std::to_string(wrong) + " bordered texels differ from the image");
  // Identity shading (ambient 1, diffuse and specular 0) is planned unshaded.
  B::ShadingDescription identity = shading;
  identity.Ambient = 1.0;
  identity.Diffuse = 0.0;
  identity.Specular = 0.0;
  check.Check(selection->SetShading(identity, error) &&
      selection->GetDrawList(*f.Octree, cam, 0.0, list, error) && list.Passes == "volume",
    "identity shading plans 'volume': " + list.Passes + " " + error);
  B::ShadingDescription bad = shading;
  bad.LightDiffuse = { 1.0 };
  check.Check(!selection->SetShading(bad, error) && error.find("3 of each") != std::string::npos,
    "lights not in threes: '" + error + "'");
  return check.Result();
}

/// Gradient opacity through the bridge: VTK's points in the selection count
/// the border of a varying function and hide everything under one that is 0
/// everywhere; SetGradientOpacity() gives the DrawList the effect
/// "gradient-opacity", bordered textures and its table (or "opacity-scale"
/// for a constant 0.5, nothing for 1); bad points are refused with a message.
int GradientOpacity()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  std::string error;
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  options.GradientOpacityPoints = { 0.0, 0.0, 5.0, 0.0 };
  B::SelectionSummary summary;
  std::unique_ptr<B::Selection> hidden = f.Octree->Select(options, error);
  check.Check(hidden && hidden->GetSummary(summary, error) && summary.Bricks == 0,
    "a gradient opacity of 0 everywhere selects no brick: " + error);
  options.GradientOpacityPoints = { 0.0, 0.0, 1.0, 1.0 };
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  if (!check.Check(selection && selection->GetSummary(summary, error), "select: " + error))
  {
    return EXIT_FAILURE;
  }
  check.Check(summary.Bricks > 0 && summary.TextureBytes <= options.BudgetBytes,
    "bricks within the budget, borders counted");
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, diagonal, false);
  const B::CameraDescription cam = vtkHybridOctreeCameraInput::DescribeCamera(camera);
  B::DrawList list;
  check.Check(selection->SetGradientOpacity(options.GradientOpacityPoints, error) &&
      selection->GetDrawList(*f.Octree, cam, 0.0, list, error),
    "list: " + error);
  check.Check(list.Effects == "gradient-opacity" && list.Gradients && list.Passes == "volume",
    "effects '" + list.Effects + "', passes '" + list.Passes + "'");
  check.Check(list.GradientOpacityTable.size() == 4096 && list.GradientOpacityEnd > 0.0 &&
      list.GradientOpacityTable.front() == 0.0f,
    "the gradient opacity table");
  std::vector<float> texels;
  if (list.GetNumberOfBricks() > 0)
  {
    texels.assign((list.Texels[0] + 2) * (list.Texels[1] + 2) * (list.Texels[2] + 2), 0.0f);
    check.Check(selection->GetBrickTexelsBordered(f.Bytes(), f.ByteCount(), f.Grid, list.Brick[0],
                  texels.data(), texels.size(), error),
      "bordered texels: " + error);
  }
  check.Check(selection->SetGradientOpacity({ 0.0, 1.0, 9.0, 1.0 }, error) &&
      selection->GetDrawList(*f.Octree, cam, 0.0, list, error) && list.Effects.empty() &&
      !list.Gradients && list.GradientOpacityTable.empty(),
    "1 everywhere is no effect: '" + list.Effects + "' " + error);
  check.Check(selection->SetGradientOpacity({ 0.0, 0.5 }, error) &&
      selection->GetDrawList(*f.Octree, cam, 0.0, list, error) && list.Effects == "opacity-scale" &&
      list.OpacityScale == 0.5 && !list.Gradients,
    "a constant 0.5 scales the opacity: '" + list.Effects + "' " + error);
  check.Check(!selection->SetGradientOpacity({ 0.0, 0.5, 1.0 }, error) &&
      error.find("pairs") != std::string::npos,
    "an odd count refused: '" + error + "'");
  check.Check(!selection->SetGradientOpacity({ 0.0, 1.5 }, error) &&
      error.find("[0, 1]") != std::string::npos,
    "an opacity above 1 refused: '" + error + "'");
  return check.Result();
}

int SurfaceBatches()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  options.HasIsovalue = true;
  options.Isovalue = 150.0;
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  B::SurfaceSummary mesh;
  const bool surface = f.Octree->IntegrateSurface(
    f.Bytes(), f.ByteCount(), f.Grid, 150.0, B::SurfaceMode::Discretized, false, mesh, error);
  if (!check.Check(selection && surface, "select and surface: " + error))
  {
    return EXIT_FAILURE;
  }
  std::vector<float> vertices;
  std::vector<unsigned int> indices;
  check.Check(f.Octree->GetSurfaceTriangles(vertices, indices, error), "triangles: " + error);
  check.Check(mesh.Polygons > 0 && indices.size() == 3 * mesh.Polygons &&
      vertices.size() == 6 * mesh.Vertices,
    "a surface");
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, diagonal, false);
  const B::CameraDescription view = vtkHybridOctreeCameraInput::DescribeCamera(camera);
  for (int round = 0; round < 2; ++round) // the second round reuses the kept slab batching
  {
    B::DrawList list;
    if (!check.Check(
          selection->GetDrawList(*f.Octree, view, 0.5, list, error), "translucent: " + error))
    {
      return check.Result();
    }
    const std::size_t n = list.GetNumberOfBricks();
    check.Check(list.Passes == "surface-in-slabs,volume", "translucent passes: " + list.Passes);
    check.Check(list.OpaqueTriangles == 0 && list.BatchOffsets.size() == n + 1 &&
        list.BatchOffsets.back() == list.BatchSlab.size() &&
        list.BatchClip.size() == 2 * list.BatchSlab.size(),
      "translucent: batch sizes");
    std::vector<bool> seen(mesh.Polygons, false);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t slices = list.SliceOffsets[i + 1] - list.SliceOffsets[i];
      for (std::size_t k = list.BatchOffsets[i]; k < list.BatchOffsets[i + 1]; ++k)
      {
        check.Check(list.BatchSlab[k] <= slices, "batch slab within the brick's slabs");
        check.Check(list.BatchClip[2 * k] < list.BatchClip[2 * k + 1], "clip near < far");
        check.Check(list.BatchFirst[k] < list.BatchEnd[k] && list.BatchEnd[k] <= mesh.Polygons,
          "batch triangles within the mesh");
        for (std::uint32_t t = list.BatchFirst[k]; t < list.BatchEnd[k] && t < mesh.Polygons; ++t)
        {
          seen[t] = true;
        }
      }
    }
    check.Check(std::all_of(seen.begin(), seen.end(), [](bool v) { return v; }),
      "every triangle is in some batch");
  }
  B::DrawList opaque;
  check.Check(selection->GetDrawList(*f.Octree, view, 1.0, opaque, error), error);
  check.Check(opaque.Passes == "surface-opaque,volume" && opaque.OpaqueTriangles == mesh.Polygons &&
      opaque.BatchSlab.empty(),
    "opaque: surface pass first, all triangles, no batches (" + opaque.Passes + ")");
  B::DrawList hidden;
  check.Check(selection->GetDrawList(*f.Octree, view, 0.0, hidden, error), error);
  check.Check(
    hidden.Passes == "volume" && hidden.OpaqueTriangles == 0, "hidden surface: volume only");
  error.clear();
  check.Check(!selection->GetDrawList(*f.Octree, view, 2.0, hidden, error) &&
      error.find("surface opacity") != std::string::npos,
    "opacity 2: '" + error + "'");
  return check.Result();
}

int Transparent()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkPiecewiseFunction> zero;
  zero->AddPoint(-1000.0, 0.0);
  zero->AddPoint(1000.0, 0.0);
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  options.OpacityPoints = B::OpacityPoints(zero);
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  if (!check.Check(selection != nullptr, "select: " + error))
  {
    return EXIT_FAILURE;
  }
  B::SelectionSummary summary;
  selection->GetSummary(summary, error);
  check.Check(summary.Bricks == 0 && summary.TextureBytes == 0 && summary.Skipped > 0,
    "a transparent transfer function selects no brick");
  vtkNew<vtkCamera> camera;
  B::DrawList list;
  check.Check(selection->GetDrawList(
                *f.Octree, vtkHybridOctreeCameraInput::DescribeCamera(camera), 0.0, list, error),
    "draw list: " + error);
  check.Check(list.GetNumberOfBricks() == 0 && list.Passes.empty(), "nothing to draw");
  // Clamping off: the opacity steps to 0 outside the nodes.
  vtkNew<vtkPiecewiseFunction> window;
  window->AddPoint(100.0, 0.5);
  window->AddPoint(200.0, 0.5);
  window->ClampingOff();
  const std::vector<double> points = B::OpacityPoints(window);
  check.Check(points == std::vector<double>{ 100.0, 0.0, 100.0, 0.5, 200.0, 0.5, 200.0, 0.0 },
    "unclamped opacity: 0 outside the nodes");
  return check.Result();
}

int Errors()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  const auto fails = [&](const B::SelectDescription& o, const std::string& fragment) {
    std::string error;
    const bool refused = f.Octree->Select(o, error) == nullptr;
    check.Check(refused && error.find(fragment) != std::string::npos,
      "expected an error with '" + fragment + "', got '" + error + "'");
  };
  B::SelectDescription options;
  options.BudgetBytes = 0;
  fails(options, "budget is 0 bytes");
  options.BudgetBytes = 30000;
  options.Tolerance = std::numeric_limits<double>::quiet_NaN();
  fails(options, "error tolerance NaN");
  options.Tolerance = 0.0;
  options.HasRoi = true;
  options.RoiRadius = 0.0;
  fails(options, "region of interest");
  options.HasRoi = false;
  options.OpacityPoints = { 0.0, 1.0, 2.0 };
  fails(options, "(value, opacity) pairs");
  options.OpacityPoints.clear();

  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  if (!check.Check(selection != nullptr, "select: " + error))
  {
    return EXIT_FAILURE;
  }
  B::CameraDescription camera; // default: at (0, 0, 1) looking at the origin
  camera.FocalPoint[2] = camera.Position[2];
  B::DrawList list;
  error.clear();
  check.Check(!selection->GetDrawList(*f.Octree, camera, 0.0, list, error) &&
      error.find("position equals the focal point") != std::string::npos,
    "camera at its focal point: '" + error + "'");
  Fixture other;
  error.clear();
  check.Check(!selection->GetDrawList(*other.Octree, B::CameraDescription(), 0.0, list, error) &&
      error.find("another octree") != std::string::npos,
    "another octree: '" + error + "'");
  std::vector<float> texels(8);
  error.clear();
  check.Check(!selection->GetBrickTexels(
                f.Bytes(), f.ByteCount(), f.Grid, 1000000, texels.data(), texels.size(), error) &&
      error.find("does not exist") != std::string::npos,
    "brick out of range: '" + error + "'");
  B::GridDescription moved = f.Grid;
  moved.Origin[0] += 1.0;
  error.clear();
  check.Check(!selection->GetBrickTexels(
                f.Bytes(), f.ByteCount(), moved, 0, texels.data(), texels.size(), error) &&
      error.find("image changed") != std::string::npos,
    "another image: '" + error + "'");
  return check.Result();
}
int Points()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  B::PointsOptions options;
  options.Factor = 2;
  options.UseBudget = true;
  options.Budget = 300; // the 300 largest underestimates of stride-2 textures
  options.UnderestimatesOnly = true;
  std::string error;
  B::PointsSummary made;
  if (!check.Check(
        f.Octree->IntegratePoints(f.Bytes(), f.ByteCount(), f.Grid, options, made, error),
        "make points: " + error))
  {
    return EXIT_FAILURE;
  }
  B::PointsDrawing drawing;
  check.Check(f.Octree->GetPointsDrawing(drawing, error), "drawing: " + error);
  const std::size_t n = drawing.Value.size();
  check.Check(n == 300 && drawing.Position.size() == 3 * n && drawing.Error.size() == n &&
      drawing.Factor == 2 && drawing.PointBytes == 6 * n,
    "300 points, 6 bytes each, with positions, values and errors");
  bool inside = true, positive = true;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double x = drawing.Position[3 * i + a];
      const double lo = f.Grid.Origin[a];
      const double hi = lo + f.Grid.Spacing[a] * static_cast<double>(f.Grid.Dims[a] - 1);
      inside = inside && x >= lo - 1e-4 && x <= hi + 1e-4;
    }
    positive = positive && drawing.Error[i] > 0.0f;
  }
  check.Check(inside, "points inside the image");
  check.Check(positive, "underestimates only");
  // Shades for a ramp: 4 floats a point, colours and opacities in [0, 1].
  const std::vector<double> colors = { 30.0, 0.1, 0.2, 0.9, 280.0, 0.9, 0.1, 0.1 };
  const std::vector<double> opacities = { 30.0, 0.0, 280.0, 0.6 };
  std::vector<float> shades;
  check.Check(
    f.Octree->GetPointShades(f.Bytes(), f.ByteCount(), f.Grid, colors, opacities, shades, error),
    "shades: " + error);
  bool ranged = shades.size() == 4 * n;
  std::size_t adding = 0;
  for (std::size_t i = 0; ranged && i < shades.size(); ++i)
  {
    ranged = shades[i] >= 0.0f && shades[i] <= 1.0f;
    adding += (i % 4 == 3 && shades[i] > 0.0f) ? 1 : 0;
  }
  check.Check(ranged && adding > 0, "shades in [0, 1], some points add opacity");
  // A budget between stride 2 and full resolution: the selection buys points.
  B::SelectDescription select;
  select.BudgetBytes = 12000;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(select, error);
  if (!check.Check(selection != nullptr, "select with points: " + error))
  {
    return EXIT_FAILURE;
  }
  B::SelectionSummary summary;
  check.Check(selection->GetSummary(summary, error), "summary: " + error);
  std::cout << "points bought " << summary.Points << " (" << summary.PointBytes
            << " bytes), texture bytes " << summary.TextureBytes << "\n";
  check.Check(summary.Points > 0 && summary.PointBytes == 6 * summary.Points &&
      summary.TextureBytes + summary.PointBytes <= 12000,
    "points bought within the budget with the textures");
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.7, 0.4 };
  Aim(camera, centre, diagonal, false);
  B::DrawList list;
  check.Check(selection->GetDrawList(
                *f.Octree, vtkHybridOctreeCameraInput::DescribeCamera(camera), 0.0, list, error),
    "draw list: " + error);
  const std::size_t bricks = list.GetNumberOfBricks();
  check.Check(list.BucketOffsets.size() == bricks + 1 &&
      list.BucketPointOffsets.size() == list.BucketSlab.size() + 1 &&
      list.BucketPoints.size() == summary.Points,
    "every point bought is in one bucket");
  check.Check(list.Passes == "volume,points", "plan 'volume,points': '" + list.Passes + "'");
  bool strides = true;
  for (std::size_t i = 0; i < bricks; ++i)
  {
    strides =
      strides && (list.BucketOffsets[i] == list.BucketOffsets[i + 1] || list.Stride[i] == 2);
  }
  check.Check(strides, "points only in bricks of stride 2");
  // Errors.
  check.Check(!f.Octree->GetPointShades(
                f.Bytes(), f.ByteCount(), f.Grid, { 0.0, 1.0 }, opacities, shades, error) &&
      error.find("tuples") != std::string::npos,
    "bad colour points: '" + error + "'");
  B::PointsOptions optimized = options;
  optimized.MaxOverestimate = 0.1;
  check.Check(
    !f.Octree->IntegratePoints(f.Bytes(), f.ByteCount(), f.Grid, optimized, made, error) &&
      error.find("max_overestimate") != std::string::npos,
    "the optimized low resolution cannot be drawn: '" + error + "'");
  B::PointsOptions odd = options;
  odd.Factor = 3;
  check.Check(!f.Octree->IntegratePoints(f.Bytes(), f.ByteCount(), f.Grid, odd, made, error) &&
      error.find("factor 3") != std::string::npos,
    "factor 3: '" + error + "'");
  // A failed integration leaves no points: the selection buys none.
  std::unique_ptr<B::Selection> without = f.Octree->Select(select, error);
  check.Check(without && without->GetSummary(summary, error) && summary.Points == 0,
    "no points after a failed integration");
  return check.Result();
}
int Geometry()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  B::SelectDescription options;
  options.BudgetBytes = 30000;
  std::string error;
  std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double direction[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, direction, false);
  const B::CameraDescription desc = vtkHybridOctreeCameraInput::DescribeCamera(camera);
  B::DrawList list;
  if (!check.Check(selection && selection->GetDrawList(*f.Octree, desc, 0.0, list, error),
        "draw list: " + error))
  {
    return EXIT_FAILURE;
  }
  const std::size_t n = list.GetNumberOfBricks();
  std::vector<std::vector<float>> ranges(n);
  B::BrickGeometryInput input;
  input.List = &list;
  std::copy(desc.Position, desc.Position + 3, input.Eye);
  std::copy(desc.ViewUp, desc.ViewUp + 3, input.ViewUp);
  std::copy(f.Grid.Spacing, f.Grid.Spacing + 3, input.Spacing);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t* dims = &list.Texels[3 * i];
    std::vector<float> texels(dims[0] * dims[1] * dims[2]);
    check.Check(selection->GetBrickTexels(f.Bytes(), f.ByteCount(), f.Grid, list.Brick[i],
                  texels.data(), texels.size(), error) &&
        B::MeasureBlockRanges(texels.data(), texels.size(), dims, ranges[i], error),
      "block ranges of brick " + std::to_string(i) + ": " + error);
    // 2 per block of 4^3 cells.
    std::size_t blocks = 1;
    for (int a = 0; a < 3; ++a)
    {
      blocks *= dims[a] > 1 ? (dims[a] - 2) / 4 + 1 : 1;
    }
    check.Check(ranges[i].size() == 2 * blocks, "two values a block");
    input.BlockRanges.push_back(&ranges[i]);
  }
  double range[2];
  f.Values->GetRange(range);
  input.TableLo = range[0];
  input.TableHi = range[1];
  // Opaque everywhere: every brick drawn in its whole box, ray-marched (no surface).
  const std::vector<float> opaque(4 * 16, 1.0f);
  input.Table = &opaque;
  B::BrickGeometry geometry;
  if (check.Check(B::GetBrickGeometry(input, geometry, error), "geometry: " + error))
  {
    check.Check(geometry.BrickFirst.size() == n + 1 && geometry.RayMarched.size() == n &&
        geometry.Drawn.size() == n && geometry.Boxes.size() == 6 * n,
      "per-brick sizes");
    check.Check(geometry.Boxes == list.Bounds, "all blocks visible: the boxes are the bricks'");
    check.Check(std::count(geometry.Drawn.begin(), geometry.Drawn.end(), 1) ==
          static_cast<std::ptrdiff_t>(n) &&
        std::count(geometry.RayMarched.begin(), geometry.RayMarched.end(), 1) ==
          static_cast<std::ptrdiff_t>(n),
      "every brick drawn, ray-marched");
    check.Check(geometry.VertexFloats == 11 * 36 * n && geometry.BrickFirst.back() == 36 * n,
      "one box (12 triangles) a brick, 11 floats a vertex");
    bool named = true;
    for (std::size_t i = 0; i < n; ++i)
    {
      for (std::size_t v = geometry.BrickFirst[i]; v < geometry.BrickFirst[i + 1]; ++v)
      {
        named = named && geometry.Vertices[11 * v + 10] == static_cast<float>(i);
      }
    }
    check.Check(named, "every vertex names its brick");
  }
  // Transparent everywhere: nothing drawn.
  const std::vector<float> clear(4 * 16, 0.0f);
  input.Table = &clear;
  if (check.Check(B::GetBrickGeometry(input, geometry, error), "geometry: " + error))
  {
    check.Check(std::count(geometry.Drawn.begin(), geometry.Drawn.end(), 0) ==
          static_cast<std::ptrdiff_t>(n) &&
        geometry.VertexFloats == 0,
      "no block visible: nothing drawn");
  }
  // Mismatched inputs: clear errors, no crash.
  const auto fails = [&](const B::BrickGeometryInput& bad, const std::string& fragment) {
    std::string message;
    B::BrickGeometry ignored;
    check.Check(
      !B::GetBrickGeometry(bad, ignored, message) && message.find(fragment) != std::string::npos,
      "expected an error with '" + fragment + "', got '" + message + "'");
  };
  B::BrickGeometryInput bad = input;
  bad.BlockRanges.pop_back();
  fails(bad, "brick block ranges");
  std::vector<float> shortRanges(1);
  bad = input;
  bad.BlockRanges[0] = &shortRanges;
  fails(bad, "block range values");
  bad = input;
  bad.Table = nullptr;
  fails(bad, "transfer function table");
  std::vector<float> vertices(6, 0.0f);
  std::vector<unsigned int> triangles;
  B::DrawList batched = list;
  batched.BatchOffsets.assign(n + 1, 1);
  batched.BatchOffsets[0] = 0;
  batched.BatchFirst = { 0 };
  batched.BatchEnd = { 1 };
  bad = input;
  bad.List = &batched;
  bad.SurfaceVertices = &vertices;
  bad.SurfaceTriangles = &triangles;
  fails(bad, "names surface triangle 0");
  std::vector<float> out;
  const std::size_t dims[3] = { 2, 2, 2 };
  const float few[3] = { 0.0f, 0.0f, 0.0f };
  check.Check(!B::MeasureBlockRanges(few, 3, dims, out, error) &&
      error.find("3 texels for a 2x2x2 brick") != std::string::npos,
    "texels that do not fill the brick: '" + error + "'");
  return check.Result();
}
} // namespace

int Region()
{
  Checker check;
  Fixture f;
  if (!f.Octree)
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkCamera> camera;
  const double centre[3] = { 12.0, 10.0, 8.0 };
  const double diagonal[3] = { 1.0, 0.8, 0.6 };
  Aim(camera, centre, diagonal, false);
  const B::CameraDescription cam = vtkHybridOctreeCameraInput::DescribeCamera(camera);
  // Selects under `region`: its summary and DrawList; false on failure (`error` set).
  auto run = [&](const B::RegionDescription& region, B::SelectionSummary& summary,
               B::DrawList& list, std::string& error) {
    B::SelectDescription options;
    options.BudgetBytes = 10000000;
    options.Region = region;
    std::unique_ptr<B::Selection> selection = f.Octree->Select(options, error);
    return selection && selection->GetSummary(summary, error) &&
      selection->GetDrawList(*f.Octree, cam, 0.0, list, error);
  };
  std::string error;
  B::SelectionSummary plain, cut, whole;
  B::DrawList plainList, cutList, wholeList;
  if (!check.Check(run(B::RegionDescription(), plain, plainList, error), "plain: " + error))
  {
    return EXIT_FAILURE;
  }
  check.Check(plainList.Effects.empty() && !plainList.Region.Cropping, "no region: no effect");
  // The image spans x 0..24, y 0..20, z 0..16: keep x <= 10 and z <= 8.
  B::RegionDescription region;
  region.Cropping = true;
  const double planes[6] = { -5.0, 10.0, 0.0, 20.0, 0.0, 16.0 };
  std::copy(planes, planes + 6, region.CroppingPlanes);
  region.ClippingPlanes = { 0.0, 0.0, 8.0, 0.0, 0.0, -1.0 };
  if (!check.Check(run(region, cut, cutList, error), "cut: " + error))
  {
    return EXIT_FAILURE;
  }
  std::cout << "bricks " << plain.Bricks << " -> " << cut.Bricks << ", skipped " << plain.Skipped
            << " -> " << cut.Skipped << ", bytes " << plain.TextureBytes << " -> "
            << cut.TextureBytes << ", effects '" << cutList.Effects << "'\n";
  check.Check(cutList.Effects == "cropping,clipping", "effects: '" + cutList.Effects + "'");
  check.Check(cutList.Region.Cropping && cutList.Region.CroppingPlanes[1] == 10.0 &&
      cutList.Region.CroppingFlags == 0x2000 &&
      cutList.Region.ClippingPlanes == region.ClippingPlanes,
    "the region that acts comes back");
  check.Check(cut.Skipped > plain.Skipped && cut.TextureBytes < plain.TextureBytes,
    "removed bricks are not selected");
  // Around the whole image, a plane with the image on its kept side: nothing acts.
  const double around[6] = { -1.0, 30.0, 0.0, 20.0, 0.0, 16.0 };
  std::copy(around, around + 6, region.CroppingPlanes);
  region.ClippingPlanes = { 0.0, 0.0, -1.0, 0.0, 0.0, 1.0 };
  check.Check(run(region, whole, wholeList, error), "whole: " + error);
  check.Check(wholeList.Effects.empty() && !wholeList.Region.Cropping &&
      wholeList.Region.ClippingPlanes.empty() && whole.TextureBytes == plain.TextureBytes,
    "a region removing nothing acts not at all: '" + wholeList.Effects + "'");
  region.ClippingPlanes = { 0.0, 0.0, 8.0, 0.0, 0.0 };
  error.clear();
  check.Check(
    !run(region, whole, wholeList, error) && error.find("6 per plane") != std::string::npos,
    "5 plane values refused: " + error);
  return check.Result();
}

int TestHybridOctreeBridge(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  if (scenario == "draw_list")
  {
    return DrawLists();
  }
  if (scenario == "texels")
  {
    return Texels();
  }
  if (scenario == "surface")
  {
    return SurfaceBatches();
  }
  if (scenario == "transparent")
  {
    return Transparent();
  }
  if (scenario == "errors")
  {
    return Errors();
  }
  if (scenario == "points")
  {
    return Points();
  }
  if (scenario == "geometry")
  {
    return Geometry();
  }
  if (scenario == "shading")
  {
    return Shading();
  }
  if (scenario == "gradient_opacity")
  {
    return GradientOpacity();
  }
  if (scenario == "region")
  {
    return Region();
  }
  std::cerr << "unknown scenario '" << scenario
            << "': use draw_list, texels, surface, transparent, errors, points, geometry, shading, "
               "gradient_opacity or region\n";
  return EXIT_FAILURE;
}
