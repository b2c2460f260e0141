// The commands' memory policy: memory is backed by 2 MB pages where the kernel allows it
// (transparent huge pages in "madvise" mode, Debian's default) — what glibc's tunable
// glibc.malloc.hugetlb=1 with arena_max=1 does, which a command cannot set for itself. A
// 2·10⁶-triangle mesh's checked path first touches ~150 MB of its own; in 4 KB pages that is
// ~40 000 page faults, which on the 2-vCPU virtual machine of docs/measured.md took most of the
// run (--full-check 0.94 → 0.36 s, OBJ 0.99 → 0.57 s).
//
// malloc, calloc and realloc are wrapped (the executable's definitions come first for every
// library in the process) and pass every block to glibc unchanged. Blocks of 8 MB and more are
// mapped on their own (the mmap threshold is fixed there) and advised one by one; smaller ones come
// from the one heap (one arena for all threads), which grows in steps of 32 MB, each advised as it
// is added, and is kept rather than trimmed back (a step freed is reused without new faults). Not
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

#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdint>

extern "C" {
void* __libc_malloc(std::size_t n);
void* __libc_calloc(std::size_t k, std::size_t n);
void* __libc_realloc(void* p, std::size_t n);
}

// Defined false by a command whose threads allocate small blocks side by side (apps/rbsim/main.cpp);
// absent (massprops): one arena.
extern "C" [[gnu::weak]] const bool massprops_app_one_arena;

namespace {

constexpr std::size_t kPage = 4096;
constexpr std::size_t kLarge = std::size_t{8} << 20;
constexpr std::size_t kHeapStep = std::size_t{32} << 20;

std::atomic<std::uintptr_t> advised_top{0};  // the heap is advised below this address

void AdviseRange(std::uintptr_t begin, std::uintptr_t end) {
#ifdef MADV_HUGEPAGE
  begin = (begin + kPage - 1) & ~(kPage - 1);
  end &= ~(kPage - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint
#endif
}

void* Advise(void* p, std::size_t n) {
  if (p == nullptr) return p;
  if (n >= kLarge) {
    AdviseRange(reinterpret_cast<std::uintptr_t>(p), reinterpret_cast<std::uintptr_t>(p) + n);
    return p;
  }
  // The heap's top (glibc keeps it; no system call): advise what it grew by since last time.
  const auto top = reinterpret_cast<std::uintptr_t>(::sbrk(0));
  std::uintptr_t seen = advised_top.load(std::memory_order_relaxed);
  if (top > seen && advised_top.compare_exchange_strong(seen, top)) AdviseRange(seen, top);
  return p;
}

[[gnu::constructor]] void SetPolicy() {
  ::mallopt(M_MMAP_THRESHOLD, static_cast<int>(kLarge));
  // One arena, unless the command says its threads allocate side by side (rbsim: one arena made
  // `rbsim poses` slower on two threads than on one, every step's small blocks behind one lock).
  if (&massprops_app_one_arena == nullptr || massprops_app_one_arena) ::mallopt(M_ARENA_MAX, 1);
  ::mallopt(M_TOP_PAD, static_cast<int>(kHeapStep));
  ::mallopt(M_TRIM_THRESHOLD, static_cast<int>(4 * kHeapStep));
  advised_top.store(reinterpret_cast<std::uintptr_t>(::sbrk(0)));
}

}  // namespace

extern "C" void* malloc(std::size_t n) { return Advise(__libc_malloc(n), n); }

extern "C" void* calloc(std::size_t k, std::size_t n) {
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(k, n, &bytes)) return __libc_calloc(k, n);  // glibc refuses it
  return Advise(__libc_calloc(k, n), bytes);
}

extern "C" void* realloc(void* p, std::size_t n) { return Advise(__libc_realloc(p, n), n); }

#endif
