#pragma once
// An uninitialised array for large temporaries. Above a few MB it is mapped on its own and, where
// the kernel allows it, backed by 2 MB pages: first touching 100 MB in 4 KB pages is 25 000 page
// faults, which on a virtual machine cost more than the pass that writes them.

#include <sys/mman.h>

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace massprops::internal {

template <typename T>
class LargeArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  LargeArray() = default;
  explicit LargeArray(std::size_t n) : size_(n) {
    bytes_ = n * sizeof(T);
    if (bytes_ >= kMapped) {
      void* p = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
      ::madvise(p, bytes_, MADV_HUGEPAGE);  // a hint: without it, 4 KB pages
#endif
      data_ = static_cast<T*>(p);
      mapped_ = true;
    } else if (n > 0) {
      data_ = static_cast<T*>(::operator new(bytes_));
    }
  }
  LargeArray(const LargeArray&) = delete;
  LargeArray& operator=(const LargeArray&) = delete;
  LargeArray(LargeArray&& o) noexcept { *this = std::move(o); }
  LargeArray& operator=(LargeArray&& o) noexcept {
    if (this != &o) {
      Release();
      data_ = o.data_, size_ = o.size_, bytes_ = o.bytes_, mapped_ = o.mapped_;
      o.data_ = nullptr, o.size_ = o.bytes_ = 0, o.mapped_ = false;
    }
    return *this;
  }
  ~LargeArray() { Release(); }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  std::size_t size() const { return size_; }

 private:
  void Release() {
    if (mapped_)
      ::munmap(data_, bytes_);
    else
      ::operator delete(data_);
  }
  static constexpr std::size_t kMapped = std::size_t{4} << 20;
  T* data_ = nullptr;
  std::size_t size_ = 0, bytes_ = 0;
  bool mapped_ = false;
};

}  // namespace massprops::internal
