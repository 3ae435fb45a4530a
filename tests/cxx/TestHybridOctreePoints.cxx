/**
 * @file   TestHybridOctreePoints.cxx
 * @brief  vtkHybridOctreePoints: the error points of a low-resolution image.
 *
 *   HybridOctreeCxxTests TestHybridOctreePoints <scenario>
 *
 * wavelet: on a 65^3 wavelet with extent -32..32 (so index and position
 *   differ), factor 4, threshold 0.05: there are points; each sits on a
 *   sample of the input and carries its value (within the 8-bit quantisation,
 *   range / 510) and an |error| above the threshold; Normals are unit
 *   vectors; the field data add up (total = low resolution + points, 6 bytes
 *   a point); Underestimates Only keeps only positive errors; a budget gives
 *   exactly that many points; File Name writes 72 + 6 n bytes.
 * bad_input: factor 3, threshold 2, an image without scalars and a file in
 *   a folder that does not exist each fail with a clear error and an empty
 *   output; the same filter then works again.
 */
#include "HybridOctreeTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkHybridOctreePoints.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

int TestHybridOctreePoints(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-32, 32, -32, 32, -32, 32);
  wavelet->Update();
  vtkImageData* image = wavelet->GetOutput();
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  const double span = range[1] - range[0];
  vtkNew<vtkHybridOctreePoints> points;
  points->SetInputConnection(wavelet->GetOutputPort());
  points->SetFactor(4);
  points->SetThreshold(0.05);

  if (scenario == "wavelet")
  {
    points->Update();
    vtkPolyData* out = points->GetOutput();
    const vtkIdType n = out->GetNumberOfPoints();
    t.Check(n > 100, "points: " + std::to_string(n));
    t.Check(out->GetNumberOfVerts() == n, "one vertex per point");
    vtkDataArray* value = out->GetPointData()->GetScalars();
    vtkDataArray* error = out->GetPointData()->GetArray("error");
    vtkDataArray* normals = out->GetPointData()->GetNormals();
    t.Check(value && error && normals, "value, error and Normals arrays");
    if (!value || !error || !normals)
    {
      return t.Result();
    }
    int off = 0, far = 0, small = 0, notUnit = 0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      const vtkIdType id = image->FindPoint(p);
      double q[3];
      image->GetPoint(id, q);
      off +=
        (id < 0 || std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > 1e-9);
      const double v = image->GetPointData()->GetScalars()->GetTuple1(id);
      far += std::abs(value->GetTuple1(i) - v) > span / 510.0 + 1e-3;
      small += std::abs(error->GetTuple1(i)) < 0.05 * span * 0.9;
      const double* nv = normals->GetTuple3(i);
      notUnit += std::abs(std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]) - 1.0) > 1e-5;
    }
    t.Check(off == 0, std::to_string(off) + " points off the input's samples");
    t.Check(far == 0, std::to_string(far) + " values differ from the input's");
    t.Check(small == 0, std::to_string(small) + " errors below the threshold");
    t.Check(notUnit == 0, std::to_string(notUnit) + " normals not unit");
    t.Check(FieldValue(out, "points") == n, "field data: points");
    t.Check(FieldValue(out, "point_bytes") == 6.0 * n, "6 bytes a point");
    t.Check(
      FieldValue(out, "low_resolution_bytes") == 4.0 * 17 * 17 * 17, "17^3 texels of 4 bytes");
    t.Check(FieldValue(out, "total_bytes") ==
        FieldValue(out, "low_resolution_bytes") + FieldValue(out, "point_bytes"),
      "total = low resolution + points");

    points->UnderestimatesOnlyOn();
    points->Update();
    vtkDataArray* e = points->GetOutput()->GetPointData()->GetArray("error");
    int negative = 0;
    for (vtkIdType i = 0; e && i < e->GetNumberOfTuples(); ++i)
    {
      negative += e->GetTuple1(i) <= 0.0;
    }
    t.Check(e && e->GetNumberOfTuples() > 0 && negative == 0, "underestimates only");
    t.Check(points->GetOutput()->GetNumberOfPoints() < n, "fewer points");
    points->UnderestimatesOnlyOff();

    points->SetPointBudget(250);
    const std::string file = "hybrid-octree-test-points.hop";
    points->SetFileName(file);
    points->Update();
    t.Check(points->GetOutput()->GetNumberOfPoints() == 250, "a budget of 250 points");
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    t.Check(in && static_cast<long>(in.tellg()) == 72 + 6 * 250, "the point file: 72 + 6 n bytes");
    in.close();
    std::remove(file.c_str());
    return t.Result();
  }
  if (scenario == "bad_input")
  {
    vtkNew<ErrorRecorder> errors;
    errors->Watch(points);
    errors->Watch(points->GetExecutive());
    points->SetFactor(3);
    points->Update();
    t.Check(errors->HasError("factor 3"), "factor 3: clear error\n" + errors->AllErrors());
    t.Check(points->GetOutput()->GetNumberOfPoints() == 0, "factor 3: empty output");
    errors->Clear();
    points->SetFactor(2);
    points->SetThreshold(2.0);
    points->Update();
    t.Check(errors->HasError("threshold 2"), "threshold 2: clear error\n" + errors->AllErrors());
    errors->Clear();
    points->SetThreshold(0.1);
    points->SetFileName("/nonexistent-folder/points.hop");
    points->Update();
    t.Check(errors->HasError("/nonexistent-folder/points.hop"),
      "unwritable file: clear error\n" + errors->AllErrors());
    t.Check(points->GetOutput()->GetNumberOfPoints() == 0, "unwritable file: empty output");
    errors->Clear();
    vtkNew<vtkImageData> empty;
    empty->SetDimensions(8, 8, 8);
    vtkNew<vtkHybridOctreePoints> noScalars;
    errors->Watch(noScalars);
    errors->Watch(noScalars->GetExecutive());
    noScalars->SetInputData(empty);
    noScalars->Update();
    t.Check(
      errors->HasError("no point scalars"), "no scalars: clear error\n" + errors->AllErrors());
    errors->Clear();
    points->SetFileName("");
    points->SetFactor(4);
    points->SetThreshold(0.05);
    points->Update();
    t.Check(errors->Errors.empty(), "good settings work again\n" + errors->AllErrors());
    t.Check(points->GetOutput()->GetNumberOfPoints() > 0, "points again");
    return t.Result();
  }
  std::cerr << "unknown scenario '" << scenario << "'; known: wavelet bad_input\n";
  return EXIT_FAILURE;
}
