#include "vtkHybridOctreeZarrReader.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeFieldData.h"
#include "vtkHybridOctreeStoreFieldData.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <filesystem>
#include <string>
#include <system_error>

vtkStandardNewMacro(vtkHybridOctreeZarrReader);

struct vtkHybridOctreeZarrReader::vtkInternals
{
  std::unique_ptr<vtkHybridOctreeBridge::OmeZarrStore> Store;
};

namespace
{
using vtkHybridOctreeBridge::ScalarType;

/// The VTK type code of the store's scalar type.
int ToVtkType(ScalarType type)
{
  switch (type)
  {
    case ScalarType::U8:
      return VTK_UNSIGNED_CHAR;
    case ScalarType::I8:
      return VTK_SIGNED_CHAR;
    case ScalarType::U16:
      return VTK_UNSIGNED_SHORT;
    case ScalarType::I16:
      return VTK_SHORT;
    case ScalarType::U32:
      return VTK_UNSIGNED_INT;
    case ScalarType::I32:
      return VTK_INT;
    case ScalarType::F64:
      return VTK_DOUBLE;
    default:
      return VTK_FLOAT;
  }
}
}

vtkHybridOctreeZarrReader::vtkHybridOctreeZarrReader()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
}

vtkHybridOctreeZarrReader::~vtkHybridOctreeZarrReader()
{
  this->SetFileName(nullptr);
}

int vtkHybridOctreeZarrReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  std::error_code ec;
  const std::filesystem::path folder(name);
  return std::filesystem::is_directory(folder, ec) &&
      (std::filesystem::exists(folder / "zarr.json", ec) ||
        std::filesystem::exists(folder / ".zattrs", ec))
    ? 1
    : 0;
}

bool vtkHybridOctreeZarrReader::OpenStore()
{
  this->Internals->Store.reset();
  this->Level = -1;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("no FileName: give the OME-Zarr image's folder (e.g. image.ome.zarr)");
    return false;
  }
  std::string error;
  this->Internals->Store = vtkHybridOctreeBridge::OmeZarrStore::Open(this->FileName, error);
  vtkHybridOctreeBridge::StoreSummary summary;
  if (!this->Internals->Store || !this->Internals->Store->GetSummary(summary, error))
  {
    this->Internals->Store.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  if (!summary.Warnings.empty())
  {
    vtkWarningMacro(<< summary.Warnings);
  }
  const double limit = this->MaximumMegabytes * 1.0e6;
  const double sampleBytes = vtkDataArray::GetDataTypeSize(ToVtkType(summary.Type));
  for (std::size_t p = 0; p < summary.Levels && 3 * p + 2 < summary.LevelDims.size(); ++p)
  {
    const std::size_t* m = &summary.LevelDims[3 * p];
    if (static_cast<double>(m[0]) * static_cast<double>(m[1]) * static_cast<double>(m[2]) *
        sampleBytes <=
      limit)
    {
      this->Level = static_cast<int>(p);
      return true;
    }
  }
  const std::size_t* coarsest = &summary.LevelDims[summary.LevelDims.size() - 3];
  vtkErrorMacro("no level of '" << this->FileName << "' fits MaximumMegabytes "
                                << this->MaximumMegabytes << ": the coarsest has " << coarsest[0]
                                << " x " << coarsest[1] << " x " << coarsest[2]
                                << " samples; raise MaximumMegabytes");
  this->Internals->Store.reset();
  return false;
}

int vtkHybridOctreeZarrReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->OpenStore())
  {
    return 0;
  }
  vtkHybridOctreeBridge::StoreSummary summary;
  std::string error;
  if (!this->Internals->Store->GetSummary(summary, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::size_t* m = &summary.LevelDims[3 * static_cast<std::size_t>(this->Level)];
  const double stride = static_cast<double>(1ULL << this->Level);
  int extent[6];
  double spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = 0;
    extent[2 * a + 1] = static_cast<int>(m[a]) - 1;
    spacing[a] = summary.Spacing[a] * stride;
  }
  vtkInformation* info = outputVector->GetInformationObject(0);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  info->Set(vtkDataObject::SPACING(), spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), summary.Origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, ToVtkType(summary.Type), 1);
  return 1;
}

int vtkHybridOctreeZarrReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!output)
  {
    vtkErrorMacro("the output is not a vtkImageData");
    return 0;
  }
  output->Initialize();
  if (!this->Internals->Store && !this->OpenStore())
  {
    return 0;
  }
  vtkHybridOctreeBridge::StoreSummary summary;
  std::string error;
  if (!this->Internals->Store->GetSummary(summary, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::size_t level = static_cast<std::size_t>(this->Level);
  const std::size_t* m = &summary.LevelDims[3 * level];
  const double stride = static_cast<double>(1ULL << level);
  const std::size_t lo[3] = { 0, 0, 0 };
  const std::size_t hi[3] = { m[0] - 1, m[1] - 1, m[2] - 1 };
  vtkSmartPointer<vtkDataArray> scalars =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(ToVtkType(summary.Type)));
  scalars->SetName(summary.Name.c_str());
  scalars->SetNumberOfComponents(1);
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(m[0] * m[1] * m[2]));
  const std::size_t bytes =
    m[0] * m[1] * m[2] * static_cast<std::size_t>(scalars->GetDataTypeSize());
  if (!this->Internals->Store->ReadLevel(level, lo, hi, scalars->GetVoidPointer(0), bytes, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  output->SetExtent(
    0, static_cast<int>(m[0]) - 1, 0, static_cast<int>(m[1]) - 1, 0, static_cast<int>(m[2]) - 1);
  output->SetSpacing(
    summary.Spacing[0] * stride, summary.Spacing[1] * stride, summary.Spacing[2] * stride);
  output->SetOrigin(summary.Origin);
  output->GetPointData()->SetScalars(scalars);
  vtkHybridOctreeStoreFieldData::StoreReference store;
  store.Path = this->FileName;
  for (int a = 0; a < 3; ++a)
  {
    store.Dims[a] = static_cast<double>(summary.Dims[a]);
    store.Spacing[a] = summary.Spacing[a];
    store.Origin[a] = summary.Origin[a];
  }
  vtkHybridOctreeStoreFieldData::Add(output->GetFieldData(), store);
  vtkHybridOctreeFieldData::AddValue<vtkIntArray>(
    output->GetFieldData(), "HybridOctreeStoreLevel", this->Level);
  vtkHybridOctreeFieldData::AddValue<vtkIntArray>(
    output->GetFieldData(), "HybridOctreeStoreLevels", summary.Levels);
  return 1;
}

void vtkHybridOctreeZarrReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "MaximumMegabytes: " << this->MaximumMegabytes << "\n";
  os << indent << "Level: " << this->Level << "\n";
}
