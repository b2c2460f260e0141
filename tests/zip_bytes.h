#pragma once
// A zip package of stored (uncompressed) entries, as some 3MF producers write them, for the
// tests and the fuzzer to build packages around bytes. CRC-32 computed here (table-driven), so
// no test needs zlib.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace massprops::testing {

inline std::uint32_t Crc32(const std::string& data) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char c : data) crc = (crc >> 8) ^ table[(crc ^ static_cast<unsigned char>(c)) & 0xffu];
  return ~crc;
}

inline std::string StoredZip(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string out, directory;
  auto u16 = [](std::string& s, std::uint32_t v) {
    s += static_cast<char>(v & 0xff);
    s += static_cast<char>(v >> 8 & 0xff);
  };
  auto u32 = [&](std::string& s, std::uint64_t v) {
    u16(s, static_cast<std::uint32_t>(v & 0xffff));
    u16(s, static_cast<std::uint32_t>(v >> 16 & 0xffff));
  };
  for (const auto& [name, data] : entries) {
    const std::uint32_t crc = Crc32(data);
    const auto offset = out.size();
    // Local header: signature, version, flags, method 0 (stored), time, date, CRC, sizes, name.
    u32(out, 0x04034b50), u16(out, 20), u16(out, 0), u16(out, 0), u16(out, 0), u16(out, 0);
    u32(out, crc), u32(out, data.size()), u32(out, data.size());
    u16(out, static_cast<std::uint32_t>(name.size())), u16(out, 0);
    out += name + data;
    // Central directory entry: the same, and where the local header is.
    u32(directory, 0x02014b50), u16(directory, 20), u16(directory, 20), u16(directory, 0), u16(directory, 0);
    u16(directory, 0), u16(directory, 0), u32(directory, crc), u32(directory, data.size());
    u32(directory, data.size()), u16(directory, static_cast<std::uint32_t>(name.size()));
    u16(directory, 0), u16(directory, 0), u16(directory, 0), u16(directory, 0), u32(directory, 0);
    u32(directory, offset);
    directory += name;
  }
  const auto at = out.size();
  out += directory;
  u32(out, 0x06054b50), u16(out, 0), u16(out, 0), u16(out, static_cast<std::uint32_t>(entries.size()));
  u16(out, static_cast<std::uint32_t>(entries.size())), u32(out, directory.size()), u32(out, at), u16(out, 0);
  return out;
}

}  // namespace massprops::testing
