// OFF reader of our own: '#' comments, the header keyword ([ST][C][N][4]OFF) possibly followed by
// the counts, coordinates kept as doubles; a malformed or truncated file is an error naming the
// fault.

#include <string>
#include <string_view>
#include <vector>

#include "io/io_internal.h"
#include "io/text_tokens.h"

namespace massprops {

using io_text::ParseNumber;
using io_text::Space;
using io_text::Tokens;

LoadedMesh ParseOff(const std::string& path, std::string_view data, int /*num_threads: one*/) {
  if (data.empty()) Fail(path, "the file is empty");
  // Line based: '#' comments, a header keyword ([ST][C][N][4]OFF) possibly followed by the counts.
  std::vector<std::string_view> lines;
  std::vector<std::size_t> line_numbers;
  {
    std::string_view rest(data);
    std::size_t n = 0;
    while (!rest.empty()) {
      const std::size_t eol = rest.find('\n');
      std::string_view ln = rest.substr(0, eol);
      rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
      ++n;
      const std::size_t hash = ln.find('#');
      if (hash != std::string_view::npos) ln = ln.substr(0, hash);
      std::size_t a = 0;
      while (a < ln.size() && Space(ln[a])) ++a;
      if (a == ln.size()) continue;
      lines.push_back(ln.substr(a));
      line_numbers.push_back(n);
    }
  }
  std::size_t li = 0;
  if (lines.empty()) Fail(path, "no content in the OFF file");
  bool counts_after_keyword = false;  // "OFF nv nf ne" on one line
  {
    Tokens head(lines[0]);
    std::string_view kw, next;
    head.Next(kw);
    if (kw.size() >= 3 && kw.substr(kw.size() - 3) == "OFF") {
      if (kw.find('4') != std::string_view::npos || kw.find('n') == 0) {
        Fail(path, "'" + std::string(kw) + "' (higher-dimensional OFF) is not a 3-D surface mesh");
      }
      if (head.Next(next)) {
        counts_after_keyword = true;
      } else {
        ++li;
      }
    } else if (kw.find("OFF") != std::string_view::npos) {
      Fail(path, "unsupported OFF variant '" + std::string(kw) + "'");
    }
  }
  auto where = [&](std::size_t i) {
    return "line " + std::to_string(line_numbers[std::min(i, lines.size() - 1)]) + ": ";
  };
  if (li >= lines.size()) Fail(path, "the OFF file ends before its counts");
  std::uint64_t nv = 0, nf = 0;
  {
    Tokens t(lines[li]);
    std::string_view a, b;
    if (counts_after_keyword) t.Next(a);  // the keyword itself
    if (!t.Next(a) || !t.Next(b) || !ParseNumber(a, nv) || !ParseNumber(b, nf)) {
      Fail(path, where(li) + "expected the vertex and face counts");
    }
    ++li;
  }
  if (nv > data.size() || nf > data.size()) Fail(path, "the counts exceed what the file can hold");
  std::vector<double> verts;
  verts.reserve(static_cast<std::size_t>(nv) * 3);
  for (std::uint64_t v = 0; v < nv; ++v, ++li) {
    if (li >= lines.size())
      Fail(path, "the OFF file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    Tokens t(lines[li]);
    for (int k = 0; k < 3; ++k) {
      std::string_view tok;
      double c;
      if (!t.Next(tok) || !ParseNumber(tok, c)) Fail(path, where(li) + "expected 3 coordinates");
      if (!std::isfinite(c)) Fail(path, where(li) + "non-finite coordinate");
      verts.push_back(c);
    }
  }
  PolygonMesh mesh;
  std::vector<std::int64_t> face;
  for (std::uint64_t f = 0; f < nf; ++f, ++li) {
    if (li >= lines.size())
      Fail(path, "the OFF file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    Tokens t(lines[li]);
    std::string_view tok;
    std::uint64_t n = 0;
    if (!t.Next(tok) || !ParseNumber(tok, n) || n < 3 || n > 1000000) {
      Fail(path, where(li) + "a face must start with its corner count (3 or more)");
    }
    face.clear();
    for (std::uint64_t k = 0; k < n; ++k) {
      std::int64_t idx;
      if (!t.Next(tok) || !ParseNumber(tok, idx))
        Fail(path, where(li) + "expected " + std::to_string(n) + " vertex indices");
      if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv) {
        Fail(path, where(li) + "vertex index " + std::to_string(idx) + " is out of range (" + std::to_string(nv) +
                       " vertices)");
      }
      face.push_back(idx);
    }
    mesh.AddFace(face);  // colour values after the indices are ignored
  }
  if (mesh.num_faces() == 0) Fail(path, "no faces found in the OFF file");
  mesh.V = Eigen::Map<const VertexMatrix>(verts.data(), static_cast<Eigen::Index>(verts.size() / 3), 3);
  LoadedMesh out;
  out.mesh = std::move(mesh);
  out.format = "off";
  return out;
}

}  // namespace massprops
