// libFuzzer target for every hand-written parser: the same bytes go through the STL (binary and
// ASCII), OBJ, PLY, OFF and 3MF readers (3MF both as the bytes and as a package holding them), the binary-STL record
// path, the shape syntax, and — when they parse — the topology checks and the integrators (or a small Monte-Carlo run).
// Any crash, sanitizer report or hang is a bug; a MeshFileError or std::invalid_argument is the expected answer to bad
// input.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "../zip_bytes.h"
#include "massprops/implicit.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/monte_carlo.h"
#include "massprops/triangle_soup.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The bytes also as the model part of a 3MF package, so that the fuzzer reaches the 3MF reader's
  // XML, not only its zip directory.
  const std::string package = massprops::testing::StoredZip({{"3D/3dmodel.model", std::string(bytes)}});
  for (const char* ext : {"stl", "obj", "ply", "off", "3mf", "3mf-package"}) {
    try {
      const bool wrap = std::string_view(ext) == "3mf-package";
      const massprops::LoadedMesh m =
          massprops::ParseMeshBuffer("fuzz", wrap ? "3mf" : ext, wrap ? std::string_view(package) : bytes);
      const massprops::MeshTopology t = massprops::AnalyzeTopology(m.mesh);
      if (m.mesh.num_faces() <= 2000) {
        if (t.components > 1) massprops::AnalyzeShells(m.mesh);
        try {
          massprops::IntegrationOptions one_thread;
          one_thread.num_threads = 1;
          massprops::ComputeMassProperties(m.mesh, 1.0, one_thread);
          massprops::ComputeMassProperties(massprops::Triangulate(m.mesh), 1.0, one_thread);
        } catch (const std::invalid_argument&) {
        }
      }
    } catch (const massprops::MeshFileError&) {
    }
  }
  // The shape syntax of --implicit: parse, and when it parses, sample a little.
  try {
    const massprops::ImplicitPtr shape = massprops::implicit::ParseShape(std::string(bytes));
    massprops::MonteCarloOptions mc;
    mc.samples = 256;
    mc.randomizations = 2;
    mc.num_threads = 1;
    massprops::EstimateMassProperties(*shape, 1.0, mc);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  }
  if (size >= 62) {
    try {
      massprops::IntegrationOptions one_thread;
      one_thread.num_threads = 1;
      massprops::IntegrateFloatTriangleRecords(data, static_cast<std::int64_t>(size / 50), 50, 12, one_thread);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
