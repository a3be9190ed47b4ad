#include "vtkRayTraceRasterSteps.h"

#include "vtkDualDepthPeelingPass.h"
#include "vtkHiddenLineRemovalPass.h"
#include "vtkLightsPass.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpaquePass.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOrderIndependentTranslucentPass.h"
#include "vtkOverlayPass.h"
#include "vtkProp.h"
#include "vtkRenderState.h"
#include "vtkTranslucentPass.h"
#include "vtkVolumetricPass.h"

vtkStandardNewMacro(vtkRayTraceRasterSteps);

vtkRayTraceRasterSteps::vtkRayTraceRasterSteps()
  : Lights(vtkSmartPointer<vtkLightsPass>::New())
  , Opaque(vtkSmartPointer<vtkOpaquePass>::New())
  , Volumes(vtkSmartPointer<vtkVolumetricPass>::New())
  , Overlay(vtkSmartPointer<vtkOverlayPass>::New())
  , Blended(vtkSmartPointer<vtkOrderIndependentTranslucentPass>::New())
{
  vtkNew<vtkTranslucentPass> translucent;
  this->Blended->SetTranslucentPass(translucent);
}

vtkRayTraceRasterSteps::~vtkRayTraceRasterSteps() = default;

void vtkRayTraceRasterSteps::Step(vtkRenderPass* pass, const vtkRenderState* s)
{
  pass->Render(s);
  this->NumberOfRenderedProps += pass->GetNumberOfRenderedProps();
}

bool vtkRayTraceRasterSteps::Translucent(const vtkRenderState* s, vtkOpenGLRenderer* ren)
{
  if (!ren->GetUseDepthPeeling())
  {
    this->Step(this->Blended, s);
    return false;
  }
  if (!this->Peeled)
  {
    if (ren->IsDualDepthPeelingSupported())
    {
      this->Peeled = vtkSmartPointer<vtkDualDepthPeelingPass>::New();
    }
    else
    {
      this->Peeled = vtkSmartPointer<vtkDepthPeelingPass>::New();
    }
    vtkNew<vtkTranslucentPass> translucent;
    this->Peeled->SetTranslucentPass(translucent);
  }
  auto* dual = vtkDualDepthPeelingPass::SafeDownCast(this->Peeled);
  const bool peelVolumes = ren->GetUseDepthPeelingForVolumes() && dual;
  if (ren->GetUseDepthPeelingForVolumes() && !dual)
  {
    vtkWarningMacro("UseDepthPeelingForVolumes requested, but unsupported since dual depth "
                    "peeling is not available.");
  }
  if (dual)
  {
    dual->SetVolumetricPass(peelVolumes ? this->Volumes.Get() : nullptr);
  }
  this->Peeled->SetMaximumNumberOfPeels(ren->GetMaximumNumberOfPeels());
  this->Peeled->SetOcclusionRatio(ren->GetOcclusionRatio());
  this->Step(this->Peeled, s);
  return peelVolumes;
}

void vtkRayTraceRasterSteps::FXAA(vtkOpenGLRenderer* ren)
{
  if (!this->FXAAFilter)
  {
    this->FXAAFilter = vtkSmartPointer<vtkOpenGLFXAAFilter>::New();
  }
  if (ren->GetFXAAOptions())
  {
    this->FXAAFilter->UpdateConfiguration(ren->GetFXAAOptions());
  }
  this->FXAAFilter->Execute(ren);
}

void vtkRayTraceRasterSteps::Render(const vtkRenderState* s)
{
  this->RenderOpaque(s);
  const int opaque = this->NumberOfRenderedProps;
  this->RenderAfterOpaque(s);
  this->NumberOfRenderedProps += opaque;
}

vtkOpenGLRenderer* vtkRayTraceRasterSteps::Begin(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  auto* ren = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
  if (!ren)
  {
    vtkErrorMacro("vtkRayTraceRasterSteps needs a vtkOpenGLRenderer.");
  }
  return ren;
}

void vtkRayTraceRasterSteps::RenderOpaque(const vtkRenderState* s)
{
  vtkOpenGLRenderer* ren = this->Begin(s);
  if (!ren)
  {
    return;
  }
  this->Step(this->Lights, s);
  if (ren->GetUseHiddenLineRemoval() &&
    vtkHiddenLineRemovalPass::WireframePropsExist(s->GetPropArray(), s->GetPropArrayCount()))
  {
    if (!this->HiddenLines)
    {
      this->HiddenLines = vtkSmartPointer<vtkHiddenLineRemovalPass>::New();
    }
    this->Step(this->HiddenLines, s);
  }
  else
  {
    this->Step(this->Opaque, s);
  }
}

void vtkRayTraceRasterSteps::RenderAfterOpaque(const vtkRenderState* s)
{
  vtkOpenGLRenderer* ren = this->Begin(s);
  if (!ren)
  {
    return;
  }
  bool translucent = false;
  for (int i = 0; i < s->GetPropArrayCount() && !translucent; ++i)
  {
    translucent = s->GetPropArray()[i]->HasTranslucentPolygonalGeometry() != 0;
  }
  const bool volumesPeeled = translucent && this->Translucent(s, ren);
  if (ren->GetUseFXAA())
  {
    this->FXAA(ren);
  }
  if (!volumesPeeled)
  {
    this->Step(this->Volumes, s);
  }
  this->Step(this->Overlay, s);
}

void vtkRayTraceRasterSteps::ReleaseGraphicsResources(vtkWindow* w)
{
  for (vtkRenderPass* pass : { this->Lights.Get(), this->Opaque.Get(), this->HiddenLines.Get(),
         this->Volumes.Get(),
         this->Overlay.Get(), static_cast<vtkRenderPass*>(this->Blended.Get()),
         static_cast<vtkRenderPass*>(this->Peeled.Get()) })
  {
    if (pass)
    {
      pass->ReleaseGraphicsResources(w);
    }
  }
  if (this->FXAAFilter)
  {
    this->FXAAFilter->ReleaseGraphicsResources();
  }
}

void vtkRayTraceRasterSteps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Peeled: " << this->Peeled << "\n";
}
