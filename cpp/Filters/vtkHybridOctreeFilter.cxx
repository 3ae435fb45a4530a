#include "vtkHybridOctreeFilter.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeFieldData.h"
#include "vtkHybridOctreeImageInput.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkHybridOctreeFilter);

/// The cached octree and what it was built from. The key is the array
/// (object and MTime: the values) and the grid description (the geometry),
/// not the image's MTime: ParaView's pipeline touches the input image on
/// every request even when its data did not change.
struct vtkHybridOctreeFilter::vtkInternals
{
  std::unique_ptr<vtkHybridOctreeBridge::HybridOctree> Octree;
  const vtkDataArray* Array = nullptr;
  vtkMTimeType ArrayMTime = 0;
  vtkHybridOctreeBridge::GridDescription Grid;
  int LeafSize = 0;

  /// The cached surface and what it was extracted with: the octree (by its
  /// build number, OctreeBuildCount at extraction) and the surface settings.
  vtkSmartPointer<vtkPolyData> Surface;
  vtkIdType SurfaceOctreeBuild = -1;
  double SurfaceIsovalue = 0.0;
  int SurfaceMode = -1;
  vtkTypeBool SurfaceMeasured = 0;

  bool IsSurfaceExtractedWith(
    vtkIdType octreeBuild, double isovalue, int mode, vtkTypeBool measured) const
  {
    // A NaN isovalue never compares equal: it is passed on to fail again.
    return this->Surface && this->SurfaceOctreeBuild == octreeBuild &&
      this->SurfaceIsovalue == isovalue && this->SurfaceMode == mode &&
      this->SurfaceMeasured == measured;
  }

  bool IsBuiltFrom(const vtkDataArray* array, vtkMTimeType arrayMTime,
    const vtkHybridOctreeBridge::GridDescription& grid, int leafSize) const
  {
    return this->Octree && this->Array == array && this->ArrayMTime == arrayMTime &&
      this->LeafSize == leafSize && vtkHybridOctreeImageInput::SameGrid(this->Grid, grid);
  }
};

namespace
{
using vtkHybridOctreeImageInput::ByteCount;
using vtkHybridOctreeImageInput::Bytes;
using vtkHybridOctreeImageInput::DescribeGrid;

/// True when every octree node id fits the int cell array "node".
bool FitsInt(const std::vector<std::uint32_t>& ids)
{
  return std::all_of(ids.begin(), ids.end(),
    [](std::uint32_t id) { return id <= static_cast<std::uint32_t>(VTK_INT_MAX); });
}

/// Progress of a request: the octree build reports 0 .. BuildShare, the
/// surface extraction starts at SurfaceShare, the end is 1.
constexpr double BuildShare = 0.8;
constexpr double SurfaceShare = 0.9;

constexpr const char* NodeIdTooLarge =
  "the octree has more than 2^31 nodes, whose ids do not fit the int cell array 'node'; use a "
  "larger LeafSize";

/// Corner pairs of the 12 edges of a box whose corner c sits at
/// x[c & 1], y[(c >> 1) & 1], z[(c >> 2) & 1]: x edges, y edges, z edges.
constexpr int BoxEdges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
  { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
} // namespace

//------------------------------------------------------------------------------
vtkHybridOctreeFilter::vtkHybridOctreeFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
  // Default input array: the point scalars of the image.
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkHybridOctreeFilter::~vtkHybridOctreeFilter() = default;

//------------------------------------------------------------------------------
int vtkHybridOctreeFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
vtkDataArray* vtkHybridOctreeFilter::GetScalars(
  vtkImageData* image, vtkInformationVector** inputVector)
{
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars =
    image ? this->GetInputArrayToProcess(0, inputVector, association) : nullptr;
  std::string error;
  scalars = vtkHybridOctreeImageInput::CheckPointScalars(image, scalars, association, error);
  if (!scalars)
  {
    vtkErrorMacro(<< error);
  }
  return scalars;
}

//------------------------------------------------------------------------------
bool vtkHybridOctreeFilter::UpdateOctree(vtkImageData* image, vtkDataArray* scalars)
{
  const vtkHybridOctreeBridge::GridDescription grid = DescribeGrid(image, scalars, this->Component);

  vtkInternals& cache = *this->Internals;
  if (cache.IsBuiltFrom(scalars, scalars->GetMTime(), grid, this->LeafSize))
  {
    return true;
  }
  cache.Octree.reset();
  cache.Surface = nullptr;
  if (!image->GetDirectionMatrix()->IsIdentity())
  {
    vtkWarningMacro("the image's direction matrix is ignored: boxes are axis-aligned");
  }

  std::string error;
  // Progress 0 .. BuildShare of the request; the abort flag is read after
  // each report with CheckAbort(), which also marks the outputs ABORTED for
  // the executive (VTK's abort protocol).
  const auto progress = [this](double fraction) {
    this->UpdateProgress(BuildShare * fraction);
    return !this->CheckAbort();
  };
  cache.Octree = vtkHybridOctreeBridge::HybridOctree::Build(Bytes(scalars), ByteCount(scalars),
    grid, static_cast<unsigned int>(this->LeafSize), progress, error);
  if (!cache.Octree)
  {
    if (this->GetAbortOutput())
    {
      vtkWarningMacro("the Hybrid Octree build was cancelled (abort): the outputs are empty; "
                      "modify the filter (ParaView: Apply) to build again");
    }
    else
    {
      vtkErrorMacro(<< error);
    }
    return false;
  }
  ++this->OctreeBuildCount;
  cache.Array = scalars;
  cache.ArrayMTime = scalars->GetMTime();
  cache.Grid = grid;
  cache.LeafSize = this->LeafSize;
  return true;
}

//------------------------------------------------------------------------------
const char* vtkHybridOctreeFilter::GetSurfaceModeAsString() const
{
  return this->SurfaceMode == SURFACE_MODE_INTERPOLATED ? "interpolated" : "discretized";
}

//------------------------------------------------------------------------------
bool vtkHybridOctreeFilter::UpdateSurface(vtkDataArray* scalars)
{
  vtkInternals& cache = *this->Internals;
  if (cache.IsSurfaceExtractedWith(
        this->OctreeBuildCount, this->Isovalue, this->SurfaceMode, this->MeasureSurfaceDistance))
  {
    return true;
  }
  cache.Surface = nullptr;

  vtkHybridOctreeBridge::SurfaceSummary mesh;
  std::string error;
  const auto mode = this->SurfaceMode == SURFACE_MODE_INTERPOLATED
    ? vtkHybridOctreeBridge::SurfaceMode::Interpolated
    : vtkHybridOctreeBridge::SurfaceMode::Discretized;
  if (!cache.Octree->IntegrateSurface(Bytes(scalars), ByteCount(scalars), cache.Grid,
        this->Isovalue, mode, this->MeasureSurfaceDistance != 0, mesh, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  ++this->SurfaceExtractCount;

  // The arrays the core writes the mesh into, sized from its summary.
  const vtkIdType vertices = static_cast<vtkIdType>(mesh.Vertices);
  const vtkIdType polygons = static_cast<vtkIdType>(mesh.Polygons);
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(vertices);
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);

  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(vertices);

  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(polygons + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(mesh.Connectivity));

  vtkNew<vtkIntArray> node;
  node->SetName("node");
  node->SetNumberOfValues(polygons);
  vtkNew<vtkIntArray> level;
  level->SetName("level");
  level->SetNumberOfValues(polygons);
  vtkNew<vtkIdTypeArray> face;
  face->SetName("face");
  face->SetNumberOfValues(polygons);

  vtkHybridOctreeBridge::SurfaceMeshBuffers buffers;
  buffers.Points = coordinates->GetPointer(0);
  buffers.Normals = normals->GetPointer(0);
  buffers.Offsets = offsets->GetPointer(0);
  buffers.Connectivity = connectivity->GetPointer(0);
  buffers.PolygonNode = node->GetPointer(0);
  buffers.PolygonLevel = level->GetPointer(0);
  buffers.PolygonFace = face->GetPointer(0);
  const bool written = cache.Octree->GetSurfaceMesh(buffers, error);
  // The filter outputs the mesh; the octree need not keep it.
  cache.Octree->RemoveSurface();
  if (!written)
  {
    vtkErrorMacro(<< error);
    return false;
  }
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);

  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(polys);
  surface->GetPointData()->SetNormals(normals);
  surface->GetCellData()->AddArray(node);
  surface->GetCellData()->AddArray(level);
  surface->GetCellData()->AddArray(face);

  vtkNew<vtkFieldData> fieldData;
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fieldData, "isovalue", this->Isovalue);
  vtkNew<vtkStringArray> modeName;
  modeName->SetName("surface_mode");
  modeName->InsertNextValue(this->GetSurfaceModeAsString());
  fieldData->AddArray(modeName);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "polygons", mesh.Polygons);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "faces", mesh.Faces);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "triangles", mesh.Triangles);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "uncompressed_triangles", mesh.UncompressedTriangles);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "vertices", mesh.Vertices);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "boundary_edges", mesh.BoundaryEdges);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(
    fieldData, "extract_ms", mesh.ExtractMilliseconds);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(
    fieldData, "compress_ms", mesh.CompressMilliseconds);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fieldData, "distance_mean", mesh.DistanceMean);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fieldData, "distance_max", mesh.DistanceMax);
  surface->SetFieldData(fieldData);

  cache.Surface = surface;
  cache.SurfaceOctreeBuild = this->OctreeBuildCount;
  cache.SurfaceIsovalue = this->Isovalue;
  cache.SurfaceMode = this->SurfaceMode;
  cache.SurfaceMeasured = this->MeasureSurfaceDistance;
  return true;
}

//------------------------------------------------------------------------------
int vtkHybridOctreeFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* boxes = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* surface = vtkPolyData::GetData(outputVector, 1);
  if (!boxes || !surface)
  {
    vtkErrorMacro("the outputs are not vtkPolyData");
    return 0;
  }
  boxes->Initialize();
  surface->Initialize();
  vtkDataArray* scalars = this->GetScalars(input, inputVector);
  if (!scalars)
  {
    return 0;
  }
  if (!this->UpdateOctree(input, scalars))
  {
    // A cancel (CheckAbort() said so) is the user's request, not a failure:
    // the request completes, empty.
    return this->GetAbortOutput() ? 1 : 0;
  }
  this->UpdateProgress(SurfaceShare);
  if (!this->UpdateSurface(scalars) || !this->FillBoxes(boxes))
  {
    boxes->Initialize();
    return 0;
  }
  surface->ShallowCopy(this->Internals->Surface);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkHybridOctreeFilter::FillBoxes(vtkPolyData* output)
{
  const vtkHybridOctreeBridge::HybridOctree& octree = *this->Internals->Octree;
  vtkHybridOctreeBridge::OctreeSummary summary;
  vtkHybridOctreeBridge::CutBoxes cut;
  std::string error;
  if (!octree.GetSummary(summary, error) || !octree.GetCutBoxes(this->ErrorTolerance, cut, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  if (!FitsInt(cut.NodeId))
  {
    vtkErrorMacro(<< NodeIdTooLarge);
    return false;
  }

  // Geometry: 8 corners and 12 outline edges per box.
  const vtkIdType boxCount = static_cast<vtkIdType>(cut.GetNumberOfBoxes());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(8 * boxCount);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(12 * boxCount + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(24 * boxCount);

  vtkNew<vtkIntArray> node;
  node->SetName("node");
  vtkNew<vtkIntArray> level;
  level->SetName("level");
  vtkNew<vtkFloatArray> nodalError;
  nodalError->SetName("nodal_error");
  vtkNew<vtkDoubleArray> minimum;
  minimum->SetName("min");
  vtkNew<vtkDoubleArray> maximum;
  maximum->SetName("max");
  for (vtkDataArray* array : { static_cast<vtkDataArray*>(node), static_cast<vtkDataArray*>(level),
         static_cast<vtkDataArray*>(nodalError), static_cast<vtkDataArray*>(minimum),
         static_cast<vtkDataArray*>(maximum) })
  {
    array->SetNumberOfTuples(12 * boxCount);
  }

  for (vtkIdType b = 0; b < boxCount; ++b)
  {
    const double* bounds = &cut.Bounds[6 * b];
    for (int c = 0; c < 8; ++c)
    {
      points->SetPoint(
        8 * b + c, bounds[c & 1], bounds[2 + ((c >> 1) & 1)], bounds[4 + ((c >> 2) & 1)]);
    }
    for (int e = 0; e < 12; ++e)
    {
      const vtkIdType cell = 12 * b + e;
      offsets->SetValue(cell, 2 * cell);
      connectivity->SetValue(2 * cell, 8 * b + BoxEdges[e][0]);
      connectivity->SetValue(2 * cell + 1, 8 * b + BoxEdges[e][1]);
      node->SetValue(cell, static_cast<int>(cut.NodeId[b]));
      level->SetValue(cell, static_cast<int>(cut.Level[b]));
      nodalError->SetValue(cell, cut.NodalError[b]);
      minimum->SetValue(cell, cut.Min[b]);
      maximum->SetValue(cell, cut.Max[b]);
    }
  }
  offsets->SetValue(12 * boxCount, 24 * boxCount);
  vtkNew<vtkCellArray> lines;
  lines->SetData(offsets, connectivity);

  output->SetPoints(points);
  output->SetLines(lines);
  vtkCellData* cellData = output->GetCellData();
  cellData->AddArray(node);
  cellData->AddArray(level);
  cellData->AddArray(nodalError);
  cellData->AddArray(minimum);
  cellData->AddArray(maximum);
  cellData->SetActiveScalars("nodal_error");

  vtkNew<vtkFieldData> fieldData;
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "node_count", summary.NodeCount);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "terminal_count", summary.TerminalCount);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "homogeneous_count", summary.HomogeneousCount);
  vtkHybridOctreeFieldData::AddValue<vtkIntArray>(fieldData, "levels", summary.Levels);
  vtkHybridOctreeFieldData::AddValue<vtkIntArray>(fieldData, "leaf_size", summary.LeafSize);
  vtkHybridOctreeFieldData::AddValue<vtkIntArray>(fieldData, "root_size", summary.RootSize);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "octree_bytes", summary.OctreeBytes);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "input_bytes", summary.InputBytes);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(
    fieldData, "build_ms", summary.BuildMilliseconds);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fieldData, "value_min", summary.ValueMin);
  vtkHybridOctreeFieldData::AddValue<vtkDoubleArray>(fieldData, "value_max", summary.ValueMax);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(
    fieldData, "nan_samples", summary.NaNSamples);
  vtkHybridOctreeFieldData::AddValue<vtkTypeInt64Array>(fieldData, "cut_count", boxCount);
  output->SetFieldData(fieldData);
  return true;
}

//------------------------------------------------------------------------------
void vtkHybridOctreeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "Isovalue: " << this->Isovalue << "\n";
  os << indent << "SurfaceMode: " << this->SurfaceMode << " (" << this->GetSurfaceModeAsString()
     << ")\n";
  os << indent << "MeasureSurfaceDistance: " << (this->MeasureSurfaceDistance ? "on" : "off")
     << "\n";
  os << indent << "OctreeBuildCount: " << this->OctreeBuildCount << "\n";
  os << indent << "SurfaceExtractCount: " << this->SurfaceExtractCount << "\n";
  os << indent << "Cached octree: " << (this->Internals->Octree ? "yes" : "no") << "\n";
  os << indent << "Cached surface: " << (this->Internals->Surface ? "yes" : "no") << "\n";
}
