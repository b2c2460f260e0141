#pragma once
// The byte layout in which a reader plugin running in a child process hands its result to the
// parent: numbers in this machine's own layout (both ends are the same build), strings and arrays
// preceded by their length. The reader side checks every length against what is left, so a child
// that died mid-message is a clear error, never an overrun.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace massprops::wire {

class Writer {
 public:
  void U64(std::uint64_t v) { Raw(&v, sizeof v); }
  void F64(double v) { Raw(&v, sizeof v); }
  void F64s(const double* v, std::size_t n) { Raw(v, n * sizeof(double)); }
  void I32s(const std::int32_t* v, std::size_t n) { Raw(v, n * sizeof(std::int32_t)); }
  void Str(std::string_view s) {
    U64(s.size());
    Raw(s.data(), s.size());
  }
  std::string& bytes() { return bytes_; }

 private:
  void Raw(const void* p, std::size_t n) {
    if (n > 0) bytes_.append(static_cast<const char*>(p), n);
  }
  std::string bytes_;
};

/// Thrown when the bytes end before what they announce.
class Truncated : public std::runtime_error {
 public:
  Truncated() : std::runtime_error("truncated") {}
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  std::uint64_t U64() {
    std::uint64_t v;
    Raw(&v, sizeof v);
    return v;
  }
  double F64() {
    double v;
    Raw(&v, sizeof v);
    return v;
  }
  /// `n` doubles appended to `out`; `n` is checked against what is left before anything grows.
  void F64s(std::uint64_t n, std::vector<double>& out) {
    if (n > Left() / sizeof(double)) throw Truncated();
    const std::size_t at = out.size();
    out.resize(at + n);
    Raw(out.data() + at, n * sizeof(double));
  }
  /// `n` 32-bit integers appended to `out`, checked as F64s.
  void I32s(std::uint64_t n, std::vector<std::int32_t>& out) {
    if (n > Left() / sizeof(std::int32_t)) throw Truncated();
    const std::size_t at = out.size();
    out.resize(at + n);
    Raw(out.data() + at, n * sizeof(std::int32_t));
  }
  std::string Str() {
    const std::uint64_t n = U64();
    if (n > Left()) throw Truncated();
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  std::size_t Left() const { return bytes_.size() - at_; }

 private:
  void Raw(void* p, std::size_t n) {
    if (n == 0) return;  // an empty array may have no storage at all
    if (n > Left()) throw Truncated();
    std::memcpy(p, bytes_.data() + at_, n);
    at_ += n;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace massprops::wire
