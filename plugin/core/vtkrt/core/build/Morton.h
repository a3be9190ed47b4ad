// Morton codes: the bits of three grid coordinates interleaved, so that
// sorting by code walks space along a Z-order curve.
#ifndef vtkrt_core_build_Morton_h
#define vtkrt_core_build_Morton_h

#include <cstdint>

namespace vtkrt::core::detail
{

/// Spreads the low 21 bits of x to every third bit (Morton codes).
inline std::uint64_t expandBits21(std::uint64_t x)
{
  x &= 0x1fffffull;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

} // namespace vtkrt::core::detail

#endif
