// Private to vtkRayTracePass: the renderer's switched-on lights as
// vtkOpenGLRenderer hands them to vtkOpenGLPolyDataMapper, in the shader's
// coordinates, and their uniforms.
#ifndef vtkRayTraceLights_h
#define vtkRayTraceLights_h

#include "vtkrt/core/GpuLayout.h"

#include <vector>

class vtkRenderer;
class vtkShaderProgram;

namespace vtkrt
{
namespace pass
{

/// `origin`: the shader's origin in world coordinates, `scale`: shader
/// units per world unit (positions and the attenuation's distances scale).
std::vector<core::gpu::Light> CollectLights(vtkRenderer* ren, const double origin[3], double scale);

/// uLightColor, uLightDirection, uLightPosition, uLightAttenuation, uLightCone.
void SetLightUniforms(vtkShaderProgram* program, const std::vector<core::gpu::Light>& lights);

} // namespace pass
} // namespace vtkrt

#endif
