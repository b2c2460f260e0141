// The commands' memory policy: blocks of 8 MB and more are backed by 2 MB pages where the kernel
// allows it (transparent huge pages in "madvise" mode, Debian's default). A 2·10⁶-triangle mesh's
// checked path first touches ~150 MB of its own; in 4 KB pages that is ~40 000 page faults, which
// on the 2-vCPU virtual machine of docs/measured.md took half the run (0.99 → 0.49 s).
//
// malloc, calloc and realloc are wrapped (the executable's definitions come first for every
// library in the process) and pass the block to glibc unchanged; blocks this large are always
// mapped on their own (the mmap threshold is fixed at 8 MB below), so the hint splits no heap. Not
// under AddressSanitizer or ThreadSanitizer, whose runtimes own malloc.

#include <cstddef>  // defines __GLIBC__

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MASSPROPS_OWN_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define MASSPROPS_OWN_MALLOC 0
#endif
#endif
#ifndef MASSPROPS_OWN_MALLOC
#define MASSPROPS_OWN_MALLOC 1
#endif

#if MASSPROPS_OWN_MALLOC && defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

extern "C" {
void* __libc_malloc(std::size_t n);
void* __libc_calloc(std::size_t k, std::size_t n);
void* __libc_realloc(void* p, std::size_t n);
}

namespace {

constexpr std::size_t kLarge = std::size_t{8} << 20;

void* Advise(void* p, std::size_t n) {
#ifdef MADV_HUGEPAGE
  if (p != nullptr && n >= kLarge) {
    const std::uintptr_t page = 4096;
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + page - 1) & ~(page - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + n) & ~(page - 1);
    if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint
  }
#endif
  return p;
}

// Blocks of 8 MB and more are mapped on their own, always (glibc otherwise raises the threshold
// as blocks are freed, up to 32 MB, and would then carve them from the heap); smaller ones come
// from the heap and are reused there.
[[gnu::constructor]] void FixMmapThreshold() { ::mallopt(M_MMAP_THRESHOLD, static_cast<int>(kLarge)); }

}  // namespace

extern "C" void* malloc(std::size_t n) { return Advise(__libc_malloc(n), n); }

extern "C" void* calloc(std::size_t k, std::size_t n) {
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(k, n, &bytes)) return __libc_calloc(k, n);  // glibc refuses it
  return Advise(__libc_calloc(k, n), bytes);
}

extern "C" void* realloc(void* p, std::size_t n) { return Advise(__libc_realloc(p, n), n); }

#endif
