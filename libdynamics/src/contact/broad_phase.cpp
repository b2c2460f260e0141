// Sweep and prune (broad_phase.h).

#include "broad_phase.h"

#include <algorithm>
#include <utility>

namespace dynamics::contact {

void FindCandidates(const std::vector<BroadBody>& bodies, const std::vector<BroadStatic>& statics,
                    std::vector<Candidate>& candidates, std::vector<SweepInterval>& intervals) {
  intervals.clear();
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const BroadBody& b = bodies[k];
    if (!b.collides) continue;
    intervals.push_back(
        {b.posed->t.x() - b.radius - b.reach, b.posed->t.x() + b.radius + b.reach, static_cast<int>(k)});
  }
  for (std::size_t s = 0; s < statics.size(); ++s) {
    intervals.push_back({statics[s].lower.x(), statics[s].upper.x(), -1 - static_cast<int>(s)});
  }
  std::sort(intervals.begin(), intervals.end(), [](const SweepInterval& x, const SweepInterval& y) {
    return x.lo < y.lo || (x.lo == y.lo && x.id < y.id);
  });
  candidates.clear();
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    for (std::size_t j = i + 1; j < intervals.size() && intervals[j].lo <= intervals[i].hi; ++j) {
      int a = intervals[i].id, b = intervals[j].id;
      if (a < 0 && b < 0) continue;                     // two static bodies
      if (a < 0 || (b >= 0 && b < a)) std::swap(a, b);  // a dynamic; the lower index first
      const BroadBody& A = bodies[static_cast<std::size_t>(a)];
      Vector3 tb;
      double rb = 0, reach_b = 0;
      if (b >= 0) {
        const BroadBody& B = bodies[static_cast<std::size_t>(b)];
        tb = B.posed->t;
        rb = B.radius;
        reach_b = B.reach;
      } else {
        const BroadStatic& s = statics[static_cast<std::size_t>(-1 - b)];
        tb = s.posed.t;
        rb = s.radius;
      }
      const double margin = A.reach + reach_b;
      if ((A.posed->t - tb).norm() - A.radius - rb >= margin) continue;
      candidates.push_back({a, b, margin});
    }
  }
}

}  // namespace dynamics::contact
