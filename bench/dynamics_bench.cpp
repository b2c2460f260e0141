// Body-steps per second of every integrator for worlds of 1, 10^3 and 10^5 torque-free bodies
// (Google Benchmark; items_per_second = body-steps/s, wall-clock, all cores).

#include <benchmark/benchmark.h>

#include "dynamics/world.h"

namespace {

void BM_FreeBodies(benchmark::State& state) {
  const auto integ = static_cast<dynamics::Integrator>(state.range(0));
  const auto n = static_cast<int>(state.range(1));
  dynamics::World world(integ);
  for (int i = 0; i < n; ++i) {
    dynamics::RigidBody b;
    b.inertia = dynamics::Vector3(1.0 + 1e-6 * i, 2.0, 2.5);
    b.angular_momentum = b.inertia.cwiseProduct(dynamics::Vector3(0.1, 1.0, 0.2 + 1e-6 * i));
    b.position = dynamics::Vector3(i, 0, 0);
    world.AddBody(b);
  }
  world.Step(1e-3);  // warm-up: the first step allocates the integrator's scratch
  for (auto _ : state) world.Step(1e-3);
  state.SetItemsProcessed(state.iterations() * n);
  state.SetLabel(dynamics::IntegratorName(integ));
}

void Args(benchmark::internal::Benchmark* b) {
  for (dynamics::Integrator integ : dynamics::kAllIntegrators) {
    for (int n : {1, 1000, 100000}) b->Args({static_cast<int>(integ), n});
  }
}
BENCHMARK(BM_FreeBodies)->Apply(Args)->ArgNames({"integrator", "bodies"})->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
