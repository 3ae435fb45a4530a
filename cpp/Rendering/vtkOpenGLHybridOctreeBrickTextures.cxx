#include "vtkOpenGLHybridOctreeBrickTextures.h"

#include "vtkHybridOctreeBridge.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <algorithm>

void vtkOpenGLHybridOctreeBrickTextures::BeginFrame(std::size_t limitBytes,
  const std::vector<std::uint32_t>& nodes, const std::vector<std::size_t>& strides)
{
  ++this->Frame;
  this->Previous = nullptr;
  this->LimitBytes = limitBytes;
  this->UploadedBytes = 0;
  // The frame's resident bricks count as used by it: MakeRoom() passes them by.
  for (std::size_t i = 0; i < std::min(nodes.size(), strides.size()); ++i)
  {
    auto found = this->Entries.find({ nodes[i], strides[i] });
    if (found != this->Entries.end())
    {
      this->Touch(found->first, found->second);
    }
  }
  // A lower limit (a smaller budget) takes effect at once.
  this->MakeRoom(0);
}

void vtkOpenGLHybridOctreeBrickTextures::Touch(const Key& key, Resident& entry)
{
  if (entry.LastFrame != this->Frame)
  {
    this->ByAge.erase({ entry.LastFrame, key });
    entry.LastFrame = this->Frame;
    this->ByAge.insert({ entry.LastFrame, key });
  }
}

bool vtkOpenGLHybridOctreeBrickTextures::MakeRoom(std::size_t incoming)
{
  while (this->ResidentBytes + incoming > this->LimitBytes)
  {
    // The least recently drawn texture (ties: the least key), if not this frame's.
    auto oldest = this->ByAge.begin();
    if (oldest == this->ByAge.end() || oldest->first >= this->Frame)
    {
      return false;
    }
    auto entry = this->Entries.find(oldest->second);
    this->ByAge.erase(oldest);
    if (entry == this->Entries.end())
    {
      continue;
    }
    this->Pages.Free(this->Window, entry->second.Slot);
    this->ResidentBytes -= entry->second.Bytes;
    this->Entries.erase(entry);
  }
  return true;
}

const vtkOpenGLHybridOctreeBrickTextures::Resident* vtkOpenGLHybridOctreeBrickTextures::Acquire(
  vtkOpenGLRenderWindow* window, const Key& key, const std::size_t texels[3], const Fetch& fetch,
  std::string& error, std::size_t border)
{
  if (this->Window && this->Window != window)
  {
    this->Clear(this->Window);
  }
  this->Window = window;
  auto found = this->Entries.find(key);
  if (found != this->Entries.end())
  {
    this->Touch(found->first, found->second);
    this->Previous = found->second.Slot.Owner;
    return &found->second;
  }
  const std::size_t channels = static_cast<std::size_t>(this->Channels);
  const std::size_t count = texels[0] * texels[1] * texels[2];
  const std::size_t bytes = this->GetTexelBytes() * count;
  if (!this->MakeRoom(bytes))
  {
    error = "the bricks of this frame need more than the texture budget of " +
      std::to_string(this->LimitBytes) + " bytes";
    return nullptr;
  }
  this->Scratch.resize(channels * count);
  // Single-channel textures of a format other than float32 upload codes, and
  // four-channel unorm8 ones (RGBA8: an RGBA volume of u8 data) their bytes.
  const bool coded = this->Coded();
  this->Encoded.resize(coded ? this->GetStagingBytes() * channels * count : 0);
  if (!fetch(this->Scratch.data(), coded ? this->Encoded.data() : nullptr, this->Scratch.size()))
  {
    return nullptr;
  }
  const vtkOpenGLHybridOctreeBrickPages::Format format = this->PageFormat();
  if (!(this->Pages.GetFormat() == format))
  {
    // Pages of another layout hold no brick of this frame's (SetChannels(), SetTexelFormat()).
    this->Clear(window);
    this->Window = window;
    this->Pages.SetFormat(window, format);
  }
  // A page holds about a sixteenth of the limit, from 64 KiB to 4 MiB.
  const std::size_t pageBytes =
    std::clamp<std::size_t>(this->LimitBytes / 16, std::size_t{ 64 } << 10, std::size_t{ 4 } << 20);
  vtkOpenGLHybridOctreeBrickPages::Slot slot;
  if (!this->Pages.Allocate(window, texels, pageBytes, slot, error, this->Previous))
  {
    return nullptr;
  }
  const void* staged =
    coded ? static_cast<const void*>(this->Encoded.data()) : this->Scratch.data();
  if (!this->Pages.Upload(slot, staged, error))
  {
    this->Pages.Free(window, slot);
    return nullptr;
  }
  std::vector<float> ranges;
  const float* own = this->Scratch.data();
  std::size_t ownTexels[3] = { texels[0], texels[1], texels[2] };
  if (border > 0 || channels > 1)
  {
    // The block ranges describe the brick's own texels, inside the border.
    for (int a = 0; a < 3; ++a)
    {
      ownTexels[a] = texels[a] - 2 * border;
    }
    this->Interior.resize(ownTexels[0] * ownTexels[1] * ownTexels[2]);
    std::size_t at = 0;
    for (std::size_t k = 0; k < ownTexels[2]; ++k)
    {
      for (std::size_t j = 0; j < ownTexels[1]; ++j)
      {
        // The last channel: the field the opacity is read from.
        const float* row = this->Scratch.data() + channels - 1 +
          channels * (border + texels[0] * ((j + border) + texels[1] * (k + border)));
        for (std::size_t i = 0; i < ownTexels[0]; ++i)
        {
          this->Interior[at++] = row[channels * i];
        }
      }
    }
    own = this->Interior.data();
  }
  if (!vtkHybridOctreeBridge::MeasureBlockRanges(
        own, ownTexels[0] * ownTexels[1] * ownTexels[2], ownTexels, ranges, error))
  {
    this->Pages.Free(window, slot);
    return nullptr;
  }
  Resident& entry = this->Entries[key];
  entry.Slot = slot;
  entry.BlockRanges.swap(ranges);
  entry.Bytes = bytes;
  entry.LastFrame = this->Frame;
  this->ByAge.insert({ entry.LastFrame, key });
  this->ResidentBytes += bytes;
  this->UploadedBytes += bytes;
  this->Previous = slot.Owner;
  return &entry;
}

bool vtkOpenGLHybridOctreeBrickTextures::HoldsAll(
  const std::vector<std::uint32_t>& nodes, const std::vector<std::size_t>& strides) const
{
  for (std::size_t i = 0; i < nodes.size() && i < strides.size(); ++i)
  {
    if (this->Entries.find({ nodes[i], strides[i] }) == this->Entries.end())
    {
      return false;
    }
  }
  return true;
}

void vtkOpenGLHybridOctreeBrickTextures::GetResident(
  std::vector<std::uint32_t>& nodes, std::vector<std::size_t>& strides) const
{
  nodes.clear();
  strides.clear();
  nodes.reserve(this->Entries.size());
  strides.reserve(this->Entries.size());
  for (const auto& entry : this->Entries)
  {
    nodes.push_back(entry.first.first);
    strides.push_back(entry.first.second);
  }
}

void vtkOpenGLHybridOctreeBrickTextures::SetChannels(vtkWindow* window, int channels)
{
  if (channels != this->Channels)
  {
    this->Clear(window);
    this->Channels = channels;
  }
}

void vtkOpenGLHybridOctreeBrickTextures::SetTexelFormat(vtkWindow* window, int format)
{
  format = format >= 1 && format <= 4 ? format : 1;
  if (format != this->TexelFormat)
  {
    this->Clear(window);
    this->TexelFormat = format;
  }
}

std::size_t vtkOpenGLHybridOctreeBrickTextures::GetStagingBytes() const
{
  static const std::size_t staging[] = { 4, 4, 4, 2, 1 };
  return staging[this->TexelFormat];
}

std::size_t vtkOpenGLHybridOctreeBrickTextures::GetTexelBytes() const
{
  static const std::size_t gpu[] = { 4, 4, 2, 2, 1 };
  return this->Channels == 1 || this->Coded()
    ? gpu[this->TexelFormat] * static_cast<std::size_t>(this->Channels)
    : 4 * static_cast<std::size_t>(this->Channels);
}

vtkOpenGLHybridOctreeBrickPages::Format vtkOpenGLHybridOctreeBrickTextures::PageFormat() const
{
  // The GL format of the texel format; R16F is filled from floats that are
  // half floats' exact values, so the conversion rounds nothing.
  static const unsigned int internalFormats[] = { GL_R32F, GL_R32F, GL_R16F, GL_R16, GL_R8 };
  static const int stagedTypes[] = { VTK_FLOAT, VTK_FLOAT, VTK_FLOAT, VTK_UNSIGNED_SHORT,
    VTK_UNSIGNED_CHAR };
  const bool coded = this->Coded();
  const int format = coded ? this->TexelFormat : 1;
  vtkOpenGLHybridOctreeBrickPages::Format out;
  out.Channels = this->Channels;
  out.StagedType = stagedTypes[format];
  out.TexelBytes = this->GetTexelBytes();
  if (this->Channels == 1)
  {
    out.InternalFormat = internalFormats[format];
  }
  else if (this->Channels == 4)
  {
    out.InternalFormat = coded ? GL_RGBA8 : GL_RGBA32F;
  }
  else
  {
    out.InternalFormat = GL_RG32F;
  }
  return out;
}

bool vtkOpenGLHybridOctreeBrickTextures::Coded() const
{
  return this->TexelFormat != 1 &&
    (this->Channels == 1 || (this->Channels == 4 && this->TexelFormat == 4));
}

void vtkOpenGLHybridOctreeBrickTextures::Clear(vtkWindow* window)
{
  this->Pages.Clear(window);
  this->Entries.clear();
  this->ByAge.clear();
  this->ResidentBytes = 0;
  this->Window = nullptr;
}
