// vtkHybridOctreeVolumeMapper: the texture-budget selections of still and interactive frames,
// made again only when their inputs change (vtkHybridOctreeVolumeMapperInternals.h).
#include "vtkHybridOctreeVolumeMapper.h"

#include "vtkHybridOctreeBridge.h"
#include "vtkHybridOctreeImageInput.h"
#include "vtkHybridOctreeSlice.h"
#include "vtkHybridOctreeVolumeMapperInternals.h"

#include "vtkContourValues.h"
#include "vtkPlane.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace
{
using namespace vtkHybridOctreeBridge;
using vtkHybridOctreeImageInput::ByteCount;
using vtkHybridOctreeImageInput::Bytes;
using vtkHybridOctreeVolumeMapperParts::GradientOpacityPoints;
using vtkHybridOctreeVolumeMapperParts::TransformPoint;

// The least share of a frame-time target the drawing aims at, whatever the
// rest of the frame spends.
constexpr double MIN_DRAW_TARGET_SHARE = 0.1;

// The ratio between two steps of the time a timed frame spends outside its
// drawing that select again (a quarter either way).
constexpr double OVERHEAD_STEP = 1.25;

} // namespace

SelectDescription vtkHybridOctreeVolumeMapper::DescribeSelection(
  vtkVolumeProperty* property, double budgetMB, std::vector<double>& key) const
{
  vtkInternals& in = *this->Internals;
  SelectDescription select;
  select.BudgetBytes = static_cast<std::size_t>(budgetMB * 1.0e6);
  select.Tolerance = this->ErrorTolerance;
  select.OpacityPoints = vtkHybridOctreeBridge::OpacityPoints(property->GetScalarOpacity(0));
  select.HasRoi = this->UseRoi;
  TransformPoint(in.ModelInverse, this->RoiCenter, select.RoiCenter);
  select.RoiRadius = this->RoiRadius;
  select.HasIsovalue = this->ShowSurface;
  select.Isovalue = this->Isovalue;
  // The blend modes the bridge draws (the others are warned about and drawn Composite).
  const int mode = this->BlendMode;
  select.BlendMode = mode >= COMPOSITE_BLEND && mode <= SLICE_BLEND ? mode : COMPOSITE_BLEND;
  // Slice on the property's vtkPlane, into the octree's frame as VTK takes
  // it; without a valid one (warned about) Composite.
  std::string sliceProblem;
  if (select.BlendMode == SLICE_BLEND &&
    !vtkHybridOctreeSlice::Describe(property, in.ModelInverse, select.SlicePlane, sliceProblem))
  {
    select.BlendMode = COMPOSITE_BLEND;
  }
  if (select.BlendMode == ISOSURFACE_BLEND)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    for (int i = 0; values && i < values->GetNumberOfContours(); ++i)
    {
      select.IsosurfaceValues.push_back(values->GetValue(i));
    }
  }
  select.AverageRange[0] = this->AverageIPScalarRange[0];
  select.AverageRange[1] = this->AverageIPScalarRange[1];
  select.TexelFormat = this->TexelFormat;
  // Shaded: the bricks' gradient borders count in the budget (Composite and
  // Isosurface only; Isosurface always has them).
  select.GradientBorder = property->GetShade(0) != 0 &&
    (select.BlendMode == COMPOSITE_BLEND || select.BlendMode == ISOSURFACE_BLEND ||
      select.BlendMode == SLICE_BLEND);
  select.GradientOpacityPoints = GradientOpacityPoints(property);
  select.Region = in.Region;
  // The 2D transfer function classifies under Composite only (VTK's TF_2D
  // mode); its texels are copied in only when a selection is made
  // (UpdateSelection): the key names them.
  if (select.BlendMode == COMPOSITE_BLEND)
  {
    in.Transfer2D.Describe(select.Transfer2DSize, nullptr, select.Transfer2DRange);
  }
  key = { static_cast<double>(select.BudgetBytes), select.Tolerance, select.HasRoi ? 1.0 : 0.0,
    select.RoiCenter[0], select.RoiCenter[1], select.RoiCenter[2], select.RoiRadius,
    select.HasIsovalue ? 1.0 : 0.0, select.Isovalue,
    in.HasPoints ? static_cast<double>(in.PointsTime.GetMTime()) : -1.0,
    select.GradientBorder ? 1.0 : 0.0, static_cast<double>(select.BlendMode),
    select.AverageRange[0], select.AverageRange[1], select.Region.Cropping ? 1.0 : 0.0,
    static_cast<double>(select.Region.CroppingFlags), static_cast<double>(select.TexelFormat) };
  key.insert(key.end(), select.Region.CroppingPlanes, select.Region.CroppingPlanes + 6);
  key.push_back(static_cast<double>(select.Region.ClippingPlanes.size()));
  key.insert(key.end(), select.Region.ClippingPlanes.begin(), select.Region.ClippingPlanes.end());
  key.push_back(static_cast<double>(select.IsosurfaceValues.size()));
  key.insert(key.end(), select.IsosurfaceValues.begin(), select.IsosurfaceValues.end());
  key.insert(key.end(), select.SlicePlane, select.SlicePlane + 6);
  key.push_back(static_cast<double>(select.GradientOpacityPoints.size()));
  key.insert(key.end(), select.GradientOpacityPoints.begin(), select.GradientOpacityPoints.end());
  const std::vector<double> transfer2D = in.Transfer2D.Key();
  key.push_back(select.Transfer2DSize[0] > 0 ? 1.0 : 0.0);
  key.insert(key.end(), transfer2D.begin(), transfer2D.end());
  // The view's settings; its camera and viewport through IsViewCurrent() only.
  select.View = in.View;
  key.insert(key.end(),
    { static_cast<double>(select.View.ViewSelection), select.View.MinTexelPixels,
      select.View.SurfaceOpacity, select.View.OpacityUnitDistance });
  return select;
}

bool vtkHybridOctreeVolumeMapper::DescribeView(vtkRenderer* ren, vtkVolumeProperty* property)
{
  vtkInternals& in = *this->Internals;
  if (!(this->ViewChangeDegrees >= 0.0))
  {
    vtkErrorMacro("ViewChangeDegrees " << this->ViewChangeDegrees
                                       << ": give the degrees the view may move before a still "
                                          "frame selects again, a number >= 0 (default 5)");
    return false;
  }
  ViewDescription& view = in.View;
  view.ViewSelection = this->ViewSelection;
  if (in.Store &&
    (view.ViewSelection == VIEW_SELECTION_VISIBILITY || view.ViewSelection == VIEW_SELECTION_BOTH))
  {
    // The visibility estimate reads every sample: a store weighs by screen space.
    view.ViewSelection = VIEW_SELECTION_SCREEN;
    if (!in.StoreViewWarned)
    {
      in.StoreViewWarned = true;
      vtkWarningMacro("view selection " << this->ViewSelection
                                        << " weighs nodes by the opacity in front of them, "
                                           "estimated from every sample: a volume drawn from "
                                           "the store '"
                                        << in.StorePath << "' is weighed by screen space alone");
    }
  }
  view.Camera = this->ModelCamera(ren);
  const int* size = ren->GetSize();
  view.Viewport[0] = static_cast<std::size_t>(std::max(size[0], 0));
  view.Viewport[1] = static_cast<std::size_t>(std::max(size[1], 0));
  view.MinTexelPixels = this->MinTexelPixels;
  view.SurfaceOpacity = this->ShowSurface ? this->SurfaceOpacity : 0.0;
  // The table's opacities are VTK's per ScalarOpacityUnitDistance, or per
  // the smallest spacing without one (UpdateTransferFunction()).
  const double unit = property->GetScalarOpacityUnitDistance(0);
  const double* spacing = in.Grid.Spacing;
  view.OpacityUnitDistance = unit > 0.0 ? unit : std::min({ spacing[0], spacing[1], spacing[2] });
  for (int k = 0; k < 3; ++k)
  {
    in.Centre[k] =
      in.Grid.Origin[k] + 0.5 * spacing[k] * (static_cast<double>(in.Grid.Dims[k]) - 1.0);
  }
  return true;
}

bool vtkHybridOctreeVolumeMapper::IsViewCurrent(
  const ViewDescription& made, const std::string& applied) const
{
  const vtkInternals& in = *this->Internals;
  if (applied == "data")
  {
    return true;
  }
  if (made.Viewport[0] != in.View.Viewport[0] || made.Viewport[1] != in.View.Viewport[1])
  {
    return false;
  }
  double degrees = 0.0;
  std::string error;
  // A camera the bridge refuses selects again, which reports it.
  return vtkHybridOctreeBridge::ViewChangeDegrees(
           made.Camera, in.View.Camera, in.Centre, degrees, error) &&
    degrees <= this->ViewChangeDegrees;
}

bool vtkHybridOctreeVolumeMapper::IsStillSelectionCurrent(
  const SelectDescription& still, const std::vector<double>& key) const
{
  const vtkInternals& in = *this->Internals;
  return in.Still.Selected && in.Still.Time > in.OctreeTime && in.Still.Key == key &&
    in.Still.Opacity == still.OpacityPoints;
}

bool vtkHybridOctreeVolumeMapper::UpdateSelection(vtkVolumeProperty* property, bool interactive)
{
  vtkInternals& in = *this->Internals;
  const double budgetMB =
    interactive ? std::min(this->InteractiveBudgetMB, this->BudgetMB) : this->BudgetMB;
  if (!(budgetMB > 0.0))
  {
    vtkErrorMacro("the texture budget is 0 MB: set BudgetMB (and InteractiveBudgetMB) above 0");
    return false;
  }
  vtkInternals::SelectionSlot& slot = interactive ? in.Moving : in.Still;
  in.Frame = &slot;
  std::vector<double> key;
  SelectDescription select = this->DescribeSelection(property, budgetMB, key);
  // Interactive frames keep their selection while the view moves (it is
  // made once per change of its other inputs); still ones select again
  // when the view moved past ViewChangeDegrees.
  if (slot.Selected && slot.Time > in.OctreeTime && slot.Key == key &&
    slot.Opacity == select.OpacityPoints &&
    (interactive || this->IsViewCurrent(slot.View, slot.Summary.ViewSelection)))
  {
    return true;
  }
  return this->Reselect(interactive, select, key, nullptr);
}

bool vtkHybridOctreeVolumeMapper::Reselect(bool interactive, SelectDescription& select,
  const std::vector<double>& key, vtkHybridOctreeBridge::FrameTimer* timer)
{
  vtkInternals& in = *this->Internals;
  vtkInternals::SelectionSlot& slot = interactive ? in.Moving : in.Still;
  if (select.Transfer2DSize[0] > 0)
  {
    in.Transfer2D.Describe(select.Transfer2DSize, &select.Transfer2DRGBA, select.Transfer2DRange);
  }
  std::string error;
  const auto start = std::chrono::steady_clock::now();
  if (!in.Store &&
    !in.Octree->PrepareView(Bytes(in.Scalars), ByteCount(in.Scalars), in.Grid, select, error))
  {
    slot.Selected.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  slot.Selected = timer ? timer->Select(*in.Octree, select, in.TimedFrame, error)
                        : in.Octree->Select(select, error);
  if (!slot.Selected || !slot.Selected->GetSummary(slot.Summary, error))
  {
    slot.Selected.reset();
    vtkErrorMacro(<< error);
    return false;
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  this->LastSelectMilliseconds = 1.0e3 * elapsed.count();
  this->LastReselected = true;
  slot.Time.Modified();
  slot.Key = key;
  slot.Opacity = select.OpacityPoints;
  slot.View = select.View;
  return true;
}

bool vtkHybridOctreeVolumeMapper::FrameTarget(
  vtkRenderer* ren, vtkVolume* vol, double& targetMs) const
{
  targetMs = 0.0;
  const double target = this->TargetFrameMilliseconds;
  if (target == 0.0)
  {
    return true;
  }
  if (target == TARGET_FRAME_WINDOW)
  {
    // Interactive frames: the mapper's share of the volume's allocated
    // render time (1 / desired update rate / renderers / props), as the
    // sampling ladder keeps to; still frames draw the full budget.
    const double allocated = vol ? vol->GetAllocatedRenderTime() : 0.0;
    if (this->IsInteractive(ren) && allocated > 0.0 && std::isfinite(allocated))
    {
      targetMs = std::min(
        1.0e3 * vtkHybridOctreeInteractiveReduction::GetTargetShare() * allocated, 600000.0);
    }
    return true;
  }
  if (!(target > 0.0 && target <= 600000.0))
  {
    vtkErrorMacro("TargetFrameMilliseconds "
      << target
      << ": give the milliseconds a frame may take to draw (above 0, at most 600000), "
         "0 for no target, or -1 for interactive frames within the window's desired update rate");
    return false;
  }
  targetMs = target;
  return true;
}

void vtkHybridOctreeVolumeMapper::ObserveFrameOverhead(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  if (!in.OverheadPending || !ren)
  {
    return;
  }
  in.OverheadPending = false;
  // The renderer's frame holds this mapper's Render(): what is left of it
  // is the other props, the renderer's passes and this mapper's own
  // preparation and DrawList. Each frame's share is smoothed into the
  // estimate, half the last frame's and half the frames' before.
  const double frameMs = 1.0e3 * ren->GetLastRenderTimeInSeconds();
  if (!(std::isfinite(frameMs) && frameMs > 0.0))
  {
    return;
  }
  const double sample = std::max(frameMs - in.PendingDrawMs - in.PendingSelectMs, 0.0);
  in.OverheadMs = in.OverheadMs < 0.0 ? sample : 0.5 * (in.OverheadMs + sample);
}

bool vtkHybridOctreeVolumeMapper::UpdateTimedSelection(
  vtkVolumeProperty* property, bool fast, bool followView, double targetMs)
{
  vtkInternals& in = *this->Internals;
  if (!(this->BudgetMB > 0.0))
  {
    vtkErrorMacro("the texture budget is 0 MB: set BudgetMB above 0");
    return false;
  }
  const int which = fast ? 1 : 0;
  vtkInternals::SelectionSlot& slot = fast ? in.Moving : in.Still;
  in.Frame = &slot;
  std::vector<double> key;
  SelectDescription select = this->DescribeSelection(property, this->BudgetMB, key);
  // The frame the cost model predicts: this frame's camera, viewport and
  // effects, as GetFrameDrawList() plans them.
  TimedFrameDescription& frame = in.TimedFrame;
  frame.Camera = in.View.Camera;
  frame.Width = in.View.Viewport[0];
  frame.Height = in.View.Viewport[1];
  frame.SurfaceOpacity = in.View.SurfaceOpacity;
  frame.Shading = in.Shading;
  frame.GradientOpacityPoints = in.GradientOpacity;
  frame.Jittering = this->UseJittering != 0;
  frame.SampleDistance = this->ActualSampleDistance();
  frame.Scattering = in.ScatteringParameters;
  // The drawing's share of a target given in milliseconds (the window's
  // share is the drawing's already): less the frame's time outside the
  // drawing, and less a search like the last one (this frame searches when
  // it selects). At least a tenth of the target: a target the rest of the
  // frame already spends is below the fastest frame, and its outcome says so.
  const bool whole = this->TargetFrameMilliseconds > 0.0;
  const double overhead = whole ? std::max(in.OverheadMs, 0.0) : 0.0;
  const double search = whole ? in.SearchMs[which] : 0.0;
  const double drawTarget =
    std::max(targetMs - overhead - search, MIN_DRAW_TARGET_SHARE * targetMs);
  frame.TargetMilliseconds = drawTarget;
  // A timed selection is made again when the target, the viewport or
  // another input changed, when the time outside the drawing moved by a
  // quarter (its step on a log scale), when its cost model asks (a warm-up
  // frame, the model fitted, its correction moved), and for a still frame
  // when the view moved past ViewChangeDegrees.
  const double overheadStep =
    overhead > 1.0 ? std::round(std::log(overhead) / std::log(OVERHEAD_STEP)) : 0.0;
  key.insert(key.end(),
    { targetMs, static_cast<double>(frame.Width), static_cast<double>(frame.Height),
      overheadStep });
  if (in.Timers[which] && !in.TimerAsks[which] && slot.Selected && slot.Time > in.OctreeTime &&
    slot.Key == key && slot.Opacity == select.OpacityPoints &&
    (!followView || this->IsViewCurrent(slot.View, slot.Summary.ViewSelection)))
  {
    return true;
  }
  if (!in.Timers[which])
  {
    in.Timers[which].reset(new vtkHybridOctreeBridge::FrameTimer());
  }
  in.TimerAsks[which] = false;
  if (!this->Reselect(fast, select, key, in.Timers[which].get()))
  {
    return false;
  }
  in.SearchMs[which] = this->LastSelectMilliseconds;
  return true;
}

void vtkHybridOctreeVolumeMapper::ObserveTimedFrame(bool interactive, double drawMs)
{
  vtkInternals& in = *this->Internals;
  const int which = interactive ? 1 : 0;
  if (!(in.FrameTargetMs > 0.0) || !in.Timers[which] || !in.Frame->Selected)
  {
    return;
  }
  bool again = false;
  std::string error;
  if (!in.Timers[which]->Observe(*in.Frame->Selected, *in.Octree, in.TimedFrame,
        static_cast<std::size_t>(std::max<vtkTypeInt64>(this->LastUploadedBytes, 0)), drawMs, again,
        error))
  {
    // The frame drew; only its time is not learnt from.
    vtkWarningMacro("the frame's time was not fed to the cost model: " << error);
    return;
  }
  in.TimerAsks[which] = again;
  const TimedSummary summary = in.Timers[which]->GetSummary();
  this->LastTargetMilliseconds = in.FrameTargetMs;
  this->LastDrawTargetMilliseconds = summary.TargetMilliseconds;
  this->LastPredictedMilliseconds = summary.PredictedMilliseconds;
  this->LastTimeOutcome = summary.Outcome;
}

bool vtkHybridOctreeVolumeMapper::ChooseSelection(vtkRenderer* ren, vtkVolume* vol)
{
  vtkVolumeProperty* property = vol->GetProperty();
  const bool interactive = this->IsInteractive(ren);
  // The frame's isosurface values (the Isosurface blend mode), whichever
  // selection it draws: every selection's key holds them.
  std::vector<double> key;
  const SelectDescription still = this->DescribeSelection(property, this->BudgetMB, key);
  this->Internals->Isosurfaces = still.IsosurfaceValues;
  double targetMs = 0.0;
  if (!this->FrameTarget(ren, vol, targetMs))
  {
    return false;
  }
  this->Internals->FrameTargetMs = targetMs;
  if (targetMs > 0.0)
  {
    // Drawn as an interactive frame is: an interactive frame, or a still
    // one whose exact drawing cannot meet this target.
    this->Internals->FrameFast = interactive || this->Internals->FastTargetMs == targetMs;
    return this->UpdateTimedSelection(property, this->Internals->FrameFast, !interactive, targetMs);
  }
  if (interactive && this->IsStillSelectionCurrent(still, key))
  {
    this->Internals->Frame = &this->Internals->Still;
    return true;
  }
  return this->UpdateSelection(property, interactive);
}
