/**
 * vtkHybridOctreeZarrReader and vtkHybridOctreeVolumeMapper drawing from an
 * OME-Zarr store written by `hybrid-octree convert --dataset shepp-logan
 * --size 64` (the CTest fixture; argv[2] is its folder), under Xvfb.
 *
 *   levels: MaximumMegabytes large reads level 0 (64^3, the store's spacing
 *           and origin); 0.2 MB reads level 1 (33^3 f32 = 0.14 MB; level 0
 *           is 1.05 MB), spacing doubled, the same origin, its samples those
 *           of level 0 at min(2 i, 63) (spot checks, the clamped last plane
 *           included); the field data names the store and its full
 *           resolution; too small a limit is an error.
 *   render: the mapper given the light level-1 image draws from the store;
 *           the same mapper settings on level 0 read whole into memory (the
 *           store's field data removed) draw the same bricks and the same
 *           picture: RGB RMSE <= 1e-6 (they are identical), unshaded and
 *           shaded (the gradient border read from the store); GetBounds()
 *           is the full volume's, not the light image's.
 *   bad:    a missing folder, a folder that is no image, a damaged zarr.json
 *           and a truncated shard: the reader reports a clear vtkErrorMacro,
 *           the request fails; a deleted shard of level 0 (Zarr reads a
 *           missing chunk as the fill value): the mapper drawing level 0's
 *           bricks finds samples outside the stored octree's ranges and
 *           reports it, nothing drawn; nothing crashes.
 */
#include "HybridOctreeMapperScene.h"
#include "HybridOctreeTestUtilities.h"
#include "vtkHybridOctreeStoreFieldData.h"
#include "vtkHybridOctreeZarrReader.h"

#include "vtkAutoInit.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

VTK_MODULE_INIT(vtkRenderingOpenGL2);

namespace
{
using namespace MapperScene;
namespace fs = std::filesystem;

/// A reader of `path` at `megabytes`, watched by `errors`, updated; its success.
bool Read(vtkHybridOctreeZarrReader* reader, const std::string& path, double megabytes,
  ErrorRecorder* errors)
{
  errors->Watch(reader);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(path.c_str());
  reader->SetMaximumMegabytes(megabytes);
  return reader->GetExecutive()->Update() == 1;
}

double At(vtkImageData* image, int i, int j, int k)
{
  return image->GetPointData()->GetScalars()->GetComponent(
    image->ComputePointId(std::array<int, 3>{ i, j, k }.data()), 0);
}

int Levels(const std::string& store)
{
  Checker check;
  vtkNew<ErrorRecorder> errors;
  vtkNew<vtkHybridOctreeZarrReader> full;
  check.Check(Read(full, store, 1000.0, errors), "level 0 read:\n" + errors->AllErrors());
  vtkNew<vtkHybridOctreeZarrReader> light;
  check.Check(Read(light, store, 0.2, errors), "level 1 read:\n" + errors->AllErrors());
  vtkImageData* a = full->GetOutput();
  vtkImageData* b = light->GetOutput();
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  std::cout << "levels " << full->GetLevel() << " " << light->GetLevel() << ", dims " << da[0]
            << " " << db[0] << ", spacing " << a->GetSpacing()[0] << " " << b->GetSpacing()[0]
            << "\n";
  check.Check(full->GetLevel() == 0 && light->GetLevel() == 1, "levels 0 and 1 chosen");
  check.Check(da[0] == 64 && da[1] == 64 && da[2] == 64, "level 0 is 64^3");
  check.Check(db[0] == 33 && db[1] == 33 && db[2] == 33, "level 1 is 33^3");
  for (int axis = 0; axis < 3; ++axis)
  {
    check.Check(b->GetSpacing()[axis] == 2.0 * a->GetSpacing()[axis], "level 1's spacing doubled");
    check.Check(b->GetOrigin()[axis] == a->GetOrigin()[axis], "the same origin");
  }
  vtkDataArray* scalars = b->GetPointData()->GetScalars();
  check.Check(scalars && scalars->GetName() &&
      std::string(scalars->GetName()) == a->GetPointData()->GetScalars()->GetName(),
    "point scalars named as the store's image");
  // Level 1 holds level 0 at min(2 i, 63): interior spot checks and the clamped last plane.
  const int probes[][3] = { { 16, 16, 16 }, { 10, 20, 12 }, { 5, 16, 25 }, { 32, 16, 16 },
    { 16, 32, 20 }, { 32, 32, 32 } };
  double signal = 0.0;
  for (const auto& p : probes)
  {
    const double want =
      At(a, std::min(2 * p[0], 63), std::min(2 * p[1], 63), std::min(2 * p[2], 63));
    const double got = At(b, p[0], p[1], p[2]);
    signal += std::fabs(want);
    check.Check(got == want, "level 1 sample equals level 0's at min(2 i, 63)");
  }
  check.Check(signal > 0.0, "the probes see the phantom");
  vtkHybridOctreeStoreFieldData::StoreReference ref;
  check.Check(vtkHybridOctreeStoreFieldData::Find(b->GetFieldData(), ref) && ref.Path == store &&
      ref.Dims[0] == 64 && ref.Spacing[0] == a->GetSpacing()[0],
    "the field data names the store and its full resolution");
  vtkNew<vtkHybridOctreeZarrReader> tiny;
  vtkNew<ErrorRecorder> tinyErrors;
  check.Check(!Read(tiny, store, 1e-9, tinyErrors), "no level fits 1e-9 MB");
  check.Check(tinyErrors->HasError("raise MaximumMegabytes"), "named:\n" + tinyErrors->AllErrors());
  return check.Result();
}

/// The picture, bricks and texture bytes of `image` through a fresh mapper.
struct Drawn
{
  std::vector<double> Rgb;
  int Bricks = 0;
  vtkTypeInt64 Bytes = 0;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  bool FromStore = false;
};

Drawn Draw(
  Checker& check, vtkImageData* image, const double centre[3], bool shade, ErrorRecorder* errors)
{
  vtkNew<vtkHybridOctreeVolumeMapper> mapper;
  errors->Watch(mapper);
  mapper->SetInputData(image);
  mapper->SetBudgetMB(0.25);
  mapper->SetViewSelectionToScreen();
  Stage stage;
  BuildStoreStage(stage, mapper, centre);
  stage.Property->SetShade(shade ? 1 : 0);
  stage.Window->Render();
  Drawn d;
  check.Check(mapper->GetLastRenderOK(), "drew:\n" + errors->AllErrors());
  d.Rgb = Grab(stage.Window);
  d.Bricks = mapper->GetLastBricks();
  d.Bytes = mapper->GetLastTextureBytes();
  mapper->GetBounds(d.Bounds);
  d.FromStore = mapper->GetLastDrawnFromStore();
  check.Check(NoGLError(stage.Window), "no OpenGL error left behind");
  return d;
}

int Render(const std::string& store)
{
  Checker check;
  vtkNew<ErrorRecorder> errors;
  vtkNew<vtkHybridOctreeZarrReader> light;
  check.Check(Read(light, store, 0.2, errors), "light read:\n" + errors->AllErrors());
  vtkNew<vtkHybridOctreeZarrReader> full;
  check.Check(Read(full, store, 1000.0, errors), "full read:\n" + errors->AllErrors());
  vtkNew<vtkImageData> memory;
  memory->ShallowCopy(full->GetOutput());
  memory->GetFieldData()->Initialize();
  for (bool shade : { false, true })
  {
    const Drawn disk = Draw(check, light->GetOutput(), memory->GetCenter(), shade, errors);
    const Drawn core = Draw(check, memory, memory->GetCenter(), shade, errors);
    const double rmse = Rmse(disk.Rgb, core.Rgb);
    std::cout << (shade ? "shaded" : "unshaded") << ": bricks " << disk.Bricks << " / "
              << core.Bricks << ", texture bytes " << disk.Bytes << " / " << core.Bytes
              << ", RGB RMSE store vs memory " << rmse << " (bound 1e-6), signal "
              << Signal(core.Rgb) << ", bounds x " << disk.Bounds[0] << ".." << disk.Bounds[1]
              << " (light image " << light->GetOutput()->GetBounds()[1] << ")\n";
    check.Check(disk.FromStore && !core.FromStore, "the light image drew from the store");
    check.Check(disk.Bricks == core.Bricks && disk.Bytes == core.Bytes, "the same selection");
    check.Check(disk.Bricks > 1 && disk.Bytes < 1048576, "a budget below the full volume");
    check.Check(Signal(core.Rgb) > 0.005, "the scene shows something");
    check.Check(rmse <= 1e-6, "the picture from the store is the picture in memory");
    for (int i = 0; i < 6; ++i)
    {
      check.Check(disk.Bounds[i] == core.Bounds[i], "GetBounds() is the full volume's");
    }
  }
  return check.Result();
}

/// A fresh copy of the store at `store` under `name` in the temporary folder.
std::string Copy(const std::string& store, const std::string& name)
{
  const fs::path to = fs::temp_directory_path() / ("ho-reader-test-" + name + ".ome.zarr");
  fs::remove_all(to);
  fs::copy(store, to, fs::copy_options::recursive);
  return to.string();
}

/// The reader of `path` fails with an error holding `fragment`.
void ExpectReadError(Checker& check, const std::string& what, const std::string& path,
  double megabytes, const std::string& fragment)
{
  vtkNew<ErrorRecorder> errors;
  vtkNew<vtkHybridOctreeZarrReader> reader;
  const bool ok = Read(reader, path, megabytes, errors);
  std::cout << what << ": " << errors->AllErrors();
  check.Check(!ok, what + ": the request fails");
  check.Check(errors->HasError(fragment), what + ": the error names '" + fragment + "'");
}

int Bad(const std::string& store)
{
  Checker check;
  ExpectReadError(
    check, "missing folder", "/nonexistent/ho-no-such.ome.zarr", 64.0, "not a folder");
  const fs::path empty = fs::temp_directory_path() / "ho-reader-test-empty.ome.zarr";
  fs::remove_all(empty);
  fs::create_directories(empty);
  ExpectReadError(check, "empty folder", empty.string(), 64.0, "metadata is missing");
  {
    const std::string damaged = Copy(store, "damaged-json");
    std::ofstream(fs::path(damaged) / "zarr.json", std::ios::trunc) << "{ \"zarr_format\": 3, ";
    ExpectReadError(check, "damaged zarr.json", damaged, 64.0, "error parsing metadata");
    fs::remove_all(damaged);
  }
  {
    const std::string truncated = Copy(store, "truncated-shard");
    const fs::path shard = LargestFile(fs::path(truncated) / "0");
    fs::resize_file(shard, fs::file_size(shard) / 2);
    ExpectReadError(
      check, "truncated shard " + shard.string(), truncated, 1000.0, "reading a subchunk");
    fs::remove_all(truncated);
  }
  {
    // A deleted shard of level 0 (Zarr reads a missing chunk as the fill
    // value, so level 0 itself reads as zeros there): the light level reads,
    // and drawing level 0's bricks finds samples outside the stored octree's
    // ranges and fails.
    const std::string deleted = Copy(store, "deleted-shard");
    const fs::path shard = LargestFile(fs::path(deleted) / "0");
    fs::remove(shard);
    vtkNew<ErrorRecorder> errors;
    vtkNew<vtkHybridOctreeZarrReader> light;
    check.Check(Read(light, deleted, 0.2, errors), "level 1 of a store missing a level-0 shard");
    vtkNew<vtkHybridOctreeVolumeMapper> mapper;
    errors->Watch(mapper);
    mapper->SetInputConnection(light->GetOutputPort());
    mapper->SetBudgetMB(64.0);
    mapper->SetViewSelectionToScreen();
    Stage stage;
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.1);
    opacity->AddPoint(1.0, 0.1);
    const double* c = light->GetOutput()->GetCenter();
    const double position[3] = { c[0] + 120.0, c[1] + 80.0, c[2] + 160.0 };
    stage.Build(mapper, color, opacity, position);
    stage.Renderer->GetActiveCamera()->SetFocalPoint(c[0], c[1], c[2]);
    stage.Renderer->ResetCameraClippingRange();
    stage.Window->Render();
    std::cout << "mapper over the deleted shard: " << errors->AllErrors();
    check.Check(!mapper->GetLastRenderOK(), "nothing drawn from a store missing a shard");
    check.Check(errors->HasError("missing"), "the mapper names the missing shard");
    check.Check(NoGLError(stage.Window), "no OpenGL error left behind");
    fs::remove_all(deleted);
  }
  fs::remove_all(empty);
  return check.Result();
}
}

int TestHybridOctreeZarrReader(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestHybridOctreeZarrReader levels|render|bad <store.ome.zarr>\n";
    return EXIT_FAILURE;
  }
  const std::string scenario = argv[1];
  const std::string store = argv[2];
  if (scenario == "levels")
  {
    return Levels(store);
  }
  if (scenario == "render")
  {
    return Render(store);
  }
  return Bad(store);
}
