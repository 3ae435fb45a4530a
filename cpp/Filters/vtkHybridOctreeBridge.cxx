/**
 * @file   vtkHybridOctreeBridge.cxx
 * @brief  The C++ half of the bridge: the only includer of the cxx header.
 *
 * Every call into Rust runs under `Guarded` (try/catch): the Rust side turns errors
 * and panics into `rust::Error`, which derives from std::exception. Outputs
 * the caller sizes cross as `rust::Slice<T>` over its memory.
 */
#include "vtkHybridOctreeBridge.h"

#include "hybrid-octree/src/ffi/mod.rs.h"

#include "vtkPiecewiseFunction.h"

#include <algorithm>
#include <exception>
#include <type_traits>
#include <utility>

namespace vtkHybridOctreeBridge
{

/// The Rust handle type behind each C++ object.
template <class Object>
struct HandleOf;
template <>
struct HandleOf<HybridOctree>
{
  using Type = hybrid_octree::HybridOctreeHandle;
};
template <>
struct HandleOf<Selection>
{
  using Type = hybrid_octree::SelectionHandle;
};
template <>
struct HandleOf<OmeZarrStore>
{
  using Type = hybrid_octree::StoreHandle;
};
template <>
struct HandleOf<FrameTimer>
{
  using Type = hybrid_octree::FrameTimer;
};

/// Owns the Rust handle of `Object`.
template <class Object>
struct RustHandle
{
  using Handle = typename HandleOf<Object>::Type;
  explicit RustHandle(rust::Box<Handle> box)
    : Box(std::move(box))
  {
  }
  rust::Box<Handle> Box;
};

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

/// The C++ object owning `box`.
template <class Object>
std::unique_ptr<Object> Own(rust::Box<typename HandleOf<Object>::Type> box)
{
  return std::unique_ptr<Object>(
    new Object(std::unique_ptr<RustHandle<Object>>(new RustHandle<Object>(std::move(box)))));
}

/// The Rust handle of `object`.
template <class Object>
const typename HandleOf<Object>::Type& HandleFor(const std::unique_ptr<RustHandle<Object>>& impl)
{
  return *impl->Box;
}

hybrid_octree::GridDesc ToRust(const GridDescription& grid)
{
  hybrid_octree::GridDesc desc;
  desc.scalar_type = grid.Type;
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

/// The borrowed samples as a byte slice. A null pointer is only legal for an
/// empty buffer; cxx maps it to a dangling, well-aligned empty slice.
rust::Slice<const std::uint8_t> ToSlice(const void* bytes, std::size_t byteCount)
{
  return rust::Slice<const std::uint8_t>(
    static_cast<const std::uint8_t*>(bytes), bytes ? byteCount : 0);
}

/// The caller's `count` values at `data` for Rust to write (null only when empty).
template <typename T>
rust::Slice<T> Out(T* data, std::size_t count)
{
  return rust::Slice<T>(data, data ? count : 0);
}

/// vtkIdType memory as the bridge's int64 (the same 8 bytes; `long long`
/// and `int64_t` may be distinct types of one size).
rust::Slice<std::int64_t> Out(vtkIdType* data, std::size_t count)
{
  static_assert(sizeof(vtkIdType) == sizeof(std::int64_t) && std::is_signed<vtkIdType>::value,
    "the bridge writes 64-bit ids: build VTK with VTK_USE_64BIT_IDS");
  return Out(reinterpret_cast<std::int64_t*>(data), count);
}

template <typename From, typename To>
void CopyInto(const rust::Vec<From>& from, std::vector<To>& to)
{
  to.assign(from.begin(), from.end());
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

/// The bridge's shading.
hybrid_octree::ShadingDesc ToRust(const ShadingDescription& shading)
{
  hybrid_octree::ShadingDesc desc;
  desc.shade = shading.Shade;
  desc.ambient = shading.Ambient;
  desc.diffuse = shading.Diffuse;
  desc.specular = shading.Specular;
  desc.specular_power = shading.SpecularPower;
  desc.two_sided = shading.TwoSided;
  desc.headlight = shading.Headlight;
  auto toRust = [](const std::vector<double>& from, rust::Vec<double>& to) {
    for (double v : from)
    {
      to.push_back(v);
    }
  };
  toRust(shading.LightDirections, desc.light_directions);
  toRust(shading.LightAmbient, desc.light_ambient);
  toRust(shading.LightDiffuse, desc.light_diffuse);
  toRust(shading.LightSpecular, desc.light_specular);
  return desc;
}

/// The bridge's scattering.
hybrid_octree::ScatteringDesc ToRust(const ScatteringDescription& scattering)
{
  hybrid_octree::ScatteringDesc desc;
  desc.blending = scattering.Blending;
  desc.reach = scattering.Reach;
  desc.anisotropy = scattering.Anisotropy;
  for (int k = 0; k < 3; ++k)
  {
    desc.headlight_ambient[k] = scattering.HeadlightAmbient[k];
  }
  desc.sample_distance = scattering.SampleDistance;
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
  list.Effects = std::string(out.effects);
  list.Gradients = out.gradients;
  list.Bordered = out.bordered;
  list.BlendMode = out.blend_mode;
  list.Shading = out.shading;
  list.TexelFormat = out.texel_format;
  list.TexelScale = out.texel_scale;
  list.TexelBias = out.texel_bias;
  list.TexelBytes = out.texel_bytes;
  CopyInto(out.rgba_reading, list.RgbaReading);
  list.OpacityScale = out.opacity_scale;
  CopyInto(out.gradient_opacity_table, list.GradientOpacityTable);
  list.GradientOpacityEnd = out.gradient_opacity_end;
  for (int k = 0; k < 3; ++k)
  {
    list.Transfer2DAxes[k] = out.transfer_2d_axes[k];
  }
  list.Region.Cropping = out.region.cropping;
  for (int k = 0; k < 6; ++k)
  {
    list.Region.CroppingPlanes[k] = out.region.cropping_planes[k];
  }
  list.Region.CroppingFlags = out.region.cropping_flags;
  CopyInto(out.region.clipping_planes, list.Region.ClippingPlanes);
  CopyInto(out.slice_plane, list.SlicePlane);
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
  desc.gradient_border = options.GradientBorder;
  desc.blend_mode = options.BlendMode;
  desc.average_range[0] = options.AverageRange[0];
  desc.average_range[1] = options.AverageRange[1];
  desc.texel_format = options.TexelFormat;
  for (double v : options.IsosurfaceValues)
  {
    desc.isosurface_values.push_back(v);
  }
  for (double v : options.GradientOpacityPoints)
  {
    desc.gradient_opacity_points.push_back(v);
  }
  desc.region.cropping = options.Region.Cropping;
  for (int k = 0; k < 6; ++k)
  {
    desc.region.cropping_planes[k] = options.Region.CroppingPlanes[k];
  }
  desc.region.cropping_flags = options.Region.CroppingFlags;
  for (double v : options.Region.ClippingPlanes)
  {
    desc.region.clipping_planes.push_back(v);
  }
  desc.transfer_2d_size[0] = options.Transfer2DSize[0];
  desc.transfer_2d_size[1] = options.Transfer2DSize[1];
  desc.transfer_2d_rgba.reserve(options.Transfer2DRGBA.size());
  for (float v : options.Transfer2DRGBA)
  {
    desc.transfer_2d_rgba.push_back(v);
  }
  desc.transfer_2d_range[0] = options.Transfer2DRange[0];
  desc.transfer_2d_range[1] = options.Transfer2DRange[1];
  for (int k = 0; k < 6; ++k)
  {
    desc.slice_plane[k] = options.SlicePlane[k];
  }
  const ViewDescription& view = options.View;
  desc.view.view_selection = view.ViewSelection;
  desc.view.camera = ToRust(view.Camera);
  desc.view.viewport[0] = view.Viewport[0];
  desc.view.viewport[1] = view.Viewport[1];
  desc.view.min_texel_pixels = view.MinTexelPixels;
  desc.view.surface_opacity = view.SurfaceOpacity;
  desc.view.opacity_unit_distance = view.OpacityUnitDistance;
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

PointsSummary FromRust(const hybrid_octree::PointsSummary& s)
{
  PointsSummary summary;
  summary.Points = s.points;
  summary.Factor = s.factor;
  summary.PointBytes = s.point_bytes;
  summary.Underestimates = s.underestimates;
  summary.GenerateMs = s.generate_ms;
  return summary;
}

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
} // namespace

HybridOctree::HybridOctree(std::unique_ptr<RustHandle<HybridOctree>> handle)
  : Impl(std::move(handle))
{
}

HybridOctree::~HybridOctree() = default;

std::unique_ptr<HybridOctree> HybridOctree::Build(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, unsigned int leafSize, std::string& error)
{
  return Build(
    bytes, byteCount, grid, leafSize, [](double) { return true; }, error);
}

std::unique_ptr<HybridOctree> HybridOctree::Build(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, unsigned int leafSize, const std::function<bool(double)>& progress,
  std::string& error)
{
  std::unique_ptr<HybridOctree> result;
  const FunctionProgress sink(progress);
  Guarded(error, [&] {
    result = Own<HybridOctree>(
      hybrid_octree::build_hybrid_octree(ToSlice(bytes, byteCount), ToRust(grid), leafSize, sink));
  });
  return result;
}

std::unique_ptr<HybridOctree> HybridOctree::BuildDependent(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, unsigned int leafSize, std::string& error)
{
  std::unique_ptr<HybridOctree> result;
  const std::function<bool(double)> always = [](double) { return true; };
  const FunctionProgress sink(always);
  Guarded(error, [&] {
    result = Own<HybridOctree>(hybrid_octree::build_dependent_octree(
      ToSlice(bytes, byteCount), ToRust(grid), leafSize, sink));
  });
  return result;
}

bool HybridOctree::GetSummary(OctreeSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::OctreeSummary s = HandleFor(this->Impl).summary();
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

bool HybridOctree::GetCutBoxes(double tolerance, CutBoxes& boxes, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::CutBoxes cut = HandleFor(this->Impl).cut_boxes(tolerance);
    CopyInto(cut.bounds, boxes.Bounds);
    CopyInto(cut.node_id, boxes.NodeId);
    CopyInto(cut.level, boxes.Level);
    CopyInto(cut.nodal_error, boxes.NodalError);
    CopyInto(cut.min, boxes.Min);
    CopyInto(cut.max, boxes.Max);
  });
}

bool HybridOctree::IntegrateSurface(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, double isovalue, SurfaceMode mode, bool measureDistance,
  SurfaceSummary& summary, std::string& error)
{
  this->SurfaceVertices = this->SurfacePolygons = this->SurfaceIndices = 0;
  return Guarded(error, [&] {
    const hybrid_octree::SurfaceSummary s = this->Impl->Box->integrate_surface(
      ToSlice(bytes, byteCount), ToRust(grid), isovalue, mode, measureDistance);
    summary.Vertices = s.vertices;
    summary.Polygons = s.polygons;
    summary.Connectivity = s.connectivity;
    summary.Faces = s.faces;
    summary.Triangles = s.triangles;
    summary.UncompressedTriangles = s.uncompressed_triangles;
    summary.BoundaryEdges = s.boundary_edges;
    summary.ExtractMilliseconds = s.extract_ms;
    summary.CompressMilliseconds = s.compress_ms;
    summary.DistanceMean = s.distance_mean;
    summary.DistanceMax = s.distance_max;
    this->SurfaceVertices = s.vertices;
    this->SurfacePolygons = s.polygons;
    this->SurfaceIndices = s.connectivity;
  });
}

void HybridOctree::RemoveSurface()
{
  std::string ignored; // dropping a Rust value cannot fail
  Guarded(ignored, [&] { this->Impl->Box->remove_surface(); });
  this->SurfaceVertices = this->SurfacePolygons = this->SurfaceIndices = 0;
}

bool HybridOctree::GetSurfaceMesh(const SurfaceMeshBuffers& mesh, std::string& error) const
{
  const std::size_t vertices = this->SurfaceVertices;
  const std::size_t polygons = this->SurfacePolygons;
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .surface_mesh(Out(mesh.Points, 3 * vertices), Out(mesh.Normals, 3 * vertices),
        Out(mesh.Offsets, polygons + 1), Out(mesh.Connectivity, this->SurfaceIndices),
        Out(mesh.PolygonNode, polygons), Out(mesh.PolygonLevel, polygons),
        Out(mesh.PolygonFace, polygons));
  });
}

bool HybridOctree::GetSurfaceTriangles(
  std::vector<float>& vertices, std::vector<unsigned int>& indices, std::string& error) const
{
  static_assert(sizeof(unsigned int) == sizeof(std::uint32_t), "32-bit triangle indices");
  vertices.resize(6 * this->SurfaceVertices);
  indices.resize(3 * this->SurfacePolygons);
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .surface_triangles(Out(vertices.data(), vertices.size()),
        Out(reinterpret_cast<std::uint32_t*>(indices.data()), indices.size()));
  });
}

bool HybridOctree::IntegratePoints(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, const PointsOptions& options, PointsSummary& summary,
  std::string& error)
{
  this->Points = this->PointsFactor = this->PointsBytes = 0;
  return Guarded(error, [&] {
    summary = FromRust(
      this->Impl->Box->integrate_points(ToSlice(bytes, byteCount), ToRust(grid), ToRust(options)));
    this->Points = summary.Points;
    this->PointsFactor = summary.Factor;
    this->PointsBytes = summary.PointBytes;
  });
}

void HybridOctree::RemovePoints()
{
  std::string ignored; // dropping a Rust value cannot fail
  Guarded(ignored, [&] { this->Impl->Box->remove_points(); });
  this->Points = this->PointsFactor = this->PointsBytes = 0;
}

bool HybridOctree::GetPointsDrawing(PointsDrawing& drawing, std::string& error) const
{
  drawing.Position.resize(3 * this->Points);
  drawing.Value.resize(this->Points);
  drawing.Error.resize(this->Points);
  drawing.Factor = this->PointsFactor;
  drawing.PointBytes = this->PointsBytes;
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .points_drawing(Out(drawing.Position.data(), drawing.Position.size()),
        Out(drawing.Value.data(), drawing.Value.size()),
        Out(drawing.Error.data(), drawing.Error.size()));
  });
}

bool HybridOctree::GetPointShades(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, const std::vector<double>& colorPoints,
  const std::vector<double>& opacityPoints, std::vector<float>& shades, std::string& error) const
{
  shades.resize(4 * this->Points);
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .point_shades(ToSlice(bytes, byteCount), ToRust(grid),
        rust::Slice<const double>(colorPoints.data(), colorPoints.size()),
        rust::Slice<const double>(opacityPoints.data(), opacityPoints.size()),
        Out(shades.data(), shades.size()));
  });
}

std::unique_ptr<Selection> HybridOctree::Select(
  const SelectDescription& options, std::string& error) const
{
  std::unique_ptr<Selection> result;
  Guarded(
    error, [&] { result = Own<Selection>(HandleFor(this->Impl).select_bricks(ToRust(options))); });
  return result;
}

bool HybridOctree::PrepareView(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, const SelectDescription& options, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl).prepare_view(ToSlice(bytes, byteCount), ToRust(grid), ToRust(options));
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

OmeZarrStore::OmeZarrStore(std::unique_ptr<RustHandle<OmeZarrStore>> handle)
  : Impl(std::move(handle))
{
}

OmeZarrStore::~OmeZarrStore() = default;

std::unique_ptr<OmeZarrStore> OmeZarrStore::Open(const std::string& path, std::string& error)
{
  std::unique_ptr<OmeZarrStore> result;
  Guarded(error, [&] { result = Own<OmeZarrStore>(hybrid_octree::open_store(path)); });
  return result;
}

bool OmeZarrStore::GetSummary(StoreSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::StoreSummary s = HandleFor(this->Impl).summary();
    for (int axis = 0; axis < 3; ++axis)
    {
      summary.Dims[axis] = s.dims[axis];
      summary.Spacing[axis] = s.spacing[axis];
      summary.Origin[axis] = s.origin[axis];
    }
    summary.Type = s.scalar_type;
    summary.Levels = s.levels;
    CopyInto(s.level_dims, summary.LevelDims);
    summary.HasOctree = s.has_octree;
    summary.Name = std::string(s.name);
    summary.Version = std::string(s.version);
    summary.Warnings = std::string(s.warnings);
  });
}

bool OmeZarrStore::ReadLevel(std::size_t level, const std::size_t lo[3], const std::size_t hi[3],
  void* bytes, std::size_t byteCount, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .read_level(level, rust::Slice<const std::size_t>(lo, 3),
        rust::Slice<const std::size_t>(hi, 3), Out(static_cast<std::uint8_t*>(bytes), byteCount));
  });
}

std::uint64_t OmeZarrStore::GetBytesRead() const
{
  return HandleFor(this->Impl).bytes_read();
}

std::unique_ptr<HybridOctree> HybridOctree::BuildFromStore(
  const OmeZarrStore& store, unsigned int leafSize, std::string& error)
{
  std::unique_ptr<HybridOctree> result;
  Guarded(error, [&] {
    result =
      Own<HybridOctree>(hybrid_octree::build_octree_from_store(HandleFor(store.Impl), leafSize));
  });
  return result;
}

bool Selection::GetBrickTexelsFromStore(const HybridOctree& octree, const OmeZarrStore& store,
  std::size_t brick, bool bordered, float* texels, std::size_t count, unsigned char* encoded,
  std::size_t encodedBytes, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels_from_store(HandleFor(octree.Impl), HandleFor(store.Impl), brick, bordered,
        Out(texels, count),
        Out(reinterpret_cast<std::uint8_t*>(encoded), encoded ? encodedBytes : 0));
  });
}

bool Selection::PlanLoading(const HybridOctree& octree, const OmeZarrStore& store,
  const std::vector<std::uint32_t>& residentNodes, const std::vector<std::size_t>& residentStrides,
  std::size_t memoryBytes, LoadingSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::LoadingSummary s =
      HandleFor(this->Impl)
        .plan_loading(HandleFor(octree.Impl), HandleFor(store.Impl),
          rust::Slice<const std::uint32_t>(residentNodes.data(), residentNodes.size()),
          rust::Slice<const std::size_t>(residentStrides.data(), residentStrides.size()),
          memoryBytes);
    summary.StandIns = s.stand_ins;
    summary.Loaded = s.loaded;
    summary.Queued = s.queued;
    summary.WaitingBytes = s.waiting_bytes;
    summary.BytesRead = s.bytes_read;
  });
}

void Selection::DrawSelected() const
{
  HandleFor(this->Impl).draw_selected();
}

Selection::Selection(std::unique_ptr<RustHandle<Selection>> handle)
  : Impl(std::move(handle))
{
}

Selection::~Selection() = default;

bool Selection::GetSummary(SelectionSummary& summary, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::SelectionSummary s = HandleFor(this->Impl).summary();
    summary.Bricks = s.bricks;
    summary.TextureBytes = s.texture_bytes;
    summary.BudgetBytes = s.budget_bytes;
    summary.EstimatedError = s.estimated_error;
    summary.EstimatedRmsError = s.estimated_rms_error;
    summary.Skipped = s.skipped;
    summary.Warning = std::string(s.warning);
    summary.Points = s.points;
    summary.PointBytes = s.point_bytes;
    summary.ViewSelection = std::string(s.view_selection);
  });
}

bool Selection::GetDrawList(const HybridOctree& octree, const CameraDescription& camera,
  double surfaceOpacity, DrawList& list, std::string& error) const
{
  return Guarded(error, [&] {
    CopyDrawList(
      HandleFor(this->Impl).draw_list(HandleFor(octree.Impl), ToRust(camera), surfaceOpacity),
      list);
  });
}

bool Selection::GetBrickTexels(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, float* texels, std::size_t count,
  std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels(ToSlice(bytes, byteCount), ToRust(grid), brick, Out(texels, count));
  });
}

bool Selection::GetBrickTexelsBordered(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, float* texels, std::size_t count,
  std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels_bordered(ToSlice(bytes, byteCount), ToRust(grid), brick, Out(texels, count));
  });
}

bool Selection::GetBrickTexelsEncoded(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, bool bordered, float* decoded, std::size_t count,
  unsigned char* encoded, std::size_t encodedBytes, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels_encoded(ToSlice(bytes, byteCount), ToRust(grid), brick, bordered,
        Out(decoded, count), Out(reinterpret_cast<std::uint8_t*>(encoded), encodedBytes));
  });
}

bool Selection::GetBrickTexelsDependent(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, bool bordered, float* texels, std::size_t count,
  std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels_dependent(
        ToSlice(bytes, byteCount), ToRust(grid), brick, bordered, Out(texels, count));
  });
}

bool Selection::GetBrickTexelsRgba(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, std::size_t brick, bool bordered, float* decoded, std::size_t count,
  unsigned char* encoded, std::size_t encodedBytes, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .brick_texels_rgba(ToSlice(bytes, byteCount), ToRust(grid), brick, bordered,
        Out(decoded, count), Out(reinterpret_cast<std::uint8_t*>(encoded), encodedBytes));
  });
}

bool Selection::SetShading(const ShadingDescription& shading, std::string& error) const
{
  return Guarded(error, [&] { HandleFor(this->Impl).set_shading(ToRust(shading)); });
}

bool Selection::SetGradientOpacity(const std::vector<double>& points, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .set_gradient_opacity(rust::Slice<const double>(points.data(), points.size()));
  });
}

bool Selection::SetJittering(bool on, std::string& error) const
{
  return Guarded(error, [&] { HandleFor(this->Impl).set_jittering(on); });
}

bool Selection::SetSampleDistance(double distance, std::string& error) const
{
  return Guarded(error, [&] { HandleFor(this->Impl).set_sample_distance(distance); });
}

bool Selection::SetScattering(const ScatteringDescription& scattering, std::string& error) const
{
  return Guarded(error, [&] { HandleFor(this->Impl).set_scattering(ToRust(scattering)); });
}

bool Selection::GetScatteringFrame(ScatteringFrame& frame, std::string& error) const
{
  return Guarded(error, [&] {
    const hybrid_octree::ScatteringFrameDesc f = HandleFor(this->Impl).scattering_frame();
    frame.Blending = f.blending;
    frame.Anisotropy = f.anisotropy;
    frame.GradientScale = f.gradient_scale;
    frame.Extent = f.extent;
    frame.Distance = f.distance;
    frame.ToVtk = f.to_vtk;
    frame.MaxSteps = f.max_steps;
    for (int k = 0; k < 3; ++k)
    {
      frame.HeadlightAmbient[k] = f.headlight_ambient[k];
      frame.TextureCorner[k] = f.texture_corner[k];
      frame.TextureSize[k] = f.texture_size[k];
      frame.ShadowDims[k] = f.shadow_dims[k];
      frame.ShadowScale[k] = f.shadow_scale[k];
      frame.ShadowShift[k] = f.shadow_shift[k];
    }
  });
}

bool Selection::GetShadowVolume(const void* bytes, std::size_t byteCount,
  const GridDescription& grid, float* texels, std::size_t count, std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .shadow_volume_texels(ToSlice(bytes, byteCount), ToRust(grid), Out(texels, count));
  });
}

bool Selection::Composite(const HybridOctree& octree, const CameraDescription& camera,
  const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const CompositeScene& scene, std::size_t width, std::size_t height, float* rgba,
  std::string& error) const
{
  return Guarded(error, [&] {
    HandleFor(this->Impl)
      .composite(HandleFor(octree.Impl), ToRust(camera), ToSlice(bytes, byteCount), ToRust(grid),
        rust::Slice<const double>(scene.ColorPoints.data(), scene.ColorPoints.size()),
        rust::Slice<const double>(scene.OpacityPoints.data(), scene.OpacityPoints.size()),
        scene.GaussianPoints, rust::Slice<const double>(scene.SurfaceRGBA, 4), width, height,
        Out(rgba, 4 * width * height));
  });
}

bool FtbDisplay(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const FtbOptions& options, const FtbImageBuffers& image, FtbResult& result, std::string& error)
{
  return Guarded(error, [&] {
    hybrid_octree::FtbDesc o;
    o.isovalue = options.Isovalue;
    o.use_label = options.UseLabel;
    o.label = options.Label;
    o.vpn = { options.Vpn[0], options.Vpn[1], options.Vpn[2] };
    o.image_size = options.ImageSize;
    o.back_to_front = options.BackToFront;
    const std::size_t pixels = options.ImageSize * options.ImageSize;
    const hybrid_octree::FtbSummary s =
      hybrid_octree::ftb_display(ToSlice(bytes, byteCount), ToRust(grid), o,
        Out(image.Depth, pixels), Out(image.Face, pixels), Out(image.Shaded, 3 * pixels));
    result.WhiteVisited = s.white_visited;
    result.BlackVisited = s.black_visited;
    result.GrayVisited = s.gray_visited;
    result.Faces = s.faces;
    result.Scanlines = s.scanlines;
    result.Pixels = s.pixels;
    result.DisplayMs = s.display_ms;
    result.BuildMs = s.build_ms;
    result.BitmapBytes = s.bitmap_bytes;
    result.WhiteOctants = s.white_octants;
    result.BlackOctants = s.black_octants;
    result.GrayOctants = s.gray_octants;
    result.Resolution = s.resolution;
    result.ViewCase = std::string(s.view_case);
  });
}

bool GeneratePoints(const void* bytes, std::size_t byteCount, const GridDescription& grid,
  const PointsOptions& options, const std::function<PointsBuffers(const PointsSummary&)>& allocate,
  PointsSummary& summary, std::string& error)
{
  return Guarded(error, [&] {
    const rust::Box<hybrid_octree::GeneratedPoints> made =
      hybrid_octree::generate_points(ToSlice(bytes, byteCount), ToRust(grid), ToRust(options));
    summary = FromRust(made->summary());
    const std::size_t n = summary.Points;
    const PointsBuffers out = allocate(summary);
    made->fill(Out(out.Ijk, 3 * n), Out(out.Value, n), Out(out.Error, n), Out(out.Normal, 3 * n));
  });
}

namespace
{
template <typename T>
rust::Slice<const T> In(const std::vector<T>& v)
{
  return rust::Slice<const T>(v.data(), v.size());
}

/// An optional input: empty when absent.
template <typename T>
rust::Slice<const T> In(const std::vector<T>* v)
{
  return v ? In(*v) : rust::Slice<const T>();
}
} // namespace

bool GetBrickGeometry(const BrickGeometryInput& input, BrickGeometry& geometry, std::string& error)
{
  if (!input.List || !input.Table)
  {
    error = "the brick geometry needs a DrawList and a transfer function table";
    return false;
  }
  const DrawList& list = *input.List;
  return Guarded(error, [&] {
    std::vector<rust::Slice<const float>> ranges;
    ranges.reserve(input.BlockRanges.size());
    for (const std::vector<float>* r : input.BlockRanges)
    {
      ranges.push_back(In(r));
    }
    static_assert(std::is_same<unsigned int, std::uint32_t>::value, "triangle ids are 32 bits");
    hybrid_octree::BrickGeometryDesc desc{};
    for (int axis = 0; axis < 3; ++axis)
    {
      desc.eye[axis] = input.Eye[axis];
      desc.forward[axis] = list.Forward[axis];
      desc.view_up[axis] = input.ViewUp[axis];
      desc.spacing[axis] = input.Spacing[axis];
    }
    desc.bounds = In(list.Bounds);
    desc.texels = In(list.Texels);
    desc.stride = In(list.Stride);
    desc.slice_offsets = In(list.SliceOffsets);
    desc.slices = In(list.Slices);
    desc.batch_offsets = In(list.BatchOffsets);
    desc.batch_first = In(list.BatchFirst);
    desc.batch_end = In(list.BatchEnd);
    desc.bucket_offsets = In(list.BucketOffsets);
    desc.bucket_slab = In(list.BucketSlab);
    desc.bucket_point_offsets = In(list.BucketPointOffsets);
    desc.bucket_points = In(list.BucketPoints);
    desc.table = In(*input.Table);
    desc.table_lo = input.TableLo;
    desc.table_hi = input.TableHi;
    desc.block_ranges = rust::Slice<const rust::Slice<const float>>(ranges.data(), ranges.size());
    desc.with_surface = input.SurfaceVertices && input.SurfaceTriangles;
    desc.surface_vertices = In(input.SurfaceVertices);
    desc.surface_triangles = In(input.SurfaceTriangles);
    desc.with_points = input.PointPositions && input.PointShades;
    desc.point_positions = In(input.PointPositions);
    desc.point_shades = In(input.PointShades);
    desc.gaussian_points = input.GaussianPoints;
    desc.slice_plane = In(list.SlicePlane);
    hybrid_octree::BrickGeometryOutput out = hybrid_octree::brick_geometry(desc);
    // The vertices stay in the Rust core's buffer, kept alive by Storage.
    auto vertices = std::make_shared<rust::Vec<float>>(std::move(out.vertices));
    geometry.Vertices = vertices->data();
    geometry.VertexFloats = vertices->size();
    geometry.Storage = std::move(vertices);
    CopyInto(out.brick_first, geometry.BrickFirst);
    CopyInto(out.ray_marched, geometry.RayMarched);
    CopyInto(out.drawn, geometry.Drawn);
    CopyInto(out.boxes, geometry.Boxes);
    std::copy(out.point_up.begin(), out.point_up.end(), geometry.PointUp);
    geometry.TrianglesPlaced = out.triangles_placed;
    geometry.PointsPlaced = out.points_placed;
  });
}

bool MeasureBlockRanges(const float* texels, std::size_t count, const std::size_t dims[3],
  std::vector<float>& ranges, std::string& error)
{
  return Guarded(error, [&] {
    const rust::Slice<const std::size_t> d(dims, 3);
    ranges.resize(hybrid_octree::block_ranges_len(d));
    hybrid_octree::brick_block_ranges(
      rust::Slice<const float>(texels, texels ? count : 0), d, Out(ranges.data(), ranges.size()));
  });
}

bool ViewChangeDegrees(const CameraDescription& a, const CameraDescription& b,
  const double centre[3], double& degrees, std::string& error)
{
  return Guarded(error, [&] {
    degrees = hybrid_octree::view_change_degrees(
      ToRust(a), ToRust(b), rust::Slice<const double>(centre, centre ? 3 : 0));
  });
}

namespace
{
/// The bridge's timed frame.
hybrid_octree::TimedFrameDesc ToRust(const TimedFrameDescription& frame)
{
  hybrid_octree::TimedFrameDesc desc;
  desc.target_ms = frame.TargetMilliseconds;
  desc.camera = ToRust(frame.Camera);
  desc.width = frame.Width;
  desc.height = frame.Height;
  desc.surface_opacity = frame.SurfaceOpacity;
  desc.shading = ToRust(frame.Shading);
  for (double v : frame.GradientOpacityPoints)
  {
    desc.gradient_opacity_points.push_back(v);
  }
  desc.jittering = frame.Jittering;
  desc.sample_distance = frame.SampleDistance;
  desc.scattering = ToRust(frame.Scattering);
  return desc;
}
} // namespace

FrameTimer::FrameTimer()
  : Impl(new RustHandle<FrameTimer>(hybrid_octree::new_frame_timer()))
{
}

FrameTimer::~FrameTimer() = default;

std::unique_ptr<Selection> FrameTimer::Select(const HybridOctree& octree,
  const SelectDescription& options, const TimedFrameDescription& frame, std::string& error)
{
  std::unique_ptr<Selection> result;
  Guarded(error, [&] {
    result = Own<Selection>(
      this->Impl->Box->select_for_time(HandleFor(octree.Impl), ToRust(options), ToRust(frame)));
  });
  return result;
}

bool FrameTimer::Observe(const Selection& selection, const HybridOctree& octree,
  const TimedFrameDescription& frame, std::size_t uploadedBytes, double milliseconds, bool& again,
  std::string& error)
{
  return Guarded(error, [&] {
    again = this->Impl->Box->observe_frame(HandleFor(selection.Impl), HandleFor(octree.Impl),
      ToRust(frame), uploadedBytes, milliseconds);
  });
}

TimedSummary FrameTimer::GetSummary() const
{
  const hybrid_octree::TimedSummary s = this->Impl->Box->summary();
  TimedSummary summary;
  summary.TargetMilliseconds = s.target_ms;
  summary.PredictedMilliseconds = s.predicted_ms;
  summary.MeasuredMilliseconds = s.measured_ms;
  summary.BudgetBytes = s.budget_bytes;
  summary.SliceFactor = s.slice_factor;
  summary.Outcome = std::string(s.outcome);
  summary.Evaluations = s.evaluations;
  summary.EstimatedRmsError = s.estimated_rms_error;
  summary.WarmUpLeft = s.warm_up_left;
  summary.Ratio = s.ratio;
  summary.Note = std::string(s.note);
  return summary;
}

} // namespace vtkHybridOctreeBridge
