// Contact patches: rows grouped by pair and normal, each patch's anchor and torsion radius, its
// warm start and friction state from the last step, and the cache for the next (solver.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "../integrators/integrator.h"
#include "solver_internal.h"

namespace dynamics::contact {
namespace {

// The tangent directions of a normal.
void Tangents(const Vector3& n, Vector3& t1, Vector3& t2) {
  const Vector3 helper = std::abs(n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
  t1 = n.cross(helper).normalized();
  t2 = n.cross(t1);
}

// ∫|x| over the triangle (0, P, Q) in the plane, signed by its orientation (so that a fan about
// any point sums to the polygon's): in polar form ∫ρ(φ)³/3 dφ with ρ = d / cos φ, d the distance
// of the edge's line.
double EdgeMoment(const Eigen::Vector2d& P, const Eigen::Vector2d& Q) {
  const Eigen::Vector2d e = Q - P;
  const double len = e.norm();
  if (!(len > 0)) return 0;
  const Eigen::Vector2d u = e / len;
  const double cross = u.y() * P.x() - u.x() * P.y();  // > 0: (0, P, Q) counter-clockwise
  const double d = std::abs(cross);
  if (!(d > 1e-15 * len)) return 0;
  auto F = [d](double s) { return d / 6 * (s * std::hypot(d, s) + d * d * std::asinh(s / d)); };
  return std::copysign(F(Q.dot(u)) - F(P.dot(u)), cross);
}

// The anchor (world) and torsion radius of a patch's points (rows warm-started). `rho_known`:
// the points are those of a cached patch, carried rigidly, whose radius `rho` already holds (the
// outline is needed then only for an anchor without load).
void Outline(const std::vector<Row>& rows, const Patch& p, Vector3& anchor, double& rho, bool rho_known,
             SolveScratch& scratch) {
  std::vector<Eigen::Vector2d>& q = scratch.points;
  q.clear();
  double height = 0, extent = 0, load = 0;
  Eigen::Vector2d pressure = Eigen::Vector2d::Zero();  // Σ λn q
  for (int i = p.first; i < p.first + p.count; ++i) {
    const Row& r = rows[static_cast<std::size_t>(i)];
    q.emplace_back(p.t1.dot(r.point), p.t2.dot(r.point));
    height += p.n.dot(r.point);
    pressure += r.lambda_n * q.back();
    load += r.lambda_n;
  }
  height /= p.count;
  if (rho_known && load > 0) {
    const Eigen::Vector2d c2 = pressure / load;
    anchor = p.t1 * c2.x() + p.t2 * c2.y() + p.n * height;
    return;
  }
  // The convex outline (Andrew's monotone chain), counter-clockwise.
  std::sort(q.begin(), q.end(),
            [](const auto& x, const auto& y) { return x.x() < y.x() || (x.x() == y.x() && x.y() < y.y()); });
  for (const auto& x : q) extent = std::max(extent, (x - q.front()).norm());
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d>& hull = scratch.hull;
  hull.clear();
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = hull.size();
    for (std::size_t k = 0; k < q.size(); ++k) {
      const Eigen::Vector2d& x = pass == 0 ? q[k] : q[q.size() - 1 - k];
      while (hull.size() >= start + 2 && turn(hull[hull.size() - 2], hull.back(), x) <= 0) hull.pop_back();
      hull.push_back(x);
    }
    hull.pop_back();
  }
  double area = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Eigen::Vector2d& x = hull[k];
    const Eigen::Vector2d& y = hull[(k + 1) % hull.size()];
    const double c = x.x() * y.y() - x.y() * y.x();
    area += c / 2;
    centroid += (x + y) * (c / 6);
  }
  Eigen::Vector2d c2;
  if (hull.size() >= 3 && area > 1e-4 * extent * extent) {
    c2 = centroid / area;
    double moment = 0, farthest = 0;
    for (std::size_t k = 0; k < hull.size(); ++k) {
      moment += EdgeMoment(hull[k] - c2, hull[(k + 1) % hull.size()] - c2);
      farthest = std::max(farthest, (hull[k] - c2).norm());
    }
    rho = std::clamp(moment / area, 0.0, farthest);
  } else if (extent > 0) {  // the points lie on a segment: its farthest pair
    Eigen::Vector2d x = q.front(), y = q.front();
    double best = -1;
    for (const auto& s : q) {
      for (const auto& t : q) {
        if ((s - t).squaredNorm() > best) {
          best = (s - t).squaredNorm();
          x = s;
          y = t;
        }
      }
    }
    c2 = (x + y) / 2;
    rho = std::sqrt(best) / 4;
  } else {
    c2 = q.front();
    rho = 0;
  }
  // The anchor: the centre of pressure of the last step's normal impulses (which the moments
  // about the tangent axes determine, however the load is shared among the points), else the
  // outline's centroid. The torsion radius is the uniform-pressure one about the centroid.
  if (load > 0) c2 = pressure / load;
  anchor = p.t1 * c2.x() + p.t2 * c2.y() + p.n * height;
}

}  // namespace

void PreparePatches(std::vector<Row>& rows, const ContactCache& cache, const std::vector<Velocities>& vel,
                    const BodyResponse& bodies, double slow, std::vector<Patch>& patches, SolveScratch& scratch) {
  const double same = std::cos(kPatchAngle);
  // Each row's normal effective mass and warm start.
  for (Row& r : rows) {
    SetRowJacobian(r, bodies);
    if (const CachedRow* cached = cache.FindRow(r.key)) r.lambda_n = cached->lambda_n;
  }
  patches.clear();
  std::vector<Row>& sorted = scratch.sorted;
  std::vector<const Row*>& leaders = scratch.leaders;  // each patch's first row
  std::vector<int>& patch_of = scratch.patch_of;
  std::vector<char>& used = scratch.used;
  for (std::size_t first = 0; first < rows.size();) {
    // The pair's rows: [first, last).
    const auto pair = std::pair{std::get<0>(rows[first].key), std::get<1>(rows[first].key)};
    std::size_t last = first;
    while (last < rows.size() && std::pair{std::get<0>(rows[last].key), std::get<1>(rows[last].key)} == pair) ++last;
    // Its patches: each row joins the first patch whose first normal agrees with its own and
    // whose friction is its own (a compound's parts may differ); the rows are reordered patch by
    // patch.
    leaders.clear();
    patch_of.clear();
    for (std::size_t i = first; i < last; ++i) {
      std::size_t k = 0;
      while (k < leaders.size() && (leaders[k]->n.dot(rows[i].n) < same || leaders[k]->mu_s != rows[i].mu_s ||
                                    leaders[k]->mu_k != rows[i].mu_k)) {
        ++k;
      }
      if (k == leaders.size()) leaders.push_back(&rows[i]);
      patch_of.push_back(static_cast<int>(k));
    }
    sorted.clear();
    const auto found = cache.FindPatches(pair);  // (first, count)
    used.assign(found.second, 0);
    for (std::size_t k = 0; k < leaders.size(); ++k) {
      Patch& p = patches.emplace_back();  // (in place: a patch is 1.4 KB)
      p.first = static_cast<int>(first + sorted.size());
      Vector3 sum = Vector3::Zero();
      for (std::size_t i = first; i < last; ++i) {
        if (patch_of[i - first] != static_cast<int>(k)) continue;
        sorted.push_back(rows[i]);
        sum += rows[i].n;
      }
      p.count = static_cast<int>(first + sorted.size()) - p.first;
      const Row& r0 = sorted[static_cast<std::size_t>(p.first) - first];
      p.a = r0.a;
      p.b = r0.b;
      p.mu_s = r0.mu_s;
      p.mu_k = r0.mu_k;
      p.n = sum.normalized();
      Tangents(p.n, p.t1, p.t2);
    }
    std::copy(sorted.begin(), sorted.end(), rows.begin() + static_cast<std::ptrdiff_t>(first));
    // Each patch's anchor, effective masses, warm start and friction state.
    for (std::size_t k = patches.size() - leaders.size(); k < patches.size(); ++k) {
      Patch& p = patches[k];
      // The patch it was last step: the cached patch of one of its rows (by the rows' feature
      // keys, as a contact is known step after step); none: a new patch.
      std::size_t best = used.size();
      for (int i = p.first; i < p.first + p.count && best == used.size(); ++i) {
        const CachedRow* cached = cache.FindRow(rows[static_cast<std::size_t>(i)].key);
        if (cached != nullptr && cached->patch >= 0 && !used[static_cast<std::size_t>(cached->patch)]) {
          best = static_cast<std::size_t>(cached->patch);
        }
      }
      // Else (its points all new: a clipped manifold's corners move along the edges) the pair's
      // unmatched cached patch whose normal is nearest, within kPatchAngle.
      if (best == used.size()) {
        for (std::size_t c = 0; c < used.size(); ++c) {
          const double dot = found.first[c].patch.n.dot(p.n);
          if (!used[c] && dot >= same && (best == used.size() || dot > found.first[best].patch.n.dot(p.n))) best = c;
        }
      }
      // Its points kept from the step before, and all of them that patch's: the same outline.
      bool same_outline = best < used.size() && found.first[best].patch.rows == p.count;
      for (int i = p.first; i < p.first + p.count && same_outline; ++i) {
        const Row& r = rows[static_cast<std::size_t>(i)];
        const CachedRow* cached = r.kept ? cache.FindRow(r.key) : nullptr;
        same_outline = cached != nullptr && cached->patch == static_cast<int>(best);
      }
      if (same_outline) p.rho = found.first[best].patch.rho;
      Vector3& anchor = p.anchor;
      Outline(rows, p, anchor, p.rho, same_outline, scratch);
      const Row& r0 = rows[static_cast<std::size_t>(p.first)];
      p.ra = anchor - (r0.point - r0.ra);
      p.rb = p.b >= 0 ? Vector3(anchor - (r0.point - r0.rb)) : Vector3::Zero();
      SetPatchJacobian(p, bodies);
      SetNormalBlock(p, rows);
      const Vector3 g = PatchVelocity(vel, p);
      bool stuck;
      if (best < used.size()) {
        used[best] = 1;
        const CachedPatch& c = found.first[best].patch;
        p.lambda = Vector3(p.t1.dot(c.force), p.t2.dot(c.force), p.rho > 0 ? c.torque / p.rho : 0.0);
        stuck = c.stuck;
      } else {
        stuck = g.norm() <= slow;
      }
      p.mu = stuck ? p.mu_s : p.mu_k;
      // Sliding: its anchor follows the centre of pressure through the iterations.
      p.sliding = !stuck && g.norm() > 0;
    }
    first = last;
  }
}

void StoreImpulses(const std::vector<Row>& rows, const std::vector<Patch>& patches, ContactCache& cache,
                   SolveScratch& scratch) {
  auto pair_of = [&](const Patch& p) {
    const RowKey& key = rows[static_cast<std::size_t>(p.first)].key;
    return ContactCache::Pair{std::get<0>(key), std::get<1>(key)};
  };
  // Each touching patch's index among its pair's cached patches: after those the cache kept, in
  // the patches' order. Not touching yet (a speculative contact): no cached patch; whether it
  // holds is decided when it touches, by how fast it slides then.
  std::vector<double>& load = scratch.load;
  std::vector<std::size_t>& by_pair = scratch.by_pair;
  load.resize(patches.size());
  by_pair.resize(patches.size());
  for (std::size_t k = 0; k < patches.size(); ++k) {
    load[k] = Load(patches[k], rows);
    by_pair[k] = k;
  }
  std::sort(by_pair.begin(), by_pair.end(), [&](std::size_t x, std::size_t y) {
    const ContactCache::Pair px = pair_of(patches[x]), py = pair_of(patches[y]);
    return px != py ? px < py : x < y;
  });
  std::vector<int>& index = scratch.index;
  index.assign(patches.size(), -1);
  for (std::size_t at = 0; at < by_pair.size();) {
    const ContactCache::Pair pair = pair_of(patches[by_pair[at]]);
    int next = static_cast<int>(cache.FindPatches(pair).second);
    for (; at < by_pair.size() && pair_of(patches[by_pair[at]]) == pair; ++at) {
      if (load[by_pair[at]] > 0) index[by_pair[at]] = next++;
    }
  }
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const Patch& p = patches[k];
    if (index[k] >= 0) {
      // On the limit: it slides (or just broke away); inside: it holds.
      const bool stuck = p.lambda.norm() < p.mu * load[k] * (1 - 1e-9);
      cache.AddPatch(pair_of(p), index[k],
                     {p.n, p.t1 * p.lambda[0] + p.t2 * p.lambda[1], p.rho * p.lambda[2], stuck, p.rho, p.count});
    }
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      cache.SetRow(r.key, {r.lambda_n, index[k]});
    }
  }
  cache.Finish();
}

const CachedRow* ContactCache::FindRow(const RowKey& key) const {
  const auto end = rows_.begin() + static_cast<std::ptrdiff_t>(sorted_rows_);
  const auto it =
      std::lower_bound(rows_.begin(), end, key, [](const RowEntry& e, const RowKey& k) { return e.key < k; });
  return it != end && it->key == key ? &it->row : nullptr;
}

std::pair<const ContactCache::PatchEntry*, std::size_t> ContactCache::FindPatches(const Pair& pair) const {
  const auto end = patches_.begin() + static_cast<std::ptrdiff_t>(sorted_patches_);
  const auto lo =
      std::lower_bound(patches_.begin(), end, pair, [](const PatchEntry& e, const Pair& p) { return e.pair < p; });
  const auto hi = std::upper_bound(lo, end, pair, [](const Pair& p, const PatchEntry& e) { return p < e.pair; });
  return {lo == hi ? nullptr : &*lo, static_cast<std::size_t>(hi - lo)};
}

void ContactCache::Finish() {
  // std::sort with the order as the tie-break: stable, and no buffer to allocate.
  std::sort(rows_.begin(), rows_.end(),
            [](const RowEntry& x, const RowEntry& y) { return x.key != y.key ? x.key < y.key : x.order < y.order; });
  std::size_t out = 0;
  for (std::size_t i = 0; i < rows_.size(); ++i) {  // of equal keys, the last set
    if (i + 1 < rows_.size() && rows_[i + 1].key == rows_[i].key) continue;
    rows_[out++] = rows_[i];
  }
  rows_.resize(out);
  std::sort(patches_.begin(), patches_.end(), [](const PatchEntry& x, const PatchEntry& y) {
    if (x.pair != y.pair) return x.pair < y.pair;
    return x.index != y.index ? x.index < y.index : x.order < y.order;
  });
  out = 0;
  for (std::size_t i = 0; i < patches_.size(); ++i) {  // of a repeated (pair, index), the first
    if (out > 0 && patches_[out - 1].pair == patches_[i].pair && patches_[out - 1].index == patches_[i].index) continue;
    patches_[out++] = patches_[i];
  }
  patches_.resize(out);
  sorted_rows_ = rows_.size();
  sorted_patches_ = patches_.size();
}

}  // namespace dynamics::contact
