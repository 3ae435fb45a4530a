// The minimal VTK volume-rendering application of the README: a 65^3
// wavelet drawn by vtkHybridOctreeVolumeMapper under a 1 MB texture budget
// with a translucent isosurface, through the installed package; exits
// non-zero unless the frame drew within the budget.
#include "vtkColorTransferFunction.h"
#include "vtkHybridOctreeVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <iostream>

int main()
{
  vtkNew<vtkRTAnalyticSource> source; // values about 37 .. 277
  source->SetWholeExtent(-32, 32, -32, 32, -32, 32);

  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  mapper->SetBudgetMB(1.0);
  mapper->ShowSurfaceOn();
  mapper->SetIsovalue(200.0);
  mapper->SetSurfaceColor(1.0, 0.9, 0.7);
  mapper->SetSurfaceOpacity(0.5);
  mapper->UsePointsOn(); // paper 3's points, paid from the same budget
  mapper->SetPointFactor(2);

  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(37.0, 0.1, 0.2, 0.9);
  color->AddRGBPoint(277.0, 0.9, 0.1, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(150.0, 0.0);
  opacity->AddPoint(277.0, 0.3);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->GetProperty()->SetColor(color);
  volume->GetProperty()->SetScalarOpacity(opacity);

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(300, 300);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();

  if (!mapper->GetLastRenderOK() || mapper->GetLastBricks() <= 0 ||
    mapper->GetLastTextureBytes() + mapper->GetLastPointBytes() > 1000000)
  {
    std::cerr << "the volume did not draw within the budget\n";
    mapper->Print(std::cerr);
    return 1;
  }
  std::cout << "volume OK: " << mapper->GetLastBricks() << " bricks, "
            << mapper->GetLastTextureBytes() << " texture bytes, " << mapper->GetLastPoints()
            << " points, plan '" << mapper->GetLastPlan() << "', "
            << mapper->GetLastFrameMilliseconds() << " ms\n";
  return 0;
}
