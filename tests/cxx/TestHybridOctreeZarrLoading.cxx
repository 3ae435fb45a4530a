/**
 * vtkHybridOctreeVolumeMapper drawing an OME-Zarr store with
 * AsynchronousLoading (the CTest fixture's store, argv[2]), under Xvfb.
 *
 * async (unshaded, then shaded: the gradient border read too): the first
 * frame does not wait. It draws the bricks still loading by stand-ins
 * (LastBricksLoading > 0), merged into at most as many bricks as the
 * selection has, and is already nearer the whole picture than the empty
 * background is (RGB RMSE below the background's). The frames that follow
 * refine it until no brick is loading, and that picture is the one a mapper
 * without AsynchronousLoading draws in its first frame (both read as drawn,
 * without drawing again): RGB RMSE <= 1e-4 (the two place the same bricks
 * in other slots of their texture pages, and the linear filter's weights
 * round with a slot's position: ~1e-5), the same bricks, resident
 * textures within the budget; the bytes read from the store grow. Switched
 * off again, a moved camera's first frame has no stand-in.
 *
 * failure: a store whose level-0 shard is truncated: the background reads
 * of the full-resolution bricks fail, a later frame reports the read's
 * error (vtkErrorMacro, nothing drawn), nothing crashes or hangs.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"
#include "vtkHybridOctreeZarrReader.h"

#include "vtkAutoInit.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace
{
using namespace MapperScene;
namespace fs = std::filesystem;

/// Frames drawn at most while bricks load (5 ms apart: 10 s).
constexpr int MaxFrames = 2000;

/// The light level-1 image of `path` (0.2 MB), through `reader`; its success.
bool ReadLight(vtkHybridOctreeZarrReader* reader, const std::string& path, ErrorRecorder* errors)
{
  errors->Watch(reader);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(path.c_str());
  reader->SetMaximumMegabytes(0.2);
  return reader->GetExecutive()->Update() == 1;
}

/// A mapper drawing `image` from its store on `stage` at `budget` MB.
void Mount(Stage& stage, vtkHybridOctreeVolumeMapper* mapper, vtkImageData* image, double budget,
  ErrorRecorder* errors)
{
  errors->Watch(mapper);
  mapper->SetInputData(image);
  mapper->SetBudgetMB(budget);
  mapper->SetViewSelectionToScreen();
  BuildStoreStage(stage, mapper, image->GetCenter());
}

int Async(const std::string& store, bool shade)
{
  Checker check;
  vtkNew<ErrorRecorder> errors;
  vtkNew<vtkHybridOctreeZarrReader> light;
  check.Check(ReadLight(light, store, errors), "light read:\n" + errors->AllErrors());
  vtkImageData* image = light->GetOutput();

  // The whole picture: a mapper that reads every brick it draws.
  vtkNew<vtkHybridOctreeVolumeMapper> whole;
  Stage reference;
  Mount(reference, whole, image, 0.25, errors);
  reference.Property->SetShade(shade ? 1 : 0);
  // Its first frame as drawn (a first frame and the next one differ by a
  // unit of 8-bit colour in a few pixels, loading or not).
  reference.Window->SwapBuffersOff();
  reference.Window->Render();
  check.Check(whole->GetLastRenderOK() && whole->GetLastBricksLoading() == 0,
    "the synchronous frame drew all:\n" + errors->AllErrors());
  const std::vector<double> want = Grab(reference.Window, false);
  const int bricks = whole->GetLastBricks();

  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->AsynchronousLoadingOn();
  Stage stage;
  Mount(stage, mapper, image, 0.25, errors);
  stage.Property->SetShade(shade ? 1 : 0);
  // Each frame read as drawn: grabbing must not draw again (bricks arrive meanwhile).
  stage.Window->SwapBuffersOff();
  const auto start = std::chrono::steady_clock::now();
  stage.Window->Render();
  const std::chrono::duration<double> firstTime = std::chrono::steady_clock::now() - start;
  check.Check(mapper->GetLastRenderOK(), "the first frame drew:\n" + errors->AllErrors());
  const int loading = mapper->GetLastBricksLoading();
  const int firstBricks = mapper->GetLastBricks();
  const vtkTypeInt64 bytesFirst = mapper->GetLastStoreBytesRead();
  const std::vector<double> first = Grab(stage.Window, false);
  std::vector<double> empty(want.size());
  for (std::size_t i = 0; i < empty.size(); ++i)
  {
    empty[i] = Background[i % 3];
  }
  int frames = 1;
  while (mapper->GetLastBricksLoading() > 0 && mapper->GetLastRenderOK() && frames < MaxFrames)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    stage.Window->Render();
    ++frames;
  }
  const std::vector<double> last = Grab(stage.Window, false);
  const double rmseFirst = Rmse(first, want);
  const double rmseEmpty = Rmse(empty, want);
  const double rmseLast = Rmse(last, want);
  std::cout << (shade ? "shaded" : "unshaded") << ": first frame " << 1e3 * firstTime.count()
            << " ms: " << loading << " of " << mapper->GetLastBricks() << " bricks by stand-ins in "
            << firstBricks << " draws, RGB RMSE to the whole picture " << rmseFirst
            << " (the empty background's " << rmseEmpty << "); " << frames
            << " frames to load all; then RMSE " << rmseLast << " (bound 1e-4); store bytes read "
            << bytesFirst << " -> " << mapper->GetLastStoreBytesRead() << " (synchronous "
            << whole->GetLastStoreBytesRead() << "); bricks " << mapper->GetLastBricks() << " / "
            << whole->GetLastBricks() << ", texture bytes " << mapper->GetLastTextureBytes()
            << " / " << whole->GetLastTextureBytes() << "\n";
  check.Check(loading > 0 && firstBricks > 0 && firstBricks <= bricks,
    "the first frame drew the selection, some bricks by stand-ins merged into fewer draws");
  check.Check(Signal(want) > 0.005, "the scene shows something");
  check.Check(rmseFirst < rmseEmpty, "the stand-ins draw the volume: nearer it than nothing");
  check.Check(mapper->GetLastRenderOK() && mapper->GetLastBricksLoading() == 0,
    "every brick loaded within " + std::to_string(MaxFrames) + " frames:\n" + errors->AllErrors());
  check.Check(frames > 1, "it took later frames");
  check.Check(rmseLast <= 1e-4, "refined to the synchronous picture");
  check.Check(mapper->GetLastBricks() == whole->GetLastBricks(), "the same bricks");
  check.Check(mapper->GetLastTextureBytes() >= whole->GetLastTextureBytes() &&
      mapper->GetLastTextureBytes() <= 250000,
    "the selection's textures resident (and stand-ins kept within the budget)");
  check.Check(mapper->GetLastStoreBytesRead() > whole->GetLastStoreBytesRead(),
    "the store read the bricks and their stand-ins");

  // Off again: a new view's frame reads what it draws.
  mapper->AsynchronousLoadingOff();
  stage.Renderer->GetActiveCamera()->Azimuth(40.0);
  stage.Renderer->ResetCameraClippingRange();
  stage.Window->Render();
  check.Check(mapper->GetLastRenderOK() && mapper->GetLastBricksLoading() == 0,
    "off: no stand-ins:\n" + errors->AllErrors());
  check.Check(NoGLError(stage.Window), "no OpenGL error left behind");
  return check.Result();
}

int Failure(const std::string& store)
{
  Checker check;
  const fs::path copy = fs::temp_directory_path() / "ho-loading-test-truncated.ome.zarr";
  fs::remove_all(copy);
  fs::copy(store, copy, fs::copy_options::recursive);
  const fs::path shard = LargestFile(copy / "0");
  fs::resize_file(shard, fs::file_size(shard) / 2);
  vtkNew<ErrorRecorder> errors;
  vtkNew<vtkHybridOctreeZarrReader> light;
  check.Check(ReadLight(light, copy.string(), errors), "level 1 of a store with a truncated shard");
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  mapper->AsynchronousLoadingOn();
  Stage stage;
  // Every brick at full resolution: all read from level 0 in the background.
  Mount(stage, mapper, light->GetOutput(), 64.0, errors);
  int frames = 0;
  do
  {
    stage.Window->Render();
    ++frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (mapper->GetLastRenderOK() && frames < MaxFrames);
  std::cout << "truncated shard " << shard.string() << ": after " << frames
            << " frames: " << errors->AllErrors();
  check.Check(!mapper->GetLastRenderOK(), "a frame fails once a background read failed");
  check.Check(errors->HasError("reading a subchunk"), "the read's error is reported");
  check.Check(NoGLError(stage.Window), "no OpenGL error left behind");
  fs::remove_all(copy);
  return check.Result();
}
}

int TestHybridOctreeZarrLoading(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestHybridOctreeZarrLoading async|failure <store.ome.zarr>\n";
    return EXIT_FAILURE;
  }
  const std::string scenario = argv[1];
  if (scenario == "async")
  {
    return Async(argv[2], false) | Async(argv[2], true);
  }
  return Failure(argv[2]);
}
