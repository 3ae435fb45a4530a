/**
 * @file   vtkHybridOctreeScattering.h
 * @brief  Volumetric scattering for vtkHybridOctreeVolumeMapper (private to the module).
 *
 * VTK 9.2's volumetric scattering (vtkGPUVolumeRayCastMapper's
 * VolumetricScatteringBlending and GlobalIlluminationReach,
 * vtkVolumeProperty's ScatteringAnisotropy; src/transfer/scattering.rs):
 * Describe() reads the frame's parameters as VTK takes them (VTK's sample
 * distance vtkSmartVolumeMapper's still-frame one, the headlight's ambient
 * colour); Activate() uploads the selection's shadow volume (the whole
 * volume at up to 64 points per axis, src/render/scattering.rs) as one R32F
 * 3D texture, linear and clamp-to-edge, again only when the octree changed,
 * and reads the selection's ScatteringFrame; SetUniforms() gives the brick
 * shader's HO_SCATTERING variant both.
 */
#ifndef vtkHybridOctreeScattering_h
#define vtkHybridOctreeScattering_h

#include "vtkHybridOctreeBridge.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <string>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;

class vtkHybridOctreeScattering
{
public:
  /**
   * The frame's scattering: `blending` and `reach` (the mapper's), the
   * property's ScatteringAnisotropy, the headlight's ambient colour (the
   * first light's of `shading`), VTK's sample distance `sampleDistance`.
   */
  static vtkHybridOctreeBridge::ScatteringDescription Describe(double blending, double reach,
    vtkVolumeProperty* property, const vtkHybridOctreeBridge::ShadingDescription& shading,
    double sampleDistance);

  /**
   * Reads `selection`'s ScatteringFrame and uploads its shadow volume of the
   * image (`bytes`, `byteCount`, `grid`) unless the one uploaded is newer
   * than `dataTime` in this context. False and `error` on failure.
   */
  bool Activate(vtkOpenGLRenderWindow* window, const vtkHybridOctreeBridge::Selection& selection,
    const void* bytes, std::size_t byteCount, const vtkHybridOctreeBridge::GridDescription& grid,
    vtkMTimeType dataTime, std::string& error);

  /// The HO_SCATTERING uniforms and the shadow volume's texture unit.
  void SetUniforms(vtkShaderProgram* program) const;

  void Deactivate() const;
  void ReleaseGraphicsResources();

private:
  vtkSmartPointer<vtkTextureObject> Texture;
  vtkTimeStamp Uploaded;
  vtkHybridOctreeBridge::ScatteringFrame Frame;
};

#endif
