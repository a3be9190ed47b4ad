// Private to vtkRayTracePass: its state and the named steps of a frame
// (vtkRayTracePassFrame.cxx); vtkRayTracePass.cxx keeps the knobs and the
// frame's page, Render.
#ifndef vtkRayTracePassInternals_h
#define vtkRayTracePassInternals_h

#include "vtkRayTracePass.h"

#include "pass/vtkRayTraceAccumulation.h"
#include "pass/vtkRayTraceBuffers.h"
#include "pass/vtkRayTraceDepthBelow.h"
#include "pass/vtkRayTraceLights.h"
#include "pass/vtkRayTracePacker.h"
#include "pass/vtkRayTraceRasterSteps.h"
#include "pass/vtkRayTraceRecords.h"
#include "pass/vtkRayTraceScene.h"
#include "pass/vtkRayTraceSelection.h"
#include "pass/vtkRayTraceShader.h"
#include "pass/vtkRayTraceTopLevel.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkDataObject.h"
#include "vtkHardwareSelector.h"
#include "vtkLightsPass.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkProp.h"
#include "vtkPropAssembly.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

/// The parts of a vtkPropAssembly, in its order; none for another prop.
inline std::vector<vtkProp*> PropAssemblyParts(vtkProp* prop)
{
  std::vector<vtkProp*> parts;
  if (auto* assembly = vtkPropAssembly::SafeDownCast(prop))
  {
    vtkCollectionSimpleIterator it;
    assembly->GetParts()->InitTraversal(it);
    while (vtkProp* part = assembly->GetParts()->GetNextProp(it))
    {
      parts.push_back(part);
    }
  }
  return parts;
}

/// The pass's state and the named steps of a frame.
struct vtkRayTracePass::Internals
{
  vtkrt::pass::Scene Scene;
  vtkNew<vtkLightsPass> Lights;
  std::vector<vtkProp*> Traced;
  std::vector<vtkProp*> Others;
  /// Of Others, the 3D props whose opaque geometry raster draws before the
  /// trace (RenderOthersBelow): empty when it draws them after.
  std::vector<vtkProp*> OthersBelow;
  /// The renderer draws over the depth of the renderers before it
  /// (KeepsDepthBelow, taken at the frame's start).
  bool KeepsBelow = false;
  vtkrt::pass::FrameCounters Counters;
  vtkrt::pass::ProgramCache Programs;
  /// The window whose context holds the pass's GL objects (none yet, or
  /// released); watched so they are released before it goes.
  vtkWeakPointer<vtkOpenGLRenderWindow> Window;
  unsigned long WindowDeleteObserver = 0;
  bool GeometryOnGpu = false;
  bool ColorsOnGpu = false;
  bool TexturesOnGpu = false;
  bool GeometryValid = true;
  bool ColorsValid = true;
  bool TexturesValid = true;
  std::size_t CheckedLimit = 0; ///< the texel limit the buffers were checked against
  std::vector<vtkrt::core::gpu::InstanceRecord> LastRecords; ///< the records on the GPU
  std::vector<std::uint32_t> LastTileEntries; ///< the tile entry lists on the GPU
  std::vector<int> WarnedTooSmallProps; ///< what the last scale warning named
  vtkrt::pass::SceneBuffers Buffers;
  vtkrt::pass::ScenePlacements Places;
  /// What the geometry and colors buffers have room for (see ExtendLayout).
  vtkrt::pass::GeometrySizes GeometryCapacity;
  std::size_t ColorsCapacity = 0; ///< words
  /// What the last append wrote or would have written (sizes the room).
  vtkrt::pass::GeometrySizes GeometryLastAppend;
  std::size_t ColorsLastAppend = 0; ///< words
  vtkrt::pass::TopLevel Top;
  vtkrt::pass::Accumulation Accumulated;
  /// Frames accumulated into the last image drawn at the window's own
  /// scale: what each tile of a scaled screenshot accumulates.
  int UntiledFrames = 1;
  vtkrt::pass::Selection Selecting;
  /// The depth below a renderer that keeps it (Features::DepthBelow),
  /// taken from its viewport each frame.
  vtkrt::pass::DepthBelow Below;
  /// GPU time of the tracing, one frame late, as vtkOpenGLPolyDataMapper
  /// times its draws (the props' render times, ReportRenderTimes).
  std::unique_ptr<vtkOpenGLRenderTimer> TraceTimer = std::make_unique<vtkOpenGLRenderTimer>();

  /// A frame ready to trace: what Prepare made for the tracer.
  struct Prepared
  {
    vtkrt::pass::CameraFrame Camera;
    vtkrt::pass::FrameRecords Frame;
    std::vector<vtkrt::core::gpu::Light> Lights;
    vtkrt::pass::Features F;
    double OcclusionRadius = 0.0;
    std::vector<vtkTextureObject*> Active; ///< bound samplers
    vtkOpenGLQuadHelper* Tracer = nullptr;
  };

  /// Writes the scene's changed geometry after what the buffers hold;
  /// false when it needs a new packing of everything (UploadGeometry).
  bool AppendGeometry(std::size_t limit);
  void UploadGeometry(const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit);
  /// The same for the colors.
  bool AppendColors(std::size_t limit);
  void UploadColors(const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit);

  void ReleaseGL(vtkWindow* w)
  {
    this->Accumulated.Release(w);
    this->Selecting.Release(w);
    this->Below.Release(w);
    this->TraceTimer->ReleaseGraphicsResources();
    this->Programs.Release(w);
    this->Buffers.Release(w);
    this->GeometryOnGpu = false;
    this->ColorsOnGpu = false;
    this->TexturesOnGpu = false;
    this->Top.Clear();
  }

  /// Makes `win` the window of the pass's GL objects: those of the window
  /// before are released in its own context first.
  void Attach(vtkOpenGLRenderWindow* win)
  {
    if (win == this->Window)
    {
      return;
    }
    this->Detach();
    // A window's PopContext may not restore the context (VTK's default).
    win->MakeCurrent();
    this->Window = win;
    auto release = vtkSmartPointer<vtkCallbackCommand>::New();
    release->SetClientData(this);
    release->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
      static_cast<Internals*>(self)->Detach();
    });
    this->WindowDeleteObserver = win->AddObserver(vtkCommand::DeleteEvent, release);
  }

  /// Releases the GL objects in their window's context (made current for it,
  /// then the current one is restored) and forgets the window.
  void Detach()
  {
    vtkOpenGLRenderWindow* win = this->Window;
    if (!win)
    {
      return;
    }
    win->RemoveObserver(this->WindowDeleteObserver);
    win->PushContext();
    this->ReleaseGL(win);
    win->PopContext();
    this->Window = nullptr;
  }

  /// The renderer's props -> traced instances and the props left to raster.
  void Extract(const vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren);
  /// A scene that could not be uploaded: its props go to the raster
  /// delegate this frame (the state's ones) and nothing counts as traced.
  void LeaveTracedToRaster(const vtkRenderState* s)
  {
    vtkProp** props = s->GetPropArray();
    const int count = s->GetPropArrayCount();
    for (vtkProp* prop : this->Traced)
    {
      if (std::find(props, props + count, prop) != props + count)
      {
        this->Others.push_back(prop);
      }
    }
    this->Traced.clear();
    this->Counters.TracedPrimitives = 0;
    this->Counters.TracedInstances = 0;
  }
  /// Packs and uploads the geometry, colors and textures that changed.
  void Upload(const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win);
  void UploadTextures(
    const vtkRayTracePass& pass, vtkOpenGLRenderWindow* win, std::size_t limit, bool limitChanged);
  /// Records (of the props `traced` says, all when null), top level,
  /// lights and shader (the selection ids variant when `selectIds`): the
  /// tracer ready, its uniforms set, its samplers bound; false when it
  /// cannot trace.
  /// The pixels a frame draws, as VTK's vtkCameraPass sets them: the
  /// renderer's tiled viewport, or all of a framebuffer that a wrapping
  /// pass (vtkSSAAPass, an image processing pass) draws the frame into.
  static void DrawnViewport(const vtkRenderState* s, vtkRenderer* ren, int size[2], int origin[2]);
  bool Prepare(const vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren,
    vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam, const std::vector<bool>* traced,
    bool selectIds, Prepared& p);
  /// Prepare, then the trace (straight or accumulated).
  /// What an accumulated image is traced from (Accumulation's signature).
  vtkrt::pass::ImageSignature AccumulationSignature(const Prepared& p) const;
  void Trace(const vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren,
    vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam, int framesBefore);
  /// One pass of the renderer's vtkHardwareSelector instead of a frame.
  void Select(vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren,
    vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam, vtkHardwareSelector* selector);
  /// What the frame needs from the shader.
  vtkrt::pass::Features FrameFeatures(const vtkRayTracePass& pass, vtkOpenGLRenderer* ren,
    const vtkrt::pass::CameraFrame& camera, const vtkrt::pass::FrameRecords& frame, std::size_t lights,
    bool topLevel, bool floatColors) const;
  /// The uniforms of the tracer other than the samplers.
  void SetUniforms(vtkShaderProgram* program, const vtkrt::pass::Features& f,
    const vtkrt::pass::CameraFrame& camera, const vtkrt::pass::FrameRecords& frame,
    const std::vector<vtkrt::core::gpu::Light>& lights, double occlusionRadius) const;
  /// Where the camera rays' walks start (the shader's VTKRT_TILE_ENTRIES):
  /// the frame's tile lists, uploaded when they changed, and their grid.
  void SetTileEntries(vtkOpenGLRenderer* ren, vtkOpenGLRenderWindow* win, Prepared& p);
  /// Whether the renderer draws over the depth that the renderers before it
  /// left: VTK clears the depth only for a renderer that erases and does not
  /// preserve it (vtkOpenGLRenderer::Clear, called only when both the window
  /// and the renderer erase), and raster tests it only where the depth test
  /// is on (a window that never erased has it off: raster draws in prop
  /// order, over a depth buffer that holds nothing).
  static bool KeepsDepthBelow(vtkRenderer* ren, vtkOpenGLState* ostate);
  /// Where traced translucent layers may lie over raster's opaque 3D props,
  /// draws those first (OthersBelow) through the delegate, so the
  /// trace ends its camera rays at their depth (Features::DepthBelow) and
  /// its layers composite over them; else OthersBelow stays empty.
  void RenderOthersBelow(vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren);
  /// Draws the rest of what the pass did not trace through the delegate.
  void RenderOthers(vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren);
};

/// One state per renderer, so that a pass shared by renderers keeps each
/// one's scene (as raster keeps each mapper's buffers) instead of
/// rebuilding it whenever the other renderer drew last.
struct vtkRayTracePass::RendererStates
{
  struct Entry
  {
    vtkWeakPointer<vtkRenderer> Renderer;
    bool Claimed = false; ///< a renderer has used it (it may be gone since)
    std::unique_ptr<Internals> State = std::make_unique<Internals>();
  };
  /// The first entry waits for the first renderer, so that the getters
  /// have a state before any frame.
  std::vector<Entry> Entries = std::vector<Entry>(1);

  /// `ren`'s state, made on its first frame; the states of deleted
  /// renderers are released (`released`: some was, in its own window's
  /// context, which may have left another current).
  Internals& For(vtkRenderer* ren, bool& released)
  {
    released = false;
    for (auto it = this->Entries.begin(); it != this->Entries.end();)
    {
      if (it->Claimed && !it->Renderer && this->Entries.size() > 1)
      {
        released = released || it->State->Window;
        it->State->Detach();
        it = this->Entries.erase(it);
        continue;
      }
      ++it;
    }
    for (Entry& e : this->Entries)
    {
      if (e.Claimed && e.Renderer == ren)
      {
        return *e.State;
      }
    }
    for (Entry& e : this->Entries)
    {
      if (!e.Claimed || !e.Renderer)
      {
        e.Renderer = ren;
        e.Claimed = true;
        return *e.State;
      }
    }
    this->Entries.emplace_back();
    this->Entries.back().Renderer = ren;
    this->Entries.back().Claimed = true;
    return *this->Entries.back().State;
  }
  /// The GL objects of the states in `w` (every state's when null)
  /// released: the window may be going away.
  void Detach(vtkWindow* w)
  {
    for (Entry& e : this->Entries)
    {
      if (!w || e.State->Window.GetPointer() == w)
      {
        e.State->Detach();
      }
    }
  }
};

#endif
