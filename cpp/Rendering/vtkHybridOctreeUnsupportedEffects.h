/**
 * @file   vtkHybridOctreeUnsupportedEffects.h
 * @brief  The vtkVolumeMapper and vtkVolumeProperty settings the Hybrid Octree mapper does not draw
 * (private to the module).
 *
 * vtkHybridOctreeVolumeMapper draws Composite blending of one scalar
 * component through a 1D colour and scalar opacity function, shaded when
 * the property asks (Shade), its opacity times the gradient opacity when one
 * is set (GradientOpacity), cropped and clipped by the mapper's cropping and
 * clipping planes, under every blend mode (Slice with a vtkPlane as its
 * slice function), classified by a 2D transfer function under Composite,
 * two dependent components and four (RGBA) in Composite. Settings that ask
 * for more (a Slice blend mode without a valid vtkPlane, a 2D transfer
 * function under another blend mode, without a usable image or with
 * dependent components, dependent components of 3 or more than 4
 * components or under a reducing blend mode) are drawn as if off; each one the
 * user has turned on is named in one warning that says what is drawn instead
 * and what to do.
 *
 * Each warning is given once while its setting stays as it is: Update()
 * returns the messages of the settings on now that were not on (with the
 * same value) at the previous call. A setting turned off and on again, or
 * changed to another value (Maximum Intensity to Additive), is warned about
 * again.
 */
#ifndef vtkHybridOctreeUnsupportedEffects_h
#define vtkHybridOctreeUnsupportedEffects_h

#include <set>
#include <string>
#include <vector>

class vtkVolumeMapper;
class vtkVolumeProperty;

class vtkHybridOctreeUnsupportedEffects
{
public:
  /// The messages of the effects `mapper` and `property` turn on for scalars
  /// of `components` components that were not on at the previous call
  /// (`translucentSurface`: the mapper draws a translucent isosurface).
  std::vector<std::string> Update(vtkVolumeMapper* mapper, vtkVolumeProperty* property,
    int components, bool translucentSurface = false);

  /// Every effect turned on now (one message each), whether warned or not.
  static std::vector<std::string> TurnedOn(vtkVolumeMapper* mapper, vtkVolumeProperty* property,
    int components, bool translucentSurface = false);

  /// VTK's name of a vtkVolumeMapper blend mode ("Maximum Intensity"), or
  /// "blend mode N" for a value VTK does not define.
  static std::string BlendModeName(int mode);

private:
  /// The messages of the previous call.
  std::set<std::string> On;
};

#endif
