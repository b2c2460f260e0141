// The velocity solve of a contact step, island by island: warm start, symmetric sweeps until the
// stopping rule holds, the energy guards and shock propagation (solver.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "../integrators/integrator.h"
#include "solver_internal.h"
#include "sweep_lanes.h"
#include "workers.h"

namespace dynamics::contact {
namespace {

// An island's bodies, their kinetic energy, and a copy of its impulses and velocities to go back to
// (in the island's working arrays).
class IslandState {
 public:
  IslandState(const std::vector<Patch>& patches, const std::vector<int>& order, const Coupling* coupling,
              IslandScratch& work)
      : w_(work) {
    std::vector<int>& members = w_.members;
    members.clear();
    auto add = [&](int body) {
      if (coupling == nullptr) {
        members.push_back(body);
        return;
      }
      const auto& tree = coupling->members[static_cast<std::size_t>(coupling->tree[static_cast<std::size_t>(body)])];
      members.insert(members.end(), tree.begin(), tree.end());  // all of them move
    };
    for (const int k : order) {
      const Patch& p = patches[static_cast<std::size_t>(k)];
      add(p.a);
      if (p.b >= 0) add(p.b);
    }
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
  }
  double Energy(const std::vector<Velocities>& vel, const BodyResponse& bodies) const {
    double e = 0;
    for (const int i : w_.members) {
      const auto k = static_cast<std::size_t>(i);
      if (!(bodies.inv_mass[k] > 0)) continue;
      e += 0.5 * vel[k].v.squaredNorm() / bodies.inv_mass[k] +
           0.5 * vel[k].w.dot(bodies.inv_inertia[k].inverse() * vel[k].w);
    }
    return e;
  }
  void Save(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
            const std::vector<Velocities>& vel) {
    w_.velocities.clear();
    w_.normal.clear();
    w_.friction.clear();
    for (const int i : w_.members) w_.velocities.push_back(vel[static_cast<std::size_t>(i)]);
    for (const int k : order) {
      const Patch& p = patches[static_cast<std::size_t>(k)];
      w_.friction.push_back(p.lambda);
      for (int i = p.first; i < p.first + p.count; ++i) w_.normal.push_back(rows[static_cast<std::size_t>(i)].lambda_n);
    }
  }
  void Restore(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel) const {
    for (std::size_t j = 0; j < w_.members.size(); ++j) vel[static_cast<std::size_t>(w_.members[j])] = w_.velocities[j];
    std::size_t n = 0, f = 0;
    for (const int k : order) {
      Patch& p = patches[static_cast<std::size_t>(k)];
      p.lambda = w_.friction[f++];
      for (int i = p.first; i < p.first + p.count; ++i) rows[static_cast<std::size_t>(i)].lambda_n = w_.normal[n++];
    }
  }

 private:
  IslandScratch& w_;
};

// Symmetric sweeps from the ground up, then back down (they carry a load through a stack in both
// directions), until the stopping rule holds. Returns the sweeps used, or max_iterations.
// An island solved as a block (`kind` not kNone, block_solve.cpp, its arrays in `block`): the
// sweeps while they converge fast (the warm start is often nearly the answer, and a sweep costs
// less than forming the block), then, once a sweep does not cut the change of the one before by
// kSlower (the contacts of a tree couple through its joints, boxes leaning on each other through
// their lever arms, and the sweeps crawl): for jointed bodies the block solve; for free bodies its
// pivoting step alone, after that sweep and the next (kTries), each taken only where it is the
// answer — else the sweeps go on as if it had not been tried (the sweeps between change the
// loaded set it starts from).
int Sweeps(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
           std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings, BlockKind kind,
           BlockScratch& block) {
  constexpr double kSlower = 0.1;
  constexpr int kTries = 2;
  double before = std::numeric_limits<double>::infinity();
  const bool free = kind == BlockKind::kFree;
  bool built = false;
  int tries = 0;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    Progress progress;
    Sweep(rows, patches, order, iteration % 2 == 0, !settings.exact, vel, bodies, progress);
    if (progress.Done(settings)) return iteration + 1;
    if (free && tries < kTries && iteration + 1 < settings.max_iterations &&
        (built || progress.speed > kSlower * before)) {
      if (PivotFree(rows, patches, order, vel, bodies, settings, block, !built)) return iteration + 2;
      built = true;
      ++tries;
    }
    if (kind == BlockKind::kJointed && iteration + 1 < settings.max_iterations && progress.speed > kSlower * before) {
      SolveSettings rest = settings;
      rest.max_iterations -= iteration + 1;
      return iteration + 1 + SolveBlock(rows, patches, order, vel, bodies, rest, block);
    }
    before = progress.speed;
  }
  return settings.max_iterations;
}

// The warm start: the last step's impulses applied again.
void WarmStart(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel) {
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      ApplyNormal(vel, r, r.lambda_n, -1);
    }
    ApplyPatch(vel, p, p.lambda, -1);
  }
}

// One island's solve: its patches in `order` (by support level), warm start, sweeps until the
// stopping rule holds, and shock propagation when they run out. Returns the sweeps. With `lanes`
// (planned for this island), its sweeps run on the workers' threads, with the same bits.
//
// Exact mode: shock propagation whenever the sweeps run out (rbsim 0.3). By default two guards
// keep the impulses from adding kinetic energy where the sweeps stop short of convergence: sweeps
// from the warm start lower ½λᵀAλ + λᵀ(Jv − target) from its value at the warm start, which may
// be positive, so an island that ends with more kinetic energy than before its contacts is solved
// again from zero impulses (from which every sweep only lowers it); and shock propagation, which
// holds lower bodies still and so is not passive by construction, is kept only where it does not
// add kinetic energy.
int SolveIsland(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                const SolveSettings& settings, IslandScratch& work, SweepLanes* lanes = nullptr,
                Workers* workers = nullptr) {
  auto sweep = [&](BlockKind kind) {
    if (lanes != nullptr && kind == BlockKind::kNone)
      return lanes->Sweeps(rows, patches, vel, bodies, settings, *workers);
    return Sweeps(rows, patches, order, vel, bodies, settings, kind, work.block);
  };
  auto shock = [&] {
    if (lanes != nullptr) {
      lanes->PropagateShock(rows, patches, vel, bodies, body_level, settings, *workers);
    } else {
      PropagateShock(rows, patches, order, vel, bodies, body_level, settings);
    }
  };
  if (settings.exact) {
    WarmStart(rows, patches, order, vel);
    const int sweeps = sweep(BlockKind::kNone);
    if (sweeps == settings.max_iterations) shock();
    return sweeps;
  }
  IslandState state(patches, order, bodies.coupling, work);
  const double kicked = state.Energy(vel, bodies);
  state.Save(rows, patches, order, vel);  // the kicked velocities, the warm start's impulses
  const BlockKind block = BlockKindOf(patches, order, bodies);
  WarmStart(rows, patches, order, vel);
  int last = sweep(block), sweeps = last;
  if (state.Energy(vel, bodies) > kicked) {
    state.Restore(rows, patches, order, vel);
    for (const int k : order) {
      Patch& p = patches[static_cast<std::size_t>(k)];
      p.lambda.setZero();
      for (int i = p.first; i < p.first + p.count; ++i) rows[static_cast<std::size_t>(i)].lambda_n = 0;
    }
    last = sweep(block);
    sweeps += last;
  }
  if (last < settings.max_iterations) return sweeps;
  const double before_shock = state.Energy(vel, bodies);
  state.Save(rows, patches, order, vel);
  shock();
  if (state.Energy(vel, bodies) > before_shock) state.Restore(rows, patches, order, vel);
  return sweeps;
}

}  // namespace

int SolveImpulses(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                  const BodyResponse& bodies, const std::vector<int>& body_level, const std::vector<int>& island,
                  const SolveSettings& settings, Workers* workers, SolveScratch& scratch) {
  for (Patch& p : patches) {
    const int la = body_level[static_cast<std::size_t>(p.a)];
    p.level = p.b < 0 ? la : std::min(la, body_level[static_cast<std::size_t>(p.b)]);
    // Jointed bodies are not held still level by level (their tree moves as one).
    if (p.coupling != nullptr) p.level = std::numeric_limits<int>::max();
  }
  // The patches by level (their order within a level kept: a sort on (level, index)).
  std::vector<int>& order = scratch.order;
  order.resize(patches.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    const int lx = patches[static_cast<std::size_t>(x)].level, ly = patches[static_cast<std::size_t>(y)].level;
    return lx < ly || (lx == ly && x < y);
  });
  // Each island's patches, in that order; the islands in the order they first appear.
  std::vector<int>& group_of = scratch.group_of;
  group_of.assign(island.size(), -1);
  std::vector<std::vector<int>>& groups = scratch.groups;
  std::size_t count = 0;
  for (const int k : order) {
    const int label = island[static_cast<std::size_t>(patches[static_cast<std::size_t>(k)].a)];
    int& g = group_of[static_cast<std::size_t>(label)];
    if (g < 0) {
      g = static_cast<int>(count++);
      if (groups.size() < count) groups.emplace_back();
      groups[count - 1].clear();
    }
    groups[static_cast<std::size_t>(g)].push_back(k);
  }
  // The largest islands first (the others fill in around them on several threads; equal sizes
  // in the order they appeared).
  std::vector<std::size_t>& by_size = scratch.by_size;
  by_size.resize(count);
  std::iota(by_size.begin(), by_size.end(), std::size_t{0});
  std::sort(by_size.begin(), by_size.end(), [&](std::size_t x, std::size_t y) {
    return groups[x].size() > groups[y].size() || (groups[x].size() == groups[y].size() && x < y);
  });
  std::vector<int>& sweeps = scratch.sweeps;
  sweeps.assign(count, 0);
  if (scratch.islands.size() < count) scratch.islands.resize(count);
  // The largest island, when large enough, with its sweeps on every thread; then the others
  // (or all), each on one thread.
  std::size_t first = 0;
  scratch.lanes_used = 1;
  if (workers != nullptr && workers->threads() > 1 && count > 0 &&
      SweepLanes::Suits(rows, patches, groups[by_size[0]])) {
    const std::size_t g = by_size[0];
    if (!scratch.lanes) scratch.lanes = std::make_shared<SweepLanes>();
    scratch.lanes_used = SweepLanes::LanesFor(groups[g].size(), workers->threads());
    scratch.lanes->Plan(patches, groups[g], scratch.lanes_used, body_level);
    sweeps[g] = SolveIsland(rows, patches, groups[g], vel, bodies, body_level, settings, scratch.islands[g],
                            scratch.lanes.get(), workers);
    first = 1;
  }
  auto solve = [&](std::size_t i) {
    const std::size_t g = by_size[first + i];
    sweeps[g] = SolveIsland(rows, patches, groups[g], vel, bodies, body_level, settings, scratch.islands[g]);
  };
  // A few small islands are not worth waking the workers for.
  if (workers != nullptr && count - first > 1 && patches.size() >= 32) {
    workers->ForEach(count - first, solve);
  } else {
    for (std::size_t i = 0; i + first < count; ++i) solve(i);
  }
  return sweeps.empty() ? 0 : *std::max_element(sweeps.begin(), sweeps.end());
}

}  // namespace dynamics::contact
