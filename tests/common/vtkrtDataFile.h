// vtkrtDataFile: where benchmarks and tests find a data file (a mesh) by
// name. The folder named by the environment variable VTKRT_DATA_DIR is
// searched first (as vtkrt-render does for its demo data), so that a larger
// or other mesh of the same name can stand in; then the project's own
// data/, compiled in as VTKRT_SOURCE_DATA_DIR by the CMake target
// vtkrtDataFile. Standard C++ only: the core benchmark uses it too.
#ifndef vtkrtDataFile_h
#define vtkrtDataFile_h

#ifndef VTKRT_SOURCE_DATA_DIR
#error "link the CMake target vtkrtDataFile (it defines VTKRT_SOURCE_DATA_DIR)"
#endif

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace vtkrtDataFile
{
/// The folders searched, in order: $VTKRT_DATA_DIR when set, then data/.
inline std::vector<std::string> Folders()
{
  std::vector<std::string> folders;
  const char* env = std::getenv("VTKRT_DATA_DIR");
  if (env && *env)
  {
    folders.emplace_back(env);
  }
  folders.emplace_back(VTKRT_SOURCE_DATA_DIR);
  return folders;
}

/// The path of `name` in the first folder that holds it; empty when none does.
inline std::string Find(const std::string& name)
{
  for (const std::string& folder : Folders())
  {
    const std::string path = folder + "/" + name;
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error))
    {
      return path;
    }
  }
  return std::string();
}

/// A sentence for a failure: `name` and the folders it was looked for in.
inline std::string NotFound(const std::string& name)
{
  std::string where;
  for (const std::string& folder : Folders())
  {
    where += (where.empty() ? "" : ", then ") + folder;
  }
  return name + " not found in " + where + " (VTKRT_DATA_DIR may name a folder to search first)";
}
}

#endif
