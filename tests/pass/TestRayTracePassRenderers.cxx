// vtkRayTracePass among several renderers, as applications arrange them:
//   SharedByRenderers one pass set on two renderers (two viewports of a
//                     window, two windows): each keeps its scene, so frames
//                     after the first build and upload nothing
//   PreservedDepth    a renderer on a layer above another that keeps its
//                     depth buffer (SetPreserveDepthBuffer), or on the same
//                     layer with Erase off: traced surfaces and translucent
//                     layers behind the lower renderer's stay hidden, as
//                     with raster
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOutlineSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
// One pass set on two renderers, as an application with several views may
// do: two viewports of one window, then two windows. Each renderer keeps
// its own scene, so every frame after the first builds and uploads no
// geometry, and each image is the one a pass of its own traces.
void TestSharedByRenderers()
{
  struct Counts
  {
    vtkRayTracePass* Pass = nullptr;
    int Builds = 0;
    vtkTypeInt64 Bytes = 0;
  };
  auto record = [](vtkRenderer* ren, Counts& counts) {
    vtkNew<vtkCallbackCommand> end;
    end->SetClientData(&counts);
    end->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
      auto* c = static_cast<Counts*>(data);
      if (c->Pass)
      {
        c->Builds += c->Pass->GetLastBVHBuilds();
        c->Bytes += c->Pass->GetLastGeometryBytesUploaded();
      }
    });
    ren->AddObserver(vtkCommand::EndEvent, end);
  };
  auto meshRenderer = [](const char* file, double azimuth) {
    auto ren = vtkSmartPointer<vtkRenderer>::New();
    ren->AddActor(MeshActor(ReadPolyData(file)));
    ren->ResetCamera();
    ren->GetActiveCamera()->Azimuth(azimuth);
    return ren;
  };
  for (const bool twoWindows : { false, true })
  {
    const std::string label = twoWindows ? "two windows" : "two viewports";
    vtkSmartPointer<vtkRenderer> ren[2] = { meshRenderer("bunny.vtp", 0.0),
      meshRenderer("bunny.vtp", 60.0) };
    ren[1]->AddActor(SphereActor(0.05, 0.1, 0.0, 0.03));
    vtkSmartPointer<vtkEGLHeadlessRenderWindow> win[2] = { MakeWindow(160, 120), nullptr };
    win[1] = twoWindows ? MakeWindow(160, 120) : win[0];
    if (!twoWindows)
    {
      ren[0]->SetViewport(0.0, 0.0, 0.5, 1.0);
      ren[1]->SetViewport(0.5, 0.0, 1.0, 1.0);
    }
    win[0]->AddRenderer(ren[0]);
    win[1]->AddRenderer(ren[1]);
    // What a pass of its own traces for each.
    vtkSmartPointer<vtkImageData> own[2];
    for (int i = 0; i < 2; ++i)
    {
      vtkNew<vtkRayTracePass> fresh;
      ren[i]->SetPass(fresh);
      win[i]->Render();
      ren[i]->SetPass(nullptr);
    }
    own[0] = Grab(win[0]);
    own[1] = Grab(win[1]);

    vtkNew<vtkRayTracePass> pass;
    Counts counts[2];
    for (int i = 0; i < 2; ++i)
    {
      ren[i]->SetPass(pass);
      counts[i].Pass = pass;
      record(ren[i], counts[i]);
    }
    auto renderAll = [&]() {
      win[0]->Render();
      if (twoWindows)
      {
        win[1]->Render();
      }
    };
    renderAll();
    Check(counts[0].Builds > 0 && counts[1].Builds > 0,
      label + ": the first frame builds each renderer's scene");
    for (Counts& c : counts)
    {
      c.Builds = 0;
      c.Bytes = 0;
    }
    for (int frame = 0; frame < 3; ++frame)
    {
      renderAll();
    }
    std::ostringstream s;
    s << label << ": three frames more build " << counts[0].Builds << " and " << counts[1].Builds
      << " trees and upload " << counts[0].Bytes << " and " << counts[1].Bytes << " bytes";
    Check(counts[0].Builds == 0 && counts[1].Builds == 0 && counts[0].Bytes == 0 &&
        counts[1].Bytes == 0,
      s.str());
    Check(Difference(Grab(win[0]), own[0]) == 0.0 && Difference(Grab(win[1]), own[1]) == 0.0,
      label + ": each image is the one a pass of its own traces");
    if (twoWindows)
    {
      // The first window's renderer removed (it releases the pass's objects
      // there): the second window's keep theirs.
      win[0]->RemoveRenderer(ren[0]);
      counts[1].Bytes = 0;
      win[1]->Render();
      Check(counts[1].Bytes == 0 && Difference(Grab(win[1]), own[1]) == 0.0,
        label + ": after the first window's renderer is removed the second uploads " +
          std::to_string(counts[1].Bytes) + " bytes");
    }
    for (int i = 0; i < 2; ++i)
    {
      counts[i].Pass = nullptr;
      ren[i]->SetPass(nullptr);
    }
    NoGLError(win[0], label);
  }
  NoVTKOutput("shared by renderers");
}

// Two layers sharing a camera: layer 0 draws a ball in front, layer 1 keeps
// that depth (SetPreserveDepthBuffer) and draws a box behind it, which the
// ball hides, traced on layer 1 (also with samples), on layer 0, or on
// both (one pass shared).
void TestPreservedDepth()
{
  // A renderer drawn over the depth that the one before it left: on a layer
  // above it with SetPreserveDepthBuffer, or on the same layer with Erase
  // off. Its box, opaque or translucent (depth peeling), lies partly in
  // front of the lower renderer's sphere and partly behind it. Coincident:
  // the upper renderer also draws the lower one's sphere, in red, which
  // raster's test (less or equal) draws over it.
  struct Options
  {
    bool EraseOff = false;
    bool Translucent = false;
    bool Coincident = false;
    int MultiSamples = 0; ///< the window's MSAA (the depth below is then resolved)
  };
  struct Layers
  {
    vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(200, 160);
    vtkNew<vtkRenderer> Lower;
    vtkNew<vtkRenderer> Upper;
    explicit Layers(const Options& o)
    {
      this->Window->SetMultiSamples(o.MultiSamples);
      this->Window->SetNumberOfLayers(2);
      this->Window->AddRenderer(this->Lower);
      this->Window->AddRenderer(this->Upper);
      if (o.EraseOff)
      {
        this->Upper->SetErase(false);
      }
      else
      {
        this->Upper->SetLayer(1);
        this->Upper->SetPreserveDepthBuffer(true);
      }
      this->Upper->SetActiveCamera(this->Lower->GetActiveCamera());
      this->Lower->SetBackground(0.1, 0.1, 0.15);
      this->Lower->AddActor(SphereActor(0.0, 0.0, o.Translucent ? -0.6 : 1.0, 0.8));
      vtkNew<vtkCubeSource> cube;
      cube->SetXLength(2.0);
      cube->SetYLength(1.2);
      cube->Update();
      auto box = MeshActor(cube->GetOutput());
      box->GetProperty()->SetColor(0.2, 0.8, 0.3);
      if (o.Translucent)
      {
        box->GetProperty()->SetOpacity(0.5);
        this->Upper->SetUseDepthPeeling(true);
      }
      this->Upper->AddActor(box);
      if (o.Coincident)
      {
        auto sphere = SphereActor(0.0, 0.0, o.Translucent ? -0.6 : 1.0, 0.8);
        sphere->GetProperty()->SetColor(0.9, 0.2, 0.2);
        this->Upper->AddActor(sphere);
      }
      this->Lower->ResetCamera(-1.0, 1.0, -0.6, 0.6, -1.4, 1.8);
      this->Lower->GetActiveCamera()->Elevation(15.0);
      this->Lower->ResetCameraClippingRange(-1.0, 1.0, -0.6, 0.6, -1.4, 1.8);
      this->Upper->ResetCameraClippingRange(-1.0, 1.0, -0.6, 0.6, -1.4, 1.8);
    }
  };
  struct Variant
  {
    const char* Label;
    Options Layout;
    bool TraceUpper;
    bool TraceLower;
    int Samples;
  };
  const Variant variants[] = {
    { "traced on the upper layer", {}, true, false, 1 },
    { "traced on the lower layer", {}, false, true, 1 },
    { "traced on both (one pass)", {}, true, true, 1 },
    { "traced on the upper layer, 4 samples a pixel", {}, true, false, 4 },
    { "translucent box traced on the upper layer", { false, true }, true, false, 1 },
    { "translucent box traced on the upper layer, 4 samples a pixel", { false, true }, true, false, 4 },
    { "erase off, traced over the other renderer", { true, false }, true, false, 1 },
    { "erase off, translucent box traced over the other renderer", { true, true }, true, false, 1 },
    { "the lower layer's sphere drawn again, traced on the upper layer", { false, false, true }, true, false, 1 },
    { "the lower layer's sphere drawn again, traced on both", { false, false, true }, true, true, 1 },
    { "traced on the upper layer, MSAA 4", { false, false, false, 4 }, true, false, 1 },
    { "erase off, traced over the other renderer, MSAA 4", { true, false, false, 4 }, true, false, 1 },
  };
  int index = 0;
  for (const Variant& v : variants)
  {
    Layers raster(v.Layout);
    raster.Window->Render();
    vtkSmartPointer<vtkImageData> expected = Grab(raster.Window);
    Layers traced(v.Layout);
    vtkNew<vtkRayTracePass> pass;
    pass->SetSamplesPerPixel(v.Samples);
    if (v.TraceUpper)
    {
      traced.Upper->SetPass(pass);
    }
    if (v.TraceLower)
    {
      traced.Lower->SetPass(pass);
    }
    traced.Window->Render();
    vtkSmartPointer<vtkImageData> image = Grab(traced.Window);
    // Samples smooth the silhouettes raster leaves hard: compared blurred.
    const long off = CountDifferingPixels(image, expected, 40);
    const double rmse = RootMeanSquareError(Blurred(image), Blurred(expected));
    // Samples and MSAA smooth silhouettes differently: compared blurred.
    const bool ok = v.Samples > 1 || v.Layout.MultiSamples > 0 ? rmse <= 2.0 : off <= 20;
    std::ostringstream s;
    s << "preserved depth, " << v.Label << ": " << off << " pixels off raster by more than 40, blurred RMSE "
      << rmse;
    Check(ok, s.str());
    if (!ok)
    {
      WriteFailedImages("preserved-depth-" + std::to_string(index), expected, image);
    }
    NoGLError(traced.Window, v.Label);
    ++index;
  }
  NoVTKOutput("preserved depth");

  // Erase off in a window that never erased: its depth holds nothing and
  // raster has the depth test off there (it draws triangles in cell order,
  // back over front), so the pass traces as over nothing, the image of a
  // window that erases to black (it drew nothing at all before).
  // Also a translucent sphere with an outline that raster draws (its opaque
  // props go before the trace only where the depth test is on).
  for (const int variant : { 0, 1, 2 })
  {
    const bool onWindow = variant == 1;
    const bool translucent = variant == 2;
    auto make = [&](bool erase, vtkRayTracePass* pass) {
      auto win = MakeWindow(160, 120);
      vtkNew<vtkRenderer> ren;
      win->AddRenderer(ren);
      auto ball = SphereActor(0.0, 0.0, 0.0, 0.8);
      ren->AddActor(ball);
      if (translucent)
      {
        ball->GetProperty()->SetOpacity(0.5);
        vtkNew<vtkOutlineSource> box;
        box->SetBounds(-1.0, 1.0, -1.0, 1.0, -1.0, 1.0);
        box->Update();
        ren->AddActor(MeshActor(box->GetOutput()));
      }
      ren->ResetCamera();
      if (onWindow)
      {
        win->SetErase(erase);
      }
      else
      {
        ren->SetErase(erase);
      }
      ren->SetPass(pass);
      win->Render();
      return Grab(win);
    };
    vtkNew<vtkRayTracePass> erasing;
    vtkSmartPointer<vtkImageData> expected = make(true, erasing);
    vtkNew<vtkRayTracePass> pass;
    vtkSmartPointer<vtkImageData> image = make(false, pass);
    const long off = CountDifferingPixels(image, expected, 40);
    std::ostringstream s;
    s << "erase off (" << (onWindow ? "window" : "renderer") << (translucent ? ", translucent over an outline" : "")
      << ") in a window that never erased: " << off << " pixels off the erasing window's image by more than 40";
    Check(pass->GetNumberOfTracedProps() == 1 && off <= 20, s.str());
  }
  NoVTKOutput("never erased");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "SharedByRenderers", TestSharedByRenderers }, { "PreservedDepth", TestPreservedDepth } });
}
