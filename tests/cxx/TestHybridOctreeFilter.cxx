// Scenarios of vtkHybridOctreeFilter on good input. Usage:
//   HybridOctreeCxxTests TestHybridOctreeFilter <wavelet|ramp|cache|array|nan_hole>
#include "HybridOctreeTestUtilities.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkHybridOctreeFilter.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

namespace
{
bool Near(double a, double b, double relative = 1e-9)
{
  return std::abs(a - b) <= relative * std::max({ 1.0, std::abs(a), std::abs(b) });
}

/// Checks the output contract shared by every scenario: 8 points and 12 lines
/// per box, consistent cell arrays, boxes inside the image that tile it.
void CheckBoxes(Checker& t, vtkPolyData* out, vtkImageData* image, double tolerance)
{
  const vtkIdType boxes = static_cast<vtkIdType>(FieldValue(out, "cut_count"));
  t.Check(boxes > 0, "the cut has boxes");
  t.Check(out->GetNumberOfPoints() == 8 * boxes, "8 points per box");
  t.Check(out->GetNumberOfLines() == 12 * boxes, "12 lines per box");
  t.Check(out->GetNumberOfCells() == 12 * boxes, "only lines");
  const char* names[] = { "node", "level", "nodal_error", "min", "max" };
  for (const char* name : names)
  {
    vtkDataArray* a = out->GetCellData()->GetArray(name);
    if (!t.Check(a && a->GetNumberOfTuples() == 12 * boxes, std::string("cell array ") + name))
    {
      return;
    }
  }
  vtkDataArray* node = out->GetCellData()->GetArray("node");
  vtkDataArray* level = out->GetCellData()->GetArray("level");
  vtkDataArray* error = out->GetCellData()->GetArray("nodal_error");
  vtkDataArray* mn = out->GetCellData()->GetArray("min");
  vtkDataArray* mx = out->GetCellData()->GetArray("max");
  const double vmin = FieldValue(out, "value_min");
  const double vmax = FieldValue(out, "value_max");
  const int levels = static_cast<int>(FieldValue(out, "levels"));

  double ib[6];
  image->GetBounds(ib);
  double volume = 0.0;
  double ub[6] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MIN, VTK_DOUBLE_MAX, VTK_DOUBLE_MIN, VTK_DOUBLE_MAX,
    VTK_DOUBLE_MIN };
  int badBoxes = 0;
  std::set<double> nodeIds;
  for (vtkIdType b = 0; b < boxes; ++b)
  {
    double lo[3], hi[3];
    out->GetPoint(8 * b, lo);
    out->GetPoint(8 * b + 7, hi);
    double v = 1.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      v *= hi[axis] - lo[axis];
      ub[2 * axis] = std::min(ub[2 * axis], lo[axis]);
      ub[2 * axis + 1] = std::max(ub[2 * axis + 1], hi[axis]);
      if (!(lo[axis] < hi[axis]) || lo[axis] < ib[2 * axis] - 1e-9 ||
        hi[axis] > ib[2 * axis + 1] + 1e-9)
      {
        ++badBoxes;
      }
    }
    volume += v;
    const vtkIdType cell = 12 * b;
    const double e = error->GetTuple1(cell);
    nodeIds.insert(node->GetTuple1(cell));
    if (node->GetTuple1(cell) < 0 || node->GetTuple1(cell + 11) != node->GetTuple1(cell) ||
      level->GetTuple1(cell) < 0 || level->GetTuple1(cell) >= levels || e < 0.0 || e > 1.0 ||
      mn->GetTuple1(cell) > mx->GetTuple1(cell) || mn->GetTuple1(cell) < vmin ||
      mx->GetTuple1(cell) > vmax)
    {
      ++badBoxes;
    }
    // A box above the tolerance must be a leaf brick (or homogeneous, error 0).
    if (e > tolerance && level->GetTuple1(cell) != levels - 1)
    {
      ++badBoxes;
    }
  }
  t.Check(badBoxes == 0, std::to_string(badBoxes) + " boxes break the output contract");
  t.Check(static_cast<vtkIdType>(nodeIds.size()) == boxes, "every box has its own node id");
  const double imageVolume = (ib[1] - ib[0]) * (ib[3] - ib[2]) * (ib[5] - ib[4]);
  t.Check(Near(volume, imageVolume),
    "box volumes sum to the image volume: " + std::to_string(volume) + " vs " +
      std::to_string(imageVolume));
  for (int i = 0; i < 6; ++i)
  {
    t.Check(Near(ub[i], ib[i]), "union of boxes has the image bounds, index " + std::to_string(i));
  }
}

int Wavelet()
{
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet; // 21^3 float samples, extent -10..10
  wavelet->SetWholeExtent(-10, 10, -10, 10, -10, 10);
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputConnection(wavelet->GetOutputPort());
  filter->SetLeafSize(4);
  filter->SetErrorTolerance(0.02);
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  filter->Update();
  t.Check(errors->Errors.empty(), "no error on the wavelet:\n" + errors->AllErrors());

  vtkImageData* image = wavelet->GetOutput();
  vtkPolyData* out = filter->GetOutput();
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  t.Check(FieldValue(out, "value_min") == range[0], "value_min is the array's minimum");
  t.Check(FieldValue(out, "value_max") == range[1], "value_max is the array's maximum");
  t.Check(FieldValue(out, "input_bytes") == 21 * 21 * 21 * 4, "input_bytes of 21^3 floats");
  t.Check(FieldValue(out, "leaf_size") == 4, "leaf_size");
  t.Check(FieldValue(out, "root_size") == 32, "20 cells pad to a 32-cell root");
  t.Check(FieldValue(out, "levels") == 4, "levels 32, 16, 8, 4");
  const double nodes = FieldValue(out, "node_count");
  const double terminal = FieldValue(out, "terminal_count");
  const double homogeneous = FieldValue(out, "homogeneous_count");
  t.Check(nodes >= terminal && terminal >= homogeneous && terminal >= 1, "node counts ordered");
  t.Check(FieldValue(out, "octree_bytes") > 0, "octree_bytes");
  t.Check(FieldValue(out, "build_ms") >= 0, "build_ms");
  t.Check(FieldValue(out, "cut_count") <= terminal, "a cut has at most the terminal count");
  CheckBoxes(t, out, image, 0.02);

  // At tolerance 0 the cut is the set of terminal nodes.
  filter->SetErrorTolerance(0.0);
  filter->Update();
  t.Check(FieldValue(out, "cut_count") == terminal, "cut at 0 = terminal nodes");
  CheckBoxes(t, out, image, 0.0);
  // At tolerance 1 every node qualifies: the root alone.
  filter->SetErrorTolerance(1.0);
  filter->Update();
  t.Check(FieldValue(out, "cut_count") == 1, "cut at 1 = the root");
  CheckBoxes(t, out, image, 1.0);
  return t.Result();
}

/// A double image with f = 2x + 3y - z on `n` points: trilinear, so every
/// node reproduces it exactly (e_0 = 0). Extent and origin are not at 0.
vtkSmartPointer<vtkImageData> MakeRamp(const int n[3])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(2, 2 + n[0] - 1, 0, n[1] - 1, -1, n[2] - 2);
  image->SetSpacing(0.5, 1.0, 2.0);
  image->SetOrigin(1.0, 2.0, 3.0);
  vtkNew<vtkDoubleArray> ramp;
  ramp->SetName("ramp");
  ramp->SetNumberOfTuples(static_cast<vtkIdType>(n[0]) * n[1] * n[2]);
  vtkIdType id = 0;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        ramp->SetValue(id++, 2.0 * i + 3.0 * j - k);
      }
    }
  }
  image->GetPointData()->SetScalars(ramp);
  return image;
}

int Ramp()
{
  Checker t;
  // A cube of 16 cells per axis: the root covers the grid exactly.
  const int cube[3] = { 17, 17, 17 };
  auto image = MakeRamp(cube);
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  filter->SetLeafSize(2);
  filter->SetErrorTolerance(0.0);
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  filter->Update();
  t.Check(errors->Errors.empty(), "no error on the ramp:\n" + errors->AllErrors());
  vtkPolyData* out = filter->GetOutput();
  t.Check(FieldValue(out, "cut_count") == 1, "a linear ramp is one box");
  t.Check(FieldValue(out, "homogeneous_count") == 1, "the root is homogeneous");
  t.Check(FieldValue(out, "node_count") == 1, "a homogeneous root is never refined");
  t.Check(FieldValue(out, "value_min") == -16.0, "ramp minimum");
  t.Check(FieldValue(out, "value_max") == 2.0 * 16 + 3.0 * 16, "ramp maximum");
  vtkDataArray* error = out->GetCellData()->GetArray("nodal_error");
  t.Check(error && error->GetTuple1(0) == 0.0, "the box has nodal error 0");
  vtkDataArray* level = out->GetCellData()->GetArray("level");
  t.Check(level && level->GetTuple1(0) == 0.0, "the box is the root");
  CheckBoxes(t, out, image, 0.0);
  double lo[3];
  out->GetPoint(0, lo);
  t.Check(Near(lo[0], 2.0) && Near(lo[1], 2.0) && Near(lo[2], 1.0),
    "the first corner is origin + extent min * spacing");

  // 16 x 8 x 4 cells: the padded root is clipped to the grid, so the cut has
  // several boxes, but every one is homogeneous with error 0.
  const int slab[3] = { 17, 9, 5 };
  auto flat = MakeRamp(slab);
  filter->SetInputData(flat);
  filter->Update();
  t.Check(errors->Errors.empty(), "no error on the flat ramp:\n" + errors->AllErrors());
  t.Check(FieldValue(out, "homogeneous_count") == FieldValue(out, "terminal_count"),
    "every terminal node of a ramp is homogeneous");
  error = out->GetCellData()->GetArray("nodal_error");
  t.Check(error && error->GetRange()[1] == 0.0, "every box has nodal error 0");
  CheckBoxes(t, out, flat, 0.0);
  return t.Result();
}

int Cache()
{
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 24, 0, 24, 0, 24);
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputConnection(wavelet->GetOutputPort());
  filter->SetLeafSize(8);
  filter->SetErrorTolerance(0.0);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  t.Check(filter->GetOctreeBuildCount() == 1, "first request builds");
  const double buildMs = FieldValue(out, "build_ms");
  const double fine = FieldValue(out, "cut_count");

  filter->SetErrorTolerance(0.3);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 1, "a tolerance change does not rebuild");
  t.Check(FieldValue(out, "build_ms") == buildMs, "build_ms unchanged: same octree");
  t.Check(FieldValue(out, "cut_count") < fine, "a larger tolerance gives a coarser cut");

  filter->SetErrorTolerance(0.0);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 1, "tolerance back: still no rebuild");
  t.Check(FieldValue(out, "cut_count") == fine, "same cut as before");

  filter->SetLeafSize(4);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 2, "a leaf size change rebuilds");
  t.Check(FieldValue(out, "leaf_size") == 4, "new leaf size");

  wavelet->SetMaximum(100.0);
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 3, "an input change rebuilds");

  filter->SetComponent(0); // 1-component array: component 0 is valid
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 4, "a component change rebuilds");

  filter->SetLeafSize(1000);
  t.Check(filter->GetLeafSize() == 256, "LeafSize is clamped to 256");
  filter->SetErrorTolerance(5.0);
  t.Check(filter->GetErrorTolerance() == 1.0, "ErrorTolerance is clamped to 1");
  filter->SetComponent(-7);
  t.Check(filter->GetComponent() == -1, "Component is clamped to -1");
  return t.Result();
}

int ArraySelection()
{
  Checker t;
  // Two point arrays: 2-component u16 "pair" (active scalars) and float "other".
  vtkNew<vtkImageData> image;
  image->SetDimensions(9, 9, 9);
  vtkNew<vtkUnsignedShortArray> pair;
  pair->SetName("pair");
  pair->SetNumberOfComponents(2);
  pair->SetNumberOfTuples(729);
  vtkNew<vtkFloatArray> other;
  other->SetName("other");
  other->SetNumberOfTuples(729);
  for (vtkIdType i = 0; i < 729; ++i)
  {
    pair->SetTypedComponent(i, 0, static_cast<unsigned short>(i % 7));
    pair->SetTypedComponent(i, 1, static_cast<unsigned short>(1000 + i));
    other->SetValue(i, -0.5f * static_cast<float>(i % 11));
  }
  image->GetPointData()->SetScalars(pair);
  image->GetPointData()->AddArray(other);

  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  filter->SetLeafSize(4);
  filter->SetComponent(1);
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  t.Check(errors->Errors.empty(), "component 1 builds:\n" + errors->AllErrors());
  t.Check(FieldValue(out, "value_min") == 1000 && FieldValue(out, "value_max") == 1728,
    "range of component 1");
  t.Check(FieldValue(out, "input_bytes") == 729 * 2, "input_bytes count one u16 component");
  filter->SetComponent(0);
  filter->Update();
  t.Check(
    FieldValue(out, "value_min") == 0 && FieldValue(out, "value_max") == 6, "range of component 0");

  filter->SetComponent(-1);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "other");
  filter->Update();
  t.Check(errors->Errors.empty(), "array 'other' builds:\n" + errors->AllErrors());
  t.Check(FieldValue(out, "value_min") == -5.0 && FieldValue(out, "value_max") == 0.0,
    "range of array 'other'");
  CheckBoxes(t, out, image, filter->GetErrorTolerance());
  return t.Result();
}
/// NaN is no data: a wavelet with a NaN ball and a NaN slab on a face builds
/// without a message; the field data counts the NaN samples, the value range
/// leaves them out, every box's range is ordered or NaN (a box of NaN only),
/// and the isosurface has finite points only.
int NanHole()
{
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet; // 21^3 float samples, extent -10..10
  wavelet->SetWholeExtent(-10, 10, -10, 10, -10, 10);
  wavelet->Update();
  vtkNew<vtkImageData> image;
  image->DeepCopy(wavelet->GetOutput());
  vtkDataArray* values = image->GetPointData()->GetScalars();
  vtkIdType nan = 0;
  double range[2] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MIN };
  for (vtkIdType id = 0; id < values->GetNumberOfTuples(); ++id)
  {
    const int x = static_cast<int>(id % 21) - 10;
    const int y = static_cast<int>(id / 21 % 21) - 10;
    const int z = static_cast<int>(id / 441) - 10;
    if (x < -8 || (x - 3) * (x - 3) + y * y + z * z <= 16)
    {
      values->SetComponent(id, 0, std::numeric_limits<double>::quiet_NaN());
      ++nan;
      continue;
    }
    range[0] = std::min(range[0], values->GetComponent(id, 0));
    range[1] = std::max(range[1], values->GetComponent(id, 0));
  }
  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  filter->SetLeafSize(4);
  filter->SetIsovalue(0.5 * (range[0] + range[1]));
  vtkNew<ErrorRecorder> errors;
  errors->Watch(filter);
  filter->Update();
  t.Check(errors->Errors.empty(), "NaN is no data, not an error:\n" + errors->AllErrors());
  vtkPolyData* boxes = filter->GetOutput(0);
  t.Check(FieldValue(boxes, "nan_samples") == static_cast<double>(nan),
    "nan_samples counts " + std::to_string(nan));
  t.Check(FieldValue(boxes, "value_min") == range[0] && FieldValue(boxes, "value_max") == range[1],
    "the value range leaves NaN out");
  vtkDataArray* lo = boxes->GetCellData()->GetArray("min");
  vtkDataArray* hi = boxes->GetCellData()->GetArray("max");
  bool ordered = lo && hi;
  for (vtkIdType c = 0; ordered && c < lo->GetNumberOfTuples(); ++c)
  {
    const double a = lo->GetTuple1(c), b = hi->GetTuple1(c);
    ordered = (std::isnan(a) && std::isnan(b)) || a <= b;
  }
  t.Check(ordered, "every box's range is ordered, or NaN for a box of NaN only");
  vtkPolyData* surface = filter->GetOutput(1);
  t.Check(surface->GetNumberOfPolys() > 50, "the isosurface around the hole");
  bool finite = true;
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    const double* x = surface->GetPoint(p);
    finite = finite && std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
  }
  t.Check(finite, "finite surface points");
  return t.Result();
}
} // namespace

int TestHybridOctreeFilter(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  if (scenario == "wavelet")
  {
    return Wavelet();
  }
  if (scenario == "ramp")
  {
    return Ramp();
  }
  if (scenario == "cache")
  {
    return Cache();
  }
  if (scenario == "array")
  {
    return ArraySelection();
  }
  if (scenario == "nan_hole")
  {
    return NanHole();
  }
  std::cerr << "unknown scenario '" << scenario
            << "': use wavelet, ramp, cache, array or nan_hole\n";
  return EXIT_FAILURE;
}
