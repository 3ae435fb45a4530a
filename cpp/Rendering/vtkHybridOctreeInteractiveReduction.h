/**
 * @file   vtkHybridOctreeInteractiveReduction.h
 * @brief  How coarsely an interactive frame samples to keep to its allocated render time
 *         (private to the module).
 *
 * VTK and ParaView ask for an interactive frame through the render window's
 * desired update rate (vtkPVRenderView::InteractiveRender sets 5 frames a
 * second, vtkRenderWindowInteractor 15): vtkRenderer gives each prop the
 * allocated render time 1 / (rate x renderers) / props
 * (vtkProp::GetAllocatedRenderTime; 1/15 s for a volume in a ParaView render
 * view). vtkGPUVolumeRayCastMapper keeps to it with AutoAdjustSampleDistances:
 * a ReductionFactor from its last frame's time widens both the image sample
 * distance and the sample distance along the rays.
 *
 * This class does the same for vtkHybridOctreeVolumeMapper on a ladder of
 * levels (image sample distance s, sample spacing m d0), finest first:
 *
 *     level  0    1    2    3    4    5    6
 *     s      1    1.5  2    3    4    4    6
 *     m      1    1    1    1    1    2    2
 *
 * with the relative cost of a level `(a + (1 - a) / m) / s^2`: the
 * fragments of the bricks' boxes (a, the per-fragment set-up) and the
 * samples along the rays (1 - a, fewer by m), both 1 / s^2 of the pixels;
 * a = 1/2 (measured on llvmpipe: 1469 bricks of the 256^3 phantom at
 * 565x330, 96 ms at m = 1, 48 ms at m = 2, 41 ms at m = 4). The image
 * sample distance goes first: at equal time it loses less (RMSE to the
 * still picture, 1130x660 in ParaView: s = 4 costs 0.010 on an MRI and 0.030
 * on the 256^3 phantom, m = 2 alone 0.008 and 0.046; docs/BENCHMARKS.md).
 *
 * Choose() takes the finest level whose predicted time is within 0.4 of
 * the allocated time (the rest of the frame, the renderer's passes and the
 * swap, is not in the mapper's time; see TargetShare), a level finer than
 * the last one within 4/5 of that, so that the choice does not swing
 * between two levels. A frame's time is a fixed
 * part (one draw per brick, the DrawList, the blend over the window) and a
 * part proportional to the level's cost: from the last recorded frame and
 * the latest one at another level (of the last 16 frames),
 *
 *     t(level) = F + P cost(level)      (F >= 0, P > 0 through both records),
 *
 * or, with one record (or when the two do not give F >= 0 and P > 0),
 * F = 0, P = t / cost. Interactive frames record their own times; a still
 * frame's time seeds the prediction only before the first interactive
 * frame. Times are the caller's (no clock here): choices are a pure
 * function of the records.
 */
#ifndef vtkHybridOctreeInteractiveReduction_h
#define vtkHybridOctreeInteractiveReduction_h

class vtkHybridOctreeInteractiveReduction
{
public:
  struct Level
  {
    double ImageSampleDistance; ///< s: pixels per target texel along x and y
    int SampleSpacing;          ///< m: samples every max(d, m d0) along the rays
  };

  /// Levels of the ladder.
  static constexpr int NumberOfLevels = 7;
  /// Level `level` (clamped to the ladder).
  static Level GetLevel(int level);
  /// The relative cost of `level` (1 at level 0).
  static double GetCost(int level);

  /// The share of the allocated render time the mapper's drawing keeps to
  /// (the rest of a frame is not in its time; see Choose()).
  static double GetTargetShare();

  /// The level of the next interactive frame for `allocatedSeconds`: the
  /// finest predicted within it; 0 with nothing recorded or no positive time.
  int Choose(double allocatedSeconds) const;

  /// Records a frame drawn at `level` in `seconds`.
  void Record(int level, double seconds, bool interactive);

  /// Forgets every record (a new window, new data).
  void Reset();

  /// The predicted time of `level` from the records (seconds; something recorded).
  double Predict(int level) const;

private:
  struct Timing
  {
    double Seconds = 0.0;
    unsigned long Frame = 0; ///< 0: none
  };
  Timing Records[NumberOfLevels];
  int Last = 0;            ///< the level recorded last
  unsigned long Frame = 0; ///< records made (0: none)
  bool HaveInteractive = false;
};

#endif
