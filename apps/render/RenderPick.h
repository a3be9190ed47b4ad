// vtkrt-render --pick: what lies under one pixel of the image, the mesh cell
// through vtkCellPicker (with a vtkBVHCellLocator when built) or a glyph
// sphere as the ray tracer sees it.
#ifndef vtkrtRenderPick_h
#define vtkrtRenderPick_h

#include <string>

namespace vtkrtRender
{
struct Options;
struct Scene;

// The pick report line for opt.PickX, opt.PickY: what was hit, where, by
// what, and the locator's build and pick times.
std::string PickPixel(const Options& opt, const Scene& scene);
} // namespace vtkrtRender

#endif
