#include <algorithm>
#include <cerrno>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io_internal.h"
#include "massprops/triangle_soup.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the binary STL readers assume a little-endian host (STL stores little-endian floats)"
#endif
#include "massprops/io.h"

namespace massprops {

[[noreturn]] void Fail(const std::string& path, const std::string& what) {
  throw MeshFileError(path + ": " + what);
}

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string_view NextToken(std::string_view& s) {
  std::size_t i = 0;
  while (i < s.size() && IsSpace(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !IsSpace(s[j])) ++j;
  std::string_view tok = s.substr(i, j - i);
  s.remove_prefix(j);
  return tok;
}

bool ParseDouble(std::string_view tok, double& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return res.ec == std::errc() && res.ptr == tok.data() + tok.size();
}

// Welds corners by bit-identical position (with -0.0 == 0.0).
struct PositionKey {
  double x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    auto bits = [](double d) {
      std::uint64_t u;
      d = d == 0.0 ? 0.0 : d;
      std::memcpy(&u, &d, sizeof u);
      return u;
    };
    std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= bits(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= bits(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

namespace {

// The weld, over corners given by an accessor (so binary STL records are read in place, without
// an intermediate copy of every coordinate).
template <typename CornerAt>
LoadedMesh Weld(const std::string& path, std::size_t corners, const CornerAt& corner_at,
                const std::vector<int>& face_sizes, const char* format) {
  LoadedMesh out;
  out.format = format;
  // Open addressing with linear probing over a power-of-two table of vertex ids (−1: empty),
  // at most half full: no allocation per vertex, unlike a node-based map. Vertices are numbered
  // in order of first appearance.
  // A closed triangle mesh has about corners/6 distinct vertices: start there and double the
  // table whenever it gets half full.
  std::size_t slots = 16;
  int shift = 60;  // slot = top log2(slots) bits of the mixed hash
  while (slots < corners / 3) slots *= 2, --shift;
  std::vector<std::int32_t> table(slots, -1);
  auto mix = [](std::uint64_t h) {
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    return h ^ (h >> 31);
  };
  const PositionHash hash;
  std::vector<double> verts;
  verts.reserve(corners / 2 + 3);
  out.mesh.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const PositionKey k = corner_at(c);
    if (!std::isfinite(k.x) || !std::isfinite(k.y) || !std::isfinite(k.z)) {
      std::ostringstream msg;
      msg << "triangle " << c / 3 << " has a non-finite coordinate (" << k.x << ", " << k.y
          << ", " << k.z << ")";
      Fail(path, msg.str());
    }
    // Float-derived doubles have many zero low bits: mix (Stafford's variant 13) and take the top bits.
    std::size_t slot = static_cast<std::size_t>(mix(hash(k)) >> shift);
    while (true) {
      const std::int32_t id = table[slot];
      if (id < 0) {
        table[slot] = static_cast<std::int32_t>(verts.size() / 3);
        out.mesh.indices.push_back(table[slot]);
        verts.insert(verts.end(), {k.x, k.y, k.z});
        if (2 * (verts.size() / 3) > slots) {  // grow: reinsert every vertex id
          slots *= 2;
          --shift;
          table.assign(slots, -1);
          for (std::size_t v = 0; v < verts.size() / 3; ++v) {
            const PositionKey kv{verts[3 * v], verts[3 * v + 1], verts[3 * v + 2]};
            std::size_t sl = static_cast<std::size_t>(mix(hash(kv)) >> shift);
            while (table[sl] >= 0) sl = (sl + 1) & (slots - 1);
            table[sl] = static_cast<std::int32_t>(v);
          }
        }
        break;
      }
      const double* v = verts.data() + 3 * static_cast<std::size_t>(id);
      if (v[0] == k.x && v[1] == k.y && v[2] == k.z) {
        out.mesh.indices.push_back(id);
        ++out.welded;
        break;
      }
      slot = (slot + 1) & (slots - 1);
    }
  }
  out.mesh.offsets.reserve(face_sizes.size() + 1);
  for (int n : face_sizes) out.mesh.offsets.push_back(out.mesh.offsets.back() + n);
  out.mesh.V = Eigen::Map<const VertexMatrix>(verts.data(), static_cast<Eigen::Index>(verts.size() / 3), 3);
  return out;
}

}  // namespace

// Welds corners given one by one (xyz per corner) into shared vertices by bit-identical position,
// with faces given by their corner counts. Used by the STL readers and the assimp path.
LoadedMesh WeldCorners(const std::string& path, const std::vector<double>& xyz,
                       const std::vector<int>& face_sizes, const char* format) {
  return Weld(path, xyz.size() / 3, [&xyz](std::size_t c) { return PositionKey{xyz[3 * c], xyz[3 * c + 1], xyz[3 * c + 2]}; },
              face_sizes, format);
}

namespace {

LoadedMesh FromTriangleSoup(const std::string& path, const std::vector<double>& xyz,
                            const char* format) {
  return WeldCorners(path, xyz, std::vector<int>(xyz.size() / 9, 3), format);
}

LoadedMesh ReadBinaryStl(const std::string& path, std::string_view data, std::uint32_t n) {
  const char* records = data.data() + 84;
  auto corner_at = [records](std::size_t c) {
    float f[3];  // record t = c / 3: 12 bytes of normal, then three corners of 12 bytes
    std::memcpy(f, records + 50 * (c / 3) + 12 + 12 * (c % 3), sizeof f);
    return PositionKey{f[0], f[1], f[2]};
  };
  LoadedMesh out = Weld(path, 3 * static_cast<std::size_t>(n), corner_at, std::vector<int>(n, 3), "stl-binary");
  out.float32_coordinates = true;
  return out;
}

LoadedMesh ReadAsciiStl(const std::string& path, std::string_view data) {
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
          Fail(path, "line " + std::to_string(line) + ": expected a number after 'vertex', got '" +
                         std::string(tok) + "'");
        }
      }
      xyz.insert(xyz.end(), v, v + 3);
      ++in_facet_vertices;
    } else if (key == "endloop") {
      if (in_facet_vertices != 3) {
        Fail(path, "line " + std::to_string(line) + ": a facet has " +
                       std::to_string(in_facet_vertices) + " vertices; STL facets have 3");
      }
      in_facet_vertices = 0;
    } else if (key == "solid") {
      saw_solid = true;
    } else if (!(key.empty() || key == "facet" || key == "outer" || key == "endfacet" ||
                 key == "endsolid")) {
      Fail(path, "line " + std::to_string(line) + ": unexpected '" + key +
                     "' in an ASCII STL");
    }
    ++line;
  }
  if (!saw_solid || xyz.empty()) Fail(path, "no facets found in the ASCII STL");
  if (in_facet_vertices != 0) Fail(path, "the ASCII STL ends inside a facet (truncated?)");
  return FromTriangleSoup(path, xyz, "stl-ascii");
}

LoadedMesh ParseStl(const std::string& path, std::string_view data) {
  if (data.empty()) Fail(path, "the file is empty");
  const StlLayout layout =
      DetectStl(path, reinterpret_cast<const unsigned char*>(data.data()), data.size());
  if (layout.ascii) return ReadAsciiStl(path, data);
  return ReadBinaryStl(path, data, layout.triangles);
}

LoadedMesh ParseObj(const std::string& path, std::string_view data) {
  if (data.empty()) Fail(path, "the file is empty");
  LoadedMesh out;
  out.format = "obj";
  std::vector<double> verts;
  std::vector<std::int32_t> face;
  std::string joined;
  std::string_view rest(data);
  std::size_t line = 0;
  while (!rest.empty()) {
    // One logical line: physical lines joined where they end with a backslash.
    joined.clear();
    const std::size_t first_line = line + 1;
    for (;;) {
      const std::size_t eol = rest.find('\n');
      std::string_view ln = rest.substr(0, eol);
      rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
      ++line;
      while (!ln.empty() && (ln.back() == '\r' || ln.back() == ' ' || ln.back() == '\t')) ln.remove_suffix(1);
      if (!ln.empty() && ln.back() == '\\' && !rest.empty()) {
        ln.remove_suffix(1);
        joined.append(ln);
        joined.push_back(' ');
        continue;
      }
      joined.append(ln);
      break;
    }
    std::string_view s(joined);
    const std::size_t hash = s.find('#');
    if (hash != std::string_view::npos) s = s.substr(0, hash);
    const std::string_view key = NextToken(s);
    auto where = [&]() { return "line " + std::to_string(first_line) + ": "; };
    if (key == "v") {
      for (int k = 0; k < 3; ++k) {
        const std::string_view tok = NextToken(s);
        double c;
        if (!ParseDouble(tok, c)) Fail(path, where() + "expected a coordinate, got '" + std::string(tok) + "'");
        if (!std::isfinite(c)) Fail(path, where() + "non-finite coordinate '" + std::string(tok) + "'");
        verts.push_back(c);
      }
    } else if (key == "f") {
      face.clear();
      const auto nv = static_cast<std::int64_t>(verts.size() / 3);
      for (std::string_view tok = NextToken(s); !tok.empty(); tok = NextToken(s)) {
        const std::string_view idx = tok.substr(0, tok.find('/'));
        std::int64_t i = 0;
        const auto res = std::from_chars(idx.data(), idx.data() + idx.size(), i);
        if (res.ec != std::errc() || res.ptr != idx.data() + idx.size() || i == 0) {
          Fail(path, where() + "bad face index '" + std::string(tok) + "'");
        }
        const std::int64_t zero_based = i > 0 ? i - 1 : nv + i;  // negative: relative to the end
        if (zero_based < 0 || zero_based >= nv) {
          Fail(path, where() + "face index " + std::to_string(i) + " is out of range (" +
                         std::to_string(nv) + " vertices so far)");
        }
        face.push_back(static_cast<std::int32_t>(zero_based));
      }
      if (face.size() < 3) Fail(path, where() + "a face needs at least 3 corners");
      out.mesh.AddFace(face);
    }
    // vt, vn, o, g, s, usemtl, mtllib, l, ...: not geometry of the solid.
  }
  if (verts.empty() || out.mesh.num_faces() == 0) Fail(path, "no faces found in the OBJ file");
  out.mesh.V = Eigen::Map<const VertexMatrix>(verts.data(), static_cast<Eigen::Index>(verts.size() / 3), 3);
  return out;
}

}  // namespace

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
    const bool looks_text = head.find('\0') == std::string_view::npos &&
                            (head.find("facet") != std::string_view::npos ||
                             head.find("endsolid") != std::string_view::npos);
    if (looks_text) return {true, 0, 0};
  }
  if (size >= 84 && n > 0 && expected < size && size - expected < 50) {
    return {false, n, size - expected};  // a few trailing bytes after the last record
  }
  if (size < 84) Fail(path, "too short for a binary STL (" + std::to_string(size) + " bytes) and not ASCII STL");
  std::ostringstream msg;
  msg << "binary STL header says " << n << " triangles, which need " << expected
      << " bytes, but the file has " << size << " bytes (truncated or not an STL)";
  Fail(path, msg.str());
}

std::optional<SoupIntegrals> IntegrateBinaryStlFile(const std::string& path,
                                                    const IntegrationOptions& options) {
  // pread block by block into small per-thread buffers: the file is read once, in parallel, and
  // each block is integrated while it is in cache (faster than a memory map, whose page-cache
  // pages the hardware prefetcher does not stream across, and than one big read).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) Fail(path, std::string("cannot open the file (") + std::strerror(errno) + ")");
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) Fail(path, "not a regular file");
  const auto size = static_cast<std::size_t>(st.st_size);
  if (size == 0) Fail(path, "the file is empty");
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
  std::vector<unsigned char> head(std::min<std::size_t>(size, 4096));
  if (::pread(fd, head.data(), head.size(), 0) != static_cast<ssize_t>(head.size())) {
    Fail(path, "cannot read the file");
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

LoadedMesh ParseMeshBuffer(const std::string& name, const std::string& extension,
                           std::string_view bytes) {
  const std::string ext = Lower(extension);
  if (ext == "obj") return ParseObj(name, bytes);
  if (ext == "stl") return ParseStl(name, bytes);
  if (ext == "ply") return ParsePly(name, bytes);
  if (ext == "off") return ParseOff(name, bytes);
  Fail(name, "no parser of our own for '" + ext + "' (formats read through assimp need a file)");
}

LoadedMesh ReadMeshFile(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : Lower(path.substr(dot + 1));
  if (ext == "obj" || ext == "stl" || ext == "ply" || ext == "off") {
    const MappedFile file(path);
    return ParseMeshBuffer(path, ext, std::string_view(reinterpret_cast<const char*>(file.data()), file.size()));
  }
  if (AssimpCanRead(ext)) return ReadWithAssimp(path);
  const std::string plugin = AssimpPluginStatus();
  if (!plugin.empty()) {
    Fail(path, "cannot read '" + ext + "' files: our own readers take OBJ, STL, PLY and OFF, and for the rest " + plugin);
  }
  Fail(path, "unknown mesh format '" + ext + "' (neither our readers nor assimp know it)");
}

}  // namespace massprops
