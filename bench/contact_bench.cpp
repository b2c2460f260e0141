// Contact throughput: piles of 100 and 1000 boxes dropped in a grid onto the ground, and a pile of
// 100 non-convex meshes (tori and Spot, each collided as its own mesh through a signed distance
// field), stepped at 1 ms after they have settled into a heap (0.5 s of warm-up), on 1 and 2
// threads. Reports steps per second and contact points solved per second. Sleeping off (the worst
// case). BM_MeshField: building one field (Spot, 5856 triangles; a torus of 2048), with its size.
//
//   build/bench/contact_bench [--benchmark_filter=...]

#include <benchmark/benchmark.h>

#include <cmath>

#include "dynamics/contact.h"
#include "massprops/io/mesh_io.h"
#include "massprops/mass_properties.h"
#include "massprops/solids.h"

namespace {

using dynamics::Vector3;

// The ground, gravity, the thread count, and 0.5 s of settling at 1 ms.
void Settle(dynamics::ContactWorld& w, int threads) {
  w.AddGround({Vector3::UnitZ(), 0, dynamics::Material{0.6, 0.5, 0.1}});
  w.AddForce(dynamics::Gravity(Vector3(0, 0, -9.81)));
  w.set_num_threads(threads);
  for (int i = 0; i < 500; ++i) w.Step(1e-3);
}

// Steps of 1 ms: steps/s, contacts/s and contacts/step.
void Measure(benchmark::State& state, dynamics::ContactWorld& w) {
  std::int64_t contacts = 0;
  for (auto _ : state) {
    w.Step(1e-3);
    contacts += w.stats().contacts;
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["contacts/s"] = benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kIsRate);
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(state.iterations());
}

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
  Settle(w, threads);
  return w;
}

void BM_BoxPile(benchmark::State& state) {
  dynamics::ContactWorld w = Pile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Measure(state, w);
}
BENCHMARK(BM_BoxPile)->Args({100, 1})->Args({100, 2})->Args({1000, 1})->Args({1000, 2})->Unit(benchmark::kMillisecond);

// A mesh collider and a body for it (principal frame), scaled to `size` across.
struct Part {
  dynamics::RigidBody body;
  dynamics::shape::Mesh shape;
};

Part MakePart(massprops::TriangleMesh m, double size) {
  m.V *= size / (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).maxCoeff();
  const dynamics::PlacedBody placed = dynamics::BodyFromMassProperties(massprops::ComputeMassProperties(m, 900));
  std::vector<Vector3> v;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) v.push_back(placed.mesh_to_body.Apply(m.V.row(i).transpose()));
  std::vector<std::array<int, 3>> t;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) t.push_back({m.F(f, 0), m.F(f, 1), m.F(f, 2)});
  return {placed.body, dynamics::MakeMesh(std::move(v), std::move(t))};
}

massprops::TriangleMesh Spot() {
  return massprops::Triangulate(massprops::ReadMeshFile(std::string(MASSPROPS_DATA_DIR) + "/meshes/spot.obj").mesh);
}

dynamics::ContactWorld MeshPile(int n, int threads) {
  const Part parts[2] = {MakePart(massprops::solids::Torus(0.035, 0.012, 32), 0.094), MakePart(Spot(), 0.07)};
  dynamics::ContactWorld w;
  const int side = static_cast<int>(std::ceil(std::sqrt(n / 4.0)));
  for (int i = 0; i < n; ++i) {
    const Part& p = parts[i % 2];
    dynamics::RigidBody b = p.body;
    const int layer = i / (side * side), cell = i % (side * side);
    b.position = Vector3(0.11 * (cell % side) + 0.01 * (layer % 3), 0.11 * (cell / side), 0.06 + 0.1 * layer);
    b.orientation = dynamics::Quaternion(Eigen::AngleAxisd(0.3 * i, Vector3(1, 2, 3).normalized()));
    w.AddBody(b, dynamics::Collider{p.shape, dynamics::Matrix3::Identity(), Vector3::Zero(),
                                    dynamics::Material{0.6, 0.5, 0.1}});
  }
  Settle(w, threads);
  return w;
}

void BM_MeshPile(benchmark::State& state) {
  dynamics::ContactWorld w = MeshPile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Measure(state, w);
}
BENCHMARK(BM_MeshPile)->Args({100, 1})->Args({100, 2})->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_MeshField(benchmark::State& state) {
  const massprops::TriangleMesh m = state.range(0) == 0 ? Spot() : massprops::solids::Torus(0.035, 0.012, 32);
  dynamics::MeshFieldInfo info;
  for (auto _ : state) {
    const Part p = MakePart(m, state.range(0) == 0 ? 0.07 : 0.094);
    info = dynamics::DescribeMeshField(p.shape);
  }
  state.counters["nodes"] = static_cast<double>(info.nodes[0]) * info.nodes[1] * info.nodes[2];
  state.counters["cell_mm"] = 1e3 * info.cell;
  state.counters["MB"] = static_cast<double>(info.bytes) / 1e6;
  state.counters["samples"] = static_cast<double>(info.samples);
  state.SetLabel(state.range(0) == 0 ? "Spot, 7 cm" : "torus, 9.4 cm");
}
BENCHMARK(BM_MeshField)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
