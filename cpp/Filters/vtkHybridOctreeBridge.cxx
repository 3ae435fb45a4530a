/**
 * @file   vtkHybridOctreeBridge.cxx
 * @brief  The C++ half of the bridge: the only includer of the cxx header.
 *
 * Every call into Rust runs under `Guarded` (try/catch): the Rust side turns errors
 * and panics into `rust::Error`, which derives from std::exception.
 */
#include "vtkHybridOctreeBridge.h"

#include "hybrid-octree/src/ffi.rs.h"

#include "vtkPiecewiseFunction.h"

#include <algorithm>
#include <exception>
#include <utility>

namespace vtkHybridOctreeBridge
{

namespace
{
/// Runs `body`, a call into Rust: a `rust::Error` (an error or a panic on the
/// Rust side, which derives from std::exception) becomes `false` with its
/// message in `error`.
template <typename Body>
bool Guarded(std::string& error, Body&& body)
{
  try
  {
    body();
    return true;
  }
  catch (const std::exception& e)
  {
    error = e.what();
  }
  return false;
}

hybrid_octree::ScalarType ToRust(ScalarType type)
{
  switch (type)
  {
    case ScalarType::U8:
      return hybrid_octree::ScalarType::U8;
    case ScalarType::I8:
      return hybrid_octree::ScalarType::I8;
    case ScalarType::U16:
      return hybrid_octree::ScalarType::U16;
    case ScalarType::I16:
      return hybrid_octree::ScalarType::I16;
    case ScalarType::U32:
      return hybrid_octree::ScalarType::U32;
    case ScalarType::I32:
      return hybrid_octree::ScalarType::I32;
    case ScalarType::F32:
      return hybrid_octree::ScalarType::F32;
    case ScalarType::F64:
      return hybrid_octree::ScalarType::F64;
  }
  return hybrid_octree::ScalarType::F64; // unreachable: every enumerator is handled
}

hybrid_octree::GridDesc ToRust(const GridDescription& grid)
{
  hybrid_octree::GridDesc desc;
  desc.scalar_type = ToRust(grid.Type);
  for (int axis = 0; axis < 3; ++axis)
  {
    desc.dims[axis] = grid.Dims[axis];
    desc.spacing[axis] = grid.Spacing[axis];
    desc.origin[axis] = grid.Origin[axis];
  }
  desc.components = grid.Components;
  desc.component = grid.Component;
  return desc;
}

hybrid_octree::SurfaceMode ToRust(SurfaceMode mode)
{
  switch (mode)
  {
    case SurfaceMode::Discretized:
      return hybrid_octree::SurfaceMode::Discretized;
    case SurfaceMode::Interpolated:
      return hybrid_octree::SurfaceMode::Interpolated;
  }
  return hybrid_octree::SurfaceMode::Discretized; // unreachable: every enumerator is handled
}

/// The borrowed samples as a byte slice. A null pointer is only legal for an
/// empty buffer; cxx maps it to a dangling, well-aligned empty slice.
rust::Slice<const std::uint8_t> ToSlice(const void* bytes, std::size_t byteCount)
{
  return rust::Slice<const std::uint8_t>(
    static_cast<const std::uint8_t*>(bytes), bytes ? byteCount : 0);
}

template <typename From, typename To>
void CopyInto(const rust::Vec<From>& from, std::vector<To>& to)
{
  to.assign(from.begin(), from.end());
}
void CopyMesh(const hybrid_octree::SurfaceOutput& s, SurfaceMesh& surface)
{
  CopyInto(s.points, surface.Points);
  CopyInto(s.normals, surface.Normals);
  CopyInto(s.offsets, surface.Offsets);
  CopyInto(s.connectivity, surface.Connectivity);
  CopyInto(s.polygon_node, surface.PolygonNode);
  CopyInto(s.polygon_level, surface.PolygonLevel);
  CopyInto(s.polygon_face, surface.PolygonFace);
  surface.Polygons = s.polygons;
  surface.Faces = s.faces;
  surface.Triangles = s.triangles;
  surface.UncompressedTriangles = s.uncompressed_triangles;
  surface.Vertices = s.vertices;
  surface.BoundaryEdges = s.boundary_edges;
  surface.ExtractMilliseconds = s.extract_ms;
  surface.CompressMilliseconds = s.compress_ms;
  surface.DistanceMean = s.distance_mean;
  surface.DistanceMax = s.distance_max;
}

/// The bridge's camera.
hybrid_octree::CameraDesc ToRust(const CameraDescription& camera)
{
  hybrid_octree::CameraDesc desc;
  for (int axis = 0; axis < 3; ++axis)
  {
    desc.position[axis] = camera.Position[axis];
    desc.focal_point[axis] = camera.FocalPoint[axis];
    desc.view_up[axis] = camera.ViewUp[axis];
  }
  desc.parallel = camera.Parallel;
  desc.parallel_scale = camera.ParallelScale;
  desc.view_angle = camera.ViewAngle;
  return desc;
}

void CopyDrawList(const hybrid_octree::DrawListOutput& out, DrawList& list)
{
  CopyInto(out.brick, list.Brick);
  CopyInto(out.node_id, list.NodeId);
  CopyInto(out.bounds, list.Bounds);
  CopyInto(out.texels, list.Texels);
  CopyInto(out.stride, list.Stride);
  CopyInto(out.slice_spacing, list.SliceSpacing);
  CopyInto(out.opacity_ratio, list.OpacityRatio);
  CopyInto(out.slice_offsets, list.SliceOffsets);
  CopyInto(out.slices, list.Slices);
  list.Passes = std::string(out.passes);
  list.ReferenceSpacing = out.reference_spacing;
  for (int axis = 0; axis < 3; ++axis)
  {
    list.Forward[axis] = out.forward[axis];
  }
  CopyInto(out.batch_offsets, list.BatchOffsets);
  CopyInto(out.batch_slab, list.BatchSlab);
  CopyInto(out.batch_first, list.BatchFirst);
  CopyInto(out.batch_end, list.BatchEnd);
  CopyInto(out.batch_clip, list.BatchClip);
  list.OpaqueTriangles = out.opaque_triangles;
  CopyInto(out.bucket_offsets, list.BucketOffsets);
  CopyInto(out.bucket_slab, list.BucketSlab);
  CopyInto(out.bucket_point_offsets, list.BucketPointOffsets);
  CopyInto(out.bucket_points, list.BucketPoints);
}

/// The bridge's select options.
hybrid_octree::SelectDesc ToRust(const SelectDescription& options)
{
  hybrid_octree::SelectDesc desc;
  desc.budget_bytes = options.BudgetBytes;
  desc.tolerance = options.Tolerance;
  desc.has_roi = options.HasRoi;
  for (int axis = 0; axis < 3; ++axis)
  {
    desc.roi_center[axis] = options.RoiCenter[axis];
  }
  desc.roi_radius = options.RoiRadius;
  for (double v : options.OpacityPoints)
  {
    desc.opacity_points.push_back(v);
  }
  desc.has_isovalue = options.HasIsovalue;
  desc.isovalue = options.Isovalue;
  return desc;
}

/// The bridge's point options.
hybrid_octree::PointsDesc ToRust(const PointsOptions& options)
{
  hybrid_octree::PointsDesc o;
  o.factor = options.Factor;
  o.threshold = options.Threshold;
  o.use_budget = options.UseBudget;
  o.budget = options.Budget;
  o.underestimates_only = options.UnderestimatesOnly;
  o.max_overestimate = options.MaxOverestimate;
  o.file_name = rust::String(options.FileName);
  return o;
}
} // namespace

struct VolumeOctree::Internals
{
  explicit Internals(rust::Box<hybrid_octree::VolumeOctreeHandle> handle)
    : Handle(std::move(handle))
  {
  }
  rust::Box<hybrid_octree::VolumeOctreeHandle> Handle;
};

VolumeOctree::VolumeOctree(std::unique_ptr<Internals> internals)
  : Impl(std::move(internals))
{
}

VolumeOctree::~VolumeOctree() = default;

std::unique_ptr<VolumeOctree> VolumeOctree::Build(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, unsigned int leafSize, std::string& error)
{
  return Build(
    bytes, byteCount, grid, leafSize, [](double) { return true; }, error);
}

namespace
{
/// The Rust build's progress sink over a std::function (never throws into Rust).
class FunctionProgress final : public hybrid_octree::BuildProgress
{
public:
  explicit FunctionProgress(const std::function<bool(double)>& f)
    : Function(f)
  {
  }
  bool report(double fraction) const noexcept override
  {
    try
    {
      return this->Function(fraction);
    }
    catch (...)
    {
      return false;
    }
  }

private:
  const std::function<bool(double)>& Function;
};
}

std::unique_ptr<VolumeOctree> VolumeOctree::Build(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, unsigned int leafSize, const std::function<bool(double)>& progress,
  std::string& error)
{
  std::unique_ptr<VolumeOctree> result;
  const FunctionProgress sink(progress);
  Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    rust::Box<hybrid_octree::VolumeOctreeHandle> handle =
      hybrid_octree::build_volume_octree_with_progress(
        ToSlice(bytes, byteCount), desc, leafSize, sink);
    result = std::unique_ptr<VolumeOctree>(
      new VolumeOctree(std::unique_ptr<Internals>(new Internals(std::move(handle)))));
  });
  return result;
}

bool VolumeOctree::GetSummary(OctreeSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::OctreeSummary s = this->Impl->Handle->summary();
    summary.NodeCount = s.node_count;
    summary.TerminalCount = s.terminal_count;
    summary.HomogeneousCount = s.homogeneous_count;
    summary.Levels = s.levels;
    summary.LeafSize = s.leaf_size;
    summary.RootSize = s.root_size;
    summary.OctreeBytes = s.octree_bytes;
    summary.InputBytes = s.input_bytes;
    summary.BuildMilliseconds = s.build_ms;
    summary.ValueMin = s.value_min;
    summary.ValueMax = s.value_max;
    summary.NaNSamples = s.nan_samples;
  });
}

bool VolumeOctree::GetCutBoxes(double tolerance, CutBoxes& boxes, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::CutBoxes cut = this->Impl->Handle->cut_boxes(tolerance);
    CopyInto(cut.bounds, boxes.Bounds);
    CopyInto(cut.node_id, boxes.NodeId);
    CopyInto(cut.level, boxes.Level);
    CopyInto(cut.nodal_error, boxes.NodalError);
    CopyInto(cut.min, boxes.Min);
    CopyInto(cut.max, boxes.Max);
  });
}

bool VolumeOctree::ExtractSurface(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, double isovalue, SurfaceMode mode, bool measureDistance,
  SurfaceMesh& surface, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    const hybrid_octree::SurfaceOutput s = this->Impl->Handle->extract_surface(
      ToSlice(bytes, byteCount), desc, isovalue, ToRust(mode), measureDistance);
    CopyMesh(s, surface);
  });
}

std::vector<double> OpacityPoints(vtkPiecewiseFunction* function)
{
  std::vector<double> points;
  const int n = function ? function->GetSize() : 0;
  if (n == 0)
  {
    return points;
  }
  points.reserve(2 * n + 4);
  double node[4];
  const bool clamped = function->GetClamping() != 0;
  for (int i = 0; i < n; ++i)
  {
    function->GetNodeValue(i, node);
    if (i == 0 && !clamped)
    {
      points.push_back(node[0]);
      points.push_back(0.0);
    }
    points.push_back(node[0]);
    points.push_back(std::min(1.0, std::max(0.0, node[1])));
  }
  if (!clamped)
  {
    points.push_back(node[0]);
    points.push_back(0.0);
  }
  return points;
}

struct Selection::Internals
{
  explicit Internals(rust::Box<hybrid_octree::SelectionHandle> handle)
    : Handle(std::move(handle))
  {
  }
  rust::Box<hybrid_octree::SelectionHandle> Handle;
};

std::unique_ptr<Selection> VolumeOctree::Select(
  const SelectDescription& options, std::string& error) const
{
  std::unique_ptr<Selection> result;
  Guarded(error, [&] {
    rust::Box<hybrid_octree::SelectionHandle> handle =
      this->Impl->Handle->select_bricks(ToRust(options));
    result = std::unique_ptr<Selection>(new Selection(
      std::unique_ptr<Selection::Internals>(new Selection::Internals(std::move(handle)))));
  });
  return result;
}

struct Points::Internals
{
  explicit Internals(rust::Box<hybrid_octree::PointsHandle> handle)
    : Handle(std::move(handle))
  {
  }
  rust::Box<hybrid_octree::PointsHandle> Handle;
};

Points::Points(std::unique_ptr<Internals> internals)
  : Impl(std::move(internals))
{
}

Points::~Points() = default;

std::unique_ptr<Points> VolumeOctree::MakePoints(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, const PointsOptions& options, std::string& error) const
{
  std::unique_ptr<Points> result;
  Guarded(error, [&] {
    rust::Box<hybrid_octree::PointsHandle> handle = this->Impl->Handle->points_for_drawing(
      ToSlice(bytes, byteCount), ToRust(grid), ToRust(options));
    result = std::unique_ptr<Points>(
      new Points(std::unique_ptr<Points::Internals>(new Points::Internals(std::move(handle)))));
  });
  return result;
}

bool Points::GetDrawing(PointsDrawing& drawing, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::PointsDrawing d = this->Impl->Handle->drawing();
    CopyInto(d.position, drawing.Position);
    CopyInto(d.value, drawing.Value);
    CopyInto(d.error, drawing.Error);
    drawing.Factor = d.factor;
    drawing.PointBytes = d.point_bytes;
  });
}

bool Points::GetShades(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const std::vector<double>& colorPoints, const std::vector<double>& opacityPoints,
  std::vector<float>& shades, std::string& error) const
{
  return Guarded(error, [&] {
    const rust::Vec<float> out = this->Impl->Handle->shades(ToSlice(bytes, byteCount), ToRust(grid),
      rust::Slice<const double>(colorPoints.data(), colorPoints.size()),
      rust::Slice<const double>(opacityPoints.data(), opacityPoints.size()));
    CopyInto(out, shades);
  });
}

std::unique_ptr<Selection> VolumeOctree::Select(
  const SelectDescription& options, const Points& points, std::string& error) const
{
  std::unique_ptr<Selection> result;
  Guarded(error, [&] {
    rust::Box<hybrid_octree::SelectionHandle> handle =
      this->Impl->Handle->select_bricks_with_points(ToRust(options), *points.Impl->Handle);
    result = std::unique_ptr<Selection>(new Selection(
      std::unique_ptr<Selection::Internals>(new Selection::Internals(std::move(handle)))));
  });
  return result;
}

Selection::Selection(std::unique_ptr<Internals> internals)
  : Impl(std::move(internals))
{
}

Selection::~Selection() = default;

bool Selection::GetSummary(SelectionSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::SelectionSummary s = this->Impl->Handle->summary();
    summary.Bricks = s.bricks;
    summary.TextureBytes = s.texture_bytes;
    summary.BudgetBytes = s.budget_bytes;
    summary.EstimatedError = s.estimated_error;
    summary.Skipped = s.skipped;
    summary.Warning = std::string(s.warning);
    summary.Points = s.points;
    summary.PointBytes = s.point_bytes;
  });
}

bool Selection::GetDrawList(const VolumeOctree& octree, const CameraDescription& camera,
  DrawList& list, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::DrawListOutput out =
      this->Impl->Handle->draw_list(*octree.Impl->Handle, ToRust(camera));
    CopyDrawList(out, list);
  });
}

bool Selection::GetBrickTexels(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, std::vector<float>& texels,
  std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    const rust::Vec<float> t =
      this->Impl->Handle->brick_texels(ToSlice(bytes, byteCount), desc, brick);
    CopyInto(t, texels);
  });
}

struct Surface::Internals
{
  explicit Internals(rust::Box<hybrid_octree::SurfaceHandle> handle)
    : Handle(std::move(handle))
  {
  }
  rust::Box<hybrid_octree::SurfaceHandle> Handle;
};

bool Selection::GetDrawList(const VolumeOctree& octree, const CameraDescription& camera,
  const Surface& surface, double surfaceOpacity, DrawList& list, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::DrawListOutput out = this->Impl->Handle->draw_list_with_surface(
      *octree.Impl->Handle, ToRust(camera), *surface.Impl->Handle, surfaceOpacity);
    CopyDrawList(out, list);
  });
}

Surface::Surface(std::unique_ptr<Internals> internals)
  : Impl(std::move(internals))
{
}

Surface::~Surface() = default;

std::unique_ptr<Surface> VolumeOctree::ExtractSurfaceForDrawing(const void* bytes,
  std::size_t byteCount, const GridDescription& grid, double isovalue, SurfaceMode mode,
  std::string& error) const
{
  std::unique_ptr<Surface> result;
  Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    rust::Box<hybrid_octree::SurfaceHandle> handle = this->Impl->Handle->surface_for_drawing(
      ToSlice(bytes, byteCount), desc, isovalue, ToRust(mode));
    result = std::unique_ptr<Surface>(
      new Surface(std::unique_ptr<Surface::Internals>(new Surface::Internals(std::move(handle)))));
  });
  return result;
}

bool Surface::GetMesh(const VolumeOctree& octree, SurfaceMesh& mesh, std::string& error) const
{
  return Guarded(error, [&] { CopyMesh(this->Impl->Handle->mesh(*octree.Impl->Handle), mesh); });
}

bool Selection::Composite(const VolumeOctree& octree, const CameraDescription& camera,
  const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const CompositeScene& scene, std::size_t width, std::size_t height, std::vector<float>& rgba,
  std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    const rust::Slice<const double> colors(scene.ColorPoints.data(), scene.ColorPoints.size());
    const rust::Slice<const double> opacities(
      scene.OpacityPoints.data(), scene.OpacityPoints.size());
    const rust::Vec<float> out = scene.SurfaceToDraw
      ? this->Impl->Handle->composite_with_surface(*octree.Impl->Handle, ToRust(camera),
          ToSlice(bytes, byteCount), desc, colors, opacities, scene.GaussianPoints,
          *scene.SurfaceToDraw->Impl->Handle, rust::Slice<const double>(scene.SurfaceRGBA, 4),
          width, height)
      : this->Impl->Handle->composite(*octree.Impl->Handle, ToRust(camera),
          ToSlice(bytes, byteCount), desc, colors, opacities, scene.GaussianPoints, width, height);
    CopyInto(out, rgba);
  });
}

bool FtbDisplay(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const FtbOptions& options, FtbResult& result, std::string& error)
{
  return Guarded(error, [&] {
    const hybrid_octree::GridDesc desc = ToRust(grid);
    hybrid_octree::FtbDesc o;
    o.isovalue = options.Isovalue;
    o.use_label = options.UseLabel;
    o.label = options.Label;
    o.vpn = { options.Vpn[0], options.Vpn[1], options.Vpn[2] };
    o.image_size = options.ImageSize;
    o.back_to_front = options.BackToFront;
    const hybrid_octree::FtbImage image =
      hybrid_octree::ftb_display(ToSlice(bytes, byteCount), desc, o);
    result.Size = image.size;
    CopyInto(image.depth, result.Depth);
    CopyInto(image.face, result.Face);
    CopyInto(image.shaded, result.Shaded);
    result.WhiteVisited = image.white_visited;
    result.BlackVisited = image.black_visited;
    result.GrayVisited = image.gray_visited;
    result.Faces = image.faces;
    result.Scanlines = image.scanlines;
    result.Pixels = image.pixels;
    result.DisplayMs = image.display_ms;
    result.BuildMs = image.build_ms;
    result.BitmapBytes = image.bitmap_bytes;
    result.WhiteOctants = image.white_octants;
    result.BlackOctants = image.black_octants;
    result.GrayOctants = image.gray_octants;
    result.Resolution = image.resolution;
    result.ViewCase = std::string(image.view_case);
  });
}

bool GeneratePoints(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const PointsOptions& options, PointsResult& result, std::string& error)
{
  return Guarded(error, [&] {
    const hybrid_octree::PointsOutput points =
      hybrid_octree::generate_points(ToSlice(bytes, byteCount), ToRust(grid), ToRust(options));
    CopyInto(points.ijk, result.Ijk);
    CopyInto(points.value, result.Value);
    CopyInto(points.error, result.Error);
    CopyInto(points.normal, result.Normal);
    result.Factor = points.factor;
    result.PointBytes = points.point_bytes;
    result.Underestimates = points.underestimates;
    result.GenerateMs = points.generate_ms;
  });
}

} // namespace vtkHybridOctreeBridge
