/**
 * @file   vtkOpenGLHybridOctreeBrickTextures.h
 * @brief  The resident textures of the selected bricks (private to the module).
 *
 * The Hybrid Octree, section 3.2: the texture memory holds the bricks of the
 * current selection, and a new selection (a moved region of interest, another
 * budget) loads only the bricks it does not find there. A brick's texels are
 * identified by its node and texel stride (level p); they stay resident across
 * frames while the byte limit allows, and the least recently drawn bricks
 * not needed by the current frame are released first, before an upload would
 * pass the limit. So resident bytes never exceed the limit, as long as one
 * frame's bricks fit it (which the selection guarantees: they fit its budget).
 * The limit counts the bricks' own texels; they live in slots of shared
 * texture pages (vtkOpenGLHybridOctreeBrickPages), whose bytes, free slots
 * included, GetPageBytes() reports.
 *
 * Texels are single-channel in the frame's texel format (SetTexelFormat():
 * R8, R16, R16F or R32F, 1 to 4 bytes each), two-channel 32-bit floats
 * (8 bytes: colour and opacity fields of dependent components, see
 * SetChannels()), or four-channel (an RGBA volume: RGBA8, 4 bytes, with
 * the unorm8 format, else RGBA32F, 16 bytes), filtered linearly and clamped to the edge. With each
 * texture the cache keeps the brick's block value ranges, measured from its texels at upload by the
 * Rust core (vtkHybridOctreeBridge::MeasureBlockRanges()) and handed back to it every frame
 * (vtkHybridOctreeBridge::GetBrickGeometry()): which blocks the transfer function leaves visible.
 */
#ifndef vtkOpenGLHybridOctreeBrickTextures_h
#define vtkOpenGLHybridOctreeBrickTextures_h

#include "vtkOpenGLHybridOctreeBrickPages.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkWindow;

/// A resident brick: its slot in a texture page and its block value ranges.
struct vtkOpenGLHybridOctreeBrickResident
{
  vtkOpenGLHybridOctreeBrickPages::Slot Slot;
  std::vector<float> BlockRanges; ///< opaque to C++: for GetBrickGeometry()
  std::size_t Bytes = 0;
  std::uint64_t LastFrame = 0;
};

class vtkOpenGLHybridOctreeBrickTextures
{
public:
  /// (octree node id, texel stride): what a brick's texture holds.
  using Key = std::pair<std::uint32_t, std::size_t>;
  /// Writes a brick's texels (x fastest) into the staging buffers it is
  /// given: `decoded`, `count` floats (the brick's texel count times the
  /// channels), the values; `encoded`, when not null (a format other than
  /// float32), the texel count times GetStagingBytes() of the format's codes,
  /// which are uploaded instead. False and a message in the caller's error
  /// string on failure.
  using Fetch = std::function<bool(float* decoded, unsigned char* encoded, std::size_t count)>;

  /// A resident brick.
  using Resident = vtkOpenGLHybridOctreeBrickResident;

  /**
   * Starts a frame whose textures may occupy at most `limitBytes` and that
   * draws the bricks (`nodes[i]`, `strides[i]`). Those already resident are
   * kept: room for the frame's new textures is made from the others only,
   * least recently used first, so a brick of the last selection that the
   * new one keeps is never evicted and uploaded again within the frame.
   */
  void BeginFrame(std::size_t limitBytes, const std::vector<std::uint32_t>& nodes,
    const std::vector<std::size_t>& strides);

  /**
   * The texture of brick `key` (`texels` per axis) for this frame: the
   * resident one, or a new one filled from `fetch`, after releasing least
   * recently drawn textures of earlier frames as needed to stay within the
   * limit. nullptr and `error` when the upload fails or this frame's textures
   * alone would pass the limit. With a gradient `border` (shading: 1) the
   * texels carry that many border texels per side; the block ranges are
   * measured on the brick's own texels inside it. A new brick takes a slot
   * of its shape. Bricks acquired in
   * compositing order: a new one goes into the page of the one acquired
   * before it when it can (vtkOpenGLHybridOctreeBrickPages::Allocate()).
   */
  const Resident* Acquire(vtkOpenGLRenderWindow* window, const Key& key,
    const std::size_t texels[3], const Fetch& fetch, std::string& error, std::size_t border = 0);

  /// Whether the bricks (`nodes[i]`, `strides[i]`) are all resident.
  bool HoldsAll(
    const std::vector<std::uint32_t>& nodes, const std::vector<std::size_t>& strides) const;

  /// The keys of all resident textures: `nodes[i]`, `strides[i]`.
  void GetResident(std::vector<std::uint32_t>& nodes, std::vector<std::size_t>& strides) const;

  /// Bytes of all resident textures.
  std::size_t GetResidentBytes() const { return this->ResidentBytes; }
  /// Bytes uploaded since BeginFrame().
  std::size_t GetUploadedBytes() const { return this->UploadedBytes; }
  /// Resident bricks.
  std::size_t GetNumberOfTextures() const { return this->Entries.size(); }
  /// Bytes of the texture pages holding them (their free slots included).
  std::size_t GetPageBytes() const { return this->Pages.GetAllocatedBytes(); }
  /// Texture pages holding them.
  std::size_t GetNumberOfPages() const { return this->Pages.GetNumberOfPages(); }

  /**
   * Texels of 1 channel (one field), 2 (colour, opacity: dependent
   * components; the fetch then writes 2 floats a texel, and the block
   * ranges are the opacity channel's) or 4 (an RGBA volume: 4 floats a
   * texel, and with the unorm8 format 4 bytes into `encoded`; the block
   * ranges are channel a's). A change releases every texture.
   */
  void SetChannels(vtkWindow* window, int channels);
  int GetChannels() const { return this->Channels; }

  /**
   * The texel format of single-channel textures (DrawList::TexelFormat: 1
   * float32 R32F, 2 float16 R16F, 3 unorm16 R16, 4 unorm8 R8). A change
   * releases every texture.
   */
  void SetTexelFormat(vtkWindow* window, int format);
  int GetTexelFormat() const { return this->TexelFormat; }
  /// Bytes of one staged texel of the format (float16 stages floats).
  std::size_t GetStagingBytes() const;
  /// Bytes of one texel on the GPU (all channels).
  std::size_t GetTexelBytes() const;

  /// Whether the fetch writes codes that are uploaded (a single-channel
  /// format other than float32, or RGBA8).
  bool Coded() const;

  /// Releases every texture (a new octree, or the context going away).
  void Clear(vtkWindow* window);

private:
  /// Releases textures not drawn in this frame, least recently drawn first,
  /// until `incoming` more bytes fit the limit; false when they cannot.
  /// Each release is O(log n) (ByAge), so a frame replacing every resident
  /// texture costs O(n log n), not a scan of the cache per upload.
  bool MakeRoom(std::size_t incoming);
  /// Marks `entry` (of `key`) drawn in this frame.
  void Touch(const Key& key, Resident& entry);

  /// The page layout of the channels and texel format.
  vtkOpenGLHybridOctreeBrickPages::Format PageFormat() const;

  vtkOpenGLHybridOctreeBrickPages Pages;
  std::map<Key, Resident> Entries;
  /// The resident textures by the frame that last drew them, then key: the
  /// release order.
  std::set<std::pair<std::uint64_t, Key>> ByAge;
  std::size_t ResidentBytes = 0;
  std::size_t UploadedBytes = 0;
  std::size_t LimitBytes = 0;
  std::uint64_t Frame = 0;
  /// The page of the brick acquired last in this frame (compared, never read).
  const vtkOpenGLHybridOctreeBrickPages::Page* Previous = nullptr;
  vtkWindow* Window = nullptr;
  std::vector<float> Scratch;
  std::vector<unsigned char> Encoded; ///< the codes of a format other than float32
  std::vector<float> Interior;        ///< a bordered brick's own texels (of the last channel)
  int Channels = 1;
  int TexelFormat = 1;
};

#endif
