#include "vtkHybridOctreeInteractiveReduction.h"

#include <algorithm>
#include <cmath>

namespace
{
constexpr vtkHybridOctreeInteractiveReduction::Level Ladder[] = { { 1.0, 1 }, { 1.5, 1 },
  { 2.0, 1 }, { 3.0, 1 }, { 4.0, 1 }, { 4.0, 2 }, { 6.0, 2 } };
constexpr int Levels = vtkHybridOctreeInteractiveReduction::NumberOfLevels;
static_assert(sizeof(Ladder) / sizeof(Ladder[0]) == Levels, "one ladder entry per level");
/// The share of the sampling cost spent per fragment rather than per sample.
constexpr double FragmentShare = 0.5;
/// The share of the allocated time a frame aims at: the rest of the frame
/// (the renderer's passes before the volume, FXAA, the swap) is not in the
/// mapper's time (17-20 ms of a 66.7 ms allocation in a ParaView render
/// view at 1130x660, llvmpipe). Measured there against ParaView's Volume
/// (interactive frames of 48-65 ms): at 1/2 ours were 0.68-1.06x of its on
/// an MRI, at 0.4 0.61-0.63x (docs/BENCHMARKS.md).
constexpr double TargetShare = 0.4;
/// A finer level than the last recorded one must be predicted within this fraction of the target.
constexpr double Hysteresis = 0.8;
/// Records older than this many interactive frames are not used for the fixed cost.
constexpr unsigned long MaxAge = 16;
}

vtkHybridOctreeInteractiveReduction::Level vtkHybridOctreeInteractiveReduction::GetLevel(int level)
{
  return Ladder[std::min(std::max(level, 0), Levels - 1)];
}

double vtkHybridOctreeInteractiveReduction::GetTargetShare()
{
  return TargetShare;
}

double vtkHybridOctreeInteractiveReduction::GetCost(int level)
{
  const Level l = GetLevel(level);
  return (FragmentShare + (1.0 - FragmentShare) / l.SampleSpacing) /
    (l.ImageSampleDistance * l.ImageSampleDistance);
}

double vtkHybridOctreeInteractiveReduction::Predict(int level) const
{
  const Timing& last = this->Records[this->Last];
  // The latest record at another level, if recent: the two give the fixed cost.
  const Timing* other = nullptr;
  for (int l = 0; l < Levels; ++l)
  {
    const Timing& r = this->Records[l];
    if (l != this->Last && r.Frame > 0 && r.Frame + MaxAge >= last.Frame &&
      (!other || r.Frame > other->Frame))
    {
      other = &r;
    }
  }
  const double cost = GetCost(this->Last);
  double fixed = 0.0;
  double perCost = last.Seconds / cost;
  if (other)
  {
    const double otherCost = GetCost(static_cast<int>(other - this->Records));
    const double slope = (last.Seconds - other->Seconds) / (cost - otherCost);
    const double intercept = last.Seconds - slope * cost;
    if (slope > 0.0 && intercept >= 0.0)
    {
      fixed = intercept;
      perCost = slope;
    }
  }
  return fixed + perCost * GetCost(level);
}

int vtkHybridOctreeInteractiveReduction::Choose(double allocatedSeconds) const
{
  if (this->Frame == 0 || !(allocatedSeconds > 0.0) || !std::isfinite(allocatedSeconds))
  {
    return 0;
  }
  for (int level = 0; level < Levels; ++level)
  {
    const double limit = TargetShare * allocatedSeconds * (level < this->Last ? Hysteresis : 1.0);
    if (this->Predict(level) <= limit)
    {
      return level;
    }
  }
  return Levels - 1;
}

void vtkHybridOctreeInteractiveReduction::Record(int level, double seconds, bool interactive)
{
  if (!(seconds >= 0.0) || !std::isfinite(seconds) || (!interactive && this->HaveInteractive))
  {
    return;
  }
  if (!this->HaveInteractive)
  {
    // A still frame seeds the prediction until the first interactive frame replaces it.
    *this = vtkHybridOctreeInteractiveReduction();
  }
  this->Last = std::min(std::max(level, 0), Levels - 1);
  this->Records[this->Last] = { seconds, ++this->Frame };
  this->HaveInteractive = this->HaveInteractive || interactive;
}

void vtkHybridOctreeInteractiveReduction::Reset()
{
  *this = vtkHybridOctreeInteractiveReduction();
}
