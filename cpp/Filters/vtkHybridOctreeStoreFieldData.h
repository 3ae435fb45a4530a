/**
 * @file   vtkHybridOctreeStoreFieldData.h
 * @brief  The field data naming the volume on disk a light image stands for.
 *
 * vtkHybridOctreeZarrReader writes it into its output (a coarse level of an
 * OME-Zarr image); vtkHybridOctreeVolumeMapper reads it and draws the full
 * resolution from the store instead of the image's own samples. Four
 * arrays: the store's folder (a string) and the full resolution's samples
 * per axis, spacing and origin (3 values each).
 */
#ifndef vtkHybridOctreeStoreFieldData_h
#define vtkHybridOctreeStoreFieldData_h

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include <string>

namespace vtkHybridOctreeStoreFieldData
{
/// The arrays' names.
constexpr const char* PathName = "HybridOctreeStorePath";
constexpr const char* DimsName = "HybridOctreeStoreDimensions";
constexpr const char* SpacingName = "HybridOctreeStoreSpacing";
constexpr const char* OriginName = "HybridOctreeStoreOrigin";

/// A store as the field data names it: its folder and full resolution.
struct StoreReference
{
  std::string Path;
  double Dims[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
};

/// Adds `store`'s four arrays to `fieldData` (replacing any of those names).
inline void Add(vtkFieldData* fieldData, const StoreReference& store)
{
  vtkNew<vtkStringArray> path;
  path->SetName(PathName);
  path->InsertNextValue(store.Path);
  fieldData->AddArray(path);
  const char* names[3] = { DimsName, SpacingName, OriginName };
  const double* values[3] = { store.Dims, store.Spacing, store.Origin };
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(names[i]);
    array->SetNumberOfTuples(3);
    for (int a = 0; a < 3; ++a)
    {
      array->SetValue(a, values[i][a]);
    }
    fieldData->AddArray(array);
  }
}

/// True, and `store` filled, when `fieldData` names a store (all four
/// arrays present, a non-empty path, three values each).
inline bool Find(vtkFieldData* fieldData, StoreReference& store)
{
  if (!fieldData)
  {
    return false;
  }
  vtkStringArray* path = vtkStringArray::SafeDownCast(fieldData->GetAbstractArray(PathName));
  if (!path || path->GetNumberOfValues() < 1 || path->GetValue(0).empty())
  {
    return false;
  }
  const char* names[3] = { DimsName, SpacingName, OriginName };
  double* values[3] = { store.Dims, store.Spacing, store.Origin };
  for (int i = 0; i < 3; ++i)
  {
    vtkDataArray* array = fieldData->GetArray(names[i]);
    if (!array || array->GetNumberOfValues() != 3)
    {
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      values[i][a] = array->GetComponent(a, 0);
    }
  }
  store.Path = path->GetValue(0);
  return true;
}
}

#endif
