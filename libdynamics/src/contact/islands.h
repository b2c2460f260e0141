#pragma once
// Islands of a contact step (internal to ContactWorld): the groups of bodies joined by contacts,
// which sleep and wake as a whole, and the support graph that orders the solve from the ground up.

#include <vector>

#include "solver.h"

namespace dynamics::contact {

/// Union–find over the bodies, joined by the rows between two bodies.
class Islands {
 public:
  Islands(int bodies, const std::vector<Row>& rows);
  /// The island's representative body.
  int Find(int i);
  /// Puts a and b in one island (the bodies of one articulation move together).
  void Join(int a, int b) { parent_[static_cast<std::size_t>(Find(a))] = Find(b); }

 private:
  std::vector<int> parent_;
};

/// Each body's level in the support graph: 0 touches a ground or a static body, k + 1 rests on
/// level k; bodies touching none of them get std::numeric_limits<int>::max().
std::vector<int> SupportLevels(int bodies, const std::vector<Row>& rows);

/// Sleeping (ContactOptions::sleeping): each body's slow time and asleep flag, kept between steps.
struct SleepState {
  std::vector<bool> asleep;
  std::vector<double> still_for;  // s the body has been slow
};

/// Wakes every sleeping body whose island holds an awake body.
void WakeTouched(Islands& islands, SleepState& sleep);

/// After a step: an island whose bodies have all moved slower than `speed` (the angular speed
/// times each body's radius counts) for `time` seconds, and that rests on something, falls asleep
/// (velocities zeroed). Only bodies with colliders sleep.
void FallAsleep(Islands& islands, const std::vector<Row>& rows, const std::vector<bool>& collides,
                const std::vector<double>& radius, double speed, double time, double h, std::vector<RigidBody>& bodies,
                SleepState& sleep);

}  // namespace dynamics::contact
