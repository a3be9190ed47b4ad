// Large arrays that skip the zero fill, and that a random reader finds on
// huge pages (Linux transparent huge pages; elsewhere plain malloc).
#ifndef vtkrt_core_HugePageArray_h
#define vtkrt_core_HugePageArray_h

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h> // madvise
#endif

namespace vtkrt::core
{

/// std::allocator whose resize() leaves new elements default-initialized
/// (no zero fill): arrays written element by element right after need no
/// memset first. Large arrays get a huge page hint (allocate()).
template <class T, bool HugePageHint = true>
struct NoFillAllocator : std::allocator<T>
{
  template <class U>
  struct rebind
  {
    using other = NoFillAllocator<U, HugePageHint>;
  };
  NoFillAllocator() = default;
  template <class U>
  NoFillAllocator(const NoFillAllocator<U, HugePageHint>&) noexcept
  {
  }
  template <class U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  /// Arrays of several MiB go on 2 MiB boundaries with a transparent huge
  /// page hint (Linux; as Embree does for its BVH): read at random with 4 KiB
  /// pages, nearly every read would also miss the TLB. Only a hint: memory
  /// is the same, and elsewhere or with THP off this is plain malloc.
  T* allocate(std::size_t n)
  {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T))
    {
      throw std::bad_alloc();
    }
    const std::size_t bytes = n * sizeof(T);
    void* p = nullptr;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::size_t kHugePage = std::size_t(2) << 20;
    if (HugePageHint && bytes >= 2 * kHugePage)
    {
      if (posix_memalign(&p, kHugePage, bytes) != 0)
      {
        throw std::bad_alloc();
      }
      madvise(p, bytes, MADV_HUGEPAGE);
      return static_cast<T*>(p);
    }
#endif
    p = std::malloc(bytes ? bytes : 1);
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept { std::free(p); }
};

/// An array read at random, or large and written in full right after it is
/// sized: no zero fill, huge pages when large (fewer TLB misses, and where
/// page faults are dear a first touch far cheaper than that of 4 KiB pages).
template <class T>
using HugePageArray = std::vector<T, NoFillAllocator<T>>;
/// An array written and read in order: no zero fill, no huge page hint.
template <class T>
using NoFillArray = std::vector<T, NoFillAllocator<T, false>>;

} // namespace vtkrt::core

#endif
