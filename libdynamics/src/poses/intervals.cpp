// Confidence intervals for drop counts, and the tally of a batch of drops (poses.h).

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>

#include "dynamics/poses.h"

namespace dynamics::poses {
namespace {

void CheckConfidence(double confidence) {
  if (!(confidence > 0 && confidence < 1)) throw std::invalid_argument("intervals: confidence must be in (0, 1)");
}

// The standard normal quantile at p.
double NormalQuantile(double p) { return boost::math::quantile(boost::math::normal_distribution<double>(), p); }

// Wilson's score interval with z² = a: (k + a/2 ± √(a (k (n − k)/n + a/4))) / (n + a), which is
// also Goodman's simultaneous interval when a is the χ²₁ quantile at 1 − α/cells.
Interval Score(std::int64_t k, std::int64_t n, double a) {
  if (n == 0) return {0.0, 1.0};
  const auto kk = static_cast<double>(k), nn = static_cast<double>(n);
  const double centre = kk + a / 2, half = std::sqrt(a * (kk * (nn - kk) / nn + a / 4));
  return {std::max(0.0, (centre - half) / (nn + a)), std::min(1.0, (centre + half) / (nn + a))};
}

}  // namespace

Interval BinomialInterval(std::int64_t k, std::int64_t n, double confidence) {
  CheckConfidence(confidence);
  if (k < 0 || n < 0 || k > n) throw std::invalid_argument("intervals: need 0 <= k <= n");
  const double z = NormalQuantile(1 - (1 - confidence) / 2);
  return Score(k, n, z * z);
}

std::vector<Interval> SimultaneousIntervals(const std::vector<std::int64_t>& counts, double confidence) {
  CheckConfidence(confidence);
  std::int64_t n = 0;
  for (std::int64_t k : counts) {
    if (k < 0) throw std::invalid_argument("intervals: counts must be >= 0");
    n += k;
  }
  // Goodman (1965): χ²₁ at 1 − α/K, i.e. the square of the normal quantile at 1 − α/(2K).
  const double cells = static_cast<double>(std::max<std::size_t>(counts.size(), 1));
  const double z = NormalQuantile(1 - (1 - confidence) / (2 * cells));
  std::vector<Interval> out;
  for (std::int64_t k : counts) out.push_back(Score(k, n, z * z));
  return out;
}

Tally Count(const std::vector<DropOutcome>& outcomes, std::size_t poses, double confidence) {
  Tally t;
  t.counts.assign(poses, 0);
  double time = 0;
  for (const DropOutcome& o : outcomes) {
    ++t.drops;
    if (o.pose == DropOutcome::kNotSettled) {
      ++t.not_settled;
      continue;
    }
    time += o.time;
    if (o.pose == DropOutcome::kOtherFace) {
      ++t.other_face;
    } else if (o.pose >= 0 && static_cast<std::size_t>(o.pose) < poses) {
      ++t.counts[static_cast<std::size_t>(o.pose)];
    } else {
      throw std::invalid_argument("tally: a drop's pose is not one of the estimate's");
    }
  }
  const std::int64_t settled = t.drops - t.not_settled;
  t.mean_time = settled > 0 ? time / static_cast<double>(settled) : 0;
  for (std::int64_t k : t.counts) t.binomial.push_back(BinomialInterval(k, t.drops, confidence));
  std::vector<std::int64_t> cells = t.counts;
  if (t.not_settled > 0) cells.push_back(t.not_settled);
  if (t.other_face > 0) cells.push_back(t.other_face);
  t.simultaneous = SimultaneousIntervals(cells, confidence);
  t.simultaneous.resize(poses);
  return t;
}

}  // namespace dynamics::poses
