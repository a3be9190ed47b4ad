// The demo scene's sphere glyphs, shared by vtkrt-render --demo and the
// tests that render that scene: a vtkSphereSource of radius 1 scaled by the
// centres' "radius" array, so each glyph is a sphere of that radius (which
// vtkRayTracePass traces as an analytic sphere), coloured by "scalar"
// through a blue-to-red LUT.
#ifndef vtkrtDemoGlyphs_h
#define vtkrtDemoGlyphs_h

#include "vtkActor.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

namespace vtkrtDemo
{
inline vtkSmartPointer<vtkActor> NewGlyphActor(vtkPolyData* centres)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.66, 0.0); // blue to red
  lut->SetSaturationRange(0.8, 0.8);
  lut->SetValueRange(0.95, 0.95);
  lut->SetTableRange(0.0, 1.0);
  lut->Build();
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centres);
  glyphs->SetSourceConnection(sphere->GetOutputPort());
  glyphs->SetScaleArray("radius");
  glyphs->SetScaleModeToScaleByMagnitude();
  glyphs->SetScaleFactor(1.0);
  glyphs->OrientOff();
  glyphs->SetLookupTable(lut);
  glyphs->SetScalarModeToUsePointFieldData();
  glyphs->SelectColorArray("scalar");
  glyphs->SetScalarRange(0.0, 1.0);
  glyphs->ScalarVisibilityOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(glyphs);
  actor->GetProperty()->SetSpecular(0.5);
  actor->GetProperty()->SetSpecularPower(40);
  return actor;
}
} // namespace vtkrtDemo

#endif
