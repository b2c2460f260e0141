// Large polygons: a prism over a regular n-gon (two caps of n corners and n side quads) through
// the options that split polygons into triangles — the repair, the self-intersection check, the
// wall's inner-surface check, the winding-number inside test. A fan from one corner made every one
// of them quadratic (slivers whose bounding boxes all overlap); the balanced split keeps them
// near-linear. Time per corner of the cap is what to read: it should stay flat as n grows, and
// the baseline (Mirtich on the polygons as they are) shows the linear cost of touching the mesh.

#include <benchmark/benchmark.h>

#include <cmath>

#include "massprops/implicit.h"
#include "massprops/mass_properties.h"
#include "massprops/repair/repair.h"
#include "massprops/shell.h"
#include "massprops/solids.h"

namespace {

massprops::PolygonMesh Prism(benchmark::State& state) {
  return massprops::solids::RegularPrism(static_cast<int>(state.range(0)), 1.0, 0.1);
}

void Finish(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * state.range(0));  // corners of one cap
}

void BM_Baseline_Mirtich(benchmark::State& state) {
  const auto mesh = Prism(state);
  for (auto _ : state) benchmark::DoNotOptimize(massprops::IntegratePolygons(mesh));
  Finish(state);
}

void BM_Repair(benchmark::State& state) {
  const auto mesh = Prism(state);
  for (auto _ : state) benchmark::DoNotOptimize(massprops::RepairMesh(mesh));
  Finish(state);
}

void BM_SelfIntersections(benchmark::State& state) {
  const auto mesh = Prism(state);
  for (auto _ : state) benchmark::DoNotOptimize(massprops::CountSelfIntersections(mesh));
  Finish(state);
}

void BM_WallInnerSurfaceCheck(benchmark::State& state) {
  const auto mesh = Prism(state);
  for (auto _ : state) {
    const massprops::OffsetResult inner = massprops::OffsetInward(mesh, 0.01);
    benchmark::DoNotOptimize(massprops::CountSelfIntersections(inner.inner, 1));
  }
  Finish(state);
}

// The inside test --winding-number samples: the solid built, then 10^4 points across its box
// (a closed mesh counts ray crossings; the side faces are slivers that kept every cluster of the
// dipole hierarchy near the points beside them).
void BM_WindingNumberInsideTest(benchmark::State& state) {
  const auto mesh = massprops::Triangulate(Prism(state));
  for (auto _ : state) {
    const auto solid = massprops::implicit::WindingNumberSolid(mesh);
    int inside = 0;
    for (int i = 0; i < 10000; ++i) {
      const double t = 0.001 * i;
      inside += solid->Inside(massprops::Vector3(std::cos(t) * 0.01 * (i % 100), std::sin(t) * 0.01 * (i % 100),
                                                 0.0009 * (i % 101) - 0.045));
    }
    benchmark::DoNotOptimize(inside);
  }
  Finish(state);
}

}  // namespace

BENCHMARK(BM_Baseline_Mirtich)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repair)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SelfIntersections)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WallInnerSurfaceCheck)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WindingNumberInsideTest)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
