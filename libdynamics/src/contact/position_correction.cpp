// Position correction by split impulses (position_correction.h).

#include "position_correction.h"

#include <algorithm>
#include <cmath>

namespace dynamics::contact {

void PushOutVelocities(std::vector<Row>& rows, int num_bodies, double h, const SolveSettings& settings,
                       std::vector<Velocities>& pseudo) {
  pseudo.clear();
  bool pushes = false;
  for (const Row& r : rows) pushes = pushes || (r.slop >= 0 && -r.separation > r.slop);
  if (!pushes) return;
  pseudo.assign(static_cast<std::size_t>(num_bodies), {Vector3::Zero(), Vector3::Zero()});
  constexpr double kPush = 0.5;  // of the excess overlap, per step
  for (int sweep = 0; sweep < settings.max_iterations; ++sweep) {
    Progress progress;
    for (Row& r : rows) {
      if (r.slop < 0) continue;
      const double target = kPush * std::max(-r.separation - r.slop, 0.0) / h;
      const double push = std::max(r.push + r.mass_n * (target - NormalSpeed(pseudo, r)), 0.0);
      const double d = push - r.push;
      progress.change = std::max(progress.change, std::abs(d));
      progress.scale = std::max(progress.scale, push);
      progress.speed = std::max(progress.speed, std::abs(d) / r.mass_n);
      r.push = push;
      ApplyNormal(pseudo, r, d, -1);
    }
    if (progress.Done(settings)) break;
  }
}

}  // namespace dynamics::contact
