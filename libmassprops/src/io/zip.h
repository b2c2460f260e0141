#pragma once
// Reading entries of a zip package held in memory (3MF, zipped AMF): the central directory, and
// an entry's bytes, stored or deflated (zlib), up to a limit.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace massprops::internal {

struct ZipEntry {
  std::string name;
  int method = 0;                ///< 0 stored, 8 deflated
  std::size_t data_offset = 0;   ///< where its bytes start in the file
  std::size_t compressed = 0;    ///< bytes in the file
  std::size_t uncompressed = 0;  ///< bytes once inflated (as the directory says)
};

/// The entries the central directory lists; empty when the bytes are not a zip package (or its
/// directory is cut short).
std::vector<ZipEntry> ZipDirectory(const unsigned char* file, std::size_t size);

/// The first `limit` bytes of the entry (all of it when shorter), or nothing when it cannot be
/// read (an unknown compression, a corrupt stream, offsets beyond the file).
std::optional<std::string> ZipRead(const unsigned char* file, std::size_t size, const ZipEntry& entry,
                                   std::size_t limit);

}  // namespace massprops::internal
