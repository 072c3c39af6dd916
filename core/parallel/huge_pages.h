#pragma once
// Large arrays filled once and read often (a million spheres, their materials) spend most of
// their first touch in page faults: on the 2-core VM these benchmarks run on, 0.15 s of the
// 0.18 s it took to make spheres:1000000. Asking for transparent huge pages for them (Linux
// honours it when /sys/kernel/mm/transparent_hugepage/enabled says madvise or always) takes
// 2 MB per fault instead of 4 KB. Advice only: nothing changes if the kernel declines.

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtiow {

// Advises huge pages for the whole 2 MB pages inside [data, data + bytes).
inline void advise_huge_pages(const void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHugePage = std::uintptr_t(1) << 21;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHugePage - 1) & ~(kHugePage - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHugePage - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// The same for a vector's reserved storage, before it is first written.
template <typename T>
void advise_huge_pages(const std::vector<T>& v) {
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace rtiow
