// Monte-Carlo path throughput and accuracy per second (Google Benchmark).
//
//   build/bench/monte_carlo_bench
//
// BM_Points/<solid>/<threads>: items_per_second = points per second (wall clock) for a sphere, a
// CSG shape (box minus sphere, unioned with a cylinder) and a 10^5-triangle torus mesh through
// the winding number. BM_ErrorPerSecond/<method>: RMS relative volume error of a sphere over 16
// seeds at 2^20 points, with its time, so that error reached per second of MC and QMC compare.

#include <benchmark/benchmark.h>

#include <cmath>

#include "massprops/implicit.h"
#include "massprops/monte_carlo.h"
#include "massprops/solids.h"

namespace {

using namespace massprops;

ImplicitPtr Solid(int which) {
  static const ImplicitPtr sphere = implicit::Sphere(1.0);
  static const ImplicitPtr csg =
      implicit::ParseShape("union(difference(box(x=2, y=2, z=2), sphere(r=0.9)), move(cylinder(r=0.3, h=3), x=0.5))");
  static const ImplicitPtr mesh =
      implicit::WindingNumberSolid(solids::Torus(1.0, 0.3, 158));  // 4·158² ≈ 10^5 triangles
  return which == 0 ? sphere : which == 1 ? csg : mesh;
}

void BM_Points(benchmark::State& state) {
  const ImplicitPtr solid = Solid(static_cast<int>(state.range(0)));
  MonteCarloOptions o;
  o.samples = state.range(0) == 2 ? (1 << 17) : (1 << 22);
  o.num_threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(EstimateMassProperties(*solid, 1.0, o));
  state.SetItemsProcessed(state.iterations() * o.samples);
  state.SetLabel(state.range(0) == 0 ? "sphere" : state.range(0) == 1 ? "csg" : "mesh 1e5 tri (winding number)");
}
BENCHMARK(BM_Points)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ErrorPerSecond(benchmark::State& state) {
  const ImplicitPtr sphere = Solid(0);
  const double truth = 4 * massprops::kPi / 3;
  double ss = 0;
  int runs = 0;
  for (auto _ : state) {
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
      MonteCarloOptions o;
      o.method = state.range(0) == 0 ? SamplingMethod::kMonteCarlo : SamplingMethod::kQuasiMonteCarlo;
      o.samples = 1 << 20;
      o.seed = seed;
      o.num_threads = 1;
      const double v = EstimateMassProperties(*sphere, 1.0, o).value.volume;
      ss += (v / truth - 1) * (v / truth - 1);
      ++runs;
    }
  }
  state.counters["rms_rel_error"] = std::sqrt(ss / runs);
  state.SetItemsProcessed(state.iterations() * 16 * (1 << 20));
  state.SetLabel(state.range(0) == 0 ? "MC" : "QMC (16 randomizations)");
}
BENCHMARK(BM_ErrorPerSecond)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
