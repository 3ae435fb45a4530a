/**
 * Two dependent components (vtkVolumeProperty::IndependentComponentsOff on
 * a 2-component array: ParaView's Use Separate Opacity Array) drawn by
 * vtkHybridOctreeVolumeMapper under Xvfb. The image: the wavelet
 * (vtkRTAnalyticSource, 65^3) in component 0, the colour field, and a ball
 * (1 - r / 28, clamped at 0) in component 1, the opacity field; colours
 * over the wavelet's range, opacity over the ball's (transparent below
 * 0.1). Metric: RMSE of the RGB channels in [0, 1] over the 256x256 window.
 *
 *   dependent:     a budget under the full volume (mixed strides): the
 *                  effects are "dependent-components", the GL picture within
 *                  RMSE 0.005 of the CPU compositor on the same DrawList
 *                  (the one algorithm, colour from channel 0 and opacity
 *                  from channel 1; measured 0.0015), no warning; the texture bytes count 8
 *                  bytes a texel; the picture is not component 0's drawn
 *                  alone (RMSE > 0.02; measured 0.24). Shaded too (the
 *                  gradient is component 0's; 0.6 MB: the bordered root
 *                  at stride 2): the same bound (measured 0.0015).
 *   gpu_dependent: the full volume in the budget, against
 *                  vtkGPUVolumeRayCastMapper with the same property
 *                  (IndependentComponentsOff): RMSE < 0.005 (measured
 *                  0.0007: the ball's opacity is smooth, so slices and rays
 *                  sample it alike).
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"

#include "vtkAutoInit.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"

#include <cmath>
#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingVolumeOpenGL2);

namespace
{
using namespace MapperScene;

/// The two-component image of the file's documentation, and its stage.
struct DependentScene : Stage
{
  vtkNew<vtkImageData> Image;
  double ColourRange[2] = { 0.0, 1.0 };

  explicit DependentScene(vtkVolumeMapper* mapper)
  {
    vtkNew<vtkRTAnalyticSource> wavelet;
    wavelet->SetWholeExtent(-32, 32, -32, 32, -32, 32);
    wavelet->Update();
    vtkImageData* w = wavelet->GetOutput();
    vtkDataArray* values = w->GetPointData()->GetScalars();
    values->GetRange(this->ColourRange);
    this->Image->CopyStructure(w);
    vtkNew<vtkFloatArray> pairs;
    pairs->SetName("colour_and_opacity");
    pairs->SetNumberOfComponents(2);
    pairs->SetNumberOfTuples(values->GetNumberOfTuples());
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      double p[3];
      w->GetPoint(i, p);
      const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      pairs->SetTuple2(i, values->GetTuple1(i), std::max(0.0, 1.0 - r / 28.0));
    }
    this->Image->GetPointData()->SetScalars(pairs);
    mapper->SetInputDataObject(this->Image);
    const double lo = this->ColourRange[0], hi = this->ColourRange[1], mid = 0.5 * (lo + hi);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(lo, 0.1, 0.2, 0.9);
    color->AddRGBPoint(mid, 0.9, 0.9, 0.2);
    color->AddRGBPoint(hi, 0.9, 0.1, 0.1);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.1, 0.0);
    opacity->AddPoint(0.5, 0.03);
    opacity->AddPoint(1.0, 0.3);
    const double position[3] = { 95.0, 75.0, 130.0 };
    this->Build(mapper, color, opacity, position);
    this->Property->IndependentComponentsOff();
  }
};

/// Mixed strides, GL against the CPU compositor on the same DrawList, unshaded and shaded.
int Dependent()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  DependentScene scene(mapper);
  mapper->SetLeafSize(8);
  // The full 65^3 float pairs are 2.2 MB: 0.2 MB holds a mix of strides.
  mapper->SetBudgetMB(0.2);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  std::vector<double> unshaded;
  for (bool shade : { false, true })
  {
    // Shaded bricks carry a gradient border: a larger budget (the root at stride 2).
    mapper->SetBudgetMB(shade ? 0.6 : 0.2);
    scene.Property->SetShade(shade);
    scene.Window->Render();
    check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
    const std::string effects = shade ? "dependent-components,shading" : "dependent-components";
    check.Check(std::string(mapper->GetLastEffects()) == effects,
      "effects '" + effects + "', not '" + mapper->GetLastEffects() + "'");
    const std::vector<double> gl = Grab(scene.Window);
    const std::vector<double> reference = CpuPicture(check, scene, mapper, errors);
    const double rmse = Rmse(gl, reference);
    std::cout << "shade " << shade << ": bricks " << mapper->GetLastBricks() << ", texture bytes "
              << mapper->GetLastTextureBytes() << ", estimated error "
              << mapper->GetLastEstimatedError() << "; RGB RMSE GL vs CPU compositor " << rmse
              << " (threshold 0.005), signal " << Signal(reference) << "\n";
    check.Check(Signal(reference) > 0.005, "the scene shows something");
    check.Check(rmse < 0.005, "GL picture within 0.005 of the CPU compositor");
    check.Check(mapper->GetLastEstimatedError() > 0.0, "a budget under the full volume");
    check.Check(NoGLError(scene.Window), "no OpenGL error left behind");
    if (!shade)
    {
      unshaded = gl;
    }
  }
  check.Check(errors->Errors.empty() && errors->Warnings.empty(),
    "no warning or error:\n" + errors->AllErrors() +
      (errors->Warnings.empty() ? "" : "  warning: " + errors->Warnings[0] + "\n"));
  // Component 0 drawn alone (independent) is another picture.
  scene.Property->ShadeOff();
  scene.Property->IndependentComponentsOn();
  mapper->SetComponent(0);
  scene.Window->Render();
  const double apart = Rmse(Grab(scene.Window), unshaded);
  std::cout << "component 0 alone differs by " << apart << "\n";
  check.Check(apart > 0.02, "the opacity field shows (component 0 alone differs)");
  return check.Result();
}

/// The full volume in the budget against vtkGPUVolumeRayCastMapper.
int GpuDependent()
{
  Checker check;
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetLeafSize(8);
  mapper->SetBudgetMB(8.0);
  DependentScene ours(mapper);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu = MakeReference();
  DependentScene theirs(gpu);
  vtkSmartPointer<ErrorRecorder> errors =
    vtkSmartPointer<ErrorRecorder>::Take(ErrorRecorder::New());
  errors->Watch(mapper);
  ours.Window->Render();
  theirs.Window->Render();
  check.Check(mapper->GetLastRenderOK(), "the mapper drew:\n" + errors->AllErrors());
  check.Check(std::string(mapper->GetLastEffects()) == "dependent-components",
    std::string("effects 'dependent-components', not '") + mapper->GetLastEffects() + "'");
  check.Check(mapper->GetLastEstimatedError() == 0.0, "the full volume at full resolution");
  const std::vector<double> a = Grab(ours.Window);
  const std::vector<double> b = Grab(theirs.Window);
  const double rmse = Rmse(a, b);
  std::cout << "dependent: bricks " << mapper->GetLastBricks() << ", texture bytes "
            << mapper->GetLastTextureBytes() << "; RGB RMSE against vtkGPUVolumeRayCastMapper "
            << rmse << " (threshold 0.005), signal " << Signal(b) << "\n";
  check.Check(Signal(b) > 0.02, "the reference shows the volume");
  check.Check(rmse < 0.005, "within 0.005 of vtkGPUVolumeRayCastMapper");
  check.Check(NoGLError(ours.Window), "no OpenGL error left behind");
  return check.Result();
}
} // namespace

int TestHybridOctreeDependent(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "dependent";
  if (scenario == "dependent")
  {
    return Dependent();
  }
  if (scenario == "gpu_dependent")
  {
    return GpuDependent();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return EXIT_FAILURE;
}
