// Wavefront OBJ: v/f records, n-gons kept whole, negative indices, several objects, backslash
// continuations, CRLF. Coordinates parsed as doubles (correctly rounded).
//
// Large files are cut at line ends into chunks parsed in parallel; each chunk keeps the indices as
// written, and a second pass resolves them (relative indices count back from the vertices read so
// far in the whole file). The first fault in file order is the one reported, with its line, so the
// result and the messages are those of a single pass.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/io_internal.h"
#include "io/text_tokens.h"
#include "massprops/parallel.h"

namespace massprops {
namespace {

using io_text::NextToken;
using io_text::ParseDouble;

// What one chunk read: vertices, and faces with their indices as written.
struct Chunk {
  std::string_view text;
  std::vector<double> verts;
  std::vector<std::int64_t> indices;  // as written (1-based, or negative: relative)
  std::vector<std::int32_t> face_sizes;
  std::vector<std::int64_t> verts_before;  // per face: this chunk's vertices read before it
  std::vector<std::size_t> face_line;      // per face: its line within the chunk (1-based)
  std::size_t lines = 0;                   // physical lines (newlines) in the chunk
  std::size_t error_line = 0;              // 0: none; else the line (within the chunk) of the fault
  std::string error;
  // `o` and `g` records: the faces of this chunk read before each, and its name.
  struct PartStart {
    std::size_t faces_before;
    bool object;  // `o` (else `g`)
    std::string name;
  };
  std::vector<PartStart> part_starts;
};

// A chunk boundary at or after `from`: just past a newline that does not continue its line.
std::size_t LineBoundary(std::string_view data, std::size_t from) {
  while (from < data.size()) {
    const std::size_t eol = data.find('\n', from);
    if (eol == std::string_view::npos) return data.size();
    std::size_t end = eol;
    while (end > 0 && (data[end - 1] == '\r' || data[end - 1] == ' ' || data[end - 1] == '\t')) --end;
    if (end == 0 || data[end - 1] != '\\') return eol + 1;
    from = eol + 1;
  }
  return data.size();
}

inline bool Blank(char ch) { return ch == ' ' || ch == '\t'; }

// The common lines — "v x y z ..." and "f i j k ..." (with optional /vt/vn parts), no comment,
// no continuation — parsed in one pass over the characters. Returns false, having changed
// nothing, for anything else; the general path then reads the line (same results, same faults).
bool ParseCommonLine(const char* p, const char* end, Chunk& c) {
  if (end - p < 2 || (p[0] != 'v' && p[0] != 'f') || !Blank(p[1])) return false;
  const char* last = end;  // p[0] is not blank: the trim stops after it
  while (last[-1] == '\r' || Blank(last[-1])) --last;
  if (last[-1] == '\\') return false;  // continued on the next line
  if (p[0] == 'v') {
    double xyz[3];
    const char* q = p + 1;
    for (double& x : xyz) {
      while (q < last && Blank(*q)) ++q;
      if (q < last && *q == '+') ++q;
#ifdef MASSPROPS_FAST_FLOAT
      const auto res = fast_float::from_chars(q, last, x);
#else
      const auto res = std::from_chars(q, last, x);
#endif
      if (res.ec != std::errc() || (res.ptr < last && !Blank(*res.ptr)) || !std::isfinite(x)) return false;
      q = res.ptr;
    }
    c.verts.insert(c.verts.end(), xyz, xyz + 3);
    return true;
  }
  if (p[0] == 'f') {
    const std::size_t before = c.indices.size();
    const char* q = p + 1;
    std::int32_t n = 0;
    while (true) {
      while (q < last && Blank(*q)) ++q;
      if (q == last) break;
      const bool negative = *q == '-';
      if (negative) ++q;
      const char* digits = q;
      std::int64_t i = 0;
      while (q < last && *q >= '0' && *q <= '9' && q - digits < 15) i = 10 * i + (*q++ - '0');
      if (q == digits || i == 0 || (q < last && *q >= '0' && *q <= '9')) break;  // no digits, 0, or too long
      if (negative) i = -i;
      if (q < last && *q == '/') {
        while (q < last && !Blank(*q) && *q != '#') ++q;
      }
      if (q < last && !Blank(*q)) break;
      c.indices.push_back(i);
      ++n;
    }
    if (q != last || n < 3) {
      c.indices.resize(before);
      return false;
    }
    c.face_sizes.push_back(n);
    c.verts_before.push_back(static_cast<std::int64_t>(c.verts.size() / 3));
    c.face_line.push_back(c.lines);
    return true;
  }
  return false;
}

void ParseChunk(Chunk& c) {
  std::string_view rest = c.text;
  std::string joined;  // only for lines continued with a backslash
  auto fail = [&](std::size_t line, std::string what) {
    c.error_line = line;
    c.error = std::move(what);
  };
  c.verts.reserve(rest.size() / 20);
  c.indices.reserve(rest.size() / 10);
  while (!rest.empty()) {
    const std::size_t first_line = c.lines + 1;
    std::string_view s;
    {
      const std::size_t eol = rest.find('\n');
      std::string_view ln = rest.substr(0, eol);
      rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
      ++c.lines;
      if (ParseCommonLine(ln.data(), ln.data() + ln.size(), c)) continue;
      while (!ln.empty() && (ln.back() == '\r' || ln.back() == ' ' || ln.back() == '\t')) ln.remove_suffix(1);
      if (!ln.empty() && ln.back() == '\\' && !rest.empty()) {
        // One logical line: physical lines joined where they end with a backslash.
        joined.assign(ln.substr(0, ln.size() - 1));
        joined.push_back(' ');
        for (;;) {
          const std::size_t e = rest.find('\n');
          std::string_view next = rest.substr(0, e);
          rest.remove_prefix(e == std::string_view::npos ? rest.size() : e + 1);
          ++c.lines;
          while (!next.empty() && (next.back() == '\r' || next.back() == ' ' || next.back() == '\t')) {
            next.remove_suffix(1);
          }
          if (!next.empty() && next.back() == '\\' && !rest.empty()) {
            joined.append(next.substr(0, next.size() - 1));
            joined.push_back(' ');
            continue;
          }
          joined.append(next);
          break;
        }
        s = joined;
      } else {
        s = ln;
      }
    }
    const std::size_t hash = s.find('#');
    if (hash != std::string_view::npos) s = s.substr(0, hash);
    const std::string_view key = NextToken(s);
    if (key == "v") {
      for (int k = 0; k < 3; ++k) {
        const std::string_view tok = NextToken(s);
        double x;
        if (!ParseDouble(tok, x)) return fail(first_line, "expected a coordinate, got '" + std::string(tok) + "'");
        if (!std::isfinite(x)) return fail(first_line, "non-finite coordinate '" + std::string(tok) + "'");
        c.verts.push_back(x);
      }
    } else if (key == "f") {
      std::int32_t n = 0;
      for (std::string_view tok = NextToken(s); !tok.empty(); tok = NextToken(s)) {
        const std::string_view idx = tok.substr(0, tok.find('/'));
        std::int64_t i = 0;
        const auto res = std::from_chars(idx.data(), idx.data() + idx.size(), i);
        if (res.ec != std::errc() || res.ptr != idx.data() + idx.size() || i == 0) {
          c.indices.resize(c.indices.size() - static_cast<std::size_t>(n));
          return fail(first_line, "bad face index '" + std::string(tok) + "'");
        }
        c.indices.push_back(i);
        ++n;
      }
      if (n < 3) {
        c.indices.resize(c.indices.size() - static_cast<std::size_t>(n));
        return fail(first_line, "a face needs at least 3 corners");
      }
      c.face_sizes.push_back(n);
      c.verts_before.push_back(static_cast<std::int64_t>(c.verts.size() / 3));
      c.face_line.push_back(first_line);
    } else if (key == "o" || key == "g") {
      // The rest of the line is the name (OBJ allows several group names; they name one part).
      std::string name;
      for (std::string_view tok = NextToken(s); !tok.empty(); tok = NextToken(s)) {
        if (!name.empty()) name.push_back(' ');
        name.append(tok);
      }
      c.part_starts.push_back({c.face_sizes.size(), key == "o", std::move(name)});
    }
    // vt, vn, s, usemtl, mtllib, l, ...: not geometry of the solid.
  }
}

// The parts: objects (`o`) when the file names any, else groups (`g`). Faces under the same name
// form one part wherever they are in the file; faces before the first name form the part "".
void AssignParts(const std::vector<Chunk>& chunks, const std::vector<std::int64_t>& face_base, LoadedMesh& out) {
  bool objects = false, groups = false;
  for (const Chunk& c : chunks) {
    for (const auto& p : c.part_starts) (p.object ? objects : groups) = true;
  }
  if (!objects && !groups) return;
  std::vector<std::int32_t>& face_part = out.face_part;
  face_part.assign(static_cast<std::size_t>(face_base.back()), 0);
  std::vector<std::string>& names = out.part_names;
  std::unordered_map<std::string, std::int32_t> index;
  auto part_of = [&](const std::string& name) {
    const auto [it, inserted] = index.emplace(name, static_cast<std::int32_t>(names.size()));
    if (inserted) names.push_back(name);
    return it->second;
  };
  std::int32_t current = -1;  // faces before any name: the part "" (created when it has faces)
  std::size_t f = 0;
  for (std::size_t b = 0; b < chunks.size(); ++b) {
    const Chunk& c = chunks[b];
    std::size_t k = 0;
    auto fill_to = [&](std::size_t end) {  // this chunk's faces before `end`
      for (; k < end; ++k, ++f) {
        if (current < 0) current = part_of("");
        face_part[f] = current;
      }
    };
    for (const auto& p : c.part_starts) {
      if (p.object != objects) continue;  // groups inside objects do not split them
      fill_to(p.faces_before);
      current = part_of(p.name);
    }
    fill_to(c.face_sizes.size());
  }
  // Names that received no faces (an `o` line followed by another) are not parts.
  std::vector<std::int64_t> count(names.size(), 0);
  for (std::int32_t p : face_part) ++count[static_cast<std::size_t>(p)];
  std::vector<std::int32_t> renumber(names.size(), -1);
  std::vector<std::string> kept;
  for (std::size_t p = 0; p < names.size(); ++p) {
    if (count[p] == 0) continue;
    renumber[p] = static_cast<std::int32_t>(kept.size());
    kept.push_back(std::move(names[p]));
  }
  for (std::int32_t& p : face_part) p = renumber[static_cast<std::size_t>(p)];
  names = std::move(kept);
}

}  // namespace

LoadedMesh ParseObj(const std::string& path, std::string_view data, int num_threads) {
  if (data.empty()) Fail(path, "the file is empty");
  // Chunks of about 4 MB (one for small files: no threads started).
  constexpr std::size_t kChunkBytes = std::size_t{4} << 20;
  std::vector<Chunk> chunks;
  for (std::size_t at = 0; at < data.size();) {
    const std::size_t end = at + kChunkBytes >= data.size() ? data.size() : LineBoundary(data, at + kChunkBytes);
    chunks.emplace_back().text = data.substr(at, end - at);
    at = end;
  }
  ParallelForBlocks(static_cast<std::int64_t>(chunks.size()), num_threads,
                    [&](std::int64_t b) { ParseChunk(chunks[static_cast<std::size_t>(b)]); });

  // Resolve the indices: each chunk's vertices follow those of the chunks before it.
  std::vector<std::int64_t> vert_base(chunks.size() + 1, 0), index_base(chunks.size() + 1, 0),
      face_base(chunks.size() + 1, 0);
  std::vector<std::size_t> line_base(chunks.size() + 1, 0);
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    vert_base[k + 1] = vert_base[k] + static_cast<std::int64_t>(chunks[k].verts.size() / 3);
    index_base[k + 1] = index_base[k] + static_cast<std::int64_t>(chunks[k].indices.size());
    face_base[k + 1] = face_base[k] + static_cast<std::int64_t>(chunks[k].face_sizes.size());
    line_base[k + 1] = line_base[k] + chunks[k].lines;
  }
  if (index_base.back() > std::numeric_limits<std::int32_t>::max() ||
      vert_base.back() > std::numeric_limits<std::int32_t>::max()) {
    Fail(path, "more than 2^31 vertices or face corners");
  }
  LoadedMesh out;
  out.format = "obj";
  PolygonMesh& mesh = out.mesh;
  mesh.indices.resize(static_cast<std::size_t>(index_base.back()));
  mesh.offsets.resize(static_cast<std::size_t>(face_base.back()) + 1);
  mesh.offsets[0] = 0;
  std::vector<std::size_t> range_error_line(chunks.size(), 0);
  std::vector<std::string> range_error(chunks.size());
  ParallelForBlocks(static_cast<std::int64_t>(chunks.size()), num_threads, [&](std::int64_t bb) {
    const auto b = static_cast<std::size_t>(bb);
    const Chunk& c = chunks[b];
    std::size_t at = static_cast<std::size_t>(index_base[b]);
    std::size_t f = static_cast<std::size_t>(face_base[b]);
    for (std::size_t i = 0, k = 0; k < c.face_sizes.size(); ++k, ++f) {
      const std::int64_t nv = vert_base[b] + c.verts_before[k];  // vertices so far in the file
      for (std::int32_t j = 0; j < c.face_sizes[k]; ++j, ++i, ++at) {
        const std::int64_t written = c.indices[i];
        const std::int64_t zero_based = written > 0 ? written - 1 : nv + written;  // negative: from the end
        if (zero_based < 0 || zero_based >= nv) {
          range_error_line[b] = c.face_line[k];
          range_error[b] =
              "face index " + std::to_string(written) + " is out of range (" + std::to_string(nv) + " vertices so far)";
          return;
        }
        mesh.indices[at] = static_cast<std::int32_t>(zero_based);
      }
      mesh.offsets[f + 1] = static_cast<std::int64_t>(at);
    }
  });
  // The first fault in file order: chunks are in order, and within a chunk a parse fault ends
  // the chunk, so an index fault before it comes first.
  for (std::size_t b = 0; b < chunks.size(); ++b) {
    const std::size_t line = range_error_line[b] > 0 ? range_error_line[b] : chunks[b].error_line;
    if (line == 0) continue;
    const std::string& what = range_error_line[b] > 0 ? range_error[b] : chunks[b].error;
    Fail(path, "line " + std::to_string(line_base[b] + line) + ": " + what);
  }
  if (vert_base.back() == 0 || face_base.back() == 0) Fail(path, "no faces found in the OBJ file");
  AssignParts(chunks, face_base, out);
  mesh.V.resize(vert_base.back(), 3);
  ParallelForBlocks(static_cast<std::int64_t>(chunks.size()), num_threads, [&](std::int64_t bb) {
    const auto b = static_cast<std::size_t>(bb);
    const std::vector<double>& v = chunks[b].verts;
    std::copy(v.begin(), v.end(), mesh.V.data() + 3 * vert_base[b]);
  });
  return out;
}

}  // namespace massprops
