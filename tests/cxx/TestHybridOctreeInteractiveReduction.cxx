/**
 * vtkHybridOctreeInteractiveReduction (private to the module, compiled into
 * this test): the level an interactive frame samples at, from recorded
 * frame times given by the test (no clock, no OpenGL).
 *
 *   ladder:     level 0 is full resolution; costs strictly decrease, image
 *               sample distances and sample spacings never get finer.
 *   choose:     nothing recorded or no allocated time: level 0; a still
 *               frame over the target seeds the finest level that fits;
 *               beyond the coarsest, the coarsest; 0.4 of the allocated
 *               time is the target.
 *   fixed_cost: two records at different levels give the fixed part of a
 *               frame's time, so a coarse record does not make finer
 *               levels look dearer than they are; hysteresis keeps a finer
 *               level out until it is predicted well within the target.
 *   still:      after an interactive record, still frames are ignored;
 *               Reset() forgets.
 */
#include "HybridOctreeTestUtilities.h"
#include "vtkHybridOctreeInteractiveReduction.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using Reduction = vtkHybridOctreeInteractiveReduction;
constexpr int Coarsest = Reduction::NumberOfLevels - 1;

int Ladder()
{
  Checker check;
  const Reduction::Level first = Reduction::GetLevel(0);
  check.Check(first.ImageSampleDistance == 1.0 && first.SampleSpacing == 1 &&
      std::fabs(Reduction::GetCost(0) - 1.0) < 1e-12,
    "level 0 is full resolution at cost 1");
  for (int l = 1; l < Reduction::NumberOfLevels; ++l)
  {
    const Reduction::Level a = Reduction::GetLevel(l - 1), b = Reduction::GetLevel(l);
    check.Check(Reduction::GetCost(l) < Reduction::GetCost(l - 1),
      "level " + std::to_string(l) + " costs less than the one before");
    check.Check(
      b.ImageSampleDistance >= a.ImageSampleDistance && b.SampleSpacing >= a.SampleSpacing,
      "level " + std::to_string(l) + " is nowhere finer");
    check.Check((b.SampleSpacing & (b.SampleSpacing - 1)) == 0, "sample spacing a power of two");
  }
  check.Check(Reduction::GetLevel(99).ImageSampleDistance ==
      Reduction::GetLevel(Coarsest).ImageSampleDistance,
    "levels beyond the ladder are clamped");
  return check.Result();
}

int Choose()
{
  Checker check;
  Reduction r;
  check.Check(r.Choose(0.05) == 0, "nothing recorded: level 0");
  r.Record(0, 0.2, false); // a still frame of 200 ms, 60 ms allocated
  check.Check(r.Choose(0.0) == 0 && r.Choose(-1.0) == 0, "no allocated time: level 0");
  const int level = r.Choose(0.06);
  std::cout << "a 200 ms still frame, 60 ms allocated: level " << level << "\n";
  check.Check(level > 0, "a frame over its time is coarser");
  check.Check(0.2 * Reduction::GetCost(level) <= 0.4 * 0.06,
    "the level chosen is predicted within 0.4 of the time");
  check.Check(0.2 * Reduction::GetCost(level - 1) > 0.4 * 0.06, "and the finer one is not");
  check.Check(r.Choose(1.0) == 0, "1 s allocated: level 0");
  check.Check(r.Choose(1.0e-6) == Coarsest, "1 microsecond allocated: the coarsest level");
  return check.Result();
}

int FixedCost()
{
  Checker check;
  // Frames of 20 ms fixed + 100 ms x cost.
  auto frame = [](int level) { return 0.020 + 0.100 * Reduction::GetCost(level); };
  Reduction r;
  r.Record(Coarsest, frame(Coarsest), true);
  r.Record(3, frame(3), true);
  for (int level = 0; level < Reduction::NumberOfLevels; ++level)
  {
    check.Check(std::fabs(r.Predict(level) - frame(level)) < 1e-9,
      "two records predict level " + std::to_string(level) + " exactly");
  }
  // 0.4 of 125 ms = 50 ms: within it level 2 (45 ms) but not 1 (64 ms);
  // finer than the last record (3) only within 4/5 of it, 40 ms: level 3.
  const double allocated = 0.125;
  check.Check(frame(2) <= 0.05 && frame(2) > 0.04 && frame(1) > 0.05, "the test's frame times");
  check.Check(r.Choose(allocated) == 3, "hysteresis: level 2 is not well within the target");
  r.Record(2, frame(2), true);
  check.Check(r.Choose(allocated) == 2, "recorded at level 2 and within the target: it stays");
  // Without the second record, the coarse one alone (ratio) makes finer levels dearer.
  Reduction one;
  one.Record(Coarsest, frame(Coarsest), true);
  check.Check(one.Predict(2) > frame(2), "one coarse record overestimates finer levels");
  // Records that give a negative fixed part fall back to the ratio of the last one.
  Reduction odd;
  odd.Record(Coarsest, 0.050, true);
  odd.Record(0, 0.040, true);
  check.Check(std::fabs(odd.Predict(1) - 0.040 * Reduction::GetCost(1)) < 1e-12,
    "inconsistent records: the last one's ratio");
  return check.Result();
}

int Still()
{
  Checker check;
  Reduction r;
  r.Record(4, 0.010, true);
  r.Record(0, 10.0, false); // a slow still frame after interactive ones
  check.Check(
    std::fabs(r.Predict(4) - 0.010) < 1e-12, "a still frame after an interactive one is ignored");
  r.Reset();
  check.Check(r.Choose(0.05) == 0, "Reset() forgets");
  r.Record(0, 1.0, false);
  r.Record(0, 0.01, false);
  check.Check(r.Choose(0.05) == 0, "the latest still frame seeds the prediction");
  return check.Result();
}
} // namespace

int TestHybridOctreeInteractiveReduction(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "ladder";
  if (scenario == "ladder")
  {
    return Ladder();
  }
  if (scenario == "choose")
  {
    return Choose();
  }
  if (scenario == "fixed_cost")
  {
    return FixedCost();
  }
  if (scenario == "still")
  {
    return Still();
  }
  std::cerr << "unknown scenario " << scenario << "\n";
  return 1;
}
