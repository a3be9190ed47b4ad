// Private to vtkRayTracePass: the fragment shader a frame's features need
// (only the chunks and defines it uses, with the GPU layout generated from
// core/GpuLayout.h), compiled once per feature key and kept.
#ifndef vtkRayTraceShader_h
#define vtkRayTraceShader_h

#include "vtkRayTraceTypes.h"

#include <map>
#include <memory>
#include <string>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

namespace vtkrt
{
namespace pass
{

/// The tracing program's sources for a feature set: the quad's vertex
/// shader, which passes the frame constants that fit in `flatSlots` varying
/// slots on as flat varyings (vtkRayTraceFrameConstants.h), and the
/// fragment shader.
struct ShaderSources
{
  std::string Vertex;
  std::string Fragment;
};
ShaderSources AssembleShaders(const Features& f, int flatSlots);

/// The resolve shader of the accumulation buffer.
std::string ResolveShaderSource();

/// The shader that draws a traced prop's pixels for a selector pass.
std::string SelectShaderSource();

/// Full-screen-quad programs by feature key.
class ProgramCache
{
public:
  ProgramCache();
  ~ProgramCache();

  /// The program for `f`, compiled on first use (counted) and made current;
  /// null (with the source kept for inspection) when it does not compile.
  /// Its key is f's and the flat varying slots given to frame constants
  /// ("f<slots>": none without `flatConstants`); a program that does not
  /// compile with flat constants is tried again with none.
  vtkOpenGLQuadHelper* Ready(
    vtkOpenGLRenderWindow* win, const Features& f, bool flatConstants, FrameCounters& counters);

  const std::string& GetLastKey() const { return this->LastKey; }
  const std::string& GetLastSource() const { return this->LastSource; }

  void Release(vtkWindow* w);

private:
  /// Ready's program with frame constants in `slots` flat varying slots.
  vtkOpenGLQuadHelper* ReadyWithSlots(
    vtkOpenGLRenderWindow* win, const Features& f, int slots, FrameCounters& counters);

  std::map<std::string, std::unique_ptr<vtkOpenGLQuadHelper>> Programs;
  std::string LastKey;
  std::string LastSource; ///< LastKey's fragment shader source (outlives the cached programs)
  std::string LastVertexSource;
  int ContextSlots = -1; ///< FlatConstantSlots of the context, once known
};

/// Makes a cached quad helper's program current, or compiles it into
/// `helper` from the fragment shader `source` (counted) and `vertexSource`
/// (empty: VTK's quad vertex shader); false when it does not compile.
bool ReadyQuadProgram(vtkOpenGLRenderWindow* win, std::unique_ptr<vtkOpenGLQuadHelper>& helper,
  const std::string& source, FrameCounters& counters, const std::string& vertexSource = std::string());

} // namespace pass
} // namespace vtkrt

#endif
