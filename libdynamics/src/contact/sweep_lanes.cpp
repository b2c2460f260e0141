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

void SweepLanes::Plan(const std::vector<Patch>& patches, const std::vector<int>& order, int lanes,
                      const std::vector<int>& body_level) {
  lanes_ = lanes;
  patches_ = order.size();
  if (lane_of_body_.size() < body_level.size()) {
    lane_of_body_.assign(body_level.size(), -1);
    last_lane_.assign(body_level.size(), -1);
    last_count_.assign(body_level.size(), 0);
  }
  // The island's longest extent across the way its contacts push (their normals' mean
  // direction, most often up: lanes split along it would wait on each other, the sweeps running
  // from the ground up), from its patches' anchors.
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo, push = Vector3::Zero();
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    lo = lo.cwiseMin(p.anchor);
    hi = hi.cwiseMax(p.anchor);
    push += p.n.cwiseAbs();
  }
  int up = 0, axis = 0;
  push.maxCoeff(&up);
  Vector3 extent = hi - lo;
  extent[up] = -1;
  extent.maxCoeff(&axis);
  // Each body's position along it (its centre: a patch's anchor less its arm), and the number of
  // patches each body leads (a patch of the sweeps runs in its first body's lane).
  placed_.clear();
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    auto place = [&](int body, const Vector3& arm) {
      int& mark = lane_of_body_[static_cast<std::size_t>(body)];
      if (mark != -1) return;
      mark = -2;  // placed
      last_count_[static_cast<std::size_t>(body)] = 0;
      placed_.emplace_back(p.anchor[axis] - arm[axis], body);
    };
    place(p.a, p.ra);
    if (p.b >= 0) place(p.b, p.rb);
  }
  for (const int k : order) ++last_count_[static_cast<std::size_t>(patches[static_cast<std::size_t>(k)].a)];
  std::sort(placed_.begin(), placed_.end());
  // Bodies in that order, into lanes of about equal numbers of patches.
  std::size_t led = 0;
  for (const auto& [position, body] : placed_) {
    const auto b = static_cast<std::size_t>(body);
    lane_of_body_[b] = static_cast<int>(std::min<std::size_t>(lanes - 1, led * lanes / patches_));
    led += last_count_[b];
  }
  // The sweeps: both directions, each patch in its first body's lane, waiting on both bodies.
  auto first_body = [&](const Patch& p) { return lane_of_body_[static_cast<std::size_t>(p.a)]; };
  auto both = [](const Patch& p) { return std::pair<int, int>(p.a, p.b); };
  sequence_.assign(order.begin(), order.end());
  Build(forward_, patches, first_body, both);
  std::reverse(sequence_.begin(), sequence_.end());
  Build(backward_, patches, first_body, both);
  // Shock propagation: level by level, each patch in the lane of the body it moves. The body it
  // holds still is on the patch's level, where that body's own patches on the ground move it:
  // it is waited for too.
  auto moved = [&](const Patch& p) { return ShockFrozen(p, body_level) == p.a ? p.b : p.a; };
  auto moved_lane = [&](const Patch& p) { return lane_of_body_[static_cast<std::size_t>(moved(p))]; };
  auto moved_first = [&](const Patch& p) { return std::pair<int, int>(moved(p), ShockFrozen(p, body_level)); };
  shock_levels_ = 0;
  int max_level = -1;
  for (const int k : order) max_level = std::max(max_level, patches[static_cast<std::size_t>(k)].level);
  for (int level = 0; level <= max_level; ++level) {
    sequence_.clear();
    for (const int k : order) {
      const Patch& p = patches[static_cast<std::size_t>(k)];
      if (p.level == level && ShockFrozen(p, body_level) != kShockSkipped) sequence_.push_back(k);
    }
    if (sequence_.empty()) continue;
    if (shock_.size() <= shock_levels_) shock_.emplace_back();
    Build(shock_[shock_levels_++], patches, moved_lane, moved_first);
  }
  for (const auto& [position, body] : placed_) lane_of_body_[static_cast<std::size_t>(body)] = -1;
  if (counter_lanes_ < lanes) {
    counters_ = std::make_unique<Counter[]>(static_cast<std::size_t>(lanes));
    progress_.resize(2 * static_cast<std::size_t>(lanes));
    counter_lanes_ = lanes;
  }
}

template <typename LaneOf, typename BodiesOf>
void SweepLanes::Build(Schedule& out, const std::vector<Patch>& patches, const LaneOf& lane_of,
                       const BodiesOf& bodies_of) {
  out.resize(static_cast<std::size_t>(lanes_));
  for (auto& lane : out) lane.clear();
  lane_size_.assign(static_cast<std::size_t>(lanes_), 0);
  for (const auto& [position, body] : placed_) last_lane_[static_cast<std::size_t>(body)] = -1;
  for (const int k : sequence_) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    const int lane = lane_of(p);
    const auto [first, second] = bodies_of(p);
    Step step;
    step.patch = k;
    // The last update of each of its bodies, when another lane's: wait for it (one wait a lane,
    // the later count).
    for (const int body : {first, second}) {
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
    for (const int body : {first, second}) {
      if (body < 0) continue;
      last_lane_[static_cast<std::size_t>(body)] = lane;
      last_count_[static_cast<std::size_t>(body)] = done;
    }
    out[static_cast<std::size_t>(lane)].push_back(step);
  }
}

void SweepLanes::Reset() {
  for (int l = 0; l < lanes_; ++l) counters_[static_cast<std::size_t>(l)].done.store(0, std::memory_order_relaxed);
  arrived_.store(0, std::memory_order_relaxed);
}

template <typename Update>
void SweepLanes::Pass(int lane, const Schedule& schedule, int pass, const Update& update) {
  std::atomic<std::uint64_t>& mine = counters_[static_cast<std::size_t>(lane)].done;
  const std::uint64_t base = static_cast<std::uint64_t>(pass) * (patches_ + 1);
  std::uint64_t done = base;
  for (const Step& step : schedule[static_cast<std::size_t>(lane)]) {
    for (int w = 0; w < step.waits; ++w) {
      const std::atomic<std::uint64_t>& theirs = counters_[static_cast<std::size_t>(step.lane[w])].done;
      const std::uint64_t needed = base + step.count[w];
      WaitFor([&] { return theirs.load(std::memory_order_acquire) >= needed; });
    }
    update(step.patch);
    mine.store(++done, std::memory_order_release);
  }
}

Progress SweepLanes::Combined(int lane, int pass, const Progress& mine) {
  // Kept per pass parity: a lane may write the next pass's before another has read this one's.
  Progress* slots = progress_.data() + static_cast<std::size_t>(pass % 2) * lanes_;
  slots[lane] = mine;
  Barrier();
  Progress all;  // the one-thread pass's: maxima
  for (int l = 0; l < lanes_; ++l) {
    all.change = std::max(all.change, slots[l].change);
    all.scale = std::max(all.scale, slots[l].scale);
    all.speed = std::max(all.speed, slots[l].speed);
  }
  return all;
}

int SweepLanes::Sweeps(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                       const BodyResponse& bodies, const SolveSettings& settings, Workers& workers) {
  Reset();
  const bool block = !settings.exact;
  int sweeps = settings.max_iterations;
  workers.Together(static_cast<std::size_t>(lanes_), [&](std::size_t l) {
    const int lane = static_cast<int>(l);
    for (int sweep = 0; sweep < settings.max_iterations; ++sweep) {
      const bool forward = sweep % 2 == 0;
      Progress progress;
      Pass(lane, forward ? forward_ : backward_, sweep, [&](int k) {
        SweepPatch(patches[static_cast<std::size_t>(k)], rows, forward, block, false, vel, bodies, progress);
      });
      if (Combined(lane, sweep, progress).Done(settings)) {
        if (lane == 0) sweeps = sweep + 1;
        return;
      }
    }
  });
  return sweeps;
}

void SweepLanes::PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                                const BodyResponse& bodies, const std::vector<int>& body_level,
                                const SolveSettings& settings, Workers& workers) {
  Reset();
  workers.Together(static_cast<std::size_t>(lanes_), [&](std::size_t l) {
    const int lane = static_cast<int>(l);
    int passes = 0;  // since the reset
    for (std::size_t s = 0; s < shock_levels_; ++s) {
      for (int pass = 0; pass < settings.max_iterations; ++pass, ++passes) {
        Progress progress;
        Pass(lane, shock_[s], passes,
             [&](int k) { ShockPatch(patches[static_cast<std::size_t>(k)], rows, vel, bodies, body_level, progress); });
        if (Combined(lane, passes, progress).Done(settings)) {
          ++passes;
          break;
        }
      }
    }
  });
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
