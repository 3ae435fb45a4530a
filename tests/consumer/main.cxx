// Builds the Volume Octree of a small image through the installed package and
// checks the cut and the isosurface; exits non-zero on any mismatch.
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkHybridOctreeFilter.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <iostream>

int main()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(17, 17, 17);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(17 * 17 * 17);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const int x = static_cast<int>(i % 17) - 8, y = static_cast<int>((i / 17) % 17) - 8,
              z = static_cast<int>(i / 289) - 8;
    values->SetValue(i, static_cast<float>(x * x + y * y + z * z));
  }
  image->GetPointData()->SetScalars(values);

  vtkNew<vtkHybridOctreeFilter> filter;
  filter->SetInputData(image);
  filter->SetLeafSize(4);
  filter->SetErrorTolerance(0.0);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* cut = out->GetFieldData()->GetArray("cut_count");
  vtkDataArray* levels = out->GetFieldData()->GetArray("levels");
  if (!cut || !levels)
  {
    std::cerr << "field data missing: the filter failed\n";
    return 1;
  }
  // 16 cells, leaf bricks of 4: levels 16, 8, 4; the quadratic is nowhere
  // trilinear, so the cut at tolerance 0 is the 64 leaf bricks.
  if (levels->GetTuple1(0) != 3 || cut->GetTuple1(0) != 64 || out->GetNumberOfPoints() != 8 * 64)
  {
    std::cerr << "unexpected cut: levels " << levels->GetTuple1(0) << ", boxes "
              << cut->GetTuple1(0) << "\n";
    return 1;
  }

  // The next Update() rebuilds both outputs (their field data included), so
  // keep the number, not the array.
  const double boxCount = cut->GetTuple1(0);

  // The isosurface x^2 + y^2 + z^2 = 40: a closed sphere of radius 6.3.
  filter->SetIsovalue(40.0);
  filter->Update();
  vtkPolyData* surface = filter->GetOutput(1);
  vtkDataArray* polygons = surface->GetFieldData()->GetArray("polygons");
  vtkDataArray* boundary = surface->GetFieldData()->GetArray("boundary_edges");
  if (!polygons || !boundary || polygons->GetTuple1(0) <= 0 ||
    surface->GetNumberOfPolys() != polygons->GetTuple1(0) || boundary->GetTuple1(0) != 0)
  {
    std::cerr << "unexpected surface: " << surface->GetNumberOfPolys() << " polygons\n";
    return 1;
  }
  std::cout << "consumer OK: " << boxCount << " boxes, " << polygons->GetTuple1(0)
            << " surface polygons\n";
  return 0;
}
