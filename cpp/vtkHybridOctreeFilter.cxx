#include "vtkHybridOctreeFilter.h"

#include "vtkHybridOctreeBridge.h"

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
#include "vtkTypeInt64Array.h"

#include <cstdint>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkHybridOctreeFilter);

/// The cached octree and what it was built from. The key is the array
/// (object and MTime: the values) and the grid description (the geometry),
/// not the image's MTime: ParaView's pipeline touches the input image on
/// every request even when its data did not change.
struct vtkHybridOctreeFilter::vtkInternals
{
  std::unique_ptr<vtkHybridOctreeBridge::VolumeOctree> Octree;
  const vtkDataArray* Array = nullptr;
  vtkMTimeType ArrayMTime = 0;
  vtkHybridOctreeBridge::GridDescription Grid;
  int LeafSize = 0;

  bool IsBuiltFrom(const vtkDataArray* array, vtkMTimeType arrayMTime,
    const vtkHybridOctreeBridge::GridDescription& grid, int leafSize) const
  {
    if (!this->Octree || this->Array != array || this->ArrayMTime != arrayMTime ||
      this->LeafSize != leafSize || this->Grid.Type != grid.Type ||
      this->Grid.Components != grid.Components || this->Grid.Component != grid.Component)
    {
      return false;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      if (this->Grid.Dims[axis] != grid.Dims[axis] ||
        this->Grid.Spacing[axis] != grid.Spacing[axis] ||
        this->Grid.Origin[axis] != grid.Origin[axis])
      {
        return false;
      }
    }
    return true;
  }
};

namespace
{
/// Maps a VTK scalar type to the core's; false for types the core cannot read.
bool ToBridgeType(int vtkType, vtkHybridOctreeBridge::ScalarType& type)
{
  using vtkHybridOctreeBridge::ScalarType;
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

/// Adds a one-value array named `name` to `fieldData`.
template <typename ArrayT, typename ValueT>
void AddFieldValue(vtkFieldData* fieldData, const char* name, ValueT value)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfTuples(1);
  array->SetValue(0, static_cast<typename ArrayT::ValueType>(value));
  fieldData->AddArray(array);
}

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
  this->SetNumberOfOutputPorts(1);
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
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  const bool cellArraysOnly = image->GetPointData()->GetNumberOfArrays() == 0 &&
    image->GetCellData()->GetNumberOfArrays() > 0;
  if ((scalars && association != vtkDataObject::FIELD_ASSOCIATION_POINTS) ||
    (!scalars && cellArraysOnly))
  {
    vtkErrorMacro("the input image has cell data only: point scalars required; use Cell Data to "
                  "Point Data (vtkCellDataToPointData) before the Hybrid Octree");
    return nullptr;
  }
  if (!scalars)
  {
    vtkErrorMacro("the input image has no point scalars to build the Hybrid Octree from; select a "
                  "point array with SetInputArrayToProcess (ParaView: 'Scalars')");
    return nullptr;
  }
  vtkHybridOctreeBridge::ScalarType type;
  if (!ToBridgeType(scalars->GetDataType(), type))
  {
    vtkErrorMacro("point array '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                  << "' has scalar type '" << scalars->GetDataTypeAsString()
                                  << "', which the Hybrid Octree does not read; cast it to float, "
                                     "double or a 8/16/32-bit integer type first (vtkImageCast, "
                                     "ParaView's Calculator with a result array type)");
    return nullptr;
  }
  if (!scalars->HasStandardMemoryLayout())
  {
    vtkErrorMacro("point array '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                  << "' does not store its values contiguously (array of "
                                     "structures); deep copy it into a vtkAOSDataArrayTemplate");
    return nullptr;
  }
  return scalars;
}

//------------------------------------------------------------------------------
bool vtkHybridOctreeFilter::UpdateOctree(vtkImageData* image, vtkDataArray* scalars)
{
  vtkHybridOctreeBridge::GridDescription grid;
  ToBridgeType(scalars->GetDataType(), grid.Type);
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
  grid.Components = static_cast<std::size_t>(scalars->GetNumberOfComponents());
  grid.Component = this->Component;

  vtkInternals& cache = *this->Internals;
  if (cache.IsBuiltFrom(scalars, scalars->GetMTime(), grid, this->LeafSize))
  {
    return true;
  }
  cache.Octree.reset();
  if (!image->GetDirectionMatrix()->IsIdentity())
  {
    vtkWarningMacro("the image's direction matrix is ignored: boxes are axis-aligned");
  }

  const std::size_t byteCount = static_cast<std::size_t>(scalars->GetNumberOfTuples()) *
    grid.Components * static_cast<std::size_t>(scalars->GetDataTypeSize());
  const void* bytes = byteCount > 0 ? scalars->GetVoidPointer(0) : nullptr;

  std::string error;
  cache.Octree = vtkHybridOctreeBridge::VolumeOctree::Build(
    bytes, byteCount, grid, static_cast<unsigned int>(this->LeafSize), error);
  if (!cache.Octree)
  {
    vtkErrorMacro(<< error);
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
int vtkHybridOctreeFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("the output is not a vtkPolyData");
    return 0;
  }
  output->Initialize();
  if (!input)
  {
    vtkErrorMacro("no input image: connect a vtkImageData with point scalars");
    return 0;
  }
  vtkDataArray* scalars = this->GetScalars(input, inputVector);
  if (!scalars || !this->UpdateOctree(input, scalars))
  {
    return 0;
  }

  const vtkHybridOctreeBridge::VolumeOctree& octree = *this->Internals->Octree;
  vtkHybridOctreeBridge::OctreeSummary summary;
  vtkHybridOctreeBridge::CutBoxes cut;
  std::string error;
  if (!octree.GetSummary(summary, error) ||
    !octree.GetCutBoxes(this->ErrorTolerance, cut, error))
  {
    vtkErrorMacro(<< error);
    return 0;
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
  for (vtkDataArray* array :
    { static_cast<vtkDataArray*>(node), static_cast<vtkDataArray*>(level),
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
      points->SetPoint(8 * b + c, bounds[c & 1], bounds[2 + ((c >> 1) & 1)],
        bounds[4 + ((c >> 2) & 1)]);
    }
    for (int e = 0; e < 12; ++e)
    {
      const vtkIdType cell = 12 * b + e;
      offsets->SetValue(cell, 2 * cell);
      connectivity->SetValue(2 * cell, 8 * b + BoxEdges[e][0]);
      connectivity->SetValue(2 * cell + 1, 8 * b + BoxEdges[e][1]);
      node->SetValue(cell, static_cast<int>(b));
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
  AddFieldValue<vtkTypeInt64Array>(fieldData, "node_count", summary.NodeCount);
  AddFieldValue<vtkTypeInt64Array>(fieldData, "terminal_count", summary.TerminalCount);
  AddFieldValue<vtkTypeInt64Array>(fieldData, "homogeneous_count", summary.HomogeneousCount);
  AddFieldValue<vtkIntArray>(fieldData, "levels", summary.Levels);
  AddFieldValue<vtkIntArray>(fieldData, "leaf_size", summary.LeafSize);
  AddFieldValue<vtkIntArray>(fieldData, "root_size", summary.RootSize);
  AddFieldValue<vtkTypeInt64Array>(fieldData, "octree_bytes", summary.OctreeBytes);
  AddFieldValue<vtkTypeInt64Array>(fieldData, "input_bytes", summary.InputBytes);
  AddFieldValue<vtkDoubleArray>(fieldData, "build_ms", summary.BuildMilliseconds);
  AddFieldValue<vtkDoubleArray>(fieldData, "value_min", summary.ValueMin);
  AddFieldValue<vtkDoubleArray>(fieldData, "value_max", summary.ValueMax);
  AddFieldValue<vtkTypeInt64Array>(fieldData, "cut_count", boxCount);
  output->SetFieldData(fieldData);
  return 1;
}

//------------------------------------------------------------------------------
void vtkHybridOctreeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "OctreeBuildCount: " << this->OctreeBuildCount << "\n";
  os << indent << "Cached octree: " << (this->Internals->Octree ? "yes" : "no") << "\n";
}
