/**
 * @file   TestHybridOctreeFilterProgress.cxx
 * @brief  Progress events and abort of vtkHybridOctreeFilter.
 *
 *   HybridOctreeCxxTests TestHybridOctreeFilterProgress <scenario>
 *
 * progress: Update of a 128^3 wavelet (32768 leaf bricks of 4 cells: 128
 *   chunks) fires ProgressEvent many times, increasing, the build's reports
 *   within [0, 0.8], the last one 1.
 * abort: an observer sets AbortExecute at the first progress event (the
 *   executive's 0 before the request). The build stops at its first report
 *   (one chunk of 256 leaf bricks), and the request returns with both outputs empty, a
 *   warning naming the cancel and no error; clearing the flag, Modified()
 *   and Update build the octree and give the same output as a filter that
 *   was never interrupted.
 */
#include "HybridOctreeTestUtilities.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkHybridOctreeFilter.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// Records the progress values of ProgressEvent; optionally aborts at the first.
class ProgressRecorder : public vtkCommand
{
public:
  static ProgressRecorder* New() { return new ProgressRecorder; }

  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    this->Values.push_back(*static_cast<double*>(callData));
    if (this->AbortAtFirst && this->Values.size() == 1)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  }

  std::vector<double> Values;
  bool AbortAtFirst = false;
};

void Configure(vtkHybridOctreeFilter* filter, vtkAlgorithm* source)
{
  filter->SetInputConnection(source->GetOutputPort());
  filter->SetLeafSize(4);
  filter->SetErrorTolerance(0.05);
  filter->SetIsovalue(150.0);
  filter->SetMeasureSurfaceDistance(0);
}
}

int TestHybridOctreeFilterProgress(int argc, char* argv[])
{
  const std::string scenario = argc > 1 ? argv[1] : "";
  if (scenario != "progress" && scenario != "abort")
  {
    std::cerr << "unknown scenario '" << scenario << "'; known: progress abort\n";
    return EXIT_FAILURE;
  }
  Checker t;
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 127, 0, 127, 0, 127);
  wavelet->Update();

  vtkNew<vtkHybridOctreeFilter> filter;
  Configure(filter, wavelet);
  vtkNew<ProgressRecorder> progress;
  progress->AbortAtFirst = scenario == "abort";
  filter->AddObserver(vtkCommand::ProgressEvent, progress);
  vtkNew<ErrorRecorder> messages;
  messages->Watch(filter);
  messages->Watch(filter->GetExecutive());
  filter->Update();
  const std::vector<double>& p = progress->Values;

  if (scenario == "progress")
  {
    t.Check(p.size() >= 100, "at least 100 progress events: " + std::to_string(p.size()));
    bool increasing = true;
    std::size_t build = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      increasing = increasing && (i == 0 || p[i] >= p[i - 1]);
      build += p[i] > 0.0 && p[i] <= 0.8 ? 1 : 0;
    }
    t.Check(increasing, "progress never goes back");
    t.Check(build >= 100, "the build reports within (0, 0.8]: " + std::to_string(build));
    t.Check(!p.empty() && p.back() == 1.0, "the last progress is 1");
    t.Check(messages->Errors.empty(), "no error:\n" + messages->AllErrors());
    t.Check(filter->GetOutput(0)->GetNumberOfPoints() > 0, "boxes");
    t.Check(filter->GetOutput(1)->GetNumberOfPolys() > 0, "surface");
    return t.Result();
  }

  // abort
  std::cout << "progress events:";
  for (double v : p)
  {
    std::cout << " " << v;
  }
  std::cout << "\n";
  // The executive reports 0 before and 1 after the request; the build's own
  // reports lie strictly between.
  std::vector<double> build;
  for (double v : p)
  {
    if (v > 0.0 && v < 1.0)
    {
      build.push_back(v);
    }
  }
  t.Check(build.size() == 1,
    "the build stops at its first report after the abort: " + std::to_string(build.size()) +
      " reports");
  t.Check(!build.empty() && build.back() < 0.1, "it stopped early");
  t.Check(messages->Errors.empty(), "a cancel is not an error:\n" + messages->AllErrors());
  bool warned = false;
  for (const std::string& w : messages->Warnings)
  {
    warned = warned || w.find("cancelled") != std::string::npos;
  }
  t.Check(warned, "a warning names the cancel");
  for (int port = 0; port < 2; ++port)
  {
    vtkPolyData* out = filter->GetOutput(port);
    t.Check(out->GetNumberOfPoints() == 0 && out->GetNumberOfCells() == 0 &&
        out->GetFieldData()->GetNumberOfArrays() == 0,
      "port " + std::to_string(port) + " empty after the cancel");
  }
  t.Check(filter->GetOctreeBuildCount() == 0, "no octree kept from the cancelled build");

  // Abort cleared and the filter modified (VTK's convention after an abort):
  // the next Update builds, and gives what an uninterrupted filter gives.
  progress->AbortAtFirst = false;
  filter->SetAbortExecute(0);
  filter->Modified();
  messages->Clear();
  filter->Update();
  t.Check(messages->Errors.empty(), "the update after the cancel works:\n" + messages->AllErrors());
  t.Check(filter->GetOctreeBuildCount() == 1, "the octree is built on the next Update");
  vtkNew<vtkHybridOctreeFilter> reference;
  Configure(reference, wavelet);
  reference->Update();
  for (int port = 0; port < 2; ++port)
  {
    vtkPolyData* out = filter->GetOutput(port);
    vtkPolyData* ref = reference->GetOutput(port);
    t.Check(out->GetNumberOfPoints() > 0 && out->GetNumberOfPoints() == ref->GetNumberOfPoints() &&
        out->GetNumberOfCells() == ref->GetNumberOfCells(),
      "port " + std::to_string(port) + ": same output as an uninterrupted filter (" +
        std::to_string(out->GetNumberOfCells()) + " vs " + std::to_string(ref->GetNumberOfCells()) +
        " cells)");
  }
  // Up to date again: a further Update does not rebuild.
  filter->Update();
  t.Check(filter->GetOctreeBuildCount() == 1, "no rebuild once up to date");
  return t.Result();
}
