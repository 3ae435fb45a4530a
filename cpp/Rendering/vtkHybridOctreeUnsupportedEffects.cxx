#include "vtkHybridOctreeUnsupportedEffects.h"
#include "vtkHybridOctreeTransfer2D.h"

#include "vtkHybridOctreeSlice.h"
#include "vtkHybridOctreeVolumeMapper.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <string>

std::string vtkHybridOctreeUnsupportedEffects::BlendModeName(int mode)
{
  switch (mode)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      return "Composite";
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return "Maximum Intensity";
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return "Minimum Intensity";
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      return "Average Intensity";
    case vtkVolumeMapper::ADDITIVE_BLEND:
      return "Additive";
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      return "Isosurface";
    case vtkVolumeMapper::SLICE_BLEND:
      return "Slice";
    default:
      return "blend mode " + std::to_string(mode);
  }
}

std::vector<std::string> vtkHybridOctreeUnsupportedEffects::TurnedOn(
  vtkVolumeMapper* mapper, vtkVolumeProperty* property, int components, bool translucentSurface)
{
  // The VTK mapper that draws the effect.
  const std::string elsewhere =
    "vtkGPUVolumeRayCastMapper (ParaView: the Volume representation), which draws it";
  std::vector<std::string> on;
  const int mode = mapper->GetBlendMode();
  if (mode < vtkVolumeMapper::COMPOSITE_BLEND || mode > vtkVolumeMapper::SLICE_BLEND)
  {
    const std::string name = BlendModeName(mode);
    on.push_back("the " + name + " blend mode (vtkVolumeMapper::SetBlendMode(" +
      std::to_string(mode) + "); ParaView: Blend Mode) is not implemented: the volume is drawn " +
      "with Composite blending; set the blend mode to Composite, maximum, minimum or average " +
      "intensity, additive, Isosurface or Slice, or use " + elsewhere);
  }
  double plane[6];
  std::string problem;
  if (mode == vtkVolumeMapper::SLICE_BLEND &&
    !vtkHybridOctreeSlice::Describe(property, nullptr, plane, problem))
  {
    on.push_back(problem);
  }
  if (translucentSurface &&
    ((mode > vtkVolumeMapper::COMPOSITE_BLEND && mode <= vtkVolumeMapper::ADDITIVE_BLEND) ||
      mode == vtkVolumeMapper::SLICE_BLEND))
  {
    on.push_back("a translucent isosurface is not drawn under the " + BlendModeName(mode) +
      " blend mode (its ray is reduced, not composited in depth order): set the surface opacity "
      "to 1 (drawn opaque, under the volume) or the blend mode to Composite");
  }
  if (property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D)
  {
    if (!vtkHybridOctreeTransfer2D::Usable(property))
    {
      on.push_back("the 2D transfer function mode (vtkVolumeProperty::SetTransferFunctionModeTo2D) "
                   "has no usable TransferFunction2D (a 2D vtkImageData of 4 components, at "
                   "most 4096 per side): the 1D colour and scalar opacity functions are drawn; "
                   "set one with SetTransferFunction2D(), or switch to the 1D mode");
    }
    else if (mode != vtkVolumeMapper::COMPOSITE_BLEND)
    {
      on.push_back("the 2D transfer function (ParaView: Use 2D Transfer Function) is drawn under "
                   "the Composite blend mode only: under " +
        BlendModeName(mode) +
        " the 1D colour and scalar opacity functions are drawn (VTK's ray caster reads its "
        "2D table there with the gradient of another sample); set the blend mode to Composite");
    }
    else if (components == 2 && !property->GetIndependentComponents())
    {
      on.push_back("the 2D transfer function (ParaView: Use 2D Transfer Function) classifies one "
                   "field, and this volume has 2 dependent components (ParaView: Use Separate "
                   "Opacity Array): the colour function at component 0 and the scalar opacity "
                   "function at component 1 are drawn; turn the 2D transfer function or the "
                   "separate opacity array off");
    }
    else if (components == 4 && !property->GetIndependentComponents())
    {
      on.push_back("the 2D transfer function (ParaView: Use 2D Transfer Function) classifies one "
                   "field, and this volume has 4 dependent components (RGBA; ParaView: Map "
                   "Scalars off with Multi Components Mapping): components 0 to 2 as the colour "
                   "and the scalar opacity function at component 3 are drawn; turn the 2D "
                   "transfer function off, or IndependentComponents on");
    }
  }
  // Two dependent components (colour, opacity) and four (RGBA) are drawn in Composite.
  const bool dependent =
    (components == 2 || components == 4) && !property->GetIndependentComponents();
  if (dependent && mode != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    on.push_back(std::to_string(components) +
      " dependent components (vtkVolumeProperty::IndependentComponentsOff; ParaView: "
      "Use Separate Opacity Array, or Map Scalars off with Multi Components Mapping) are "
      "drawn in Composite only: under the " +
      BlendModeName(mode) +
      " blend mode the component chosen with SetComponent() is drawn through the colour and "
      "scalar opacity functions; set the blend mode to Composite, or use " +
      elsewhere);
  }
  // Volumetric scattering runs in Composite, one field through the 1D functions.
  auto* hybrid = vtkHybridOctreeVolumeMapper::SafeDownCast(mapper);
  if (hybrid && hybrid->GetVolumetricScatteringBlending() > 0.0 && property->GetShade() &&
    (mode != vtkVolumeMapper::COMPOSITE_BLEND ||
      property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D || dependent))
  {
    on.push_back("volumetric scattering (VolumetricScatteringBlending; ParaView: Volumetric "
                 "Scattering Blending) is drawn under the Composite blend mode with the 1D "
                 "transfer functions of one field only: here the volume is drawn unscattered; "
                 "set the blend mode to Composite without a 2D transfer function or separate "
                 "opacity array, or use " +
      elsewhere);
  }
  if ((components == 3 || components > 4) && !property->GetIndependentComponents())
  {
    on.push_back("dependent components of a " + std::to_string(components) +
      "-component array (vtkVolumeProperty::IndependentComponentsOff) are not drawn: VTK draws "
      "dependent components of 2 (colour, opacity) or 4 (RGBA) components; the component "
      "chosen with SetComponent() is drawn through the colour and scalar opacity functions; "
      "append an opacity component (vtkImageAppendComponents) for RGBA, or turn "
      "IndependentComponents on, or use " +
      elsewhere);
  }
  return on;
}

std::vector<std::string> vtkHybridOctreeUnsupportedEffects::Update(
  vtkVolumeMapper* mapper, vtkVolumeProperty* property, int components, bool translucentSurface)
{
  const std::vector<std::string> now = TurnedOn(mapper, property, components, translucentSurface);
  std::vector<std::string> fresh;
  for (const std::string& message : now)
  {
    if (this->On.count(message) == 0)
    {
      fresh.push_back(message);
    }
  }
  this->On = std::set<std::string>(now.begin(), now.end());
  return fresh;
}
