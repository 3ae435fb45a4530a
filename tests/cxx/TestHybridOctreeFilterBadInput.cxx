// vtkHybridOctreeFilter on bad input: every request fails with a message that
// says what is wrong, both outputs (boxes and surface) are empty, nothing
// crashes, and the filter works again on good input afterwards. Usage:
//   HybridOctreeCxxTests TestHybridOctreeFilterBadInput <scenario>
#include "HybridOctreeTestUtilities.h"

#include "vtkCellData.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkHybridOctreeFilter.h"
#include "vtkImageData.h"
#include "vtkLongLongArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>

namespace
{
/// A float image of `nx x ny x nz` points with point scalars "f" = i + j + k^2.
vtkSmartPointer<vtkImageData> MakeImage(int nx, int ny, int nz, int components = 1)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  vtkNew<vtkFloatArray> f;
  f->SetName("f");
  f->SetNumberOfComponents(components);
  f->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  for (vtkIdType id = 0; id < f->GetNumberOfTuples(); ++id)
  {
    int ijk[3] = { static_cast<int>(id % nx), static_cast<int>((id / nx) % ny),
      static_cast<int>(id / (static_cast<vtkIdType>(nx) * ny)) };
    for (int c = 0; c < components; ++c)
    {
      f->SetTypedComponent(id, c, static_cast<float>(ijk[0] + ijk[1] + ijk[2] * ijk[2] + c));
    }
  }
  image->GetPointData()->SetScalars(f);
  return image;
}

/// What the core says about a NaN or infinite isovalue.
const char* const ISOVALUE_ERROR = "must be a finite number (inside the data range";

struct Scenario
{
  /// Prepares the filter (input, settings) for the failing request.
  std::function<void(vtkHybridOctreeFilter*)> Setup;
  /// Text the error must contain.
  std::string Expected;
};

std::map<std::string, Scenario> Scenarios()
{
  std::map<std::string, Scenario> s;
  s["no_input"] = { [](vtkHybridOctreeFilter*) {}, "has 0 connections but is not optional" };
  s["wrong_type"] = { [](vtkHybridOctreeFilter* f) {
                       vtkNew<vtkPolyData> poly;
                       f->SetInputData(poly);
                     },
    "a vtkImageData is required" };
  s["no_scalars"] = { [](vtkHybridOctreeFilter* f) {
                       auto image = MakeImage(5, 5, 5);
                       image->GetPointData()->Initialize();
                       f->SetInputData(image);
                     },
    "has no point scalars" };
  s["cell_scalars"] = { [](vtkHybridOctreeFilter* f) {
                         auto image = MakeImage(5, 5, 5);
                         vtkNew<vtkFloatArray> c;
                         c->SetName("c");
                         c->SetNumberOfTuples(image->GetNumberOfCells());
                         c->FillValue(1.0f);
                         image->GetPointData()->Initialize();
                         image->GetCellData()->SetScalars(c);
                         f->SetInputData(image);
                       },
    "point scalars required; use Cell Data to Point Data" };
  s["multi_component"] = { [](vtkHybridOctreeFilter* f) { f->SetInputData(MakeImage(5, 5, 5, 3)); },
    "has 3 components; choose one" };
  s["component_out_of_range"] = { [](vtkHybridOctreeFilter* f) {
                                   f->SetInputData(MakeImage(5, 5, 5, 2));
                                   f->SetComponent(2);
                                 },
    "component 2 does not exist" };
  // NaN is no data; an infinity is an error naming the first one.
  s["infinity"] = { [](vtkHybridOctreeFilter* f) {
                     auto image = MakeImage(5, 5, 5);
                     auto* a = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
                     a->SetValue(7, std::numeric_limits<float>::quiet_NaN());
                     a->SetValue(9, std::numeric_limits<float>::infinity());
                     a->SetValue(11, -std::numeric_limits<float>::infinity());
                     f->SetInputData(image);
                   },
    "2 infinite sample(s), the first at point index 9" };
  s["all_nan"] = { [](vtkHybridOctreeFilter* f) {
                    auto image = MakeImage(5, 5, 5);
                    image->GetPointData()->GetScalars()->Fill(
                      std::numeric_limits<double>::quiet_NaN());
                    f->SetInputData(image);
                  },
    "no data: all 125 samples are NaN" };
  s["one_wide"] = { [](vtkHybridOctreeFilter* f) { f->SetInputData(MakeImage(6, 6, 1)); },
    "image dimensions 6x6x1 are too small" };
  s["empty"] = { [](vtkHybridOctreeFilter* f) {
                  vtkNew<vtkImageData> image;
                  image->SetExtent(0, -1, 0, -1, 0, -1);
                  vtkNew<vtkFloatArray> a;
                  a->SetName("f");
                  image->GetPointData()->SetScalars(a);
                  f->SetInputData(image);
                },
    "image dimensions 0x0x0 are too small" };
  s["unsupported_type"] = { [](vtkHybridOctreeFilter* f) {
                             auto image = MakeImage(5, 5, 5);
                             vtkNew<vtkLongLongArray> a;
                             a->SetName("big");
                             a->SetNumberOfTuples(125);
                             a->FillValue(3);
                             image->GetPointData()->SetScalars(a);
                             f->SetInputData(image);
                           },
    "has scalar type 'long long', which the Hybrid Octree does not read; cast it" };
  s["leaf_size"] = { [](vtkHybridOctreeFilter* f) {
                      f->SetInputData(MakeImage(9, 9, 9));
                      f->SetLeafSize(12);
                    },
    "leaf brick size 12 is not allowed: use a power of two" };
  s["infinity_after_success"] = { [](vtkHybridOctreeFilter* f) {
                                   auto image = MakeImage(9, 9, 9);
                                   f->SetInputData(image);
                                   f->Update(); // builds and caches an octree
                                   image->GetPointData()->GetScalars()->SetTuple1(
                                     3, std::numeric_limits<double>::infinity());
                                   image->GetPointData()->GetScalars()->Modified();
                                 },
    "infinite sample(s)" };
  s["nan_isovalue"] = { [](vtkHybridOctreeFilter* f) {
                         f->SetInputData(MakeImage(9, 9, 9));
                         f->SetIsovalue(std::numeric_limits<double>::quiet_NaN());
                       },
    std::string("isovalue NaN ") + ISOVALUE_ERROR };
  s["infinite_isovalue"] = { [](vtkHybridOctreeFilter* f) {
                              f->SetInputData(MakeImage(9, 9, 9));
                              f->SetSurfaceModeToInterpolated();
                              f->SetIsovalue(-std::numeric_limits<double>::infinity());
                            },
    std::string("isovalue -inf ") + ISOVALUE_ERROR };
  // The octree is cached and fine, only the surface fails: the boxes of the
  // previous request must not survive on port 0.
  s["nan_isovalue_after_success"] = { [](vtkHybridOctreeFilter* f) {
                                       f->SetInputData(MakeImage(9, 9, 9));
                                       f->SetIsovalue(20.0);
                                       f->Update();
                                       f->SetIsovalue(std::numeric_limits<double>::quiet_NaN());
                                     },
    ISOVALUE_ERROR };
  return s;
}
} // namespace

int TestHybridOctreeFilterBadInput(int argc, char* argv[])
{
  const std::string name = argc > 1 ? argv[1] : "";
  const std::map<std::string, Scenario> scenarios = Scenarios();
  auto found = scenarios.find(name);
  if (found == scenarios.end())
  {
    std::cerr << "unknown scenario '" << name << "'; known:";
    for (const auto& s : scenarios)
    {
      std::cerr << " " << s.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }

  Checker t;
  vtkNew<vtkHybridOctreeFilter> filter;
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  errors->Watch(filter->GetExecutive()); // pipeline errors (connections, data types)
  found->second.Setup(filter);
  errors->Clear();
  filter->Update();

  t.Check(errors->HasError(found->second.Expected),
    "expected an error containing \"" + found->second.Expected + "\"; got:\n" +
      errors->AllErrors());
  for (int port = 0; port < 2; ++port)
  {
    vtkPolyData* out = filter->GetOutput(port);
    const std::string what = "port " + std::to_string(port) + ": ";
    t.Check(out->GetNumberOfPoints() == 0 && out->GetNumberOfCells() == 0, what + "empty output");
    t.Check(out->GetFieldData()->GetNumberOfArrays() == 0, what + "no field data on failure");
  }

  // The filter recovers: good input and settings work on the same instance.
  errors->Clear();
  filter->SetLeafSize(4);
  filter->SetComponent(-1);
  filter->SetIsovalue(20.0);
  filter->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  filter->SetInputData(MakeImage(9, 9, 9));
  filter->Update();
  t.Check(errors->Errors.empty(), "good input after a failure works:\n" + errors->AllErrors());
  t.Check(filter->GetOutput(0)->GetNumberOfPoints() > 0, "boxes after recovery");
  t.Check(filter->GetOutput(1)->GetNumberOfPolys() > 0, "surface after recovery");
  std::cout << "scenario " << name << ": " << (t.Failures ? "failed" : "passed") << "\n";
  return t.Result();
}
