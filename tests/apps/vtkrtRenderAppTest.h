// What the vtkrt-render test drivers share: a check that counts failures,
// running the app and reading its report and images.
#ifndef vtkrtRenderAppTest_h
#define vtkrtRenderAppTest_h

#include "vtkrtCheck.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkSmartPointer.h"
#include "vtkrtTestOutputWindow.h"
#include "vtksys/SystemTools.hxx"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
#include <string>

namespace
{
using vtkrtTest::Failures;
std::string App;
// One directory per driver and case: CTest runs the cases at once, and some
// write files of the same name with different contents.
std::string Tmp;

using vtkrtTest::Check;

struct Result
{
  int Code = -1;
  std::string Output; // stdout and stderr together
};

Result RunApp(const std::string& args, const std::string& environment = "")
{
  const std::string command = environment + " '" + App + "' " + args + " 2>&1";
  std::cout << "$ " << environment << (environment.empty() ? "" : " ") << "vtkrt-render " << args
            << "\n";
  Result r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
  {
    return r;
  }
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0)
  {
    r.Output.append(buffer, n);
  }
  const int status = pclose(pipe);
  r.Code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::cout << r.Output << "[exit " << r.Code << "]\n";
  return r;
}

bool Contains(const std::string& text, const std::string& pattern)
{
  return std::regex_search(text, std::regex(pattern));
}

// Reads `key: <integer>` from the report.
long long ReportNumber(const std::string& text, const std::string& key)
{
  std::smatch m;
  if (std::regex_search(text, m, std::regex(key + ":\\s+([0-9]+)")))
  {
    return std::stoll(m[1]);
  }
  return -1;
}

vtkSmartPointer<vtkImageData> ReadPNG(const std::string& path)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return nullptr;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}
// A driver's main: runs the case argv[2] against the vtkrt-render argv[1],
// in its own directory under program's, and fails on any check or VTK
// error or warning.
int RunCase(int argc, char* argv[], const char* program,
  const std::map<std::string, std::function<void()>>& cases)
{
  vtkrtTestOutputWindow* output = vtkrtTestOutputWindow::Install();
  if (argc != 3 || cases.find(argv[2]) == cases.end())
  {
    std::cerr << "usage: " << argv[0] << " <vtkrt-render> <case>; cases:";
    for (const auto& c : cases)
    {
      std::cerr << " " << c.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }
  App = argv[1];
  Tmp = std::string(VTKRT_TEMP_DIR) + "/" + program + "/" + argv[2];
  vtksys::SystemTools::MakeDirectory(Tmp);
  cases.at(argv[2])();
  Check(output->GetNumberOfErrors() == 0 && output->GetNumberOfWarnings() == 0,
    "no VTK error or warning in the driver");
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
} // namespace

#endif
