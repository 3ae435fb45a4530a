#include "vtkHybridOctreeImageInput.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

namespace vtkHybridOctreeImageInput
{
using vtkHybridOctreeBridge::GridDescription;
using vtkHybridOctreeBridge::ScalarType;

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

GridDescription DescribeGrid(vtkImageData* image, vtkDataArray* scalars, int component)
{
  GridDescription grid;
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
  grid.Component = component;
  return grid;
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

vtkDataArray* CheckPointScalars(
  vtkImageData* image, vtkDataArray* scalars, int association, std::string& error)
{
  if (!image)
  {
    error = "no input image: connect a vtkImageData with point scalars";
    return nullptr;
  }
  const bool cellArraysOnly = image->GetPointData()->GetNumberOfArrays() == 0 &&
    image->GetCellData()->GetNumberOfArrays() > 0;
  const std::string name = scalars && scalars->GetName() ? scalars->GetName() : "(unnamed)";
  vtkHybridOctreeBridge::ScalarType type;
  if ((scalars && association != vtkDataObject::FIELD_ASSOCIATION_POINTS) ||
    (!scalars && cellArraysOnly))
  {
    error = "the input image has cell data only: point scalars required; use Cell Data to "
            "Point Data (vtkCellDataToPointData) before the Hybrid Octree";
  }
  else if (!scalars)
  {
    error = "the input image has no point scalars to build the Hybrid Octree from; select a "
            "point array with SetInputArrayToProcess (ParaView: 'Scalars')";
  }
  else if (!ToBridgeType(scalars->GetDataType(), type))
  {
    error = "point array '" + name + "' has scalar type '" + scalars->GetDataTypeAsString() +
      "', which the Hybrid Octree does not read; cast it to float, double or a 8/16/32-bit "
      "integer type first (vtkImageCast, ParaView's Calculator with a result array type)";
  }
  else if (!scalars->HasStandardMemoryLayout())
  {
    error = "point array '" + name +
      "' does not store its values contiguously (array of structures); deep copy it into a "
      "vtkAOSDataArrayTemplate";
  }
  else
  {
    return scalars;
  }
  return nullptr;
}

void RequestWholeExtent(vtkInformationVector** inputVector)
{
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  if (in && in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
}

}
