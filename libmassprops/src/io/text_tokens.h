#pragma once
// Tokens of the text formats (internal): whitespace, words, numbers as doubles.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

// Numbers are parsed by fast_float when it is there (Debian's libfast-float-dev; several times
// faster than libstdc++'s from_chars), else by from_chars: both round correctly, so the doubles
// are the same bits either way.
#if __has_include(<fast_float/fast_float.h>)
#include <fast_float/fast_float.h>
#define MASSPROPS_FAST_FLOAT 1
#endif

namespace massprops::io_text {

inline std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// A file's extension, lower case, without its dot ("STL" → "stl"); "" when the file name has
/// none (a dot in a folder's name is not one). The one home of this rule for the readers.
inline std::string FileExtension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  return Lower(path.substr(dot + 1));
}

inline bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

inline std::string_view NextToken(std::string_view& s) {
  std::size_t i = 0;
  while (i < s.size() && IsSpace(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !IsSpace(s[j])) ++j;
  std::string_view tok = s.substr(i, j - i);
  s.remove_prefix(j);
  return tok;
}

// Parses a whole token as a double (a leading '+' allowed; "inf" and "nan" parse, and callers
// refuse them where they must).
inline bool ParseDouble(std::string_view tok, double& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
#ifdef MASSPROPS_FAST_FLOAT
  const auto res = fast_float::from_chars(tok.data(), tok.data() + tok.size(), out);
#else
  const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), out);
#endif
  return res.ec == std::errc() && res.ptr == tok.data() + tok.size();
}

// Whitespace tokenizer over a buffer, counting lines for messages.
inline bool Space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

class Tokens {
 public:
  explicit Tokens(std::string_view s, std::size_t pos = 0) : s_(s), pos_(pos) {}
  bool Next(std::string_view& tok) {
    while (pos_ < s_.size() && Space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= s_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !Space(s_[pos_])) ++pos_;
    tok = s_.substr(start, pos_ - start);
    return true;
  }
  std::size_t line() const { return line_; }

 private:
  std::string_view s_;
  std::size_t pos_;
  std::size_t line_ = 1;
};

template <typename T>
bool ParseNumber(std::string_view tok, T& out) {
  if constexpr (std::is_same_v<T, double>) {
    return ParseDouble(tok, out);
  } else {
    if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
    const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return res.ec == std::errc() && res.ptr == tok.data() + tok.size();
  }
}

}  // namespace massprops::io_text
