// vtkrt-render --pick: what lies under one pixel of the image, the mesh cell
// through vtkCellPicker (with a vtkBVHCellLocator when built) or a glyph
// sphere as the ray tracer sees it.
#ifndef vtkrtRenderPick_h
#define vtkrtRenderPick_h

#include <string>

namespace vtkrtRender
{
struct Pixel;
struct Scene;

// The pick report line for `pixel` of an image `height` pixels high (rows
// top down): what was hit, where, by what, and the locator's build and pick
// times.
std::string PickPixel(const Scene& scene, const Pixel& pixel, int height);
} // namespace vtkrtRender

#endif
