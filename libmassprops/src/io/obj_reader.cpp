// Wavefront OBJ: v/f records, n-gons kept whole, negative indices, several objects, backslash
// continuations, CRLF. Coordinates parsed as doubles.

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "io_internal.h"
#include "text_tokens.h"

namespace massprops {

using io_text::NextToken;
using io_text::ParseDouble;

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
          Fail(path, where() + "face index " + std::to_string(i) + " is out of range (" + std::to_string(nv) +
                         " vertices so far)");
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

}  // namespace massprops
