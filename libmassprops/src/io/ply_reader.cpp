// PLY (ASCII and binary, any property layout) reader of our own: coordinates are kept
// in the precision the file stores (double stays double), and a malformed or truncated file is
// an error naming the fault, never a hang (Debian's assimp 5.2 loops forever on a PLY whose
// header is cut short, and reads every coordinate as a 32-bit float).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "io/io_internal.h"
#include "io/text_tokens.h"

namespace massprops {
namespace {

using io_text::ParseNumber;
using io_text::Tokens;

// ---------------------------------------------------------------- PLY

enum class PlyType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

bool ParsePlyType(std::string_view name, PlyType& t) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUInt8},
      {"uint8", PlyType::kUInt8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUInt16},  {"uint16", PlyType::kUInt16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUInt32},     {"uint32", PlyType::kUInt32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [n, type] : kNames) {
    if (name == n) {
      t = type;
      return true;
    }
  }
  return false;
}

int PlySize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUInt8: return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16: return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32: return 4;
    case PlyType::kFloat64: return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// Reads one scalar of a binary PLY at `p` (bounds already checked), converting to double.
double ReadBinary(const char* p, PlyType t, bool swap) {
  unsigned char b[8];
  const int n = PlySize(t);
  std::memcpy(b, p, static_cast<std::size_t>(n));
  if (swap) std::reverse(b, b + n);
  switch (t) {
    case PlyType::kInt8: {
      std::int8_t v;
      std::memcpy(&v, b, 1);
      return v;
    }
    case PlyType::kUInt8: return b[0];
    case PlyType::kInt16: {
      std::int16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    case PlyType::kUInt16: {
      std::uint16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    case PlyType::kInt32: {
      std::int32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    case PlyType::kUInt32: {
      std::uint32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    case PlyType::kFloat32: {
      float v;
      std::memcpy(&v, b, 4);
      return v;
    }
    case PlyType::kFloat64: {
      double v;
      std::memcpy(&v, b, 8);
      return v;
    }
  }
  return 0;
}

// The PLY header (the text before "end_header"): its format and elements with their properties.
std::vector<PlyElement> ParsePlyHeader(const std::string& path, std::string_view text, std::string& format) {
  std::vector<PlyElement> elements;
  std::istringstream header{std::string(text)};
  std::string line;
  std::size_t n = 0;
  while (std::getline(header, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    auto where = [&] { return "header line " + std::to_string(n) + ": "; };
    if (key == "format") {
      ls >> format;
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      ls >> e.name >> count;
      if (!ParseNumber(count, e.count)) Fail(path, where() + "bad element count '" + count + "'");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) Fail(path, where() + "a property before any element");
      PlyProperty p;
      std::string type;
      ls >> type;
      if (type == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.is_list = true;
        if (!ParsePlyType(ct, p.count_type) || !ParsePlyType(it, p.type)) {
          Fail(path, where() + "unknown list types '" + ct + " " + it + "'");
        }
      } else {
        ls >> p.name;
        if (!ParsePlyType(type, p.type)) Fail(path, where() + "unknown property type '" + type + "'");
      }
      elements.back().properties.push_back(p);
    }
    // ply, comment, obj_info: nothing to do
  }
  return elements;
}

bool IsLittleEndianHost() {
  const std::uint16_t one = 1;
  unsigned char c;
  std::memcpy(&c, &one, 1);
  return c == 1;
}

}  // namespace

LoadedMesh ParsePly(const std::string& path, std::string_view data, int /*num_threads: one*/) {
  if (data.empty()) Fail(path, "the file is empty");
  if (data.substr(0, 3) != "ply") Fail(path, "not a PLY file (it does not start with 'ply')");
  const std::size_t header_end_tag = data.find("end_header");
  if (header_end_tag == std::string_view::npos) Fail(path, "the PLY header has no 'end_header' line (truncated?)");
  std::size_t body = data.find('\n', header_end_tag);
  if (body == std::string_view::npos) Fail(path, "nothing after the PLY header");
  ++body;

  std::string format;
  const std::vector<PlyElement> elements = ParsePlyHeader(path, data.substr(0, header_end_tag), format);
  const bool ascii = format == "ascii";
  const bool binary_le = format == "binary_little_endian";
  const bool binary_be = format == "binary_big_endian";
  if (!ascii && !binary_le && !binary_be) Fail(path, "unknown PLY format '" + format + "'");
  const bool swap = binary_be == IsLittleEndianHost();

  std::vector<double> verts;
  PolygonMesh mesh;
  std::vector<std::int64_t> face_corners;
  bool have_vertices = false;
  std::size_t pos = body;
  Tokens tokens(data, body);
  for (const PlyElement& e : elements) {
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const auto& p = e.properties[k];
      if (e.name == "vertex" && !p.is_list) {
        if (p.name == "x") ix = static_cast<int>(k);
        if (p.name == "y") iy = static_cast<int>(k);
        if (p.name == "z") iz = static_cast<int>(k);
      }
      if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        iface = static_cast<int>(k);
      }
    }
    if (e.name == "vertex") {
      if (ix < 0 || iy < 0 || iz < 0) Fail(path, "the vertex element lacks an x, y or z property");
      have_vertices = true;
      verts.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, data.size())) * 3);
    }
    // Every row of an element with properties takes at least a byte of the body: a count beyond
    // that is a lie (and would loop for ages); an element without properties holds nothing.
    if (e.properties.empty()) continue;
    if (e.count > data.size() - std::min(body, data.size())) {
      Fail(path, "the header promises " + std::to_string(e.count) + " rows of element '" + e.name +
                     "', more than the " + std::to_string(data.size() - std::min(body, data.size())) +
                     " bytes of its body can hold");
    }
    for (std::uint64_t r = 0; r < e.count; ++r) {
      double xyz[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        std::uint64_t items = 1;
        if (p.is_list) {
          double count;
          if (ascii) {
            std::string_view tok;
            if (!tokens.Next(tok) || !ParseNumber(tok, count)) {
              Fail(path,
                   "line " + std::to_string(tokens.line()) + ": bad or missing list count in element '" + e.name + "'");
            }
          } else {
            if (pos + PlySize(p.count_type) > data.size()) Fail(path, "the binary PLY body is truncated");
            count = ReadBinary(data.data() + pos, p.count_type, swap);
            pos += static_cast<std::size_t>(PlySize(p.count_type));
          }
          if (!(count >= 0) || count > 1e6)
            Fail(path, "implausible list length " + std::to_string(count) + " in element '" + e.name + "'");
          items = static_cast<std::uint64_t>(count);
        }
        if (static_cast<int>(k) == iface) face_corners.clear();
        for (std::uint64_t it = 0; it < items; ++it) {
          double v;
          if (ascii) {
            std::string_view tok;
            if (!tokens.Next(tok))
              Fail(path, "the PLY body ends early, in element '" + e.name + "' " + std::to_string(r));
            if (!ParseNumber(tok, v)) {
              Fail(path,
                   "line " + std::to_string(tokens.line()) + ": expected a number, got '" + std::string(tok) + "'");
            }
          } else {
            if (pos + PlySize(p.type) > data.size()) Fail(path, "the binary PLY body is truncated");
            v = ReadBinary(data.data() + pos, p.type, swap);
            pos += static_cast<std::size_t>(PlySize(p.type));
          }
          if (!p.is_list) {
            if (static_cast<int>(k) == ix) xyz[0] = v;
            if (static_cast<int>(k) == iy) xyz[1] = v;
            if (static_cast<int>(k) == iz) xyz[2] = v;
          } else if (static_cast<int>(k) == iface) {
            face_corners.push_back(static_cast<std::int64_t>(v));
          }
        }
      }
      if (e.name == "vertex") {
        for (double c : xyz) {
          if (!std::isfinite(c)) Fail(path, "vertex " + std::to_string(r) + " has a non-finite coordinate");
        }
        verts.insert(verts.end(), xyz, xyz + 3);
      } else if (iface >= 0) {
        if (!have_vertices) Fail(path, "faces come before the vertices");
        if (face_corners.size() < 3) Fail(path, "face " + std::to_string(r) + " has fewer than 3 corners");
        const auto nv = static_cast<std::int64_t>(verts.size() / 3);
        for (std::int64_t c : face_corners) {
          if (c < 0 || c >= nv) {
            Fail(path, "face " + std::to_string(r) + " refers to vertex " + std::to_string(c) + ", but there are " +
                           std::to_string(nv) + " vertices");
          }
        }
        mesh.AddFace(face_corners);
      }
    }
  }
  if (!have_vertices || mesh.num_faces() == 0) Fail(path, "no faces found in the PLY file");
  mesh.V = Eigen::Map<const VertexMatrix>(verts.data(), static_cast<Eigen::Index>(verts.size() / 3), 3);
  LoadedMesh out;
  out.mesh = std::move(mesh);
  out.format = ascii ? "ply-ascii" : "ply-binary";
  // Single-precision vertex properties mean 32-bit coordinates.
  for (const PlyElement& e : elements) {
    if (e.name != "vertex") continue;
    for (const auto& p : e.properties) {
      if ((p.name == "x" || p.name == "y" || p.name == "z") && p.type == PlyType::kFloat32) {
        out.float32_coordinates = true;
      }
    }
  }
  return out;
}

}  // namespace massprops
