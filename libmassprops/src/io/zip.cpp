// The definitions of zip.h: reading entries of a zip package held in memory (3MF, zipped AMF).

#include "io/zip.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>

namespace massprops::internal {
namespace {

std::uint32_t U32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t{p[3]} << 24; }
std::uint16_t U16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }

}  // namespace

std::vector<ZipEntry> ZipDirectory(const unsigned char* file, std::size_t size) {
  std::vector<ZipEntry> out;
  if (size < 22) return out;
  std::size_t eocd = std::string::npos;
  for (std::size_t i = size - 22 + 1; i-- > (size > 65557 ? size - 65557 : 0);) {
    if (U32(file + i) == 0x06054b50) {
      eocd = i;
      break;
    }
  }
  if (eocd == std::string::npos) return out;
  const std::size_t entries = U16(file + eocd + 10);
  std::size_t at = U32(file + eocd + 16);
  for (std::size_t e = 0; e < entries && at + 46 <= size && U32(file + at) == 0x02014b50; ++e) {
    const std::size_t name_len = U16(file + at + 28), extra = U16(file + at + 30), comment = U16(file + at + 32);
    if (at + 46 + name_len > size) break;
    ZipEntry entry;
    entry.name.assign(reinterpret_cast<const char*>(file + at + 46), name_len);
    entry.method = U16(file + at + 10);
    entry.compressed = U32(file + at + 20);
    entry.uncompressed = U32(file + at + 24);
    const std::size_t local = U32(file + at + 42);
    if (local + 30 <= size && U32(file + local) == 0x04034b50) {
      entry.data_offset = local + 30 + U16(file + local + 26) + U16(file + local + 28);
      if (entry.data_offset <= size) out.push_back(std::move(entry));
    }
    at += 46 + name_len + extra + comment;
  }
  return out;
}

std::optional<std::string> ZipRead(const unsigned char* file, std::size_t size, const ZipEntry& entry,
                                   std::size_t limit) {
  if (entry.data_offset > size) return std::nullopt;
  const unsigned char* data = file + entry.data_offset;
  const std::size_t available = std::min(size - entry.data_offset, entry.compressed);
  if (entry.method == 0) return std::string(reinterpret_cast<const char*>(data), std::min(available, limit));
  if (entry.method != 8) return std::nullopt;
  std::string out;
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return std::nullopt;
  z.next_in = const_cast<unsigned char*>(data);
  std::size_t fed = 0;
  int status = Z_OK;
  char buffer[1 << 16];
  while (out.size() < limit) {
    if (z.avail_in == 0 && fed < available) {
      const std::size_t chunk = std::min<std::size_t>(available - fed, 1u << 30);
      z.next_in = const_cast<unsigned char*>(data + fed);
      z.avail_in = static_cast<uInt>(chunk);
      fed += chunk;
    }
    const std::size_t want = std::min<std::size_t>(sizeof buffer, limit - out.size());
    z.next_out = reinterpret_cast<unsigned char*>(buffer);
    z.avail_out = static_cast<uInt>(want);
    status = inflate(&z, Z_NO_FLUSH);
    out.append(buffer, want - z.avail_out);
    if (status == Z_STREAM_END) break;
    if (status != Z_OK && status != Z_BUF_ERROR) {
      inflateEnd(&z);
      return std::nullopt;
    }
    if (status == Z_BUF_ERROR && z.avail_in == 0 && fed >= available) break;  // input ended early
  }
  inflateEnd(&z);
  return out;
}

}  // namespace massprops::internal
