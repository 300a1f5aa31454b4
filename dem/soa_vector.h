#pragma once
// SoaVector<T>: one component of structure-of-arrays particle or contact data. It is a
// std::vector whose storage is shifted by a few cache lines, so that the many arrays a force
// loop reads at the same index do not all fall into the same L1 cache set.
//
// Why: arrays of the same length are large enough to come from mmap, so they all start at the
// same offset modulo 4 KiB. Element i of every array then maps to one set of the 8- or 12-way L1
// data cache, and a loop that streams more arrays than there are ways (kick_and_drift reads and
// writes about 14, the pair loop about 13 per disc) evicts its own data at every index. Measured
// on the 40,000-disc benchmark: about 15 % of the step time (bench/RESULTS.md).
//
// The shift is a function of the block's address only (no global state, no effect on results):
// consecutive page-aligned blocks of the same size get different shifts, spread over 61 of the
// 64 cache lines of a 4 KiB page.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace geohybrid::dem
{
template <class T>
struct CacheStaggeredAllocator
{
  using value_type = T;

  CacheStaggeredAllocator() noexcept = default;
  template <class U>
  CacheStaggeredAllocator(const CacheStaggeredAllocator<U> &) noexcept
  {}

  static constexpr std::size_t cache_line = 64;
  static constexpr std::size_t n_shifts = 61; // prime: page-multiple strides spread over all shifts

  T *allocate(std::size_t n)
  {
    static_assert(alignof(T) <= cache_line, "over-aligned element type");
    // One line more than the largest shift holds the original pointer just before the data.
    const std::size_t bytes = n * sizeof(T) + (n_shifts + 1) * cache_line;
    auto *raw = static_cast<unsigned char *>(::operator new(bytes, std::align_val_t(cache_line)));
    const std::size_t page = reinterpret_cast<std::uintptr_t>(raw) >> 12;
    unsigned char *data = raw + cache_line * (1 + page % n_shifts);
    reinterpret_cast<unsigned char **>(data)[-1] = raw;
    return reinterpret_cast<T *>(data);
  }

  void deallocate(T *p, std::size_t) noexcept
  {
    unsigned char *raw = reinterpret_cast<unsigned char **>(p)[-1];
    ::operator delete(raw, std::align_val_t(cache_line));
  }

  template <class U>
  bool operator==(const CacheStaggeredAllocator<U> &) const noexcept
  {
    return true;
  }
  template <class U>
  bool operator!=(const CacheStaggeredAllocator<U> &) const noexcept
  {
    return false;
  }
};

template <class T>
using SoaVector = std::vector<T, CacheStaggeredAllocator<T>>;
} // namespace geohybrid::dem
