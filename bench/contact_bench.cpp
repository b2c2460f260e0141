// Contact throughput: piles of 100 and 1000 boxes dropped in a grid onto the ground, stepped at
// 1 ms after they have settled into a heap (0.5 s of warm-up), on 1 and 2 threads. Reports steps
// per second and contact points solved per second. Sleeping off (the worst case).
//
//   build/bench/contact_bench [--benchmark_filter=...]

#include <benchmark/benchmark.h>

#include <cmath>

#include "dynamics/contact.h"

namespace {

using dynamics::Vector3;

dynamics::ContactWorld Pile(int n, int threads) {
  dynamics::ContactWorld w;
  const Vector3 half(0.04, 0.03, 0.025);
  const int side = static_cast<int>(std::ceil(std::sqrt(n / 4.0)));
  for (int i = 0; i < n; ++i) {
    dynamics::RigidBody b;
    const Vector3 s = 2 * half;
    b.mass = 600 * s.prod();
    b.inertia =
        Vector3(s[1] * s[1] + s[2] * s[2], s[0] * s[0] + s[2] * s[2], s[0] * s[0] + s[1] * s[1]) * (b.mass / 12);
    const int layer = i / (side * side), cell = i % (side * side);
    b.position = Vector3(0.1 * (cell % side) + 0.01 * (layer % 3), 0.1 * (cell / side), 0.05 + 0.08 * layer);
    b.orientation = dynamics::Quaternion(Eigen::AngleAxisd(0.3 * i, Vector3(1, 2, 3).normalized()));
    w.AddBody(b, dynamics::Collider{dynamics::shape::Box{half}, dynamics::Matrix3::Identity(), Vector3::Zero(),
                                    dynamics::Material{0.6, 0.5, 0.1}});
  }
  w.AddGround({Vector3::UnitZ(), 0, dynamics::Material{0.6, 0.5, 0.1}});
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  w.world().set_num_threads(threads);
  for (int i = 0; i < 500; ++i) w.Step(1e-3);
  return w;
}

void BM_BoxPile(benchmark::State& state) {
  dynamics::ContactWorld w = Pile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::int64_t contacts = 0;
  for (auto _ : state) {
    w.Step(1e-3);
    contacts += w.stats().contacts;
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["contacts/s"] = benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kIsRate);
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_BoxPile)->Args({100, 1})->Args({100, 2})->Args({1000, 1})->Args({1000, 2})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
