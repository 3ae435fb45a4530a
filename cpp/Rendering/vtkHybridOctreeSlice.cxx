#include "vtkHybridOctreeSlice.h"

#include "vtkImplicitFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkPlane.h"
#include "vtkVolumeProperty.h"

#include <cmath>

bool vtkHybridOctreeSlice::Describe(
  vtkVolumeProperty* property, vtkMatrix4x4* modelInverse, double plane[6], std::string& problem)
{
  vtkImplicitFunction* function = property ? property->GetSliceFunction() : nullptr;
  const std::string what = "the Slice blend mode draws the volume on vtkVolumeProperty's "
                           "SliceFunction (ParaView: Slice Function), ";
  if (!function)
  {
    problem = what +
      "and none is set: set a vtkPlane with SetSliceFunction(); the volume is drawn "
      "with Composite blending";
    return false;
  }
  vtkPlane* p = vtkPlane::SafeDownCast(function);
  if (!p)
  {
    problem = what + "which must be a vtkPlane, not a " + std::string(function->GetClassName()) +
      " (vtkGPUVolumeRayCastMapper: \"Implicit function type is not supported by this "
      "mapper\"): set a vtkPlane; the volume is drawn with Composite blending";
    return false;
  }
  double origin[4] = { p->GetOrigin()[0], p->GetOrigin()[1], p->GetOrigin()[2], 1.0 };
  double normal[4] = { p->GetNormal()[0], p->GetNormal()[1], p->GetNormal()[2], 0.0 };
  double o[4] = { origin[0], origin[1], origin[2], 1.0 };
  double n[4] = { normal[0], normal[1], normal[2], 0.0 };
  if (modelInverse)
  {
    modelInverse->MultiplyPoint(origin, o);
    modelInverse->MultiplyPoint(normal, n);
    for (int k = 0; k < 3; ++k)
    {
      o[k] /= o[3];
    }
  }
  double length2 = 0.0;
  bool finite = true;
  for (int k = 0; k < 3; ++k)
  {
    plane[k] = o[k];
    plane[3 + k] = n[k];
    length2 += n[k] * n[k];
    finite = finite && std::isfinite(o[k]) && std::isfinite(n[k]);
  }
  if (!finite || !(length2 > 0.0) || !std::isfinite(length2))
  {
    problem = what + "and its vtkPlane (origin " + std::to_string(origin[0]) + ", " +
      std::to_string(origin[1]) + ", " + std::to_string(origin[2]) + ", normal " +
      std::to_string(normal[0]) + ", " + std::to_string(normal[1]) + ", " +
      std::to_string(normal[2]) +
      ") needs a finite origin and a non-zero normal; the volume is drawn with Composite blending";
    return false;
  }
  return true;
}
