#include "vtkHybridOctreeCameraInput.h"

#include "vtkCamera.h"

namespace vtkHybridOctreeCameraInput
{
vtkHybridOctreeBridge::CameraDescription DescribeCamera(vtkCamera* camera)
{
  vtkHybridOctreeBridge::CameraDescription d;
  if (!camera)
  {
    return d;
  }
  camera->GetPosition(d.Position);
  camera->GetFocalPoint(d.FocalPoint);
  camera->GetViewUp(d.ViewUp);
  d.Parallel = camera->GetParallelProjection() != 0;
  d.ParallelScale = camera->GetParallelScale();
  d.ViewAngle = camera->GetViewAngle();
  return d;
}
}
