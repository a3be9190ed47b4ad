// vtkRayTracePass's upload room: the frame's geometry, colors and textures
// into the GL buffers, each only when it changed.
#include "vtkRayTracePassInternals.h"

#include <algorithm>
#include <string>
#include <utility>

void vtkRayTracePass::Internals::Upload(const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win)
{
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  std::size_t limit = static_cast<std::size_t>(maxTexels);
  if (pass.MaximumTextureBufferTexels > 0)
  {
    limit = std::min(limit, static_cast<std::size_t>(pass.MaximumTextureBufferTexels));
  }
  // A scene refused for its size is tried again when the limit changes.
  const bool limitChanged = limit != this->CheckedLimit;
  this->CheckedLimit = limit;
  // What changed is appended to what the buffers hold, while they have
  // room; otherwise everything is packed anew.
  std::string unused;
  // A new limit: a refused scene is tried again, an uploaded one that no
  // longer fits is refused.
  const bool geometryRecheck = limitChanged &&
    (!this->GeometryValid || !vtkrt::pass::SceneBuffers::Fits(this->Places.Geometry, limit, unused));
  const bool colorsRecheck = limitChanged &&
    (!this->ColorsValid || !vtkrt::pass::SceneBuffers::Fits(this->Places.Colors, limit, unused));
  if (this->Scene.GeometryChanged() || !this->GeometryOnGpu || geometryRecheck)
  {
    const bool retree = this->Scene.OnlyTreesChanged() && this->GeometryOnGpu && !geometryRecheck;
    const std::size_t before = this->Counters.GeometryBytesUploaded;
    if (!(this->GeometryOnGpu && this->GeometryValid && !limitChanged && this->AppendGeometry(limit)))
    {
      this->UploadGeometry(pass, win, limit);
    }
    if (retree)
    {
      this->Counters.RetreeBytesUploaded += this->Counters.GeometryBytesUploaded - before;
    }
    this->Scene.MarkGeometryPacked();
    this->GeometryOnGpu = true;
  }
  if (this->Scene.ColorsChanged() || !this->ColorsOnGpu || colorsRecheck)
  {
    if (!(this->ColorsOnGpu && this->ColorsValid && !limitChanged && this->AppendColors(limit)))
    {
      this->UploadColors(pass, win, limit);
    }
    this->Scene.MarkColorsPacked();
    this->ColorsOnGpu = true;
  }
  this->UploadTextures(pass, win, limit, limitChanged);
}

bool vtkRayTracePass::Internals::AppendGeometry(std::size_t limit)
{
  vtkrt::pass::PhaseClock clock;
  vtkrt::pass::GeometryLayout next;
  std::vector<const vtkrt::pass::Geometry*> appended;
  std::string error;
  // The room was sized for the limit of its upload, which may have been
  // lowered since: a scene past the limit now is refused by UploadGeometry.
  const bool extended =
    vtkrt::pass::ExtendLayout(this->Scene, this->Places.Geometry, this->GeometryCapacity, next, appended);
  this->GeometryLastAppend = vtkrt::pass::SizesPast(this->Places.Geometry, next);
  if (!extended || !vtkrt::pass::SceneBuffers::Fits(next, limit, error))
  {
    return false;
  }
  this->Counters.PackingSeconds += clock.Lap();
  const vtkrt::pass::GeometryTargets targets = this->Buffers.MapAppended(this->Places.Geometry, next);
  this->Counters.UploadSeconds += clock.Lap();
  vtkrt::pass::WriteAppended(appended, next, targets);
  this->Counters.PackingSeconds += clock.Lap();
  this->Counters.GeometryBytesUploaded += this->Buffers.UnmapAppended();
  this->Counters.UploadSeconds += clock.Lap();
  this->Places.Geometry = std::move(next);
  return true;
}

void vtkRayTracePass::Internals::UploadGeometry(
  const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit)
{
  // Packed straight into the mapped GPU buffers: no copy of the scene on
  // the way; with room to append what changes later. A scene of one
  // geometry lends its arrays instead where the buffers can take them.
  vtkrt::pass::PhaseClock clock;
  vtkrt::pass::GeometryLayout layout = vtkrt::pass::LayOutGeometry(this->Scene);
  std::string error;
  this->GeometryValid = vtkrt::pass::SceneBuffers::Fits(layout, limit, error);
  if (this->GeometryValid)
  {
    const std::shared_ptr<const vtkrt::pass::Geometry> sole = this->Scene.SoleGeometry();
    const vtkrt::pass::GeometryLoans loans = sole ? vtkrt::pass::LendableArrays(*sole) : vtkrt::pass::GeometryLoans();
    this->Counters.PackingSeconds += clock.Lap();
    this->GeometryCapacity = vtkrt::pass::WithRoom(layout, limit, this->GeometryLastAppend);
    const vtkrt::pass::GeometryTargets targets =
      this->Buffers.MapGeometry(layout, this->GeometryCapacity, loans, sole);
    this->Counters.UploadSeconds += clock.Lap();
    vtkrt::pass::WriteGeometry(this->Scene, layout, targets);
    this->Counters.PackingSeconds += clock.Lap();
    this->Counters.GeometryBytesUploaded += this->Buffers.UnmapGeometry(win);
    this->Counters.GeometryBytesBorrowed += targets.BorrowedBytes;
    this->Counters.UploadSeconds += clock.Lap();
  }
  else
  {
    vtkErrorWithObjectMacro(&pass, << error);
  }
  this->Places.Geometry = std::move(layout);
}

bool vtkRayTracePass::Internals::AppendColors(std::size_t limit)
{
  vtkrt::pass::PhaseClock clock;
  vtkrt::pass::ColorsLayout next;
  std::vector<const vtkrt::pass::Colors*> appended;
  std::string error;
  const bool extended =
    vtkrt::pass::ExtendColors(this->Scene, this->Places.Colors, this->ColorsCapacity, next, appended);
  this->ColorsLastAppend = next.Words - this->Places.Colors.Words;
  if (!extended || !vtkrt::pass::SceneBuffers::Fits(next, limit, error))
  {
    return false;
  }
  const std::size_t from = this->Places.Colors.Words;
  auto* words = static_cast<std::uint32_t*>(this->Buffers.Colors.MapRange(from / 4, (next.Words - from) / 4));
  if (words)
  {
    vtkrt::pass::WriteAppendedColors(appended, next, words, from);
  }
  this->Counters.PackingSeconds += clock.Lap();
  this->Counters.GeometryBytesUploaded += this->Buffers.Colors.UnmapRange();
  this->Counters.UploadSeconds += clock.Lap();
  this->Places.Colors = std::move(next);
  return true;
}

void vtkRayTracePass::Internals::UploadColors(
  const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit)
{
  vtkrt::pass::PhaseClock clock;
  vtkrt::pass::ColorsLayout layout = vtkrt::pass::LayOutColors(this->Scene);
  std::string error;
  this->ColorsValid = vtkrt::pass::SceneBuffers::Fits(layout, limit, error);
  if (this->ColorsValid)
  {
    this->ColorsCapacity = vtkrt::pass::ColorWordsWithRoom(layout.Words, limit, this->ColorsLastAppend);
    auto* words = static_cast<std::uint32_t*>(this->Buffers.Colors.Map(layout.Words / 4, this->ColorsCapacity / 4));
    vtkrt::pass::WriteColors(this->Scene, layout, words);
    this->Counters.PackingSeconds += clock.Lap();
    this->Counters.GeometryBytesUploaded += this->Buffers.Colors.Unmap(win);
    this->Counters.UploadSeconds += clock.Lap();
  }
  else
  {
    vtkErrorWithObjectMacro(&pass, << error);
  }
  this->Places.Colors = std::move(layout);
}

void vtkRayTracePass::Internals::UploadTextures(
  const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit, bool limitChanged)
{
  vtkrt::pass::TextureCache& textures = this->Scene.GetTextures();
  if (!textures.Changed() && this->TexturesOnGpu && (this->TexturesValid || !limitChanged))
  {
    return;
  }
  vtkrt::pass::PhaseClock clock;
  vtkrt::pass::PackedTextures packed = textures.Pack();
  textures.MarkPacked();
  this->Counters.PackingSeconds += clock.Lap();
  std::string error;
  this->Counters.GeometryBytesUploaded +=
    this->Buffers.UploadTextures(win, packed, limit, this->TexturesValid, error);
  this->Counters.UploadSeconds += clock.Lap();
  this->Places.TextureBases = std::move(packed.Bases);
  this->TexturesOnGpu = true;
  if (!this->TexturesValid)
  {
    vtkErrorWithObjectMacro(&pass, << error);
  }
}
