#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkContourValues.h"
#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeCameraInput.h"
#include "vtkHybridOctreeImageInput.h"
#include "vtkHybridOctreeInteractiveReduction.h"
#include "vtkHybridOctreeScattering.h"
#include "vtkHybridOctreeSlice.h"
#include "vtkHybridOctreeStoreFieldData.h"
#include "vtkHybridOctreeTransfer2D.h"
#include "vtkHybridOctreeUnsupportedEffects.h"
#include "vtkOpenGLHybridOctreeBrickDrawer.h"
#include "vtkOpenGLHybridOctreeBrickTextures.h"
#include "vtkOpenGLHybridOctreeFloatTarget.h"
#include "vtkOpenGLHybridOctreeSurfaceDrawer.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
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
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

vtkStandardNewMacro(vtkHybridOctreeVolumeMapper);

namespace
{
using namespace vtkHybridOctreeBridge;
using vtkHybridOctreeCameraInput::DescribeCamera;
using vtkHybridOctreeImageInput::ByteCount;
using vtkHybridOctreeImageInput::Bytes;

/// When the store at `path` last changed: the latest modification time of
/// its folder and of its root metadata (NGFF 0.5's zarr.json, 0.4's
/// .zattrs), as a count of the file clock's ticks (0 when none is found).
std::int64_t StoreModifiedTime(const std::string& path)
{
  std::int64_t latest = 0;
  const std::filesystem::path folder(path);
  for (const std::filesystem::path& p : { folder, folder / "zarr.json", folder / ".zattrs" })
  {
    std::error_code ec;
    const auto t = std::filesystem::last_write_time(p, ec);
    if (!ec)
    {
      latest = std::max<std::int64_t>(latest, t.time_since_epoch().count());
    }
  }
  return latest;
}

/// `m` applied to the point `p` (w = 1).
void TransformPoint(vtkMatrix4x4* m, const double p[3], double out[3])
{
  double in[4] = { p[0], p[1], p[2], 1.0 };
  double r[4];
  m->MultiplyPoint(in, r);
  for (int k = 0; k < 3; ++k)
  {
    out[k] = r[k] / r[3];
  }
}

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

/// The gradient opacity VTK 9.2's GPU ray caster applies (vtkVolumeShaderComposer.h,
/// HasGradientOpacity; vtkVolumeInputHelper): the 1D mode's function of the
/// first component, when one was set and is not disabled, as (magnitude,
/// opacity) pairs (magnitudes per mean voxel spacing, VTK's convention);
/// empty for none.
std::vector<double> GradientOpacityPoints(vtkVolumeProperty* property)
{
  if (property->GetTransferFunctionMode() != vtkVolumeProperty::TF_1D ||
    property->GetDisableGradientOpacity(0) || !property->HasGradientOpacity(0))
  {
    return {};
  }
  return vtkHybridOctreeBridge::OpacityPoints(property->GetStoredGradientOpacity(0));
}

/// The reduction of the DrawList's blend mode, the brick shader's
/// reduceMode: 1 maximum, 2 minimum, 3 average intensity, 4 additive (VTK's
/// values), 0 for the compositing modes.
int ReduceMode(int blendMode)
{
  return blendMode >= vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND &&
      blendMode <= vtkVolumeMapper::ADDITIVE_BLEND
    ? blendMode
    : 0;
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

struct vtkHybridOctreeVolumeMapper::vtkInternals
{
  // The octree, rebuilt when the scalars, the image geometry or LeafSize change.
  std::unique_ptr<HybridOctree> Octree;
  vtkDataArray* Array = nullptr;
  vtkMTimeType ArrayMTime = 0;
  GridDescription Grid;
  int LeafSize = 0;
  /// NaN samples (no data) of the image the octree was built from.
  vtkTypeInt64 NaNSamples = 0;
  /// The octree's value range (NaN left out): what average and additive
  /// blending normalise by.
  double ValueRange[2] = { 0.0, 1.0 };
  /// When the octree was built: the caches below are current when made after it.
  vtkTimeStamp OctreeTime;
  // The OME-Zarr store the input image names (vtkHybridOctreeStoreFieldData.h),
  // opened once per path and modification time; null for an image in memory.
  std::unique_ptr<OmeZarrStore> Store;
  std::string StorePath;
  std::int64_t StoreTime = 0;
  /// The visibility view selections were said to weigh by screen space (once per store).
  bool StoreViewWarned = false;
  /// The full resolution's bounds of the last store named by the input.
  double StoreBounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
  vtkDataArray* Scalars = nullptr;

  // The points integrated into the octree, made again when the octree or
  // their settings change.
  bool HasPoints = false;
  PointsDrawing Drawing;
  vtkTimeStamp PointsTime;
  std::vector<double> PointsKey;
  // What each point adds under the transfer function, for those points and that table.
  std::vector<float> Shades;
  vtkTimeStamp ShadesTime;
  std::vector<double> ShadesColors;
  std::vector<double> ShadesOpacities;

  // The selections of still and of interactive frames, each made again
  // when its inputs change, and the one of this frame.
  struct SelectionSlot
  {
    std::unique_ptr<Selection> Selected;
    SelectionSummary Summary;
    vtkTimeStamp Time;
    std::vector<double> Key;
    std::vector<double> Opacity;
    ViewDescription View; ///< the view it was made for
  };
  SelectionSlot Still;
  SelectionSlot Moving;
  SelectionSlot* Frame = &Still;
  // This frame's view (DescribeView) and the volume's centre in the
  // octree's frame, what the view change is measured around.
  ViewDescription View;
  double Centre[3] = { 0.0, 0.0, 0.0 };
  // The last frame's bricks: their boxes (6 each, the octree's frame) and texture bytes.
  std::vector<double> FrameBounds;
  std::vector<vtkTypeInt64> FrameBytes;

  // The isosurface integrated into the octree, extracted again when the
  // octree or the isovalue change.
  bool HasIso = false;
  vtkTimeStamp IsoTime;
  double IsoValue = 0.0;

  // Transfer function table (what the CPU compositor gets too).
  CompositeScene Transfer;
  std::vector<float> Table;
  double RangeLo = 0.0;
  double RangeHi = 1.0;
  bool TableUploaded = false;

  // Two dependent fields (vtkHybridOctreeDependent.h): asked for by the
  // property and blend mode (Prepare), drawn for a 2-component array; the
  // octree built for them; the table's colour column over ColourRange
  // (component 0's), its opacity column over RangeLo, RangeHi (component 1's).
  // An RGBA volume (4 components, Rgba): the same octree kind and request;
  // the colour is the components' own, the opacity column over component 3's range.
  bool WantsDependent = false;
  bool Dependent = false;
  bool Rgba = false;
  bool OctreeDependent = false;
  double ColourRange[2] = { 0.0, 1.0 };
  /// When the resident brick textures were made (older than the octree: released).
  vtkTimeStamp TexturesTime;

  // Model matrix (volume matrix x image direction) and its inverse.
  vtkNew<vtkMatrix4x4> Model;
  vtkNew<vtkMatrix4x4> ModelInverse;

  // GL resources.
  vtkOpenGLHybridOctreeBrickTextures Bricks;
  vtkOpenGLHybridOctreeBrickDrawer Drawer;
  vtkOpenGLHybridOctreeFloatTarget Target;
  vtkOpenGLHybridOctreeSurfaceDrawer SurfaceDrawer;
  vtkSmartPointer<vtkTextureObject> TableTexture;

  // Settings the mapper does not draw, each warned about once while on.
  vtkHybridOctreeUnsupportedEffects Unsupported;
  /// The frame's shading (Prepare), light directions in the octree's frame.
  ShadingDescription Shading;
  /// The frame's cropping and clipping planes (Prepare), in the octree's frame.
  RegionDescription Region;
  /// The frame's gradient opacity (Prepare), VTK's points.
  std::vector<double> GradientOpacity;
  /// The property's 2D transfer function in TF_2D mode (Prepare), and its texture.
  vtkHybridOctreeTransfer2D Transfer2D;
  /// The frame's volumetric scattering (Prepare), and its shadow volume's texture.
  ScatteringDescription ScatteringParameters;
  vtkHybridOctreeScattering Scattering;
  /// Whether the resident brick textures carry gradient borders.
  bool BorderedTextures = false;
  /// The isosurface values of the Isosurface blend mode (the selection's).
  std::vector<double> Isosurfaces;
  /// Whether the resident coarse brick textures keep their peaks (MIP or MinIP).
  bool PooledTextures = false;
  // Interactive frames' sampling, from the times of the frames before.
  vtkHybridOctreeInteractiveReduction Reduction;
};

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

vtkDataArray* vtkHybridOctreeVolumeMapper::CheckInput(vtkImageData*& image)
{
  image = nullptr;
  if (this->GetNumberOfInputConnections(0) == 0 && !this->GetDataSetInput())
  {
    vtkErrorMacro("no input: connect a vtkImageData with point scalars");
    return nullptr;
  }
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkDataSet* data = this->GetDataSetInput();
  if (!data)
  {
    vtkErrorMacro("no input: connect a vtkImageData with point scalars");
    return nullptr;
  }
  image = vtkImageData::SafeDownCast(data);
  if (!image)
  {
    vtkErrorMacro("the input is a " << data->GetClassName()
                                    << ", not a vtkImageData: the mapper draws images only");
    return nullptr;
  }
  // The array VTK's scalar selection names (SelectScalarArray, ScalarMode;
  // by default the point scalars), as vtkSmartVolumeMapper picks it.
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(
    image, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (scalars && cellFlag != 0)
  {
    vtkErrorMacro("the selected array " << (scalars->GetName() ? scalars->GetName() : "")
                                        << " is cell data: the mapper draws point data "
                                           "(convert with vtkCellDataToPointData)");
    return nullptr;
  }
  if (!scalars || image->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("the input image is empty or has no point scalars"
      << (this->ScalarMode == VTK_SCALAR_MODE_DEFAULT
             ? std::string()
             : std::string(" named ") + (this->ArrayName ? this->ArrayName : "(none)"))
      << ": give it point scalars or select an existing point array");
    return nullptr;
  }
  const int components = scalars->GetNumberOfComponents();
  const bool dependent = (components == 2 || components == 4) && this->Internals->WantsDependent;
  if (components > 1 && this->Component < 0 && !dependent)
  {
    vtkErrorMacro(
      "the point scalars have " << components << " components: choose one with SetComponent()");
    return nullptr;
  }
  if (this->Component >= components)
  {
    vtkErrorMacro("component " << this->Component << " does not exist: the point scalars have "
                               << components << " components");
    return nullptr;
  }
  ScalarType type;
  if (!vtkHybridOctreeImageInput::ToBridgeType(scalars->GetDataType(), type) ||
    !scalars->HasStandardMemoryLayout())
  {
    vtkErrorMacro("scalar type " << scalars->GetDataTypeAsString()
                                 << " is not supported: cast to float, double or an 8/16/32-bit "
                                    "integer type (vtkImageCast)");
    return nullptr;
  }
  return scalars;
}

bool vtkHybridOctreeVolumeMapper::UpdateOctree(vtkImageData* image, vtkDataArray* scalars)
{
  vtkInternals& in = *this->Internals;
  vtkHybridOctreeStoreFieldData::StoreReference store;
  if (vtkHybridOctreeStoreFieldData::Find(image->GetFieldData(), store))
  {
    // A piece of the light image (ParaView's ranks each get one) would draw
    // the whole store on every rank: only the whole level is drawn from it.
    int dims[3];
    image->GetDimensions(dims);
    for (int a = 0; a < 3; ++a)
    {
      const double stride = std::round(image->GetSpacing()[a] / store.Spacing[a]);
      const double level = stride >= 1.0 ? std::ceil((store.Dims[a] - 1.0) / stride) + 1.0 : 0.0;
      if (static_cast<double>(dims[a]) != level)
      {
        vtkErrorMacro("the image names the OME-Zarr store '"
          << store.Path << "' but holds " << dims[0] << " x " << dims[1] << " x " << dims[2]
          << " samples, not a whole level of it (a piece, as each of several ranks gets): "
             "drawing a store in parallel is not supported yet; run on one rank");
        return false;
      }
    }
    return this->UpdateOctreeFromStore(
      store.Path, store.Dims, store.Spacing, store.Origin, scalars);
  }
  if (in.Store)
  {
    // Drawn from a store before: the octree is the store's.
    in.Store.reset();
    in.StorePath.clear();
    in.Octree.reset();
  }
  const int components = scalars->GetNumberOfComponents();
  in.Dependent = in.WantsDependent && (components == 2 || components == 4);
  in.Rgba = in.Dependent && components == 4;
  // Dependent: every component is read; component 0 names the first.
  const GridDescription grid = vtkHybridOctreeImageInput::DescribeGrid(image, scalars,
    in.Dependent ? 0 : (scalars->GetNumberOfComponents() > 1 ? this->Component : -1));
  in.Scalars = scalars;
  if (in.Octree && in.Array == scalars && in.ArrayMTime == scalars->GetMTime() &&
    vtkHybridOctreeImageInput::SameGrid(in.Grid, grid) && in.LeafSize == this->LeafSize &&
    in.OctreeDependent == in.Dependent)
  {
    this->LastNaNSamples = in.NaNSamples;
    return true;
  }
  in.Still.Selected.reset();
  in.Moving.Selected.reset();
  in.Reduction.Reset();
  in.HasIso = false;
  in.HasPoints = false;
  in.Octree.reset();
  std::string error;
  in.Octree = in.Dependent ? HybridOctree::BuildDependent(Bytes(scalars), ByteCount(scalars), grid,
                               static_cast<unsigned int>(this->LeafSize), error)
                           : HybridOctree::Build(Bytes(scalars), ByteCount(scalars), grid,
                               static_cast<unsigned int>(this->LeafSize), error);
  in.OctreeDependent = in.Dependent;
  vtkHybridOctreeBridge::OctreeSummary summary;
  if (!in.Octree || !in.Octree->GetSummary(summary, error))
  {
    in.Octree.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  in.NaNSamples = static_cast<vtkTypeInt64>(summary.NaNSamples);
  in.ValueRange[0] = summary.ValueMin;
  in.ValueRange[1] = summary.ValueMax;
  this->LastNaNSamples = in.NaNSamples;
  in.Array = scalars;
  in.ArrayMTime = scalars->GetMTime();
  in.Grid = grid;
  in.LeafSize = this->LeafSize;
  in.OctreeTime.Modified();
  return true;
}

bool vtkHybridOctreeVolumeMapper::UpdateOctreeFromStore(const std::string& path,
  const double dims[3], const double spacing[3], const double origin[3], vtkDataArray* scalars)
{
  vtkInternals& in = *this->Internals;
  in.Scalars = scalars;
  in.Dependent = in.WantsDependent &&
    (scalars->GetNumberOfComponents() == 2 || scalars->GetNumberOfComponents() == 4);
  in.Rgba = false;
  if (in.Dependent || scalars->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("the image names the OME-Zarr store '"
      << path
      << "', which holds one component: dependent or RGBA components (and ParaView's separate "
         "opacity array) are not drawn from a store; turn them off, or draw an image in memory");
    return false;
  }
  const std::int64_t time = StoreModifiedTime(path);
  if (in.Octree && in.Store && in.StorePath == path && in.StoreTime == time &&
    in.LeafSize == this->LeafSize)
  {
    this->LastNaNSamples = in.NaNSamples;
    return true;
  }
  in.Still.Selected.reset();
  in.Moving.Selected.reset();
  in.Reduction.Reset();
  in.HasIso = false;
  in.HasPoints = false;
  in.Octree.reset();
  in.Store.reset();
  in.StorePath.clear();
  in.Array = nullptr;
  std::string error;
  StoreSummary summary;
  in.Store = OmeZarrStore::Open(path, error);
  if (!in.Store || !in.Store->GetSummary(summary, error))
  {
    in.Store.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    const double tolerance = 1e-9 * std::max(1.0, std::fabs(summary.Spacing[a]));
    if (static_cast<double>(summary.Dims[a]) != dims[a] ||
      std::fabs(summary.Spacing[a] - spacing[a]) > tolerance ||
      std::fabs(summary.Origin[a] - origin[a]) > 1e-9 * std::max(1.0, std::fabs(origin[a])))
    {
      in.Store.reset();
      vtkErrorMacro("the OME-Zarr store '"
        << path
        << "' is not the volume the image was read from (its dims, spacing or origin "
           "changed): update the reader, or read the store again");
      return false;
    }
  }
  in.Octree =
    HybridOctree::BuildFromStore(*in.Store, static_cast<unsigned int>(this->LeafSize), error);
  OctreeSummary built;
  if (!in.Octree || !in.Octree->GetSummary(built, error))
  {
    in.Octree.reset();
    in.Store.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  GridDescription grid;
  grid.Type = summary.Type;
  for (int a = 0; a < 3; ++a)
  {
    grid.Dims[a] = summary.Dims[a];
    grid.Spacing[a] = summary.Spacing[a];
    grid.Origin[a] = summary.Origin[a];
  }
  grid.Components = 1;
  grid.Component = -1;
  in.Grid = grid;
  in.NaNSamples = static_cast<vtkTypeInt64>(built.NaNSamples);
  in.ValueRange[0] = built.ValueMin;
  in.ValueRange[1] = built.ValueMax;
  this->LastNaNSamples = in.NaNSamples;
  in.OctreeDependent = false;
  in.LeafSize = this->LeafSize;
  in.StorePath = path;
  in.StoreTime = time;
  in.StoreViewWarned = false;
  in.OctreeTime.Modified();
  return true;
}

bool vtkHybridOctreeVolumeMapper::CheckStoreSettings(vtkVolumeProperty* property)
{
  const vtkInternals& in = *this->Internals;
  if (!in.Store)
  {
    return true;
  }
  const char* needs = nullptr;
  if (this->UsePoints)
  {
    needs = "points (UsePoints)";
  }
  else if (this->ShowSurface && this->SurfaceOpacity > 0.0)
  {
    needs = "the isosurface (ShowSurface)";
  }
  else if (property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D &&
    this->BlendMode == COMPOSITE_BLEND)
  {
    needs = "a 2D transfer function";
  }
  if (!needs)
  {
    return true;
  }
  vtkErrorMacro(<< needs
                << " needs every sample in memory, and the image names the OME-Zarr "
                   "store '"
                << in.StorePath
                << "', drawn from disk: turn it off, or read the store's full resolution "
                   "(vtkHybridOctreeZarrReader's MaximumMegabytes large enough for level 0) "
                   "into an image without the store's field data");
  return false;
}

double* vtkHybridOctreeVolumeMapper::GetBounds()
{
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetDataSetInput());
  vtkHybridOctreeStoreFieldData::StoreReference store;
  if (!image || !vtkHybridOctreeStoreFieldData::Find(image->GetFieldData(), store))
  {
    return this->Superclass::GetBounds();
  }
  // The full resolution's corners placed as the image places its samples:
  // origin + direction * (index * spacing).
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  double* b = this->Internals->StoreBounds;
  for (int a = 0; a < 3; ++a)
  {
    b[2 * a] = VTK_DOUBLE_MAX;
    b[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    double local[3];
    for (int a = 0; a < 3; ++a)
    {
      local[a] = ((corner >> a) & 1) ? (store.Dims[a] - 1.0) * store.Spacing[a] : 0.0;
    }
    for (int r = 0; r < 3; ++r)
    {
      double x = store.Origin[r];
      for (int c = 0; c < 3; ++c)
      {
        x += direction->GetElement(r, c) * local[c];
      }
      b[2 * r] = std::min(b[2 * r], x);
      b[2 * r + 1] = std::max(b[2 * r + 1], x);
    }
  }
  std::copy(b, b + 6, this->Bounds);
  return this->Bounds;
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

SelectDescription vtkHybridOctreeVolumeMapper::DescribeSelection(
  vtkVolumeProperty* property, double budgetMB, std::vector<double>& key) const
{
  vtkInternals& in = *this->Internals;
  SelectDescription select;
  select.BudgetBytes = static_cast<std::size_t>(budgetMB * 1.0e6);
  select.Tolerance = this->ErrorTolerance;
  select.OpacityPoints = vtkHybridOctreeBridge::OpacityPoints(property->GetScalarOpacity(0));
  select.HasRoi = this->UseRoi;
  TransformPoint(in.ModelInverse, this->RoiCenter, select.RoiCenter);
  select.RoiRadius = this->RoiRadius;
  select.HasIsovalue = this->ShowSurface;
  select.Isovalue = this->Isovalue;
  // The blend modes the bridge draws (the others are warned about and drawn Composite).
  const int mode = this->BlendMode;
  select.BlendMode = mode >= COMPOSITE_BLEND && mode <= SLICE_BLEND ? mode : COMPOSITE_BLEND;
  // Slice on the property's vtkPlane, into the octree's frame as VTK takes
  // it; without a valid one (warned about) Composite.
  std::string sliceProblem;
  if (select.BlendMode == SLICE_BLEND &&
    !vtkHybridOctreeSlice::Describe(property, in.ModelInverse, select.SlicePlane, sliceProblem))
  {
    select.BlendMode = COMPOSITE_BLEND;
  }
  if (select.BlendMode == ISOSURFACE_BLEND)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    for (int i = 0; values && i < values->GetNumberOfContours(); ++i)
    {
      select.IsosurfaceValues.push_back(values->GetValue(i));
    }
  }
  select.AverageRange[0] = this->AverageIPScalarRange[0];
  select.AverageRange[1] = this->AverageIPScalarRange[1];
  select.TexelFormat = this->TexelFormat;
  // Shaded: the bricks' gradient borders count in the budget (Composite and
  // Isosurface only; Isosurface always has them).
  select.GradientBorder = property->GetShade(0) != 0 &&
    (select.BlendMode == COMPOSITE_BLEND || select.BlendMode == ISOSURFACE_BLEND ||
      select.BlendMode == SLICE_BLEND);
  select.GradientOpacityPoints = GradientOpacityPoints(property);
  select.Region = in.Region;
  // The 2D transfer function classifies under Composite only (VTK's TF_2D
  // mode); its texels are copied in only when a selection is made
  // (UpdateSelection): the key names them.
  if (select.BlendMode == COMPOSITE_BLEND)
  {
    in.Transfer2D.Describe(select.Transfer2DSize, nullptr, select.Transfer2DRange);
  }
  key = { static_cast<double>(select.BudgetBytes), select.Tolerance, select.HasRoi ? 1.0 : 0.0,
    select.RoiCenter[0], select.RoiCenter[1], select.RoiCenter[2], select.RoiRadius,
    select.HasIsovalue ? 1.0 : 0.0, select.Isovalue,
    in.HasPoints ? static_cast<double>(in.PointsTime.GetMTime()) : -1.0,
    select.GradientBorder ? 1.0 : 0.0, static_cast<double>(select.BlendMode),
    select.AverageRange[0], select.AverageRange[1], select.Region.Cropping ? 1.0 : 0.0,
    static_cast<double>(select.Region.CroppingFlags), static_cast<double>(select.TexelFormat) };
  key.insert(key.end(), select.Region.CroppingPlanes, select.Region.CroppingPlanes + 6);
  key.push_back(static_cast<double>(select.Region.ClippingPlanes.size()));
  key.insert(key.end(), select.Region.ClippingPlanes.begin(), select.Region.ClippingPlanes.end());
  key.push_back(static_cast<double>(select.IsosurfaceValues.size()));
  key.insert(key.end(), select.IsosurfaceValues.begin(), select.IsosurfaceValues.end());
  key.insert(key.end(), select.SlicePlane, select.SlicePlane + 6);
  key.push_back(static_cast<double>(select.GradientOpacityPoints.size()));
  key.insert(key.end(), select.GradientOpacityPoints.begin(), select.GradientOpacityPoints.end());
  const std::vector<double> transfer2D = in.Transfer2D.Key();
  key.push_back(select.Transfer2DSize[0] > 0 ? 1.0 : 0.0);
  key.insert(key.end(), transfer2D.begin(), transfer2D.end());
  // The view's settings; its camera and viewport through IsViewCurrent() only.
  select.View = in.View;
  key.insert(key.end(),
    { static_cast<double>(select.View.ViewSelection), select.View.MinTexelPixels,
      select.View.SurfaceOpacity, select.View.OpacityUnitDistance });
  return select;
}

bool vtkHybridOctreeVolumeMapper::DescribeView(vtkRenderer* ren, vtkVolumeProperty* property)
{
  vtkInternals& in = *this->Internals;
  if (!(this->ViewChangeDegrees >= 0.0))
  {
    vtkErrorMacro("ViewChangeDegrees " << this->ViewChangeDegrees
                                       << ": give the degrees the view may move before a still "
                                          "frame selects again, a number >= 0 (default 5)");
    return false;
  }
  ViewDescription& view = in.View;
  view.ViewSelection = this->ViewSelection;
  if (in.Store &&
    (view.ViewSelection == VIEW_SELECTION_VISIBILITY || view.ViewSelection == VIEW_SELECTION_BOTH))
  {
    // The visibility estimate reads every sample: a store weighs by screen space.
    view.ViewSelection = VIEW_SELECTION_SCREEN;
    if (!in.StoreViewWarned)
    {
      in.StoreViewWarned = true;
      vtkWarningMacro("view selection " << this->ViewSelection
                                        << " weighs nodes by the opacity in front of them, "
                                           "estimated from every sample: a volume drawn from "
                                           "the store '"
                                        << in.StorePath << "' is weighed by screen space alone");
    }
  }
  view.Camera = this->ModelCamera(ren);
  const int* size = ren->GetSize();
  view.Viewport[0] = static_cast<std::size_t>(std::max(size[0], 0));
  view.Viewport[1] = static_cast<std::size_t>(std::max(size[1], 0));
  view.MinTexelPixels = this->MinTexelPixels;
  view.SurfaceOpacity = this->ShowSurface ? this->SurfaceOpacity : 0.0;
  // The table's opacities are VTK's per ScalarOpacityUnitDistance, or per
  // the smallest spacing without one (UpdateTransferFunction()).
  const double unit = property->GetScalarOpacityUnitDistance(0);
  const double* spacing = in.Grid.Spacing;
  view.OpacityUnitDistance = unit > 0.0 ? unit : std::min({ spacing[0], spacing[1], spacing[2] });
  for (int k = 0; k < 3; ++k)
  {
    in.Centre[k] =
      in.Grid.Origin[k] + 0.5 * spacing[k] * (static_cast<double>(in.Grid.Dims[k]) - 1.0);
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::IsViewCurrent(
  const ViewDescription& made, const std::string& applied) const
{
  const vtkInternals& in = *this->Internals;
  if (applied == "data")
  {
    return true;
  }
  if (made.Viewport[0] != in.View.Viewport[0] || made.Viewport[1] != in.View.Viewport[1])
  {
    return false;
  }
  double degrees = 0.0;
  std::string error;
  // A camera the bridge refuses selects again, which reports it.
  return vtkHybridOctreeBridge::ViewChangeDegrees(
           made.Camera, in.View.Camera, in.Centre, degrees, error) &&
    degrees <= this->ViewChangeDegrees;
}

bool vtkHybridOctreeVolumeMapper::IsStillSelectionCurrent(
  const SelectDescription& still, const std::vector<double>& key) const
{
  const vtkInternals& in = *this->Internals;
  return in.Still.Selected && in.Still.Time > in.OctreeTime && in.Still.Key == key &&
    in.Still.Opacity == still.OpacityPoints;
}

bool vtkHybridOctreeVolumeMapper::UpdateSelection(vtkVolumeProperty* property, bool interactive)
{
  vtkInternals& in = *this->Internals;
  const double budgetMB =
    interactive ? std::min(this->InteractiveBudgetMB, this->BudgetMB) : this->BudgetMB;
  if (!(budgetMB > 0.0))
  {
    vtkErrorMacro("the texture budget is 0 MB: set BudgetMB (and InteractiveBudgetMB) above 0");
    return false;
  }
  vtkInternals::SelectionSlot& slot = interactive ? in.Moving : in.Still;
  in.Frame = &slot;
  std::vector<double> key;
  SelectDescription select = this->DescribeSelection(property, budgetMB, key);
  // Interactive frames keep their selection while the view moves (it is
  // made once per change of its other inputs); still ones select again
  // when the view moved past ViewChangeDegrees.
  if (slot.Selected && slot.Time > in.OctreeTime && slot.Key == key &&
    slot.Opacity == select.OpacityPoints &&
    (interactive || this->IsViewCurrent(slot.View, slot.Summary.ViewSelection)))
  {
    return true;
  }
  if (select.Transfer2DSize[0] > 0)
  {
    in.Transfer2D.Describe(select.Transfer2DSize, &select.Transfer2DRGBA, select.Transfer2DRange);
  }
  std::string error;
  const auto start = std::chrono::steady_clock::now();
  if (!in.Store &&
    !in.Octree->PrepareView(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid, select, error))
  {
    slot.Selected.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  slot.Selected = in.Octree->Select(select, error);
  if (!slot.Selected || !slot.Selected->GetSummary(slot.Summary, error))
  {
    slot.Selected.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  this->LastSelectMilliseconds = 1.0e3 * elapsed.count();
  this->LastReselected = true;
  slot.Time.Modified();
  slot.Key = key;
  slot.Opacity = select.OpacityPoints;
  slot.View = select.View;
  return true;
}

bool vtkHybridOctreeVolumeMapper::ChooseSelection(vtkRenderer* ren, vtkVolumeProperty* property)
{
  const bool interactive = this->IsInteractive(ren);
  // The frame's isosurface values (the Isosurface blend mode), whichever
  // selection it draws: every selection's key holds them.
  std::vector<double> key;
  const SelectDescription still = this->DescribeSelection(property, this->BudgetMB, key);
  this->Internals->Isosurfaces = still.IsosurfaceValues;
  if (interactive && this->IsStillSelectionCurrent(still, key))
  {
    this->Internals->Frame = &this->Internals->Still;
    return true;
  }
  return this->UpdateSelection(property, interactive);
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
    this->ChooseSelection(ren, property) && this->UpdateSurface();
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
  DrawList list;
  if (!this->Prepare(ren, vol) || !this->GetFrameDrawList(ren, list))
  {
    return;
  }
  if (interactive && in.Frame == &in.Still && !in.Bricks.HoldsAll(list.NodeId, list.Stride))
  {
    // The still selection is no longer resident: an interactive one, uploaded.
    list = DrawList();
    if (!this->UpdateSelection(vol->GetProperty(), true) || !this->GetFrameDrawList(ren, list))
    {
      return;
    }
  }
  const int level = interactive && this->AutoAdjustSampleDistances
    ? in.Reduction.Choose(vol->GetAllocatedRenderTime())
    : 0;
  if (this->DrawFrame(ren, window, camera, list, interactive, level))
  {
    this->LastRenderOK = true;
  }
  this->LastPlan = interactive ? InteractivePlan(list.Passes) : list.Passes;
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
  this->LastPointBytes = static_cast<vtkTypeInt64>(in.Frame->Summary.PointBytes);
  this->LastTextureBytes = static_cast<vtkTypeInt64>(in.Bricks.GetResidentBytes());
  this->LastUploadedBytes = static_cast<vtkTypeInt64>(in.Bricks.GetUploadedBytes());
  // The frame's time to the end of its drawing: what the next interactive
  // frame's sampling is chosen from.
  glFinish();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  this->LastFrameMilliseconds = 1.0e3 * elapsed.count();
  if (this->LastRenderOK)
  {
    in.Reduction.Record(level, elapsed.count(), interactive);
  }
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

bool vtkHybridOctreeVolumeMapper::DrawFrame(vtkRenderer* ren, vtkOpenGLRenderWindow* window,
  vtkOpenGLCamera* camera, const DrawList& list, bool interactive, int level)
{
  vtkInternals& in = *this->Internals;
  std::vector<vtkTextureObject*> textures;
  vtkHybridOctreeBridge::BrickGeometryInput geometryInput;
  if (!this->AcquireBrickTextures(window, list, textures, geometryInput) ||
    !this->UploadTable(window))
  {
    return false;
  }
  const CameraDescription cam = this->ModelCamera(ren);
  const vtkHybridOctreeInteractiveReduction::Level sampling =
    vtkHybridOctreeInteractiveReduction::GetLevel(level);
  if (!this->MakeBrickGeometry(list, cam, interactive, sampling.SampleSpacing, geometryInput))
  {
    return false;
  }
  this->LastImageSampleDistance = sampling.ImageSampleDistance;
  this->LastSampleSpacing = sampling.SampleSpacing;

  // Model to clip: VTK's key matrices are transposed for OpenGL.
  vtkMatrix4x4* wcvc;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  vtkMatrix3x3* normals;
  camera->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  vtkNew<vtkMatrix4x4> mcwc;
  vtkMatrix4x4::Transpose(in.Model, mcwc);
  vtkNew<vtkMatrix4x4> mcdc;
  vtkMatrix4x4::Multiply4x4(mcwc, wcdc, mcdc);
  const double rgba[4] = { this->SurfaceColor[0], this->SurfaceColor[1], this->SurfaceColor[2],
    this->SurfaceOpacity };

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cull(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglActiveTexture activeTexture(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  in.Drawer.SetRegion(list.Region);
  return this->DrawOpaqueSurface(window, mcdc, cam, list, rgba) &&
    this->DrawBricks(ren, window, mcdc, cam, list, textures, interactive,
      sampling.ImageSampleDistance, sampling.SampleSpacing, rgba);
}

bool vtkHybridOctreeVolumeMapper::AcquireBrickTextures(vtkOpenGLRenderWindow* window,
  const DrawList& list, std::vector<vtkTextureObject*>& textures,
  vtkHybridOctreeBridge::BrickGeometryInput& geometryInput)
{
  vtkInternals& in = *this->Internals;
  std::string error;
  const std::size_t bricks = list.GetNumberOfBricks();
  // The points bought share the budget: the textures get the rest.
  const Selection& selected = *in.Frame->Selected;
  const double textureBudget =
    this->BudgetMB * 1.0e6 - static_cast<double>(in.Frame->Summary.PointBytes);
  // Gradients (shading, gradient opacity) or Isosurface: textures with one
  // border texel per side (the gradient and the sample before a brick's
  // first read them); the resident ones of the other kind are released first.
  const bool isosurface = list.BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND;
  const bool bordered = list.Bordered;
  // MIP and MinIP: coarse textures keep their peaks (other texels, so the
  // resident textures of the other kind go too).
  const int reduceMode = ReduceMode(list.BlendMode);
  const bool pooled = reduceMode == 1 || reduceMode == 2;
  // Dependent: (colour, opacity) texel pairs; RGBA: four channels, RGBA8
  // (TexelFormat unorm8, u8 data) or RGBA32F, alpha decoded by TexelScale.
  const bool dependent = list.Effects.find("dependent-components") != std::string::npos;
  const bool rgba = list.Effects.find("rgba-components") != std::string::npos;
  in.Bricks.SetChannels(window, rgba ? 4 : dependent ? 2 : 1);
  in.Bricks.SetTexelFormat(window, list.TexelFormat);
  in.Drawer.SetTexelDecode(list.TexelScale, list.TexelBias);
  in.Drawer.SetDependent(dependent, in.ColourRange);
  in.Drawer.SetRgba(rgba, list.RgbaReading);
  if (bordered != in.BorderedTextures || pooled != in.PooledTextures ||
    in.TexturesTime < in.OctreeTime)
  {
    in.TexturesTime.Modified();
    in.Bricks.Clear(window);
    in.BorderedTextures = bordered;
    in.PooledTextures = pooled;
  }
  // Scattering shades (VTK's model blends the gradient shading, identity or not).
  const bool scatters = list.Effects.find("volume-scattering") != std::string::npos;
  ShadingDescription shading = in.Shading;
  shading.Shade = list.Shading || scatters;
  in.Drawer.SetShading(shading);
  if (scatters && in.Store)
  {
    vtkErrorMacro("volumetric scattering's shadow volume needs every sample in memory, and the "
                  "image names the OME-Zarr store '"
      << in.StorePath << "', drawn from disk: set VolumetricScatteringBlending to 0");
    return false;
  }
  if (scatters &&
    !in.Scattering.Activate(window, selected, Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
      in.OctreeTime.GetMTime(), error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.Drawer.SetScattering(scatters ? &in.Scattering : nullptr);
  in.Drawer.SetIsosurfaces(isosurface ? in.Isosurfaces : std::vector<double>());
  in.Drawer.SetSlice(!list.SlicePlane.empty());
  in.Drawer.SetOpacityEffects(
    list.Gradients, list.GradientOpacityTable, list.GradientOpacityEnd, list.OpacityScale);
  // The 2D transfer function's texture, when the plan classifies by it.
  vtkTextureObject* transfer2D = nullptr;
  if (list.Effects.find("transfer-2d") != std::string::npos &&
    !(transfer2D = in.Transfer2D.Activate(window, error)))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.Drawer.SetTransfer2D(transfer2D, list.Transfer2DAxes);
  const std::size_t border = bordered ? 1 : 0;
  in.Bricks.BeginFrame(
    static_cast<std::size_t>(std::max(textureBudget, 0.0)), list.NodeId, list.Stride);
  textures.assign(bricks, nullptr);
  // The frame's geometry is made from each brick's block ranges (kept with its texture).
  geometryInput.BlockRanges.assign(bricks, nullptr);
  for (std::size_t i = 0; i < bricks; ++i)
  {
    const std::size_t brick = list.Brick[i];
    const std::size_t dims[3] = { list.Texels[3 * i] + 2 * border,
      list.Texels[3 * i + 1] + 2 * border, list.Texels[3 * i + 2] + 2 * border };
    const vtkOpenGLHybridOctreeBrickTextures::Resident* resident = in.Bricks.Acquire(
      window, { list.NodeId[i], list.Stride[i] }, dims,
      [&](float* texels, unsigned char* encoded, std::size_t count) {
        if (in.Store)
        {
          return selected.GetBrickTexelsFromStore(*in.Octree, *in.Store, brick, bordered, texels,
            count, encoded, encoded ? count * in.Bricks.GetStagingBytes() : 0, error);
        }
        if (rgba)
        {
          return selected.GetBrickTexelsRgba(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, encoded, encoded ? count : 0, error);
        }
        if (dependent)
        {
          return selected.GetBrickTexelsDependent(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, error);
        }
        if (encoded)
        {
          return selected.GetBrickTexelsEncoded(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
            brick, bordered, texels, count, encoded, count * in.Bricks.GetStagingBytes(), error);
        }
        return bordered ? selected.GetBrickTexelsBordered(Bytes(in.Scalars), ByteCount(in.Scalars),
                            in.Grid, brick, texels, count, error)
                        : selected.GetBrickTexels(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid,
                            brick, texels, count, error);
      },
      error, border);
    if (!resident)
    {
      vtkErrorMacro(<< error);
      return false;
    }
    textures[i] = resident->Texture;
    geometryInput.BlockRanges[i] = &resident->BlockRanges;
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::UploadTable(vtkOpenGLRenderWindow* window)
{
  vtkInternals& in = *this->Internals;
  if (!in.TableTexture)
  {
    in.TableTexture = vtkSmartPointer<vtkTextureObject>::New();
    in.TableUploaded = false;
  }
  if (!in.TableUploaded || in.TableTexture->GetContext() != window)
  {
    in.TableTexture->SetContext(window);
    in.TableTexture->SetWrapS(vtkTextureObject::ClampToEdge);
    in.TableTexture->SetWrapT(vtkTextureObject::ClampToEdge);
    in.TableTexture->SetMinificationFilter(vtkTextureObject::Linear);
    in.TableTexture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!in.TableTexture->Create2DFromRaw(
          static_cast<unsigned int>(this->TableSize), 1, 4, VTK_FLOAT, in.Table.data()))
    {
      vtkErrorMacro("OpenGL could not create the transfer function table texture");
      return false;
    }
    in.TableUploaded = true;
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::MakeBrickGeometry(const DrawList& list,
  const CameraDescription& cam, bool interactive, double sampleSpacing,
  vtkHybridOctreeBridge::BrickGeometryInput& geometryInput)
{
  vtkInternals& in = *this->Internals;
  const bool batches = !list.BatchOffsets.empty() && list.BatchOffsets.back() > 0;
  // Per brick its slices clipped to its visible blocks, the translucent
  // triangles and the points in the slabs between them, or its ray-marched
  // box. Interactive: every brick ray-marched, no triangles or points in slabs.
  geometryInput.List = &list;
  std::copy(cam.Position, cam.Position + 3, geometryInput.Eye);
  std::copy(cam.ViewUp, cam.ViewUp + 3, geometryInput.ViewUp);
  std::copy(in.Grid.Spacing, in.Grid.Spacing + 3, geometryInput.Spacing);
  geometryInput.Table = &in.Table;
  geometryInput.TableLo = in.RangeLo;
  geometryInput.TableHi = in.RangeHi;
  if (list.Effects.find("transfer-2d") != std::string::npos)
  {
    // A block is empty when the 2D table is 0 over its values at every gradient.
    geometryInput.Table = &in.Transfer2D.ColumnTable(geometryInput.TableLo, geometryInput.TableHi);
  }
  if (batches && !interactive)
  {
    geometryInput.SurfaceVertices = &in.SurfaceDrawer.GetVertexData();
    geometryInput.SurfaceTriangles = &in.SurfaceDrawer.GetIndexData();
  }
  if (in.HasPoints && !list.BucketOffsets.empty() && !interactive)
  {
    geometryInput.PointPositions = &in.Drawing.Position;
    geometryInput.PointShades = &in.Shades;
    geometryInput.GaussianPoints = this->PointFootprint == 1;
  }
  std::string error;
  vtkHybridOctreeBridge::BrickGeometry geometry;
  if (!vtkHybridOctreeBridge::GetBrickGeometry(geometryInput, geometry, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(geometry.TrianglesPlaced);
  this->LastPoints = static_cast<vtkTypeInt64>(geometry.PointsPlaced);
  in.Drawer.SetGeometry(std::move(geometry), list.ReferenceSpacing);
  for (std::size_t i = 0; i < list.GetNumberOfBricks(); ++i)
  {
    if (in.Drawer.IsDrawn(i))
    {
      // The lattice planes sampled: every factor-th slice of a sparser ray march.
      const double slices = static_cast<double>(list.SliceOffsets[i + 1] - list.SliceOffsets[i]);
      const double factor = list.SliceSpacing[i] > 0.0
        ? std::max(1.0, sampleSpacing * list.ReferenceSpacing / list.SliceSpacing[i])
        : 1.0;
      this->LastSlices += static_cast<vtkTypeInt64>(std::ceil(slices / factor));
      ++this->LastBricks;
    }
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::DrawOpaqueSurface(vtkOpenGLRenderWindow* window,
  vtkMatrix4x4* mcdc, const CameraDescription& cam, const DrawList& list, const double rgba[4])
{
  vtkInternals& in = *this->Internals;
  if (list.OpaqueTriangles == 0)
  {
    return true;
  }
  // Written to depth, so that the volume behind it is hidden.
  vtkOpenGLState* state = window->GetState();
  state->vtkglDisable(GL_BLEND);
  state->vtkglDepthMask(GL_TRUE);
  std::string error;
  if (!in.SurfaceDrawer.Bind(window, mcdc, cam.Position, list.Forward, cam.Parallel, rgba, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  in.SurfaceDrawer.Draw(0, list.OpaqueTriangles);
  in.SurfaceDrawer.Unbind();
  this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(list.OpaqueTriangles);
  return true;
}

bool vtkHybridOctreeVolumeMapper::DrawBricks(vtkRenderer* ren, vtkOpenGLRenderWindow* window,
  vtkMatrix4x4* mcdc, const CameraDescription& cam, const DrawList& list,
  const std::vector<vtkTextureObject*>& textures, bool interactive, double imageSampleDistance,
  double sampleSpacing, const double rgba[4])
{
  vtkInternals& in = *this->Internals;
  const std::size_t bricks = list.GetNumberOfBricks();
  const bool batches = !list.BatchOffsets.empty() && list.BatchOffsets.back() > 0;
  // Interactive: its triangles drawn before or after each brick, not in slabs.
  const bool surfacePerBrick = interactive && batches;
  vtkOpenGLState* state = window->GetState();
  std::string error;
  // Bricks back to front, each one draw: its slices back to front with the
  // translucent triangles of each slab between them; blended premultiplied,
  // depth tested, not written. The region of the window drawn: the bricks'
  // boxes (their triangles included); points' footprints may reach past
  // them, so all of it then. Additive shows every ray crossing the volume's
  // box (opaque, black without a sample), so its region is that box: the
  // bricks' boxes leave out those cropping and clipping remove whole.
  const int reduceMode = ReduceMode(list.BlendMode);
  double region[4] = { -1.0, 1.0, -1.0, 1.0 };
  if (this->LastPoints == 0 && reduceMode == 4)
  {
    std::vector<double> volume(6);
    for (int a = 0; a < 3; ++a)
    {
      volume[2 * a] = in.Grid.Origin[a];
      volume[2 * a + 1] = in.Grid.Origin[a] + (in.Grid.Dims[a] - 1.0) * in.Grid.Spacing[a];
    }
    this->ScreenRegion(mcdc, volume, region);
  }
  else if (this->LastPoints == 0)
  {
    this->ScreenRegion(mcdc, list.Bounds, region);
  }
  // The blend modes besides Composite reduce each ray in the target by the
  // blend equation (maximum: GL_MAX, sums: GL_FUNC_ADD) and resolve it at End().
  const bool extremum = reduceMode == 1 || reduceMode == 2;
  const float clear[4] = { extremum ? -3.0e38f : 0.0f, 0.0f, 0.0f, 0.0f };
  if (!in.Target.Begin(ren, window, imageSampleDistance, region, error, clear))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  state->vtkglEnable(GL_BLEND);
  if (reduceMode == 0)
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  else
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    state->vtkglBlendEquation(extremum ? GL_MAX : GL_FUNC_ADD);
  }
  in.Drawer.SetReduction(reduceMode, in.ValueRange, this->AverageIPScalarRange);
  state->vtkglDisable(GL_DEPTH_TEST); // the shader tests against the copied opaque depth
  state->vtkglDepthMask(GL_FALSE);
  in.TableTexture->Activate();
  in.Target.GetDepth()->Activate();
  in.Drawer.SetSampleSpacing(sampleSpacing);
  in.Drawer.SetJitter(list.Effects.find("jittering") != std::string::npos, list);
  if (surfacePerBrick)
  {
    in.SurfaceDrawer.OrderByBrick(
      list, cam.Position, list.Forward, cam.Parallel, this->IsInsideOpaque());
  }
  bool ok = !surfacePerBrick ||
    in.SurfaceDrawer.Bind(
      window, mcdc, cam.Position, list.Forward, cam.Parallel, rgba, error, &in.Target);
  ok = ok &&
    in.Drawer.Bind(window, mcdc, in.TableTexture, in.Target, this->TableSize, in.RangeLo,
      in.RangeHi, cam.Position, list.Forward, cam.Parallel, rgba, error);
  if (ok)
  {
    // Clip distances (the slabs' triangles) on while the program that writes
    // them is bound; interactive frames have no slabs.
    for (unsigned int plane : { GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE0 + 1 })
    {
      if (!interactive)
      {
        state->vtkglEnable(plane);
      }
    }
    // Ray-marched boxes keep only the faces rays leave by (see
    // plan::draw_geometry); a mirroring model matrix turns their winding
    // over. Culling is restored before the target is blended.
    vtkOpenGLState::ScopedglEnableDisable brickCulling(state, GL_CULL_FACE);
    state->vtkglCullFace(GL_BACK);
    glFrontFace(in.Model->Determinant() < 0.0 ? GL_CW : GL_CCW);
    for (std::size_t i = 0; i < bricks; ++i)
    {
      if (in.Drawer.IsRayMarched(i))
      {
        state->vtkglEnable(GL_CULL_FACE);
      }
      else
      {
        state->vtkglDisable(GL_CULL_FACE);
      }
      const std::size_t before = surfacePerBrick ? this->DrawSurfaceBefore(window, i) : 0;
      if (before > 0)
      {
        this->LastSurfaceTriangles += static_cast<vtkTypeInt64>(before);
        state->vtkglEnable(GL_CULL_FACE); // every brick of an interactive frame is ray-marched
      }
      textures[i]->Activate();
      in.Drawer.DrawBrick(list, i, in.Grid.Spacing, textures[i]);
      textures[i]->Deactivate();
    }
    if (surfacePerBrick)
    {
      this->LastSurfaceTriangles +=
        static_cast<vtkTypeInt64>(this->DrawSurfaceBefore(window, bricks));
    }
    glFrontFace(GL_CCW);
    for (unsigned int plane : { GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE0 + 1 })
    {
      state->vtkglDisable(plane);
    }
    in.Drawer.Unbind();
  }
  state->vtkglBlendEquation(GL_FUNC_ADD);
  in.Target.GetDepth()->Deactivate();
  in.TableTexture->Deactivate();
  vtkOpenGLHybridOctreeFloatTarget::Resolve resolve;
  resolve.ReduceMode = reduceMode;
  resolve.Table = in.TableTexture;
  resolve.TableEntries = this->TableSize;
  resolve.TableRange[0] = in.RangeLo;
  resolve.TableRange[1] = in.RangeHi;
  resolve.MCDC = mcdc;
  for (int a = 0; a < 3; ++a)
  {
    resolve.VolumeLo[a] = in.Grid.Origin[a];
    resolve.VolumeHi[a] = in.Grid.Origin[a] + (in.Grid.Dims[a] - 1.0) * in.Grid.Spacing[a];
  }
  in.Target.End(window, reduceMode != 0 ? &resolve : nullptr);
  if (!ok)
  {
    vtkErrorMacro(<< error);
  }
  return ok;
}

void vtkHybridOctreeVolumeMapper::ScreenRegion(
  vtkMatrix4x4* mcdc, const std::vector<double>& bounds, double region[4]) const
{
  // The normalized device box of the boxes' corners (VTK's key matrices are
  // transposed: clip_r = sum_j mcdc(j, r) p_j); everything when a corner
  // lies behind the eye.
  double box[4] = { 1.0, -1.0, 1.0, -1.0 };
  for (std::size_t i = 0; 6 * i + 5 < bounds.size(); ++i)
  {
    for (int c = 0; c < 8; ++c)
    {
      const double p[4] = { bounds[6 * i + (c & 1)], bounds[6 * i + 2 + ((c >> 1) & 1)],
        bounds[6 * i + 4 + ((c >> 2) & 1)], 1.0 };
      double clip[4];
      for (int r = 0; r < 4; ++r)
      {
        clip[r] = mcdc->GetElement(0, r) * p[0] + mcdc->GetElement(1, r) * p[1] +
          mcdc->GetElement(2, r) * p[2] + mcdc->GetElement(3, r) * p[3];
      }
      if (!(clip[3] > 0.0))
      {
        region[0] = region[2] = -1.0;
        region[1] = region[3] = 1.0;
        return;
      }
      for (int a = 0; a < 2; ++a)
      {
        box[2 * a] = std::min(box[2 * a], clip[a] / clip[3]);
        box[2 * a + 1] = std::max(box[2 * a + 1], clip[a] / clip[3]);
      }
    }
  }
  std::copy(box, box + 4, region);
}

std::size_t vtkHybridOctreeVolumeMapper::DrawSurfaceBefore(
  vtkOpenGLRenderWindow* window, std::size_t i)
{
  vtkInternals& in = *this->Internals;
  const std::pair<std::size_t, std::size_t> range = in.SurfaceDrawer.GetTrianglesBefore(i);
  if (range.second <= range.first)
  {
    return 0;
  }
  window->GetState()->vtkglDisable(GL_CULL_FACE);
  in.SurfaceDrawer.Rebind(window);
  in.SurfaceDrawer.Draw(range.first, range.second);
  in.Drawer.Rebind(window);
  return range.second - range.first;
}

bool vtkHybridOctreeVolumeMapper::IsInsideOpaque() const
{
  // The mean table opacity above the isovalue against below it.
  const vtkInternals& in = *this->Internals;
  const int n = this->TableSize;
  double sum[2] = { 0.0, 0.0 };
  int count[2] = { 0, 0 };
  for (int k = 0; k < n && 4 * static_cast<std::size_t>(k) + 3 < in.Table.size(); ++k)
  {
    const double v = in.RangeLo + (in.RangeHi - in.RangeLo) * k / (n - 1);
    const int inside = v >= this->Isovalue ? 1 : 0;
    sum[inside] += in.Table[4 * static_cast<std::size_t>(k) + 3];
    ++count[inside];
  }
  return sum[1] * std::max(count[0], 1) >= sum[0] * std::max(count[1], 1);
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
  if (in.Store)
  {
    vtkErrorMacro("CompositeOnCPU draws from the image in memory, and the image names the "
                  "OME-Zarr store '"
      << in.StorePath
      << "': read its full resolution into an image without the store's field data");
    return false;
  }
  CompositeScene scene = in.Transfer;
  scene.GaussianPoints = this->PointFootprint == 1;
  if (in.HasIso && this->ShowSurface && this->SurfaceOpacity > 0.0)
  {
    for (int k = 0; k < 3; ++k)
    {
      scene.SurfaceRGBA[k] = this->SurfaceColor[k];
    }
    scene.SurfaceRGBA[3] = this->SurfaceOpacity;
  }
  // The compositor writes the picture into `rgba` itself.
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  std::string error;
  if (!in.Frame->Selected->SetShading(in.Shading, error) ||
    !in.Frame->Selected->SetGradientOpacity(in.GradientOpacity, error) ||
    !in.Frame->Selected->SetJittering(this->UseJittering != 0, error) ||
    !in.Frame->Selected->SetSampleDistance(this->ActualSampleDistance(), error) ||
    !in.Frame->Selected->SetScattering(in.ScatteringParameters, error) ||
    !in.Frame->Selected->Composite(*in.Octree, this->ModelCamera(ren), Bytes(in.Scalars),
      ByteCount(in.Scalars), in.Grid, scene, static_cast<std::size_t>(width),
      static_cast<std::size_t>(height), rgba->GetPointer(0), error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

void vtkHybridOctreeVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  in.Bricks.Clear(window);
  in.Reduction.Reset();
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
  os << indent << "LastViewSelection: view: " << this->LastViewSelection << "\n";
}
