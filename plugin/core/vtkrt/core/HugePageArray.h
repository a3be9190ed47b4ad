// Large arrays that skip the zero fill, and that a random reader finds on
// huge pages (Linux transparent huge pages; elsewhere plain malloc).
#ifndef vtkrt_core_HugePageArray_h
#define vtkrt_core_HugePageArray_h

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h> // mmap, madvise
#include <unistd.h>   // sysconf
#endif

namespace vtkrt::core
{

namespace detail
{
/// Blocks of at least this size get huge pages.
constexpr std::size_t kHugePageMinBytes = std::size_t(4) << 20;
constexpr std::size_t kHugePage = std::size_t(2) << 20;

inline std::size_t hugePageBytes(std::size_t bytes)
{
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

/// `bytes` (rounded up to whole huge pages) of fresh memory on a huge page
/// boundary, in a mapping of its own with a transparent huge page hint, or
/// nullptr. A mapping of its own: the hint leaves with it (unmapHugePages),
/// instead of staying on heap memory that small allocations reuse (a huge
/// page fault for a few bytes).
inline void* mapHugePages(std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::size_t size = hugePageBytes(bytes);
  void* base = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (base == MAP_FAILED)
  {
    return nullptr;
  }
  const std::uintptr_t b = reinterpret_cast<std::uintptr_t>(base);
  const std::uintptr_t aligned = (b + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > b)
  {
    munmap(base, aligned - b);
  }
  if (b + kHugePage > aligned)
  {
    munmap(reinterpret_cast<void*>(aligned + size), b + kHugePage - aligned);
  }
  madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
#else
  (void)bytes;
  return nullptr;
#endif
}

/// Gives back what mapHugePages(bytes) returned.
inline void unmapHugePages(void* p, std::size_t bytes) noexcept
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  munmap(p, hugePageBytes(bytes));
#else
  (void)p;
  (void)bytes;
#endif
}

/// Whether allocations of `bytes` go to mapHugePages.
inline bool usesHugePages(std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  return bytes >= kHugePageMinBytes;
#else
  (void)bytes;
  return false;
#endif
}
} // namespace detail

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
  /// Arrays of several MiB go on 2 MiB boundaries, in mappings of their
  /// own, with a transparent huge page hint (Linux; as Embree does for its
  /// BVH): read at random with 4 KiB pages, nearly every read would also
  /// miss the TLB. Only a hint: memory is the same, and elsewhere this is
  /// plain malloc.
  T* allocate(std::size_t n)
  {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T))
    {
      throw std::bad_alloc();
    }
    const std::size_t bytes = n * sizeof(T);
    if (HugePageHint && detail::usesHugePages(bytes))
    {
      void* p = detail::mapHugePages(bytes);
      if (!p)
      {
        throw std::bad_alloc();
      }
      return static_cast<T*>(p);
    }
    void* p = std::malloc(bytes ? bytes : 1);
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept
  {
    if (HugePageHint && detail::usesHugePages(n * sizeof(T)))
    {
      detail::unmapHugePages(p, n * sizeof(T));
      return;
    }
    std::free(p);
  }
};

/// An array read at random, or large and written in full right after it is
/// sized: no zero fill, huge pages when large (fewer TLB misses, and where
/// page faults are dear a first touch far cheaper than that of 4 KiB pages).
template <class T>
using HugePageArray = std::vector<T, NoFillAllocator<T>>;
/// An array written and read in order: no zero fill, no huge page hint.
template <class T>
using NoFillArray = std::vector<T, NoFillAllocator<T, false>>;

/// Bytes that may be read past the last element of `array`: the rest of
/// its own mapping for a large array, none for a block of malloc's, which
/// may end there.
template <class T>
std::size_t readableBytesPastEnd(const HugePageArray<T>& array)
{
  const std::size_t capacityBytes = array.capacity() * sizeof(T);
  return detail::usesHugePages(capacityBytes) ? detail::hugePageBytes(capacityBytes) - array.size() * sizeof(T)
                                              : 0;
}

/// Gives back the memory of `array` past its size, for an array sized for
/// the most it could hold that holds less: the pages of its own mapping
/// past the size (the capacity stays, read as zeros if used again), or, a
/// small array on malloc's heap, a copy of exactly its size.
template <class T>
void giveBackPastSize(HugePageArray<T>& array)
{
  if (!detail::usesHugePages(array.capacity() * sizeof(T)))
  {
    HugePageArray<T>(array.begin(), array.end()).swap(array);
    return;
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto base = reinterpret_cast<std::uintptr_t>(array.data());
  const std::uintptr_t used = (base + array.size() * sizeof(T) + page - 1) / page * page;
  const std::uintptr_t end = base + detail::hugePageBytes(array.capacity() * sizeof(T));
  if (end > used)
  {
    madvise(reinterpret_cast<void*>(used), end - used, MADV_DONTNEED);
  }
#endif
}

} // namespace vtkrt::core

#endif
