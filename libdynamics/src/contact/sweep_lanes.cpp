// One island's sweeps on several threads with the bits of one (sweep_lanes.h).

#include "sweep_lanes.h"

#include <algorithm>
#include <limits>
#include <thread>

#include "solver_internal.h"
#include "workers.h"

namespace dynamics::contact {
namespace {

// Waits until `ready()`: spinning a while (a neighbour's update takes a fraction of a
// microsecond), then yielding (the other thread may have lost its core).
template <typename Ready>
void WaitFor(const Ready& ready) {
  for (int spins = 0; !ready(); ++spins) {
    if (spins < 4096) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }
}

}  // namespace

bool SweepLanes::Suits(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order) {
  if (order.size() < kMinPatches) return false;
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    if (p.coupling != nullptr) return false;
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      if (r.a != p.a || r.b != p.b || r.coupling != nullptr) return false;
    }
  }
  return true;
}

void SweepLanes::Plan(const std::vector<Patch>& patches, const std::vector<int>& order, int lanes, std::size_t bodies) {
  lanes_ = lanes;
  patches_ = order.size();
  if (lane_of_body_.size() < bodies) {
    lane_of_body_.assign(bodies, -1);
    last_lane_.assign(bodies, -1);
    last_count_.assign(bodies, 0);
  }
  // The island's longest extent, from its patches' anchors.
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const int k : order) {
    const Vector3& x = patches[static_cast<std::size_t>(k)].anchor;
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  // Each body's position along it (its centre: a patch's anchor less its arm), and the patches
  // led by each body (a patch runs in its first body's lane).
  placed_.clear();
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    auto place = [&](int body, const Vector3& arm) {
      int& mark = lane_of_body_[static_cast<std::size_t>(body)];
      if (mark != -1) return;
      mark = -2;  // placed
      placed_.emplace_back(p.anchor[axis] - arm[axis], body);
    };
    place(p.a, p.ra);
    if (p.b >= 0) place(p.b, p.rb);
  }
  std::sort(placed_.begin(), placed_.end());
  // Bodies in that order, into lanes of about equal numbers of patches.
  last_count_.assign(last_count_.size(), 0);  // (as a count of the patches each body leads)
  for (const int k : order) ++last_count_[static_cast<std::size_t>(patches[static_cast<std::size_t>(k)].a)];
  std::size_t led = 0;
  for (const auto& [position, body] : placed_) {
    const auto b = static_cast<std::size_t>(body);
    lane_of_body_[b] = static_cast<int>(std::min<std::size_t>(lanes - 1, led * lanes / patches_));
    led += last_count_[b];
  }
  forward_.resize(static_cast<std::size_t>(lanes));
  backward_.resize(static_cast<std::size_t>(lanes));
  BuildSteps(patches, order, true);
  BuildSteps(patches, order, false);
  for (const auto& [position, body] : placed_) lane_of_body_[static_cast<std::size_t>(body)] = -1;
  if (!counters_ || progress_.size() < 2 * static_cast<std::size_t>(lanes)) {
    counters_ = std::make_unique<Counter[]>(static_cast<std::size_t>(lanes));
    progress_.resize(2 * static_cast<std::size_t>(lanes));
  }
}

void SweepLanes::BuildSteps(const std::vector<Patch>& patches, const std::vector<int>& order, bool forward) {
  auto& steps = forward ? forward_ : backward_;
  for (auto& lane : steps) lane.clear();
  lane_size_.assign(static_cast<std::size_t>(lanes_), 0);
  for (const auto& [position, body] : placed_) last_lane_[static_cast<std::size_t>(body)] = -1;
  const std::size_t n = order.size();
  for (std::size_t j = 0; j < n; ++j) {
    const int k = order[forward ? j : n - 1 - j];
    const Patch& p = patches[static_cast<std::size_t>(k)];
    const int lane = lane_of_body_[static_cast<std::size_t>(p.a)];
    Step step;
    step.patch = k;
    // The last update of each of its bodies, when another lane's: wait for it (one wait a lane,
    // the later count).
    for (const int body : {p.a, p.b}) {
      if (body < 0) continue;
      const int other = last_lane_[static_cast<std::size_t>(body)];
      if (other < 0 || other == lane) continue;
      const std::uint32_t count = last_count_[static_cast<std::size_t>(body)];
      if (step.waits == 1 && step.lane[0] == other) {
        step.count[0] = std::max(step.count[0], count);
      } else {
        step.lane[step.waits] = other;
        step.count[step.waits] = count;
        ++step.waits;
      }
    }
    const std::uint32_t done = ++lane_size_[static_cast<std::size_t>(lane)];
    for (const int body : {p.a, p.b}) {
      if (body < 0) continue;
      last_lane_[static_cast<std::size_t>(body)] = lane;
      last_count_[static_cast<std::size_t>(body)] = done;
    }
    steps[static_cast<std::size_t>(lane)].push_back(step);
  }
}

int SweepLanes::Sweeps(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                       const BodyResponse& bodies, const SolveSettings& settings, Workers& workers) {
  for (int l = 0; l < lanes_; ++l) counters_[static_cast<std::size_t>(l)].done.store(0, std::memory_order_relaxed);
  arrived_.store(0, std::memory_order_relaxed);
  int sweeps = settings.max_iterations;
  workers.ForEach(static_cast<std::size_t>(lanes_), [&](std::size_t lane) {
    const int used = Lane(static_cast<int>(lane), rows, patches, vel, bodies, settings);
    if (lane == 0) sweeps = used;
  });
  return sweeps;
}

int SweepLanes::Lane(int lane, std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                     const BodyResponse& bodies, const SolveSettings& settings) {
  const bool block = !settings.exact;
  Counter& mine = counters_[static_cast<std::size_t>(lane)];
  for (int sweep = 0; sweep < settings.max_iterations; ++sweep) {
    const bool forward = sweep % 2 == 0;
    const std::uint64_t base = static_cast<std::uint64_t>(sweep) * (patches_ + 1);
    Progress progress;
    std::uint64_t done = base;
    for (const Step& step : (forward ? forward_ : backward_)[static_cast<std::size_t>(lane)]) {
      for (int w = 0; w < step.waits; ++w) {
        const std::atomic<std::uint64_t>& theirs = counters_[static_cast<std::size_t>(step.lane[w])].done;
        const std::uint64_t needed = base + step.count[w];
        WaitFor([&] { return theirs.load(std::memory_order_acquire) >= needed; });
      }
      SweepPatch(patches[static_cast<std::size_t>(step.patch)], rows, forward, block, false, vel, bodies, progress);
      mine.done.store(++done, std::memory_order_release);
    }
    // Every lane's progress (kept per sweep parity: a lane may write the next sweep's before
    // another has read this one's), combined as the one-thread sweep's: maxima.
    Progress* slots = progress_.data() + static_cast<std::size_t>(sweep % 2) * lanes_;
    slots[lane] = progress;
    Barrier();
    Progress all;
    for (int l = 0; l < lanes_; ++l) {
      all.change = std::max(all.change, slots[l].change);
      all.scale = std::max(all.scale, slots[l].scale);
      all.speed = std::max(all.speed, slots[l].speed);
    }
    if (all.Done(settings)) return sweep + 1;
  }
  return settings.max_iterations;
}

void SweepLanes::Barrier() {
  const int generation = generation_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) == lanes_ - 1) {
    arrived_.store(0, std::memory_order_relaxed);
    generation_.store(generation + 1, std::memory_order_release);
    return;
  }
  WaitFor([&] { return generation_.load(std::memory_order_acquire) != generation; });
}

}  // namespace dynamics::contact
