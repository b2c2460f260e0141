// STL, binary and ASCII (told apart by content, not by the "solid" keyword), and the streamed
// integration of big binary files.

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/io_internal.h"
#include "io/text_tokens.h"
#include "io/weld.h"
#include "massprops/triangle_soup.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the binary STL readers assume a little-endian host (STL stores little-endian floats)"
#endif

namespace massprops {
namespace {

using io_text::Lower;
using io_text::NextToken;
using io_text::ParseDouble;

LoadedMesh ReadBinaryStl(const std::string& path, std::string_view data, std::uint32_t n, int num_threads) {
  const char* records = data.data() + 84;
  auto corner_at = [records](std::size_t c) {
    float f[3];  // record t = c / 3: 12 bytes of normal, then three corners of 12 bytes
    const char* record = records + 50 * (c / 3);
    // The weld reads the records in order first: fetch bytes ahead, across the mapping's 4 KiB
    // pages that the hardware prefetcher does not cross (a hint; past the end is no access).
    __builtin_prefetch(record + 2048);
    std::memcpy(f, record + 12 + 12 * (c % 3), sizeof f);
    return weld::FloatKey{f[0], f[1], f[2]};
  };
  LoadedMesh out = weld::Weld(path, 3 * static_cast<std::size_t>(n), corner_at, nullptr, "stl-binary", num_threads);
  out.float32_coordinates = true;
  return out;
}

LoadedMesh ReadAsciiStl(const std::string& path, std::string_view data, int num_threads) {
  std::vector<double> xyz;
  std::string_view rest(data);
  std::size_t line = 1;
  int in_facet_vertices = 0;
  bool saw_solid = false;
  while (!rest.empty()) {
    const std::size_t eol = rest.find('\n');
    std::string_view ln = rest.substr(0, eol);
    rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
    std::string_view s = ln;
    const std::string key = Lower(std::string(NextToken(s)));  // keywords are case-insensitive
    if (key == "vertex") {
      double v[3];
      for (double& c : v) {
        const std::string_view tok = NextToken(s);
        if (!ParseDouble(tok, c)) {
          Fail(path,
               "line " + std::to_string(line) + ": expected a number after 'vertex', got '" + std::string(tok) + "'");
        }
      }
      xyz.insert(xyz.end(), v, v + 3);
      ++in_facet_vertices;
    } else if (key == "endloop") {
      if (in_facet_vertices != 3) {
        Fail(path, "line " + std::to_string(line) + ": a facet has " + std::to_string(in_facet_vertices) +
                       " vertices; STL facets have 3");
      }
      in_facet_vertices = 0;
    } else if (key == "solid") {
      saw_solid = true;
    } else if (!(key.empty() || key == "facet" || key == "outer" || key == "endfacet" || key == "endsolid")) {
      Fail(path, "line " + std::to_string(line) + ": unexpected '" + key + "' in an ASCII STL");
    }
    ++line;
  }
  if (!saw_solid || xyz.empty()) Fail(path, "no facets found in the ASCII STL");
  if (in_facet_vertices != 0) Fail(path, "the ASCII STL ends inside a facet (truncated?)");
  return WeldCorners(path, xyz, nullptr, "stl-ascii", num_threads);
}

}  // namespace

LoadedMesh ParseStl(const std::string& path, std::string_view data, int num_threads) {
  if (data.empty()) Fail(path, "the file is empty");
  const StlLayout layout = DetectStl(path, reinterpret_cast<const unsigned char*>(data.data()), data.size());
  if (layout.ascii) return ReadAsciiStl(path, data, num_threads);
  return ReadBinaryStl(path, data, layout.triangles, num_threads);
}

StlLayout DetectStl(const std::string& path, const unsigned char* bytes, std::size_t size) {
  const char* data = reinterpret_cast<const char*>(bytes);
  std::uint32_t n = 0;
  if (size >= 84) std::memcpy(&n, data + 80, 4);
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(n);
  const bool starts_solid = size >= 5 && std::memcmp(data, "solid", 5) == 0;
  if (size >= 84 && expected == size && n > 0) return {false, n, 0};
  if (starts_solid) {
    // Binary files from some exporters also begin with "solid"; text has no NUL bytes and
    // mentions "facet" early.
    const std::string_view head(data, std::min<std::size_t>(size, 4096));
    const bool looks_text =
        head.find('\0') == std::string_view::npos &&
        (head.find("facet") != std::string_view::npos || head.find("endsolid") != std::string_view::npos);
    if (looks_text) return {true, 0, 0};
  }
  if (size >= 84 && n > 0 && expected < size && size - expected < 50) {
    return {false, n, size - expected};  // a few trailing bytes after the last record
  }
  if (size < 84) Fail(path, "too short for a binary STL (" + std::to_string(size) + " bytes) and not ASCII STL");
  if (n == 0 && size == 84) Fail(path, "the binary STL holds no triangles (its header says 0)");
  std::ostringstream msg;
  msg << "binary STL header says " << n << " triangles, which need " << expected << " bytes, but the file has " << size
      << " bytes (truncated or not an STL)";
  Fail(path, msg.str());
}

std::optional<SoupIntegrals> IntegrateBinaryStlFile(const std::string& path, const IntegrationOptions& options) {
  // pread block by block into small per-thread buffers: the file is read once, in parallel, and
  // each block is integrated while it is in cache (faster than a memory map, whose page-cache
  // pages the hardware prefetcher does not stream across, and than one big read).
  const int fd = OpenRegularFile(path);
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) FailAccess(path, "not a regular file");
  const auto size = static_cast<std::size_t>(st.st_size);
  if (size == 0) Fail(path, "the file is empty");
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
  std::vector<unsigned char> head(std::min<std::size_t>(size, 4096));
  if (::pread(fd, head.data(), head.size(), 0) != static_cast<ssize_t>(head.size())) {
    FailAccess(path, "cannot read the file");
  }
  const StlLayout layout = DetectStl(path, head.data(), size);
  if (layout.ascii) return std::nullopt;
  const RecordReader read = [&](std::int64_t first, std::int64_t count, unsigned char* dest) {
    std::size_t want = static_cast<std::size_t>(count) * 50;
    auto at = static_cast<off_t>(84 + static_cast<std::size_t>(first) * 50);
    while (want > 0) {
      const ssize_t got = ::pread(fd, dest, want, at);
      if (got <= 0) Fail(path, "read error (the file changed or shrank while it was read?)");
      dest += got;
      at += got;
      want -= static_cast<std::size_t>(got);
    }
  };
  try {
    return IntegrateFloatTriangleRecords(read, layout.triangles, 50, 12, options);
  } catch (const std::invalid_argument& e) {
    Fail(path, e.what());
  }
}

}  // namespace massprops
