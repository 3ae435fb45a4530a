#include "vtkHybridOctreePoints.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeImageInput.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkStandardNewMacro(vtkHybridOctreePoints);

vtkHybridOctreePoints::vtkHybridOctreePoints()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkHybridOctreePoints::~vtkHybridOctreePoints() = default;

void vtkHybridOctreePoints::SetFileName(const std::string& name)
{
  if (this->FileName != name)
  {
    this->FileName = name;
    this->Modified();
  }
}

int vtkHybridOctreePoints::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkHybridOctreePoints::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkHybridOctreeImageInput::RequestWholeExtent(inputVector);
  return 1;
}

namespace
{
void AddField(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

/// Texels of the stride-`factor` low resolution of `dims` samples, 4 bytes each.
double LowResolutionBytes(const int dims[3], int factor)
{
  double texels = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    texels *= static_cast<double>((dims[a] - 1 + factor - 1) / factor + 1);
  }
  return 4.0 * texels;
}
}

int vtkHybridOctreePoints::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("the output is not vtkPolyData");
    return 0;
  }
  output->Initialize();
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* chosen =
    input ? this->GetInputArrayToProcess(0, inputVector, association) : nullptr;
  std::string error;
  vtkDataArray* scalars =
    vtkHybridOctreeImageInput::CheckPointScalars(input, chosen, association, error);
  if (!scalars)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (this->Factor != 2 && this->Factor != 4 && this->Factor != 8)
  {
    vtkErrorMacro(
      "the low-resolution factor " << this->Factor << " is not supported: use 2, 4 or 8");
    return 0;
  }
  vtkHybridOctreeBridge::PointsOptions options;
  options.Factor = static_cast<std::size_t>(this->Factor);
  options.Threshold = this->Threshold;
  options.UseBudget = this->PointBudget > 0;
  options.Budget = static_cast<std::size_t>(this->PointBudget);
  options.UnderestimatesOnly = this->UnderestimatesOnly != 0;
  options.MaxOverestimate = this->MaxOverestimate;
  options.FileName = this->FileName;
  // The core writes values, errors and normals into the output arrays, the
  // grid indices into `ijk` (placed below through the image's geometry).
  vtkNew<vtkFloatArray> value;
  value->SetName("value");
  vtkNew<vtkFloatArray> err;
  err->SetName("error");
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  std::vector<std::uint32_t> ijk;
  const auto allocate = [&](const vtkHybridOctreeBridge::PointsSummary& made) {
    const vtkIdType count = static_cast<vtkIdType>(made.Points);
    value->SetNumberOfTuples(count);
    err->SetNumberOfTuples(count);
    normals->SetNumberOfTuples(count);
    ijk.resize(3 * made.Points);
    vtkHybridOctreeBridge::PointsBuffers buffers;
    buffers.Ijk = ijk.data();
    buffers.Value = value->GetPointer(0);
    buffers.Error = err->GetPointer(0);
    buffers.Normal = normals->GetPointer(0);
    return buffers;
  };
  vtkHybridOctreeBridge::PointsSummary result;
  if (!vtkHybridOctreeBridge::GeneratePoints(vtkHybridOctreeImageInput::Bytes(scalars),
        vtkHybridOctreeImageInput::ByteCount(scalars),
        vtkHybridOctreeImageInput::DescribeGrid(input, scalars, this->Component), options, allocate,
        result, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::size_t n = result.Points;
  int extent[6];
  input->GetExtent(extent);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    // Grid index (from the extent's start) to the physical point, direction matrix included.
    const int index[3] = { extent[0] + static_cast<int>(ijk[3 * i]),
      extent[2] + static_cast<int>(ijk[3 * i + 1]), extent[4] + static_cast<int>(ijk[3 * i + 2]) };
    double xyz[3];
    input->TransformIndexToPhysicalPoint(index, xyz);
    points->SetPoint(static_cast<vtkIdType>(i), xyz);
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(n); ++i)
  {
    connectivity->SetValue(i, i);
  }
  vtkNew<vtkCellArray> verts;
  verts->SetData(1, connectivity);
  output->SetPoints(points);
  output->SetVerts(verts);
  output->GetPointData()->SetScalars(value);
  output->GetPointData()->AddArray(err);
  output->GetPointData()->SetNormals(normals);

  int dims[3];
  input->GetDimensions(dims);
  const double lowBytes = LowResolutionBytes(dims, this->Factor);
  vtkFieldData* fd = output->GetFieldData();
  AddField(fd, "points", static_cast<double>(n));
  AddField(fd, "point_bytes", static_cast<double>(result.PointBytes));
  AddField(fd, "underestimates", static_cast<double>(result.Underestimates));
  AddField(fd, "factor", static_cast<double>(result.Factor));
  AddField(fd, "generate_ms", result.GenerateMs);
  AddField(fd, "low_resolution_bytes", lowBytes);
  AddField(fd, "total_bytes", lowBytes + static_cast<double>(result.PointBytes));
  return 1;
}

void vtkHybridOctreePoints::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Factor: " << this->Factor << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "PointBudget: " << this->PointBudget << "\n";
  os << indent << "UnderestimatesOnly: " << this->UnderestimatesOnly << "\n";
  os << indent << "MaxOverestimate: " << this->MaxOverestimate << "\n";
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Component: " << this->Component << "\n";
}
