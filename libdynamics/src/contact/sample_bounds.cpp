// The mesh pairs' kept bounds from step to step (sample_bounds.h).

#include "sample_bounds.h"

#include <algorithm>
#include <utility>

namespace dynamics::contact {
namespace {

bool Before(const PairSampleBounds& x, int a, int b) { return x.a < a || (x.a == a && x.b < b); }

}  // namespace

void SampleBoundsCache::Begin(std::size_t pairs) {
  next_.clear();
  next_.reserve(pairs);
}

PairSampleBounds* SampleBoundsCache::Slot(int a, int b) {
  auto it = std::lower_bound(
      kept_.begin(), kept_.end(), std::make_pair(a, b),
      [](const PairSampleBounds& x, const std::pair<int, int>& key) { return Before(x, key.first, key.second); });
  if (it != kept_.end() && it->a == a && it->b == b) {
    next_.push_back(std::move(*it));
    it->of[0].valid = it->of[1].valid = false;  // (moved out: empty if asked for again)
  } else {
    next_.emplace_back();
    next_.back().a = a, next_.back().b = b;
  }
  return &next_.back();
}

void SampleBoundsCache::Flip() {
  std::sort(next_.begin(), next_.end(),
            [](const PairSampleBounds& x, const PairSampleBounds& y) { return Before(x, y.a, y.b); });
  std::swap(kept_, next_);
  next_.clear();
}

}  // namespace dynamics::contact
