// Which mappers the pass traces, and as what, against VTK's raster of the
// same scene: vtkDataSetMapper (its surface traced as its own polydata
// mapper draws it: colors, cell ids, updates), composite and field-data
// colors, and vtkAssembly parts (traced under their paths' matrices,
// selected as their assembly) and vtkLODProp3D levels (chosen by hand or
// by render time), vtkPropAssembly groups. Mappers and actors raster must
// keep: TestRayTracePassLeftToRaster.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkAssembly.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkConeSource.h"
#include "vtkCubeSource.h"
#include "vtkDataSetMapper.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLODProp3D.h"
#include "vtkLineSource.h"
#include "vtkLookupTable.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropAssembly.h"
#include "vtkPropPicker.h"
#include "vtkTextActor.h"
#include "vtkProperty.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkShaderProperty.h"
#include "vtkUnstructuredGrid.h"

#include <cstdlib>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 320;

/// The mappers' scenes, seen from one orbit: failed images as mappers-N.*.png.
struct Scene : ComparedScene
{
  Scene()
    : ComparedScene(kSize, "mappers")
  {
  }
  void View() { this->ComparedScene::View(30.0, 20.0); }
};

/// A block of n^3 voxels with point scalars (distance from a corner).
vtkSmartPointer<vtkImageData> Block(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n + 1, n + 1, n + 1);
  image->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
  vtkNew<vtkFloatArray> distance;
  distance->SetName("distance");
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    distance->InsertNextValue(static_cast<float>(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])));
  }
  image->GetPointData()->SetScalars(distance);
  return image;
}

/// The block split into tetrahedra, each with its own cell scalar.
vtkSmartPointer<vtkUnstructuredGrid> Tetrahedra(vtkImageData* block)
{
  vtkNew<vtkDataSetTriangleFilter> tets;
  tets->SetInputData(block);
  tets->Update();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->DeepCopy(tets->GetOutput());
  grid->GetPointData()->SetScalars(nullptr);
  vtkNew<vtkFloatArray> ids;
  ids->SetName("cell");
  for (vtkIdType i = 0; i < grid->GetNumberOfCells(); ++i)
  {
    ids->InsertNextValue(static_cast<float>(i % 7));
  }
  grid->GetCellData()->SetScalars(ids);
  return grid;
}

vtkSmartPointer<vtkActor> DataSetActor(vtkDataSet* data, double lo, double hi)
{
  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputData(data);
  mapper->SetScalarRange(lo, hi);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// The pixels of the screen's left half and right half.
const unsigned int kLeft[4] = { 0, 0, kSize / 2 - 1, kSize - 1 };
const unsigned int kRight[4] = { kSize / 2, 0, kSize - 1, kSize - 1 };

// vtkDataSetMapper: an image block with point scalars and a grid of
// tetrahedra with cell scalars are traced, look like raster, select the
// cells raster selects, and follow camera moves (nothing uploaded), new
// points and a new scalar range.
void TestDataSetMapper()
{
  Scene scene;
  vtkSmartPointer<vtkImageData> block = Block(4);
  vtkSmartPointer<vtkUnstructuredGrid> grid = Tetrahedra(block);
  auto blockActor = DataSetActor(block, 0.0, 1.8);
  auto gridActor = DataSetActor(grid, 0.0, 6.0);
  gridActor->SetPosition(1.4, 0.0, 0.0);
  scene.Renderer->AddActor(blockActor);
  scene.Renderer->AddActor(gridActor);
  scene.View();
  RasterAndTraced frames = scene.Compare("image block and tetrahedra", 2, 2.0);

  scene.Renderer->SetPass(nullptr);
  const auto rasterBlock = SelectedCells(scene.Renderer, kLeft, blockActor);
  const auto rasterGrid = SelectedCells(scene.Renderer, kRight, gridActor);
  scene.Renderer->SetPass(frames.Pass);
  const auto tracedBlock = SelectedCells(scene.Renderer, kLeft, blockActor);
  const auto tracedGrid = SelectedCells(scene.Renderer, kRight, gridActor);
  // VTK 9.1's raster reports the ids of the triangles it draws for
  // vtkDataSetMapper (that mapper does not map them to cells): the block's
  // quads are two triangles each, its tetrahedra's faces one.
  std::set<vtkIdType> rasterBlockQuads;
  for (vtkIdType id : rasterBlock)
  {
    rasterBlockQuads.insert(id / 2);
  }
  std::size_t gridDifferences = 0;
  for (vtkIdType id : rasterGrid)
  {
    gridDifferences += tracedGrid.count(id) ? 0 : 1;
  }
  for (vtkIdType id : tracedGrid)
  {
    gridDifferences += rasterGrid.count(id) ? 0 : 1;
  }
  std::ostringstream s;
  s << "selected cells raster / traced: block " << rasterBlock.size() << " triangles of "
    << rasterBlockQuads.size() << " quads / " << tracedBlock.size() << " quads, tetrahedra' faces "
    << rasterGrid.size() << " / " << tracedGrid.size() << " (" << gridDifferences
    << " in one only: pixels on an edge)";
  Check(!rasterBlock.empty() && rasterBlockQuads == tracedBlock && !rasterGrid.empty() &&
      gridDifferences <= 1 + rasterGrid.size() / 50,
    s.str());

  scene.Window->Render();
  scene.Renderer->GetActiveCamera()->Azimuth(25.0);
  scene.Window->Render();
  Check(frames.Pass->GetLastGeometryBytesUploaded() == 0 && frames.Pass->GetLastBVHBuilds() == 0,
    "a camera move uploads no geometry (" +
      std::to_string(frames.Pass->GetLastGeometryBytesUploaded()) + " bytes, " +
      std::to_string(frames.Pass->GetLastBVHBuilds()) + " builds)");
  scene.Window->Render();
  Check(frames.Pass->GetLastBVHBuilds() == 0, "a second frame builds nothing");

  // New points: the grid stretched to twice its height.
  vtkPoints* points = grid->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0], 2.0 * p[1], p[2]);
  }
  points->Modified();
  scene.Renderer->SetPass(frames.Pass);
  scene.Window->Render();
  Check(frames.Pass->GetLastBVHBuilds() > 0, "new points are built again");
  scene.Compare("tetrahedra stretched", 2, 2.0);
  blockActor->GetMapper()->SetScalarRange(0.0, 0.6);
  scene.Compare("block, a new scalar range", 2, 2.0);
  NoVTKOutput("vtkDataSetMapper");
}

/// Values 0 1 2 3 4 0 1 ... for `n` points or cells (scalars over [0, 4]).
vtkSmartPointer<vtkFloatArray> CyclingValues(vtkIdType n)
{
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  for (vtkIdType i = 0; i < n; ++i)
  {
    values->InsertNextValue(static_cast<float>(i % 5));
  }
  return values;
}

// Colors that replace scalars: a composite block's color (its own or
// inherited) replaces point and cell scalar colors, as
// vtkCompositePolyDataMapper2 draws it; field-data coloring gives every cell
// the color of the tuple FieldDataTupleId, or with -1 cell i tuple i's.
void TestReplacedColors()
{
  for (bool cellScalars : { false, true })
  {
    Scene scene;
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(3);
    for (unsigned int b = 0; b < 3; ++b)
    {
      vtkSmartPointer<vtkPolyData> sphere = Sphere(1.2 * b, 24);
      vtkSmartPointer<vtkFloatArray> values =
        CyclingValues(cellScalars ? sphere->GetNumberOfCells() : sphere->GetNumberOfPoints());
      if (cellScalars)
      {
        sphere->GetCellData()->SetScalars(values);
      }
      else
      {
        sphere->GetPointData()->SetScalars(values);
      }
      if (b == 2)
      {
        vtkNew<vtkMultiBlockDataSet> inner;
        inner->SetNumberOfBlocks(1);
        inner->SetBlock(0, sphere);
        blocks->SetBlock(b, inner);
      }
      else
      {
        blocks->SetBlock(b, sphere);
      }
    }
    vtkNew<vtkCompositePolyDataMapper2> mapper;
    mapper->SetInputDataObject(blocks);
    mapper->SetScalarRange(0.0, 4.0);
    vtkNew<vtkCompositeDataDisplayAttributes> attributes;
    mapper->SetCompositeDataDisplayAttributes(attributes);
    double yellow[3] = { 1.0, 1.0, 0.0 };
    double green[3] = { 0.2, 0.9, 0.3 };
    mapper->SetBlockColor(1, yellow); // the first sphere
    mapper->SetBlockColor(3, green);  // the inner multiblock: the third sphere inherits it
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    scene.Renderer->AddActor(actor);
    scene.View();
    scene.Compare(std::string("block colors over ") + (cellScalars ? "cell" : "point") + " scalars", 1, 2.0);
  }
  {
    // Scalar colors with alpha under a block color: raster keeps their
    // alpha (the block translucent over the plane behind it): left to raster.
    Scene scene;
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(2);
    for (unsigned int b = 0; b < 2; ++b)
    {
      vtkSmartPointer<vtkPolyData> sphere = Sphere(1.2 * b, 24);
      sphere->GetPointData()->SetScalars(CyclingValues(sphere->GetNumberOfPoints()));
      blocks->SetBlock(b, sphere);
    }
    vtkNew<vtkLookupTable> table;
    table->SetAlphaRange(0.4, 0.4);
    table->Build();
    vtkNew<vtkCompositePolyDataMapper2> mapper;
    mapper->SetInputDataObject(blocks);
    mapper->SetScalarRange(0.0, 4.0);
    mapper->SetLookupTable(table);
    vtkNew<vtkCompositeDataDisplayAttributes> attributes;
    mapper->SetCompositeDataDisplayAttributes(attributes);
    double yellow[3] = { 1.0, 1.0, 0.0 };
    mapper->SetBlockColor(1, yellow);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    scene.Renderer->AddActor(actor);
    auto plane = MeshActor(Sphere(0.6, 8));
    plane->SetPosition(0.0, 0.0, -2.0);
    plane->SetScale(4.0, 4.0, 0.1);
    scene.Renderer->AddActor(plane);
    scene.View();
    scene.Compare("block color over scalars with alpha 0.4", 1, 2.0);
  }
  // -1: cell i takes tuple i (the array as long as the cells).
  for (int tuple : { 0, 3, -1 })
  {
    Scene scene;
    vtkSmartPointer<vtkPolyData> sphere = Sphere(0.0, 32);
    vtkNew<vtkFloatArray> field;
    field->SetName("field");
    for (vtkIdType i = 0; i < sphere->GetNumberOfCells(); ++i)
    {
      field->InsertNextValue(static_cast<float>(i % 5));
    }
    sphere->GetFieldData()->AddArray(field);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(sphere);
    mapper->SetScalarModeToUseFieldData();
    mapper->SelectColorArray("field");
    mapper->SetFieldDataTupleId(tuple);
    mapper->SetScalarRange(0.0, 4.0);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    scene.Renderer->AddActor(actor);
    scene.View();
    scene.Compare("field data, tuple " + std::to_string(tuple), 1, 2.0);
  }
  NoVTKOutput("replaced colors");
}


/// A sphere and a cube side by side and a cone in an assembly nested in
/// theirs, every level turned, moved or scaled (origins too); a yellow
/// segment beside the sphere when `withLine` (its part's lines go to
/// raster through a stand-in).
struct Parts
{
  vtkNew<vtkAssembly> Assembly;
  vtkNew<vtkAssembly> Inner;
  vtkSmartPointer<vtkActor> Ball, Box, Cone;
  explicit Parts(bool withLine)
  {
    vtkSmartPointer<vtkPolyData> ball = Sphere(0.0, 32);
    if (withLine)
    {
      vtkNew<vtkLineSource> line;
      line->SetPoint1(-1.0, -0.8, 0.0);
      line->SetPoint2(1.0, 0.8, 0.6);
      vtkNew<vtkAppendPolyData> append;
      append->AddInputData(ball);
      append->AddInputConnection(line->GetOutputPort());
      append->Update();
      ball = append->GetOutput();
    }
    this->Ball = MeshActor(ball);
    this->Ball->GetProperty()->SetColor(1.0, 1.0, 0.0);
    this->Ball->GetProperty()->SetLineWidth(3.0);
    vtkNew<vtkCubeSource> cube;
    cube->Update();
    this->Box = MeshActor(cube->GetOutput());
    this->Box->GetProperty()->SetColor(0.3, 0.9, 0.3);
    this->Box->SetPosition(1.4, 0.0, 0.0);
    this->Box->RotateZ(30.0);
    vtkNew<vtkConeSource> cone;
    cone->SetResolution(24);
    cone->Update();
    this->Cone = MeshActor(cone->GetOutput());
    this->Cone->GetProperty()->SetColor(0.3, 0.4, 1.0);
    this->Cone->SetPosition(0.0, 1.3, 0.0);
    this->Cone->SetScale(1.0, 1.6, 1.0);
    this->Inner->AddPart(this->Cone);
    this->Inner->SetPosition(0.5, 0.0, 0.0);
    this->Inner->RotateX(20.0);
    this->Assembly->AddPart(this->Ball);
    this->Assembly->AddPart(this->Box);
    this->Assembly->AddPart(this->Inner);
    this->Assembly->SetOrigin(0.5, 0.5, 0.0);
    this->Assembly->RotateY(35.0);
    this->Assembly->SetScale(1.2);
  }
};

/// The props and cell counts a cell selection of the whole window reports.
std::map<vtkProp*, vtkIdType> SelectedProps(vtkRenderer* ren)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(ren);
  selector->SetArea(0, 0, kSize - 1, kSize - 1);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(selector->Select());
  std::map<vtkProp*, vtkIdType> props;
  for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = result->GetNode(n);
    auto* prop = vtkProp::SafeDownCast(node->GetProperties()->Get(vtkSelectionNode::PROP()));
    props[prop] += node->GetSelectionList()->GetNumberOfTuples();
  }
  return props;
}

/// A whole-window cell selection traced (the renderer's pass), then raster
/// (the pass taken off): the cells each reports per prop.
struct Selections
{
  std::map<vtkProp*, vtkIdType> Traced;
  std::map<vtkProp*, vtkIdType> Raster;
  explicit Selections(vtkRenderer* ren)
    : Traced(SelectedProps(ren))
  {
    ren->SetPass(nullptr);
    this->Raster = SelectedProps(ren);
  }
  static vtkIdType CellsOf(const std::map<vtkProp*, vtkIdType>& cells, vtkProp* prop)
  {
    const auto it = cells.find(prop);
    return it == cells.end() ? 0 : it->second;
  }
  /// Whether raster selects more than `least` cells of `prop` and traced
  /// as many within one and a `share`-th; `counts` gets " raster / traced".
  bool Agree(vtkProp* prop, vtkIdType least, vtkIdType share, std::string& counts) const
  {
    const vtkIdType r = CellsOf(this->Raster, prop), t = CellsOf(this->Traced, prop);
    counts += " " + std::to_string(r) + " / " + std::to_string(t);
    return r > least && std::abs(t - r) <= 1 + r / share;
  }
};

// vtkAssembly: its parts are traced under their paths' matrices (nested
// assemblies, origins, scales), cast traced shadows, keep their raster
// lines, are selected and picked as raster selects them (the assembly),
// follow camera and part moves without rebuilding, and keep their geometry
// while culled; an assembly with a part the tracer cannot draw goes to
// raster whole.
void TestAssemblies()
{
  {
    Scene scene;
    Parts parts(false);
    scene.Renderer->AddActor(parts.Assembly);
    scene.View();
    RasterAndTraced frames = scene.Compare("a nested assembly", 1, 1.0);
    Check(frames.Pass->GetLastTracedInstances() == 3,
      "its three parts are traced (" + std::to_string(frames.Pass->GetLastTracedInstances()) +
        " instances)");

    const Selections selected(scene.Renderer);
    std::string counts;
    const bool agree = selected.Agree(parts.Assembly, 100, 50, counts);
    Check(selected.Raster.size() == 1 && selected.Traced.size() == 1 && agree,
      "a selection reports the assembly, raster / traced:" + counts + " cells");
    scene.Renderer->SetPass(frames.Pass);
    scene.Renderer->GetActiveCamera()->Azimuth(20.0);
    scene.Window->Render();
    Check(frames.Pass->GetLastGeometryBytesUploaded() == 0 && frames.Pass->GetLastBVHBuilds() == 0,
      "a camera move uploads no geometry");
    parts.Box->SetPosition(1.4, 0.4, 0.0);
    parts.Inner->RotateX(10.0);
    scene.Window->Render();
    Check(frames.Pass->GetLastGeometryBytesUploaded() == 0 && frames.Pass->GetLastBVHBuilds() == 0,
      "moving a part and a nested assembly uploads no geometry");
    scene.Compare("parts moved", 1, 1.0);
    parts.Ball->VisibilityOff();
    scene.Compare("a part hidden", 1, 1.0);
    parts.Ball->VisibilityOn();
    // A part without a mapper draws nothing, with raster as traced.
    vtkNew<vtkActor> empty;
    parts.Inner->AddPart(empty);
    scene.Compare("a part without a mapper", 1, 1.0);
    parts.Inner->RemovePart(empty);

    // Culled: the camera turned away, then back.
    scene.Renderer->SetPass(frames.Pass);
    scene.Window->Render();
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    camera->Yaw(120.0);
    scene.Window->Render();
    const int culledInstances = frames.Pass->GetLastTracedInstances();
    camera->Yaw(-120.0);
    scene.Window->Render();
    Check(culledInstances == 0 && frames.Pass->GetLastBVHBuilds() == 0 &&
        frames.Pass->GetLastGeometryBytesUploaded() == 0,
      "culled and back in view: " + std::to_string(culledInstances) + " instances while culled, " +
        std::to_string(frames.Pass->GetLastBVHBuilds()) + " builds after");

    scene.Renderer->GetActiveCamera()->Azimuth(-20.0);
    scene.Window->Render();
    vtkNew<vtkPropPicker> picker;
    Check(picker->Pick(kSize / 2, kSize / 2, 0.0, scene.Renderer) &&
        picker->GetViewProp() == parts.Assembly.GetPointer(),
      "a pick in its middle picks the assembly");
  }
  {
    // A light above: the parts' traced shadows darken the floor; the
    // ball's segment is drawn by raster beside them.
    Scene scene;
    Parts parts(true);
    parts.Assembly->SetPosition(0.0, 1.2, 0.0);
    scene.Renderer->AddActor(parts.Assembly);
    scene.Renderer->AddActor(FloorActor(3.0));
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(0.3, 10.0, 0.2);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    scene.Renderer->AddLight(light);
    scene.View();
    RasterAndTraced frames = scene.Compare("an assembly with a line over a floor", 2, 1.5);
    const unsigned char yellow[3] = { 255, 255, 0 };
    const long rasterLine = CountColor(frames.Raster, yellow);
    frames.Pass->SetShadows(true);
    scene.Window->Render();
    vtkSmartPointer<vtkImageData> shadowed = Grab(scene.Window);
    std::vector<long> all(static_cast<std::size_t>(kSize) * kSize);
    std::iota(all.begin(), all.end(), 0L);
    const double unshadowedMean = MeanOver(frames.Traced, all);
    const double shadowedMean = MeanOver(shadowed, all);
    const long shadowedLine = CountColor(shadowed, yellow);
    std::ostringstream s;
    s << "shadows: mean level " << unshadowedMean << " -> " << shadowedMean
      << "; the segment's yellow pixels raster / shadowed " << rasterLine << " / " << shadowedLine;
    Check(shadowedMean < unshadowedMean - 2.0 && rasterLine > 20 && shadowedLine >= rasterLine / 2, s.str());
  }
  {
    Scene scene;
    Parts parts(false);
    const std::string red = "//VTK::Light::Impl\n  gl_FragData[0] = vec4(1.0, 0.0, 0.0, 1.0);\n";
    parts.Cone->GetShaderProperty()->AddFragmentShaderReplacement(
      "//VTK::Light::Impl", false, red, false);
    scene.Renderer->AddActor(parts.Assembly);
    scene.Renderer->AddActor(MeshActor(Sphere(-1.5, 24)));
    scene.View();
    scene.Compare("an assembly with a part of custom shader code beside a mesh", 1, 1.0);
  }
  {
    // One actor in three assemblies: a traced one beside it, and one left
    // to raster by a part of shader code; each is selected where it is.
    Scene scene;
    Parts parts(false);
    vtkNew<vtkAssembly> twin, mixed;
    // The ball: triangles, whose ids VTK 9.1's raster reports as cells
    // (under an assembly it reports a quad's triangles, not its cell).
    twin->AddPart(parts.Ball);
    twin->SetPosition(0.0, -1.6, 0.0);
    auto coded = MeshActor(Sphere(0.0, 16));
    coded->GetShaderProperty()->AddFragmentShaderReplacement("//VTK::Light::Impl", false,
      "//VTK::Light::Impl\n  gl_FragData[0] = vec4(1.0, 0.0, 0.0, 1.0);\n", false);
    coded->SetPosition(1.5, 0.0, 0.0);
    mixed->AddPart(parts.Ball);
    mixed->AddPart(coded);
    mixed->SetPosition(-2.0, 1.5, 0.0);
    for (vtkAssembly* a : { parts.Assembly.GetPointer(), twin.GetPointer(), mixed.GetPointer() })
    {
      scene.Renderer->AddActor(a);
    }
    scene.View();
    RasterAndTraced frames = scene.Compare("one actor in three assemblies", 2, 1.0);
    const Selections selected(scene.Renderer);
    std::string counts;
    bool same = selected.Raster.size() == 3 && selected.Traced.size() == 3;
    for (const auto& r : selected.Raster)
    {
      same = selected.Agree(r.first, 20, 20, counts) && same;
    }
    Check(same, "one actor in three assemblies, cells selected raster / traced:" + counts);
  }
  NoVTKOutput("assemblies");
}

// vtkLODProp3D: the level chosen for it is traced under its matrix, follows
// a change of level, and is selected as the LOD prop, as raster does.
void TestLODProps()
{
  Scene scene;
  vtkNew<vtkLODProp3D> lod;
  int levels[2];
  vtkSmartPointer<vtkPolyDataMapper> mappers[2];
  const int resolutions[2] = { 8, 48 };
  for (int k = 0; k < 2; ++k)
  {
    mappers[k] = vtkSmartPointer<vtkPolyDataMapper>::New();
    mappers[k]->SetInputData(Sphere(0.0, resolutions[k]));
    vtkNew<vtkProperty> property;
    property->SetColor(0.9, 0.6 - 0.3 * k, 0.3 + 0.5 * k);
    levels[k] = lod->AddLOD(mappers[k], property, 1.0 + k);
  }
  lod->AutomaticLODSelectionOff();
  lod->SetSelectedLODID(levels[0]);
  lod->SetPosition(0.4, 0.2, 0.0);
  lod->RotateZ(30.0);
  lod->SetScale(1.0, 1.6, 1.0);
  scene.Renderer->AddActor(lod);
  scene.Renderer->AddActor(MeshActor(Sphere(-1.2, 24)));
  scene.View();
  RasterAndTraced frames = scene.Compare("a vtkLODProp3D, its coarse level", 2, 1.0);
  Check(frames.Pass->GetLastTracedPrimitives() < 2 * 24 * 24 + 2 * 8 * 8 + 1,
    "the coarse level's triangles are traced (" +
      std::to_string(frames.Pass->GetLastTracedPrimitives()) + " in all)");
  lod->SetSelectedLODID(levels[1]);
  frames = scene.Compare("its fine level", 2, 1.0);
  Check(frames.Pass->GetLastTracedPrimitives() > 2 * 48 * 46,
    "the fine level's triangles are traced (" +
      std::to_string(frames.Pass->GetLastTracedPrimitives()) + " in all)");
  const Selections selected(scene.Renderer);
  std::string counts;
  const bool agree = selected.Agree(lod, 50, 50, counts);
  Check(agree, "a selection reports the LOD prop, raster / traced:" + counts + " cells");
  NoVTKOutput("LOD props");
}

// vtkLODProp3D choosing its level by render time (automatic selection):
// each traced level reports its share of the traced frame, as raster
// levels report their draw times, so it measures every level once (none
// has a time yet) and then keeps the best level within the window's time,
// as with raster, which an unmeasured level would take from it forever.
void TestLODPropsByTime()
{
  std::vector<int> chosen[2];
  for (const bool traced : { false, true })
  {
    Scene scene;
    vtkNew<vtkLODProp3D> lod;
    const int resolutions[3] = { 8, 24, 48 };
    for (int k = 0; k < 3; ++k)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(Sphere(0.0, resolutions[k]));
      vtkNew<vtkProperty> property;
      property->SetColor(0.9, 0.7 - 0.3 * k, 0.2 + 0.3 * k);
      lod->SetLODLevel(lod->AddLOD(mapper, property, 0.0), 2.0 - k); // the finest is level 0
    }
    scene.Renderer->AddActor(lod);
    scene.View();
    vtkNew<vtkRayTracePass> pass;
    scene.Renderer->SetPass(traced ? pass.Get() : nullptr);
    for (int frame = 0; frame < 6; ++frame)
    {
      scene.Window->Render();
      chosen[traced].push_back(lod->GetLastRenderedLODID());
      Check(!traced || pass->GetNumberOfTracedProps() == 1,
        "frame " + std::to_string(frame) + ": the chosen level traced");
    }
    if (traced)
    {
      scene.Compare("a vtkLODProp3D choosing its level by time, then", 1, 1.0);
    }
  }
  auto text = [](const std::vector<int>& ids) {
    std::string s;
    for (int id : ids)
    {
      s += " " + std::to_string(id);
    }
    return s;
  };
  Check(chosen[0] == chosen[1] && std::set<int>(chosen[1].begin(), chosen[1].end()).size() == 3,
    "levels chosen by time, raster:" + text(chosen[0]) + ", traced:" + text(chosen[1]) +
      " (each tried, then the finest)");
  NoVTKOutput("LOD props by time");
}

// vtkPropAssembly: its visible props are traced as they draw themselves (an
// actor, an assembly's parts under their matrices), selected as the group;
// a group with a prop the tracer cannot draw (a 2D text) goes to raster.
void TestPropAssemblies()
{
  Scene scene;
  Parts parts(false);
  vtkNew<vtkPropAssembly> group;
  auto ball = MeshActor(Sphere(0.0, 24));
  ball->SetPosition(-1.6, 0.3, 0.0);
  auto hidden = MeshActor(Sphere(0.0, 12));
  hidden->VisibilityOff();
  group->AddPart(ball);
  group->AddPart(parts.Assembly);
  group->AddPart(hidden);
  scene.Renderer->AddActor(group);
  scene.View();
  RasterAndTraced frames = scene.Compare("a vtkPropAssembly of an actor and an assembly", 1, 1.0);
  Check(frames.Pass->GetLastTracedInstances() == 4,
    "its four visible actors are traced (" +
      std::to_string(frames.Pass->GetLastTracedInstances()) + " instances)");
  const Selections selected(scene.Renderer);
  std::string counts;
  const bool agree = selected.Agree(group, 50, 50, counts);
  Check(selected.Traced.size() == 1 && selected.Raster.size() == 1 && agree,
    "a selection reports the group, raster / traced:" + counts + " cells");
  vtkNew<vtkTextActor> text;
  text->SetInput("a label");
  group->AddPart(text);
  scene.Compare("the group with a 2D text, left to raster", 0, 1.0);
  // A LOD prop chooses its level while the group renders (the group hands
  // it its time), which a traced group never does: left to raster.
  vtkNew<vtkPropAssembly> levels;
  vtkNew<vtkLODProp3D> lod;
  vtkNew<vtkPolyDataMapper> coarse;
  coarse->SetInputData(Sphere(0.0, 12));
  vtkNew<vtkProperty> look;
  lod->AddLOD(coarse, look, 0.0);
  levels->AddPart(lod);
  scene.Renderer->RemoveViewProp(group);
  scene.Renderer->AddViewProp(levels);
  scene.Compare("a group with a vtkLODProp3D, left to raster", 0, 1.0);
  NoVTKOutput("prop assemblies");
}

} // namespace

/// vtkCompositePolyDataMapper2's ColorMissingArraysWithNanColor: blocks
/// without the array the mapper colors by are drawn in the lookup table's
/// NaN color (a vtkLookupTable's, then a vtkColorTransferFunction's), by
/// point and by cell field data, and a new NaN color recolors them.
void TestMissingArraysNanColor()
{
  for (bool cells : { false, true })
  {
    for (bool transferFunction : { false, true })
    {
      Scene scene;
      vtkNew<vtkMultiBlockDataSet> blocks;
      blocks->SetNumberOfBlocks(3);
      for (unsigned int b = 0; b < 3; ++b)
      {
        vtkSmartPointer<vtkPolyData> sphere = Sphere(1.2 * b, 24);
        if (b == 1)
        {
          vtkSmartPointer<vtkFloatArray> values =
            CyclingValues(cells ? sphere->GetNumberOfCells() : sphere->GetNumberOfPoints());
          values->SetName("values");
          (cells ? static_cast<vtkDataSetAttributes*>(sphere->GetCellData()) : sphere->GetPointData())
            ->AddArray(values);
        }
        blocks->SetBlock(b, sphere);
      }
      vtkNew<vtkCompositePolyDataMapper2> mapper;
      mapper->SetInputDataObject(blocks);
      mapper->SetScalarRange(0.0, 4.0);
      cells ? mapper->SetScalarModeToUseCellFieldData() : mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("values");
      mapper->ColorMissingArraysWithNanColorOn();
      vtkNew<vtkLookupTable> lut;
      vtkNew<vtkColorTransferFunction> ctf;
      ctf->AddRGBPoint(0.0, 0.1, 0.1, 0.9);
      ctf->AddRGBPoint(4.0, 0.9, 0.9, 0.1);
      if (transferFunction)
      {
        ctf->SetNanColor(0.1, 0.9, 0.2);
        mapper->SetLookupTable(ctf);
      }
      else
      {
        lut->SetNanColor(0.1, 0.9, 0.2, 1.0);
        mapper->SetLookupTable(lut);
      }
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      scene.Renderer->AddActor(actor);
      scene.View();
      const std::string what = std::string(cells ? "cell" : "point") + " field array missing from two blocks, " +
        (transferFunction ? "a color transfer function" : "a lookup table");
      const RasterAndTraced first = scene.Compare(what + ": NaN color", 1, 2.0);
      // The same pass, its next frame.
      transferFunction ? ctf->SetNanColor(0.9, 0.2, 0.7) : lut->SetNanColor(0.9, 0.2, 0.7, 1.0);
      scene.Window->Render();
      auto traced = Grab(scene.Window);
      scene.Renderer->SetPass(nullptr);
      scene.Window->Render();
      auto raster = Grab(scene.Window);
      const double rmse = RootMeanSquareError(Blurred(raster), Blurred(traced));
      Check(rmse <= 2.0 && RootMeanSquareError(first.Traced, traced) > 10.0,
        what + ": another NaN color, the next frame: blurred RGB RMSE vs raster " + std::to_string(rmse));
    }
  }
  NoVTKOutput("missing arrays in the NaN color");
}

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "DataSetMapper", TestDataSetMapper },
      { "ReplacedColors", TestReplacedColors }, { "Assemblies", TestAssemblies },
      { "LODProps", TestLODProps }, { "LODPropsByTime", TestLODPropsByTime },
      { "PropAssemblies", TestPropAssemblies }, { "MissingArraysNanColor", TestMissingArraysNanColor } });
}
