// The programs' operator new (rtiow, its Python module and its benchmarks link this file; the
// library alone does not, so a program built on it keeps its own allocator): malloc as the
// standard library's, and huge pages advised for each large block before its first touch
// (core/parallel/huge_pages.h). A film-sized array is written whole soon after it is made (the
// sums zeroed, the denoiser's planes filled), and in 4 KB pages each first write is a fault:
// measured on this 2-core VM (docs/performance.md), they took a 3840x2160 render's zeroed sums
// 3.3 s on one thread and the denoiser of that image some 20 of its 50 s. Every block is
// malloc's, large or small, so operator delete is free(), as the standard library's is.

#include <cstddef>
#include <cstdlib>
#include <new>

#include "core/parallel/huge_pages.h"

namespace {

// Below this a block holds at most one whole 2 MB page: not worth the system call.
constexpr std::size_t kAdvisedFrom = std::size_t(4) << 20;

}  // namespace

void* operator new(std::size_t bytes) {
  for (;;) {
    if (void* block = std::malloc(bytes == 0 ? 1 : bytes)) {
      if (bytes >= kAdvisedFrom) rtiow::advise_huge_pages(block, bytes);
      return block;
    }
    // As the standard's operator new: the new-handler may free memory, else bad_alloc.
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void operator delete(void* block) noexcept {
  std::free(block);
}
void operator delete(void* block, std::size_t) noexcept {
  std::free(block);
}
