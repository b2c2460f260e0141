// ManifoldCache (manifold_cache.h): pairs' contact points kept in the first shape's frame.

#include "manifold_cache.h"

#include <algorithm>
#include <tuple>

namespace dynamics::contact {

namespace {

bool Before(const KeptManifold& m, int a, int b) { return std::tie(m.a, m.b) < std::tie(a, b); }

// b's pose in a's frame.
void Relative(const Posed& pa, const Posed& pb, Matrix3& R, Vector3& t) {
  R = pa.R.transpose() * pb.R;
  t = pa.R.transpose() * (pb.t - pa.t);
}

}  // namespace

const KeptManifold* ManifoldCache::Find(int a, int b) const {
  const auto it =
      std::lower_bound(kept_.begin(), kept_.end(), 0, [&](const KeptManifold& m, int) { return Before(m, a, b); });
  return it != kept_.end() && it->a == a && it->b == b ? &*it : nullptr;
}

bool ManifoldCache::Reuse(int a, int b, const Posed& pa, const Posed& pb, double radius_b, double margin, double gate,
                          std::vector<ContactPoint>& out) {
  const KeptManifold* m = Find(a, b);
  if (m == nullptr) return false;
  Matrix3 R;
  Vector3 t;
  Relative(pa, pb, R, t);
  // A point q of b within radius_b of its origin has moved by |(R − R₀) q + t − t₀| ≤ this in a's
  // frame (the Frobenius norm bounds the spectral one).
  const double moved = (t - m->t).norm() + (R - m->R).norm() * radius_b;
  if (!(moved <= gate) || !(margin + moved <= m->margin)) return false;
  for (std::uint32_t i = m->first; i < m->first + m->count; ++i) {
    const KeptPoint& k = points_[i];
    const Vector3 delta = R * k.at_b + t - k.at_a;  // how far b's point has moved, in a's frame
    const double separation = k.separation - k.normal_a.dot(delta);
    if (!(separation < margin)) continue;
    out.push_back({pa.R * k.at_a + pa.t, pa.R * k.normal_a, separation, k.feature, k.material_a, k.material_b});
  }
  KeptManifold again = *m;  // kept as it was found: the gate stays on the motion since then
  again.first = static_cast<std::uint32_t>(next_points_.size());
  next_points_.insert(next_points_.end(), points_.begin() + m->first, points_.begin() + m->first + m->count);
  next_.push_back(again);
  return true;
}

void ManifoldCache::Keep(int a, int b, const Posed& pa, const Posed& pb, double wide_margin,
                         const std::vector<ContactPoint>& found) {
  KeptManifold m;
  m.a = a;
  m.b = b;
  Relative(pa, pb, m.R, m.t);
  m.margin = wide_margin;
  m.first = static_cast<std::uint32_t>(next_points_.size());
  m.count = static_cast<std::uint32_t>(found.size());
  const Matrix3 to_a = pa.R.transpose();
  for (const ContactPoint& p : found) {
    KeptPoint k;
    k.at_a = to_a * (p.point - pa.t);
    k.at_b = m.R.transpose() * (k.at_a - m.t);
    k.normal_a = to_a * p.normal;
    k.separation = p.separation;
    k.feature = p.feature;
    k.material_a = p.material_a;
    k.material_b = p.material_b;
    next_points_.push_back(k);
  }
  next_.push_back(m);
}

void ManifoldCache::Flip() {
  std::sort(next_.begin(), next_.end(),
            [](const KeptManifold& x, const KeptManifold& y) { return Before(x, y.a, y.b); });
  std::swap(kept_, next_);
  std::swap(points_, next_points_);
  next_.clear();
  next_points_.clear();
}

void ManifoldCache::Clear() {
  kept_.clear();
  next_.clear();
  points_.clear();
  next_points_.clear();
}

}  // namespace dynamics::contact
