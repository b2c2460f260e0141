// Loads the CAD plugin (libmassprops_cad.so, OpenCASCADE) on first use and reads STEP, IGES and
// BREP files through it in a child process with a time limit: OpenCASCADE can loop or crash on a
// malformed file, and neither may take the program (or its other files) down.

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "cad_plugin.h"
#include "io_internal.h"
#include "plugins.h"
#include "text_tokens.h"
#include "wire.h"

namespace massprops {
namespace {

struct Plugin {
  MasspropsCadReadFn read = nullptr;
  MasspropsCadFreeFn free = nullptr;
  std::string error;  // why it could not be loaded
};

const Plugin& LoadPlugin() {
  static Plugin plugin;
  static std::once_flag once;
  std::call_once(once, [] {
#ifndef MASSPROPS_WITH_CAD
    plugin.error =
        "this build of massprops was configured without OpenCASCADE (MASSPROPS_WITH_CAD=OFF, or its packages "
        "libocct-data-exchange-dev, libocct-modeling-algorithms-dev and libocct-ocaf-dev were missing), so STEP, "
        "IGES and BREP files cannot be read; export the part as STL or OBJ, or rebuild with OpenCASCADE";
    return;
#endif
    const std::string name = "libmassprops_cad.so";
    std::string tried;
    void* handle = plugins::Open(plugins::ModuleCandidates(name, "MASSPROPS_CAD_PLUGIN"), tried);
    if (handle == nullptr) {
      plugin.error = "the CAD plugin (" + name + ", OpenCASCADE) was not found (" + tried +
                     "; set MASSPROPS_CAD_PLUGIN to its path)";
      return;
    }
    plugin.read = reinterpret_cast<MasspropsCadReadFn>(::dlsym(handle, "massprops_cad_read"));
    plugin.free = reinterpret_cast<MasspropsCadFreeFn>(::dlsym(handle, "massprops_cad_free"));
    if (!plugin.read || !plugin.free) {
      plugin.error = "the CAD plugin lacks its entry points (a mismatched build?)";
      plugin.read = nullptr;
    }
  });
  return plugin;
}

std::string Extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  return io_text::Lower(path.substr(dot + 1));
}

int FormatOf(const std::string& ext) {
  if (ext == "step" || ext == "stp") return kMasspropsCadStep;
  if (ext == "iges" || ext == "igs") return kMasspropsCadIges;
  if (ext == "brep" || ext == "brp") return kMasspropsCadBrep;
  return -1;
}

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

}  // namespace

bool IsCadFile(const std::string& path) { return FormatOf(Extension(path)) >= 0; }

LoadedMesh ReadCadFile(const std::string& path, const CadOptions& cad) {
  const int format = FormatOf(Extension(path));
  const Plugin& p = LoadPlugin();
  if (p.read == nullptr) Fail(path, p.error);
  if (!(cad.deflection >= 0 && std::isfinite(cad.deflection)) ||
      !(cad.relative_deflection >= 1e-6 && cad.relative_deflection <= 0.5) ||
      !(cad.angular_deflection > 0 && cad.angular_deflection <= 3.2)) {
    throw std::invalid_argument(
        "the tessellation needs a finite deflection >= 0 (0: relative), a relative "
        "deflection in [1e-6, 0.5] and an angular deflection in (0, pi] rad");
  }
  OpenRegularFile(path);  // a clear message for a missing file, a folder or a FIFO, before any child
  MasspropsCadOptions options{};
  options.abi = MASSPROPS_CAD_ABI;
  options.format = format;
  options.deflection = cad.deflection;
  options.relative_deflection = cad.relative_deflection;
  options.angular_deflection = cad.angular_deflection;
  options.brep_tolerance = 1e-12;
  // The child's work: the plugin's status and bytes, as they are.
  const auto read_in_child = [&] {
    // Parts of OpenCASCADE print to standard output directly (BRepTools::Read's complaints): in
    // this child, standard output is not the program's, so it goes nowhere.
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    char* out = nullptr;
    std::size_t size = 0;
    const std::uint64_t status = p.read(path.c_str(), &options, &out, &size);
    wire::Writer w;
    w.U64(status);
    w.Str(std::string_view(out == nullptr ? "" : out, size));
    p.free(out);
    return std::move(w.bytes());
  };
  // STEP parsing, tessellation and integration: 30 s plus 5 s per MB.
  const double limit = plugins::TimeLimitSeconds(path, "MASSPROPS_CAD_TIMEOUT", 30.0, 5.0);
  const std::string data =
      plugins::ReadIsolated(path, "OpenCASCADE", limit, "MASSPROPS_CAD_TIMEOUT", "MASSPROPS_CAD_FAULT", read_in_child);
  LoadedMesh mesh;
  std::vector<double> xyz;
  try {
    wire::Reader outer(data);
    const std::uint64_t status = outer.U64();
    const std::string body = outer.Str();
    wire::Reader r(body);
    if (status != 0) Fail(path, body.empty() ? "the CAD plugin failed" : r.Str());
    const std::string format_word = r.Str();
    const std::string unit_word = r.Str();
    const double mm_per_unit = r.F64();
    const auto unit = UnitOfMillimetres(mm_per_unit);
    // The readers hand out millimetres (OpenCASCADE's session unit); back to the file's unit, by
    // division (correctly rounded: an inch file's 1 in comes back as exactly 1).
    const double mm = format != kMasspropsCadBrep && unit ? mm_per_unit : 1.0;
    if (format != kMasspropsCadBrep) {
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
    const std::uint64_t parts = r.U64();
    if (parts > r.Left()) throw wire::Truncated();
    std::vector<int> sizes;
    for (std::uint64_t i = 0; i < parts; ++i) {
      mesh.part_names.push_back(r.Str());
      CadPart part;
      part.material = r.Str();
      part.density = r.F64();
      part.solid = r.U64() != 0;
      const double volume = r.F64();
      Vector3 com;
      for (int c = 0; c < 3; ++c) com[c] = r.F64();
      Matrix3 inertia;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) inertia(a, b) = r.F64();
      part.brep_error = r.F64();
      part.deflection = r.F64() / mm;
      part.untessellated_faces = static_cast<std::int64_t>(r.U64());
      // Unit density, file unit: ∫r rᵀ = C + V c cᵀ with the covariance C = tr(I)/2 𝟙 − I.
      const double mm3 = mm * mm * mm;
      part.brep.volume = volume / mm3;
      com /= mm;
      inertia /= mm3 * mm * mm;
      const Matrix3 covariance = 0.5 * inertia.trace() * Matrix3::Identity() - inertia;
      part.brep.first = part.brep.volume * com;
      part.brep.second = covariance + part.brep.volume * com * com.transpose();
      mesh.cad_parts.push_back(part);
      const std::uint64_t triangles = r.U64();
      if (triangles > r.Left() / 72) throw wire::Truncated();
      const std::size_t at = xyz.size();
      r.F64s(9 * triangles, xyz);
      if (mm != 1.0) {
        for (std::size_t j = at; j < xyz.size(); ++j) xyz[j] /= mm;
      }
      sizes.insert(sizes.end(), triangles, 3);
      mesh.face_part.insert(mesh.face_part.end(), triangles, static_cast<std::int32_t>(i));
    }
    if (sizes.empty()) {
      Fail(path,
           "OpenCASCADE made no triangles of it (no faces: the file holds no solid or surface, only curves or "
           "points)");
    }
    LoadedMesh welded = WeldCorners(path, xyz, sizes, mesh.format.c_str());
    mesh.mesh = std::move(welded.mesh);
    mesh.welded = welded.welded;
  } catch (const wire::Truncated&) {
    Fail(path, "the OpenCASCADE reader process sent a truncated result");
  }
  // A file of one unnamed part names none (the pipeline names it after the file).
  if (mesh.part_names.size() == 1 && mesh.part_names[0].empty()) {
    mesh.part_names.clear();
    mesh.face_part.clear();
  }
  return mesh;
}

}  // namespace massprops
