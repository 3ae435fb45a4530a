/**
 * RGBA volumes (vtkVolumeProperty::IndependentComponentsOff on a
 * 4-component array: ParaView's Map Scalars off with Multi Components
 * Mapping) drawn by vtkHybridOctreeVolumeMapper under Xvfb. The image, on
 * the wavelet's 65^3 grid (vtkRTAnalyticSource): red the wavelet's value
 * normalised, green 1 - red, blue a ball's radius r / 32, alpha a ball
 * (1 - r / 28, clamped at 0); as unsigned char (255 x, rounded: an RGBA8
 * texture, 4 bytes a texel; VTK 9.2 reads x) or as float (colour 100 x -
 * 20, alpha 2 x: RGBA32F, 16 bytes a texel; VTK 9.2 reads the colour as it
 * is, clamped, and the opacity at lo + clamp(v) (hi - lo) of alpha's range).
 * Opacity over alpha's range, transparent below a tenth of it; a colour
 * function that would paint magenta (VTK does not read it). Metric: RMSE of
 * the RGB channels in [0, 1] over the 256x256 window.
 *
 *   rgba:     budgets under the full volume: the effects are
 *             "rgba-components", the GL picture within RMSE 0.005 of the
 *             CPU compositor on the same DrawList (measured: u8 0.0015, u8
 *             shaded with the gradient of component 0 0.0016, float
 *             0.0015); the texture bytes within the budget, 4 (u8) or 16
 *             (float) bytes a texel; no warning; the picture is not
 *             component 3's drawn alone through the colour function (RMSE
 *             > 0.05; measured 0.095, 0.18).
 *   gpu_rgba: the full volume in the budget, against
 *             vtkGPUVolumeRayCastMapper with the same property, as unsigned
 *             char, float, int (colour 1000 x - 200, alpha 1000 x), unsigned
 *             int (colour and alpha 1000 x) and double (as float): RMSE <
 *             0.03 (measured u8 0.0008, float 0.0035, int 0.0008, unsigned
 *             int 0.0008, double 0.0008: VTK 9.2 scales the wide types'
 *             components to their ranges, so double's picture is not
 *             float's), and below a tenth of the reference's RMSE to the
 *             empty window.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// The four-component image of the file's documentation, and its stage.
struct RgbaScene : Stage
{
  vtkNew<vtkImageData> Image;

  RgbaScene(vtkVolumeMapper* mapper, int type)
  {
    vtkNew<vtkRTAnalyticSource> wavelet;
    wavelet->SetWholeExtent(-32, 32, -32, 32, -32, 32);
    wavelet->Update();
    vtkImageData* w = wavelet->GetOutput();
    vtkDataArray* values = w->GetPointData()->GetScalars();
    double range[2];
    values->GetRange(range);
    this->Image->CopyStructure(w);
    vtkSmartPointer<vtkDataArray> rgba =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    rgba->SetName("rgba");
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(values->GetNumberOfTuples());
    const bool integers = type == VTK_INT || type == VTK_UNSIGNED_INT;
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      double p[3];
      w->GetPoint(i, p);
      const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      const double red = (values->GetTuple1(i) - range[0]) / (range[1] - range[0]);
      const double c[4] = { red, 1.0 - red, std::min(1.0, r / 32.0),
        std::max(0.0, 1.0 - r / 28.0) };
      if (type == VTK_UNSIGNED_CHAR)
      {
        rgba->SetTuple4(i, std::round(255.0 * c[0]), std::round(255.0 * c[1]),
          std::round(255.0 * c[2]), std::round(255.0 * c[3]));
      }
      else if (integers)
      {
        // Colour 1000 x (less 200 for int), alpha 1000 x, rounded.
        const double shift = type == VTK_INT ? -200.0 : 0.0;
        rgba->SetTuple4(i, std::round(1000.0 * c[0]) + shift, std::round(1000.0 * c[1]) + shift,
          std::round(1000.0 * c[2]) + shift, std::round(1000.0 * c[3]));
      }
      else
      {
        rgba->SetTuple4(
          i, 100.0 * c[0] - 20.0, 100.0 * c[1] - 20.0, 100.0 * c[2] - 20.0, 2.0 * c[3]);
      }
    }
    this->Image->GetPointData()->SetScalars(rgba);
    mapper->SetInputDataObject(this->Image);
    const double top = type == VTK_UNSIGNED_CHAR ? 255.0 : integers ? 1000.0 : 2.0;
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.0, 1.0, 0.0, 1.0);
    color->AddRGBPoint(top, 1.0, 0.0, 1.0);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.1 * top, 0.0);
    opacity->AddPoint(0.5 * top, 0.03);
    opacity->AddPoint(top, 0.3);
    const double position[3] = { 95.0, 75.0, 130.0 };
    this->Build(mapper, color, opacity, position);
    this->Property->IndependentComponentsOff();
  }
};

/// Mixed strides, GL against the CPU compositor on the same DrawList.
int Rgba()
{
  Checker check;
  struct Case
  {
    bool Bytes;
    bool Shade;
    double BudgetMB;
  };
  // The full 65^3 volume is 1.1 MB as RGBA8, 4.4 MB as RGBA32F; shaded
  // bricks carry a gradient border (a larger budget).
  for (const Case& c :
    { Case{ true, false, 0.1 }, Case{ true, true, 0.3 }, Case{ false, false, 0.4 } })
  {
    vtkNew<vtkHybridOctreeVolumeMapper> mapper;
    RgbaScene scene(mapper, c.Bytes ? VTK_UNSIGNED_CHAR : VTK_FLOAT);
    mapper->SetLeafSize(8);
    mapper->SetBudgetMB(c.BudgetMB);
    scene.Property->SetShade(c.Shade);
    vtkSmartPointer<ErrorRecorder> errors =
      vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
    errors->Watch(mapper);
    scene.Window->Render();
    const std::string what = std::string(c.Bytes ? "u8" : "float") + (c.Shade ? " shaded" : "");
    check.Check(mapper->GetLastRenderOK(), what + ": the mapper drew:\n" + errors->AllErrors());
    const std::string effects = c.Shade ? "rgba-components,shading" : "rgba-components";
    check.Check(std::string(mapper->GetLastEffects()) == effects,
      what + ": effects '" + effects + "', not '" + mapper->GetLastEffects() + "'");
    const std::vector<double> gl = Grab(scene.Window);
    const std::vector<double> reference = CpuPicture(check, scene, mapper, errors);
    const double rmse = Rmse(gl, reference);
    const double perTexel = c.Bytes ? 4.0 : 16.0;
    std::cout << what << ": bricks " << mapper->GetLastBricks() << ", texture bytes "
              << mapper->GetLastTextureBytes() << ", estimated error "
              << mapper->GetLastEstimatedError() << "; RGB RMSE GL vs CPU compositor " << rmse
              << " (threshold 0.005), signal " << Signal(reference) << "\n";
    check.Check(Signal(reference) > 0.005, what + ": the scene shows something");
    check.Check(rmse < 0.005, what + ": GL picture within 0.005 of the CPU compositor");
    check.Check(mapper->GetLastEstimatedError() > 0.0, what + ": a budget under the full volume");
    check.Check(mapper->GetLastTextureBytes() <= c.BudgetMB * 1.0e6 &&
        std::fmod(static_cast<double>(mapper->GetLastTextureBytes()), perTexel) == 0.0,
      what + ": texture bytes within the budget, " + std::to_string(perTexel) + " a texel");
    check.Check(NoGLError(scene.Window), what + ": no OpenGL error left behind");
    check.Check(errors->Errors.empty() && errors->Warnings.empty(),
      what + ": no warning or error:\n" + errors->AllErrors() +
        (errors->Warnings.empty() ? "" : "  warning: " + errors->Warnings[0] + "\n"));
    if (!c.Shade)
    {
      // Component 3 drawn alone (independent) through the colour function is another picture.
      scene.Property->IndependentComponentsOn();
      mapper->SetComponent(3);
      scene.Window->Render();
      const double apart = Rmse(Grab(scene.Window), gl);
      std::cout << what << ": component 3 alone differs by " << apart << "\n";
      check.Check(apart > 0.05, what + ": the colour components show (component 3 alone differs)");
    }
  }
  return check.Result();
}

/// The full volume in the budget against vtkGPUVolumeRayCastMapper.
int GpuRgba()
{
  Checker check;
  for (const int type : { VTK_UNSIGNED_CHAR, VTK_FLOAT, VTK_INT, VTK_UNSIGNED_INT, VTK_DOUBLE })
  {
    vtkNew<vtkHybridOctreeVolumeMapper> mapper;
    mapper->SetLeafSize(8);
    mapper->SetBudgetMB(16.0);
    RgbaScene ours(mapper, type);
    vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
    RgbaScene theirs(gpu, type);
    vtkSmartPointer<ErrorRecorder> errors =
      vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
    errors->Watch(mapper);
    ours.Window->Render();
    theirs.Window->Render();
    const std::string what = vtkImageScalarTypeNameMacro(type);
    check.Check(mapper->GetLastRenderOK(), what + ": the mapper drew:\n" + errors->AllErrors());
    check.Check(std::string(mapper->GetLastEffects()) == "rgba-components",
      what + ": effects 'rgba-components', not '" + mapper->GetLastEffects() + "'");
    // Wide types (int, unsigned int, double) are measured normalised in
    // 32-bit floats: an error of one float step (measured 4.8e-8 to 6e-8).
    check.Check(
      mapper->GetLastEstimatedError() < 1.0e-6, what + ": the full volume at full resolution");
    const std::vector<double> a = Grab(ours.Window);
    const std::vector<double> b = Grab(theirs.Window);
    const double rmse = Rmse(a, b);
    std::cout << what << ": bricks " << mapper->GetLastBricks() << ", texture bytes "
              << mapper->GetLastTextureBytes() << ", estimated error "
              << mapper->GetLastEstimatedError() << "; RGB RMSE against vtkGPUVolumeRayCastMapper "
              << rmse << " (threshold 0.03), signal " << Signal(b) << "\n";
    // The window without the volume: a bound of 0.03 must be well under its distance.
    std::vector<double> empty(b.size());
    for (std::size_t i = 0; i < empty.size(); ++i)
    {
      empty[i] = Background[i % 3];
    }
    const double shown = Rmse(b, empty);
    std::cout << what << ": the volume is " << shown << " from the empty window\n";
    check.Check(Signal(b) > 0.02, what + ": the reference shows the volume");
    check.Check(
      rmse < 0.1 * shown, what + ": within a tenth of the volume's distance to the empty window");
    check.Check(rmse < 0.03, what + ": within 0.03 of vtkGPUVolumeRayCastMapper");
    check.Check(NoGLError(ours.Window), what + ": no OpenGL error left behind");
  }
  return check.Result();
}
} // namespace

int TestHybridOctreeRgba(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "rgba";
  if (scenario == "rgba")
  {
    return Rgba();
  }
  if (scenario == "gpu_rgba")
  {
    return GpuRgba();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
