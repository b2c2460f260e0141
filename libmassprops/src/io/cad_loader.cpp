// Loads the CAD plugin (libmassprops_cad.so, OpenCASCADE) on first use and reads STEP, IGES and
// BREP files through it in a child process with a time limit: OpenCASCADE can loop or crash on a
// malformed file, and neither may take the program (or its other files) down.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/cad/plugin_abi.h"
#include "io/cad_reply.h"
#include "io/io_internal.h"
#include "io/plugins.h"
#include "io/text_tokens.h"
#include "io/wire.h"

namespace massprops {
namespace {

struct Plugin {
  MasspropsCadReadFn read = nullptr;
  std::string error;  // why it could not be loaded
};

const Plugin& LoadPlugin() {
  static const Plugin plugin = [] {
    Plugin p;
#ifndef MASSPROPS_WITH_CAD
    p.error =
        "this build of massprops was configured without OpenCASCADE (MASSPROPS_WITH_CAD=OFF, or its packages "
        "libocct-data-exchange-dev, libocct-modeling-algorithms-dev and libocct-ocaf-dev were missing), so STEP, "
        "IGES and BREP files cannot be read; export the part as STL or OBJ, or rebuild with OpenCASCADE";
    return p;
#endif
    const plugins::Module m =
        plugins::LoadModule({"the CAD plugin (libmassprops_cad.so, OpenCASCADE)",
                             plugins::ModuleCandidates("libmassprops_cad.so", "MASSPROPS_CAD_PLUGIN"),
                             "set MASSPROPS_CAD_PLUGIN to its path",
                             {"massprops_cad_read"}});
    p.error = m.error;
    if (m.loaded()) p.read = reinterpret_cast<MasspropsCadReadFn>(m.entries[0]);
    return p;
  }();
  return plugin;
}

int FormatOf(const std::string& ext) {
  if (ext == "step" || ext == "stp") return kMasspropsCadStep;
  if (ext == "iges" || ext == "igs") return kMasspropsCadIges;
  if (ext == "brep" || ext == "brp") return kMasspropsCadBrep;
  return -1;
}

// The child's side: each message of the plugin framed (tag 0), then its status (tag 1).
struct ChildSend {
  const IsolatedSend* send;
};

void SendFramed(void* context, const char* bytes, std::size_t size) {
  auto* child = static_cast<ChildSend*>(context);
  wire::Writer w;
  w.U64(0);
  w.Str(std::string_view(bytes, size));
  (*child->send)(w.bytes());
}

}  // namespace

bool IsCadFile(const std::string& path) { return FormatOf(io_text::FileExtension(path)) >= 0; }

LoadedMesh ReadCadFile(const std::string& path, const CadOptions& cad) {
  const int format = FormatOf(io_text::FileExtension(path));
  const Plugin& p = LoadPlugin();
  if (p.read == nullptr) Fail(path, p.error);
  if (!(cad.deflection >= 0 && std::isfinite(cad.deflection)) ||
      !(cad.relative_deflection == 0 || (cad.relative_deflection >= 1e-6 && cad.relative_deflection <= 0.5)) ||
      !(cad.angular_deflection > 0 && cad.angular_deflection <= 3.2)) {
    throw std::invalid_argument(
        "the tessellation needs a finite deflection >= 0 (0: relative), a relative "
        "deflection in [1e-6, 0.5] (0: the default) and an angular deflection in (0, pi] rad");
  }
  OpenRegularFile(path);  // a clear message for a missing file, a folder or a FIFO, before any child
  MasspropsCadOptions options{};
  options.abi = MASSPROPS_CAD_ABI;
  options.format = format;
  options.deflection = cad.deflection;
  options.relative_deflection = cad.relative_deflection > 0 ? cad.relative_deflection : 1e-4;
  options.angular_deflection = cad.angular_deflection;
  options.brep_tolerance = 1e-12;
  options.interference_pairs = cad.interference_pairs;
  options.threads = std::max(0, cad.num_threads);
  // The child's work: the plugin's messages as they come, then its status.
  const auto read_in_child = [&](const IsolatedSend& send) {
    // Parts of OpenCASCADE print to standard output directly (BRepTools::Read's complaints): in
    // this child, standard output is not the program's, so it goes nowhere.
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    ChildSend child{&send};
    const std::uint64_t status = p.read(path.c_str(), &options, SendFramed, &child);
    wire::Writer w;
    w.U64(1);
    w.U64(status);
    send(w.bytes());
  };
  // STEP parsing, solids, tessellation and integration: 30 s plus 5 s per MB; the interference
  // test after the result gets as long again.
  const double limit = plugins::TimeLimitSeconds(path, "MASSPROPS_CAD_TIMEOUT", 30.0, 5.0);
  const IsolatedOutcome outcome = plugins::ReadIsolatedPieces(path, "OpenCASCADE", limit, read_in_child);
  std::string stopped;
  if (outcome.end == IsolatedEnd::kTimedOut) {
    stopped = "stopped after " + std::to_string(static_cast<long long>(limit)) + " s (MASSPROPS_CAD_TIMEOUT)";
  } else if (outcome.end == IsolatedEnd::kCrashed) {
    stopped = "OpenCASCADE crashed during it (signal " + std::to_string(outcome.signal) + ")";
  } else if (outcome.end != IsolatedEnd::kFinished) {
    stopped = "the reader process failed during it";
  }
  std::optional<LoadedMesh> mesh = internal::DecodeCadReply(path, format == kMasspropsCadBrep, outcome.output, stopped);
  if (!mesh) {
    if (outcome.end != IsolatedEnd::kFinished)
      plugins::FailOutcome(path, "OpenCASCADE", outcome, limit, "MASSPROPS_CAD_TIMEOUT");
    Fail(path, "the OpenCASCADE reader process sent no result");
  }
  // Bit-identical corners that the B-rep's topology did not join (faces that share no edge).
  mesh->welded = MergeCoincidentVertices(mesh->mesh, cad.num_threads);
  // A file of one unnamed part names none (the pipeline names it after the file).
  if (mesh->part_names.size() == 1 && mesh->part_names[0].empty()) {
    mesh->part_names.clear();
    mesh->face_part.clear();
  }
  return std::move(*mesh);
}

}  // namespace massprops
