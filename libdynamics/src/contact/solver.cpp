// The velocity solve of a contact step (solver.h).

#include "solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../integrators/integrator.h"

namespace dynamics::contact {
namespace {

// The normal and tangential effective masses of a row for the response matrix K.
void SetEffectiveMasses(Row& r, const Matrix3& K) {
  r.mass_n = 1.0 / r.n.dot(K * r.n);
  Eigen::Matrix2d Kt;
  Kt << r.t1.dot(K * r.t1), r.t1.dot(K * r.t2), r.t2.dot(K * r.t1), r.t2.dot(K * r.t2);
  r.mass_t = Kt.inverse();
}

double InvMass(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_mass[static_cast<std::size_t>(i)] : 0.0;
}
Matrix3 InvInertia(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_inertia[static_cast<std::size_t>(i)] : Matrix3::Zero().eval();
}

// One Gauss–Seidel update of a row: the normal impulse, then the friction.
void Update(Row& r, std::vector<Velocities>& vel, const BodyResponse& bodies, int frozen, double& change,
            double& scale) {
  // Normal: the least impulse that keeps the normal velocity at its target.
  const double vn = r.n.dot(RelativeVelocity(vel, r));
  const double ln = std::max(r.lambda_n + r.mass_n * (r.target - vn), 0.0);
  const double dn = ln - r.lambda_n;
  r.lambda_n = ln;
  ApplyImpulse(vel, bodies, r, r.n * dn, frozen);
  // Friction: the impulse that stops the point's sliding, within the cone μ λn. Within the
  // cone it holds (or comes to rest in this step); beyond it, a sliding contact takes μk λn
  // against its sliding, a holding one breaks away at the cone's edge.
  const Vector3 rel = RelativeVelocity(vel, r);
  const Eigen::Vector2d vt(r.t1.dot(rel), r.t2.dot(rel));
  const Eigen::Vector2d stop = r.lambda_t - r.mass_t * vt;
  const double bound = r.mu * r.lambda_n;
  Eigen::Vector2d lt = stop;
  if (stop.norm() > bound) {
    lt = r.sliding ? Eigen::Vector2d(-bound * r.slip_direction) : Eigen::Vector2d(stop * (bound / stop.norm()));
  }
  const Eigen::Vector2d dt = lt - r.lambda_t;
  r.lambda_t = lt;
  ApplyImpulse(vel, bodies, r, r.t1 * dt[0] + r.t2 * dt[1], frozen);
  change = std::max({change, std::abs(dn), dt.norm()});
  scale = std::max({scale, r.lambda_n, lt.norm()});
}

}  // namespace

Vector3 RelativeVelocity(const std::vector<Velocities>& vel, const Row& r) {
  const Velocities& va = vel[static_cast<std::size_t>(r.a)];
  Vector3 v = va.v + va.w.cross(r.ra);
  if (r.b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(r.b)];
    v -= vb.v + vb.w.cross(r.rb);
  }
  return v;
}

void ApplyImpulse(std::vector<Velocities>& vel, const BodyResponse& bodies, const Row& r, const Vector3& impulse,
                  int frozen) {
  if (r.a != frozen) {
    Velocities& va = vel[static_cast<std::size_t>(r.a)];
    va.v += InvMass(bodies, r.a) * impulse;
    va.w += bodies.inv_inertia[static_cast<std::size_t>(r.a)] * r.ra.cross(impulse);
  }
  if (r.b >= 0 && r.b != frozen) {
    Velocities& vb = vel[static_cast<std::size_t>(r.b)];
    vb.v -= InvMass(bodies, r.b) * impulse;
    vb.w -= bodies.inv_inertia[static_cast<std::size_t>(r.b)] * r.rb.cross(impulse);
  }
}

void PrepareRows(std::vector<Row>& rows, const ContactCache& cache, const std::vector<Velocities>& vel,
                 const BodyResponse& bodies, double slow) {
  for (Row& r : rows) {
    const Vector3 helper = std::abs(r.n.x()) < 0.6 ? Vector3::UnitX() : Vector3::UnitY();
    r.t1 = r.n.cross(helper).normalized();
    r.t2 = r.n.cross(r.t1);
    // K = (1/ma + 1/mb) E − [ra]× Ia⁻¹ [ra]× − [rb]× Ib⁻¹ [rb]×: the point's response to an impulse.
    const Matrix3 Sa = internal::Skew(r.ra), Sb = internal::Skew(r.rb);
    r.Ka = InvMass(bodies, r.a) * Matrix3::Identity() - Sa * InvInertia(bodies, r.a) * Sa;
    r.Kb = InvMass(bodies, r.b) * Matrix3::Identity() - Sb * InvInertia(bodies, r.b) * Sb;
    SetEffectiveMasses(r, r.Ka + r.Kb);
    // Static or kinetic: a contact that held last step (or a new one whose points barely slide)
    // holds while its friction stays within μs; one that slid slides at μk until it stops.
    const auto it = cache.find(r.key);
    bool stuck;
    if (it != cache.end()) {
      r.lambda_n = it->second.lambda_n;
      r.lambda_t = it->second.lambda_t;
      stuck = it->second.stuck;
    } else {
      const Vector3 rel = RelativeVelocity(vel, r);
      stuck = (rel - r.n * r.n.dot(rel)).norm() <= slow;
    }
    r.mu = stuck ? r.mu_s : r.mu_k;
    if (!stuck) {
      // Friction opposes the sliding: its direction at the start of the step, kept through the
      // iterations (the direction of the impulse that would stop the point is tilted by the
      // body's rotation, and following the changing velocity would not converge).
      const Vector3 rel = RelativeVelocity(vel, r);
      const Eigen::Vector2d vt(r.t1.dot(rel), r.t2.dot(rel));
      r.sliding = vt.norm() > 0;
      if (r.sliding) r.slip_direction = vt / vt.norm();
    }
  }
}

int SolveImpulses(std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                  const std::vector<int>& body_level, int max_iterations, double tolerance) {
  constexpr int kNone = std::numeric_limits<int>::max();
  int max_level = -1;
  for (Row& r : rows) {
    const int la = body_level[static_cast<std::size_t>(r.a)];
    r.level = r.b < 0 ? la : std::min(la, body_level[static_cast<std::size_t>(r.b)]);
    if (r.level != kNone) max_level = std::max(max_level, r.level);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return x.level < y.level; });
  // Warm start, then iterate until no impulse changes.
  for (const Row& r : rows)
    ApplyImpulse(vel, bodies, r, r.n * r.lambda_n + r.t1 * r.lambda_t[0] + r.t2 * r.lambda_t[1]);
  // Sweeps from the ground up, then back down (symmetric Gauss-Seidel carries a load through a
  // stack in both directions), until no impulse changes.
  int iteration = 0;
  for (; iteration < max_iterations; ++iteration) {
    double change = 0, scale = 0;
    if (iteration % 2 == 0) {
      for (Row& r : rows) Update(r, vel, bodies, -1, change, scale);
    } else {
      for (auto it = rows.rbegin(); it != rows.rend(); ++it) Update(*it, vel, bodies, -1, change, scale);
    }
    if (change <= tolerance * scale) {
      ++iteration;
      break;
    }
  }
  if (iteration < max_iterations) return iteration;
  // Shock propagation (Guendelman, Bridson & Fedkiw 2003): level by level from the ground up,
  // each body's contacts with the level below are solved with the lower body held still, so
  // what the iterations left of a resting stack's velocities does not survive the step.
  for (int level = 0; level <= max_level; ++level) {
    for (int pass = 0; pass < max_iterations; ++pass) {
      double change = 0, scale = 0;
      for (Row& r : rows) {
        if (r.level != level) continue;
        const int la = body_level[static_cast<std::size_t>(r.a)];
        const int lb = r.b >= 0 ? body_level[static_cast<std::size_t>(r.b)] : -1;
        if (la == lb) continue;
        const int frozen = la < lb ? r.a : r.b;
        const Row saved = r;
        SetEffectiveMasses(r, frozen == r.a ? r.Kb : r.Ka);
        Update(r, vel, bodies, frozen, change, scale);
        r.mass_n = saved.mass_n;
        r.mass_t = saved.mass_t;
      }
      if (change <= tolerance * scale) break;
    }
  }
  return iteration;
}

void StoreImpulses(const std::vector<Row>& rows, ContactCache& cache) {
  for (const Row& r : rows) {
    // On the cone's surface: it slides (or just broke away); inside: it holds.
    const bool stuck = r.lambda_t.norm() < r.mu * r.lambda_n * (1 - 1e-9) || r.lambda_n == 0;
    cache[r.key] = {r.lambda_n, r.lambda_t, stuck};
  }
}

}  // namespace dynamics::contact
