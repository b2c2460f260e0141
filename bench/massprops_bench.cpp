// Throughput of the integration paths on generated meshes (Google Benchmark).
//
//   build/bench/massprops_bench                       # everything
//   build/bench/massprops_bench --benchmark_filter=Triangle
//
// items_per_second = triangles (or polygons) per second, wall-clock (the library runs its own
// threads, so real time is the honest measure). Meshes are tori generated at run time; the
// 10^7-triangle one takes ~240 MB.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "massprops/io/load.h"
#include "massprops/mass_properties.h"
#include "massprops/mesh_topology.h"
#include "massprops/solids.h"
#include "massprops/triangle_soup.h"

namespace {

using massprops::IntegrationOptions;
using massprops::TriangleMesh;

// Torus with 2n × n quads = 4n² triangles; n chosen for ~target triangles.
const TriangleMesh& TorusMesh(std::int64_t target) {
  static std::map<std::int64_t, TriangleMesh> cache;
  auto it = cache.find(target);
  if (it == cache.end()) {
    int n = 1;
    while (4LL * n * n < target) ++n;
    it = cache.emplace(target, massprops::solids::Torus(2.0, 0.5, n)).first;
  }
  return it->second;
}

void BM_TrianglePath(benchmark::State& state) {
  const TriangleMesh& mesh = TorusMesh(state.range(0));
  IntegrationOptions opt;
  opt.num_threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    benchmark::DoNotOptimize(massprops::ComputeMassProperties(mesh, 1000.0, opt));
  }
  state.SetItemsProcessed(state.iterations() * mesh.F.rows());
  state.counters["triangles"] = static_cast<double>(mesh.F.rows());
}
BENCHMARK(BM_TrianglePath)
    ->ArgNames({"tris", "threads"})
    ->Args({10000, 1})
    ->Args({1000000, 1})
    ->Args({1000000, 2})
    ->Args({10000000, 1})
    ->Args({10000000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The edge analysis every checked path runs (boundary, non-manifold and inconsistent edges,
// components, holes): triangles per second.
void BM_AnalyzeTopology(benchmark::State& state) {
  const massprops::PolygonMesh mesh = massprops::ToPolygonMesh(TorusMesh(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(massprops::AnalyzeTopology(mesh));
  state.SetItemsProcessed(state.iterations() * mesh.num_faces());
}
BENCHMARK(BM_AnalyzeTopology)->ArgName("tris")->Arg(10000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

// What Python's mass_properties runs on its arrays, one thread: the weld, the edge analysis, the
// shells and the integrals with their result. Beside BM_TrianglePath/BM_AnalyzeTopology of the
// same torus, the checks' share of a call.
void BM_SolveMesh(benchmark::State& state) {
  const massprops::PolygonMesh mesh = massprops::ToPolygonMesh(TorusMesh(state.range(0)));
  massprops::LoadOptions options;
  options.num_threads = 1;
  options.unit_stated = true;
  for (auto _ : state) {
    massprops::LoadedMesh loaded;
    loaded.format = "arrays";
    loaded.mesh = mesh;
    benchmark::DoNotOptimize(massprops::SolveMesh(std::move(loaded), "torus", options));
  }
  state.SetItemsProcessed(state.iterations() * mesh.num_faces());
}
BENCHMARK(BM_SolveMesh)->ArgName("tris")->Arg(10000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

void BM_PolygonPath(benchmark::State& state) {
  static std::map<std::int64_t, massprops::PolygonMesh> cache;
  auto it = cache.find(state.range(0));
  if (it == cache.end()) {
    it = cache.emplace(state.range(0), massprops::ToPolygonMesh(TorusMesh(state.range(0)))).first;
  }
  IntegrationOptions opt;
  opt.num_threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    benchmark::DoNotOptimize(massprops::ComputeMassProperties(it->second, 1000.0, opt));
  }
  state.SetItemsProcessed(state.iterations() * it->second.num_faces());
}
BENCHMARK(BM_PolygonPath)
    ->ArgNames({"tris", "threads"})
    ->Args({1000000, 1})
    ->Args({1000000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Baseline: the simplest single-thread loop over a binary-STL-like buffer (50-byte records of
// float32), accumulating only the signed volume. What "integrating while reading the file" costs
// at the least; the full paths above compute ten moments and the area in double precision.
void BM_BaselineStlVolumeLoop(benchmark::State& state) {
  const TriangleMesh& mesh = TorusMesh(state.range(0));
  std::vector<char> buffer(static_cast<std::size_t>(mesh.F.rows()) * 50);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) rec[3 + 3 * k + j] = static_cast<float>(mesh.V(mesh.F(f, k), j));
    }
    std::memcpy(buffer.data() + 50 * f, rec, sizeof rec);
  }
  for (auto _ : state) {
    double six_v = 0;
    for (std::size_t f = 0; f < static_cast<std::size_t>(mesh.F.rows()); ++f) {
      float t[9];
      std::memcpy(t, buffer.data() + 50 * f + 12, sizeof t);
      six_v += double(t[0]) * (double(t[4]) * t[8] - double(t[5]) * t[7]) +
               double(t[1]) * (double(t[5]) * t[6] - double(t[3]) * t[8]) +
               double(t[2]) * (double(t[3]) * t[7] - double(t[4]) * t[6]);
    }
    benchmark::DoNotOptimize(six_v);
  }
  state.SetItemsProcessed(state.iterations() * mesh.F.rows());
}
BENCHMARK(BM_BaselineStlVolumeLoop)
    ->ArgName("tris")
    ->Arg(1000000)
    ->Arg(10000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The binary-STL path on records in memory (50-byte records, float32), with the streaming
// closed-surface check: what `massprops FILE.stl` does after mapping the file.
void BM_TriangleSoupPath(benchmark::State& state) {
  const TriangleMesh& mesh = TorusMesh(state.range(0));
  std::vector<unsigned char> buffer(static_cast<std::size_t>(mesh.F.rows()) * 50);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) rec[3 + 3 * k + j] = static_cast<float>(mesh.V(mesh.F(f, k), j));
    }
    std::memcpy(buffer.data() + 50 * f, rec, sizeof rec);
  }
  IntegrationOptions opt;
  opt.num_threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    benchmark::DoNotOptimize(massprops::IntegrateFloatTriangleRecords(buffer.data(), mesh.F.rows(), 50, 12, opt));
  }
  state.SetItemsProcessed(state.iterations() * mesh.F.rows());
}
BENCHMARK(BM_TriangleSoupPath)
    ->ArgNames({"tris", "threads"})
    ->Args({1000000, 1})
    ->Args({1000000, 2})
    ->Args({10000000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
