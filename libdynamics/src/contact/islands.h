#pragma once
// Islands of a contact step (internal to ContactWorld): the groups of bodies joined by contacts,
// which sleep and wake as a whole, and the support graph that orders the solve from the ground up.

#include <vector>

#include "solver.h"

namespace dynamics::contact {

/// Sleeping (ContactOptions::sleeping): each body's slow time and asleep flag, kept between steps.
struct SleepState {
  std::vector<bool> asleep;
  std::vector<double> still_for;  // s the body has been slow
};

/// Union–find over the bodies, joined by the rows between two bodies; kept from step to step
/// (Reset reuses its arrays).
class Islands {
 public:
  Islands() = default;
  Islands(int bodies, const std::vector<Row>& rows) { Reset(bodies, rows); }
  /// Each body its own island, then the rows' bodies joined.
  void Reset(int bodies, const std::vector<Row>& rows);
  /// The island's representative body.
  int Find(int i);
  /// Puts a and b in one island (the bodies of one articulation move together).
  void Join(int a, int b) { parent_[static_cast<std::size_t>(Find(a))] = Find(b); }

  /// Wakes every sleeping body whose island holds an awake body.
  void WakeTouched(SleepState& sleep);
  /// After a step: an island whose bodies have all moved slower than `speed` (the angular speed
  /// times each body's radius counts) for `time` seconds, and that rests on something, falls
  /// asleep (velocities zeroed). Only bodies with colliders sleep.
  void FallAsleep(const std::vector<Row>& rows, const std::vector<bool>& collides, const std::vector<double>& radius,
                  double speed, double time, double h, std::vector<RigidBody>& bodies, SleepState& sleep);

 private:
  std::vector<int> parent_;
  std::vector<char> flag_, other_flag_;  // per island (by representative), working
};

/// Each body's level in the support graph (into `level`): 0 touches a ground or a static body,
/// k + 1 rests on level k; bodies touching none of them get std::numeric_limits<int>::max().
void SupportLevels(int bodies, const std::vector<Row>& rows, std::vector<int>& level);

}  // namespace dynamics::contact
