// Decodes the CAD reader's reply (cad_reply.h): the result's parts, units and meshes, then the
// interference report.

#include "io/cad_reply.h"

#include <cmath>
#include <vector>

#include "io/io_internal.h"
#include "io/text_tokens.h"
#include "io/wire.h"

namespace massprops::internal {
namespace {

// Our unit for the file's, when it is one of ours (else the coordinates stay in millimetres).
std::optional<LengthUnit> UnitOfMillimetres(double mm) {
  for (LengthUnit u : kAllLengthUnits) {
    if (std::abs(MetresPerUnit(u) * 1000 - mm) <= 1e-12 * mm) return u;
  }
  return std::nullopt;
}

std::string PluralUnitWord(LengthUnit u) {
  switch (u) {
    case LengthUnit::kMetre: return "metres";
    case LengthUnit::kCentimetre: return "centimetres";
    case LengthUnit::kMillimetre: return "millimetres";
    case LengthUnit::kInch: return "inches";
    case LengthUnit::kFoot: return "feet";
    case LengthUnit::kMicrometre: return "micrometres";
  }
  return UnitName(u);
}

// A malformed result: the child's bytes, not the file, are at fault.
[[noreturn]] void Malformed(const std::string& path, const std::string& what) {
  Fail(path, "the OpenCASCADE reader process sent a malformed result (" + what + ")");
}

double Finite(wire::Reader& r, const std::string& path, const char* what) {
  const double x = r.F64();
  if (!std::isfinite(x)) Malformed(path, std::string("a non-finite ") + what);
  return x;
}

std::vector<std::string> Strings(wire::Reader& r) {
  const std::uint64_t n = r.U64();
  if (n > r.Left() / 8) throw wire::Truncated();
  std::vector<std::string> out;
  for (std::uint64_t i = 0; i < n; ++i) out.push_back(r.Str());
  return out;
}

// One part's record; its vertices and triangles appended to the whole's.
void ReadPart(wire::Reader& r, const std::string& path, double mm, std::size_t index, LoadedMesh& mesh) {
  mesh.part_names.push_back(r.Str());
  CadPart part;
  part.instance = r.Str();
  part.material = r.Str();
  part.unit = r.Str();
  part.density = r.F64();
  if (!(part.density >= 0 && std::isfinite(part.density))) Malformed(path, "a density that is not a number >= 0");
  part.solid = r.U64() > 0;
  const double volume = Finite(r, path, "volume");
  Vector3 com;
  for (int c = 0; c < 3; ++c) com[c] = Finite(r, path, "center of mass");
  Matrix3 inertia;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) inertia(a, b) = Finite(r, path, "inertia");
  part.brep_error = r.F64();
  part.brep_area = Finite(r, path, "area") / (mm * mm);
  part.deflection = Finite(r, path, "deflection") / mm;
  part.untessellated_faces = static_cast<std::int64_t>(r.U64() & 0x7fffffffffffffff);
  part.unwelded_edges = static_cast<std::int64_t>(r.U64() & 0x7fffffffffffffff);
  part.fixes = Strings(r);
  const std::uint64_t flags = r.U64();
  const double file_volume = r.F64();
  Vector3 file_centroid;
  for (int c = 0; c < 3; ++c) file_centroid[c] = r.F64();
  const double file_area = r.F64();
  const auto ok = [](double x) { return std::isfinite(x); };
  if ((flags & 1) && ok(file_volume)) part.file.volume = file_volume / (mm * mm * mm);
  if ((flags & 2) && file_centroid.allFinite()) part.file.centroid = file_centroid / mm;
  if ((flags & 4) && ok(file_area)) part.file.area = file_area / (mm * mm);
  // Unit density, file unit: ∫r rᵀ = C + V c cᵀ with the covariance C = tr(I)/2 𝟙 − I.
  const double mm3 = mm * mm * mm;
  part.brep.volume = volume / mm3;
  com /= mm;
  inertia /= mm3 * mm * mm;
  const Matrix3 covariance = 0.5 * inertia.trace() * Matrix3::Identity() - inertia;
  part.brep.first = part.brep.volume * com;
  part.brep.second = covariance + part.brep.volume * com * com.transpose();
  mesh.cad_parts.push_back(part);
  // The check mesh, indexed.
  const std::uint64_t vertices = r.U64();
  if (vertices > r.Left() / 24 || vertices > 0x7fffffff) throw wire::Truncated();
  std::vector<double> xyz;
  r.F64s(3 * vertices, xyz);
  const std::uint64_t triangles = r.U64();
  if (triangles > r.Left() / 12) throw wire::Truncated();
  std::vector<std::int32_t> tris;
  r.I32s(3 * triangles, tris);
  PolygonMesh& m = mesh.mesh;
  const auto base = static_cast<std::int32_t>(m.V.rows());
  if (static_cast<std::uint64_t>(base) + vertices > 0x7fffffff) Malformed(path, "too many vertices");
  m.V.conservativeResize(base + static_cast<Eigen::Index>(vertices), 3);
  for (std::uint64_t v = 0; v < vertices; ++v) {
    for (int c = 0; c < 3; ++c) {
      const double x = xyz[3 * v + static_cast<std::size_t>(c)];
      if (!std::isfinite(x)) Malformed(path, "a non-finite coordinate");
      m.V(base + static_cast<Eigen::Index>(v), c) = x / mm;
    }
  }
  for (std::uint64_t t = 0; t < triangles; ++t) {
    for (int c = 0; c < 3; ++c) {
      const std::int32_t i = tris[3 * t + static_cast<std::size_t>(c)];
      if (i < 0 || static_cast<std::uint64_t>(i) >= vertices) Malformed(path, "a triangle corner out of range");
      m.indices.push_back(base + i);
    }
    m.offsets.push_back(static_cast<std::int64_t>(m.indices.size()));
    mesh.face_part.push_back(static_cast<std::int32_t>(index));
  }
}

LoadedMesh ReadResult(const std::string& path, bool brep_format, const std::string& body, double& mm) {
  wire::Reader r(body);
  LoadedMesh mesh;
  mesh.mesh.V.resize(0, 3);
  const std::string format_word = r.Str();
  const std::string unit_word = r.Str();
  const double mm_per_unit = r.F64();
  const auto unit = std::isfinite(mm_per_unit) && mm_per_unit > 0 ? UnitOfMillimetres(mm_per_unit) : std::nullopt;
  // The readers hand out millimetres (OpenCASCADE's session unit); back to the file's unit, by
  // division (correctly rounded: an inch file's 1 in comes back as exactly 1).
  mm = !brep_format && unit ? mm_per_unit : 1.0;
  if (!brep_format) {
    if (unit) {
      mesh.declared_unit = unit;
      mesh.declared_unit_name = PluralUnitWord(*unit) + " (the " + format_word + " file's unit, '" + unit_word + "')";
    } else {
      mesh.declared_unit = LengthUnit::kMillimetre;
      mesh.declared_unit_name = "millimetres (OpenCASCADE's conversion of the " + format_word + " file's unit" +
                                (unit_word.empty() ? "" : " '" + unit_word + "'") + ")";
    }
  }
  mesh.format = io_text::Lower(format_word);
  mesh.cad_notes = Strings(r);
  const std::uint64_t parts = r.U64();
  if (parts == 0) Malformed(path, "no parts");
  if (parts > r.Left() / 8) throw wire::Truncated();
  for (std::uint64_t i = 0; i < parts; ++i) ReadPart(r, path, mm, static_cast<std::size_t>(i), mesh);
  return mesh;
}

void ReadInterference(const std::string& body, double mm, CadInterference& out, std::size_t parts) {
  wire::Reader r(body);
  out.candidates = r.U64();
  out.measured = r.U64();
  const std::uint64_t n = r.U64();
  if (n > r.Left() / 24) throw wire::Truncated();
  for (std::uint64_t i = 0; i < n; ++i) {
    CadOverlap o;
    const std::uint64_t a = r.U64(), b = r.U64();
    const double v = r.F64();
    if (a >= parts || b >= parts || !std::isfinite(v)) throw wire::Truncated();
    o.a = static_cast<std::size_t>(a);
    o.b = static_cast<std::size_t>(b);
    o.volume = v < 0 ? -1.0 : v / (mm * mm * mm);
    out.overlaps.push_back(o);
  }
  out.done = true;
}

}  // namespace

std::optional<LoadedMesh> DecodeCadReply(const std::string& path, bool brep_format, std::string_view bytes,
                                         const std::string& stopped) {
  std::vector<std::string> pieces;
  std::optional<std::uint64_t> status;
  try {
    wire::Reader frames(bytes);
    while (frames.Left() > 0 && !status) {
      const std::uint64_t tag = frames.U64();
      if (tag == 0) {
        pieces.push_back(frames.Str());
      } else if (tag == 1) {
        status = frames.U64();
      } else {
        break;  // not a frame: what follows cannot be trusted
      }
    }
  } catch (const wire::Truncated&) {
    // The child died mid-frame: the whole frames before it stand.
  }
  if (status && *status != 0 && pieces.size() <= 1) {
    std::string reason = "the CAD plugin failed";
    try {
      if (!pieces.empty()) reason = wire::Reader(pieces.front()).Str();
    } catch (const wire::Truncated&) {
    }
    Fail(path, reason);
  }
  if (pieces.empty()) return std::nullopt;
  LoadedMesh mesh;
  double mm = 1.0;
  try {
    mesh = ReadResult(path, brep_format, pieces.front(), mm);
  } catch (const wire::Truncated&) {
    if (!status) return std::nullopt;  // cut short by the child's end: the caller says how it ended
    Malformed(path, "truncated");
  }
  CadInterference& interference = mesh.cad_interference;
  if (pieces.size() >= 2 && status && *status == 0) {
    try {
      ReadInterference(pieces[1], mm, interference, mesh.cad_parts.size());
    } catch (const wire::Truncated&) {
      interference = {};
      interference.not_done = "its report was malformed";
    }
  } else {
    interference.not_done = stopped.empty() ? "the reader process ended before it" : stopped;
  }
  return mesh;
}

}  // namespace massprops::internal
