/**
 * @file   TestHybridOctreeDepthImage.cxx
 * @brief  vtkHybridOctreeDepthImage: front to back equals back to front.
 *
 *   HybridOctreeCxxTests TestHybridOctreeDepthImage <scenario>
 *
 * same_depth: on a 64^3 wavelet thresholded at 150, for the paper's four
 *   view plane normals, the FRONT_TO_BACK and BACK_TO_FRONT outputs are
 *   identical (depth bits, face, shaded), the object is seen, FTB
 *   scan-converts fewer faces and the field data are there.
 * bad_input: a (0, 0, 0) view plane normal, an image without point scalars
 *   and a NaN isovalue each fail with a clear error and an empty output; the
 *   same filter then works again.
 */
#include "HybridOctreeTestUtilities.h"

#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkHybridOctreeDepthImage.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace
{
double Field(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::nan("");
}

bool SameBits(vtkFloatArray* a, vtkFloatArray* b)
{
  return a && b && a->GetNumberOfValues() == b->GetNumberOfValues() &&
    std::memcmp(a->GetPointer(0), b->GetPointer(0), sizeof(float) * a->GetNumberOfValues()) == 0;
}
}

int TestHybridOctreeDepthImage(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 63, 0, 63, 0, 63);
  vtkNew<vtkHybridOctreeDepthImage> ftb;
  ftb->SetInputConnection(wavelet->GetOutputPort());
  ftb->SetIsovalue(150.0);
  ftb->SetImageSize(96);
  vtkNew<vtkHybridOctreeDepthImage> btf;
  btf->SetInputConnection(wavelet->GetOutputPort());
  btf->SetIsovalue(150.0);
  btf->SetImageSize(96);
  btf->SetMethod(vtkHybridOctreeDepthImage::BACK_TO_FRONT);

  if (scenario == "same_depth")
  {
    const double vpns[4][3] = { { 1, -2, 1 }, { -1, -2, 1 }, { 1, -1, 0 }, { 0, -1, 0 } };
    for (const auto& vpn : vpns)
    {
      const std::string v = "vpn (" + std::to_string(vpn[0]) + ", " + std::to_string(vpn[1]) +
        ", " + std::to_string(vpn[2]) + "): ";
      ftb->SetViewPlaneNormal(vpn[0], vpn[1], vpn[2]);
      btf->SetViewPlaneNormal(vpn[0], vpn[1], vpn[2]);
      ftb->Update();
      btf->Update();
      vtkImageData* f = ftb->GetOutput();
      vtkImageData* b = btf->GetOutput();
      int dims[3];
      f->GetDimensions(dims);
      t.Check(dims[0] == 96 && dims[1] == 96 && dims[2] == 1, v + "a 96 x 96 image");
      auto* fd = vtkFloatArray::SafeDownCast(f->GetPointData()->GetArray("depth"));
      auto* bd = vtkFloatArray::SafeDownCast(b->GetPointData()->GetArray("depth"));
      t.Check(SameBits(fd, bd), v + "the same depth, bit for bit");
      auto* ff = vtkUnsignedCharArray::SafeDownCast(f->GetPointData()->GetArray("face"));
      auto* bf = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetArray("face"));
      t.Check(
        ff && bf && std::memcmp(ff->GetPointer(0), bf->GetPointer(0), ff->GetNumberOfValues()) == 0,
        v + "the same faces");
      vtkIdType seen = 0;
      for (vtkIdType i = 0; fd && i < fd->GetNumberOfValues(); ++i)
      {
        seen += std::isnan(fd->GetValue(i)) ? 0 : 1;
      }
      t.Check(seen > 500, v + "the object is seen: " + std::to_string(seen) + " pixels");
      t.Check(Field(f, "faces") < Field(b, "faces"),
        v + "FTB scan-converts fewer faces: " + std::to_string(Field(f, "faces")) + " vs " +
          std::to_string(Field(b, "faces")));
      t.Check(Field(f, "bitmap_bytes") > 0 && Field(b, "bitmap_bytes") == 0, v + "bitmap bytes");
      t.Check(f->GetPointData()->GetArray("shaded") &&
          f->GetPointData()->GetArray("shaded")->GetNumberOfComponents() == 3,
        v + "an RGB shaded picture");
    }
    return t.Result();
  }
  if (scenario == "bad_input")
  {
    vtkNew<ErrorRecorder> errors;
    errors->Watch(ftb);
    errors->Watch(ftb->GetExecutive());
    ftb->SetViewPlaneNormal(0, 0, 0);
    ftb->Update();
    t.Check(errors->HasError("(0, 0, 0)"), "zero VPN: clear error\n" + errors->AllErrors());
    t.Check(ftb->GetOutput()->GetNumberOfPoints() == 0, "zero VPN: empty output");
    errors->Clear();
    ftb->SetViewPlaneNormal(1, 1, 1);
    ftb->SetIsovalue(std::numeric_limits<double>::quiet_NaN());
    ftb->Update();
    t.Check(errors->HasError("not a finite"), "NaN isovalue: clear error\n" + errors->AllErrors());
    errors->Clear();
    vtkNew<vtkImageData> empty;
    empty->SetDimensions(4, 4, 4);
    vtkNew<vtkHybridOctreeDepthImage> noScalars;
    errors->Watch(noScalars);
    noScalars->SetInputData(empty);
    noScalars->Update();
    t.Check(
      errors->HasError("no point scalars"), "no scalars: clear error\n" + errors->AllErrors());
    errors->Clear();
    ftb->SetIsovalue(150.0);
    ftb->Update();
    t.Check(errors->Errors.empty(), "good settings work again\n" + errors->AllErrors());
    t.Check(ftb->GetOutput()->GetNumberOfPoints() == 96 * 96, "an image again");
    return t.Result();
  }
  std::cerr << "unknown scenario '" << scenario << "'; known: same_depth bad_input\n";
  return EXIT_FAILURE;
}
