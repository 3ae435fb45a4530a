#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeVolumeMapperInternals.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeCameraInput.h"
#include "vtkHybridOctreeImageInput.h"
#include "vtkHybridOctreeScattering.h"
#include "vtkHybridOctreeTransfer2D.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkRenderer.h"
#include "vtkTimeStamp.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkHybridOctreeVolumeMapper);

namespace
{
using namespace vtkHybridOctreeBridge;
using vtkHybridOctreeCameraInput::DescribeCamera;
using vtkHybridOctreeImageInput::ByteCount;
using vtkHybridOctreeImageInput::Bytes;
using vtkHybridOctreeVolumeMapperParts::GradientOpacityPoints;
using vtkHybridOctreeVolumeMapperParts::TransformPoint;

/// `m`'s linear part applied to the vector `v`.
void TransformVector(vtkMatrix4x4* m, const double v[3], double out[3])
{
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m->GetElement(r, 0) * v[0] + m->GetElement(r, 1) * v[1] + m->GetElement(r, 2) * v[2];
  }
}

/// The volume's shading as VTK's GPU ray caster takes it (vtkOpenGLGPUVolumeRayCastMapper,
/// VTK 9.2): the property's Shade, Ambient, Diffuse, Specular, SpecularPower
/// and the renderer's switched-on lights: its default lighting when exactly
/// one, a headlight of intensity 1, is on, else every light as a
/// directional one (focal point - position, through `modelInverse` into the
/// octree's frame; colours times intensity). No light on (a light kit
/// switched off after the renderer made its automatic headlight): VTK
/// shades every sample black (its computeLighting starts from vec4(0) and
/// adds each light's ambient, diffuse and specular terms), so the
/// description is one light of black colours.
ShadingDescription DescribeShading(
  vtkRenderer* ren, vtkVolumeProperty* property, vtkMatrix4x4* modelInverse)
{
  ShadingDescription shading;
  shading.Shade = property->GetShade(0) != 0;
  shading.Ambient = property->GetAmbient(0);
  shading.Diffuse = property->GetDiffuse(0);
  shading.Specular = property->GetSpecular(0);
  shading.SpecularPower = property->GetSpecularPower(0);
  shading.TwoSided = ren->GetTwoSidedLighting() != 0;
  if (!shading.Shade)
  {
    return shading;
  }
  int on = 0;
  bool headlight = false;
  vtkLightCollection* lights = ren->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (light->GetSwitch() == 0)
    {
      continue;
    }
    ++on;
    headlight = on == 1 && light->GetIntensity() == 1.0 && light->LightTypeIsHeadlight();
    const double* p = light->GetTransformedPosition();
    const double* f = light->GetTransformedFocalPoint();
    const double world[3] = { f[0] - p[0], f[1] - p[1], f[2] - p[2] };
    double model[3];
    TransformVector(modelInverse, world, model);
    const double intensity = light->GetIntensity();
    for (int a = 0; a < 3; ++a)
    {
      shading.LightDirections.push_back(model[a]);
      shading.LightAmbient.push_back(light->GetAmbientColor()[a] * intensity);
      shading.LightDiffuse.push_back(light->GetDiffuseColor()[a] * intensity);
      shading.LightSpecular.push_back(light->GetSpecularColor()[a] * intensity);
    }
  }
  shading.Headlight = on == 1 && headlight;
  shading.LightsOn = on;
  if (on == 0)
  {
    const double down[3] = { 0.0, 0.0, -1.0 };
    for (int a = 0; a < 3; ++a)
    {
      shading.LightDirections.push_back(down[a]);
      shading.LightAmbient.push_back(0.0);
      shading.LightDiffuse.push_back(0.0);
      shading.LightSpecular.push_back(0.0);
    }
  }
  return shading;
}

/// The mapper's cropping (vtkVolumeMapper: region planes in the image's data
/// coordinates, taken as the octree's frame) and clipping planes
/// (vtkAbstractMapper: world coordinates, into the octree's frame through
/// `modelInverse`: origin o' = M^-1 o, normal n' = A^T n with A the linear
/// part of `model`, so that n' . (x' - o') = n . (x - o)).
RegionDescription DescribeRegion(
  vtkVolumeMapper* mapper, vtkMatrix4x4* model, vtkMatrix4x4* modelInverse)
{
  RegionDescription region;
  region.Cropping = mapper->GetCropping() != 0;
  mapper->GetCroppingRegionPlanes(region.CroppingPlanes);
  region.CroppingFlags = static_cast<std::uint32_t>(mapper->GetCroppingRegionFlags());
  vtkPlaneCollection* planes = mapper->GetClippingPlanes();
  if (!planes)
  {
    return region;
  }
  vtkCollectionSimpleIterator it;
  planes->InitTraversal(it);
  while (vtkPlane* plane = planes->GetNextPlane(it))
  {
    double origin[3], normal[3];
    TransformPoint(modelInverse, plane->GetOrigin(), origin);
    const double* n = plane->GetNormal();
    for (int c = 0; c < 3; ++c)
    {
      normal[c] = model->GetElement(0, c) * n[0] + model->GetElement(1, c) * n[1] +
        model->GetElement(2, c) * n[2];
    }
    region.ClippingPlanes.insert(region.ClippingPlanes.end(),
      { origin[0], origin[1], origin[2], normal[0], normal[1], normal[2] });
  }
  return region;
}

/// The passes an interactive frame runs for the DrawList's `passes`: a
/// translucent surface per brick instead of in the slabs, no points.
std::string InteractivePlan(const std::string& passes)
{
  std::string plan;
  std::size_t start = 0;
  while (start <= passes.size())
  {
    std::size_t end = passes.find(',', start);
    end = end == std::string::npos ? passes.size() : end;
    std::string pass = passes.substr(start, end - start);
    if (pass == "surface-in-slabs")
    {
      pass = "surface-per-brick";
    }
    if (!pass.empty() && pass != "points")
    {
      plan += (plan.empty() ? "" : ",") + pass;
    }
    start = end + 1;
  }
  return plan;
}

} // namespace

vtkHybridOctreeVolumeMapper::vtkHybridOctreeVolumeMapper()
  : Internals(new vtkInternals)
{
}

vtkHybridOctreeVolumeMapper::~vtkHybridOctreeVolumeMapper() = default;

int vtkHybridOctreeVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  // Any data set, so that a non-image input is a clear error, not a pipeline failure.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  // Optional, so that Render() with no input reports its own error.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

bool vtkHybridOctreeVolumeMapper::IsInteractive(vtkRenderer* ren) const
{
  vtkRenderWindow* window = ren ? ren->GetRenderWindow() : nullptr;
  return window && window->GetDesiredUpdateRate() > this->InteractiveUpdateRate;
}

double vtkHybridOctreeVolumeMapper::FrameBudgetMB(vtkRenderer* ren) const
{
  return this->IsInteractive(ren) ? std::min(this->InteractiveBudgetMB, this->BudgetMB)
                                  : this->BudgetMB;
}

bool vtkHybridOctreeVolumeMapper::GetLastDrawnFromStore() const
{
  return this->Internals->Store != nullptr && this->LastRenderOK;
}

void vtkHybridOctreeVolumeMapper::UpdateModelMatrix(vtkImageData* image, vtkVolume* vol)
{
  // Samples sit at origin + direction * (index * spacing): the octree's frame
  // (origin + index * spacing) maps to it by T(origin) D T(-origin).
  vtkInternals& in = *this->Internals;
  vtkNew<vtkMatrix4x4> frame;
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  const double* o = in.Grid.Origin;
  for (int r = 0; r < 3; ++r)
  {
    double shift = o[r];
    for (int c = 0; c < 3; ++c)
    {
      frame->SetElement(r, c, direction->GetElement(r, c));
      shift -= direction->GetElement(r, c) * o[c];
    }
    frame->SetElement(r, 3, shift);
  }
  vtkMatrix4x4::Multiply4x4(vol->GetMatrix(), frame, in.Model);
  vtkMatrix4x4::Invert(in.Model, in.ModelInverse);
}

bool vtkHybridOctreeVolumeMapper::UpdateTransferFunction(vtkVolumeProperty* property)
{
  vtkInternals& in = *this->Internals;
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  // Dependent: the opacity column over the last component's range (1, or 3
  // of RGBA), the colour column over component 0's (VTK's tables: each over
  // its component's range; an RGBA volume's colour is not the table's).
  const int last = in.Scalars->GetNumberOfComponents() - 1;
  double range[2];
  in.Scalars->GetRange(
    range, in.Dependent ? last : (in.Grid.Component < 0 ? 0 : in.Grid.Component));
  if (in.Store)
  {
    // Drawn from a store: the full resolution's range (the light image's may be narrower).
    range[0] = in.ValueRange[0];
    range[1] = in.ValueRange[1];
  }
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  double colour[2] = { range[0], range[1] };
  if (in.Dependent)
  {
    in.Scalars->GetRange(colour, 0);
    if (!(colour[1] > colour[0]))
    {
      colour[1] = colour[0] + 1.0;
    }
  }
  // VTK's opacities are per ScalarOpacityUnitDistance U, the DrawList's per
  // d0 = the smallest spacing; VTK's rule per blend mode
  // (vtkOpenGLVolumeOpacityTable, plan::blend's BlendMode::reference_opacity):
  //   Composite  a_d0 = 1 - (1 - a)^(d0 / U)  (the DrawList's correction then
  //              gives 1 - (1 - a)^(d / U), VTK's at its sample distance d)
  //   Additive   a_d0 = a d0 / U              (each sample weighs d / d0: a d / U)
  //   the others a_d0 = a                     (VTK takes the table as it is)
  // VTK's GPU ray caster corrects dependent components' opacity with the
  // unit distance of the last component (vtkVolumeInputHelper: the opacity
  // table of component numComp - 1), not the first.
  const double unit = property->GetScalarOpacityUnitDistance(in.Dependent ? last : 0);
  const double d0 = std::min({ in.Grid.Spacing[0], in.Grid.Spacing[1], in.Grid.Spacing[2] });
  const double ratio = unit > 0.0 ? d0 / unit : 1.0;
  const bool composite = this->BlendMode == COMPOSITE_BLEND;
  const bool additive = this->BlendMode == ADDITIVE_BLEND;
  const int n = this->TableSize;
  std::vector<double> rgb(3 * static_cast<std::size_t>(n));
  std::vector<double> alpha(static_cast<std::size_t>(n));
  if (property->GetColorChannels(0) == 1)
  {
    // A grey colour function (SetColor(vtkPiecewiseFunction*)): asking the
    // property for its RGB function would replace it with VTK's default ramp.
    std::vector<double> grey(static_cast<std::size_t>(n));
    property->GetGrayTransferFunction(0)->GetTable(colour[0], colour[1], n, grey.data());
    for (int k = 0; k < n; ++k)
    {
      std::fill_n(rgb.begin() + 3 * k, 3, grey[static_cast<std::size_t>(k)]);
    }
  }
  else
  {
    property->GetRGBTransferFunction(0)->GetTable(colour[0], colour[1], n, rgb.data());
  }
  opacity->GetTable(range[0], range[1], n, alpha.data());
  std::vector<float> table(4 * static_cast<std::size_t>(n));
  in.Transfer.ColorPoints.clear();
  in.Transfer.OpacityPoints.clear();
  for (int k = 0; k < n; ++k)
  {
    const double v = range[0] + (range[1] - range[0]) * k / (n - 1);
    const double vc = colour[0] + (colour[1] - colour[0]) * k / (n - 1);
    double a = std::min(1.0, std::max(0.0, alpha[k]));
    if (composite)
    {
      a = a < 1.0 ? 1.0 - std::pow(1.0 - a, ratio) : 1.0;
    }
    else if (additive)
    {
      a = std::min(1.0, a * ratio);
    }
    for (int c = 0; c < 3; ++c)
    {
      table[4 * k + c] = static_cast<float>(rgb[3 * k + c]);
    }
    table[4 * k + 3] = static_cast<float>(a);
    in.Transfer.ColorPoints.insert(in.Transfer.ColorPoints.end(),
      { vc, static_cast<double>(table[4 * k]), static_cast<double>(table[4 * k + 1]),
        static_cast<double>(table[4 * k + 2]) });
    in.Transfer.OpacityPoints.insert(
      in.Transfer.OpacityPoints.end(), { v, static_cast<double>(table[4 * k + 3]) });
  }
  if (table != in.Table || range[0] != in.RangeLo || range[1] != in.RangeHi ||
    colour[0] != in.ColourRange[0] || colour[1] != in.ColourRange[1])
  {
    in.Table.swap(table);
    in.RangeLo = range[0];
    in.RangeHi = range[1];
    in.ColourRange[0] = colour[0];
    in.ColourRange[1] = colour[1];
    in.TableUploaded = false;
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::UpdatePoints()
{
  vtkInternals& in = *this->Internals;
  if (!this->UsePoints)
  {
    if (in.HasPoints)
    {
      in.Octree->RemovePoints();
      in.HasPoints = false;
    }
    in.Drawing = PointsDrawing();
    return true;
  }
  const std::vector<double> key = { static_cast<double>(this->PointFactor), this->PointThreshold,
    static_cast<double>(this->PointBudget) };
  if (in.HasPoints && in.PointsTime > in.OctreeTime && in.PointsKey == key)
  {
    return this->UpdatePointShades();
  }
  in.HasPoints = false;
  PointsOptions options;
  options.Factor = static_cast<std::size_t>(this->PointFactor);
  options.Threshold = this->PointThreshold;
  options.UseBudget = this->PointBudget > 0;
  options.Budget = static_cast<std::size_t>(this->PointBudget);
  options.UnderestimatesOnly = true;
  options.MaxOverestimate = -1.0;
  std::string error;
  PointsSummary made;
  if (!in.Octree->IntegratePoints(
        Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid, options, made, error) ||
    !in.Octree->GetPointsDrawing(in.Drawing, error))
  {
    in.Octree->RemovePoints();
    vtkErrorMacro(<< error);
    return false;
  }
  in.HasPoints = true;
  in.PointsTime.Modified();
  in.PointsKey = key;
  return this->UpdatePointShades();
}

bool vtkHybridOctreeVolumeMapper::UpdatePointShades()
{
  vtkInternals& in = *this->Internals;
  if (in.ShadesTime > in.PointsTime && in.ShadesColors == in.Transfer.ColorPoints &&
    in.ShadesOpacities == in.Transfer.OpacityPoints)
  {
    return true;
  }
  std::string error;
  if (!in.Octree->GetPointShades(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
        in.Transfer.ColorPoints, in.Transfer.OpacityPoints, in.Shades, error))
  {
    in.ShadesTime = vtkTimeStamp();
    vtkErrorMacro(<< error);
    return false;
  }
  in.ShadesTime.Modified();
  in.ShadesColors = in.Transfer.ColorPoints;
  in.ShadesOpacities = in.Transfer.OpacityPoints;
  return true;
}

bool vtkHybridOctreeVolumeMapper::UpdateSurface()
{
  vtkInternals& in = *this->Internals;
  if (!this->ShowSurface || !(this->SurfaceOpacity > 0.0))
  {
    return true;
  }
  if (!std::isfinite(this->Isovalue))
  {
    vtkErrorMacro("the isovalue " << this->Isovalue << " is not a finite number");
    return false;
  }
  if (in.HasIso && in.IsoTime > in.OctreeTime && in.IsoValue == this->Isovalue)
  {
    return true;
  }
  in.HasIso = false;
  std::string error;
  SurfaceSummary extracted;
  if (!in.Octree->IntegrateSurface(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
        this->Isovalue, SurfaceMode::Discretized, false, extracted, error) ||
    !in.SurfaceDrawer.Upload(*in.Octree, error))
  {
    in.Octree->RemoveSurface();
    vtkErrorMacro(<< error);
    return false;
  }
  in.HasIso = true;
  in.IsoTime.Modified();
  in.IsoValue = this->Isovalue;
  return true;
}

bool vtkHybridOctreeVolumeMapper::Prepare(vtkRenderer* ren, vtkVolume* vol)
{
  vtkImageData* image = nullptr;
  vtkVolumeProperty* property = vol ? vol->GetProperty() : nullptr;
  // Dependent components (2 fields, or RGBA) are drawn in Composite (the other modes reduce one
  // field).
  this->Internals->WantsDependent =
    property && !property->GetIndependentComponents() && this->BlendMode == COMPOSITE_BLEND;
  vtkDataArray* scalars = this->CheckInput(image);
  if (!scalars)
  {
    return false;
  }
  if (!property)
  {
    vtkErrorMacro("the volume has no vtkVolumeProperty: give it one with a scalar opacity");
    return false;
  }
  // The picture stays the Composite, unshaded one: said once per setting, not silently.
  for (const std::string& message :
    this->Internals->Unsupported.Update(this, property, scalars->GetNumberOfComponents(),
      this->ShowSurface && this->SurfaceOpacity > 0.0 && this->SurfaceOpacity < 1.0))
  {
    vtkWarningMacro(<< message);
  }
  if (!(this->FrameBudgetMB(ren) > 0.0))
  {
    vtkErrorMacro("the texture budget is 0 MB: set BudgetMB (and InteractiveBudgetMB) above 0");
    return false;
  }
  if (!this->UpdateOctree(image, scalars) || !this->CheckStoreSettings(property))
  {
    return false;
  }
  this->UpdateModelMatrix(image, vol);
  if (!this->DescribeView(ren, property))
  {
    return false;
  }
  this->Internals->Shading = DescribeShading(ren, property, this->Internals->ModelInverse);
  this->Internals->Region =
    DescribeRegion(this, this->Internals->Model, this->Internals->ModelInverse);
  this->Internals->GradientOpacity = GradientOpacityPoints(property);
  this->Internals->Transfer2D.Update(property, this->Internals->Scalars,
    this->Internals->Grid.Component, this->Internals->Grid.Spacing, this->Internals->Grid.Dims,
    this->Transfer2DSampleDistance);
  this->Internals->ScatteringParameters =
    vtkHybridOctreeScattering::Describe(this->VolumetricScatteringBlending,
      this->GlobalIlluminationReach, property, this->Internals->Shading,
      this->ScatteringSampleDistance > 0.0
        ? this->ScatteringSampleDistance
        : vtkHybridOctreeTransfer2D::SmartSampleDistance(
            this->Internals->Grid.Spacing, this->Internals->Grid.Dims));
  return this->UpdateTransferFunction(property) && this->UpdatePoints() &&
    this->ChooseSelection(ren, vol) && this->UpdateSurface();
}

double vtkHybridOctreeVolumeMapper::ActualSampleDistance() const
{
  return this->SampleDistance >= 0.0 ? this->SampleDistance
                                     : vtkHybridOctreeTransfer2D::SmartSampleDistance(
                                         this->Internals->Grid.Spacing, this->Internals->Grid.Dims);
}

CameraDescription vtkHybridOctreeVolumeMapper::ModelCamera(vtkRenderer* ren) const
{
  // The camera in the octree's frame: position and focal point through the
  // inverse model matrix, view up through its linear part.
  CameraDescription cam = DescribeCamera(ren->GetActiveCamera());
  vtkMatrix4x4* inverse = this->Internals->ModelInverse;
  double p[3], f[3], up[3];
  TransformPoint(inverse, cam.Position, p);
  TransformPoint(inverse, cam.FocalPoint, f);
  TransformVector(inverse, cam.ViewUp, up);
  const double scale = std::cbrt(std::fabs(this->Internals->Model->Determinant()));
  for (int k = 0; k < 3; ++k)
  {
    cam.Position[k] = p[k];
    cam.FocalPoint[k] = f[k];
    cam.ViewUp[k] = up[k];
  }
  if (scale > 0.0)
  {
    cam.ParallelScale /= scale;
  }
  return cam;
}

bool vtkHybridOctreeVolumeMapper::GetFrameDrawList(vtkRenderer* ren, DrawList& list)
{
  vtkInternals& in = *this->Internals;
  std::string error;
  const CameraDescription cam = this->ModelCamera(ren);
  const bool surface = in.HasIso && this->ShowSurface && this->SurfaceOpacity > 0.0;
  if (!this->PlanLoading())
  {
    return false;
  }
  const bool ok = in.Frame->Selected->SetShading(in.Shading, error) &&
    in.Frame->Selected->SetGradientOpacity(in.GradientOpacity, error) &&
    in.Frame->Selected->SetJittering(this->UseJittering != 0, error) &&
    in.Frame->Selected->SetSampleDistance(this->ActualSampleDistance(), error) &&
    in.Frame->Selected->SetScattering(in.ScatteringParameters, error) &&
    in.Frame->Selected->GetDrawList(
      *in.Octree, cam, surface ? this->SurfaceOpacity : 0.0, list, error);
  if (!ok)
  {
    vtkErrorMacro(<< error);
  }
  return ok;
}

void vtkHybridOctreeVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  this->LastRenderOK = false;
  this->LastBricks = 0;
  this->LastSlices = 0;
  this->LastSurfaceTriangles = 0;
  this->LastBrickDraws = 0;
  this->LastPoints = 0;
  this->LastPointBytes = 0;
  this->LastUploadedBytes = 0;
  this->LastNaNSamples = 0;
  this->LastPlan.clear();
  this->LastEffects.clear();
  this->LastImageSampleDistance = 1.0;
  this->LastSampleSpacing = 1;
  this->LastReselected = false;
  this->LastSelectMilliseconds = 0.0;
  this->LastViewSelection.clear();
  this->ObserveFrameOverhead(ren);
  this->LastTargetMilliseconds = 0.0;
  this->LastDrawTargetMilliseconds = 0.0;
  this->LastPredictedMilliseconds = 0.0;
  this->LastDrawMilliseconds = 0.0;
  this->LastTimeOutcome.clear();
  this->LastEstimatedRMSError = 0.0;
  this->LastBricksLoading = 0;
  this->Internals->FrameTargetMs = 0.0;
  this->Internals->FrameBounds.clear();
  this->Internals->FrameBytes.clear();
  const bool interactive = this->IsInteractive(ren);
  this->LastInteractive = interactive;
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* window =
    ren ? vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()) : nullptr;
  vtkOpenGLCamera* camera = ren ? vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera()) : nullptr;
  if (!window || !camera)
  {
    vtkErrorMacro("an OpenGL render window and camera are required");
    return;
  }
  // The frame's own time: from the end of what was drawn before it (glFinish)
  // to the end of its drawing.
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  // What this frame builds once (the octree, its isosurface, its points) is
  // no part of the time later frames spend outside their drawing.
  const vtkMTimeType built[3] = { in.OctreeTime.GetMTime(), in.IsoTime.GetMTime(),
    in.PointsTime.GetMTime() };
  DrawList list;
  if (!this->Prepare(ren, vol) || !this->GetFrameDrawList(ren, list))
  {
    return;
  }
  const bool timed = in.FrameTargetMs > 0.0;
  if (!timed && interactive && in.Frame == &in.Still &&
    !in.Bricks.HoldsAll(list.NodeId, list.Stride))
  {
    // The still selection is no longer resident: an interactive one, uploaded.
    list = DrawList();
    if (!this->UpdateSelection(vol->GetProperty(), true) || !this->GetFrameDrawList(ren, list))
    {
      return;
    }
  }
  // A timed frame's slice spacing is its cost model's choice.
  const int level = interactive && this->AutoAdjustSampleDistances && !timed
    ? in.Reduction.Choose(vol->GetAllocatedRenderTime())
    : 0;
  // A timed frame draws as its selection was made for (see ChooseSelection).
  const bool fast = timed ? in.FrameFast : interactive;
  // The drawing's own time, what a timed frame's cost model learns from.
  const auto drawStart = std::chrono::steady_clock::now();
  if (this->DrawFrame(ren, window, camera, list, fast, level))
  {
    this->LastRenderOK = true;
  }
  this->LastPlan = fast ? InteractivePlan(list.Passes) : list.Passes;
  this->LastEffects = list.Effects;
  this->LastViewSelection = in.Frame->Summary.ViewSelection;
  in.FrameBounds = list.Bounds;
  in.FrameBytes.clear();
  const std::size_t border = list.Bordered ? 2 : 0;
  for (std::size_t i = 0; 3 * i + 2 < list.Texels.size(); ++i)
  {
    std::size_t texels = 1;
    for (int k = 0; k < 3; ++k)
    {
      texels *= list.Texels[3 * i + k] + border;
    }
    in.FrameBytes.push_back(static_cast<vtkTypeInt64>(texels * in.Bricks.GetTexelBytes()));
  }
  this->LastEstimatedError = in.Frame->Summary.EstimatedError;
  this->LastEstimatedRMSError = in.Frame->Summary.EstimatedRmsError;
  this->LastPointBytes = static_cast<vtkTypeInt64>(in.Frame->Summary.PointBytes);
  this->LastTextureBytes = static_cast<vtkTypeInt64>(in.Bricks.GetResidentBytes());
  this->LastUploadedBytes = static_cast<vtkTypeInt64>(in.Bricks.GetUploadedBytes());
  this->LastStoreBytesRead = in.Store ? static_cast<vtkTypeInt64>(in.Store->GetBytesRead()) : 0;
  // The frame's time to the end of its drawing: what the next interactive
  // frame's sampling is chosen from.
  glFinish();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  this->LastFrameMilliseconds = 1.0e3 * elapsed.count();
  const std::chrono::duration<double> drawn = std::chrono::steady_clock::now() - drawStart;
  this->LastDrawMilliseconds = 1.0e3 * drawn.count();
  if (this->LastRenderOK)
  {
    in.Reduction.Record(level, elapsed.count(), interactive);
    this->ObserveTimedFrame(fast, this->LastDrawMilliseconds);
  }
  // The exact drawing's slab work (translucent surfaces, points) made even
  // the coarsest frame slower than the target: the next frames of this
  // target draw as interactive frames do.
  const bool slabWork = (!list.BatchOffsets.empty() && list.BatchOffsets.back() > 0) ||
    (in.HasPoints && !list.BucketOffsets.empty() && list.BucketOffsets.back() > 0);
  if (timed && !fast && slabWork && this->LastTimeOutcome == "below-fastest")
  {
    in.FastTargetMs = in.FrameTargetMs;
  }
  else if (timed && fast && !interactive && !slabWork)
  {
    // The slab work is gone (the surface hidden, the points off): the
    // next still frame tries the exact drawing again.
    in.FastTargetMs = 0.0;
  }
  const bool builds = in.OctreeTime.GetMTime() != built[0] || in.IsoTime.GetMTime() != built[1] ||
    in.PointsTime.GetMTime() != built[2];
  in.OverheadPending = this->LastRenderOK && timed && !builds;
  in.PendingDrawMs = this->LastDrawMilliseconds;
  in.PendingSelectMs = this->LastSelectMilliseconds;
}

vtkTypeInt64 vtkHybridOctreeVolumeMapper::GetLastTextureBytesWithin(const double bounds[6]) const
{
  const vtkInternals& in = *this->Internals;
  vtkTypeInt64 bytes = 0;
  for (std::size_t i = 0; i < in.FrameBytes.size() && 6 * i + 5 < in.FrameBounds.size(); ++i)
  {
    const double* b = &in.FrameBounds[6 * i];
    bool inside = true;
    for (int k = 0; k < 3; ++k)
    {
      inside = inside && b[2 * k] >= bounds[2 * k] && b[2 * k + 1] <= bounds[2 * k + 1];
    }
    bytes += inside ? in.FrameBytes[i] : 0;
  }
  return bytes;
}

void vtkHybridOctreeVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  in.Bricks.Clear(window);
  in.Reduction.Reset();
  // A new window may draw at another speed: its timed frames warm up again.
  in.Timers[0].reset();
  in.Timers[1].reset();
  in.OverheadMs = -1.0;
  in.OverheadPending = false;
  in.FastTargetMs = 0.0;
  in.SearchMs[0] = in.SearchMs[1] = 0.0;
  if (in.TableTexture)
  {
    in.TableTexture->ReleaseGraphicsResources(window);
    in.TableUploaded = false;
  }
  in.Drawer.ReleaseGraphicsResources();
  in.Transfer2D.ReleaseGraphicsResources();
  in.Scattering.ReleaseGraphicsResources();
  in.Target.ReleaseGraphicsResources(window);
  in.SurfaceDrawer.ReleaseGraphicsResources();
  this->Superclass::ReleaseGraphicsResources(window);
}

vtkTypeInt64 vtkHybridOctreeVolumeMapper::GetResidentTextureCount() const
{
  return static_cast<vtkTypeInt64>(this->Internals->Bricks.GetNumberOfTextures());
}

vtkTypeInt64 vtkHybridOctreeVolumeMapper::GetResidentTexturePageCount() const
{
  return static_cast<vtkTypeInt64>(this->Internals->Bricks.GetNumberOfPages());
}

vtkTypeInt64 vtkHybridOctreeVolumeMapper::GetResidentTexturePageBytes() const
{
  return static_cast<vtkTypeInt64>(this->Internals->Bricks.GetPageBytes());
}

void vtkHybridOctreeVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BudgetMB: " << this->BudgetMB << "\n";
  os << indent << "TexelFormat: " << this->TexelFormat << "\n";
  os << indent << "InteractiveBudgetMB: " << this->InteractiveBudgetMB << "\n";
  os << indent << "InteractiveUpdateRate: " << this->InteractiveUpdateRate << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "UseJittering: " << this->UseJittering << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "UseRoi: " << this->UseRoi << "\n";
  os << indent << "RoiCenter: (" << this->RoiCenter[0] << ", " << this->RoiCenter[1] << ", "
     << this->RoiCenter[2] << ")\n";
  os << indent << "RoiRadius: " << this->RoiRadius << "\n";
  os << indent << "ShowSurface: " << this->ShowSurface << "\n";
  os << indent << "Isovalue: " << this->Isovalue << "\n";
  os << indent << "SurfaceColor: (" << this->SurfaceColor[0] << ", " << this->SurfaceColor[1]
     << ", " << this->SurfaceColor[2] << ")\n";
  os << indent << "SurfaceOpacity: " << this->SurfaceOpacity << "\n";
  os << indent << "ViewSelection: " << this->ViewSelection << "\n";
  os << indent << "MinTexelPixels: " << this->MinTexelPixels << "\n";
  os << indent << "ViewChangeDegrees: " << this->ViewChangeDegrees << "\n";
  os << indent << "AsynchronousLoading: " << this->AsynchronousLoading << "\n";
  os << indent << "LoadingMemoryMB: " << this->LoadingMemoryMB << "\n";
  os << indent << "Transfer2DSampleDistance: " << this->Transfer2DSampleDistance << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "UsePoints: " << this->UsePoints << "\n";
  os << indent << "PointFactor: " << this->PointFactor << "\n";
  os << indent << "PointThreshold: " << this->PointThreshold << "\n";
  os << indent << "PointBudget: " << this->PointBudget << "\n";
  os << indent << "PointFootprint: " << (this->PointFootprint == 1 ? "Gaussian" : "square") << "\n";
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "TableSize: " << this->TableSize << "\n";
  os << indent << "LastBricks: " << this->LastBricks << "\n";
  os << indent << "LastTextureBytes: " << this->LastTextureBytes << "\n";
  os << indent << "LastUploadedBytes: " << this->LastUploadedBytes << "\n";
  os << indent << "LastSlices: " << this->LastSlices << "\n";
  os << indent << "LastSurfaceTriangles: " << this->LastSurfaceTriangles << "\n";
  os << indent << "LastBrickDraws: " << this->LastBrickDraws << "\n";
  os << indent << "LastPoints: " << this->LastPoints << "\n";
  os << indent << "LastPointBytes: " << this->LastPointBytes << "\n";
  os << indent << "LastPlan: " << this->LastPlan << "\n";
  os << indent << "LastEffects: " << this->LastEffects << "\n";
  os << indent << "LastFrameMilliseconds: " << this->LastFrameMilliseconds << "\n";
  os << indent << "LastEstimatedError: " << this->LastEstimatedError << "\n";
  os << indent << "LastNaNSamples: " << this->LastNaNSamples << "\n";
  os << indent << "LastInteractive: " << this->LastInteractive << "\n";
  os << indent << "LastRenderOK: " << this->LastRenderOK << "\n";
  os << indent << "LastImageSampleDistance: " << this->LastImageSampleDistance << "\n";
  os << indent << "LastSampleSpacing: " << this->LastSampleSpacing << "\n";
  os << indent << "LastReselected: " << this->LastReselected << "\n";
  os << indent << "LastSelectMilliseconds: " << this->LastSelectMilliseconds << "\n";
  os << indent << "TargetFrameMilliseconds: " << this->TargetFrameMilliseconds << "\n";
  os << indent << "LastTargetMilliseconds: " << this->LastTargetMilliseconds << "\n";
  os << indent << "LastDrawTargetMilliseconds: " << this->LastDrawTargetMilliseconds << "\n";
  os << indent << "LastPredictedMilliseconds: " << this->LastPredictedMilliseconds << "\n";
  os << indent << "LastDrawMilliseconds: " << this->LastDrawMilliseconds << "\n";
  os << indent << "LastTimeOutcome: " << this->LastTimeOutcome << "\n";
  os << indent << "LastEstimatedRMSError: " << this->LastEstimatedRMSError << "\n";
  os << indent << "LastViewSelection: view: " << this->LastViewSelection << "\n";
}
