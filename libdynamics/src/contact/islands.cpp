// Islands, the support graph and sleeping (islands.h).

#include "islands.h"

#include <limits>
#include <utility>

namespace dynamics::contact {

void Islands::Reset(int bodies, const std::vector<Row>& rows) {
  parent_.resize(static_cast<std::size_t>(bodies));
  for (int i = 0; i < bodies; ++i) parent_[static_cast<std::size_t>(i)] = i;
  for (const Row& r : rows) {
    if (r.b >= 0) parent_[static_cast<std::size_t>(Find(r.a))] = Find(r.b);
  }
}

int Islands::Find(int i) {
  while (parent_[static_cast<std::size_t>(i)] != i) {
    parent_[static_cast<std::size_t>(i)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
    i = parent_[static_cast<std::size_t>(i)];
  }
  return i;
}

// Breadth first from the bodies on a ground or a static body: level k is every body one row
// above a body of level k − 1 (the graph distance, whatever the rows' order).
void SupportLevels(int bodies, const std::vector<Row>& rows, std::vector<int>& level) {
  constexpr int kNone = std::numeric_limits<int>::max();
  level.assign(static_cast<std::size_t>(bodies), kNone);
  bool any = false;
  for (const Row& r : rows) {
    if (r.b < 0) {
      level[static_cast<std::size_t>(r.a)] = 0;
      any = true;
    }
  }
  for (int k = 1; any; ++k) {
    any = false;
    for (const Row& r : rows) {
      if (r.b < 0) continue;
      for (const auto& [lower, upper] : {std::pair{r.a, r.b}, std::pair{r.b, r.a}}) {
        if (level[static_cast<std::size_t>(lower)] == k - 1 && level[static_cast<std::size_t>(upper)] == kNone) {
          level[static_cast<std::size_t>(upper)] = k;
          any = true;
        }
      }
    }
  }
}

void Islands::WakeTouched(SleepState& sleep) {
  const int nb = static_cast<int>(sleep.asleep.size());
  std::vector<char>& island_awake = flag_;
  island_awake.assign(static_cast<std::size_t>(nb), 0);
  for (int i = 0; i < nb; ++i) {
    if (!sleep.asleep[static_cast<std::size_t>(i)]) island_awake[static_cast<std::size_t>(Find(i))] = 1;
  }
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (sleep.asleep[k] && island_awake[static_cast<std::size_t>(Find(i))]) sleep.asleep[k] = false;
  }
}

void Islands::FallAsleep(const std::vector<Row>& rows, const std::vector<bool>& collides,
                         const std::vector<double>& radius, double speed, double time, double h,
                         std::vector<RigidBody>& bodies, SleepState& sleep) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<char>& slow = flag_;
  slow.assign(static_cast<std::size_t>(nb), 1);
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const RigidBody& b = bodies[k];
    const bool still = b.velocity.norm() + b.AngularVelocity().norm() * radius[k] < speed;
    sleep.still_for[k] = still ? sleep.still_for[k] + h : 0.0;
    if (sleep.still_for[k] < time) slow[static_cast<std::size_t>(Find(i))] = 0;
  }
  std::vector<char>& touches = other_flag_;  // islands resting on something
  touches.assign(static_cast<std::size_t>(nb), 0);
  for (const Row& r : rows) touches[static_cast<std::size_t>(Find(r.a))] = 1;
  for (int i = 0; i < nb; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const int root = Find(i);
    if (collides[k] && slow[static_cast<std::size_t>(root)] && touches[static_cast<std::size_t>(root)] &&
        !sleep.asleep[k]) {
      sleep.asleep[k] = true;
      bodies[k].velocity.setZero();
      bodies[k].angular_momentum.setZero();
    }
  }
}

}  // namespace dynamics::contact
