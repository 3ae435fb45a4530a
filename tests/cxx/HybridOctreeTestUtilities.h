/**
 * @file   HybridOctreeTestUtilities.h
 * @brief  Helpers shared by the CTest executables of tests/cxx.
 */
#ifndef HybridOctreeTestUtilities_h
#define HybridOctreeTestUtilities_h

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkObject.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

/// Records the text of every ErrorEvent (and WarningEvent) it observes.
class ErrorRecorder : public vtkCommand
{
public:
  static ErrorRecorder* New() { return new ErrorRecorder; }

  void Execute(vtkObject* vtkNotUsed(caller), unsigned long event, void* callData) override
  {
    const std::string text = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(text);
  }

  /// Observes errors and warnings of `object`.
  void Watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }

  bool HasError(const std::string& fragment) const
  {
    for (const std::string& e : this->Errors)
    {
      if (e.find(fragment) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }

  std::string AllErrors() const
  {
    std::string all;
    for (const std::string& e : this->Errors)
    {
      all += "  [" + e + "]\n";
    }
    return all.empty() ? "  (none)\n" : all;
  }

  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }

  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

/// Counts failed checks; `Check(cond, what)` prints `what` on failure.
struct Checker
{
  int Failures = 0;

  bool Check(bool condition, const std::string& what)
  {
    if (!condition)
    {
      ++this->Failures;
      std::cerr << "FAILED: " << what << "\n";
    }
    return condition;
  }

  int Result() const
  {
    if (this->Failures)
    {
      std::cerr << this->Failures << " check(s) failed\n";
    }
    return this->Failures ? EXIT_FAILURE : EXIT_SUCCESS;
  }
};

/// The one value of field data array `name`, or NaN when it is missing.
inline double FieldValue(vtkPolyData* output, const char* name)
{
  vtkDataArray* array = output->GetFieldData()->GetArray(name);
  if (!array || array->GetNumberOfTuples() != 1)
  {
    std::cerr << "field data array '" << name << "' is missing\n";
    return std::nan("");
  }
  return array->GetTuple1(0);
}

/// The largest file under `folder` other than zarr.json: a store level's
/// shard holding data (for the tests that damage one).
inline std::filesystem::path LargestFile(const std::filesystem::path& folder)
{
  std::filesystem::path best;
  std::uintmax_t size = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
  {
    if (entry.is_regular_file() && entry.path().filename() != "zarr.json" &&
      entry.file_size() > size)
    {
      size = entry.file_size();
      best = entry.path();
    }
  }
  return best;
}

#endif
