// vtkrt tests: one checked assertion, printed, and the program's count of
// failed ones (its main returns non-zero when any failed).
#ifndef vtkrtCheck_h
#define vtkrtCheck_h

#include <iostream>
#include <string>

namespace vtkrtTest
{
inline int Failures = 0;

inline void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  if (!ok)
  {
    ++Failures;
  }
}
} // namespace vtkrtTest

#endif
