/**
 * @file   vtkHybridOctreeBuildProgress.h
 * @brief  The C++ side of the build's progress sink, called by Rust (private to the module).
 *
 * `hybrid_octree::build_hybrid_octree` (src/ffi/mod.rs) calls
 * `report(fraction)` on the thread that started the build, between chunks of
 * leaf bricks, with fractions increasing to 1 (the leaf pass, which is
 * nearly all of the build time). Returning false cancels the build: Rust then
 * returns the error "the Hybrid Octree build was cancelled; nothing was
 * produced" and drops everything it built. `report` must not throw (an
 * exception cannot cross into Rust); implementations catch what they call.
 */
#ifndef vtkHybridOctreeBuildProgress_h
#define vtkHybridOctreeBuildProgress_h

namespace hybrid_octree
{
class BuildProgress
{
public:
  virtual ~BuildProgress() = default;
  /// `fraction` of the build done, in (0, 1]; false asks the build to stop.
  virtual bool report(double fraction) const noexcept = 0;
};
}

#endif
