#include "vtkOpenGLHybridOctreeBrickPages.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <algorithm>

namespace
{
/// The largest texels per axis of a page: at most 1024, and what the context allows.
std::size_t MaxPageAxis(vtkOpenGLRenderWindow* window)
{
  const int limit = vtkTextureObject::GetMaximumTextureSize3D(window);
  return static_cast<std::size_t>(std::clamp(limit, 1, 1024));
}
}

vtkTextureObject* vtkOpenGLHybridOctreeBrickPages::GetTexture(const Slot& slot)
{
  return slot.Owner ? slot.Owner->Texture.Get() : nullptr;
}

const unsigned int* vtkOpenGLHybridOctreeBrickPages::GetPageTexels(const Slot& slot)
{
  return slot.Owner->Texels;
}

bool vtkOpenGLHybridOctreeBrickPages::Allocate(vtkOpenGLRenderWindow* window,
  const std::size_t texels[3], std::size_t pageBytes, Slot& slot, std::string& error,
  const Page* near)
{
  const Shape shape = { texels[0], texels[1], texels[2] };
  std::vector<std::unique_ptr<Page>>& pages = this->Shapes[shape];
  // `near` when it is a page of this shape with a free slot, else the page
  // of this shape using the most slots that has a free one (ties: the oldest).
  Page* best = nullptr;
  for (const auto& page : pages)
  {
    if (page->FreeSlots.empty())
    {
      continue;
    }
    if (page.get() == near)
    {
      best = page.get();
      break;
    }
    if (!best || page->Used > best->Used)
    {
      best = page.get();
    }
  }
  if (!best)
  {
    const std::size_t slotBytes = this->TexelFormat.TexelBytes * texels[0] * texels[1] * texels[2];
    const std::size_t held = pages.size();
    // The k-th page of a shape holds 8 * 2^k slots, up to about pageBytes.
    std::size_t wanted = held < 40 ? std::size_t{ 8 } << held : ~std::size_t{ 0 };
    wanted =
      std::max<std::size_t>(1, std::min(wanted, pageBytes / std::max<std::size_t>(slotBytes, 1)));
    auto page = std::make_unique<Page>();
    const std::size_t maxAxis = MaxPageAxis(window);
    for (int a = 0; a < 3; ++a)
    {
      page->Shape[a] = texels[a];
    }
    // Near-cubic in texels: grow the axis of the smallest extent that can grow.
    while (page->Capacity() < wanted)
    {
      int grow = -1;
      for (int a = 0; a < 3; ++a)
      {
        const bool can = texels[a] >= 2 && (page->Slots[a] + 1) * texels[a] <= maxAxis;
        if (can && (grow < 0 || page->Slots[a] * texels[a] < page->Slots[grow] * texels[grow]))
        {
          grow = a;
        }
      }
      if (grow < 0)
      {
        break;
      }
      ++page->Slots[grow];
    }
    for (int a = 0; a < 3; ++a)
    {
      page->Texels[a] = static_cast<unsigned int>(page->Slots[a] * texels[a]);
    }
    if (page->Texels[0] > maxAxis || page->Texels[1] > maxAxis || page->Texels[2] > maxAxis)
    {
      error = "a brick of " + std::to_string(texels[0]) + "x" + std::to_string(texels[1]) + "x" +
        std::to_string(texels[2]) + " texels is larger than this OpenGL's largest 3D texture (" +
        std::to_string(maxAxis) +
        " a side, or 1024): draw with an OpenGL that allows larger 3D textures";
      return false;
    }
    page->Texture = vtkSmartPointer<vtkTextureObject>::New();
    vtkTextureObject* texture = page->Texture;
    texture->SetContext(window);
    texture->SetWrapS(vtkTextureObject::ClampToEdge);
    texture->SetWrapT(vtkTextureObject::ClampToEdge);
    texture->SetWrapR(vtkTextureObject::ClampToEdge);
    texture->SetMinificationFilter(vtkTextureObject::Linear);
    texture->SetMagnificationFilter(vtkTextureObject::Linear);
    texture->SetInternalFormat(this->TexelFormat.InternalFormat);
    if (!texture->Create3DFromRaw(page->Texels[0], page->Texels[1], page->Texels[2],
          this->TexelFormat.Channels, this->TexelFormat.StagedType, nullptr))
    {
      error = "OpenGL could not create a " + std::to_string(page->Texels[0]) + "x" +
        std::to_string(page->Texels[1]) + "x" + std::to_string(page->Texels[2]) +
        " 3D texture page for bricks of " + std::to_string(texels[0]) + "x" +
        std::to_string(texels[1]) + "x" + std::to_string(texels[2]) + " texels";
      return false;
    }
    page->Bytes =
      this->TexelFormat.TexelBytes * page->Texels[0] * page->Texels[1] * page->Texels[2];
    // Slot 0 is taken first.
    for (std::size_t s = page->Capacity(); s-- > 0;)
    {
      page->FreeSlots.push_back(s);
    }
    this->AllocatedBytes += page->Bytes;
    best = page.get();
    pages.push_back(std::move(page));
  }
  slot.Owner = best;
  for (int a = 0; a < 3; ++a)
  {
    slot.Texels[a] = texels[a];
  }
  slot.Index = best->FreeSlots.back();
  best->FreeSlots.pop_back();
  ++best->Used;
  const std::size_t i = slot.Index % best->Slots[0];
  const std::size_t j = (slot.Index / best->Slots[0]) % best->Slots[1];
  const std::size_t k = slot.Index / (best->Slots[0] * best->Slots[1]);
  slot.Offset[0] = static_cast<unsigned int>(i * texels[0]);
  slot.Offset[1] = static_cast<unsigned int>(j * texels[1]);
  slot.Offset[2] = static_cast<unsigned int>(k * texels[2]);
  return true;
}

bool vtkOpenGLHybridOctreeBrickPages::Upload(
  const Slot& slot, const void* staged, std::string& error)
{
  Page* page = slot.Owner;
  vtkTextureObject* texture = page->Texture;
  vtkOpenGLRenderWindow* window = texture->GetContext();
  window->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  texture->Activate();
  // Errors left by others are not this upload's (a bounded drain).
  for (int pending = 0; pending < 16 && glGetError() != GL_NO_ERROR; ++pending)
  {
  }
  const int type = this->TexelFormat.StagedType;
  glTexSubImage3D(GL_TEXTURE_3D, 0, static_cast<GLint>(slot.Offset[0]),
    static_cast<GLint>(slot.Offset[1]), static_cast<GLint>(slot.Offset[2]),
    static_cast<GLsizei>(slot.Texels[0]), static_cast<GLsizei>(slot.Texels[1]),
    static_cast<GLsizei>(slot.Texels[2]),
    texture->GetFormat(type, this->TexelFormat.Channels, false), texture->GetDataType(type),
    staged);
  texture->Deactivate();
  if (glGetError() != GL_NO_ERROR)
  {
    error = "OpenGL could not write a brick of " + std::to_string(slot.Texels[0]) + "x" +
      std::to_string(slot.Texels[1]) + "x" + std::to_string(slot.Texels[2]) +
      " texels into its texture page";
    return false;
  }
  return true;
}

void vtkOpenGLHybridOctreeBrickPages::Free(vtkWindow* window, const Slot& slot)
{
  Page* page = slot.Owner;
  if (!page)
  {
    return;
  }
  page->FreeSlots.push_back(slot.Index);
  --page->Used;
  if (page->Used > 0)
  {
    return;
  }
  const Shape shape = { page->Shape[0], page->Shape[1], page->Shape[2] };
  auto found = this->Shapes.find(shape);
  if (found == this->Shapes.end())
  {
    return;
  }
  auto& pages = found->second;
  for (auto it = pages.begin(); it != pages.end(); ++it)
  {
    if (it->get() == page)
    {
      page->Texture->ReleaseGraphicsResources(window);
      this->AllocatedBytes -= page->Bytes;
      pages.erase(it);
      break;
    }
  }
  if (pages.empty())
  {
    this->Shapes.erase(found);
  }
}

void vtkOpenGLHybridOctreeBrickPages::SetFormat(vtkWindow* window, const Format& format)
{
  if (!(format == this->TexelFormat))
  {
    this->Clear(window);
    this->TexelFormat = format;
  }
}

std::size_t vtkOpenGLHybridOctreeBrickPages::GetNumberOfPages() const
{
  std::size_t count = 0;
  for (const auto& shape : this->Shapes)
  {
    count += shape.second.size();
  }
  return count;
}

void vtkOpenGLHybridOctreeBrickPages::Clear(vtkWindow* window)
{
  for (auto& shape : this->Shapes)
  {
    for (auto& page : shape.second)
    {
      page->Texture->ReleaseGraphicsResources(window);
    }
  }
  this->Shapes.clear();
  this->AllocatedBytes = 0;
}
