#include "vtkRayTraceSelection.h"

#include "vtkRayTraceScene.h"
#include "vtkRayTraceSelectionMapper.h"
#include "vtkRayTraceShader.h"

#include "vtkActor.h"
#include "vtkHardwareSelector.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <utility>

namespace vtkrt
{
namespace pass
{

namespace
{
/// Which value of the id buffer a selector pass writes (see the shader).
int componentOf(int currentPass)
{
  switch (currentPass)
  {
    case vtkHardwareSelector::POINT_ID_LOW24:
    case vtkHardwareSelector::CELL_ID_LOW24:
      return 1;
    case vtkHardwareSelector::POINT_ID_HIGH24:
    case vtkHardwareSelector::CELL_ID_HIGH24:
      return 2;
    case vtkHardwareSelector::COMPOSITE_INDEX_PASS:
      return 3;
    default: // actor and process passes: the selector's prop color
      return 0;
  }
}
/// VTK 9.1 keeps the pick list of vtkRenderer::PickPropFrom protected with
/// no accessor; vtkOpenGLRenderer::UpdateGeometry reads it, and so must we.
struct ViewportPickList : vtkViewport
{
  static vtkPropCollection* Of(vtkViewport* viewport)
  {
    return viewport->*(&ViewportPickList::PickFromProps);
  }
};
/// VTK 9.1 keeps the prop a selector renders (its PropID) protected with no
/// accessor; the stand-in mappers need it to know which prop draws them.
struct SelectorPropID : vtkHardwareSelector
{
  static int Of(vtkHardwareSelector* selector)
  {
    return selector->*(&SelectorPropID::PropID);
  }
};
} // namespace

std::vector<SelectableProp> SelectablePropsOf(
  const std::vector<vtkProp*>& traced, const std::vector<Instance>& instances)
{
  std::vector<SelectableProp> selectable(traced.size());
  std::vector<PropPart> parts;
  for (std::size_t i = 0; i < traced.size(); ++i)
  {
    selectable[i].Prop = traced[i];
    PartsOf(traced[i], parts);
    for (const PropPart& part : parts)
    {
      selectable[i].Actors.push_back(part.Actor);
    }
  }
  for (const Instance& inst : instances)
  {
    std::uint32_t& maximum = selectable[static_cast<std::size_t>(inst.PropIndex)].MaximumId;
    maximum = std::max(maximum, inst.Geom->MaximumId);
  }
  return selectable;
}

std::vector<vtkProp*> SelectionProps(vtkRenderer* ren, vtkProp** props, int count)
{
  vtkPropCollection* pickFrom = ViewportPickList::Of(ren);
  if (!pickFrom)
  {
    return std::vector<vtkProp*>(props, props + count);
  }
  std::vector<vtkProp*> picked;
  vtkCollectionSimpleIterator it;
  pickFrom->InitTraversal(it);
  while (vtkProp* prop = pickFrom->GetNextProp(it))
  {
    if (prop->GetVisibility())
    {
      picked.push_back(prop);
    }
  }
  return picked;
}

Selection::Selection() = default;
Selection::~Selection() = default;

void Selection::Allocate(vtkOpenGLRenderWindow* win, int width, int height)
{
  vtkOpenGLState* ostate = win->GetState();
  this->Ids->SetContext(win);
  this->Ids->SetMinificationFilter(vtkTextureObject::Nearest);
  this->Ids->SetMagnificationFilter(vtkTextureObject::Nearest);
  this->Ids->Allocate2D(width, height, 4, VTK_FLOAT);
  this->Depth->SetContext(win);
  this->Depth->AllocateDepth(width, height, vtkTextureObject::Float32);
  this->FBO->SetContext(win);
  ostate->PushFramebufferBindings();
  this->FBO->Bind();
  this->FBO->AddColorAttachment(0, this->Ids);
  this->FBO->AddDepthAttachment(this->Depth);
  ostate->PopFramebufferBindings();
  this->Size[0] = width;
  this->Size[1] = height;
}

std::array<int, 4> Selection::AreaInViewport(
  vtkHardwareSelector* selector, const int viewportOrigin[2], const int viewportSize[2])
{
  const unsigned int* area = selector->GetArea();
  // Inclusive display pixels, clamped to the viewport.
  const long x0 = std::max<long>(static_cast<long>(area[0]) - viewportOrigin[0], 0);
  const long y0 = std::max<long>(static_cast<long>(area[1]) - viewportOrigin[1], 0);
  const long x1 = std::min<long>(static_cast<long>(area[2]) - viewportOrigin[0], viewportSize[0] - 1L);
  const long y1 = std::min<long>(static_cast<long>(area[3]) - viewportOrigin[1], viewportSize[1] - 1L);
  if (x1 < x0 || y1 < y0)
  {
    return { 0, 0, 0, 0 };
  }
  return { static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 - x0 + 1),
    static_cast<int>(y1 - y0 + 1) };
}

bool Selection::Holds(const ImageSignature& signature, const std::array<int, 4>& area) const
{
  return this->Traced && area == this->TracedArea && signature.Same(this->TracedSignature);
}

void Selection::Invalidate()
{
  this->Traced = false;
  this->TracedSignature.Clear();
}

void Selection::TraceIds(vtkOpenGLRenderWindow* win, const int viewportOrigin[2], const int viewportSize[2],
  const std::array<int, 4>& area, vtkOpenGLQuadHelper* tracer, ImageSignature signature)
{
  vtkOpenGLState* ostate = win->GetState();
  const int width = std::max(viewportSize[0], 1), height = std::max(viewportSize[1], 1);
  if (width != this->Size[0] || height != this->Size[1])
  {
    this->Allocate(win, width, height);
  }
  ostate->PushFramebufferBindings();
  this->FBO->Bind();
  this->FBO->ActivateDrawBuffers(1);
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  vtkOpenGLState::ScopedglEnableDisable scissorTest(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor scissor(ostate);
  vtkOpenGLState::ScopedglClearColor clearColor(ostate);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglViewport(0, 0, width, height);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // Only the pixels the selection reads are traced.
  if (area[2] > 0 && area[3] > 0)
  {
    ostate->vtkglEnable(GL_SCISSOR_TEST);
    ostate->vtkglScissor(area[0], area[1], area[2], area[3]);
    tracer->Render();
  }
  ostate->PopFramebufferBindings();
  this->Traced = true;
  this->TracedSignature = std::move(signature);
  this->TracedArea = area;
  this->TracedOrigin[0] = viewportOrigin[0];
  this->TracedOrigin[1] = viewportOrigin[1];
}

int Selection::RenderPass(vtkOpenGLRenderWindow* win, vtkRenderer* ren,
  vtkHardwareSelector* selector, std::vector<vtkProp*>& props,
  const std::vector<SelectableProp>& traced, FrameCounters& counters)
{
  this->Window = win;
  this->Counters = &counters;
  this->Props = &traced;
  // The actors keep their own mappers except for this one call; an actor
  // in two props draws the ids of the one being rendered.
  std::vector<std::pair<vtkActor*, vtkSmartPointer<vtkMapper>>> originals;
  std::size_t used = 0;
  for (std::size_t i = 0; i < traced.size(); ++i)
  {
    for (vtkActor* actor : traced[i].Actors)
    {
      if (std::any_of(originals.begin(), originals.end(),
            [actor](const std::pair<vtkActor*, vtkSmartPointer<vtkMapper>>& o) { return o.first == actor; }))
      {
        continue;
      }
      if (used == this->StandIns.size())
      {
        this->StandIns.push_back(vtkSmartPointer<vtkRayTraceSelectionMapper>::New());
      }
      vtkRayTraceSelectionMapper* standIn = this->StandIns[used++];
      originals.emplace_back(actor, actor->GetMapper());
      standIn->SetStandIn(this, actor->GetMapper());
      actor->SetMapper(standIn);
    }
  }
  const int rendered = selector->Render(ren, props.data(), static_cast<int>(props.size()));
  for (std::size_t k = 0; k < originals.size(); ++k)
  {
    originals[k].first->SetMapper(originals[k].second);
    this->StandIns[k]->SetStandIn(nullptr, nullptr);
  }
  this->Props = nullptr;
  this->Window = nullptr;
  this->Counters = nullptr;
  return rendered;
}

int Selection::CurrentIndex(vtkHardwareSelector* selector) const
{
  vtkProp* current = selector->GetPropFromID(SelectorPropID::Of(selector));
  if (!this->Props || !current)
  {
    return -1;
  }
  for (std::size_t i = 0; i < this->Props->size(); ++i)
  {
    if ((*this->Props)[i].Prop == current)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::uint32_t Selection::MaximumId(int index) const
{
  return this->Props && index >= 0 && index < static_cast<int>(this->Props->size())
    ? (*this->Props)[static_cast<std::size_t>(index)].MaximumId
    : 0u;
}

void Selection::DrawProp(vtkHardwareSelector* selector, int index)
{
  if (!this->Window || !this->Traced ||
    !ReadyQuadProgram(this->Window, this->DrawProgram, SelectShaderSource(), *this->Counters))
  {
    return;
  }
  vtkOpenGLState* ostate = this->Window->GetState();
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissorTest(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor scissor(ostate);
  // The traced area (the selection's) in window pixels: the rest holds no hit.
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  ostate->vtkglScissor(this->TracedOrigin[0] + this->TracedArea[0], this->TracedOrigin[1] + this->TracedArea[1],
    this->TracedArea[2], this->TracedArea[3]);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  vtkShaderProgram* program = this->DrawProgram->Program;
  this->Ids->Activate();
  this->Depth->Activate();
  program->SetUniformi("uSelectIds", this->Ids->GetTextureUnit());
  program->SetUniformi("uSelectDepth", this->Depth->GetTextureUnit());
  program->SetUniformf("uProp", static_cast<float>(index + 1));
  program->SetUniformi("uComponent", componentOf(selector->GetCurrentPass()));
  program->SetUniform3f("uPropColor", selector->GetPropColorValue());
  this->DrawProgram->Render();
  this->Ids->Deactivate();
  this->Depth->Deactivate();
}

void Selection::Release(vtkWindow* w)
{
  if (this->DrawProgram)
  {
    this->DrawProgram->ReleaseGraphicsResources(w);
    this->DrawProgram.reset();
  }
  this->FBO->ReleaseGraphicsResources(w);
  this->Ids->ReleaseGraphicsResources(w);
  this->Depth->ReleaseGraphicsResources(w);
  this->Size[0] = this->Size[1] = 0;
  this->Invalidate();
}

} // namespace pass
} // namespace vtkrt
