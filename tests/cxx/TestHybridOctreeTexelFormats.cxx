/**
 * Texel formats (vtkHybridOctreeVolumeMapper::SetTexelFormat) drawn under
 * Xvfb. The image: the wavelet (vtkRTAnalyticSource, 65^3) as floats, or
 * mapped linearly onto 0..255 (unsigned char) or 0..65535 (unsigned short);
 * the Scene's colours and opacity over its range. Metric: RMSE of the RGB
 * channels in [0, 1] over the 256x256 window.
 *
 *   r8:        8-bit data, TexelFormat Auto: R8 textures. At a budget
 *              holding the volume: 1 byte a texel (texture bytes at most
 *              1.1 x 65^3, a quarter of Float32's), no estimated error, the
 *              Float32 picture (RMSE < 0.002; measured 0.0011, the
 *              filtering of 8-bit texels), and within 0.03 of
 *              vtkGPUVolumeRayCastMapper (which uploads R8 too; measured
 *              0.0032). A budget under the full volume (a coarse stride): GL
 *              within 0.005 of the CPU compositor on the same DrawList,
 *              which reads the same codes (measured 0.0017).
 *   r16:       16-bit data, Auto: R16, 2 bytes a texel, the Float32 picture
 *              (measured 0.00001); GL within 0.005 of the CPU compositor at
 *              a coarse stride (measured 0.0015).
 *   quantized: float data in Unorm8 and Float16: at a budget holding the
 *              volume, the picture within 0.02 (Unorm8) and 0.005 (Float16)
 *              of the Float32 one (measured 0.0011, 0.0003), the estimated
 *              error the quantization error (above 0, below 0.002 of the
 *              range: 1/510 and 2^-12) and a quarter / half of the bytes;
 *              under a smaller budget (a coarse stride) GL within 0.005 of the
 *              CPU compositor.
 *   nan_unorm: float data with a NaN sample in Unorm8: the render fails with
 *              an error naming the NaN samples and the formats that hold
 *              them; Float16 then draws it.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// The Scene with its wavelet replaced by `levels`-level integers (255: unsigned
/// char, 65535: unsigned short) or by floats with a NaN (levels 0).
struct FormatScene : Scene
{
  vtkNew<vtkImageData> Image;

  FormatScene(vtkVolumeMapper* mapper, int levels)
    : Scene(mapper)
  {
    vtkImageData* w = this->Wavelet->GetOutput();
    vtkDataArray* values = w->GetPointData()->GetScalars();
    this->Image->CopyStructure(w);
    vtkSmartPointer<vtkDataArray> out;
    if (levels == 255)
    {
      out = vtkSmartPointer<vtkUnsignedCharArray>::New();
    }
    else if (levels == 65535)
    {
      out = vtkSmartPointer<vtkUnsignedShortArray>::New();
    }
    else
    {
      out = vtkSmartPointer<vtkFloatArray>::New();
    }
    out->SetName("wavelet");
    out->SetNumberOfTuples(values->GetNumberOfTuples());
    const double lo = this->Range[0], hi = this->Range[1];
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      const double v = values->GetTuple1(i);
      out->SetTuple1(i, levels > 0 ? std::round((v - lo) / (hi - lo) * levels) : v);
    }
    if (levels == 0)
    {
      out->SetTuple1(values->GetNumberOfTuples() / 2 + 7, std::numeric_limits<double>::quiet_NaN());
    }
    this->Image->GetPointData()->SetScalars(out);
    mapper->SetInputDataObject(this->Image);
    if (levels > 0)
    {
      // The same colours and opacity over the integers' range.
      const double scale = levels / (hi - lo);
      vtkColorTransferFunction* color = this->Property->GetRGBTransferFunction(0);
      color->RemoveAllPoints();
      color->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
      color->AddRGBPoint(0.5 * levels, 0.9, 0.9, 0.2);
      color->AddRGBPoint(levels, 0.9, 0.1, 0.1);
      vtkPiecewiseFunction* opacity = this->Property->GetScalarOpacity(0);
      const double mid = 0.5 * (lo + hi);
      opacity->RemoveAllPoints();
      opacity->AddPoint(0.0, 0.0);
      opacity->AddPoint((mid - lo) * scale, 0.0);
      opacity->AddPoint((mid + 0.2 * (hi - mid) - lo) * scale, 0.05);
      opacity->AddPoint(levels, 0.4);
    }
  }
};

vtkSmartPointer<ErrorRecorder> Watch(vtkObject* object)
{
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(object);
  return errors;
}

/// Integer data at their width: GL vs CPU at a coarse stride, the bytes, and
/// (8-bit) vtkGPUVolumeRayCastMapper at the full budget.
int Integers(int levels)
{
  Checker check;
  const std::size_t bytes = levels == 255 ? 1 : 2;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  // The data-space selection: its bricks at full resolution share the
  // fewest borders, which the bytes-a-texel bound below counts (a view's
  // weights split differently: 1.14 x the voxels at 1 byte a texel).
  mapper->SetViewSelectionToData();
  FormatScene scene(mapper, levels);
  auto errors = Watch(mapper);
  const double voxels = 65.0 * 65.0 * 65.0;
  mapper->SetBudgetMB(8.0);
  scene.Window->Render();
  const double ownBytes = static_cast<double>(mapper->GetLastTextureBytes());
  std::cout << "full budget: texture bytes " << ownBytes << " for " << voxels << " voxels\n";
  check.Check(mapper->GetLastEstimatedError() == 0.0, "the full volume, no quantization error");
  check.Check(ownBytes <= 1.1 * voxels * static_cast<double>(bytes) && ownBytes >= voxels,
    std::to_string(bytes) + " byte(s) a texel");
  const std::vector<double> ours = Grab(scene.Window);
  // Another format releases the resident textures: only the new ones count.
  mapper->SetTexelFormat(vtkHybridOctreeVolumeMapper::TEXELS_FLOAT32);
  scene.Window->Render();
  const double floatBytes = static_cast<double>(mapper->GetLastTextureBytes());
  const double same = Rmse(Grab(scene.Window), ours);
  std::cout << "float32: texture bytes " << floatBytes << ", RMSE to the "
            << (levels == 255 ? "R8" : "R16") << " picture " << same << "\n";
  check.Check(std::fabs(floatBytes - ownBytes * 4.0 / static_cast<double>(bytes)) < 1.0,
    "float32 textures take 4 bytes a texel");
  check.Check(same < 0.002, "exact integers: the float32 picture");
  mapper->SetTexelFormat(vtkHybridOctreeVolumeMapper::TEXELS_AUTO);
  mapper->SetBudgetMB(0.2 * static_cast<double>(bytes));
  CompareWithCpu(check, scene, mapper, 0.005, errors);
  check.Check(mapper->GetLastEstimatedError() > 0.0, "a budget under the full volume");
  if (levels == 255)
  {
    vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
    FormatScene theirs(gpu, levels);
    theirs.Window->Render();
    const double rmse = Rmse(ours, Grab(theirs.Window));
    std::cout << "RGB RMSE against vtkGPUVolumeRayCastMapper " << rmse << " (threshold 0.03)\n";
    check.Check(rmse < 0.03, "within 0.03 of vtkGPUVolumeRayCastMapper");
  }
  check.Check(errors->Errors.empty(), "no error:\n" + errors->AllErrors());
  return check.Result();
}

/// Float data quantized to Unorm8 and Float16.
int Quantized()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  Scene scene(mapper);
  auto errors = Watch(mapper);
  mapper->SetBudgetMB(8.0);
  mapper->SetTexelFormat(vtkHybridOctreeVolumeMapper::TEXELS_FLOAT32);
  scene.Window->Render();
  const std::vector<double> exact = Grab(scene.Window);
  const double floatBytes = static_cast<double>(mapper->GetLastTextureBytes());
  check.Check(mapper->GetLastEstimatedError() == 0.0, "float32: no error at the full budget");
  for (int format :
    { vtkHybridOctreeVolumeMapper::TEXELS_UNORM8, vtkHybridOctreeVolumeMapper::TEXELS_FLOAT16 })
  {
    const bool unorm8 = format == vtkHybridOctreeVolumeMapper::TEXELS_UNORM8;
    mapper->SetTexelFormat(format);
    mapper->SetBudgetMB(8.0);
    scene.Window->Render();
    const double moved = Rmse(Grab(scene.Window), exact);
    const double error = mapper->GetLastEstimatedError();
    const double bytes = static_cast<double>(mapper->GetLastTextureBytes());
    std::cout << (unorm8 ? "unorm8" : "float16") << ": RMSE to float32 " << moved
              << ", estimated error " << error << ", bytes " << bytes << " of " << floatBytes
              << "\n";
    check.Check(moved < (unorm8 ? 0.02 : 0.005), "the picture stays near the float32 one");
    check.Check(error > 0.0 && error < 0.002, "the estimated error is the quantization error");
    check.Check(std::fabs(bytes * (unorm8 ? 4.0 : 2.0) - floatBytes) < 1.0, "the format's bytes");
    mapper->SetBudgetMB(unorm8 ? 0.2 : 0.4);
    CompareWithCpu(check, scene, mapper, 0.005, errors);
  }
  check.Check(errors->Errors.empty(), "no error:\n" + errors->AllErrors());
  return check.Result();
}

/// NaN samples cannot be normalized codes: a clear error, and Float16 draws them.
int NanUnorm()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  FormatScene scene(mapper, 0);
  auto errors = Watch(mapper);
  mapper->SetTexelFormat(vtkHybridOctreeVolumeMapper::TEXELS_UNORM8);
  scene.Window->Render();
  const std::string all = errors->AllErrors();
  std::cout << "unorm8 with a NaN: " << all << "\n";
  check.Check(!mapper->GetLastRenderOK(), "the render fails");
  check.Check(all.find("NaN") != std::string::npos && all.find("float16") != std::string::npos,
    "the error names the NaN samples and a format that holds them");
  errors->Errors.clear();
  mapper->SetTexelFormat(vtkHybridOctreeVolumeMapper::TEXELS_FLOAT16);
  scene.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "float16 draws it:\n" + errors->AllErrors());
  check.Check(Signal(Grab(scene.Window)) > 0.005, "the volume shows");
  return check.Result();
}
} // namespace

int TestHybridOctreeTexelFormats(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "r8";
  if (scenario == "r8" || scenario == "r16")
  {
    return Integers(scenario == "r8" ? 255 : 65535);
  }
  if (scenario == "quantized")
  {
    return Quantized();
  }
  if (scenario == "nan_unorm")
  {
    return NanUnorm();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
