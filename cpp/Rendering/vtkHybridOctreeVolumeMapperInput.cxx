// vtkHybridOctreeVolumeMapper: the input, an image in memory or the OME-Zarr store it names,
// and the Volume Octree built from it (vtkHybridOctreeVolumeMapperInternals.h).
#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeImageInput.h"
#include "vtkHybridOctreeStoreFieldData.h"
#include "vtkHybridOctreeVolumeMapperInternals.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace
{
using namespace vtkHybridOctreeBridge;
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

} // namespace

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
  in.ForgetOctree();
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
  in.ForgetOctree();
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

bool vtkHybridOctreeVolumeMapper::PlanLoading()
{
  vtkInternals& in = *this->Internals;
  const Selection& selected = *in.Frame->Selected;
  if (!in.Store || !this->AsynchronousLoading)
  {
    selected.DrawSelected();
    return true;
  }
  std::vector<std::uint32_t> nodes;
  std::vector<std::size_t> strides;
  in.Bricks.GetResident(nodes, strides);
  LoadingSummary loading;
  std::string error;
  if (!selected.PlanLoading(*in.Octree, *in.Store, nodes, strides,
        static_cast<std::size_t>(this->LoadingMemoryMB * 1.0e6), loading, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  this->LastBricksLoading = static_cast<int>(loading.StandIns);
  return true;
}
