// The velocity solve of a contact step (solver.h).

#include "solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "../integrators/integrator.h"
#include "workers.h"

namespace dynamics::contact {
namespace {

double InvMass(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_mass[static_cast<std::size_t>(i)] : 0.0;
}
Matrix3 InvInertia(const BodyResponse& bodies, int i) {
  return i >= 0 ? bodies.inv_inertia[static_cast<std::size_t>(i)] : Matrix3::Zero().eval();
}

// K = (1/m) E − [r]× I⁻¹ [r]×: a body's share of a point's response to an impulse at r.
Matrix3 PointResponse(const BodyResponse& bodies, int i, const Vector3& r) {
  const Matrix3 S = internal::Skew(r);
  return InvMass(bodies, i) * Matrix3::Identity() - S * InvInertia(bodies, i) * S;
}

// Jointed bodies: the response of a's generalized directions Wa (columns of wrenches on a) minus
// b's to impulses along them (+ on a, − on b): Waᵀ G_aa Wa + Wbᵀ G_bb Wb − Waᵀ G_ab Wb − Wbᵀ G_ba Wa.
template <int N>
Eigen::Matrix<double, N, N> CoupledResponse(const Coupling& c, int a, int b, const Eigen::Matrix<double, 6, N>& Wa,
                                            const Eigen::Matrix<double, 6, N>& Wb) {
  Eigen::Matrix<double, N, N> K = Wa.transpose() * c.Response(a, a) * Wa;
  if (b >= 0) {
    K += Wb.transpose() * c.Response(b, b) * Wb;
    if (c.Joined(a, b)) {
      K -= Wa.transpose() * c.Response(a, b) * Wb;
      K -= Wb.transpose() * c.Response(b, a) * Wa;
    }
  }
  return K;
}

// A row's effective masses and Jacobian.
void SetRowJacobian(Row& r, const BodyResponse& bodies) {
  if (bodies.coupling != nullptr) {
    r.coupling = bodies.coupling;
    r.ang_a = r.ra.cross(r.n);
    r.ang_b = r.b >= 0 ? Vector3(r.rb.cross(r.n)) : Vector3::Zero();
    r.Ka.setZero();  // (the point responses serve shock propagation, which leaves jointed bodies out)
    r.Kb.setZero();
    r.mass_n = 1.0 / r.coupling->NormalResponse(r);
    return;
  }
  r.Ka = PointResponse(bodies, r.a, r.ra);
  r.Kb = PointResponse(bodies, r.b, r.rb);
  r.mass_n = 1.0 / r.n.dot((r.Ka + r.Kb) * r.n);
  r.inv_mass_a = InvMass(bodies, r.a);
  r.inv_mass_b = InvMass(bodies, r.b);
  r.ang_a = r.ra.cross(r.n);
  r.turn_a = InvInertia(bodies, r.a) * r.ang_a;
  if (r.b >= 0) {
    r.ang_b = r.rb.cross(r.n);
    r.turn_b = InvInertia(bodies, r.b) * r.ang_b;
  }
}

// The effective mass of a patch's friction, K⁻¹ (the tangential 2 × 2 block's alone when the patch
// has no torsion radius).
Matrix3 PatchMass(const Matrix3& K, double rho) {
  if (rho > 0) return K.inverse();
  Matrix3 m = Matrix3::Zero();
  m.topLeftCorner<2, 2>() = K.topLeftCorner<2, 2>().inverse();
  return m;
}

// A patch's Jacobian and effective masses at its anchor (ra, rb): generalized directions (t1, t2
// at r; ρ n as a turn), each body's K_ij = (1/m) d_i·d_j + a_i·I⁻¹ a_j.
void SetPatchJacobian(Patch& p, const BodyResponse& bodies) {
  if (bodies.coupling != nullptr) {
    p.coupling = bodies.coupling;
    auto directions = [&](const Vector3& r, Matrix3& ang) {
      ang.col(0) = r.cross(p.t1);
      ang.col(1) = r.cross(p.t2);
      ang.col(2) = p.rho * p.n;
      Eigen::Matrix<double, 6, 3> W;
      W.topRows<3>() << p.t1, p.t2, Vector3::Zero();
      W.bottomRows<3>() = ang;
      return W;
    };
    const Eigen::Matrix<double, 6, 3> Wa = directions(p.ra, p.ang_a);
    Eigen::Matrix<double, 6, 3> Wb = Eigen::Matrix<double, 6, 3>::Zero();
    if (p.b >= 0) {
      Wb = directions(p.rb, p.ang_b);
    } else {
      p.ang_b.setZero();
    }
    p.Ka = CoupledResponse<3>(*p.coupling, p.a, p.b, Wa, Wb);
    // A tree may not move a point along every direction (a hinge's bob not along its axis): the
    // response is then singular there, and so is the relative velocity, which no impulse
    // changes. A regularization of 10⁻⁹ of the largest response keeps the inverse finite.
    p.Ka.diagonal().array() += 1e-9 * p.Ka.diagonal().maxCoeff();
    p.Kb.setZero();
    p.mass = PatchMass(p.Ka, p.rho);
    return;
  }
  p.inv_mass_a = InvMass(bodies, p.a);
  p.inv_mass_b = InvMass(bodies, p.b);
  auto side = [&](int i, const Vector3& r, double inv_mass, Matrix3& ang, Matrix3& turn, Matrix3& K) {
    ang.col(0) = r.cross(p.t1);
    ang.col(1) = r.cross(p.t2);
    ang.col(2) = p.rho * p.n;
    turn = InvInertia(bodies, i) * ang;
    K = ang.transpose() * turn;
    K(0, 0) += inv_mass;
    K(1, 1) += inv_mass;
  };
  side(p.a, p.ra, p.inv_mass_a, p.ang_a, p.turn_a, p.Ka);
  if (p.b >= 0) {
    side(p.b, p.rb, p.inv_mass_b, p.ang_b, p.turn_b, p.Kb);
  } else {
    p.ang_b.setZero();
    p.turn_b.setZero();
    p.Kb.setZero();
  }
  p.mass = PatchMass(p.Ka + p.Kb, p.rho);
}

// The patch's generalized sliding velocity: (v·t1, v·t2, ρ ω·n) at its anchor.
Vector3 PatchVelocity(const std::vector<Velocities>& vel, const Patch& p) {
  const Velocities& va = vel[static_cast<std::size_t>(p.a)];
  Vector3 v = va.v;
  Vector3 g = p.ang_a.transpose() * va.w;
  if (p.b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(p.b)];
    v -= vb.v;
    g -= p.ang_b.transpose() * vb.w;
  }
  g[0] += p.t1.dot(v);
  g[1] += p.t2.dot(v);
  return g;
}

void ApplyPatch(std::vector<Velocities>& vel, const Patch& p, const Vector3& d, int frozen) {
  const Vector3 f = p.t1 * d[0] + p.t2 * d[1];
  if (p.coupling != nullptr) {
    p.coupling->Apply(vel, p.a, f, p.ang_a * d);
    if (p.b >= 0) p.coupling->Apply(vel, p.b, -f, -(p.ang_b * d));
    return;
  }
  if (p.a != frozen) {
    Velocities& va = vel[static_cast<std::size_t>(p.a)];
    va.v += p.inv_mass_a * f;
    va.w += p.turn_a * d;
  }
  if (p.b >= 0 && p.b != frozen) {
    Velocities& vb = vel[static_cast<std::size_t>(p.b)];
    vb.v -= p.inv_mass_b * f;
    vb.w -= p.turn_b * d;
  }
}

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

// The anchor (world) and torsion radius of a patch's points (rows warm-started).
void Outline(const std::vector<Row>& rows, const Patch& p, Vector3& anchor, double& rho) {
  std::vector<Eigen::Vector2d> q;
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
  // The convex outline (Andrew's monotone chain), counter-clockwise.
  std::sort(q.begin(), q.end(),
            [](const auto& x, const auto& y) { return x.x() < y.x() || (x.x() == y.x() && x.y() < y.y()); });
  for (const auto& x : q) extent = std::max(extent, (x - q.front()).norm());
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull;
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

// One Gauss–Seidel update of a row's normal impulse: the least that keeps its normal velocity
// at its target.
void UpdateNormal(Row& r, std::vector<Velocities>& vel, int frozen, double mass_n, Progress& progress) {
  const double vn = NormalSpeed(vel, r);
  const double ln = std::max(r.lambda_n + mass_n * (r.target - vn), 0.0);
  const double dn = ln - r.lambda_n;
  r.lambda_n = ln;
  ApplyNormal(vel, r, dn, frozen);
  progress.change = std::max(progress.change, std::abs(dn));
  progress.scale = std::max(progress.scale, ln);
  progress.speed = std::max(progress.speed, std::abs(dn) / mass_n);
}

// The impulse nearest `target` in the metric of the response K (the one that leaves the least
// kinetic energy) within the ball |λ| ≤ bound, over the first `dim` components: Coulomb's
// maximal dissipation, the friction then opposing the patch's sliding at the end of the update.
// On the ball's surface λ(ν) = (K + ν E)⁻¹ K target with ν ≥ 0 such that |λ| = bound (a
// trust-region step: Newton on 1/|λ(ν)| − 1/bound, which is nearly linear in ν).
Vector3 ProjectOntoBall(const Matrix3& K, const Vector3& target, double bound, int dim, double& nu_guess) {
  if (!(bound > 0)) return Vector3::Zero();
  Matrix3 Kd = K;
  if (dim == 2) {
    Kd.row(2).setZero();
    Kd.col(2).setZero();
    Kd(2, 2) = 1;
  }
  const Vector3 Kt = Kd * target;
  // x(ν) = (K + ν E)⁻¹ K t, d|x|²/dν = −2 xᵀ (K + ν E)⁻¹ x: a 3 × 3 inverse an iteration.
  auto at = [&](double nu, Vector3& x, double& length, double& slope) {
    const Matrix3 inverse = (Kd + nu * Matrix3::Identity()).inverse();
    x = inverse * Kt;
    length = x.norm();
    slope = -2 * x.dot(inverse * x);
  };
  // Newton on φ(ν) = 1/|x| − 1/bound, φ' = −½ |x|⁻³ d|x|²/dν: nearly linear and concave, so from
  // below the root it approaches monotonically, and from above it lands below it. Started from
  // the ν of the patch's last projection (the sweeps change it little), else from 0 (x = t).
  double nu = nu_guess > 0 && std::isfinite(nu_guess) ? nu_guess : 0.0, length = 0, slope = 0;
  Vector3 x;
  at(nu, x, length, slope);
  for (int k = 0; k < 50; ++k) {
    const double phi = 1 / length - 1 / bound, dphi = -0.5 * slope / (length * length * length);
    if (std::abs(phi) * bound <= 1e-12 || !(dphi > 0) || !std::isfinite(dphi)) break;
    const double next = nu - phi / dphi;
    nu = next > 0 ? next : nu * 1e-3;  // (ν ≥ 0: below 0 the ball holds x(0) = t already)
    at(nu, x, length, slope);
  }
  nu_guess = nu;
  if (!(length <= bound)) x *= bound / length;  // the last rounding (or a direction without response)
  if (dim == 2) x[2] = 0;
  return x;
}

// A patch's total normal impulse N, and (when `centre` is given) its centre of pressure
// Σ λn x / N (left as it is when N = 0).
double Load(const Patch& p, const std::vector<Row>& rows, Vector3* centre = nullptr) {
  double N = 0;
  Vector3 weighted = Vector3::Zero();
  for (int i = p.first; i < p.first + p.count; ++i) {
    const Row& r = rows[static_cast<std::size_t>(i)];
    N += r.lambda_n;
    if (centre != nullptr) weighted += r.lambda_n * r.point;
  }
  if (centre != nullptr && N > 0) *centre = weighted / N;
  return N;
}

// Moves a sliding patch's anchor to the centre of pressure of its rows' present normal impulses
// (kinetic friction so acts where the load is, as friction distributed over the points would: a
// sliding box does not yaw because its points are unevenly spread), carrying the friction impulse
// already applied along: off where it was, on where it now is. (A holding patch with three or
// more points holds the body whatever its anchor.)
void FollowPressure(Patch& p, std::vector<Velocities>& vel, const BodyResponse& bodies, int frozen, Vector3 centre) {
  centre += p.n * p.n.dot(p.anchor - centre);                                               // in the patch's plane
  if ((centre - p.anchor).squaredNorm() <= std::max(1e-24, 1e-16 * p.rho * p.rho)) return;  // within 10⁻⁸ ρ
  ApplyPatch(vel, p, -p.lambda, frozen);
  p.ra += centre - p.anchor;
  if (p.b >= 0) p.rb += centre - p.anchor;
  p.anchor = centre;
  SetPatchJacobian(p, bodies);
  ApplyPatch(vel, p, p.lambda, frozen);
}

// One update of a patch's friction: the impulse that stops its sliding and turning, if it lies
// within the limit μ N (the patch holds, or comes to rest in this step); else the impulse of
// least kinetic energy on the limit (μs: a holding patch breaks away; μk: a sliding one slides,
// opposing its sliding). With a body held still (shock propagation), only the other's response
// counts.
void UpdateFriction(Patch& p, const std::vector<Row>& rows, std::vector<Velocities>& vel, const BodyResponse& bodies,
                    int frozen, Progress& progress) {
  const bool follow = p.sliding && frozen < 0;
  Vector3 centre = p.anchor;
  const double N = Load(p, rows, follow ? &centre : nullptr);
  if (follow && N > 0) FollowPressure(p, vel, bodies, frozen, centre);
  const Matrix3 mass = frozen < 0 ? p.mass : PatchMass(frozen == p.a ? p.Kb : p.Ka, p.rho);
  const Vector3 g = PatchVelocity(vel, p);
  const Vector3 stop = p.lambda - mass * g;
  const double bound = p.mu * N;
  Vector3 lt = stop;
  if (stop.norm() > bound) {
    const Matrix3 K = frozen < 0 ? Matrix3(p.Ka + p.Kb) : (frozen == p.a ? p.Kb : p.Ka);
    lt = ProjectOntoBall(K, stop, bound, p.rho > 0 ? 3 : 2, p.nu);
  }
  const Vector3 d = lt - p.lambda;
  p.lambda = lt;
  ApplyPatch(vel, p, d, frozen);
  progress.change = std::max(progress.change, d.norm());
  progress.scale = std::max(progress.scale, lt.norm());
  const Matrix3 K = frozen < 0 ? Matrix3(p.Ka + p.Kb) : (frozen == p.a ? p.Kb : p.Ka);
  progress.speed = std::max(progress.speed, (K * d).norm());
}

// A patch's normals' coupled response (Patch::block).
void SetNormalBlock(Patch& p, const std::vector<Row>& rows) {
  p.block.setZero();
  if (p.count < 2 || p.count > 4) return;
  const Row* r = &rows[static_cast<std::size_t>(p.first)];
  if (p.coupling != nullptr) {
    Eigen::Matrix<double, 6, 4> Wa = Eigen::Matrix<double, 6, 4>::Zero(), Wb = Eigen::Matrix<double, 6, 4>::Zero();
    for (int i = 0; i < p.count; ++i) {
      Wa.col(i) << r[i].n, r[i].ang_a;
      if (p.b >= 0) Wb.col(i) << r[i].n, r[i].ang_b;
    }
    p.block = CoupledResponse<4>(*p.coupling, p.a, p.b, Wa, Wb);
    return;
  }
  for (int i = 0; i < p.count; ++i) {
    for (int j = 0; j < p.count; ++j) {
      const double nn = r[i].n.dot(r[j].n);
      double a = r[i].inv_mass_a * nn + r[i].ang_a.dot(r[j].turn_a);
      if (r[i].b >= 0) a += r[i].inv_mass_b * nn + r[i].ang_b.dot(r[j].turn_b);
      p.block(i, j) = a;
    }
  }
}

// A patch's normal impulses (2 to 4 points) solved together: the new impulses x ≥ 0 whose normal
// velocities w = A x − c reach their targets (w ≥ 0), complementary (x·w = 0), with A the points'
// coupled response — the linear complementarity problem of the patch alone, by trying the sets of
// loaded points, the most first. Four coplanar points make A singular (a rigid face's load is
// shared in infinitely many ways): a regularization of 10⁻⁹ of its diagonal picks the evenest
// sharing and misses each target by 10⁻⁹ of the change. Returns false where no set solves it
// (rounding), for the point-by-point update.
bool UpdateNormalBlock(Patch& p, std::vector<Row>& rows, std::vector<Velocities>& vel, Progress& progress) {
  const int m = p.count;
  if (m < 2 || m > 4) return false;
  const Eigen::Matrix4d& A = p.block;
  Eigen::Vector4d c = Eigen::Vector4d::Zero(), old = Eigen::Vector4d::Zero();
  Row* r = &rows[static_cast<std::size_t>(p.first)];
  for (int i = 0; i < m; ++i) old[i] = r[i].lambda_n;
  for (int i = 0; i < m; ++i) {
    c[i] = r[i].target - NormalSpeed(vel, r[i]) + A.row(i).head(m).dot(old.head(m));
  }
  const double scale = c.head(m).cwiseAbs().maxCoeff();
  Eigen::Vector4d x = Eigen::Vector4d::Zero();
  // One set of loaded points: their impulses solve their block (Cholesky, the regularization on
  // its diagonal), none negative, and the others' velocities reach their targets unloaded.
  auto try_set = [&](int set) {
    int index[4], k = 0;
    for (int i = 0; i < m; ++i) {
      if (set & (1 << i)) index[k++] = i;
    }
    double(&L)[4][4] = p.factor;
    if (p.factored != set) {
      p.factored = set;
      p.factor_ok = false;
      for (int i = 0; i < k; ++i) {
        for (int j = 0; j <= i; ++j) {
          double sum = A(index[i], index[j]) * (i == j ? 1 + 1e-9 : 1.0);
          for (int l = 0; l < j; ++l) sum -= L[i][l] * L[j][l];
          if (i == j) {
            if (!(sum > 0)) return false;  // singular beyond the regularization
            L[i][i] = std::sqrt(sum);
          } else {
            L[i][j] = sum / L[j][j];
          }
        }
      }
      p.factor_ok = true;
    }
    if (!p.factor_ok) return false;
    double y[4] = {};
    for (int i = 0; i < k; ++i) {
      double sum = c[index[i]];
      for (int l = 0; l < i; ++l) sum -= L[i][l] * y[l];
      y[i] = sum / L[i][i];
    }
    Eigen::Vector4d trial = Eigen::Vector4d::Zero();
    for (int i = k - 1; i >= 0; --i) {
      double sum = y[i];
      for (int l = i + 1; l < k; ++l) sum -= L[l][i] * trial[index[l]];
      trial[index[i]] = sum / L[i][i];
      if (!(trial[index[i]] >= 0)) return false;
    }
    for (int i = 0; i < m; ++i) {
      if (!(set & (1 << i)) && !(A.row(i).head(m).dot(trial.head(m)) - c[i] >= -1e-9 * scale)) return false;
    }
    x = trial;
    return true;
  };
  // The points loaded now first (the set rarely changes from sweep to sweep), then every set, the
  // most points first.
  static constexpr int kBySize[] = {15, 14, 13, 11, 7, 12, 10, 9, 6, 5, 3, 8, 4, 2, 1, 0};
  int loaded = 0;
  for (int i = 0; i < m; ++i) loaded |= old[i] > 0 ? 1 << i : 0;
  bool solved = loaded != 0 && try_set(loaded);
  for (const int set : kBySize) {
    if (solved) break;
    if (set >> m == 0 && (loaded == 0 || set != loaded)) solved = try_set(set);
  }
  if (!solved) return false;
  const Eigen::Vector4d d = x - old;
  const Eigen::Vector4d dv = A * d;
  for (int i = 0; i < m; ++i) {
    ApplyNormal(vel, r[i], d[i], -1);
    r[i].lambda_n = x[i];
    progress.change = std::max(progress.change, std::abs(d[i]));
    progress.scale = std::max(progress.scale, x[i]);
    progress.speed = std::max(progress.speed, std::abs(dv[i]));
  }
  return true;
}

// A sweep over the patches in `order` (forward or backward): each patch's normals (together, by
// default; point by point in exact mode, as rbsim 0.3), then its friction.
void Sweep(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order, bool forward, bool block,
           std::vector<Velocities>& vel, const BodyResponse& bodies, Progress& progress) {
  const int n = static_cast<int>(order.size());
  for (int k = 0; k < n; ++k) {
    Patch& p = patches[static_cast<std::size_t>(order[static_cast<std::size_t>(forward ? k : n - 1 - k)])];
    if (block && UpdateNormalBlock(p, rows, vel, progress)) {
      UpdateFriction(p, rows, vel, bodies, -1, progress);
      continue;
    }
    for (int j = 0; j < p.count; ++j) {
      Row& r = rows[static_cast<std::size_t>(forward ? p.first + j : p.first + p.count - 1 - j)];
      UpdateNormal(r, vel, -1, r.mass_n, progress);
    }
    UpdateFriction(p, rows, vel, bodies, -1, progress);
  }
}

// Shock propagation (Guendelman, Bridson & Fedkiw 2003): level by level from the ground up, each
// body's contacts with the level below are solved with the lower body held still, so what the
// iterations left of a resting stack's velocities does not survive the step.
void PropagateShock(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                    std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                    const SolveSettings& settings) {
  constexpr int kNone = std::numeric_limits<int>::max();
  int max_level = -1;
  for (const int k : order) {
    const int level = patches[static_cast<std::size_t>(k)].level;
    if (level != kNone) max_level = std::max(max_level, level);
  }
  for (int level = 0; level <= max_level; ++level) {
    for (int pass = 0; pass < settings.max_iterations; ++pass) {
      Progress progress;
      for (const int k : order) {
        Patch& p = patches[static_cast<std::size_t>(k)];
        if (p.level != level) continue;
        const int la = body_level[static_cast<std::size_t>(p.a)];
        const int lb = p.b >= 0 ? body_level[static_cast<std::size_t>(p.b)] : -1;
        if (la == lb) continue;
        const int frozen = la < lb ? p.a : p.b;
        for (int i = p.first; i < p.first + p.count; ++i) {
          Row& r = rows[static_cast<std::size_t>(i)];
          const Matrix3& K = frozen == r.a ? r.Kb : r.Ka;
          UpdateNormal(r, vel, frozen, 1.0 / r.n.dot(K * r.n), progress);
        }
        UpdateFriction(p, rows, vel, bodies, frozen, progress);
      }
      if (progress.Done(settings)) break;
    }
  }
}

// An island's bodies, their kinetic energy, and a copy of its impulses and velocities to go back to.
class IslandState {
 public:
  IslandState(const std::vector<Patch>& patches, const std::vector<int>& order, const Coupling* coupling) {
    auto add = [&](int body) {
      if (coupling == nullptr) {
        members_.push_back(body);
        return;
      }
      const auto& tree = coupling->members[static_cast<std::size_t>(coupling->tree[static_cast<std::size_t>(body)])];
      members_.insert(members_.end(), tree.begin(), tree.end());  // all of them move
    };
    for (const int k : order) {
      const Patch& p = patches[static_cast<std::size_t>(k)];
      add(p.a);
      if (p.b >= 0) add(p.b);
    }
    std::sort(members_.begin(), members_.end());
    members_.erase(std::unique(members_.begin(), members_.end()), members_.end());
  }
  double Energy(const std::vector<Velocities>& vel, const BodyResponse& bodies) const {
    double e = 0;
    for (const int i : members_) {
      const auto k = static_cast<std::size_t>(i);
      if (!(bodies.inv_mass[k] > 0)) continue;
      e += 0.5 * vel[k].v.squaredNorm() / bodies.inv_mass[k] +
           0.5 * vel[k].w.dot(bodies.inv_inertia[k].inverse() * vel[k].w);
    }
    return e;
  }
  void Save(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
            const std::vector<Velocities>& vel) {
    velocities_.clear();
    normal_.clear();
    friction_.clear();
    for (const int i : members_) velocities_.push_back(vel[static_cast<std::size_t>(i)]);
    for (const int k : order) {
      const Patch& p = patches[static_cast<std::size_t>(k)];
      friction_.push_back(p.lambda);
      for (int i = p.first; i < p.first + p.count; ++i) normal_.push_back(rows[static_cast<std::size_t>(i)].lambda_n);
    }
  }
  void Restore(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel) const {
    for (std::size_t j = 0; j < members_.size(); ++j) vel[static_cast<std::size_t>(members_[j])] = velocities_[j];
    std::size_t n = 0, f = 0;
    for (const int k : order) {
      Patch& p = patches[static_cast<std::size_t>(k)];
      p.lambda = friction_[f++];
      for (int i = p.first; i < p.first + p.count; ++i) rows[static_cast<std::size_t>(i)].lambda_n = normal_[n++];
    }
  }

 private:
  std::vector<int> members_;
  std::vector<Velocities> velocities_;
  std::vector<double> normal_;
  std::vector<Vector3> friction_;
};

// Symmetric sweeps from the ground up, then back down (they carry a load through a stack in both
// directions), until the stopping rule holds. Returns the sweeps used, or max_iterations.
int Sweeps(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
           std::vector<Velocities>& vel, const BodyResponse& bodies, const SolveSettings& settings) {
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    Progress progress;
    Sweep(rows, patches, order, iteration % 2 == 0, !settings.exact, vel, bodies, progress);
    if (progress.Done(settings)) return iteration + 1;
  }
  return settings.max_iterations;
}

// The warm start: the last step's impulses applied again.
void WarmStart(const std::vector<Row>& rows, const std::vector<Patch>& patches, const std::vector<int>& order,
               std::vector<Velocities>& vel) {
  for (const int k : order) {
    const Patch& p = patches[static_cast<std::size_t>(k)];
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      ApplyNormal(vel, r, r.lambda_n, -1);
    }
    ApplyPatch(vel, p, p.lambda, -1);
  }
}

// One island's solve: its patches in `order` (by support level), warm start, sweeps until the
// stopping rule holds, and shock propagation when they run out. Returns the sweeps.
//
// Exact mode: shock propagation whenever the sweeps run out (rbsim 0.3). By default two guards
// keep the impulses from adding kinetic energy where the sweeps stop short of convergence: sweeps
// from the warm start lower ½λᵀAλ + λᵀ(Jv − target) from its value at the warm start, which may
// be positive, so an island that ends with more kinetic energy than before its contacts is solved
// again from zero impulses (from which every sweep only lowers it); and shock propagation, which
// holds lower bodies still and so is not passive by construction, is kept only where it does not
// add kinetic energy.
int SolveIsland(std::vector<Row>& rows, std::vector<Patch>& patches, const std::vector<int>& order,
                std::vector<Velocities>& vel, const BodyResponse& bodies, const std::vector<int>& body_level,
                const SolveSettings& settings) {
  if (settings.exact) {
    WarmStart(rows, patches, order, vel);
    const int sweeps = Sweeps(rows, patches, order, vel, bodies, settings);
    if (sweeps == settings.max_iterations) PropagateShock(rows, patches, order, vel, bodies, body_level, settings);
    return sweeps;
  }
  IslandState state(patches, order, bodies.coupling);
  const double kicked = state.Energy(vel, bodies);
  state.Save(rows, patches, order, vel);  // the kicked velocities, the warm start's impulses
  WarmStart(rows, patches, order, vel);
  int last = Sweeps(rows, patches, order, vel, bodies, settings), sweeps = last;
  if (state.Energy(vel, bodies) > kicked) {
    state.Restore(rows, patches, order, vel);
    for (const int k : order) {
      Patch& p = patches[static_cast<std::size_t>(k)];
      p.lambda.setZero();
      for (int i = p.first; i < p.first + p.count; ++i) rows[static_cast<std::size_t>(i)].lambda_n = 0;
    }
    last = Sweeps(rows, patches, order, vel, bodies, settings);
    sweeps += last;
  }
  if (last < settings.max_iterations) return sweeps;
  const double before_shock = state.Energy(vel, bodies);
  state.Save(rows, patches, order, vel);
  PropagateShock(rows, patches, order, vel, bodies, body_level, settings);
  if (state.Energy(vel, bodies) > before_shock) state.Restore(rows, patches, order, vel);
  return sweeps;
}

}  // namespace

void Coupling::Apply(std::vector<Velocities>& vel, int a, const Vector3& f, const Vector3& tau) const {
  const auto t = static_cast<std::size_t>(tree[static_cast<std::size_t>(a)]);
  const std::vector<int>& m = members[t];
  const std::size_t n = m.size(), k = static_cast<std::size_t>(slot[static_cast<std::size_t>(a)]);
  Vector6 w;
  w << f, tau;
  for (std::size_t j = 0; j < n; ++j) {
    const Vector6 d = response[t][j * n + k] * w;
    Velocities& v = vel[static_cast<std::size_t>(m[j])];
    v.v += d.head<3>();
    v.w += d.tail<3>();
  }
}

double Coupling::NormalResponse(const Row& r) const {
  Vector6 wa, wb = Vector6::Zero();
  wa << r.n, r.ra.cross(r.n);
  if (r.b >= 0) wb << r.n, r.rb.cross(r.n);
  return CoupledResponse<1>(*this, r.a, r.b, Eigen::Matrix<double, 6, 1>(wa), Eigen::Matrix<double, 6, 1>(wb))(0, 0);
}

Vector3 RelativeVelocity(const std::vector<Velocities>& vel, int a, int b, const Vector3& ra, const Vector3& rb) {
  const Velocities& va = vel[static_cast<std::size_t>(a)];
  Vector3 v = va.v + va.w.cross(ra);
  if (b >= 0) {
    const Velocities& vb = vel[static_cast<std::size_t>(b)];
    v -= vb.v + vb.w.cross(rb);
  }
  return v;
}

std::vector<Patch> PreparePatches(std::vector<Row>& rows, const ContactCache& cache, const std::vector<Velocities>& vel,
                                  const BodyResponse& bodies, double slow) {
  const double same = std::cos(kPatchAngle);
  // Each row's normal effective mass and warm start.
  for (Row& r : rows) {
    SetRowJacobian(r, bodies);
    const auto it = cache.rows.find(r.key);
    if (it != cache.rows.end()) r.lambda_n = it->second.lambda_n;
  }
  std::vector<Patch> patches;
  patches.reserve(rows.size());
  std::vector<Row> sorted;
  for (std::size_t first = 0; first < rows.size();) {
    // The pair's rows: [first, last).
    const auto pair = std::pair{std::get<0>(rows[first].key), std::get<1>(rows[first].key)};
    std::size_t last = first;
    while (last < rows.size() && std::pair{std::get<0>(rows[last].key), std::get<1>(rows[last].key)} == pair) ++last;
    // Its patches: each row joins the first patch whose first normal agrees with its own and
    // whose friction is its own (a compound's parts may differ); the rows are reordered patch by
    // patch.
    std::vector<const Row*> leaders;  // each patch's first row
    std::vector<int> patch_of;
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
    const auto found = cache.patches.find(pair);
    std::vector<char> used(found != cache.patches.end() ? found->second.size() : 0, 0);
    for (std::size_t k = 0; k < leaders.size(); ++k) {
      Patch p;
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
      patches.push_back(p);
    }
    std::copy(sorted.begin(), sorted.end(), rows.begin() + static_cast<std::ptrdiff_t>(first));
    // Each patch's anchor, effective masses, warm start and friction state.
    for (std::size_t k = patches.size() - leaders.size(); k < patches.size(); ++k) {
      Patch& p = patches[k];
      Vector3& anchor = p.anchor;
      Outline(rows, p, anchor, p.rho);
      const Row& r0 = rows[static_cast<std::size_t>(p.first)];
      p.ra = anchor - (r0.point - r0.ra);
      p.rb = p.b >= 0 ? Vector3(anchor - (r0.point - r0.rb)) : Vector3::Zero();
      SetPatchJacobian(p, bodies);
      SetNormalBlock(p, rows);
      // The patch it was last step: the cached patch of one of its rows (by the rows' feature
      // keys, as a contact is known step after step); none: a new patch.
      std::size_t best = used.size();
      for (int i = p.first; i < p.first + p.count && best == used.size(); ++i) {
        const auto it = cache.rows.find(rows[static_cast<std::size_t>(i)].key);
        if (it != cache.rows.end() && it->second.patch >= 0 && !used[static_cast<std::size_t>(it->second.patch)]) {
          best = static_cast<std::size_t>(it->second.patch);
        }
      }
      // Else (its points all new: a clipped manifold's corners move along the edges) the pair's
      // unmatched cached patch whose normal is nearest, within kPatchAngle.
      if (best == used.size()) {
        for (std::size_t c = 0; c < used.size(); ++c) {
          const double dot = found->second[c].n.dot(p.n);
          if (!used[c] && dot >= same && (best == used.size() || dot > found->second[best].n.dot(p.n))) best = c;
        }
      }
      const Vector3 g = PatchVelocity(vel, p);
      bool stuck;
      if (best < used.size()) {
        used[best] = 1;
        const CachedPatch& c = found->second[best];
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
  return patches;
}

int SolveImpulses(std::vector<Row>& rows, std::vector<Patch>& patches, std::vector<Velocities>& vel,
                  const BodyResponse& bodies, const std::vector<int>& body_level, const std::vector<int>& island,
                  const SolveSettings& settings, Workers* workers) {
  for (Patch& p : patches) {
    const int la = body_level[static_cast<std::size_t>(p.a)];
    p.level = p.b < 0 ? la : std::min(la, body_level[static_cast<std::size_t>(p.b)]);
    // Jointed bodies are not held still level by level (their tree moves as one).
    if (p.coupling != nullptr) p.level = std::numeric_limits<int>::max();
  }
  std::vector<int> order(patches.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return patches[static_cast<std::size_t>(x)].level < patches[static_cast<std::size_t>(y)].level;
  });
  // Each island's patches, in that order; the islands in the order they first appear.
  std::vector<int> group_of(island.size(), -1);
  std::vector<std::vector<int>> groups;
  for (const int k : order) {
    const int label = island[static_cast<std::size_t>(patches[static_cast<std::size_t>(k)].a)];
    int& g = group_of[static_cast<std::size_t>(label)];
    if (g < 0) {
      g = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(g)].push_back(k);
  }
  // The largest islands first (the others fill in around them on several threads).
  std::vector<std::size_t> by_size(groups.size());
  std::iota(by_size.begin(), by_size.end(), std::size_t{0});
  std::stable_sort(by_size.begin(), by_size.end(),
                   [&](std::size_t x, std::size_t y) { return groups[x].size() > groups[y].size(); });
  std::vector<int> sweeps(groups.size(), 0);
  auto solve = [&](std::size_t i) {
    const std::size_t g = by_size[i];
    sweeps[g] = SolveIsland(rows, patches, groups[g], vel, bodies, body_level, settings);
  };
  // A few small islands are not worth waking the workers for.
  if (workers != nullptr && groups.size() > 1 && patches.size() >= 32) {
    workers->ForEach(groups.size(), solve);
  } else {
    for (std::size_t i = 0; i < groups.size(); ++i) solve(i);
  }
  return sweeps.empty() ? 0 : *std::max_element(sweeps.begin(), sweeps.end());
}

void StoreImpulses(const std::vector<Row>& rows, const std::vector<Patch>& patches, ContactCache& cache) {
  for (const Patch& p : patches) {
    const double N = Load(p, rows);
    const RowKey& key = rows[static_cast<std::size_t>(p.first)].key;
    std::vector<CachedPatch>& pair = cache.patches[{std::get<0>(key), std::get<1>(key)}];
    // Not touching yet (a speculative contact): whether it holds is decided when it touches, by
    // how fast it slides then.
    int index = -1;
    if (N > 0) {
      // On the limit: it slides (or just broke away); inside: it holds.
      const bool stuck = p.lambda.norm() < p.mu * N * (1 - 1e-9);
      index = static_cast<int>(pair.size());
      pair.push_back({p.n, p.t1 * p.lambda[0] + p.t2 * p.lambda[1], p.rho * p.lambda[2], stuck});
    }
    for (int i = p.first; i < p.first + p.count; ++i) {
      const Row& r = rows[static_cast<std::size_t>(i)];
      cache.rows[r.key] = {r.lambda_n, index};
    }
  }
}

}  // namespace dynamics::contact
