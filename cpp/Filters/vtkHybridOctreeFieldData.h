/**
 * @file   vtkHybridOctreeFieldData.h
 * @brief  One-value field-data arrays, the filters' statistics (private to the module).
 */
#ifndef vtkHybridOctreeFieldData_h
#define vtkHybridOctreeFieldData_h

#include "vtkFieldData.h"
#include "vtkNew.h"

namespace vtkHybridOctreeFieldData
{
/// Adds to `fieldData` an `ArrayT` named `name` holding the one value `value`.
template <typename ArrayT, typename ValueT>
void AddValue(vtkFieldData* fieldData, const char* name, ValueT value)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfTuples(1);
  array->SetValue(0, static_cast<typename ArrayT::ValueType>(value));
  fieldData->AddArray(array);
}
}

#endif
