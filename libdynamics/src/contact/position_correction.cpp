// Position correction by split impulses (position_correction.h).

#include "position_correction.h"

#include <algorithm>
#include <cmath>

namespace dynamics::contact {

std::vector<Velocities> PushOutVelocities(std::vector<Row>& rows, const BodyResponse& bodies, int num_bodies, double h,
                                          int max_iterations, double tolerance) {
  std::vector<Velocities> pseudo;
  bool pushes = false;
  for (const Row& r : rows) pushes = pushes || (r.slop >= 0 && -r.separation > r.slop);
  if (!pushes) return pseudo;
  pseudo.assign(static_cast<std::size_t>(num_bodies), {Vector3::Zero(), Vector3::Zero()});
  constexpr double kPush = 0.5;  // of the excess overlap, per step
  for (int sweep = 0; sweep < max_iterations; ++sweep) {
    double change = 0, scale = 0;
    for (Row& r : rows) {
      if (r.slop < 0) continue;
      const double target = kPush * std::max(-r.separation - r.slop, 0.0) / h;
      const double push = std::max(r.push + r.mass_n * (target - r.n.dot(RelativeVelocity(pseudo, r))), 0.0);
      const Vector3 impulse = r.n * (push - r.push);
      change = std::max(change, std::abs(push - r.push));
      scale = std::max(scale, push);
      r.push = push;
      ApplyImpulse(pseudo, bodies, r.a, r.b, r.ra, r.rb, impulse, Vector3::Zero());
    }
    if (change <= tolerance * scale) break;
  }
  return pseudo;
}

}  // namespace dynamics::contact
