// Actors the pass leaves to raster, drawn as raster draws them: each beside
// a traced mesh, the window compared with raster's (pass.LeftToRaster).
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkCallbackCommand.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"
#include "vtkShaderProperty.h"
#include "vtkSkybox.h"
#include "vtkTexture.h"

#include <string>

using namespace vtkrtPassTest;

namespace
{
/// The scenes, seen from one orbit: failed images as raster-props-N.*.png.
struct Scene : ComparedScene
{
  Scene()
    : ComparedScene(320, "raster-props")
  {
  }
  void View() { this->ComparedScene::View(30.0, 20.0); }
};

// Mappers and actors that only raster can draw as VTK does are left to it
// beside a traced mesh: point splats (their polygons would be traced as a
// surface), shader code of the application's (on the actor's shader
// property or through the mapper's deprecated API), and an actor forced
// opaque whose opacity is not 1 (VTK blends it in its opaque pass), and
// highlights VTK draws over a surface (a mapper's selection, vertices
// beside edges), and a projective matrix (raster divides by w).
void TestLeftToRaster()
{
  // `actor` beside a traced mesh: only the mesh is traced.
  auto compareBeside = [](const std::string& label, vtkActor* actor, bool hiddenLines = false) {
    Scene scene;
    scene.Renderer->AddActor(MeshActor(Sphere(-0.6, 24)));
    scene.Renderer->AddActor(actor);
    scene.Renderer->SetUseHiddenLineRemoval(hiddenLines);
    scene.View();
    scene.Compare(label, 1, 2.0);
  };
  {
    // An environment texture, as vtkSkybox draws it behind the scene.
    vtkNew<vtkImageData> grid;
    grid->SetDimensions(32, 32, 1);
    grid->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    auto* texels = static_cast<unsigned char*>(grid->GetScalarPointer());
    for (int i = 0; i < 32 * 32 * 3; ++i)
    {
      texels[i] = static_cast<unsigned char>(((i / 3) % 32 / 4 + (i / 96) / 4) % 2 ? 200 : 40);
    }
    vtkNew<vtkTexture> texture;
    texture->SetInputData(grid);
    vtkNew<vtkSkybox> skybox;
    skybox->SetTexture(texture);
    skybox->SetProjectionToSphere();
    compareBeside("a vtkSkybox", skybox);
  }
  {
    // The observer sets a uniform of the mapper's own program.
    auto actor = MeshActor(Sphere(0.6, 24));
    vtkNew<vtkCallbackCommand> red;
    red->SetCallback([](vtkObject*, unsigned long, void*, void* data) {
      const float color[3] = { 1.0f, 0.0f, 0.0f };
      static_cast<vtkShaderProgram*>(data)->SetUniform3f("diffuseColorUniform", color);
    });
    actor->GetMapper()->AddObserver(vtkCommand::UpdateShaderEvent, red);
    compareBeside("a mapper with an UpdateShaderEvent observer", actor);
  }
  {
    // Raster's hidden line removal hides the wires behind the wireframe's
    // own surfaces, not those behind the traced mesh only.
    auto wires = MeshActor(Sphere(0.6, 16));
    wires->GetProperty()->SetRepresentationToWireframe();
    wires->GetProperty()->LightingOff();
    compareBeside("a wireframe under the renderer's hidden line removal", wires, true);
    // Raster's pass for it takes lone actors: an assembly's wireframe part
    // is drawn plainly, so it is traced.
    Scene scene;
    scene.Renderer->AddActor(MeshActor(Sphere(-0.6, 24)));
    vtkNew<vtkAssembly> group;
    group->AddPart(wires);
    scene.Renderer->AddActor(group);
    scene.Renderer->UseHiddenLineRemovalOn();
    scene.View();
    scene.Compare("an assembly's wireframe part under hidden line removal", 2, 2.0);
    // Only the default delegate draws it; id mode draws no raster.
    vtkNew<vtkRayTracePass> pass;
    scene.Renderer->RemoveActor(group);
    scene.Renderer->AddActor(wires);
    scene.Renderer->SetPass(pass);
    for (const bool ids : { false, true })
    {
      pass->SetIdMode(ids);
      vtkNew<vtkRenderStepsPass> steps;
      pass->SetDelegatePass(ids ? nullptr : steps.Get());
      scene.Window->Render();
      Check(pass->GetNumberOfTracedProps() == 2,
        ids ? "hidden line removal in id mode: the wireframe traced"
            : "hidden line removal with a user's delegate: the wireframe traced");
    }
    scene.Renderer->SetPass(nullptr);
  }
  {
    vtkNew<vtkPointGaussianMapper> splats;
    splats->SetInputData(Sphere(0.6, 16));
    splats->SetScaleFactor(0.08);
    splats->EmissiveOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(splats);
    compareBeside("vtkPointGaussianMapper of a sphere with polygons", actor);
  }
  const std::string red = "//VTK::Light::Impl\n  gl_FragData[0] = vec4(1.0, 0.0, 0.0, 1.0);\n";
  {
    auto actor = MeshActor(Sphere(0.6, 24));
    actor->GetShaderProperty()->AddFragmentShaderReplacement("//VTK::Light::Impl", false, red, false);
    compareBeside("a shader replacement on the actor's shader property", actor);
  }
  {
    auto actor = MeshActor(Sphere(0.6, 24));
    auto* mapper = vtkOpenGLPolyDataMapper::SafeDownCast(actor->GetMapper());
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
    mapper->AddShaderReplacement(vtkShader::Fragment, "//VTK::Light::Impl", false, red, false);
#pragma GCC diagnostic pop
    Output->Clear(); // VTK's deprecation warning
    compareBeside("a shader replacement through the mapper's deprecated API", actor);
  }
  {
    auto glass = MeshActor(Sphere(0.6, 24));
    glass->GetProperty()->SetOpacity(0.3);
    glass->ForceOpaqueOn();
    compareBeside("an actor forced opaque with opacity 0.3", glass);
  }
  {
    // VTK 9.1's mapper-side highlight: the selected cells' outlines.
    auto actor = MeshActor(Sphere(0.6, 24));
    vtkNew<vtkIdTypeArray> ids;
    for (vtkIdType i = 0; i < 300; i += 3)
    {
      ids->InsertNextValue(i);
    }
    vtkNew<vtkSelectionNode> node;
    node->SetContentType(vtkSelectionNode::INDICES);
    node->SetFieldType(vtkSelectionNode::CELL);
    node->SetSelectionList(ids);
    vtkNew<vtkSelection> selection;
    selection->AddNode(node);
    actor->GetMapper()->SetSelection(selection);
    actor->GetProperty()->SetSelectionColor(1.0, 0.0, 0.0, 1.0);
    actor->GetProperty()->SetSelectionLineWidth(2.0);
    compareBeside("a mapper given a selection to highlight", actor);
  }
  {
    auto actor = MeshActor(Sphere(0.6, 16));
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->VertexVisibilityOn();
    actor->GetProperty()->SetVertexColor(1.0, 0.0, 0.0);
    actor->GetProperty()->SetPointSize(5.0);
    compareBeside("vertices drawn over a surface with edges", actor);
  }
  {
    // A planar shadow's matrix: projective (last row not 0 0 0 1).
    auto actor = MeshActor(Sphere(0.6, 24));
    vtkNew<vtkMatrix4x4> flatten;
    flatten->SetElement(1, 1, 0.0);
    flatten->SetElement(3, 1, -0.5);
    flatten->SetElement(3, 3, 2.0);
    actor->SetUserMatrix(flatten);
    compareBeside("an actor whose matrix is projective", actor);
  }
  NoVTKOutput("left to raster");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv, { { "LeftToRaster", TestLeftToRaster } });
}
