/**
 * @file   vtkHybridOctreeVolumeMapperInternals.h
 * @brief  What vtkHybridOctreeVolumeMapper keeps between frames, shared by the source files
 *         its definition is split into by stage of a frame (private to the module).
 *
 * - vtkHybridOctreeVolumeMapper.cxx: settings, Render, the model matrix, the transfer
 *   function table, the points and the isosurface;
 * - vtkHybridOctreeVolumeMapperInput.cxx: the input image or the OME-Zarr store it names,
 *   and the Volume Octree built from it;
 * - vtkHybridOctreeVolumeMapperSelection.cxx: the selections of still and interactive frames;
 * - vtkHybridOctreeVolumeMapperDraw.cxx: the frame's brick textures and its OpenGL drawing.
 */
#ifndef vtkHybridOctreeVolumeMapperInternals_h
#define vtkHybridOctreeVolumeMapperInternals_h

#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeInteractiveReduction.h"
#include "vtkHybridOctreeScattering.h"
#include "vtkHybridOctreeTransfer2D.h"
#include "vtkHybridOctreeUnsupportedEffects.h"
#include "vtkOpenGLHybridOctreeBrickDrawer.h"
#include "vtkOpenGLHybridOctreeBrickTextures.h"
#include "vtkOpenGLHybridOctreeFloatTarget.h"
#include "vtkOpenGLHybridOctreeSurfaceDrawer.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtkVolumeProperty.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;

/// Helpers more than one of the mapper's source files use.
namespace vtkHybridOctreeVolumeMapperParts
{
/// `m` applied to the point `p` (w = 1).
inline void TransformPoint(vtkMatrix4x4* m, const double p[3], double out[3])
{
  double in[4] = { p[0], p[1], p[2], 1.0 };
  double r[4];
  m->MultiplyPoint(in, r);
  for (int k = 0; k < 3; ++k)
  {
    out[k] = r[k] / r[3];
  }
}

/// The gradient opacity VTK 9.2's GPU ray caster applies (vtkVolumeShaderComposer.h,
/// HasGradientOpacity; vtkVolumeInputHelper): the 1D mode's function of the
/// first component, when one was set and is not disabled, as (magnitude,
/// opacity) pairs (magnitudes per mean voxel spacing, VTK's convention);
/// empty for none.
inline std::vector<double> GradientOpacityPoints(vtkVolumeProperty* property)
{
  if (property->GetTransferFunctionMode() != vtkVolumeProperty::TF_1D ||
    property->GetDisableGradientOpacity(0) || !property->HasGradientOpacity(0))
  {
    return {};
  }
  return vtkHybridOctreeBridge::OpacityPoints(property->GetStoredGradientOpacity(0));
}
} // namespace vtkHybridOctreeVolumeMapperParts

struct vtkHybridOctreeVolumeMapper::vtkInternals
{
  // The octree, rebuilt when the scalars, the image geometry or LeafSize change.
  std::unique_ptr<vtkHybridOctreeBridge::HybridOctree> Octree;
  vtkDataArray* Array = nullptr;
  vtkMTimeType ArrayMTime = 0;
  vtkHybridOctreeBridge::GridDescription Grid;
  int LeafSize = 0;
  /// NaN samples (no data) of the image the octree was built from.
  vtkTypeInt64 NaNSamples = 0;
  /// The octree's value range (NaN left out): what average and additive
  /// blending normalise by.
  double ValueRange[2] = { 0.0, 1.0 };
  /// When the octree was built: the caches below are current when made after it.
  vtkTimeStamp OctreeTime;
  // The OME-Zarr store the input image names (vtkHybridOctreeStoreFieldData.h),
  // opened once per path and modification time; null for an image in memory.
  std::unique_ptr<vtkHybridOctreeBridge::OmeZarrStore> Store;
  std::string StorePath;
  std::int64_t StoreTime = 0;
  /// The visibility view selections were said to weigh by screen space (once per store).
  bool StoreViewWarned = false;
  /// The full resolution's bounds of the last store named by the input.
  double StoreBounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
  vtkDataArray* Scalars = nullptr;

  // The points integrated into the octree, made again when the octree or
  // their settings change.
  bool HasPoints = false;
  vtkHybridOctreeBridge::PointsDrawing Drawing;
  vtkTimeStamp PointsTime;
  std::vector<double> PointsKey;
  // What each point adds under the transfer function, for those points and that table.
  std::vector<float> Shades;
  vtkTimeStamp ShadesTime;
  std::vector<double> ShadesColors;
  std::vector<double> ShadesOpacities;

  // The selections of still and of interactive frames, each made again
  // when its inputs change, and the one of this frame.
  struct SelectionSlot
  {
    std::unique_ptr<vtkHybridOctreeBridge::Selection> Selected;
    vtkHybridOctreeBridge::SelectionSummary Summary;
    vtkTimeStamp Time;
    std::vector<double> Key;
    std::vector<double> Opacity;
    vtkHybridOctreeBridge::ViewDescription View; ///< the view it was made for
  };
  SelectionSlot Still;
  SelectionSlot Moving;
  SelectionSlot* Frame = &Still;
  // This frame's view (DescribeView) and the volume's centre in the
  // octree's frame, what the view change is measured around.
  vtkHybridOctreeBridge::ViewDescription View;
  double Centre[3] = { 0.0, 0.0, 0.0 };
  // The last frame's bricks: their boxes (6 each, the octree's frame) and texture bytes.
  std::vector<double> FrameBounds;
  std::vector<vtkTypeInt64> FrameBytes;

  // The isosurface integrated into the octree, extracted again when the
  // octree or the isovalue change.
  bool HasIso = false;
  vtkTimeStamp IsoTime;
  double IsoValue = 0.0;

  // Transfer function table (what the CPU compositor gets too).
  vtkHybridOctreeBridge::CompositeScene Transfer;
  std::vector<float> Table;
  double RangeLo = 0.0;
  double RangeHi = 1.0;
  bool TableUploaded = false;

  // Two dependent fields (vtkHybridOctreeDependent.h): asked for by the
  // property and blend mode (Prepare), drawn for a 2-component array; the
  // octree built for them; the table's colour column over ColourRange
  // (component 0's), its opacity column over RangeLo, RangeHi (component 1's).
  // An RGBA volume (4 components, Rgba): the same octree kind and request;
  // the colour is the components' own, the opacity column over component 3's range.
  bool WantsDependent = false;
  bool Dependent = false;
  bool Rgba = false;
  bool OctreeDependent = false;
  double ColourRange[2] = { 0.0, 1.0 };
  /// When the resident brick textures were made (older than the octree: released).
  vtkTimeStamp TexturesTime;

  // Model matrix (volume matrix x image direction) and its inverse.
  vtkNew<vtkMatrix4x4> Model;
  vtkNew<vtkMatrix4x4> ModelInverse;

  // GL resources.
  vtkOpenGLHybridOctreeBrickTextures Bricks;
  vtkOpenGLHybridOctreeBrickDrawer Drawer;
  vtkOpenGLHybridOctreeFloatTarget Target;
  vtkOpenGLHybridOctreeSurfaceDrawer SurfaceDrawer;
  vtkSmartPointer<vtkTextureObject> TableTexture;

  // Settings the mapper does not draw, each warned about once while on.
  vtkHybridOctreeUnsupportedEffects Unsupported;
  /// The frame's shading (Prepare), light directions in the octree's frame.
  vtkHybridOctreeBridge::ShadingDescription Shading;
  /// The frame's cropping and clipping planes (Prepare), in the octree's frame.
  vtkHybridOctreeBridge::RegionDescription Region;
  /// The frame's gradient opacity (Prepare), VTK's points.
  std::vector<double> GradientOpacity;
  /// The property's 2D transfer function in TF_2D mode (Prepare), and its texture.
  vtkHybridOctreeTransfer2D Transfer2D;
  /// The frame's volumetric scattering (Prepare), and its shadow volume's texture.
  vtkHybridOctreeBridge::ScatteringDescription ScatteringParameters;
  vtkHybridOctreeScattering Scattering;
  /// Whether the resident brick textures carry gradient borders.
  bool BorderedTextures = false;
  /// The isosurface values of the Isosurface blend mode (the selection's).
  std::vector<double> Isosurfaces;
  /// Whether the resident coarse brick textures keep their peaks (MIP or MinIP).
  bool PooledTextures = false;
  // Interactive frames' sampling, from the times of the frames before.
  vtkHybridOctreeInteractiveReduction Reduction;
  // Frames within a time (TargetFrameMilliseconds): the cost models of
  // still (0) and interactive (1) frames, made at their first timed frame
  // and kept across octrees (they model the machine), whether each asked
  // for a new selection, and this frame's target (0: untimed) and frame.
  std::unique_ptr<vtkHybridOctreeBridge::FrameTimer> Timers[2];
  bool TimerAsks[2] = { false, false };
  double FrameTargetMs = 0.0;
  // What a timed frame spends outside its drawing: the renderer's frame
  // less this mapper's drawing and selection, smoothed over frames (-1:
  // not measured yet); the last timed frame's drawing and selection, until
  // the next frame reads the renderer's time of it; and each kind's last
  // time-budgeted search.
  double OverheadMs = -1.0;
  bool OverheadPending = false;
  double PendingDrawMs = 0.0;
  double PendingSelectMs = 0.0;
  double SearchMs[2] = { 0.0, 0.0 };
  // Whether this timed frame draws as an interactive frame does, and the
  // target a still frame's exact drawing was found below the fastest frame
  // for (0: none): the still frames of that target draw that way.
  bool FrameFast = false;
  double FastTargetMs = 0.0;
  vtkHybridOctreeBridge::TimedFrameDescription TimedFrame;

  /// Drops the octree and what was made from it (both selections, the
  /// interactive frames' times, the isosurface and the points): a new
  /// octree is about to be built.
  void ForgetOctree()
  {
    this->Still.Selected.reset();
    this->Moving.Selected.reset();
    this->Reduction.Reset();
    this->HasIso = false;
    this->HasPoints = false;
    this->Octree.reset();
  }
};

#endif
