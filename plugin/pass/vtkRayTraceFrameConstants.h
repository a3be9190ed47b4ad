// Private to vtkRayTracePass: the values the tracing shader reads the same
// at every pixel of a frame (the camera's rays, the single instance's
// record, the lights ...), set as uniforms by name. llvmpipe loads a
// fragment shader's uniform once per pixel lane (it cannot assume a lane is
// active), a flat input once per block of pixels: so the quad's vertex shader
// reads the uniforms and passes the most read ones on as flat varyings, as
// many as the varying slots hold, and the fragment shader reads those under
// the uniforms' names. The values and their arithmetic are unchanged.
#ifndef vtkRayTraceFrameConstants_h
#define vtkRayTraceFrameConstants_h

#include "vtkRayTraceTypes.h"

#include <string>
#include <vector>

namespace vtkrt
{
namespace pass
{

/// A frame constant: a uniform `Type Name[Count]` (Count 0: not an array).
struct FrameConstant
{
  std::string Type;
  std::string Name;
  int Count = 0;
  int SlotsPerElement = 1; ///< varying slots (vec4s) an element takes
  bool ReadByShader = true; ///< false: declared, but this shader never reads it (kept a uniform)
};

/// The frame constants of a shader of features `f`, the most read per pixel
/// first. Those the tracing shader's chunks declare themselves (the edges'
/// uCameraToPixels, the top level's uCameraToAnchor) are not among them.
std::vector<FrameConstant> FrameConstantsOf(const Features& f);

/// The two shaders' declarations of `constants`: the first ones that fit in
/// `slots` varying slots (in order; a later, smaller one may still fit) are
/// flat varyings the vertex shader copies from its uniforms.
struct FrameConstantShaders
{
  std::string Vertex;               ///< the quad's whole vertex shader
  std::string FragmentDeclarations; ///< flat inputs aliased to the names, the rest uniforms
  int FlatConstants = 0;            ///< how many constants are flat inputs
};
FrameConstantShaders DeclareFrameConstants(const std::vector<FrameConstant>& constants, int slots);

/// The varying slots a vertex shader can pass to the fragment shader in
/// the current context besides the quad's texture coordinate.
int FlatConstantSlots();

} // namespace pass
} // namespace vtkrt

#endif
