// The checked path, stage by stage, on a binary STL of a torus (2·10^6 triangles by default;
// MASSPROPS_BENCH_TRIANGLES overrides): reading and welding, the edge analysis, integration, and the
// whole pipeline with --full-check. Read it beside `cat` of the same file (bench/end_to_end.py
// measures that ratio); the stages say where the rest of the time goes.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "massprops/io.h"
#include "massprops/load.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"

namespace {

// Writes the torus once per process into the temporary folder (removed at exit).
const std::string& TorusFile() {
  static const std::string path = [] {
    const char* env = std::getenv("MASSPROPS_BENCH_TRIANGLES");
    const long long target = env ? std::atoll(env) : 2000000;
    int n = 3;
    while (4LL * n * n < target) ++n;
    const massprops::TriangleMesh m = massprops::solids::Torus(2.0, 0.5, n);
    const std::string p =
        (std::filesystem::temp_directory_path() / ("checked_path_bench_" + std::to_string(::getpid()) + ".stl"))
            .string();
    std::ofstream out(p, std::ios::binary);
    std::string header(80, ' ');
    out.write(header.data(), 80);
    const auto count = static_cast<std::uint32_t>(m.F.rows());
    out.write(reinterpret_cast<const char*>(&count), 4);
    char rec[50] = {};
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      float c[12] = {};
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 3; ++j) c[3 + 3 * k + j] = static_cast<float>(m.V(m.F(f, k), j));
      }
      std::memcpy(rec, c, 48);
      out.write(rec, 50);
    }
    std::atexit([] { std::filesystem::remove(TorusFile()); });
    return p;
  }();
  return path;
}

void BM_ReadAndWeld(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(massprops::ReadMeshFile(TorusFile()));
}

void BM_EdgeAnalysis(benchmark::State& state) {
  const massprops::LoadedMesh m = massprops::ReadMeshFile(TorusFile());
  for (auto _ : state) benchmark::DoNotOptimize(massprops::AnalyzeTopology(m.mesh));
}

void BM_Integrate(benchmark::State& state) {
  const massprops::LoadedMesh m = massprops::ReadMeshFile(TorusFile());
  for (auto _ : state) benchmark::DoNotOptimize(massprops::IntegratePolygons(m.mesh));
}

void BM_LoadSolidFullCheck(benchmark::State& state) {
  massprops::LoadOptions o;
  o.full_check = true;
  o.unit_stated = true;
  for (auto _ : state) benchmark::DoNotOptimize(massprops::LoadSolid(TorusFile(), o));
}

}  // namespace

BENCHMARK(BM_ReadAndWeld)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EdgeAnalysis)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Integrate)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadSolidFullCheck)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
