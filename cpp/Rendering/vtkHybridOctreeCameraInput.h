/**
 * @file   vtkHybridOctreeCameraInput.h
 * @brief  A vtkCamera as the Rust core reads it (private to the module).
 *
 * The one place that maps a VTK camera to the bridge's description, so the
 * bridge (in HybridOctree::Filters) needs no rendering module.
 */
#ifndef vtkHybridOctreeCameraInput_h
#define vtkHybridOctreeCameraInput_h

#include "vtkHybridOctreeBridge.h"

class vtkCamera;

namespace vtkHybridOctreeCameraInput
{
/// The camera's position, focal point, view up, projection, parallel scale
/// and (vertical) view angle; the default description for a null camera.
vtkHybridOctreeBridge::CameraDescription DescribeCamera(vtkCamera* camera);
}

#endif
