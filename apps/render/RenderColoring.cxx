#include "RenderColoring.h"

#include "RenderOptions.h"
#include "RenderScene.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkPointData.h"
#include "vtkScalarBarActor.h"
#include "vtkTextProperty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace vtkrtRender
{
namespace
{
struct ControlPoint
{
  double X, R, G, B;
};

// Control points sampled from the published maps (matplotlib's viridis and
// inferno, Moreland's cool-warm); rainbow is VTK's blue-to-red hue ramp.
std::vector<ControlPoint> ControlPoints(const std::string& name)
{
  if (name == "viridis")
  {
    return { { 0.0, 0.267, 0.005, 0.329 }, { 0.25, 0.229, 0.322, 0.546 },
      { 0.5, 0.128, 0.567, 0.551 }, { 0.75, 0.369, 0.789, 0.383 }, { 1.0, 0.993, 0.906, 0.144 } };
  }
  if (name == "inferno")
  {
    return { { 0.0, 0.001, 0.000, 0.014 }, { 0.25, 0.341, 0.062, 0.429 },
      { 0.5, 0.735, 0.216, 0.330 }, { 0.75, 0.978, 0.557, 0.035 }, { 1.0, 0.988, 0.998, 0.645 } };
  }
  if (name == "coolwarm")
  {
    return { { 0.0, 0.230, 0.299, 0.754 }, { 0.5, 0.865, 0.865, 0.865 },
      { 1.0, 0.706, 0.016, 0.150 } };
  }
  if (name == "grayscale")
  {
    return { { 0.0, 0.0, 0.0, 0.0 }, { 1.0, 1.0, 1.0, 1.0 } };
  }
  return {};
}

// The array of `mesh` that `options` asks for; throws UsageError naming the
// arrays it has when there is none.
vtkDataArray* FindArray(const SceneMesh& mesh, const ScalarOptions& options)
{
  vtkFieldData* fields = options.Cells ? static_cast<vtkFieldData*>(mesh.Mesh->GetCellData())
                                       : static_cast<vtkFieldData*>(mesh.Mesh->GetPointData());
  auto* attributes = static_cast<vtkDataSetAttributes*>(fields);
  // Normals this tool computed for shading are not the file's data.
  auto fromFile = [&](vtkDataArray* a) {
    return a && !(mesh.ComputedNormals && !options.Cells && a == attributes->GetNormals()) ? a : nullptr;
  };
  vtkDataArray* array = fromFile(
    options.Array.empty() ? attributes->GetScalars() : fields->GetArray(options.Array.c_str()));
  // No active scalars: the first numeric array that is not the normals or
  // texture coordinates (whose colours mean nothing), else the first.
  for (int i = 0; !array && options.Array.empty() && i < fields->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* candidate = fields->GetArray(i);
    if (candidate && candidate != attributes->GetNormals() && candidate != attributes->GetTCoords())
    {
      array = candidate;
    }
  }
  for (int i = 0; !array && options.Array.empty() && i < fields->GetNumberOfArrays(); ++i)
  {
    array = fromFile(fields->GetArray(i));
  }
  const std::string kind = options.Cells ? "cell" : "point";
  if (!array)
  {
    std::string names;
    for (int i = 0; i < fields->GetNumberOfArrays(); ++i)
    {
      if (fromFile(fields->GetArray(i)) && fields->GetArrayName(i))
      {
        names += std::string(names.empty() ? "" : ", ") + fields->GetArrayName(i);
      }
    }
    throw UsageError{ "--scalars: '" + mesh.File + "' has no " + kind + " array" +
      (options.Array.empty() ? std::string() : " '" + options.Array + "'") + " (its " + kind +
      " arrays: " + (names.empty() ? "none" : names) + ")" };
  }
  if (options.Component >= array->GetNumberOfComponents())
  {
    throw UsageError{ "--comp " + std::to_string(options.Component) + ": the " + kind + " array '" +
      (array->GetName() ? array->GetName() : "") + "' of '" + mesh.File + "' has " +
      std::to_string(array->GetNumberOfComponents()) + " component(s)" };
  }
  return array;
}

void Describe(
  Scene& scene, const ScalarOptions& options, const std::string& name, const double range[2])
{
  std::ostringstream text;
  text << (options.Cells ? "cell" : "point") << " array '" << name << "' ("
       << (options.Component < 0 ? std::string("magnitude")
                                 : "component " + std::to_string(options.Component))
       << "), range [" << range[0] << ", " << range[1] << "], " << options.Colormap;
  scene.Coloring = text.str();
}

void AddScalarBar(Scene& scene, vtkLookupTable* table, const std::string& title)
{
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(table);
  bar->SetTitle(title.c_str());
  bar->SetNumberOfLabels(5);
  bar->SetPosition(0.84, 0.1);
  bar->SetPosition2(0.1, 0.8);
  bar->UnconstrainedFontSizeOn();
  bar->GetTitleTextProperty()->SetFontSize(14);
  bar->GetLabelTextProperty()->SetFontSize(12);
  scene.Renderer->AddActor2D(bar);
  scene.ScalarBar = bar;
}
} // namespace

vtkSmartPointer<vtkLookupTable> NewColormap(const std::string& name)
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetNumberOfTableValues(256);
  const std::vector<ControlPoint> points = ControlPoints(name);
  if (points.empty())
  {
    table->SetHueRange(0.667, 0.0); // rainbow
    table->Build();
    return table;
  }
  vtkNew<vtkColorTransferFunction> ramp;
  if (name == "coolwarm")
  {
    ramp->SetColorSpaceToDiverging();
  }
  for (const ControlPoint& p : points)
  {
    ramp->AddRGBPoint(p.X, p.R, p.G, p.B);
  }
  for (int i = 0; i < 256; ++i)
  {
    double rgb[3];
    ramp->GetColor(i / 255.0, rgb);
    table->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  return table;
}

void ColorByScalars(Scene& scene, const ScalarOptions& options)
{
  std::vector<vtkDataArray*> arrays;
  double range[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest() };
  for (const SceneMesh& mesh : scene.Meshes)
  {
    vtkDataArray* array = FindArray(mesh, options);
    arrays.push_back(array);
    double r[2];
    array->GetRange(r, options.Component);
    range[0] = std::min(range[0], r[0]);
    range[1] = std::max(range[1], r[1]);
  }
  if (options.RangeGiven)
  {
    std::copy(options.Range, options.Range + 2, range);
  }
  else if (range[1] - range[0] <= 1e-6 * std::max({ 1.0, std::abs(range[0]), std::abs(range[1]) }))
  {
    // A constant array (to rounding) gets the colormap's middle, not its noise.
    const double mid = 0.5 * (range[0] + range[1]), half = 0.5 * std::max(1.0, std::abs(mid));
    range[0] = mid - half;
    range[1] = mid + half;
  }
  vtkSmartPointer<vtkLookupTable> table = NewColormap(options.Colormap);
  table->SetRange(range);
  if (options.Component < 0)
  {
    table->SetVectorModeToMagnitude();
  }
  else
  {
    table->SetVectorModeToComponent();
    table->SetVectorComponent(options.Component);
  }
  for (size_t i = 0; i < scene.Meshes.size(); ++i)
  {
    vtkMapper* mapper = scene.Meshes[i].Actor->GetMapper();
    mapper->SetLookupTable(table);
    mapper->UseLookupTableScalarRangeOn();
    if (arrays[i]->GetName())
    {
      mapper->SetScalarMode(
        options.Cells ? VTK_SCALAR_MODE_USE_CELL_FIELD_DATA : VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
      mapper->SelectColorArray(arrays[i]->GetName());
    }
    else
    {
      // A nameless array is the active scalars: no name to select it by.
      mapper->SetScalarMode(
        options.Cells ? VTK_SCALAR_MODE_USE_CELL_DATA : VTK_SCALAR_MODE_USE_POINT_DATA);
    }
    mapper->SetColorModeToMapScalars();
    mapper->ScalarVisibilityOn();
  }
  const std::string name = arrays.front()->GetName() ? arrays.front()->GetName() : "scalars";
  Describe(scene, options, name, range);
  if (options.Bar)
  {
    AddScalarBar(scene, table, name);
  }
}
} // namespace vtkrtRender
