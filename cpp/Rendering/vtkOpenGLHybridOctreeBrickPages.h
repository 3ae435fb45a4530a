/**
 * @file   vtkOpenGLHybridOctreeBrickPages.h
 * @brief  The 3D texture pages the resident bricks share (private to the module).
 *
 * The Hybrid Octree's texture memory (section 3.2) holds one texture per
 * brick in the paper. A brick of 9^3 one-byte texels is 729 bytes, and a
 * driver pads and tracks every texture on its own: Mesa's llvmpipe pads each
 * row to a cache line and each image to a multiple of four rows, so a 9^3 R8
 * texture takes ~9 KB of memory and ~15 us to create (measured,
 * docs/BENCHMARKS.md). Large-volume renderers keep their bricks in a brick
 * pool instead: a few large textures, each brick in a slot of one. So here.
 *
 * A page is one 3D texture holding a grid of a_x * a_y * a_z slots of one
 * shape, n texels per axis (slot (i, j, k) at texel offset (i n_x, j n_y,
 * k n_z)); an axis with n = 1 has one slot along it. A brick takes a slot
 * of its own shape (a stride mixes 9^3 and 129^3 bricks, so slots of a
 * stride's largest brick would hold mostly nothing). A shape's
 * k-th page (of those it holds now) has 8 * 2^k slots, up to the target
 * page bytes, so a shape's pages grow with its bricks and its first pages
 * stay small.
 * A brick takes a free slot of the page the brick before it in the frame's
 * compositing order lies in, when that page is of its shape and has one, so
 * that runs of bricks share a page and draw in one call (an octree
 * traversal keeps a subtree's bricks together in every view's order); else
 * of the page of its shape that uses the most slots (so sparse pages
 * drain). A page whose last slot is freed is released at once.
 *
 * The shader clamps a brick's texel coordinate u_a into
 *
 *     [g, n_a - 1 - g],   g = 1/64   (min(g, (n_a - 1) / 2) when n_a < 2 + 2g)
 *
 * (n_a the brick's own texels) so the linear filter never reads past the
 * brick (a neighbouring slot may hold another brick, or be NaN or not
 * written): a sample within 1/64 texel of a brick's face reads
 * its face texel within 1/64 of one texel step, where a texture of its own
 * clamped to the edge would read the face texel exactly.
 */
#ifndef vtkOpenGLHybridOctreeBrickPages_h
#define vtkOpenGLHybridOctreeBrickPages_h

#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkWindow;

class vtkOpenGLHybridOctreeBrickPages
{
public:
  /// The texel layout of every page: the GL internal format, the channels and
  /// the VTK type of the staged texels uploaded into a slot.
  struct Format
  {
    unsigned int InternalFormat = 0;
    int Channels = 1;
    int StagedType = 0;
    std::size_t TexelBytes = 4; ///< on the GPU, all channels

    bool operator==(const Format& other) const
    {
      return this->InternalFormat == other.InternalFormat && this->Channels == other.Channels &&
        this->StagedType == other.StagedType && this->TexelBytes == other.TexelBytes;
    }
  };

  /// One 3D texture of slots of one shape.
  struct Page
  {
    vtkSmartPointer<vtkTextureObject> Texture;
    std::size_t Shape[3] = { 0, 0, 0 };   ///< a slot's texels per axis
    std::size_t Slots[3] = { 1, 1, 1 };   ///< slots per axis
    unsigned int Texels[3] = { 0, 0, 0 }; ///< the page's texels per axis
    std::vector<std::size_t> FreeSlots;   ///< free slot indices, taken from the back
    std::size_t Used = 0;
    std::size_t Bytes = 0;

    std::size_t Capacity() const { return this->Slots[0] * this->Slots[1] * this->Slots[2]; }
  };

  /// A brick's place: its page, its texel offset in it and the brick's
  /// texels per axis (the page's slot shape).
  struct Slot
  {
    Page* Owner = nullptr;
    std::size_t Index = 0;
    unsigned int Offset[3] = { 0, 0, 0 };
    std::size_t Texels[3] = { 0, 0, 0 };
  };

  /// The texture of `slot`'s page and its texels per axis.
  static vtkTextureObject* GetTexture(const Slot& slot);
  static const unsigned int* GetPageTexels(const Slot& slot);

  /**
   * A free slot for a brick of `texels` per axis, in a page of slots of
   * that shape and `Format` (SetFormat()):
   * of an existing page of the shape, or of a new one of at most about
   * `pageBytes` (at least one slot); of `near` when it is a page of the
   * shape with a free slot (only compared, never read: it may be gone).
   * False and `error` when OpenGL cannot create the page.
   */
  bool Allocate(vtkOpenGLRenderWindow* window, const std::size_t texels[3], std::size_t pageBytes,
    Slot& slot, std::string& error, const Page* near = nullptr);

  /// Writes the brick's texels staged in the format's type (x fastest, the
  /// slot's Texels) into `slot`. False and `error` on an OpenGL error.
  bool Upload(const Slot& slot, const void* staged, std::string& error);

  /// Frees `slot`; its page is released when it was the last one used.
  void Free(vtkWindow* window, const Slot& slot);

  /// The layout of every page; a change releases every page.
  void SetFormat(vtkWindow* window, const Format& format);
  const Format& GetFormat() const { return this->TexelFormat; }

  /// Bytes of every page's texels (used and free slots).
  std::size_t GetAllocatedBytes() const { return this->AllocatedBytes; }
  /// Pages (3D textures) allocated.
  std::size_t GetNumberOfPages() const;

  /// Releases every page (the slots given out are then invalid).
  void Clear(vtkWindow* window);

private:
  using Shape = std::array<std::size_t, 3>;
  /// The pages of each shape, in creation order.
  std::map<Shape, std::vector<std::unique_ptr<Page>>> Shapes;
  Format TexelFormat;
  std::size_t AllocatedBytes = 0;
};

#endif
